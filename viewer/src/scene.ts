// The 3-D scene: the machine's solids, the mandrel and its path, the
// payout point, all placed by the poses the server sent.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import type { MachineScene, MandrelScene, Sample, Solid } from './api';

export class Scene {
  readonly renderer: THREE.WebGLRenderer;
  readonly camera: THREE.PerspectiveCamera;
  readonly controls: OrbitControls;
  private readonly scene = new THREE.Scene();
  private readonly links: THREE.Group[] = [];
  private readonly payout: THREE.Mesh;
  private readonly trail: THREE.Line;
  private readonly trailPositions: Float32Array;
  private trailCount = 0;
  private readonly box = new THREE.Box3();

  constructor(
    private readonly host: HTMLElement,
    machine: MachineScene,
    mandrel: MandrelScene | null,
    private readonly payoutIndex: number,
  ) {
    this.renderer = new THREE.WebGLRenderer({ antialias: false, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
    host.appendChild(this.renderer.domElement);
    this.scene.background = new THREE.Color('#dfe4ea');
    this.camera = new THREE.PerspectiveCamera(40, 1, 5, 100000);
    this.camera.up.set(0, 0, 1);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.scene.add(new THREE.HemisphereLight('#ffffff', '#7a8088', 1.6));
    const sun = new THREE.DirectionalLight('#ffffff', 1.6);
    sun.position.set(2000, -3000, 4000);
    this.scene.add(sun);

    for (const link of machine.links) {
      const g = new THREE.Group();
      g.name = link.name;
      for (const s of link.solids) g.add(solid(s));
      this.links.push(g);
      this.scene.add(g);
    }
    if (mandrel) this.addMandrel(mandrel);

    this.payout = new THREE.Mesh(
      new THREE.SphereGeometry(15, 20, 12),
      new THREE.MeshStandardMaterial({ color: '#e0322b', emissive: '#601010' }),
    );
    this.scene.add(this.payout);
    this.trailPositions = new Float32Array(3 * 4096);
    const tg = new THREE.BufferGeometry();
    tg.setAttribute('position', new THREE.BufferAttribute(this.trailPositions, 3));
    tg.setDrawRange(0, 0);
    this.trail = new THREE.Line(tg, new THREE.LineBasicMaterial({ color: '#e0322b' }));
    this.trail.frustumCulled = false;
    this.scene.add(this.trail);
    this.resize();
    new ResizeObserver(() => this.resize()).observe(host);
  }

  private addMandrel(m: MandrelScene): void {
    const g = this.links[m.link];
    if (!g) return;
    const pts = m.meridian.map(([z, r]) => new THREE.Vector2(r, z));
    if (pts.length >= 2) {
      const lathe = new THREE.LatheGeometry(pts, 96);
      // The lathe turns about y; the mandrel's axis is the link's z.
      lathe.rotateX(Math.PI / 2);
      const mesh = new THREE.Mesh(
        lathe,
        new THREE.MeshStandardMaterial({ color: '#8fa7bd', side: THREE.DoubleSide, roughness: 0.6 }),
      );
      mesh.name = 'mandrel';
      g.add(mesh);
    }
    if (m.path.length >= 2) {
      const pos = new Float32Array(m.path.flat());
      const geo = new THREE.BufferGeometry();
      geo.setAttribute('position', new THREE.BufferAttribute(pos, 3));
      const line = new THREE.Line(geo, new THREE.LineBasicMaterial({ color: '#173f8a' }));
      line.name = 'path';
      g.add(line);
    }
  }

  /** Places every link and the payout point as `s` says. */
  show(s: Sample): void {
    s.poses.forEach((p, i) => {
      const g = this.links[i];
      if (!g) return;
      g.position.set(p[0], p[1], p[2]);
      g.quaternion.set(p[3], p[4], p[5], p[6]);
    });
    const q = s.points[this.payoutIndex];
    if (q) {
      this.payout.position.set(q[0], q[1], q[2]);
      const n = this.trailCount % 4096;
      this.trailPositions.set(q, 3 * n);
      this.trailCount++;
      this.trail.geometry.setDrawRange(0, Math.min(this.trailCount, 4096));
      this.trail.geometry.attributes.position.needsUpdate = true;
    }
  }

  /** Forgets the payout point's trail (after a jump). */
  clearTrail(): void {
    this.trailCount = 0;
    this.trail.geometry.setDrawRange(0, 0);
  }

  render(): void {
    this.controls.update();
    this.renderer.render(this.scene, this.camera);
  }

  /** Looks at the whole machine from `view`. */
  look(view: 'front' | 'top' | 'axis'): void {
    this.box.setFromObject(this.scene);
    const centre = this.box.getCenter(new THREE.Vector3());
    const size = this.box.getSize(new THREE.Vector3()).length();
    let dir = new THREE.Vector3(0, -1, 0.35);
    let target = centre;
    if (view === 'top') dir = new THREE.Vector3(0, -0.001, 1);
    const mandrel = this.scene.getObjectByName('mandrel');
    if (view === 'axis' && mandrel) {
      const mb = new THREE.Box3().setFromObject(mandrel);
      target = mb.getCenter(new THREE.Vector3());
      // The mandrel's axis: its link's z.
      // From the mandrel's far end (+z), away from the spindle's drive.
      dir = new THREE.Vector3(0, 0, 1).applyQuaternion(mandrel.getWorldQuaternion(new THREE.Quaternion()));
      this.controls.target.copy(target);
      this.camera.position.copy(target).addScaledVector(dir.normalize(), mb.getSize(new THREE.Vector3()).length() * 2.2);
      this.camera.lookAt(target);
      return;
    }
    this.controls.target.copy(target);
    this.camera.position.copy(target).addScaledVector(dir.normalize(), size * 1.5);
    this.camera.lookAt(target);
  }

  private resize(): void {
    const w = Math.max(this.host.clientWidth, 1);
    const h = Math.max(this.host.clientHeight, 1);
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
  }
}

function solid(s: Solid): THREE.Mesh {
  let geo: THREE.BufferGeometry;
  switch (s.shape) {
    case 'box':
      geo = new THREE.BoxGeometry(s.size[0], s.size[1], s.size[2]);
      break;
    case 'cylinder':
      geo = new THREE.CylinderGeometry(s.radius, s.radius, s.length, 40);
      // three's cylinder runs along y; the machine's along z.
      geo.rotateX(Math.PI / 2);
      break;
    case 'sphere':
      geo = new THREE.SphereGeometry(s.radius, 32, 16);
      break;
  }
  const m = new THREE.Mesh(geo, new THREE.MeshStandardMaterial({ color: s.color, roughness: 0.7 }));
  const o = s.origin;
  m.position.set(o[0], o[1], o[2]);
  m.quaternion.set(o[3], o[4], o[5], o[6]);
  return m;
}
