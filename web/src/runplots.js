// The linked plots of a run: position, attitude, forces, energy balance, and apex height
// and duty per stride. Each returns its charts; syncTo(t) moves their cursors.
import { columns, sampleIndex } from './data.js';
import { linePlot, setCursorX } from './plots.js';

/// Mechanical energy of a reduced-model run from its trajectory, and the leg work
/// integrated (trapezoid on the samples) from the net leg force.
function reducedEnergy(run, tr) {
  const sc = run.scene, m = sc.body?.mass ?? 1, g = sc.gravity ?? 9.81;
  const I = sc.body?.inertia_tensor ?? [[sc.body.inertia[0], 0, 0], [0, sc.body.inertia[1], 0], [0, 0, sc.body.inertia[2]]];
  const n = tr.length, E = new Array(n), W = new Array(n);
  let work = 0;
  for (let i = 0; i < n; i++) {
    const w = [tr.wx[i], tr.wy[i], tr.wz[i]];
    let rot = 0;
    for (let a = 0; a < 3; a++) for (let b = 0; b < 3; b++) rot += w[a] * I[a][b] * w[b];
    E[i] = 0.5 * m * (tr.vx[i] ** 2 + tr.vy[i] ** 2 + tr.vz[i] ** 2) + 0.5 * rot + m * g * tr.z[i];
    if (i > 0) {
      const p = (k) => tr.Fx[k] * tr.vx[k] + tr.Fy[k] * tr.vy[k] + tr.Fz[k] * tr.vz[k];
      work += 0.5 * (p(i) + p(i - 1)) * (tr.t[i] - tr.t[i - 1]);
    }
    W[i] = E[0] + work;
  }
  return { E, W };
}

export function robotPlots(box, run, onSeek) {
  const tr = columns(run.trajectory);
  const t = tr.t;
  const o = (title, ylabel) => ({ title, ylabel, onSeek });
  const charts = [
    linePlot(box, t, [{ label: 'x', values: tr.x }, { label: 'y', values: tr.y }, { label: 'z', values: tr.z },
      { label: 'x_d', values: tr.x_d, dash: [4, 4], color: '#1f77b4' }, { label: 'y_d', values: tr.y_d, dash: [4, 4], color: '#d62728' }],
    o('CoM position and setpoint', 'm')),
    linePlot(box, t, [{ label: 'roll', values: tr.roll_deg }, { label: 'pitch', values: tr.pitch_deg }, { label: 'yaw', values: tr.yaw_deg }],
      o('attitude (1-2-3 Euler)', 'deg')),
  ];
  const feet = columns(run.feet);
  const forces = [{ label: 'Fx', values: tr.Fx }, { label: 'Fy', values: tr.Fy }, { label: 'Fz', values: tr.Fz }];
  charts.push(linePlot(box, t, forces, o('net leg force (world)', 'N')));
  if (feet) {
    const legs = run.feet.columns.filter((c) => c !== 't').map((c) => ({ label: c, values: feet[c] }));
    charts.push(linePlot(box, feet.t, legs, o('leg actuator forces (feet.csv)', 'N')));
  }
  const energy = columns(run.energy);
  if (energy) {
    const cols = run.energy.columns.filter((c) => c !== 't');
    charts.push(linePlot(box, energy.t, cols.map((c) => ({ label: c, values: energy[c], width: c === 'balance' ? 2.5 : 1.2 })),
      o('energy by class and balance (energy.csv)', 'J')));
  } else {
    const { E, W } = reducedEnergy(run, tr);
    charts.push(linePlot(box, t, [{ label: 'E mechanical', values: E }, { label: 'E(0) + leg work', values: W, dash: [5, 4] }],
      o('energy balance (leg work integrated on the samples: approximate where the force jumps between samples)', 'J')));
  }
  const st = columns(run.strides);
  let strideChart = null;
  if (st && st.length) {
    const k = st.stride.map(Number);
    strideChart = linePlot(box, k, [
      { label: 'apex height [m]', values: st.apex_height, points: true, size: 7 },
      { label: 'duty cycle', values: st.duty_cycle, points: true, size: 7, scale: 'y2', color: '#2ca02c' }],
    { title: 'apex height and duty per stride', xlabel: 'stride', ylabel: 'apex [m]', y2label: 'duty',
      onSeek: (s) => onSeek(st.t_touchdown[Math.max(0, Math.min(st.length - 1, Math.round(s)))]) });
  }
  return {
    syncTo(time) {
      for (const c of charts) setCursorX(c, time);
      if (strideChart) {
        const i = st.t_touchdown.filter((s) => s <= time + 1e-9).length - 1;
        if (i >= 0) setCursorX(strideChart, st.stride[i]);
      }
    },
  };
}

export function mechanismPlots(box, run, onSeek) {
  const charts = [];
  const b = columns(run.bodies);
  const o = (title, ylabel) => ({ title, ylabel, onSeek });
  if (b && run.bodies.columns.length > 1) {
    const pos = run.bodies.columns.filter((c) => /_[xyz]$/.test(c));
    charts.push(linePlot(box, b.t, pos.map((c) => ({ label: c, values: b[c] })), o('body CoM', 'm')));
    const att = run.bodies.columns.filter((c) => /_(roll|pitch|yaw)$/.test(c));
    charts.push(linePlot(box, b.t, att.map((c) => ({ label: c, values: b[c].map((v) => v * 180 / Math.PI) })), o('body attitude', 'deg')));
  } else {
    const n = columns(run.nodes);
    const z = run.nodes.columns.filter((c) => c.endsWith('_z')).slice(0, 8);
    charts.push(linePlot(box, n.t, z.map((c) => ({ label: c, values: n[c] })), o('node heights', 'm')));
  }
  const e = columns(run.energy);
  const cols = run.energy.columns.filter((c) => c !== 't');
  charts.push(linePlot(box, e.t, cols.map((c) => ({ label: c, values: e[c], width: c === 'balance' ? 2.5 : 1.2 })),
    o('energy by class and balance', 'J')));
  return { syncTo(time) { for (const c of charts) setCursorX(c, time); } };
}

export { sampleIndex };
