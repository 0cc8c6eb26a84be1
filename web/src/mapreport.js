// The map report: the stabilized-fraction heat map (uPlot scales and axes, cells drawn in
// its draw hook) with the bisected boundary, hover details per cell, and a click on a
// cell that plays its stored trial (playback.json: trial 0 of the primary model).
import uPlot from 'uplot';
import { el, fmt, columns, ramp, htmlTable, countText } from './data.js';
import { runScene, installTestHook } from './runscene.js';
import { widthOf } from './plots.js';
import { Player } from './player.js';

// Fractional index of value v among sorted axis values (for the boundary line).
function indexOf(values, v) {
  if (values.length < 2) return 0;
  for (let i = 0; i + 1 < values.length; i++) {
    if (v <= values[i + 1]) return i + (v - values[i]) / (values[i + 1] - values[i]);
  }
  return values.length - 1 + (v - values[values.length - 1]) / (values[values.length - 1] - values[values.length - 2]);
}

function cellDetails(c, i, models, a0, a1) {
  const lines = [`cell ${c.cell[i]}: ${a0.name} = ${fmt(c[a0.name][i])}` + (a1 ? `, ${a1.name} = ${fmt(c[a1.name][i])}` : ''),
    `trials ${c.trials[i]}`];
  for (const m of models) lines.push(`stabilized (${m}) ${fmt(c['stabilized_' + m][i] * c.trials[i], 3)} of ${c.trials[i]}`);
  const add = (k, label) => { if (c[k]) lines.push(`${label} ${fmt(c[k][i])}`); };
  add('mean_settle_strides', 'mean settle strides');
  add('mean_duty', 'mean duty');
  add('disagreements', 'disagreements');
  add('fell_fraction', 'fell fraction');
  add('spectral_radius', 'spectral radius');
  add('peak_force_N', 'peak force [N]');
  return lines.join('\n');
}

/// The rows the boundary line was last drawn through (the browser test).
const drawnRows = [];

export function mapReport(box, D) {
  const s = D.summary;
  const c = columns(D.cells);
  const models = s.models ?? [s.primary_model];
  const primary = s.primary_model ?? models[models.length - 1];
  const a0 = s.axes[0], a1 = s.axes[1];
  const ncol = a0.values.length, nrow = a1 ? a1.values.length : 1;
  // cells.csv: stabilized_<model> is the fraction of the cell's trials that stabilized.
  const frac = c['stabilized_' + primary];
  box.append(el('p', { class: 'sub', text: `${countText(ncol * nrow, 'cell')} × ${countText(s.trials_per_cell, 'trial')}, models ${models.join(', ')} (primary ${primary}); colour: fraction of trials stabilized in the primary model; black line: the bisected boundary; hover a cell for details, click it to play its trial 0.` }));
  const bnd = columns(D.boundary);
  const plotBox = el('div', { class: 'plot' });
  const tip = el('div', { class: 'tip' });
  tip.style.display = 'none';
  document.body.append(tip);
  box.append(plotBox);
  const cellAt = (col, row) => c.cell.findIndex((_, i) => c.column[i] === col && c.row[i] === row);
  const draw = (u) => {
    const ctx = u.ctx;
    ctx.save();
    for (let i = 0; i < c.cell.length; i++) {
      const x0 = u.valToPos(c.column[i] - 0.5, 'x', true), x1 = u.valToPos(c.column[i] + 0.5, 'x', true);
      const y0 = u.valToPos(c.row[i] - 0.5, 'y', true), y1 = u.valToPos(c.row[i] + 0.5, 'y', true);
      ctx.fillStyle = ramp(frac[i]);
      ctx.fillRect(Math.min(x0, x1), Math.min(y0, y1), Math.abs(x1 - x0) + 0.5, Math.abs(y1 - y0) + 0.5);
      if (c.disagreements && c.disagreements[i] > 0) {
        ctx.strokeStyle = '#ff4d4d';
        ctx.lineWidth = 2;
        ctx.strokeRect(Math.min(x0, x1) + 2, Math.min(y0, y1) + 2, Math.abs(x1 - x0) - 4, Math.abs(y1 - y0) - 4);
      }
    }
    if (bnd && bnd.boundary) {
      // Only rows with a boundary: a row where no value was good has none, and the line
      // breaks there instead of running through it.
      ctx.strokeStyle = '#000';
      ctx.lineWidth = 3;
      ctx.beginPath();
      drawnRows.length = 0;
      let open = false;
      for (let r = 0; r < bnd.row.length; r++) {
        const b = bnd.boundary[r];
        if (bnd.status[r] === 'none_good' || b === null || !Number.isFinite(Number(b))) { open = false; continue; }
        drawnRows.push(bnd.row[r]);
        const xi = indexOf(a0.values, Number(b));
        const px = u.valToPos(Math.min(ncol - 0.5, Math.max(-0.5, xi)), 'x', true);
        for (const dy of [-0.5, 0.5]) {
          const py = u.valToPos(bnd.row[r] + dy, 'y', true);
          if (!open) ctx.moveTo(px, py); else ctx.lineTo(px, py);
          open = true;
        }
      }
      ctx.stroke();
    }
    ctx.restore();
  };
  const tickVals = (values) => (u, splits) => splits.map((i) => (values[Math.round(i)] !== undefined ? fmt(values[Math.round(i)], 3) : ''));
  const step = (n) => Math.max(1, Math.ceil(n / 12));
  const u = new uPlot({
    title: `stabilized fraction (${primary})`, width: Math.max(320, widthOf(box)), height: Math.max(220, 60 * nrow + 80),
    scales: { x: { time: false, range: [-0.5, ncol - 0.5] }, y: { range: [-0.5, nrow - 0.5] } },
    axes: [{ label: `${a0.name} [${a0.unit}]`, splits: () => a0.values.map((_, i) => i).filter((i) => i % step(ncol) === 0), values: tickVals(a0.values) },
      { label: a1 ? `${a1.name} [${a1.unit}]` : '', splits: () => (a1 ? a1.values.map((_, i) => i).filter((i) => i % step(nrow) === 0) : [0]), values: a1 ? tickVals(a1.values) : () => [''], size: 60 }],
    legend: { show: false }, cursor: { drag: { x: false, y: false }, points: { show: false } },
    series: [{}, { stroke: 'transparent', points: { show: false } }],
    hooks: { draw: [draw] },
  }, [[-0.5, ncol - 0.5], [null, null]], plotBox);
  const hovered = () => {
    if (u.cursor.left < 0) return -1;
    return cellAt(Math.round(u.posToVal(u.cursor.left, 'x')), Math.round(u.posToVal(u.cursor.top, 'y')));
  };
  u.over.addEventListener('mousemove', (e) => {
    const i = hovered();
    if (i < 0) { tip.style.display = 'none'; return; }
    tip.textContent = cellDetails(c, i, models, a0, a1);
    tip.style.display = 'block';
    tip.style.left = `${e.clientX + 14}px`;
    tip.style.top = `${e.clientY + 14}px`;
  });
  u.over.addEventListener('mouseleave', () => { tip.style.display = 'none'; });
  // Key: the colour ramp in readable swatches, the boundary line and the disagreement frame.
  const swatch = (text, style) => {
    const sw = el('span', { text });
    Object.assign(sw.style, { display: 'inline-block', minWidth: '3.2em', padding: '4px 8px', margin: '0 2px',
      textAlign: 'center', fontSize: '14px', ...style });
    return sw;
  };
  box.append(el('div', { class: 'key' }, el('strong', { text: 'key: ' }), 'fraction of trials stabilized ',
    ...[0, 0.25, 0.5, 0.75, 1].map((f) => swatch(String(f), { background: ramp(f), color: f > 0.6 ? '#000' : '#fff' })),
    ' ', swatch('boundary', { borderBottom: '3px solid #000' }),
    ' ', swatch('models disagree', { outline: '2px solid #ff4d4d', outlineOffset: '-2px' })));
  const played = playbackArea(box, D, c, u, hovered);
  if (bnd) {
    box.append(el('h3', { text: 'boundary per row' }),
      htmlTable(D.boundary.columns, bnd.row.map((_, r) => D.boundary.columns.map((k) => bnd[k][r]))));
  }
  return played;
}

function playbackArea(box, D, c, u, hovered) {
  const pb = D.playback;
  box.append(el('h3', { text: 'trial playback' }));
  if (!pb || !pb.cells) {
    box.append(el('p', { class: 'note', text: pb?.skipped ?? 'no playback.json: this map was written before pronk stored one trial per cell.' }));
    window.pronkTest = { mapCells: () => c.cell.length, boundaryRows: () => drawnRows.slice() };
    return null;
  }
  const caption = el('div', { class: 'caption' });
  const area = el('div');
  box.append(caption, area);
  const current = { scene: null, player: null };
  const play = (i) => {
    const cell = pb.cells.find((k) => k.cell === c.cell[i]);
    if (!cell) return;
    if (current.scene) current.scene.viewer.dispose();
    area.replaceChildren();
    const stage = el('div', { class: 'stage short' });
    area.append(stage);
    const run = { kind: 'robot', scene: cell.scene, trajectory: { columns: pb.columns, data: cell.data },
      strides: { columns: ['t_touchdown'], data: [cell.touchdowns] } };
    const scene = runScene(stage, run);
    caption.textContent = `cell ${cell.cell} (trial ${pb.trial}, ${pb.model} model): ${cell.status}`;
    const player = new Player(area, {
      t0: scene.t0, t1: scene.t1, strideTimes: scene.strideTimes, onTime: (t) => scene.update(t),
      onFollow: (on) => { scene.viewer.follow = on; scene.viewer.lastFollow = null; },
      follow: scene.viewer.follow,
    });
    current.scene = scene;
    current.player = player;
    // The test hook follows the trial on show.
    installTestHook(scene, player, { mapCells: () => c.cell.length, playedCell: () => cell.cell, boundaryRows: () => drawnRows.slice() });
  };
  u.over.addEventListener('click', () => { const i = hovered(); if (i >= 0) play(i); });
  play(0);
  return {
    get scene() { return current.scene; },
    get player() { return current.player; },
  };
}
