// The studio's page in a real browser (tests/browser/studio_harness.mjs) against
// `avar studio --sim` on a copy of the bundled show. It poses the figure with a slider and reads
// where the simulated servo went, scrubs and checks the figure follows, drags keys in the dope
// sheet and the graph editor, edits a key in the inspector, copies, pastes and ripples time,
// undoes, redoes, saves and diffs the file, and takes the screenshots the studio guide shows.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import { onCanvas, openStudio, out, until } from './studio_harness.mjs';

let page;
let showFile;
let original;
let close;

/// Waits until every message the page sent is answered and what the server broadcast before
/// those answers has arrived (a last request's reply comes after them).
const settled = () =>
  page.evaluate(async () => {
    const connection = window.avarStudio.state.connection;
    while (connection.inFlight() > 0) await new Promise((r) => setTimeout(r, 5));
    await connection.request({ type: 'curves' });
  });
const status = () => page.evaluate(() => window.avarStudio.state.status);
const showState = () => page.evaluate(() => window.avarStudio.state.show);
const channelStatus = async (name) => (await status())?.channels.find((c) => c.name === name);
/// Where a key of a channel is drawn in the dope sheet (CSS pixels of its canvas).
const keyInDopeSheet = (channel, index) =>
  page.evaluate(
    ([channel, index]) => {
      const { state, dope } = window.avarStudio;
      const row = state.rig.channels.findIndex((c) => c.name === channel);
      return { x: dope.axis().x(state.keys(channel)[index].time), y: 24 + row * 22 + 11 };
    },
    [channel, index],
  );

before(async () => {
  ({ page, showFile, original, close } = await openStudio({ show: 'hello-head.yaml', rig: 'hello-head.yaml', channel: 'jaw' }));
});

after(async () => {
  await close?.();
});

test('the page shows the rig, the show and the figure, and draws the keys', async () => {
  assert.equal(await page.textContent('#title'), 'hello-head');
  assert.equal(await page.locator('.pose-row').count(), 8);
  assert.equal(await page.textContent('#connection'), 'connected');
  // The dope sheet draws the jaw's keys where their times are.
  const key = await keyInDopeSheet('jaw', 2);
  const pixel = await page.evaluate(([x, y]) => {
    const canvas = document.getElementById('dopesheet');
    const ratio = canvas.width / canvas.clientWidth;
    return [...canvas.getContext('2d').getImageData(Math.round(x * ratio), Math.round(y * ratio), 1, 1).data];
  }, [key.x, key.y]);
  assert.deepEqual(pixel.slice(0, 3), [0xd7, 0xdb, 0xe0], 'a key is drawn at its time');
  await page.screenshot({ path: join(out, 'studio.png') });
});

test('a slider holds the channel and the simulated servo goes there; letting go hands it back', async () => {
  const slider = page.locator('.pose-row[data-channel="jaw"] input[type="range"]');
  const box = await slider.boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.down();
  await page.mouse.move(box.x + box.width * 0.75, box.y + box.height / 2, { steps: 5 });
  const wanted = Number(await slider.inputValue());
  assert.ok(wanted > 15 && wanted < 30, `the slider moved to ${wanted}`);
  const reached = await until('the simulated jaw to reach the slider', async () => {
    const jaw = await channelStatus('jaw');
    return jaw.held && Math.abs(jaw.measured - wanted) < 0.2 && jaw;
  });
  assert.ok(reached.command <= 30 && reached.command >= 0);
  await page.mouse.up();
  await until('the jaw to be handed back to the show', async () => !(await channelStatus('jaw')).held);
});

test('scrubbing the ruler moves show time and the figure follows', async () => {
  const from = await page.evaluate(() => window.avarStudio.dope.axis().x(2));
  const to = await page.evaluate(() => window.avarStudio.dope.axis().x(3.3));
  const start = await onCanvas(page, 'dopesheet', from, 12);
  const end = await onCanvas(page, 'dopesheet', to, 12);
  await page.mouse.move(start.x, start.y);
  await page.mouse.down();
  await page.mouse.move(end.x, end.y, { steps: 8 });
  await page.mouse.up();
  const s = await until('show time at the playhead', async () => {
    const now = await status();
    return now.paused && Math.abs(now.show_time - 3.3) < 0.02 && now;
  });
  const expected = await page.evaluate((t) => window.avarStudio.state.engine.sample('neck_pan', t), s.show_time);
  await until('the neck to follow the scrub', async () => Math.abs((await channelStatus('neck_pan')).measured - expected) < 0.3);
});

test('a key dragged in the dope sheet moves; undo, redo and save write the file', async () => {
  const before = (await showState()).show.tracks.eyes_pan[4].time;
  const key = await keyInDopeSheet('eyes_pan', 4);
  const start = await onCanvas(page, 'dopesheet', key.x, key.y);
  await page.mouse.move(start.x, start.y);
  await page.mouse.down();
  await page.mouse.move(start.x - 40, start.y, { steps: 6 });
  await page.mouse.up();
  await settled();
  const moved = await until('the moved key', async () => {
    const s = await showState();
    const t = s.show.tracks.eyes_pan[4].time;
    return t < before - 0.1 && s.modified && t;
  });
  assert.ok(moved > 5.5, 'the key stays after its neighbour');
  assert.deepEqual(readFileSync(showFile), original, 'nothing is written before save');
  await page.keyboard.press('Control+z');
  await until('the undo', async () => {
    const s = await showState();
    return !s.modified && s.show.tracks.eyes_pan[4].time === before;
  });
  await page.keyboard.press('Control+Shift+z');
  await until('the redo', async () => (await showState()).show.tracks.eyes_pan[4].time === moved);
  await page.click('#save');
  await until('the save', async () => (await page.textContent('#notice')).startsWith('saved'));
  const saved = readFileSync(showFile, 'utf8');
  assert.notDeepEqual(Buffer.from(saved), original);
  assert.match(saved, new RegExp(`time: ${String(moved).replace('.', '\\.')}`));
  // Undone back to the show as opened, save writes the original bytes.
  await page.click('#undo');
  await until('the undo', async () => (await showState()).show.tracks.eyes_pan[4].time === before);
  await page.evaluate(() => (window.avarStudio.state.notice = ''));
  await page.click('#save');
  await until('the second save', async () => (await page.textContent('#notice')).startsWith('saved'));
  assert.ok(readFileSync(showFile).equals(original), 'the show as opened is saved as its own bytes');
  assert.equal((await showState()).modified, false);
});

test('the graph editor draws the curve from the engine and a key dragged there changes its value', async () => {
  await page.click('.pose-row[data-channel="neck_pan"] .channel-name');
  await page.screenshot({ path: join(out, 'studio-graph.png') });
  const at = await page.evaluate(() => {
    const { state, graph } = window.avarStudio;
    const axes = graph.axes();
    const key = state.keys('neck_pan')[2];
    return { x: axes.time.x(key.time), y: axes.y(key.value), value: key.value };
  });
  const start = await onCanvas(page, 'graph', at.x, at.y);
  await page.mouse.move(start.x, start.y);
  await page.mouse.down();
  await page.mouse.move(start.x, start.y + 25, { steps: 5 });
  await page.mouse.up();
  await settled();
  const value = await until('the key to take its new value', async () => {
    const v = (await showState()).show.tracks.neck_pan[2].value;
    return v < at.value - 1 && v;
  });
  // The engine now draws the curve through the new value.
  await until('the redrawn curve', () =>
    page.evaluate((v) => window.avarStudio.state.engine.sample('neck_pan', 3) === v, value),
  );
  await page.click('#undo');
  await until('the undo', async () => (await showState()).show.tracks.neck_pan[2].value === at.value);
});

/// Clicks a key in the dope sheet (selecting it alone).
async function clickKey(channel, index) {
  const key = await keyInDopeSheet(channel, index);
  const at = await onCanvas(page, 'dopesheet', key.x, key.y);
  await page.mouse.click(at.x, at.y);
}
const keyOf = async (channel, index) => (await showState()).show.tracks[channel][index];
/// Undoes until the show is as opened.
async function undoAll() {
  while ((await showState()).undo !== '') {
    const before = (await showState()).version;
    await page.click('#undo');
    await until('the undo', async () => (await showState()).version > before);
  }
  assert.equal((await showState()).modified, false);
}

test('the key inspector sets an exact value, an interpolation and a handle type', async () => {
  await clickKey('jaw', 3);
  await until('the inspector to show the key', async () => (await page.textContent('#key-label')) === 'jaw key 3');
  assert.equal(await page.inputValue('#key-value'), '4');
  await page.fill('#key-value', '10');
  await page.press('#key-value', 'Enter');
  await until('the typed value', async () => (await keyOf('jaw', 3)).value === 10);
  await page.selectOption('#key-interpolation', 'bezier');
  await until('the interpolation', async () => (await keyOf('jaw', 3)).interpolation === 'bezier');
  // An automatic side made free keeps the handle the engine computed, so the curve does not jump.
  const computed = await page.evaluate(() => window.avarStudio.state.engine.handleOf('jaw', 3, 'right'));
  assert.ok(computed, 'a Bezier key has a computed right handle');
  await page.selectOption('#key-right-type', 'free');
  const key = await until('the handle type', async () => {
    const k = await keyOf('jaw', 3);
    return k.right_type === 'free' && k;
  });
  assert.deepEqual(key.right, computed);
  await page.screenshot({ path: join(out, 'studio-inspector.png') });
  await undoAll();
  assert.equal((await keyOf('jaw', 3)).value, 4);
});

test('copy and paste put keys at the playhead; ripple insert and delete time move every track', async () => {
  const scrub = async (t) => {
    await page.evaluate((time) => window.avarStudio.state.connection.send({ type: 'scrub', time }), t);
    await until(`show time ${t}`, async () => Math.abs((await status()).show_time - t) < 1e-9);
  };
  await scrub(11);
  await clickKey('eyes_pan', 1);
  await page.keyboard.press('Control+c');
  await page.keyboard.press('Control+v');
  await until('the pasted key', async () => (await showState()).show.tracks.eyes_pan.length === 7);
  assert.deepEqual(await keyOf('eyes_pan', 6), { ...(await keyOf('eyes_pan', 1)), time: 11 });
  await scrub(2);
  await page.fill('#time-length', '0.5');
  await page.click('#insert-time');
  await until('the inserted time', async () => (await showState()).show.duration === 12.5);
  assert.equal((await keyOf('eyes_pan', 2)).time, 3.9);
  await page.click('#delete-time');
  await until('the deleted time', async () => (await showState()).show.duration === 12);
  assert.equal((await keyOf('eyes_pan', 2)).time, 3.4);
  await undoAll();
  assert.equal((await showState()).show.tracks.eyes_pan.length, 6);
});

test('arrow keys nudge the selected keys by a tick of the rig; Home shows the whole show', async () => {
  await clickKey('neck_roll', 1);
  const before = (await keyOf('neck_roll', 1)).time;
  await page.keyboard.press('ArrowRight');
  await until('the nudge', async () => (await keyOf('neck_roll', 1)).time !== before);
  assert.ok(Math.abs((await keyOf('neck_roll', 1)).time - (before + 0.02)) < 1e-9, 'one tick at 50 Hz');
  await page.keyboard.press('Shift+ArrowLeft');
  await until('the ten-tick nudge', async () => Math.abs((await keyOf('neck_roll', 1)).time - (before - 0.18)) < 1e-9);
  await page.evaluate(() => {
    const { state } = window.avarStudio;
    state.view = { t0: 5, t1: 6 };
  });
  await page.keyboard.press('Home');
  await until('the whole show in view', () =>
    page.evaluate(() => {
      const { view } = window.avarStudio.state;
      return view.t0 < 0 && view.t1 > 12;
    }),
  );
  await undoAll();
});

test('what asks too much is drawn red with what it asks, and Retime stretches it', async () => {
  await page.click('.pose-row[data-channel="jaw"] .channel-name');
  // The jaw's 25 deg key 0.05 s after its 2 deg key: 460 deg/s, and the jaw allows 300.
  assert.ok(
    await page.evaluate(() =>
      window.avarStudio.state.edit([{ op: 'move', channel: 'jaw', keys: [8], dt: -0.15, dv: 0 }]),
    ),
  );
  await until('the check to find it', async () => (await page.textContent('#retime')) === 'Retime (1)');
  const finding = await page.evaluate(() => window.avarStudio.state.findings.find((f) => f.kind === 'speed'));
  assert.equal(finding.channel, 'jaw');
  assert.ok(Math.abs(finding.required - 460) < 1e-6 && finding.allowed === 300);
  // The dope sheet's row is red over the span.
  const x = await page.evaluate((t) => window.avarStudio.dope.axis().x(t), (finding.t0 + finding.t1) / 2);
  const y = 24 + 0 * 22 + 4;
  const [r, g] = await page.evaluate(([x, y]) => {
    const canvas = document.getElementById('dopesheet');
    const ratio = canvas.width / canvas.clientWidth;
    return [...canvas.getContext('2d').getImageData(Math.round(x * ratio), Math.round(y * ratio), 1, 1).data];
  }, [x, y]);
  assert.ok(r > g + 20, `red over the span (${r}, ${g})`);
  await page.evaluate((t) => {
    const { state } = window.avarStudio;
    state.view = { t0: t - 1.2, t1: t + 1.2 };
    state.changed();
  }, finding.t0);
  await page.screenshot({ path: join(out, 'studio-feasibility.png') });
  await page.click('#retime');
  await until('the retime', async () => (await page.textContent('#retime')) === 'Retime');
  assert.match((await showState()).undo, /^retime 1 span/);
  await page.evaluate(() => {
    const { state } = window.avarStudio;
    state.view = { t0: -0.24, t1: 12.36 };
    state.changed();
  });
  await undoAll();
});

test('the e-stop button stops every actuator at once', async () => {
  await page.click('#estop');
  await until('the e-stop in the status', async () => (await status()).estop);
  await until('the status bar to say so', async () => /E-STOP/.test(await page.textContent('#phase')));
});
