// The studio's page on a talking show (tests/browser/studio_harness.mjs): the jaw's track is made
// from a voice, and the dope sheet and the graph editor draw that voice's waveform under it. The
// voice is made here (bursts of a 400 Hz tone, like syllables) so that the test needs no speech
// synthesiser.
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import { openStudio, out, until } from './studio_harness.mjs';

/// A mono 16-bit WAV: `seconds` of syllable-like bursts at `rate` Hz.
function voice(seconds, rate) {
  const n = Math.round(seconds * rate);
  const data = Buffer.alloc(44 + 2 * n);
  data.write('RIFF', 0);
  data.writeUInt32LE(36 + 2 * n, 4);
  data.write('WAVEfmt ', 8);
  data.writeUInt32LE(16, 16);
  data.writeUInt16LE(1, 20); // PCM
  data.writeUInt16LE(1, 22); // mono
  data.writeUInt32LE(rate, 24);
  data.writeUInt32LE(2 * rate, 28);
  data.writeUInt16LE(2, 32);
  data.writeUInt16LE(16, 34);
  data.write('data', 36);
  data.writeUInt32LE(2 * n, 40);
  for (let i = 0; i < n; i++) {
    const t = i / rate;
    const syllable = Math.max(0, Math.sin(Math.PI * ((t * 4) % 1))) * (Math.floor(t * 4) % 5 === 4 ? 0 : 1);
    data.writeInt16LE(Math.round(20000 * syllable * Math.sin(2 * Math.PI * 400 * t)), 44 + 2 * i);
  }
  return data;
}

let page;
let close;

before(async () => {
  const fs = await import('node:fs');
  const source = join(import.meta.dirname, '../../examples/shows');
  ({ page, close } = await openStudio({
    show: 'talking-skull.yaml',
    rig: 'talking-skull.yaml',
    channel: 'jaw',
    files: { 'talking-skull.wav': voice(3.5, 16000), 'talking-skull.tsv': fs.readFileSync(join(source, 'talking-skull.tsv')) },
  }));
});

after(async () => {
  await close?.();
});

test("the jaw's voice is drawn under its keys, where the show plays it", async () => {
  const wave = await until('the waveform', () => page.evaluate(() => window.avarStudio.state.waveforms.get('jaw')));
  assert.equal(wave.start, 0.5);
  assert.equal(wave.duration, 3.5);
  assert.equal(wave.bucket, 0.01);
  assert.equal(wave.peaks.length, 700);
  // Loudest in the middle of a syllable (0.125 s into the sound), silent in the fifth's pause.
  assert.ok(wave.peaks[2 * 12 + 1] > 0.55, `a syllable's crest: ${wave.peaks[2 * 12 + 1]}`);
  assert.ok(wave.peaks[2 * 112 + 1] < 0.01, `a pause: ${wave.peaks[2 * 112 + 1]}`);
  // The jaw's row (the first) is green where the voice sounds: 0.5 s + 0.125 s, in the dope sheet.
  const x = await page.evaluate(() => window.avarStudio.dope.axis().x(0.625));
  const green = await until('the waveform drawn', () =>
    page.evaluate((x) => {
      const canvas = document.getElementById('dopesheet');
      const ratio = canvas.width / canvas.clientWidth;
      const g = canvas.getContext('2d');
      // Any pixel of the column within the row, above and below its middle (the keys sit there).
      for (const y of [24 + 3, 24 + 6, 24 + 16, 24 + 19]) {
        const [r, gr, b] = g.getImageData(Math.round(x * ratio), Math.round(y * ratio), 1, 1).data;
        if (gr > r + 25 && gr > b + 25) return [r, gr, b];
      }
      return null;
    }, x),
  );
  assert.ok(green);
  await page.screenshot({ path: join(out, 'studio-audio.png') });
});

test('time inserted before the voice moves it with the keys, and undo moves it back', async () => {
  const start = () => page.evaluate(() => window.avarStudio.state.waveforms.get('jaw')?.start);
  await page.evaluate(() => window.avarStudio.state.edit([{ op: 'insert_time', at: 0.25, length: 0.5 }]));
  await until('the voice to start at 1 s', async () => (await start()) === 1);
  await page.keyboard.press('Control+z');
  await until('the voice back at 0.5 s', async () => (await start()) === 0.5);
});
