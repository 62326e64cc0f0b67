// Preview against wire: the studio page's curve engine (WebAssembly) against `avar sample`, the
// command line's own evaluation of a show, bit for bit. For every plain example show the probe
// found (tests/tools/wasm_curves_probe.cpp), `avar sample` writes its tracks every millisecond
// from half a second before the show to half a second after it (numbers that read back exactly);
// the module builds the same tracks from their flat keys and samples them at the same times.
//
//   node wasm_sample_test.mjs --avar build/apps/avar --module build/studio/avar_curves.js --probe probe.json
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { resolve } from 'node:path';

const args = process.argv.slice(2);
const option = (name) => {
  const at = args.indexOf(name);
  if (at < 0 || at + 1 >= args.length) {
    console.error(`usage: node wasm_sample_test.mjs --avar AVAR --module avar_curves.js --probe probe.json (missing ${name})`);
    process.exit(2);
  }
  return args[at + 1];
};
const avar = resolve(option('--avar'));
const engine = await createRequire(import.meta.url)(resolve(option('--module')))();
const probe = JSON.parse(readFileSync(option('--probe'), 'utf8'));

const bitsOf = (value) => {
  const view = new DataView(new ArrayBuffer(8));
  view.setFloat64(0, value);
  return view.getBigUint64(0);
};

/// The module's values of flat keys at `times`.
function sampleInModule(flat, times) {
  const keys = engine._malloc(flat.length * 8);
  engine.HEAPF64.set(flat, keys / 8);
  const id = engine._avar_curve_build(keys, flat.length);
  engine._free(keys);
  if (id < 0) throw new Error(engine.UTF8ToString(engine._avar_error()));
  const at = engine._malloc(times.length * 8);
  const out = engine._malloc(times.length * 8);
  engine.HEAPF64.set(times, at / 8);
  engine._avar_curve_sample_many(id, at, out, times.length);
  const values = engine.HEAPF64.slice(out / 8, out / 8 + times.length);
  engine._free(at);
  engine._free(out);
  engine._avar_curve_free(id);
  return values;
}

const shows = new Map();
for (const curve of probe.curves) {
  if (!curve.show) continue;
  if (!shows.has(curve.show)) shows.set(curve.show, { duration: curve.duration, curves: [] });
  shows.get(curve.show).curves.push(curve);
}
let samples = 0;
const mismatches = [];
for (const [show, { duration, curves }] of shows) {
  const channels = curves.map((c) => c.channel);
  const csv = execFileSync(
    avar,
    ['sample', show, '--step', '0.001', '--from', '-0.5', '--to', String(duration + 0.5), '--channels', channels.join(',')],
    { encoding: 'utf8', maxBuffer: 1 << 28 },
  );
  const rows = csv.trim().split('\n');
  const header = rows.shift().split(',');
  if (header.join(',') !== ['seconds', ...channels].join(','))
    throw new Error(`${show}: avar sample wrote columns ${header.join(',')}, expected seconds,${channels.join(',')}`);
  const table = rows.map((row) => row.split(',').map(Number));
  const times = table.map((row) => row[0]);
  curves.forEach((curve, c) => {
    const values = sampleInModule(curve.flat, times);
    times.forEach((t, i) => {
      samples += 1;
      const wire = table[i][c + 1];
      if (bitsOf(values[i]) !== bitsOf(wire)) mismatches.push(`${curve.name} at t=${t}: avar sample ${wire}, the page's engine ${values[i]}`);
    });
  });
}
if (shows.size === 0) {
  console.error('the probe found no plain example show');
  process.exit(1);
}
if (mismatches.length > 0) {
  console.error(`${mismatches.length} of ${samples} samples differ:`);
  for (const m of mismatches.slice(0, 20)) console.error(`  ${m}`);
  process.exit(1);
}
console.log(`preview against wire: ${shows.size} shows, ${samples} samples of the page's engine, every one avar sample's bits`);
