// A URDF figure in the studio's 3-D preview (tests/browser/studio_harness.mjs): the urdf-head's
// boxes, cylinders, spheres, STL skull and OBJ jaw drawn in their links' frames and moving with
// the simulated servos; a mesh that cannot be had is named, and simple shapes draw the figure;
// a Collada mesh (tests/browser/fixtures/jaw.dae) loads too.
import assert from 'node:assert/strict';
import { mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { test } from 'node:test';
import { openStudio, out, previewPixelAt, source, until } from './studio_harness.mjs';

const background = [0x18, 0x1b, 0x20];
const pixelAt = (page, { x, y }) => previewPixelAt(page, x, y);
const measured = (page, name) =>
  page.evaluate((n) => window.avarStudio.state.status.channels.find((c) => c.name === n).measured, name);
async function holdAt(page, channel, value) {
  await page.evaluate(([c, v]) => window.avarStudio.state.connection.send({ type: 'hold', channel: c, value: v }), [channel, value]);
  await until(`${channel} at ${value}`, async () => Math.abs((await measured(page, channel)) - value) < 0.5);
}
const linkAt = (page, link, point) => page.evaluate(([l, p]) => window.avarStudio.preview.linkScreenPosition(l, p), [link, point]);

test("the urdf-head is drawn from its URDF's shapes and meshes, and its jaw hinges with the servo", async () => {
  const { page, close } = await openStudio({ show: 'look-around.yaml', rig: 'urdf-head.yaml', channel: 'jaw' });
  try {
    const ready = await page.evaluate(() => window.avarStudio.preview.visualsReady());
    assert.deepEqual(ready, { drawn: 7, problems: [] });
    assert.equal(await page.isVisible('#preview-message'), false);
    // The skull's crown (an STL) and the pedestal (a box) are drawn where their links are.
    await until('the skull drawn', async () => {
      const crown = await linkAt(page, 'skull', [0.015, 0, 0.12]);
      return crown && String(await pixelAt(page, crown)) !== String(background);
    });
    assert.notDeepEqual(await pixelAt(page, await linkAt(page, 'base', [0.05, 0.05, 0.04])), background);
    // The jaw (an OBJ) turns about its hinge with its channel: its tip moves on screen.
    await holdAt(page, 'jaw', 0);
    const tip = [0.1, 0, -0.02];
    const closed = await linkAt(page, 'jaw', tip);
    await holdAt(page, 'jaw', 28);
    const open = await until('the jaw to open in the view', async () => {
      const p = await linkAt(page, 'jaw', tip);
      return Math.hypot(p.x - closed.x, p.y - closed.y) > 3 && p;
    });
    assert.notDeepEqual(await pixelAt(page, open), background);
    await page.screenshot({ path: join(out, 'studio-urdf.png') });
  } finally {
    await close();
  }
});

test('a mesh that is not there is named, the simple shapes draw the figure, and a Collada jaw loads', async () => {
  // The same figure, its skull's file renamed and its jaw a Collada file, in a copy of the URDF.
  const work = mkdtempSync(join(tmpdir(), 'avar-urdf-'));
  const folder = join(source, 'examples/rigs/urdf-head');
  writeFileSync(join(work, 'jaw.dae'), readFileSync(join(source, 'tests/browser/fixtures/jaw.dae')));
  const urdf = readFileSync(join(folder, 'urdf-head.urdf'), 'utf8')
    .replace('package://urdf-head/meshes/head.stl', `file://${folder}/meshes/skull-missing.stl`)
    .replace('filename="meshes/jaw.obj"', 'filename="jaw.dae"');
  writeFileSync(join(work, 'urdf-head.urdf'), urdf);
  const rig = join(work, 'urdf-head.yaml');
  writeFileSync(
    rig,
    readFileSync(join(source, 'examples/rigs/urdf-head.yaml'), 'utf8').replace('urdf: urdf-head/urdf-head.urdf', `urdf: ${work}/urdf-head.urdf`),
  );
  const { page, close } = await openStudio({ show: 'look-around.yaml', rig, channel: 'jaw' });
  try {
    const ready = await page.evaluate(() => window.avarStudio.preview.visualsReady());
    assert.equal(ready.drawn, 6);  // the Collada jaw among them
    assert.equal(ready.problems.length, 1);
    assert.match(ready.problems[0], /skull-missing\.stl of link skull: not found/);
    await until('the note under the view', () => page.isVisible('#preview-message'));
    assert.match(await page.textContent('#preview-message'), /drawn with simple shapes as well: .*skull-missing\.stl/);
  } finally {
    await close();
  }
});
