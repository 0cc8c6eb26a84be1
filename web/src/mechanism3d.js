// A pseudo-rigid mechanism in 3-D from nodes.csv and bodies.csv: point masses, ghost
// points, springs (connections), body ellipsoids, plane and line surfaces.
import { THREE, segment, setSegment, sphere } from './viewer3d.js';
import { columns, interp } from './data.js';

function quatOf(a, set) {
  const ax = (k, angle) => new THREE.Quaternion().setFromAxisAngle(
    new THREE.Vector3(k === 0 ? 1 : 0, k === 1 ? 1 : 0, k === 2 ? 1 : 0), angle);
  // 1-2-3: Rx Ry Rz; 3-1-3: Rz Rx Rz (intrinsic, as sim/math/rotation.hpp).
  return set === '313' ? ax(2, a[0]).multiply(ax(0, a[1])).multiply(ax(2, a[2]))
    : ax(0, a[0]).multiply(ax(1, a[1])).multiply(ax(2, a[2]));
}

/// Adds the mechanism of `run` ({scene, nodes, bodies}); returns {update(t), extent, source}.
export function addMechanism(viewer, run) {
  const sc = run.scene;
  const nodes = columns(run.nodes);
  const bodies = columns(run.bodies);
  const names = run.nodes.columns.filter((c) => c.endsWith('_x')).map((c) => c.slice(0, -2));
  const ghosts = new Set((sc.bodies ?? []).flatMap((b) => (b.ghost_points ?? []).map((g) => g.name)));
  const massOf = Object.fromEntries((sc.masses ?? []).map((m) => [m.name, m.mass]));
  const T = nodes.t;
  const at = (name, t) => new THREE.Vector3(interp(T, nodes[name + '_x'], t),
    interp(T, nodes[name + '_y'], t), interp(T, nodes[name + '_z'], t));
  let span = 0.2;
  for (const n of names) for (const k of ['_x', '_y', '_z']) {
    for (const v of [nodes[n + k][0], nodes[n + k][nodes.length - 1]]) span = Math.max(span, Math.abs(v));
  }
  const r0 = 0.02 * Math.min(1, span);
  const points = names.map((n) => {
    const ghost = ghosts.has(n), onSurface = n.endsWith('.point');
    const mass = massOf[n];
    const mesh = ghost || onSurface
      ? new THREE.Mesh(new THREE.SphereGeometry(r0 * 0.7, 12, 8),
        new THREE.MeshBasicMaterial({ color: onSurface ? 0x7a5195 : 0x2a9d8f, wireframe: true }))
      : sphere(mass ? r0 * Math.max(0.5, Math.min(2, Math.cbrt(mass / 0.1))) : r0, 0x3b6ea8);
    viewer.scene.add(mesh);
    return { name: n, mesh };
  });
  const springs = (sc.connections ?? []).filter((c) => nodes[c.a + '_x'] && nodes[c.b + '_x'])
    .map((c) => {
      const line = segment(c.class === 'leg' ? 0x222222 : c.class === 'internal' ? 0xb0b8c0 : 0xef8a17);
      viewer.scene.add(line);
      return { a: c.a, b: c.b, line };
    });
  const euler = sc.simulation?.euler_set ?? '123';
  const bodyMeshes = (sc.bodies ?? []).filter((b) => bodies && bodies[b.name + '_x']).map((b) => {
    const I = b.inertia ?? [0.01, 0.01, 0.01];
    const m = b.mass ?? 1;
    const semi = [0, 1, 2].map((k) => Math.sqrt(Math.max(2.5 * (I[(k + 1) % 3] + I[(k + 2) % 3] - I[k]) / m, 1e-6)));
    const mesh = new THREE.Mesh(new THREE.SphereGeometry(1, 24, 16),
      new THREE.MeshStandardMaterial({ color: 0x3b6ea8, transparent: true, opacity: 0.45 }));
    mesh.scale.set(...semi);
    mesh.add(new THREE.AxesHelper(1.2));
    viewer.scene.add(mesh);
    return { name: b.name, mesh };
  });
  const lines = (sc.surfaces ?? []).filter((s) => s.type === 'line' && nodes[s.name + '.point_x'])
    .map((s) => {
      const line = segment(0x7a5195);
      viewer.scene.add(line);
      return { s, line, body: bodyMeshes.find((b) => b.name === s.body) };
    });
  for (const s of sc.surfaces ?? []) {
    if (s.type !== 'plane') continue;
    const n = new THREE.Vector3(...s.direction).normalize();
    if (Math.abs(n.z) > 0.999 && Math.abs(s.point[2]) < 1e-9) continue;  // the ground: drawn already
    const plane = new THREE.Mesh(new THREE.PlaneGeometry(4 * span, 4 * span),
      new THREE.MeshLambertMaterial({ color: 0xc8b6e2, transparent: true, opacity: 0.4, side: THREE.DoubleSide }));
    plane.position.set(...s.point);
    plane.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), n);
    viewer.scene.add(plane);
  }
  // The tracked point: the first body's CoM, else the first point mass.
  const track = bodyMeshes.length ? { file: 'bodies.csv', prefix: bodyMeshes[0].name }
    : { file: 'nodes.csv', prefix: points.find((p) => massOf[p.name] !== undefined)?.name ?? names[0] };

  function update(t) {
    for (const p of points) p.mesh.position.copy(at(p.name, t));
    for (const s of springs) setSegment(s.line, at(s.a, t), at(s.b, t));
    for (const b of bodyMeshes) {
      const c = (k) => interp(bodies.t, bodies[b.name + k], t);
      b.mesh.position.set(c('_x'), c('_y'), c('_z'));
      b.mesh.quaternion.copy(quatOf([c('_roll'), c('_pitch'), c('_yaw')], euler));
      b.mesh.updateMatrixWorld();
    }
    for (const l of lines) {
      const p = at(l.s.name + '.point', t);
      const d = new THREE.Vector3(...l.s.direction).normalize().multiplyScalar(span * 0.3);
      if (l.body) d.applyQuaternion(l.body.mesh.quaternion);
      setSegment(l.line, p.clone().sub(d), p.clone().add(d));
    }
    const src = track.file === 'bodies.csv' ? bodyMeshes[0].mesh.position : at(track.prefix, t);
    return src.clone();
  }
  return {
    update, extent: Math.max(0.4, span),
    source: { file: track.file, columns: ['_x', '_y', '_z'].map((k) => track.prefix + k) },
    trackedMesh: () => (bodyMeshes.length ? bodyMeshes[0].mesh : points.find((p) => p.name === track.prefix).mesh),
  };
}
