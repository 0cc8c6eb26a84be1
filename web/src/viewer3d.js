// The 3-D view: a three.js renderer in a z-up world (pronk's frame), the ground, lights
// and an orbit camera that can follow a point.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

export { THREE };

export class Viewer3D {
  constructor(container, extent = 1) {
    this.container = container;
    // preserveDrawingBuffer: the browser test reads pixels of the drawn frame.
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    container.append(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0xf4f6f8);
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.01, 200);
    this.camera.up.set(0, 0, 1);
    this.camera.position.set(-1.6 * extent, -2.2 * extent, 1.2 * extent);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.target.set(0, 0, 0.2 * extent);
    this.controls.addEventListener('change', () => this.render());
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x8899aa, 2.0));
    const sun = new THREE.DirectionalLight(0xffffff, 1.6);
    sun.position.set(2, -3, 5);
    this.scene.add(sun);
    this.follow = false;
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
  }

  /// The ground: a grid and a translucent plane at z = 0 of half size `half` around (cx, cy).
  addGround(cx, cy, half) {
    const step = half > 4 ? 1 : half > 1 ? 0.25 : 0.1;
    const n = Math.max(2, Math.ceil((2 * half) / step));
    const grid = new THREE.GridHelper(n * step, n, 0x9aa7b4, 0xc9d1d9);
    grid.rotation.x = Math.PI / 2;
    grid.position.set(cx, cy, 0);
    this.scene.add(grid);
    const plane = new THREE.Mesh(new THREE.PlaneGeometry(n * step, n * step),
      new THREE.MeshLambertMaterial({ color: 0xe3e8ec, transparent: true, opacity: 0.6 }));
    plane.position.set(cx, cy, -0.0005);
    this.scene.add(plane);
  }

  resize() {
    const w = Math.max(50, this.container.clientWidth), h = Math.max(50, this.container.clientHeight);
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.render();
  }

  /// Moves camera and target by the change of the followed point.
  followPoint(p) {
    if (this.follow && this.lastFollow) {
      const d = p.clone().sub(this.lastFollow);
      this.camera.position.add(d);
      this.controls.target.add(d);
      this.controls.update();
    }
    this.lastFollow = p.clone();
  }

  render() { this.renderer.render(this.scene, this.camera); }

  /// Frees the WebGL context (a page may show many runs one after another).
  dispose() {
    this.controls.dispose();
    this.renderer.dispose();
    this.renderer.forceContextLoss();
    this.renderer.domElement.remove();
  }

  /// Screen position (CSS pixels from the canvas's top left) of a world point.
  project(p) {
    const v = new THREE.Vector3(p[0], p[1], p[2]).project(this.camera);
    const c = this.renderer.domElement;
    return { x: (v.x + 1) / 2 * c.clientWidth, y: (1 - v.y) / 2 * c.clientHeight };
  }

  /// RGBA of the drawn frame at CSS pixel (x, y).
  pixel(x, y) {
    const gl = this.renderer.getContext();
    const r = this.renderer.getPixelRatio();
    const out = new Uint8Array(4);
    const h = this.renderer.domElement.height;
    gl.readPixels(Math.round(x * r), Math.round(h - 1 - y * r), 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, out);
    return Array.from(out);
  }
}

/// A line through points (updated in place, drawn up to a count).
export function polyline(points, color) {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(points, 3));
  return new THREE.Line(g, new THREE.LineBasicMaterial({ color }));
}

export function segment(color) {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute([0, 0, 0, 0, 0, 0], 3));
  return new THREE.Line(g, new THREE.LineBasicMaterial({ color }));
}

export function setSegment(line, a, b) {
  const p = line.geometry.attributes.position;
  p.setXYZ(0, a.x, a.y, a.z);
  p.setXYZ(1, b.x, b.y, b.z);
  p.needsUpdate = true;
  line.geometry.computeBoundingSphere();
}

export function sphere(radius, color) {
  return new THREE.Mesh(new THREE.SphereGeometry(radius, 16, 12),
    new THREE.MeshStandardMaterial({ color, roughness: 0.6 }));
}

/// A force arrow: from `origin` along `f` scaled by `scale` [m/N]; hidden when tiny.
export function setArrow(arrow, origin, f, scale) {
  const len = f.length() * scale;
  arrow.visible = len > 1e-3;
  if (!arrow.visible) return;
  arrow.position.copy(origin);
  arrow.setDirection(f.clone().normalize());
  arrow.setLength(len, Math.min(0.05, 0.3 * len), Math.min(0.03, 0.2 * len));
}

/// Box dimensions of a uniform box with the given principal inertia and mass.
export function inertiaBox(I, m) {
  const side = (a, b, c) => Math.sqrt(Math.max(6 * (b + c - a) / m, 1e-6));
  return [side(I[0], I[1], I[2]), side(I[1], I[0], I[2]), side(I[2], I[0], I[1])];
}
