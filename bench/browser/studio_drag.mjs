// avar-bench-studio-page: the studio's page under a big show, in headless Chromium (Debian's,
// driven by Playwright) against `avar studio --sim`. A seeded show of 100,000 Bezier keys on 64
// channels (a rig of 64 Art-Net channels, simulated); 1,000 keys selected across the channels and
// dragged back and forth in the dope sheet by the pointer for a few seconds.
// - Frame time while dragging: the intervals between the page's animation frames. Target: p95 at
//   most 18 ms (60 frames a second is 16.7 ms).
// - How often the studio's answers (the moved keys) reach the page during the drag.
// - The dope sheet redrawn with the whole show in view (every key of every track).
// Usage: node studio_drag.mjs --avar AVAR --modules studio/page --out DIR [--seconds S]
import assert from 'node:assert/strict';
import { mkdtempSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { onCanvas, openStudio, until } from '../../tests/browser/studio_harness.mjs';

const CHANNELS = 64;
const KEYS = 100000;
const SELECTED = 1000;
const at = process.argv.indexOf('--seconds');
const SECONDS = at > 0 ? Number(process.argv[at + 1]) : 6;
// The dope sheet's layout (timeline.ts): the ruler's height and a row's.
const RULER = 24;
const ROW = 22;

/// A seeded generator (mulberry32): the same show every run.
function random(seed) {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

/// The rig and the show, written to a scratch folder; their paths.
function bigShow() {
  const dir = mkdtempSync(join(tmpdir(), 'avar-bench-studio-page-'));
  const u = random(20261206);
  const perChannel = Math.floor(KEYS / CHANNELS);
  let rig = 'name: big-rig\nrate_hz: 50\nlinks:\n  lights: {port: sim, artnet: {to: 10.0.0.20, net: 0, subnet: 0, universe: 1}}\nchannels:\n';
  let actuators = 'actuators:\n';
  let show = 'name: big\nduration: 610\nloop: false\ntracks:\n';
  for (let c = 0; c < CHANNELS; c++) {
    rig += `  ch${c}: {unit: deg, min: -100, max: 100, rest: 0, max_velocity: 5000, max_acceleration: 200000, max_jerk: 100000000}\n`;
    actuators += `  - {channel: ch${c}, link: lights, address: ${c + 1}}\n`;
    const keys = [];
    let t = 0;
    for (let k = 0; k < perChannel; k++) {
      keys.push(`{time: ${t.toFixed(4)}, value: ${(-90 + 180 * u()).toFixed(3)}, interpolation: bezier}`);
      t += 0.2 + 0.17 * u() + 0.2 * u();
    }
    show += `  ch${c}: [${keys.join(', ')}]\n`;
  }
  writeFileSync(join(dir, 'big-rig.yaml'), rig + actuators);
  writeFileSync(join(dir, 'big.yaml'), show);
  return { rig: join(dir, 'big-rig.yaml'), show: join(dir, 'big.yaml'), keys: perChannel * CHANNELS };
}

function percentile(sorted, p) {
  return sorted[Math.min(sorted.length - 1, Math.floor(p * sorted.length))];
}
const ms = (x) => `${x.toFixed(1)} ms`;

const files = bigShow();
const loadStart = Date.now();
const { page, close } = await openStudio({ show: files.show, rig: files.rig, channel: 'ch0', patience: 180 });
try {
  await until('every track in the engine', () => page.evaluate((c) => window.avarStudio.state.engine.has(c), `ch${CHANNELS - 1}`), 180);
  const loaded = (Date.now() - loadStart) / 1000;

  // 15 s of show in view; 1,000 keys picked between 126 s and 133 s, row after row.
  const picked = await page.evaluate((n) => {
    const s = window.avarStudio.state;
    s.view = { t0: 120, t1: 135 };
    s.selection.clear();
    let count = 0;
    for (const channel of s.rig.channels) {
      const set = new Set();
      s.keys(channel.name).forEach((key, index) => {
        if (key.time >= 126 && key.time < 133 && count < n) {
          set.add(index);
          count++;
        }
      });
      if (set.size > 0) s.selection.set(channel.name, set);
    }
    s.channel = 'ch0';
    s.changed();
    const first = Math.min(...s.selection.get('ch0'));
    return { count, index: first, time: s.keys('ch0')[first].time, secondsPerPixel: window.avarStudio.dope.axis().secondsPerPixel() };
  }, SELECTED);
  assert.equal(picked.count, SELECTED, 'the show has 1,000 keys in the picked stretch');

  // The pointer on ch0's first picked key, then back and forth by up to 8 px (about 0.1 s, less
  // than the keys' spacing: no key reaches its neighbour), a move every 16 ms.
  const x0 = await page.evaluate((t) => window.avarStudio.dope.axis().x(t), picked.time);
  const start = await onCanvas(page, 'dopesheet', x0, RULER + ROW / 2);
  await page.evaluate(() => {
    window.benchFrames = [];
    window.benchVersions = [];
    window.benchStop = false;
    const frame = (t) => {
      window.benchFrames.push(t);
      window.benchVersions.push(window.avarStudio.state.show.version);
      if (!window.benchStop) requestAnimationFrame(frame);
    };
    requestAnimationFrame(frame);
  });
  await page.mouse.move(start.x, start.y);
  await page.mouse.down();
  const began = Date.now();
  let offset = 0;
  while (Date.now() - began < SECONDS * 1000) {
    const phase = (Date.now() - began) / 1000;
    offset = Math.round(8 * Math.sin(2 * Math.PI * phase));
    await page.mouse.move(start.x + offset, start.y);
    await new Promise((r) => setTimeout(r, 16));
  }
  offset = 4;
  await page.mouse.move(start.x + offset, start.y);
  await page.mouse.up();
  const { frames, versions } = await page.evaluate(() => {
    window.benchStop = true;
    return { frames: window.benchFrames, versions: window.benchVersions };
  });
  // Every move answered: the key sits where the pointer left it.
  const expected = picked.time + offset * picked.secondsPerPixel;
  await until('the last move applied', () =>
    page.evaluate(
      ({ index, expected }) => Math.abs(window.avarStudio.state.keys('ch0')[index].time - expected) < 2e-4 && window.avarStudio.state.connection.inFlight() === 0,
      { index: picked.index, expected },
    ),
  );

  const intervals = frames.slice(1).map((t, i) => t - frames[i]).sort((a, b) => a - b);
  const answers = versions.filter((v, i) => i > 0 && v !== versions[i - 1]).length;

  // The dope sheet with every key of the show in view, drawn 20 times.
  const whole = await page.evaluate(() => {
    const { state, dope } = window.avarStudio;
    state.selection.clear();
    state.view = { t0: -10, t1: 620 };
    const times = [];
    for (let i = 0; i < 20; i++) {
      const t0 = performance.now();
      dope.render();
      times.push(performance.now() - t0);
    }
    return times.sort((a, b) => a - b);
  });

  console.log(`studio page: ${files.keys.toLocaleString('en')} keys on ${CHANNELS} channels (loaded in ${loaded.toFixed(1)} s), ${SELECTED.toLocaleString('en')} selected, dragged ${SECONDS} s`);
  console.log(
    `  frame time while dragging: median ${ms(percentile(intervals, 0.5))}, p95 ${ms(percentile(intervals, 0.95))}, worst ${ms(intervals[intervals.length - 1])} over ${intervals.length} frames (target: p95 <= 18 ms)`,
  );
  console.log(`  the studio's answers reaching the page: ${answers} in ${SECONDS} s (one every ${ms((SECONDS * 1000) / Math.max(1, answers))})`);
  console.log(`  dope sheet with the whole show in view: median ${ms(percentile(whole, 0.5))}, worst ${ms(whole[whole.length - 1])} a redraw`);
} finally {
  await close();
}
