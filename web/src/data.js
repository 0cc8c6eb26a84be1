// The page's data: one JSON document that pronk embeds in the page
// (<script id="pronk-data" type="application/json">), and helpers to read its tables.

export function pageData() {
  return JSON.parse(document.getElementById('pronk-data').textContent);
}

/// A table as pronk writes it ({columns: [...], data: [[column 0], [column 1], ...]})
/// as an object: name -> array of numbers; `undefined` for a missing table.
export function columns(table) {
  if (!table) return undefined;
  const out = {};
  table.columns.forEach((name, i) => { out[name] = table.data[i]; });
  out.length = table.data.length ? table.data[0].length : 0;
  return out;
}

/// Index i with t[i] <= time < t[i + 1] (clamped), by bisection.
export function sampleIndex(t, time) {
  if (time <= t[0]) return 0;
  const n = t.length;
  if (time >= t[n - 1]) return n - 1;
  let lo = 0, hi = n - 1;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (t[mid] <= time) lo = mid; else hi = mid;
  }
  return lo;
}

/// Linear interpolation of column `v` at `time`; angles (deg) that wrap between two
/// samples take the nearer sample instead.
export function interp(t, v, time, wrapDeg = false) {
  const i = sampleIndex(t, time);
  if (i >= t.length - 1) return v[t.length - 1];
  const dt = t[i + 1] - t[i];
  const s = dt > 0 ? Math.min(1, Math.max(0, (time - t[i]) / dt)) : 0;
  if (wrapDeg && Math.abs(v[i + 1] - v[i]) > 90) return s < 0.5 ? v[i] : v[i + 1];
  return v[i] + s * (v[i + 1] - v[i]);
}

export function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === 'class') e.className = v;
    else if (k === 'text') e.textContent = v;
    else if (k.startsWith('on')) e.addEventListener(k.slice(2), v);
    else e.setAttribute(k, v);
  }
  for (const c of children) if (c != null) e.append(c);
  return e;
}

/// "1 trial", "2 trials": a count and its noun for page text.
export function countText(n, singular, plural = singular + 's') {
  return `${n} ${n === 1 ? singular : plural}`;
}

export function fmt(v, digits = 4) {
  if (v === null || v === undefined) return '–';
  if (typeof v !== 'number') return String(v);
  if (v === 0) return '0';
  const a = Math.abs(v);
  if (a >= 1e5 || a < 1e-3) return v.toExponential(digits - 1);
  return String(Number(v.toPrecision(digits)));
}

/// A table element from a header row and body rows.
export function htmlTable(head, rows, cls = 'tbl') {
  return el('table', { class: cls },
    el('thead', {}, el('tr', {}, ...head.map((h) => el('th', { text: h })))),
    el('tbody', {}, ...rows.map((r) => el('tr', {}, ...r.map((c) => el('td', { text: fmt(c) }))))));
}

/// Viridis-like colour ramp for s in [0, 1].
export function ramp(s) {
  const stops = [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]];
  const x = Math.min(1, Math.max(0, s)) * (stops.length - 1);
  const i = Math.min(stops.length - 2, Math.floor(x));
  const f = x - i;
  const c = stops[i].map((a, k) => Math.round(a + f * (stops[i + 1][k] - a)));
  return `rgb(${c[0]},${c[1]},${c[2]})`;
}
