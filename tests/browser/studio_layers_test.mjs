// The studio's page on a layered show (tests/browser/studio_harness.mjs): the dope sheet draws
// each layer's clip placements as bars under the channels, where their times are.
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import { openStudio, out, until } from './studio_harness.mjs';

let page;
let close;

before(async () => {
  ({ page, close } = await openStudio({ show: 'layered-head.yaml', rig: 'hello-head.yaml', channel: 'lid_left' }));
});

after(async () => {
  await close?.();
});

test("each layer is a row of its clips' placements", async () => {
  const rows = await page.evaluate(() =>
    window.avarStudio.dope.extraRows().map((r) => `${r.layer.name}: ${r.layer.clips.map((p) => `${p.clip}@${p.start}`).join(' ')}`),
  );
  assert.deepEqual(rows, [
    'idle: idle@0',
    'blinks: blink@3 blink@7.5 blink@12',
    'performance: look@2 talk@4 talk@9',
  ]);
  // The look placement's bar is drawn at its time, in the layer's row (the fourth row under the
  // eight channels: 24 + (8 + 2) * 22 + 11).
  const x = await page.evaluate(() => window.avarStudio.dope.axis().x(3.5));
  const y = 24 + 10 * 22 + 11;
  const drawn = await until('the bar', () =>
    page.evaluate(
      ([x, y]) => {
        const canvas = document.getElementById('dopesheet');
        const ratio = canvas.width / canvas.clientWidth;
        const [r, g, b] = canvas.getContext('2d').getImageData(Math.round(x * ratio), Math.round(y * ratio), 1, 1).data;
        return b > r + 30 && [r, g, b];
      },
      [x, y],
    ),
  );
  assert.ok(drawn);
  await page.screenshot({ path: join(out, 'studio-layers.png') });
});
