// report.html of a multi-objective study: the front (a 2-D scatter, or a scatter matrix for
// three or more objectives) over every evaluated design, the knee marked; a click on a point
// selects that design: its parameters, objectives, constraints, validation outcome and
// playback; and the hypervolume over the generations (how the front converged).
import { el, fmt, htmlTable, countText } from './data.js';
import { linePlot } from './plots.js';
import { runScene } from './runscene.js';
import { Player } from './player.js';

const grey = '#b0b7bf', blue = '#1f77b4', red = '#d62728', green = '#2ca02c';

/// Points sorted by objective a: {x, all, front, knee, chosen, ids} as uPlot series (one x array).
function scatterData(P, a, b, chosen) {
  const n = P.evaluations.objectives[a].length;
  const order = [...Array(n).keys()].filter((i) => Number.isFinite(P.evaluations.objectives[a][i])
    && Number.isFinite(P.evaluations.objectives[b][i]))
    .sort((i, j) => P.evaluations.objectives[a][i] - P.evaluations.objectives[a][j]);
  const frontOf = new Map(P.front.map((f, k) => [f.evaluation, k]));
  const x = order.map((i) => P.evaluations.objectives[a][i]);
  const y = order.map((i) => P.evaluations.objectives[b][i]);
  const pick = (test) => order.map((i, r) => (test(i) ? y[r] : null));
  return {
    x, y, order, frontOf,
    all: pick((i) => !frontOf.has(i)),
    front: pick((i) => frontOf.has(i)),
    knee: pick((i) => frontOf.get(i) === P.knee),
    chosen: pick((i) => frontOf.get(i) === chosen),
  };
}

/// One scatter of objective b over objective a; a click picks the nearest front design
/// (in screen distance) and calls onPick(front index).
/// The axis range that shows the front and the reference point (evaluations far beyond it,
/// such as falls with their penalties, would squeeze the front into a corner).
function frontRange(P, k) {
  const v = P.front.map((f) => f.objectives[k]);
  if (Number.isFinite(P.reference?.[k])) v.push(P.reference[k]);
  let lo = Math.min(...v), hi = Math.max(...v);
  const pad = 0.08 * (hi - lo || Math.abs(hi) || 1);
  return [lo - pad, hi + pad];
}

function scatter(cell, P, a, b, chosen, onPick, small) {
  const s = scatterData(P, a, b, chosen);
  const name = (k) => P.objectives[k].name;
  const xr = frontRange(P, a), yr = frontRange(P, b);
  const outside = s.x.filter((x, r) => x < xr[0] || x > xr[1] || s.y[r] < yr[0] || s.y[r] > yr[1]).length;
  const u = linePlot(cell, s.x, [
    { label: 'evaluated', values: s.all, points: true, size: 4, color: grey },
    { label: 'non-dominated', values: s.front, points: true, size: 7, color: blue },
    { label: 'knee', values: s.knee, points: true, size: 12, color: green },
    { label: 'selected', values: s.chosen, points: true, size: 13, color: red }],
  { title: (small ? `${name(b)} over ${name(a)}` : `the front: ${name(b)} over ${name(a)} (evaluated designs; click a point)`)
      + (outside ? ` · ${outside} beyond the reference point not shown` : ''),
    xlabel: name(a), ylabel: name(b), height: small ? 200 : 320, legend: !small, xrange: xr, yrange: yr });
  u.over.addEventListener('click', () => {
    const cx = u.cursor.left, cy = u.cursor.top;
    if (!(cx >= 0 && cy >= 0)) return;
    let best = -1, dist = Infinity;
    s.order.forEach((i, r) => {
      if (!s.frontOf.has(i)) return;
      const dx = u.valToPos(s.x[r], 'x') - cx, dy = u.valToPos(s.y[r], 'y') - cy;
      if (dx * dx + dy * dy < dist) { dist = dx * dx + dy * dy; best = s.frontOf.get(i); }
    });
    if (best >= 0) onPick(best);
  });
  return u;
}

function hypervolumePlot(box, P) {
  const h = P.hypervolume;
  if (!h?.length) return;
  linePlot(box, h.map((g) => g.generation), [{ label: 'hypervolume', values: h.map((g) => g.value), points: true, size: 5 }],
    { title: `hypervolume of the non-dominated designs so far, per generation (reference point ${P.reference.map((v) => fmt(v)).join(', ')})`,
      xlabel: 'generation', ylabel: 'hypervolume', height: 200, legend: false });
}

function frontTable(P) {
  const names = P.objectives.map((o) => o.name);
  const vnames = P.validation_metrics ?? [];
  return htmlTable(['#', 'evaluation', ...names, ...vnames.map((v) => `validation ${v}`)],
    P.front.map((f, k) => [k === P.knee ? `${k} (knee)` : String(k), f.evaluation, ...f.objectives,
      ...vnames.map((v) => f.validation?.[v])]));
}

/// The selected design: its numbers and its playback (a new 3-D view per selection).
function designPanel(panel, P, D, k) {
  panel.replaceChildren();
  const f = P.front[k];
  panel.append(el('h3', { text: `design ${k} of the front${k === P.knee ? ' (the knee)' : ''}: evaluation ${f.evaluation}` }));
  const grid = el('div', { class: 'grid3' });
  panel.append(grid);
  grid.append(el('div', {}, el('h3', { text: 'parameters' }),
    htmlTable(['parameter', 'value'], Object.entries(f.parameters))));
  grid.append(el('div', {}, el('h3', { text: 'objectives and constraints' }),
    htmlTable(['quantity', 'value'], [...P.objectives.map((o, j) => [o.name, f.objectives[j]]),
      ...Object.entries(f.constraints ?? {}), ['feasible', f.feasible ? 'yes' : 'no']])));
  grid.append(el('div', {}, el('h3', { text: f.validation ? `validation (${countText(f.validation.trials ?? 0, 'held-out trial')})` : 'validation' }),
    f.validation ? htmlTable(['metric', 'value'], Object.entries(f.validation).filter(([key]) => key !== 'trials'))
      : el('p', { class: 'note', text: 'the study has no validation set' })));
  const run = D.runs?.[k];
  if (!run) {
    panel.append(el('p', { class: 'note', text: 'no playback recorded for this design' }));
    return null;
  }
  panel.append(el('h3', { text: `playback: ${P.playback ?? 'its first trial'} · ${run.summary?.status ?? ''}` }));
  const stage = el('div', { class: 'stage' });
  panel.append(stage);
  const scene = runScene(stage, run, 0x1f77b4);
  const player = new Player(panel, {
    t0: scene.t0, t1: scene.t1, strideTimes: scene.strideTimes,
    onTime: (t) => scene.update(t),
    onFollow: (on) => { scene.viewer.follow = on; scene.viewer.lastFollow = null; },
    follow: scene.viewer.follow,
  });
  return { scene, player };
}

export function paretoReport(box, D) {
  const P = D.pareto;
  const m = P.objectives.length;
  box.append(el('p', { class: 'sub', text: `${P.algorithm}: ${countText(P.evaluations.objectives[0].length, 'evaluated design')}, `
    + `${countText(P.front.length, 'non-dominated design')}; every objective is minimized (${P.objectives.map((o) => `${o.name}: ${o.description}`).join('; ')}).` }));
  const plots = el('div');
  const panel = el('div');
  box.append(plots);
  let state = { chosen: P.knee, played: null };
  const test = { frontPoints: P.front.length, chosen: () => state.chosen, pick: null };
  const draw = () => {
    plots.replaceChildren();
    if (m === 2) {
      scatter(plots, P, 0, 1, state.chosen, pick, false);
    } else {
      plots.append(el('h3', { text: 'the front, every pair of objectives (click a point)' }));
      const grid = el('div', { class: 'grid3' });
      plots.append(grid);
      for (let a = 0; a < m; a++) {
        for (let b = a + 1; b < m; b++) {
          const cell = el('div');
          grid.append(cell);
          scatter(cell, P, a, b, state.chosen, pick, true);
        }
      }
    }
  };
  function pick(k) {
    state = { chosen: k, played: designPanel(panel, P, D, k) };
    draw();
  }
  test.pick = pick;
  draw();
  box.append(panel);
  state.played = designPanel(panel, P, D, state.chosen);
  box.append(el('h2', { text: 'convergence' }));
  hypervolumePlot(box, P);
  box.append(el('h2', { text: 'the non-dominated designs' }), frontTable(P));
  return { played: () => state.played, extra: { frontPoints: () => test.frontPoints, chosen: test.chosen, pick: (k) => test.pick(k) } };
}
