// Browser test of pronk's pages (CTest: browser_pages). Builds the page templates from
// web/src, has pronk write each page type (robot run, mechanism run, study, staged study,
// map, comparison of designs; a full-model robot run and a study without the stability analysis
// beside the pulse-model ones), opens each in headless Chromium (Debian's /usr/bin/chromium
// through playwright-core) and checks, at two playback times:
//   - no console error, no page error, no network request (only the page's own file);
//   - the 3-D canvas is not blank, the drawn body sits where the CSV puts it (projected
//     with the page's camera) and moves between the two times in the CSV's direction;
//   - a robot is inside the 3-D view's frame at its first and its last sample;
//   - every plot axis has at least two labelled ticks;
//   - a study report shows as many history points as its journal has evaluations, and the
//     spectral radius only when the study computed it;
//   - a comparison shows one playback per design and one row per trial.
// Usage: node web/test/pages.mjs PRONK_EXE WORK_DIR [--screenshots DIR]
// Exit 77 (CTest: skipped) when Chromium or the npm packages are absent.
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const web = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const root = path.resolve(web, '..');
const [pronk, workArg] = process.argv.slice(2);
const shotsAt = process.argv.indexOf('--screenshots');
const shots = shotsAt > 0 ? path.resolve(process.argv[shotsAt + 1]) : null;
const chromium = process.env.PRONK_CHROMIUM ?? '/usr/bin/chromium';
function skip(why) {
  console.log(`browser test skipped: ${why} (PRONK_WITH_WEB=1 bash scripts/setup.sh installs it)`);
  process.exit(77);
}
if (!pronk || !workArg) { console.error('usage: pages.mjs PRONK_EXE WORK_DIR [--screenshots DIR]'); process.exit(2); }
if (!fs.existsSync(chromium)) skip(`no Chromium at ${chromium}`);
if (!fs.existsSync(path.join(web, 'node_modules', 'playwright-core'))) skip('no web/node_modules (npm ci in web/)');
const { chromium: pw } = await import('playwright-core');

const work = path.resolve(workArg);
fs.rmSync(work, { recursive: true, force: true });
fs.mkdirSync(work, { recursive: true });
const dist = path.join(work, 'dist');
execFileSync(process.execPath, [path.join(web, 'build.mjs'), dist], { stdio: 'inherit' });
const env = { ...process.env, PRONK_WEB_DIR: dist };
const run = (...args) => execFileSync(pronk, args, { env, cwd: root, stdio: ['ignore', 'pipe', 'inherit'] });
const exitOf = (...args) => { try { run(...args); return 0; } catch (e) { return e.status; } };

// The pages under test (simulate exits 1 for a run that fell; its page is still written).
exitOf('simulate', 'studies/scenes/case3_legged_pulse.json', '--out', `${work}/robot`, '-q');
exitOf('simulate', 'studies/mechanisms/four_leg_drop.json', '--out', `${work}/mechanism`, '-q');
exitOf('simulate', 'studies/scenes/pr_running.json', '--out', `${work}/full`, '-q', '--set', '/simulation/duration=2');
run('optimize', 'studies/study2_legged_pulse_duty50.json', '--out', `${work}/study`, '-q',
  '--set', '/optimizer/max_evaluations=24', '--set', '/scenarios/random/count=2', '--set', '/validation/random/count=2');
run('optimize', 'studies/study2_legged_pulse_duty50.json', '--out', `${work}/study_nostab`, '-q',
  '--set', '/optimizer/max_evaluations=6', '--set', '/scenarios/random/count=2', '--set', '/validation/random/count=2',
  '--set', '/stability=false');
run('compare', 'results/study4_cobyla/design.json', 'results/study4_bobyqa/design.json', '--out', `${work}/compare`,
  '-q', '--trials', '4', '--play', 'validation:1');
run('optimize', 'studies/moo_impulse_example.json', '--out', `${work}/pareto`, '-q');
const paretoJson = JSON.parse(fs.readFileSync(`${work}/pareto/pareto.json`, 'utf8'));
fs.cpSync(path.join(root, 'results/study5_fidelity_gap'), `${work}/staged`, { recursive: true });
run('view', `${work}/staged`, '-q');
run('map', 'studies/map_seed_duty.json', '--out', `${work}/map`, '-q', '--set', '/axes/0/count=4',
  '--set', '/axes/1/count=2', '--set', '/trials/count=2', '--set', '/stability=false', '--set', '/trials/duration=4');

function readCsv(file) {
  const lines = fs.readFileSync(file, 'utf8').trim().split('\n');
  const head = lines[0].split(',');
  const rows = lines.slice(1).map((l) => l.split(',').map(Number));
  return Object.fromEntries(head.map((h, i) => [h, rows.map((r) => r[i])]));
}
function at(csv, name, t) {
  const T = csv.t;
  let i = T.findIndex((v) => v > t);
  if (i <= 0) i = i === 0 ? 1 : T.length - 1;
  const s = (t - T[i - 1]) / (T[i] - T[i - 1] || 1);
  return csv[name][i - 1] + Math.min(1, Math.max(0, s)) * (csv[name][i] - csv[name][i - 1]);
}
function evaluations(journal) {
  return fs.readFileSync(journal, 'utf8').split('\n').filter((l) => l.includes('"type":"evaluation"')).length;
}

const pages = [
  { name: 'robot', file: 'robot/view.html', dir: 'robot', times: [0.1, 0.9] },
  { name: 'full model', file: 'full/view.html', dir: 'full', times: [0.1, 0.9] },
  { name: 'mechanism', file: 'mechanism/view.html', dir: 'mechanism', times: [0.05, 0.5] },
  { name: 'study', file: 'study/report.html', dir: 'study/tuned', times: [0.1, 0.9],
    evaluations: evaluations(`${work}/study/journal.jsonl`), spectralRow: true },
  { name: 'study (stability off)', file: 'study_nostab/report.html', dir: 'study_nostab/tuned', times: [0.1, 0.9],
    evaluations: evaluations(`${work}/study_nostab/journal.jsonl`), spectralRow: false },
  { name: 'staged', file: 'staged/report.html', dir: 'staged/stages/4_mujoco/tuned', times: [0.1, 0.9],
    evaluations: ['1_impulse', '2_pulse', '3_full', '4_mujoco'].map((s) => evaluations(`${work}/staged/stages/${s}/journal.jsonl`)).reduce((a, b) => a + b) },
  { name: 'map', file: 'map/report.html', dir: null, times: [0.1, 0.9] },
  { name: 'pareto', file: 'pareto/report.html', dir: `pareto/front/${paretoJson.knee}`, times: [0.1, 0.9],
    front: paretoJson.front.length, knee: paretoJson.knee },
  { name: 'compare', file: 'compare/report.html', dir: 'compare/runs/study4_cobyla', times: [0.1, 0.9],
    designs: 2, trialRows: fs.readFileSync(`${work}/compare/trials.csv`, 'utf8').trim().split('\n').length - 1 },
];

const browser = await pw.launch({
  executablePath: chromium, headless: true,
  args: ['--headless=new', '--no-sandbox', '--enable-unsafe-swiftshader', '--disable-gpu', '--disable-quic',
    '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});
let passed = 0, failed = 0;
const check = (page, what, ok, detail = '') => {
  if (ok) passed++; else failed++;
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${page}: ${what}${detail ? ' (' + detail + ')' : ''}`);
};
for (const p of pages) {
  const ctx = await browser.newContext({ viewport: { width: 1400, height: 900 } });
  const page = await ctx.newPage();
  // Generous limits: they only catch a page that never becomes ready, and a loaded machine
  // (software WebGL on 2 busy cores) must not fail the test by being slow.
  page.setDefaultTimeout(180000);
  const errors = [], requests = [];
  const url = pathToFileURL(path.join(work, p.file)).href;
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('request', (r) => { if (r.url() !== url) requests.push(r.url()); });
  await page.goto(url);
  await page.waitForFunction(() => window.pronkTest !== undefined);
  const size = fs.statSync(path.join(work, p.file)).size;
  const hasScene = await page.evaluate(() => typeof window.pronkTest.tracked === 'function');
  if (p.name !== 'map' || hasScene) {
    const hook = await page.evaluate(() => ({ t0: pronkTest.t0, t1: pronkTest.t1, source: pronkTest.source }));
    const dir = p.dir ?? null;
    // A robot is framed at its start and followed (the default): inside the 3-D view's
    // frame at the first and at the last sample, whatever the path's length.
    if (await page.evaluate(() => pronkTest.follow())) {
      const framed = [];
      for (const t of [hook.t0, hook.t1]) {
        framed.push(await page.evaluate((tt) => {
          pronkTest.setTime(tt);
          const c = pronkTest.canvas(), s = pronkTest.tracked().screen;
          return { x: s.x, y: s.y, w: c.width, h: c.height };
        }, t));
      }
      check(p.name, 'the robot is inside the frame at t0 and at the last sample',
        framed.every((f) => f.x > 0 && f.x < f.w && f.y > 0 && f.y < f.h),
        framed.map((f) => `(${f.x.toFixed(0)}, ${f.y.toFixed(0)}) in ${f.w} x ${f.h}`).join(', '));
      // The motion checks below need a fixed camera.
      await page.evaluate((tt) => { pronkTest.setTime(tt); pronkTest.setFollow(false); }, hook.t0);
    } else {
      check(p.name, 'follow is on for robots only (a mechanism page keeps its camera)', p.name === 'mechanism', 'follow is off');
    }
    const ts = p.times.map((f) => hook.t0 + f * (hook.t1 - hook.t0));
    const drawn = [];
    for (const t of ts) {
      drawn.push(await page.evaluate((tt) => {
        pronkTest.setTime(tt);
        const c = pronkTest.canvas();
        const colors = new Set();
        for (let i = 1; i < 24; i++) for (let j = 1; j < 24; j++) colors.add(pronkTest.pixel(c.width * i / 24, c.height * j / 24).join());
        const tr = pronkTest.tracked();
        return { ...tr, colors: colors.size, here: pronkTest.pixel(tr.screen.x, tr.screen.y) };
      }, t));
    }
    check(p.name, 'the 3-D canvas is not blank', drawn.every((d) => d.colors >= 3), `${drawn.map((d) => d.colors).join(', ')} colours on a grid`);
    // Where the CSV puts the tracked point (map: the stored trial, read back from the page data).
    let table;
    if (dir) {
      table = readCsv(path.join(work, dir, hook.source.file));
    } else {  // a map: the trial on show, as playback.json stores it
      const pb = JSON.parse(fs.readFileSync(`${work}/map/playback.json`, 'utf8'));
      const shown = await page.evaluate(() => pronkTest.playedCell());
      const cell = pb.cells.find((c) => c.cell === shown);
      table = Object.fromEntries(pb.columns.map((c, i) => [c, cell.data[i]]));
    }
    const want = ts.map((t) => hook.source.columns.map((c) => at(table, c, t)));
    const err = Math.max(...drawn.map((d, k) => Math.hypot(...d.world.map((v, i) => v - want[k][i]))));
    check(p.name, 'the drawn body is where the CSV (map: playback.json) says', err < 2e-3, `max ${err.toExponential(2)} m`);
    const proj = [];
    for (const w of want) proj.push(await page.evaluate((ww) => pronkTest.project(ww), w));
    const dd = [drawn[1].screen.x - drawn[0].screen.x, drawn[1].screen.y - drawn[0].screen.y];
    const dc = [proj[1].x - proj[0].x, proj[1].y - proj[0].y];
    const cos = (dd[0] * dc[0] + dd[1] * dc[1]) / (Math.hypot(...dd) * Math.hypot(...dc) || 1);
    check(p.name, 'the body moves on screen in the direction of the trajectory',
      Math.hypot(...dd) > 5 && cos > 0.99, `moved ${Math.hypot(...dd).toFixed(0)} px, cos ${cos.toFixed(4)}`);
    const back = await page.evaluate((s) => pronkTest.pixel(s.x, s.y), drawn[0].screen);
    check(p.name, 'the body was drawn where it was (the pixel changed after it left)',
      back.join() !== drawn[0].here.join(), `${drawn[0].here} then ${back}`);
  }
  // Every linear plot axis on the page has at least two labelled ticks (a scale to read).
  const ticks = await page.evaluate(() => (pronkTest.fewestAxisTicks ? pronkTest.fewestAxisTicks() : null));
  check(p.name, 'every plot axis has at least two labelled ticks',
    ticks !== null && (Number.isFinite(ticks) || p.name === 'map') && !(ticks < 2), `fewest ${ticks}`);
  const widths = await page.evaluate(() => ({ page: document.documentElement.scrollWidth, window: window.innerWidth }));
  check(p.name, 'no horizontal scrolling', widths.page <= widths.window, `${widths.page} px wide in a ${widths.window} px window`);
  if (p.name === 'map') {
    // The boundary line runs through exactly the rows that have a boundary (not none_good).
    const [head, ...rows] = fs.readFileSync(`${work}/map/boundary.csv`, 'utf8').trim().split('\n').map((l) => l.split(','));
    const want = rows.filter((r) => r[head.indexOf('status')] !== 'none_good').map((r) => Number(r[head.indexOf('row')]));
    const drawnRows = await page.evaluate(() => pronkTest.boundaryRows());
    check(p.name, 'the boundary line is drawn through the rows with a boundary, and only those',
      JSON.stringify(drawnRows) === JSON.stringify(want),
      `drawn ${JSON.stringify(drawnRows)}, rows with a boundary ${JSON.stringify(want)} of ${rows.length}`);
  }
  if (p.designs !== undefined) {
    // A comparison: one playback per design, one table row per trial of trials.csv.
    const shown = await page.evaluate(() => ({ designs: pronkTest.designs(), rows: pronkTest.trialRows(),
      canvases: document.querySelectorAll('.stage canvas').length }));
    check(p.name, 'one playback per design', shown.designs === p.designs && shown.canvases === p.designs,
      `${shown.canvases} views of ${shown.designs} designs`);
    check(p.name, 'trial rows = trials.csv rows', shown.rows === p.trialRows, `${shown.rows} vs ${p.trialRows}`);
  }
  if (p.front !== undefined) {
    // A multi-objective study: every front design is a point; the knee is selected first and a
    // pick selects another design and plays it (a new 3-D view).
    const shown = await page.evaluate(() => ({ front: pronkTest.frontPoints(), chosen: pronkTest.chosen() }));
    check(p.name, 'front points = pareto.json front', shown.front === p.front, `${shown.front} vs ${p.front}`);
    check(p.name, 'the knee is selected first', shown.chosen === p.knee, `${shown.chosen} vs ${p.knee}`);
    const other = (p.knee + 1) % p.front;
    const picked = await page.evaluate((k) => { pronkTest.pick(k); return { chosen: pronkTest.chosen(),
      canvases: document.querySelectorAll('.stage canvas').length,
      heading: [...document.querySelectorAll('h3')].map((h) => h.textContent).find((t) => t.startsWith('design ')) }; }, other);
    check(p.name, 'a pick selects that design and shows its playback',
      picked.chosen === other && picked.canvases === 1 && picked.heading.startsWith(`design ${other} `),
      `${picked.chosen}, ${picked.canvases} views, "${picked.heading}"`);
  }
  if (p.spectralRow !== undefined) {
    // The spectral radius is a row of the metric tables only when the study computed it (off,
    // it would read 0: a perfect value).
    const rows = await page.evaluate(() => [...document.querySelectorAll('td')]
      .filter((td) => td.textContent.trim() === 'spectral_radius').length);
    check(p.name, p.spectralRow ? 'the spectral radius is shown (stability on)' : 'no spectral radius row (stability off)',
      (rows > 0) === p.spectralRow, `${rows} rows`);
  }
  if (p.evaluations !== undefined) {
    const n = await page.evaluate(() => pronkTest.historyPoints());
    check(p.name, 'history points = journal evaluations', n === p.evaluations, `${n} vs ${p.evaluations}`);
  }
  if (shots) {
    fs.mkdirSync(shots, { recursive: true });
    await page.screenshot({ path: path.join(shots, `${p.name}.png`), fullPage: false });
  }
  check(p.name, 'no console errors', errors.length === 0, errors.slice(0, 3).join(' | '));
  check(p.name, 'no network requests', requests.length === 0, requests.slice(0, 3).join(' '));
  check(p.name, 'page under 5 MB', size < 5e6, `${(size / 1e6).toFixed(2)} MB`);
  await ctx.close();
}
await browser.close();
console.log(`${passed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);
