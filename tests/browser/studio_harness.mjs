// What the studio's browser tests share: `avar studio --sim` started on a copy of an example show
// (its rig's link watchdog widened: Chromium and the build share two cores here, and a stalled
// simulator must not fault the figure in the middle of a test; the watchdog itself is tested in
// the fault matrix), headless Chromium from Debian driven by Playwright (npm), and waiting on
// conditions rather than on time.
//
// A test file is run as: node FILE --avar build/apps/avar --modules studio/page --out DIR
// It exits 77 (skipped) when Chromium is not installed.
import assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import { copyFileSync, existsSync, mkdirSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import { basename, dirname, isAbsolute, join, resolve } from 'node:path';

const args = process.argv.slice(2);
const option = (name) => {
  const at = args.indexOf(name);
  if (at < 0 || at + 1 >= args.length) {
    console.error(`usage: node ${basename(process.argv[1])} --avar AVAR --modules studio/page --out DIR (missing ${name})`);
    process.exit(2);
  }
  return resolve(args[at + 1]);
};
const avar = option('--avar');
const modules = option('--modules');
export const out = option('--out');
export const source = resolve(import.meta.dirname, '../..');
const CHROMIUM = process.env.AVAR_CHROMIUM ?? '/usr/bin/chromium';
if (!existsSync(CHROMIUM)) {
  console.log(`skipped: no Chromium at ${CHROMIUM} (apt-get install chromium; scripts/install-deps.sh does)`);
  process.exit(77);
}
const { chromium } = createRequire(join(modules, 'package.json'))('playwright-core');
mkdirSync(out, { recursive: true });

/// Polls `probe` until it returns a truthy value, which it returns; fails with `what` after
/// `seconds` (15).
export async function until(what, probe, seconds = 15) {
  const deadline = Date.now() + seconds * 1000;
  for (;;) {
    const value = await probe();
    if (value) return value;
    if (Date.now() > deadline) assert.fail(`timed out waiting for ${what}`);
    await new Promise((r) => setTimeout(r, 20));
  }
}

/// Starts `avar studio` on a copy of examples/shows/SHOW with examples/rigs/RIG (or the files at
/// those absolute paths) on the simulator, opens its page in Chromium and waits for the first
/// status and the engine's curves of `channel` (up to `patience` seconds, 15). `files` (name to
/// contents) are written beside the show first: what it names (a sound, a viseme table).
/// Returns {page, showFile, original (the show's bytes), close()}.
export async function openStudio({ show, rig, channel, patience = 15, files = {} }) {
  const work = mkdtempSync(join(tmpdir(), 'avar-studio-page-'));
  for (const [name, contents] of Object.entries(files)) writeFileSync(join(work, name), contents);
  const showFile = join(work, basename(show));
  copyFileSync(isAbsolute(show) ? show : join(source, 'examples/shows', show), showFile);
  const original = readFileSync(showFile);
  const rigFile = join(work, `rig-${basename(rig)}`);
  const rigSource = isAbsolute(rig) ? rig : join(source, 'examples/rigs', rig);
  // The copy stays beside nothing: a URDF the rig names relative to itself is named in full.
  const rigText = readFileSync(rigSource, 'utf8').replace(/\n( +)urdf: (\S+)/, (line, indent, path) =>
    isAbsolute(path) ? line : `\n${indent}urdf: ${join(dirname(rigSource), path)}`,
  );
  // A link written as a block (port: sim on a line of its own) or in flow style ({port: sim, ...}).
  const widened = rigText
    .replace(/\n( +)port: sim([^\n]*)\n/g, '\n$1port: sim$2\n$1watchdog_ms: 5000\n')
    .replace(/\{port: sim,/g, '{port: sim, watchdog_ms: 5000,');
  assert.notEqual(widened, rigText, `${rig} has a simulated link`);
  writeFileSync(rigFile, widened);

  const server = spawn(avar, ['studio', showFile, '--rig', rigFile, '--sim'], { stdio: ['ignore', 'pipe', 'pipe'] });
  let printed = '';
  server.stderr.on('data', (d) => process.stderr.write(d));
  const url = await until('avar studio to print its URL', () => {
    const chunk = server.stdout.read();
    if (chunk) printed += chunk.toString();
    return printed.match(/studio: (http:\/\/\S+)/)?.[1];
  });
  // WebGL in headless Chromium without a GPU: SwiftShader, which Chromium asks to be allowed.
  const browser = await chromium.launch({ executablePath: CHROMIUM, args: ['--no-sandbox', '--enable-unsafe-swiftshader'] });
  const page = await browser.newPage({ viewport: { width: 1400, height: 860 } });
  page.on('pageerror', (e) => assert.fail(`the page threw: ${e.message}`));
  await page.goto(url);
  await page.waitForSelector('body[data-ready="yes"]', { timeout: patience * 1000 });
  await until('the first status', () => page.evaluate(() => window.avarStudio.state.status), patience);
  await until("the engine's curves", () => page.evaluate((c) => window.avarStudio.state.engine.has(c), channel), patience);
  const close = async () => {
    await browser.close();
    if (server.exitCode === null) {
      server.kill('SIGINT');
      await new Promise((r) => server.once('exit', r));
    }
  };
  return { page, showFile, original, close };
}

/// Client coordinates of a point of a canvas (#id) given in its CSS pixels.
export async function onCanvas(page, id, x, y) {
  const box = await page.locator(`#${id}`).boundingBox();
  return { x: box.x + x, y: box.y + y };
}

/// The colour drawn at a point of the 3-D view (its CSS pixels), as [r, g, b].
export const previewPixelAt = (page, x, y) =>
  page.evaluate(
    ([x, y]) => {
      const view = document.getElementById('preview');
      const copy = document.createElement('canvas');
      copy.width = view.width;
      copy.height = view.height;
      const g = copy.getContext('2d');
      g.drawImage(view, 0, 0);
      const ratio = view.width / view.clientWidth;
      return [...g.getImageData(Math.round(x * ratio), Math.round(y * ratio), 1, 1).data].slice(0, 3);
    },
    [x, y],
  );
