// Bundles the studio page for `avar studio` to serve: src/main.ts and three.js into app.js, with
// index.html, style.css and the curve engine (avar_curves.js, built by emscripten) beside them.
// No network at run time: everything the page loads is in the output folder.
//
//   node build.mjs --outdir build/studio/page --engine build/studio/avar_curves.js
import { build } from 'esbuild';
import { copyFileSync, mkdirSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const args = process.argv.slice(2);
const option = (name) => {
  const at = args.indexOf(name);
  if (at < 0 || at + 1 >= args.length) {
    console.error(`usage: node build.mjs --outdir DIR --engine avar_curves.js (missing ${name})`);
    process.exit(2);
  }
  return args[at + 1];
};
const outdir = option('--outdir');
const engine = option('--engine');

mkdirSync(outdir, { recursive: true });
await build({
  entryPoints: [join(here, 'src/main.ts')],
  bundle: true,
  minify: true,
  sourcemap: true,
  format: 'esm',
  target: 'es2022',
  outfile: join(outdir, 'app.js'),
  logLevel: 'warning',
  legalComments: 'linked',
});
for (const file of ['index.html', 'style.css']) copyFileSync(join(here, file), join(outdir, file));
copyFileSync(engine, join(outdir, 'avar_curves.js'));
