// One run in a 3-D view (robot or mechanism), and the test hook of the browser test.
import { Viewer3D, THREE } from './viewer3d.js';
import { addRobot, robotSource } from './robot3d.js';
import { addMechanism } from './mechanism3d.js';
import { columns } from './data.js';
import { fewestAxisTicks } from './plots.js';

/// Builds the 3-D view of `run` in `container`; returns {viewer, update(t), t0, t1, strideTimes, ...}.
export function runScene(container, run, color) {
  const robot = run.kind === 'robot';
  const table = columns(robot ? run.trajectory : run.nodes);
  const T = table.t;
  // Ground extent: the span of the tracked path.
  let lo = [Infinity, Infinity], hi = [-Infinity, -Infinity];
  const xs = robot ? table.x : null, ys = robot ? table.y : null;
  if (robot) {
    for (let i = 0; i < T.length; i++) {
      lo = [Math.min(lo[0], xs[i]), Math.min(lo[1], ys[i])];
      hi = [Math.max(hi[0], xs[i]), Math.max(hi[1], ys[i])];
    }
  } else { lo = [0, 0]; hi = [0, 0]; }
  const viewer = new Viewer3D(container, 1);
  const model = robot ? addRobot(viewer, run, color) : addMechanism(viewer, run);
  const half = Math.max(model.extent, 0.6 * Math.max(hi[0] - lo[0], hi[1] - lo[1])) + 0.3;
  viewer.addGround((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, half);
  const e = model.extent;
  // A robot: the camera frames it where it starts and follows it (the follow box, on by
  // default), so it is on screen at every time whatever the path's length. A mechanism: the
  // middle of its motion, fixed.
  const c = robot ? new THREE.Vector3(xs[0], ys[0], 0.5 * e)
    : new THREE.Vector3((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, 0.3 * e);
  viewer.controls.target.copy(c);
  const d = robot ? 2.5 * e : Math.min(half, 2.5 * e);
  viewer.camera.position.set(c.x - 0.9 * d, c.y - 1.6 * d, c.z + 0.8 * d);
  viewer.follow = robot;
  viewer.controls.update();
  const strideTimes = robot && run.strides ? columns(run.strides).t_touchdown.slice() : [];
  let tracked = null;
  const update = (t) => {
    const p = model.update(t);
    viewer.followPoint(p);
    tracked = p;
    viewer.render();
  };
  const source = robot ? robotSource : model.source;
  const trackedMesh = robot ? () => model.body : model.trackedMesh;
  return {
    viewer, model, update, t0: T[0], t1: T[T.length - 1], strideTimes, source,
    tracked: () => {
      const w = trackedMesh().getWorldPosition(new THREE.Vector3());
      return { world: [w.x, w.y, w.z], screen: viewer.project([w.x, w.y, w.z]), last: tracked && [tracked.x, tracked.y, tracked.z] };
    },
  };
}

/// window.pronkTest: the browser test reads the drawn state through it.
export function installTestHook(scene, player, extra = {}) {
  window.pronkTest = {
    t0: scene.t0, t1: scene.t1, source: scene.source,
    setTime(t) { player.seek(t); },
    follow: () => scene.viewer.follow,
    fewestAxisTicks,
    setFollow(on) { scene.viewer.follow = on; scene.viewer.lastFollow = null; },
    tracked: () => scene.tracked(),
    project: (p) => scene.viewer.project(p),
    pixel: (x, y) => scene.viewer.pixel(x, y),
    canvas: () => {
      const c = scene.viewer.renderer.domElement;
      return { width: c.clientWidth, height: c.clientHeight };
    },
    ...extra,
  };
}
