// uPlot charts: time plots whose cursor follows the playback time (a click seeks),
// and scatter/line charts for the reports.
import uPlot from 'uplot';
import { el } from './data.js';

const palette = ['#1f77b4', '#d62728', '#2ca02c', '#9467bd', '#ff7f0e', '#8c564b', '#e377c2', '#17becf'];
export { palette };

/// The plot width that fits the container's content box (clientWidth includes its padding).
export function widthOf(container) {
  const cs = getComputedStyle(container);
  const content = container.clientWidth - parseFloat(cs.paddingLeft || 0) - parseFloat(cs.paddingRight || 0);
  return Math.max(240, content - 8);
}

/// The fewest labelled ticks any plot axis of the page has had (the browser test).
let fewestTicks = Infinity;
export function fewestAxisTicks() { return fewestTicks; }

/// Ticks of a linear axis: uPlot's multiples of its increment, the increment halved until at
/// least two fall in the range (a short plot of a wide range would otherwise show one, "0").
/// Each tick is its integer multiple i x step, not a running sum: summed steps miss zero by the
/// rounding of the sum (a tick labelled -5.55112e-17 on [-1.2, 0]).
function atLeastTwoTicks(u, axisIdx, min, max, incr) {
  let step = incr;
  let ticks = [];
  for (let k = 0; k < 12 && ticks.length < 2 && step > 0; k++, step /= 2) {
    ticks = [];
    for (let i = Math.ceil(min / step); i * step <= max + 1e-9 * step; i++) {
      ticks.push(Number((i * step).toPrecision(12)));
    }
  }
  if (ticks.length < 2) ticks = [min, max];
  fewestTicks = Math.min(fewestTicks, ticks.length);
  return ticks;
}

/// Ticks of a log axis (or of an asinh axis: then also 0 and the negatives): the powers of ten
/// in the range, else its 1-2-5 multiples, else every digit's, else the range's ends, so that
/// at least two fall in the range (uPlot's own may leave one, e.g. "1" on [1, 3]); at most 8.
function logTicks(u, axisIdx, min, max) {
  const sc = u.scales[u.axes[axisIdx].scale];
  const signed = sc.distr === 4;
  const big = Math.max(Math.abs(min), Math.abs(max));
  const small = signed ? Math.min(big, sc.asinh ?? 1) : Math.max(min, Number.MIN_VALUE);
  const inRange = (v) => v >= min - 1e-9 * Math.abs(v) && v <= max + 1e-9 * Math.abs(v);
  let ticks = [];
  for (const mantissas of [[1], [1, 2, 5], [1, 2, 3, 4, 5, 6, 7, 8, 9]]) {
    const set = new Set(signed && inRange(0) ? [0] : []);
    for (let k = Math.floor(Math.log10(small)); k <= Math.ceil(Math.log10(big)); k++) {
      for (const m of mantissas) {
        const v = Number((m * 10 ** k).toPrecision(12));
        for (const s of signed ? [v, -v] : [v]) if (inRange(s)) set.add(s);
      }
    }
    ticks = [...set].sort((a, b) => a - b);
    if (ticks.length >= 2) break;
  }
  if (ticks.length < 2) ticks = [min, max];
  const every = Math.ceil(ticks.length / 8);
  if (every > 1) ticks = ticks.filter((_, i) => i % every === 0);
  fewestTicks = Math.min(fewestTicks, ticks.length);
  return ticks;
}

/// Tick labels with the digits the ticks need, no more.
function tickLabels(u, splits) {
  return splits.map((v) => (v === 0 ? '0' : String(Number(v.toPrecision(6)))));
}

/// A line chart: x values and series [{label, values, color, dash, points, scale}].
/// `opts`: {title, xlabel, ylabel, height, onSeek(x), points: true for markers only}.
export function linePlot(container, x, series, opts = {}) {
  const box = el('div', { class: 'plot' });
  container.append(box);
  const scales = { x: { time: false } };
  // y: 'asinh' (symmetric log: spans signs and decades) or 'log'.
  if (opts.yscale === 'asinh') scales.y = { distr: 4, asinh: opts.asinh ?? 1 };
  if (opts.yscale === 'log') scales.y = { distr: 3 };
  const linear = { splits: atLeastTwoTicks, values: tickLabels };
  const logarithmic = { splits: logTicks, filter: (u, splits) => splits, values: tickLabels };
  const axes = [{ label: opts.xlabel ?? 't [s]', size: 36, ...linear },
    { label: opts.ylabel ?? '', size: 56, ...(opts.yscale ? logarithmic : linear) }];
  if (opts.xticks) {  // category axis: labels at 0, 1, 2, ...
    axes[0].splits = () => opts.xticks.map((_, i) => i);
    axes[0].values = () => opts.xticks;
    axes[0].rotate = -30;
    axes[0].size = 70;
  }
  const padding = opts.xticks ? [12, 60, 0, 0] : undefined;
  if (opts.yrange) scales.y = { range: opts.yrange };
  if (opts.xrange) scales.x = { time: false, range: opts.xrange };
  if (series.some((s) => s.scale === 'y2')) {
    scales.y2 = {};
    axes.push({ scale: 'y2', side: 1, label: opts.y2label ?? '', grid: { show: false }, size: 56, ...linear });
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
