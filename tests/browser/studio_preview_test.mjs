// The studio's 3-D preview in a real browser (tests/browser/studio_harness.mjs): the gaze head's
// kinematic tree drawn with WebGL, posed by where the simulated servos are, and a click on a
// joint selecting its channel's track.
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import { onCanvas, openStudio, out, previewPixelAt, until } from './studio_harness.mjs';

let page;
let close;

before(async () => {
  ({ page, close } = await openStudio({ show: 'look-around.yaml', rig: 'gaze-head.yaml', channel: 'jaw' }));
});

after(async () => {
  await close?.();
});

const measured = (name) =>
  page.evaluate((n) => window.avarStudio.state.status.channels.find((c) => c.name === n).measured, name);
/// Holds a channel at a value and waits until the simulated servo is there.
async function holdAt(channel, value) {
  await page.evaluate(([c, v]) => window.avarStudio.state.connection.send({ type: 'hold', channel: c, value: v }), [channel, value]);
  // Within half a degree: the simulated hobby servo has a deadband, as real ones do.
  await until(`${channel} at ${value}`, async () => Math.abs((await measured(channel)) - value) < 0.5);
}
const pixelAt = (x, y) => previewPixelAt(page, x, y);
const drawnAt = (name) => page.evaluate((n) => window.avarStudio.preview.screenPosition(n), name);

test('the 3-D view draws the joints and turns with the simulated servos', async () => {
  assert.equal(await page.isVisible('#preview'), true);
  assert.equal(await page.isVisible('#preview-message'), false);
  await holdAt('neck_pan', -40);
  // The joint takes the angle of where the servo is: degrees on the channel, radians at the joint.
  await until('the view to take the pose', async () => {
    const [angle, at] = await page.evaluate(() => [
      window.avarStudio.preview.jointValue('pan'),
      window.avarStudio.state.status.channels.find((c) => c.name === 'neck_pan').measured,
    ]);
    return Math.abs(angle - (at * Math.PI) / 180) < 1e-12 && Math.abs(at + 40) < 0.5;
  });
  const left = await drawnAt('eyes');
  await holdAt('neck_pan', 40);
  const right = await until('the eyes to move in the view', async () => {
    const p = await drawnAt('eyes');
    return Math.hypot(p.x - left.x, p.y - left.y) > 5 && p;
  });
  assert.ok(right, 'the effector moved on screen');
  // The joint is drawn where the view says it is: not the background.
  const pan = await drawnAt('pan');
  assert.notDeepEqual(await pixelAt(pan.x, pan.y), [0x18, 0x1b, 0x20]);
  await page.screenshot({ path: join(out, 'studio-preview.png') });
});

test('letting the neck go hands it back to the show', async () => {
  await page.evaluate(() => window.avarStudio.state.connection.send({ type: 'release', channel: 'neck_pan' }));
  await until('the neck to follow the show', () =>
    page.evaluate(() => !window.avarStudio.state.status.channels.find((c) => c.name === 'neck_pan').held),
  );
});

test("dragging the show's target holds it there and the neck follows; letting go hands it back", async () => {
  const status = () => page.evaluate(() => window.avarStudio.state.status);
  const before = (await status()).targets[0];
  assert.equal(before.name, 'eyes');
  assert.equal(before.held, false);
  const drawn = await until('the target drawn', () => page.evaluate(() => window.avarStudio.preview.targetScreenPosition(0)));
  const start = await onCanvas(page, 'preview', drawn.x, drawn.y);
  const panBefore = await measured('neck_pan');
  await page.mouse.move(start.x, start.y);
  await page.mouse.down();
  // Across the view: the fly starts to the figure's right; dragged toward its left.
  await page.mouse.move(start.x + 90, start.y, { steps: 10 });
  const held = await until('the target held where it was dragged', async () => {
    const t = (await status()).targets[0];
    return t.held && Math.hypot(t.point[0] - before.point[0], t.point[1] - before.point[1], t.point[2] - before.point[2]) > 0.05 && t;
  });
  await until('the neck to turn toward it', async () => Math.abs((await measured('neck_pan')) - panBefore) > 5);
  await page.screenshot({ path: join(out, 'studio-aim.png') });
  await page.mouse.up();
  await until('the target handed back to the show', async () => !(await status()).targets[0].held);
  assert.ok(held.point.every(Number.isFinite));
});

test("the dope sheet shows the target's keys under the channels", async () => {
  const rows = await page.evaluate(() => window.avarStudio.dope.extraRows().map((r) => `${r.name}.${r.axis}:${r.keys.length}`));
  assert.deepEqual(rows, ['eyes.x:3', 'eyes.y:5', 'eyes.z:4']);
});

test('a click on a joint selects its channel', async () => {
  const tilt = await drawnAt('tilt');
  const at = await onCanvas(page, 'preview', tilt.x, tilt.y);
  await page.mouse.click(at.x, at.y);
  await until('the tilt channel to be selected', () => page.evaluate(() => window.avarStudio.state.channel === 'neck_tilt'));
  await until('its row to show it', () => page.isVisible('.pose-row.selected[data-channel="neck_tilt"]'));
});
