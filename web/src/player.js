// Playback controls: play/pause, time slider, speed x0.1 to x10, stride stepping
// (touchdown to touchdown), follow camera, force arrows. Calls onTime(t) on every change.
import { el } from './data.js';

export class Player {
  constructor(container, { t0, t1, strideTimes = [], onTime, onFollow, follow = false, onArrows }) {
    this.t0 = t0; this.t1 = t1; this.t = t0; this.speed = 1; this.playing = false;
    this.strideTimes = strideTimes; this.onTime = onTime;
    this.play = el('button', { class: 'play', text: '▶', title: 'play / pause (space)', onclick: () => this.toggle() });
    this.slider = el('input', { type: 'range', min: 0, max: 10000, value: 0, class: 'slider' });
    this.slider.addEventListener('input', () => this.seek(t0 + (t1 - t0) * this.slider.value / 10000));
    this.label = el('span', { class: 'time' });
    const speed = el('select', { title: 'playback speed' },
      ...[0.1, 0.25, 0.5, 1, 2, 5, 10].map((s) => el('option', { value: s, text: `×${s}` })));
    speed.value = '1';
    speed.addEventListener('change', () => { this.speed = Number(speed.value); });
    const bits = [this.play];
    if (strideTimes.length) {
      bits.push(el('button', { text: '◀ stride', title: 'previous touchdown', onclick: () => this.stride(-1) }),
        el('button', { text: 'stride ▶', title: 'next touchdown', onclick: () => this.stride(1) }));
    }
    bits.push(this.slider, this.label, speed);
    if (onFollow) {
      const f = el('input', { type: 'checkbox' });
      f.checked = follow;
      f.addEventListener('change', () => onFollow(f.checked));
      bits.push(el('label', {}, f, ' follow'));
    }
    if (onArrows) {
      const a = el('input', { type: 'checkbox' });
      a.checked = true;
      a.addEventListener('change', () => onArrows(a.checked));
      bits.push(el('label', {}, a, ' forces'));
    }
    container.append(el('div', { class: 'controls' }, ...bits));
    this.seek(t0);
  }

  toggle() {
    this.playing = !this.playing;
    this.play.textContent = this.playing ? '⏸' : '▶';
    if (this.playing) {
      if (this.t >= this.t1) this.seek(this.t0);
      this.last = performance.now();
      requestAnimationFrame((n) => this.tick(n));
    }
  }

  tick(now) {
    if (!this.playing) return;
    const dt = Math.min(0.1, (now - this.last) / 1000);
    this.last = now;
    const t = this.t + dt * this.speed;
    this.seek(Math.min(t, this.t1));
    if (t >= this.t1) { this.toggle(); return; }
    requestAnimationFrame((n) => this.tick(n));
  }

  /// Jumps to the next (dir = 1) or previous (dir = -1) touchdown.
  stride(dir) {
    const eps = 1e-9;
    const ts = this.strideTimes;
    const next = dir > 0 ? ts.find((s) => s > this.t + eps) : [...ts].reverse().find((s) => s < this.t - eps);
    this.seek(next ?? (dir > 0 ? this.t1 : this.t0));
  }

  seek(t) {
    this.t = Math.min(this.t1, Math.max(this.t0, t));
    this.slider.value = String(Math.round(10000 * (this.t - this.t0) / Math.max(1e-12, this.t1 - this.t0)));
    const k = this.strideTimes.filter((s) => s <= this.t + 1e-9).length;
    this.label.textContent = `t = ${this.t.toFixed(3)} s` + (this.strideTimes.length ? ` · stride ${k}` : '');
    this.onTime(this.t);
  }
}
