// uPlot charts: time plots whose cursor follows the playback time (a click seeks),
// and scatter/line charts for the reports.
import uPlot from 'uplot';
import { el } from './data.js';

const palette = ['#1f77b4', '#d62728', '#2ca02c', '#9467bd', '#ff7f0e', '#8c564b', '#e377c2', '#17becf'];
export { palette };

function widthOf(container) { return Math.max(240, container.clientWidth - 8); }

/// A line chart: x values and series [{label, values, color, dash, points, scale}].
/// `opts`: {title, xlabel, ylabel, height, onSeek(x), points: true for markers only}.
export function linePlot(container, x, series, opts = {}) {
  const box = el('div', { class: 'plot' });
  container.append(box);
  const scales = { x: { time: false } };
  // y: 'asinh' (symmetric log: spans signs and decades) or 'log'.
  if (opts.yscale === 'asinh') scales.y = { distr: 4, asinh: opts.asinh ?? 1 };
  if (opts.yscale === 'log') scales.y = { distr: 3 };
  const axes = [{ label: opts.xlabel ?? 't [s]', size: 36 }, { label: opts.ylabel ?? '', size: 56 }];
  if (opts.xticks) {  // category axis: labels at 0, 1, 2, ...
    axes[0].splits = () => opts.xticks.map((_, i) => i);
    axes[0].values = () => opts.xticks;
    axes[0].rotate = -30;
    axes[0].size = 70;
  }
  const padding = opts.xticks ? [12, 60, 0, 0] : undefined;
  if (opts.yrange) scales.y = { range: opts.yrange };
  if (series.some((s) => s.scale === 'y2')) {
    scales.y2 = {};
    axes.push({ scale: 'y2', side: 1, label: opts.y2label ?? '', grid: { show: false }, size: 56 });
  }
  const u = new uPlot({
    title: opts.title, width: widthOf(container), height: opts.height ?? 170, padding,
    scales, axes,
    legend: { show: opts.legend !== false, live: true },
    cursor: { y: false, drag: { x: false, y: false }, points: { show: !opts.manySeries } },
    series: [{ label: opts.xlabel ?? 't' }, ...series.map((s, i) => ({
      label: s.label, stroke: s.color ?? palette[i % palette.length], width: s.width ?? 1.5,
      dash: s.dash, scale: s.scale ?? 'y', spanGaps: false,
      ...(s.points ? { paths: () => null, points: { show: true, size: s.size ?? 5, fill: s.color ?? palette[i % palette.length] } }
        : { points: { show: false } }),
    }))],
    hooks: opts.hooks ?? {},
  }, [x, ...series.map((s) => s.values)], box);
  if (opts.onSeek) {
    u.over.addEventListener('click', () => {
      if (u.cursor.left >= 0) opts.onSeek(u.posToVal(u.cursor.left, 'x'));
    });
  }
  new ResizeObserver(() => u.setSize({ width: widthOf(container), height: opts.height ?? 170 })).observe(container);
  return u;
}

/// Moves a plot's cursor to x (the playback time or stride).
export function setCursorX(u, x) {
  const left = u.valToPos(x, 'x');
  if (!Number.isFinite(left)) return;
  u.setCursor({ left, top: u.over.clientHeight / 2 }, false);
}
