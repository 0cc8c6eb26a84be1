// CTest web_templates: the committed page templates web/dist/view.html and report.html are
// exactly what web/build.mjs builds from web/src and the packages pinned by
// web/package-lock.json, so they cannot go stale. Exit 77 (skipped) without the packages.
// Usage: node web/test/templates.mjs WORK_DIR
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const web = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const work = process.argv[2];
if (!work) { console.error('usage: templates.mjs WORK_DIR'); process.exit(2); }
if (!fs.existsSync(path.join(web, 'node_modules', 'esbuild'))) {
  console.log('web_templates skipped: no web/node_modules (PRONK_WITH_WEB=1 bash scripts/setup.sh runs npm ci)');
  process.exit(77);
}
fs.rmSync(work, { recursive: true, force: true });
execFileSync(process.execPath, [path.join(web, 'build.mjs'), work], { stdio: ['ignore', 'ignore', 'inherit'] });
let stale = 0;
for (const name of ['view.html', 'report.html']) {
  const committed = path.join(web, 'dist', name);
  const fresh = fs.readFileSync(path.join(work, name));
  const have = fs.existsSync(committed) ? fs.readFileSync(committed) : Buffer.alloc(0);
  if (Buffer.compare(fresh, have) === 0) {
    console.log(`ok   web/dist/${name} equals a fresh build (${fresh.length} bytes)`);
    continue;
  }
  let at = 0;
  while (at < fresh.length && at < have.length && fresh[at] === have[at]) at++;
  console.log(`FAIL web/dist/${name} (${have.length} bytes) differs from a fresh build of web/src ` +
    `(${fresh.length} bytes) from byte ${at}: rebuild it with \`(cd web && npm ci && node build.mjs)\` ` +
    'and commit web/dist');
  stale++;
}
process.exit(stale ? 1 : 0);
