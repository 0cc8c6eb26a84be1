// The robot in 3-D from trajectory.csv: body (box of its inertia), hips, legs, feet, CoM
// trail, setpoint, net leg force at the CoM and the ground forces at the stance feet.
import { THREE, polyline, segment, setSegment, sphere, setArrow, inertiaBox } from './viewer3d.js';
import { columns, interp } from './data.js';

function principalInertia(body) {
  if (body.inertia) return body.inertia;
  const T = body.inertia_tensor;
  return T ? [T[0][0], T[1][1], T[2][2]] : [0.01, 0.01, 0.01];
}

/// Adds the robot of `run` ({scene, trajectory, feet}) to `viewer`; returns {update(t), body}.
export function addRobot(viewer, run, color = 0x3b6ea8) {
  const tr = columns(run.trajectory);
  const sc = run.scene;
  const g = sc.gravity ?? 9.81;
  const m = sc.body?.mass ?? 1;
  const dims = inertiaBox(principalInertia(sc.body ?? {}), m);
  const body = new THREE.Mesh(new THREE.BoxGeometry(...dims),
    new THREE.MeshStandardMaterial({ color, roughness: 0.5, metalness: 0.1 }));
  body.add(new THREE.AxesHelper(0.6 * Math.max(...dims)));
  viewer.scene.add(body);
  const legged = sc.legs?.kind === 'legged';
  const hips = legged ? sc.legs.hips : [];
  const disabled = new Set(sc.legs?.disabled ?? []);
  const length = sc.legs?.length ?? 0.25;
  const parts = hips.map((h, i) => {
    const hip = sphere(0.012, 0x223344);
    const foot = sphere(0.015, disabled.has(i) ? 0x999999 : 0x333333);
    const leg = segment(disabled.has(i) ? 0xaaaaaa : 0x222222);
    const ground = new THREE.ArrowHelper(new THREE.Vector3(0, 0, 1), new THREE.Vector3(), 0.1, 0x2a9d4b);
    viewer.scene.add(hip, foot, leg, ground);
    return { hipBody: new THREE.Vector3(...h), hip, foot, leg, ground, disabled: disabled.has(i) };
  });
  // The CoM trail over the whole run, drawn up to the current sample.
  const pts = [];
  for (let i = 0; i < tr.length; i++) pts.push(tr.x[i], tr.y[i], tr.z[i]);
  const trail = polyline(pts, 0xd1495b);
  viewer.scene.add(trail);
  const setpoint = new THREE.Mesh(new THREE.RingGeometry(0.02, 0.035, 24),
    new THREE.MeshBasicMaterial({ color: 0xd1495b, side: THREE.DoubleSide }));
  viewer.scene.add(setpoint);
  const net = new THREE.ArrowHelper(new THREE.Vector3(0, 0, 1), new THREE.Vector3(), 0.1, 0xf18f01);
  viewer.scene.add(net);
  let fmax = 1e-9;
  for (let i = 0; i < tr.length; i++) fmax = Math.max(fmax, Math.hypot(tr.Fx[i], tr.Fy[i], tr.Fz[i]));
  const scale = 0.35 / Math.max(fmax, m * g);
  const state = { arrows: true };

  function update(t) {
    const T = tr.t;
    const p = new THREE.Vector3(interp(T, tr.x, t), interp(T, tr.y, t), interp(T, tr.z, t));
    const deg = Math.PI / 180;
    body.position.copy(p);
    // 1-2-3 Euler angles: R = Rx(roll) Ry(pitch) Rz(yaw), three.js order 'XYZ'.
    body.rotation.set(interp(T, tr.roll_deg, t, true) * deg, interp(T, tr.pitch_deg, t, true) * deg,
      interp(T, tr.yaw_deg, t, true) * deg, 'XYZ');
    body.updateMatrixWorld();
    const i = Math.min(tr.length - 1, Math.max(0, Math.round(interpIndex(T, t))));
    trail.geometry.setDrawRange(0, Math.max(2, i + 1));
    setpoint.position.set(interp(T, tr.x_d, t), interp(T, tr.y_d, t), 0.001);
    const F = new THREE.Vector3(tr.Fx[i], tr.Fy[i], tr.Fz[i]);
    net.visible = state.arrows;
    if (state.arrows) setArrow(net, p, F, scale);
    const stance = parts.filter((q) => !q.disabled);
    const inStance = tr.stance ? tr.stance[i] > 0.5 : F.length() > 1e-9;
    for (const q of parts) {
      const hw = q.hipBody.clone().applyMatrix4(body.matrixWorld);
      q.hip.position.copy(hw);
      // Massless legs hang vertically at rest length (length - hip depth) in flight.
      // In stance (the pulse pushes on after the CoM rises past touchdown height) the leg
      // extends and the foot stays on the ground.
      const legLen = length + q.hipBody.z;
      const fz = inStance && !q.disabled ? 0 : Math.max(0, hw.z - legLen);
      q.foot.position.set(hw.x, hw.y, fz);
      setSegment(q.leg, hw, q.foot.position);
      const down = fz <= 1e-6 && !q.disabled && F.length() > 1e-9;
      q.ground.visible = state.arrows && down;
      if (q.ground.visible) setArrow(q.ground, q.foot.position, F.clone().divideScalar(stance.length), scale);
    }
    return p;
  }
  return { update, body, state, extent: Math.max(0.6, length * 3) };
}

function interpIndex(T, t) {
  let lo = 0, hi = T.length - 1;
  if (t <= T[0]) return 0;
  if (t >= T[hi]) return hi;
  while (hi - lo > 1) { const mid = (lo + hi) >> 1; if (T[mid] <= t) lo = mid; else hi = mid; }
  return lo + (t - T[lo]) / (T[hi] - T[lo]);
}

/// Where the drawn body comes from, for the browser test.
export const robotSource = { file: 'trajectory.csv', columns: ['x', 'y', 'z'] };
