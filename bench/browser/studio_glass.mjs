// The browser half of avar-bench-studio's glass-to-wire measurement (bench/studio.cpp runs it):
// opens the studio's page at URL in headless Chromium (Debian's, driven by Playwright), presses
// the pointer on the jaw's slider HOLDS times, each at a random phase, and prints when each
// pointerdown happened, as the page's event time stamp on the system clock, for the bench to
// pair with the moment the simulated device took the new command. Between presses it lets go
// and waits for the jaw to be back at rest.
// Output lines: `skew MS` (the page's clock minus the system clock, as read in the page), then
// `pointer EPOCH_MS` per press, then `done`. Exits 77 without Chromium.
// Usage: node studio_glass.mjs --url URL --modules studio/page [--holds N]
import { existsSync } from 'node:fs';
import { createRequire } from 'node:module';
import { join, resolve } from 'node:path';

const args = process.argv.slice(2);
const option = (name, fallback) => {
  const at = args.indexOf(name);
  return at >= 0 && at + 1 < args.length ? args[at + 1] : fallback;
};
const url = option('--url');
const modules = resolve(option('--modules', 'studio/page'));
const holds = Number(option('--holds', '100'));
const CHROMIUM = process.env.AVAR_CHROMIUM ?? '/usr/bin/chromium';
if (!url) {
  console.error('usage: node studio_glass.mjs --url URL --modules studio/page [--holds N]');
  process.exit(2);
}
if (!existsSync(CHROMIUM)) {
  console.log(`skipped: no Chromium at ${CHROMIUM}`);
  process.exit(77);
}
const { chromium } = createRequire(join(modules, 'package.json'))('playwright-core');

async function until(what, probe, seconds = 15) {
  const deadline = Date.now() + seconds * 1000;
  for (;;) {
    const value = await probe();
    if (value) return value;
    if (Date.now() > deadline) throw new Error(`timed out waiting for ${what}`);
    await new Promise((r) => setTimeout(r, 5));
  }
}

const browser = await chromium.launch({ executablePath: CHROMIUM, args: ['--no-sandbox', '--enable-unsafe-swiftshader'] });
try {
  const page = await browser.newPage({ viewport: { width: 1400, height: 860 } });
  await page.goto(url);
  await page.waitForSelector('body[data-ready="yes"]', { timeout: 30000 });
  await until('the first status', () => page.evaluate(() => window.avarStudio.state.status));
  // Every pointerdown's time stamp on the system clock (ms since the epoch).
  await page.evaluate(() => {
    window.pointerDowns = [];
    document.addEventListener('pointerdown', (e) => window.pointerDowns.push(performance.timeOrigin + e.timeStamp), { capture: true });
  });
  const skew = await page.evaluate(() => performance.timeOrigin + performance.now() - Date.now());
  console.log(`skew ${skew.toFixed(3)}`);
  const jaw = (field) =>
    page.evaluate((f) => window.avarStudio.state.status.channels.find((c) => c.name === 'jaw')[f], field);
  const slider = page.locator('[data-channel="jaw"] input[type="range"]');
  const box = await slider.boundingBox();
  let seed = 20261207;
  const random = () => {
    seed = (seed * 1103515245 + 12345) % 2147483648;
    return seed / 2147483648;
  };
  for (let i = 0; i < holds; i++) {
    // At rest, and the slider showing it again (a press must change its value to send a hold).
    await until(
      'the jaw at rest',
      async () => (await jaw('command')) === 0 && !(await jaw('held')) && Number(await slider.inputValue()) === 0,
    );
    // Still for longer than the bench's settle time (45 ms), then a random phase of the 20 ms tick.
    await new Promise((r) => setTimeout(r, 60 + 20 * random()));
    // Half way along the slider: about 15 degrees of the jaw's 0 to 30.
    await page.mouse.move(box.x + box.width * 0.5, box.y + box.height / 2);
    await page.mouse.down();
    const at = await until('the pointerdown', () => page.evaluate(() => window.pointerDowns.shift()));
    console.log(`pointer ${at.toFixed(3)}`);
    await until('the jaw to move', async () => (await jaw('command')) > 0);
    await page.mouse.up();
    // Let go of the slider's focus too: the status moves a slider only while nobody has it.
    await slider.blur();
  }
  console.log('done');
} finally {
  await browser.close();
}
