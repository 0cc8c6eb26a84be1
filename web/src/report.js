// report.html: a study (history, parameters, parallel coordinates, constraints, tables,
// validation, initial vs tuned playback), a staged study (stages and the fidelity gap), a
// map (stabilized-fraction heat map with the boundary, hover details, click to play), or a
// comparison of designs (metrics and trials side by side, every design's playback).
import { pageData, el, fmt, htmlTable, columns, ramp } from './data.js';
import { linePlot, fewestAxisTicks } from './plots.js';
import { runScene, installTestHook } from './runscene.js';
import { Player } from './player.js';
import { mapReport } from './mapreport.js';
import { compareReport } from './comparereport.js';
import { paretoReport } from './paretoreport.js';

const test = { historyPoints: 0 };

/// The rows worth reading: an objective term "mean(m)" that repeats the row m is left out,
/// and so is the spectral radius when the study did not compute it (it reads 0, which would
/// look perfect).
function metricRows(a, b, stability = true) {
  const keys = [...new Set([...Object.keys(a ?? {}), ...Object.keys(b ?? {})])].sort();
  return keys.filter((k) => {
    if (k === 'spectral_radius' && !stability) return false;
    const m = /^mean\((.*)\)$/.exec(k);
    return !(m && a?.[m[1]] === a?.[k] && b?.[m[1]] === b?.[k]);
  }).map((k) => [k, a?.[k], b?.[k]]);
}

/// Whether a design's study computed the stride map's spectral radius.
const computedStability = (d) => Boolean(d.stability?.method);

/// Cost of every evaluation (feasible and infeasible apart) and the best feasible so far.
function historyPlot(box, h) {
  const n = h.length;
  const feas = h.feasible ?? h.cost.map(() => 1);
  const good = h.cost.map((c, i) => (feas[i] ? c : null));
  const bad = h.cost.map((c, i) => (feas[i] ? null : c));
  let best = null;
  const bestSoFar = h.cost.map((c, i) => { if (feas[i] && (best === null || c < best)) best = c; return best; });
  test.historyPoints += good.filter((v) => v !== null).length + bad.filter((v) => v !== null).length;
  linePlot(box, h.index, [
    { label: 'feasible evaluation', values: good, points: true, size: 4, color: '#1f77b4' },
    { label: 'infeasible evaluation', values: bad, points: true, size: 4, color: '#d62728' },
    { label: 'best feasible so far', values: bestSoFar, color: '#2ca02c', width: 2 }],
  { title: `optimization history (${n} evaluations; cost axis asinh: linear near 0, logarithmic beyond)`,
    xlabel: 'evaluation', ylabel: 'cost', height: 230, yscale: 'asinh', asinh: asinhScale(h.cost) });
}

// The linear range of an asinh axis: the median cost magnitude.
function asinhScale(costs) {
  const a = costs.map(Math.abs).filter((v) => v > 0).sort((x, y) => x - y);
  return a.length ? Math.max(1e-6, a[a.length >> 1]) : 1;
}

function paramNames(stage) {
  return Object.keys(stage.design.parameters ?? {}).filter((p) => stage.history.columns.includes(p));
}

function parameterTraces(box, h, names, stage) {
  const specs = Object.fromEntries((stage.design.study_document?.parameters ?? []).map((p) => [p.name, p]));
  const grid = el('div', { class: 'grid3' });
  box.append(grid);
  for (const p of names) {
    const cell = el('div');
    grid.append(cell);
    linePlot(cell, h.index, [{ label: p, values: h[p], points: true, size: 3 }],
      { title: p + (specs[p]?.log ? ' (log)' : ''), xlabel: 'evaluation', height: 140, legend: false,
        yscale: specs[p]?.log ? 'log' : undefined });
  }
}

/// Parallel coordinates: one line per evaluation over the parameters (normalized to
/// the range seen, log where the parameter is log-scaled) and the cost, coloured by cost.
function parallelCoordinates(box, stage, h, names) {
  const specs = Object.fromEntries((stage.design.study_document?.parameters ?? []).map((p) => [p.name, p]));
  const axes = [...names, 'cost'];
  const costs = [...h.cost].sort((a, b) => a - b);
  const rank = (c) => costs.indexOf(c) / Math.max(1, costs.length - 1);
  const norm = axes.map((a) => {
    if (a === 'cost') return rank;
    const log = specs[a]?.log === true;
    const f = (v) => (log ? Math.log(v) : v);
    const lo = specs[a]?.lower !== undefined ? f(specs[a].lower) : Math.min(...h[a].map(f));
    const hi = specs[a]?.upper !== undefined ? f(specs[a].upper) : Math.max(...h[a].map(f));
    return (v) => (hi > lo ? (f(v) - lo) / (hi - lo) : 0.5);
  });
  const x = axes.map((_, i) => i);
  const series = [];
  const order = h.index.map((_, i) => i).sort((a, b) => h.cost[b] - h.cost[a]);  // best drawn last
  for (const i of order) {
    series.push({ label: `#${h.index[i]}`, values: axes.map((a, k) => norm[k](k < names.length ? h[a][i] : h.cost[i])),
      color: ramp(1 - rank(h.cost[i])), width: 1 });
  }
  const u = linePlot(box, x, series, {
    title: 'parallel coordinates (every evaluation; yellow = lowest cost; parameters between their bounds, log where the parameter is; cost by rank)',
    xlabel: '', ylabel: 'normalized', height: 320, legend: false, manySeries: true, xticks: axes, yrange: [0, 1],
  });
  test.parallelLines = u.series.length - 1;
}

function constraintPlot(box, h) {
  const gs = Object.keys(h).filter((c) => /^g\d+$/.test(c));
  if (!gs.length) return;
  linePlot(box, h.index, [...gs.map((g) => ({ label: g, values: h[g], points: true, size: 3 })),
    { label: 'g = 0', values: h.index.map(() => 0), color: '#333', dash: [4, 4] }],
  { title: 'constraint values (g ≤ 0 is feasible)', xlabel: 'evaluation', ylabel: 'g', height: 200 });
}

function playback(box, initial, tuned) {
  const grid = el('div', { class: 'grid2' });
  const a = el('div', { class: 'stage' }), b = el('div', { class: 'stage' });
  grid.append(el('div', {}, el('div', { class: 'caption', text: 'initial design' }), a),
    el('div', {}, el('div', { class: 'caption', text: 'tuned design' }), b));
  box.append(grid);
  const sa = runScene(a, initial, 0x8c8c8c), sb = runScene(b, tuned, 0x3b6ea8);
  const player = new Player(box, {
    t0: Math.min(sa.t0, sb.t0), t1: Math.max(sa.t1, sb.t1), strideTimes: sb.strideTimes,
    onTime: (t) => { sa.update(t); sb.update(t); },
    onFollow: (on) => { for (const s of [sa, sb]) { s.viewer.follow = on; s.viewer.lastFollow = null; } },
    follow: sb.viewer.follow,
  });
  return { scene: sb, player };
}

function studySection(box, stage, title, withPlayback = true) {
  const d = stage.design;
  const h = columns(stage.history);
  const opt = d.optimizer ?? {};
  box.append(el('h2', { text: title }),
    el('p', { class: 'sub', text: `${opt.library ?? ''} ${opt.algorithm ?? ''}: ${opt.status ?? ''} (${opt.message ?? ''}), `
      + `${opt.evaluations ?? h.length} evaluations, cost ${fmt(d.initial_cost)} → ${fmt(d.cost)}`
      + `${d.feasible === false ? ' (INFEASIBLE)' : ''}, ${fmt(d.wall_time_s)} s` }));
  historyPlot(box, h);
  const names = paramNames(stage);
  box.append(el('h3', { text: 'parameter traces' }));
  parameterTraces(box, h, names, stage);
  parallelCoordinates(box, stage, h, names);
  constraintPlot(box, h);
  const grid = el('div', { class: 'grid2' });
  const left = el('div'), right = el('div');
  grid.append(left, right);
  box.append(grid);
  const init = Object.fromEntries(names.map((p) => [p, h[p][0]]));
  left.append(el('h3', { text: 'parameters (initial = evaluation 0)' }),
    htmlTable(['parameter', 'initial', 'tuned'], names.map((p) => [p, init[p], d.parameters[p]])));
  const gs = Object.keys(h).filter((c) => /^g\d+$/.test(c));
  if (gs.length) {
    const labels = (d.study_document?.constraints ?? []).map((c) =>
      `${c.aggregate}(${c.metric}) ${c.max !== undefined ? '≤ ' + c.max : '≥ ' + c.min}`);
    left.append(el('h3', { text: 'constraints (g ≤ 0 is feasible)' }),
      htmlTable(['constraint', 'initial g', 'tuned g'], gs.map((g, i) => [labels[i] ?? g, h[g][0], d.constraints?.[i]])));
  }
  right.append(el('h3', { text: 'metrics over the scenarios' }),
    htmlTable(['metric', 'initial', 'tuned'], [['cost', d.initial_cost, d.cost], ...metricRows(d.initial_metrics, d.metrics, computedStability(d))]));
  if (d.validation) {
    const v = d.validation;
    right.append(el('h3', { text: `validation on ${Array.isArray(v.scenarios) ? v.scenarios.length : v.scenarios ?? 'held-out'} held-out scenarios` }),
      htmlTable(['metric', 'initial', 'tuned'], [['cost', v.initial_cost, v.cost], ...metricRows(v.initial_metrics, v.metrics, computedStability(d))]));
  }
  if (withPlayback && stage.initial && stage.tuned) {
    box.append(el('h3', { text: 'first scenario: initial vs tuned' }));
    return playback(box, stage.initial, stage.tuned);
  }
  return null;
}

function stagedReport(box, D) {
  const d = D.design;
  box.append(el('h3', { text: 'stages' }),
    htmlTable(['stage', 'model', 'evaluations', 'initial cost', 'tuned cost'], (d.stages ?? []).map((s) =>
      [s.name, s.model, s.optimizer?.evaluations, s.initial_cost, s.cost])));
  const gap = d.fidelity_gap;
  if (gap && gap.first_stage_design) {
    box.append(el('h3', { text: `fidelity gap: the first stage's design (${gap.first_stage}) and the final design, both in the last stage's model` }),
      htmlTable(['metric', 'first stage\'s design', 'final design'],
        [['cost', gap.first_stage_design.cost, gap.final_design?.cost],
          ...metricRows(gap.first_stage_design.metrics, gap.final_design?.metrics, computedStability(d))]));
  }
  // Every stage's evaluations on one axis (each stage in its own model: costs differ by model).
  const xs = [], series = D.stages.map((st) => ({ label: `${st.name} cost`, values: [], points: true, size: 4 }));
  D.stages.forEach((st, k) => {
    const h = columns(st.history);
    for (let i = 0; i < h.length; i++) {
      xs.push(xs.length);
      series.forEach((se, j) => se.values.push(j === k ? h.cost[i] : null));
    }
  });
  linePlot(box, xs, series, { title: 'stages: every evaluation, stage after stage (each in its own model)',
    xlabel: 'evaluation (all stages)', ylabel: 'cost', height: 220, yscale: 'asinh', asinh: asinhScale(series.flatMap((se) => se.values.filter((v) => v !== null))) });
  let last = null;
  D.stages.forEach((s, i) => {
    const r = studySection(box, s, `stage ${s.name}`, i === D.stages.length - 1);
    if (r) last = r;
  });
  return last;
}

function main() {
  const D = pageData();
  const kinds = { map: 'robustness map', staged: 'staged study', compare: 'comparison of designs',
    pareto: 'multi-objective study: the Pareto front' };
  const name = D.kind === 'map' ? D.summary.name
    : D.kind === 'pareto' ? D.pareto.name
    : D.kind === 'compare' ? D.comparison.designs.map((d) => d.label).join(' · ')
      : D.design.staged_study ?? D.design.study;
  document.title = `${name} · pronk report`;
  const app = document.getElementById('app');
  app.append(el('header', {}, el('h1', { text: name }),
    el('div', { class: 'sub', text: kinds[D.kind] ?? 'study' })));
  const box = el('div', { class: 'report' });
  app.append(box);
  let played = null;
  let extra = { historyPoints: () => test.historyPoints };
  if (D.kind === 'pareto') {
    const r = paretoReport(box, D);
    played = r.played();
    extra = { ...extra, ...r.extra };
  } else if (D.kind === 'compare') {
    const r = compareReport(box, D);
    played = r.played;
    extra = { ...extra, ...r.extra };
  } else if (D.kind === 'map') played = mapReport(box, D);
  else if (D.kind === 'staged') played = stagedReport(box, D);
  else played = studySection(box, D, 'optimization');
  if (D.kind === 'map') return;  // the map's playback installs the hook of the trial on show
  if (played) installTestHook(played.scene, played.player, extra);
  else window.pronkTest = { ...extra, fewestAxisTicks };
}

main();
