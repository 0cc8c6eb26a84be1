// report.html of a comparison (`pronk compare`): the designs and where they came from, the
// metrics side by side, every trial's outcome for every design, and each design's playback
// of the same trial on one time line, with its height, position errors and attitude plotted.
import { el, fmt, htmlTable, columns, interp } from './data.js';
import { linePlot, setCursorX, palette } from './plots.js';
import { runScene } from './runscene.js';
import { Player } from './player.js';

const outcomeColors = {
  stabilized: '#cdebd3', completed: '#eceff1', fell: '#f6c9c9', diverged: '#e3c9f0', failed: '#ffe0a0',
};
const outcomes = Object.keys(outcomeColors);

function designsTable(C) {
  return htmlTable(['design', 'study', 'scene', "its study's model", 'run here in', "on its own study's trials", 'file'],
    C.designs.map((d) => [d.label, d.study, d.scene, d.own_model, d.model,
      d.own_study ? 'yes (the numbers design.json records)' : 'no', d.file]));
}

/// The set's rows of compare.csv: metric, then one value per design.
function metricsTable(M, labels, set) {
  const rows = [];
  for (let i = 0; i < M.length; i++) {
    if (M.set[i] === set) rows.push([M.metric[i], ...labels.map((l) => M[l][i])]);
  }
  return htmlTable(['metric', ...labels], rows);
}

/// Every trial of the set: one row, each design's outcome coloured (trials.csv).
function trialsTable(T, labels, set) {
  const counts = labels.map(() => Object.fromEntries(outcomes.map((o) => [o, 0])));
  const body = [];
  for (let i = 0; i < T.length; i++) {
    if (T.set[i] !== set) continue;
    const cells = labels.map((l, k) => {
      const o = T[`${l}.outcome`][i];
      counts[k][o] = (counts[k][o] ?? 0) + 1;
      const err = T[`${l}.hop_height_error`]?.[i];
      return el('td', { style: `background:${outcomeColors[o] ?? '#fff'}`, title: `hop height error ${fmt(err)} m`, text: o });
    });
    body.push(el('tr', {}, el('td', { text: `${T.index[i]} ${T.name[i]}` }), ...cells));
  }
  const summary = outcomes.filter((o) => counts.some((c) => c[o] > 0)).map((o) =>
    el('tr', {}, el('td', { text: `${o} (trials)` }), ...counts.map((c) => el('td', { text: String(c[o]) }))));
  const table = el('table', { class: 'tbl' },
    el('thead', {}, el('tr', {}, ...['trial', ...labels].map((h) => el('th', { text: h })))),
    el('tbody', {}, ...summary, ...body));
  return { table, rows: body.length };
}

/// Each design's playback run on one time line: a 3-D view per design, one player.
function playbacks(box, D, labels) {
  const n = labels.length;
  const grid = el('div', { class: n === 2 ? 'grid2' : 'grid3' });
  box.append(grid);
  const scenes = [];
  D.runs.forEach((run, k) => {
    const d = D.comparison.designs[k];
    const caption = el('div', { class: 'caption', style: `color:${palette[k % palette.length]}`,
      text: `■ ${d.label} (${d.model} model)${run ? ` · ${run.summary?.status ?? ''}` : ': no playback (see summary.md)'}` });
    const stage = el('div', { class: n > 2 ? 'stage short' : 'stage' });
    grid.append(el('div', {}, caption, stage));
    if (run) scenes.push({ k, scene: runScene(stage, run, parseInt(palette[k % palette.length].slice(1), 16)), run });
  });
  if (!scenes.length) return null;
  let plots = [];
  const player = new Player(box, {
    t0: Math.min(...scenes.map((s) => s.scene.t0)), t1: Math.max(...scenes.map((s) => s.scene.t1)),
    strideTimes: scenes[0].scene.strideTimes,
    onTime: (t) => { for (const s of scenes) s.scene.update(t); for (const u of plots) setCursorX(u, t); },
    onFollow: (on) => { for (const s of scenes) { s.scene.viewer.follow = on; s.scene.viewer.lastFollow = null; } },
    follow: scenes[0].scene.viewer.follow,
  });
  plots = runPlots(box, scenes, labels, (t) => player.seek(t));
  return { scene: scenes[0].scene, player };
}

/// Height, position errors and attitude of every design's run, on the first run's times, in
/// the colours of the captions; a click seeks the playback.
function runPlots(box, scenes, labels, onSeek) {
  const grid = el('div', { class: 'grid3' });
  box.append(grid);
  const tables = scenes.map((s) => columns(s.run.trajectory));
  const T = tables[0].t;
  const quantities = [
    ['height z', 'z [m]', (c) => c.z], ['x − x_d', 'error [m]', (c) => c.x.map((v, i) => v - c.x_d[i])],
    ['y − y_d', 'error [m]', (c) => c.y.map((v, i) => v - c.y_d[i])],
    ['roll', 'roll [deg]', (c) => c.roll_deg], ['pitch', 'pitch [deg]', (c) => c.pitch_deg]];
  return quantities.map(([title, ylabel, f]) => {
    const cell = el('div');
    grid.append(cell);
    const series = scenes.map((s, j) => {
      const c = tables[j], v = f(c), end = c.t[c.t.length - 1];
      return { label: labels[s.k], color: palette[s.k % palette.length], values: T.map((t) => (t <= end ? interp(c.t, v, t) : null)) };
    });
    return linePlot(cell, T, series, { title, ylabel, height: 160, onSeek, legend: false });
  });
}

export function compareReport(box, D) {
  const C = D.comparison;
  const labels = C.designs.map((d) => d.label);
  const M = columns(D.metrics), T = columns(D.trials);
  box.append(el('p', { class: 'sub', text: `Every design ran the trials of ${C.reference.file} (study ${C.reference.study}), `
    + `judged by that study's objective; each with its own scene and parameters, ${C.model ? `all in the ${C.model} model` : "each in its own study's model"}.` }));
  box.append(el('h3', { text: 'designs' }), designsTable(C));
  for (const note of C.notes ?? []) box.append(el('p', { class: 'note', text: note }));
  let trialRows = 0;
  for (const s of [...C.sets].reverse()) {
    box.append(el('h2', { text: `${s.name}: ${s.description}` }));
    const grid = el('div', { class: 'grid2' });
    const left = el('div'), right = el('div');
    grid.append(left, right);
    box.append(grid);
    left.append(el('h3', { text: 'metrics (mean over the trials, and the objective\'s aggregates)' }), metricsTable(M, labels, s.name));
    const t = trialsTable(T, labels, s.name);
    trialRows += t.rows;
    right.append(el('h3', { text: 'every trial\'s outcome' }), t.table);
  }
  box.append(el('h2', { text: `playback: ${C.playback.description}` }));
  const played = playbacks(box, D, labels);
  return { played, extra: { designs: () => labels.length, trialRows: () => trialRows } };
}
