// Builds the page templates dist/view.html and dist/report.html: each is one HTML file
// with uPlot's CSS, the page CSS and the bundled script (three.js, uPlot and src/) inlined.
// pronk fills the placeholder @PRONK_DATA@ with the run's JSON when it writes a page.
import * as esbuild from 'esbuild';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const read = (p) => fs.readFileSync(path.join(here, p), 'utf8');
const css = read('node_modules/uplot/dist/uPlot.min.css') + '\n' + read('src/page.css');
const versions = ['three', 'uplot'].map((n) => `${n} ${JSON.parse(read(`node_modules/${n}/package.json`)).version}`);
// node build.mjs [OUT_DIR] (default: web/dist)
const outDir = path.resolve(process.argv[2] ?? path.join(here, 'dist'));
fs.mkdirSync(outDir, { recursive: true });
for (const name of ['view', 'report']) {
  const out = await esbuild.build({
    entryPoints: [path.join(here, 'src', `${name}.js`)], bundle: true, minify: true, format: 'iife',
    target: 'es2020', write: false, legalComments: 'eof', logLevel: 'warning',
  });
  // A script element ends at the first "</script": escape it inside the bundle.
  const js = out.outputFiles[0].text.replace(/<\/script/gi, '<\\/script');
  const html = `<!doctype html>
<html lang="en"><head><meta charset="utf-8"><meta name="viewport" content="width=device-width, initial-scale=1">
<meta name="generator" content="pronk (${versions.join(', ')})"><title>pronk</title>
<style>${css}</style></head>
<body><div id="app"></div>
<script id="pronk-data" type="application/json">@PRONK_DATA@</script>
<script>${js}</script>
</body></html>
`;
  if (html.indexOf('@PRONK_DATA@') !== html.lastIndexOf('@PRONK_DATA@')) throw new Error('placeholder twice');
  fs.writeFileSync(path.join(outDir, `${name}.html`), html);
  console.log(`web: ${path.join(outDir, name + '.html')} ${(html.length / 1024).toFixed(0)} KiB (${versions.join(', ')})`);
}
