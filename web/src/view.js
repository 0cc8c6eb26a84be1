// view.html: the 3-D playback of one robot or mechanism run beside its linked plots.
import { pageData, el, fmt } from './data.js';
import { runScene, installTestHook } from './runscene.js';
import { robotPlots, mechanismPlots } from './runplots.js';
import { Player } from './player.js';

function header(D) {
  const s = D.summary ?? {};
  const model = D.kind === 'robot' ? `${D.scene.model} model` : 'mechanism';
  const bits = [`${model}`, `status ${s.status ?? '?'}${s.reason ? ' (' + s.reason + ')' : ''}`];
  if (s.t_end !== undefined) bits.push(`t_end ${fmt(s.t_end)} s`);
  const every = (D.trajectory ?? D.nodes)?.every ?? 1;
  if (every > 1) bits.push(`every ${every}th sample shown`);
  return el('header', {}, el('h1', { text: D.name }), el('div', { class: 'sub', text: bits.join(' · ') }));
}

function main() {
  const D = pageData();
  document.title = `${D.name} · pronk view`;
  const app = document.getElementById('app');
  app.append(header(D));
  const stage = el('div', { class: 'stage' });
  const plots = el('div', { class: 'plots' });
  const left = el('div', { class: 'left' }, stage);
  app.append(el('div', { class: 'layout' }, left, plots));
  const scene = runScene(stage, D);
  let linked = null;
  const player = new Player(left, {
    t0: scene.t0, t1: scene.t1, strideTimes: scene.strideTimes,
    onTime: (t) => { scene.update(t); if (linked) linked.syncTo(t); },
    onFollow: (on) => { scene.viewer.follow = on; scene.viewer.lastFollow = null; },
    follow: scene.viewer.follow,
    onArrows: D.kind === 'robot' ? (on) => { scene.model.state.arrows = on; player.seek(player.t); } : null,
  });
  linked = (D.kind === 'robot' ? robotPlots : mechanismPlots)(plots, D, (t) => player.seek(t));
  player.seek(scene.t0);
  left.append(el('p', { class: 'note', text: D.kind === 'robot'
    ? 'Body: box of the inertia; legs hang at rest length in flight; orange: net leg force at the CoM; green: its share at each stance foot; red: CoM trail and setpoint. Drag to orbit, wheel to zoom; click a plot to seek.'
    : 'Blue: point masses and body ellipsoids; wireframe: ghost points and surface points; lines: springs (black legs, orange others), purple: surfaces. Drag to orbit; click a plot to seek.' }));
  installTestHook(scene, player);
}

main();
