// The studio page's curve engine (WebAssembly) against the native one, bit for bit: every curve
// the probe wrote (tests/tools/wasm_curves_probe.cpp) is built from its flat keys in the module
// and sampled at the probe's times; every value must have the native value's bits.
//
//   node wasm_curves_test.mjs --module build/studio/avar_curves.js --probe probe.json
import { createRequire } from 'node:module';
import { readFileSync } from 'node:fs';
import { resolve } from 'node:path';

const args = process.argv.slice(2);
const option = (name) => {
  const at = args.indexOf(name);
  if (at < 0 || at + 1 >= args.length) {
    console.error(`usage: node wasm_curves_test.mjs --module avar_curves.js --probe probe.json (missing ${name})`);
    process.exit(2);
  }
  return args[at + 1];
};
const require = createRequire(import.meta.url);
const AvarCurves = require(resolve(option('--module')));
const probe = JSON.parse(readFileSync(option('--probe'), 'utf8'));
const engine = await AvarCurves();

const bitsOf = (value) => {
  const view = new DataView(new ArrayBuffer(8));
  view.setFloat64(0, value);
  return view.getBigUint64(0).toString(16).padStart(16, '0');
};
/// Copies numbers into the module's heap; returns the address (free it).
const toHeap = (numbers) => {
  const address = engine._malloc(numbers.length * 8);
  engine.HEAPF64.set(numbers, address / 8);
  return address;
};

let samples = 0;
let handleNumbers = 0;
const mismatches = [];
let previousFlat = null;
let rebuilt = 0;
for (const curve of probe.curves) {
  // Every curve after the first is made as the page makes an edited track: the one before it
  // built, then rebuilt from this one's keys (reusing what it can). The same bits either way.
  const firstFlat = previousFlat ?? curve.flat;
  const flat = toHeap(firstFlat);
  const id = engine._avar_curve_build(flat, firstFlat.length);
  engine._free(flat);
  if (id < 0) {
    mismatches.push(`${curve.name}: the module refused keys the native engine built: ${engine.UTF8ToString(engine._avar_error())}`);
    continue;
  }
  if (previousFlat) {
    const next = toHeap(curve.flat);
    if (engine._avar_curve_rebuild(id, next, curve.flat.length) !== 0)
      mismatches.push(`${curve.name}: the module refused to rebuild: ${engine.UTF8ToString(engine._avar_error())}`);
    engine._free(next);
    rebuilt += 1;
  }
  previousFlat = curve.flat;
  const times = toHeap(curve.times);
  const out = engine._malloc(curve.times.length * 8);
  engine._avar_curve_sample_many(id, times, out, curve.times.length);
  const values = engine.HEAPF64.slice(out / 8, out / 8 + curve.times.length);
  engine._free(times);
  engine._free(out);
  engine._avar_curve_free(id);
  // The handles the graph editor draws: the native engine's, bit for bit.
  const flatAgain = toHeap(curve.flat);
  const handlesOut = engine._malloc(Math.max(1, curve.handles.length) * 8);
  const keys = engine._avar_curve_handles(flatAgain, curve.flat.length, handlesOut);
  const handles = engine.HEAPF64.slice(handlesOut / 8, handlesOut / 8 + curve.handles.length);
  engine._free(flatAgain);
  engine._free(handlesOut);
  if (keys * 4 !== curve.handles.length) mismatches.push(`${curve.name}: handles of ${keys} keys, native ${curve.handles.length / 4}`);
  curve.handles.forEach((bits, i) => {
    handleNumbers += 1;
    // NaN marks a side without a handle: any NaN matches it.
    if (Number.isNaN(handles[i]) && bits.startsWith('7ff')) return;
    if (bitsOf(handles[i]) !== bits) mismatches.push(`${curve.name}: handle number ${i}: native ${bits}, WebAssembly ${bitsOf(handles[i])}`);
  });
  curve.times.forEach((t, i) => {
    samples += 1;
    const got = bitsOf(values[i]);
    if (got !== curve.bits[i]) mismatches.push(`${curve.name} at t=${t}: native ${curve.bits[i]}, WebAssembly ${got} (${values[i]})`);
  });
}
if (mismatches.length > 0) {
  console.error(`${mismatches.length} differences in ${samples} samples and ${handleNumbers} handle numbers:`);
  for (const m of mismatches.slice(0, 20)) console.error(`  ${m}`);
  process.exit(1);
}
console.log(
  `wasm curves: ${probe.curves.length} curves (${rebuilt} rebuilt from the one before), ${samples} samples and ${handleNumbers} handle numbers, every one bit-identical to the native engine`,
);
