// The show's markers in the studio's page (tests/browser/studio_harness.mjs), on the simulated
// hello-head: M adds one at the playhead, ] and [ jump to them, a double-click on the ruler
// renames one, Shift+M deletes it, undo brings it back, and save writes them to the show file.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import { onCanvas, openStudio, out, until } from './studio_harness.mjs';

let page;
let close;
let showFile;

before(async () => {
  ({ page, close, showFile } = await openStudio({ show: 'hello-head.yaml', rig: 'hello-head.yaml', channel: 'jaw' }));
});

after(async () => {
  await close?.();
});

const markers = () => page.evaluate(() => window.avarStudio.state.show.show.markers ?? []);
const showTime = () => page.evaluate(() => window.avarStudio.state.status.show_time);
async function seek(time) {
  await page.evaluate((t) => window.avarStudio.state.ask({ type: 'seek', time: t }), time);
  await until(`show time ${time}`, async () => Math.abs((await showTime()) - time) < 1e-6);
}

test('M adds markers at the playhead and ] and [ jump between them', async () => {
  await seek(1.5);
  await page.keyboard.press('m');
  await until('the first marker', async () => (await markers()).length === 1);
  await seek(4);
  await page.keyboard.press('m');
  await until('the second marker', async () => (await markers()).length === 2);
  assert.deepEqual(await markers(), [
    { time: 1.5, name: 'marker 1' },
    { time: 4, name: 'marker 2' },
  ]);
  await seek(0);
  await page.keyboard.press(']');
  await until('the jump to marker 1', async () => Math.abs((await showTime()) - 1.5) < 1e-6);
  await page.keyboard.press(']');
  await until('the jump to marker 2', async () => Math.abs((await showTime()) - 4) < 1e-6);
  await page.keyboard.press('[');
  await until('the jump back to marker 1', async () => Math.abs((await showTime()) - 1.5) < 1e-6);
  await page.locator('#dopesheet').screenshot({ path: join(out, 'studio-markers.png') });
});

test('a double-click on the ruler renames a marker, Shift+M deletes it and undo brings it back', async () => {
  const x = await page.evaluate(() => window.avarStudio.dope.axis().x(4));
  page.once('dialog', (dialog) => dialog.accept('the scream'));
  const at = await onCanvas(page, 'dopesheet', x, 18);
  await page.mouse.dblclick(at.x, at.y);
  await until('the rename', async () => (await markers()).some((m) => m.name === 'the scream'));
  await seek(1.5);
  await page.keyboard.press('Shift+M');
  await until('the deletion', async () => (await markers()).length === 1);
  assert.equal((await markers())[0].name, 'the scream');
  await page.keyboard.press('Control+z');
  await until('the undo', async () => (await markers()).length === 2);
});

test('save writes the markers to the show file', async () => {
  await page.keyboard.press('Control+s');
  await until('the save', () => page.evaluate(() => !window.avarStudio.state.show.modified));
  const text = readFileSync(showFile, 'utf8');
  assert.match(text, /markers:\n {2}- \{time: 1\.5, name: "marker 1"\}\n {2}- \{time: 4, name: "the scream"\}/);
});
