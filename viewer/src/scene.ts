// The 3-D scene: the machine's solids, the mandrel and its path, the
// payout point, the eye trajectory and the band laid, all placed by the
// poses the server sent; the camera's views and the follow mode.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { toCreasedNormals } from 'three/examples/jsm/utils/BufferGeometryUtils.js';
import { meshData } from './api';
import type { Band, EyeTrajectory, MachineScene, MandrelScene, Sample, Solid } from './api';

export type View = 'front' | 'top' | 'axis';

/** The colour of a solid named in a violation. */
const ALARM = new THREE.Color('#ff2a1a');

/** Edges of a mesh solid sharper than this are drawn sharp, the rest smooth. */
const CREASE = THREE.MathUtils.degToRad(35);
/**
 * How far the drawn meridian may stray from the one the server sent (mm):
 * the surface is drawn, never measured, and a straight or gently curved
 * meridian needs few of its points (drawing cost grows with triangles in
 * software GL).
 */
const MERIDIAN_TOLERANCE_MM = 0.02;

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
  /** Every link's solids (for highlighting). */
  private readonly solids: THREE.Mesh[][] = [];
  private highlighted = new Set<number>();
  private band: THREE.Mesh | null = null;
  private bandTotal = 0;
  private bandShown = 0;
  private eye: THREE.Line | null = null;
  /** The mesh solids drawn and their triangles. */
  private readonly meshSolids: THREE.Mesh[] = [];
  private meshTriangles = 0;
  /** What the page says about mesh solids (unreadable, thinned). */
  private readonly meshNotes: string[] = [];
  /** Resolved when every mesh solid's triangles are drawn (or said unreadable). */
  readonly meshesLoaded: Promise<void>;
  /** Keep the payout point at the centre of the view. */
  follow = false;
  /** Whether anything changed since the last frame drawn. */
  dirty = true;

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
    this.controls.addEventListener('change', () => { this.dirty = true; });
    this.scene.add(new THREE.HemisphereLight('#ffffff', '#7a8088', 1.6));
    const sun = new THREE.DirectionalLight('#ffffff', 1.6);
    sun.position.set(2000, -3000, 4000);
    this.scene.add(sun);

    for (const link of machine.links) {
      const g = new THREE.Group();
      g.name = link.name;
      const meshes = link.solids.map(solid);
      for (const m of meshes) g.add(m);
      this.solids.push(meshes);
      this.links.push(g);
      this.scene.add(g);
    }
    this.meshesLoaded = this.loadMeshes(machine);
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

  /**
   * Fills every mesh solid with its triangles from the server, shaded by
   * normals computed here (smooth across edges under CREASE); a mesh the
   * server could not read, or thinned for drawing, is said on the page.
   */
  private async loadMeshes(machine: MachineScene): Promise<void> {
    const loads: Promise<void>[] = [];
    machine.links.forEach((link, i) => link.solids.forEach((s, k) => {
      if (s.shape !== 'mesh') return;
      const m = this.solids[i][k];
      if (s.mesh === undefined) {
        this.meshNotes.push(`mesh not drawn: ${s.error ?? s.file}`);
        return;
      }
      if (s.drawn < s.triangles) {
        this.meshNotes.push(`${s.file}: drawn with ${s.drawn} of its ${s.triangles} triangles`);
      }
      loads.push(meshData(s.mesh).then((d) => {
        const g = new THREE.BufferGeometry();
        g.setAttribute('position', new THREE.BufferAttribute(d.positions, 3));
        g.setIndex(new THREE.BufferAttribute(d.indices, 1));
        const shaded = toCreasedNormals(g, CREASE);
        shaded.computeBoundingBox();
        shaded.computeBoundingSphere();
        g.dispose();
        m.geometry.dispose();
        m.geometry = shaded;
        this.meshSolids.push(m);
        this.meshTriangles += d.indices.length / 3;
        this.dirty = true;
      }, (e: unknown) => {
        this.meshNotes.push(`mesh not drawn: ${s.file}: ${e instanceof Error ? e.message : String(e)}`);
      }));
    }));
    await Promise.all(loads);
    if (this.meshNotes.length > 0) {
      const note = document.createElement('div');
      note.className = 'mesh-notes';
      note.textContent = this.meshNotes.join('\n');
      this.host.appendChild(note);
    }
  }

  /**
   * The mesh solids drawn: their triangles, what the page says about them,
   * and where each one's centre is drawn, px from the canvas's centre.
   */
  meshes(): { mesh_triangles: number; mesh_notes: string[]; mesh_px: [number, number][] } {
    const c = this.renderer.domElement;
    const mesh_px = this.meshSolids.map((m): [number, number] => {
      const p = new THREE.Box3().setFromObject(m).getCenter(new THREE.Vector3()).project(this.camera);
      return [(p.x * c.clientWidth) / 2, (-p.y * c.clientHeight) / 2];
    });
    return { mesh_triangles: this.meshTriangles, mesh_notes: [...this.meshNotes], mesh_px };
  }

  private addMandrel(m: MandrelScene): void {
    const g = this.links[m.link];
    if (!g) return;
    const pts = simplified(m.meridian, MERIDIAN_TOLERANCE_MM).map(([z, r]) => new THREE.Vector2(r, z));
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

  /** The payout point's path over the whole program (world frame). */
  addEye(e: EyeTrajectory): void {
    if (e.points.length < 2) return;
    const geo = new THREE.BufferGeometry();
    geo.setAttribute('position', new THREE.BufferAttribute(new Float32Array(e.points.flat()), 3));
    this.eye = new THREE.Line(
      geo,
      new THREE.LineBasicMaterial({ color: '#7b3fa0', transparent: true, opacity: 0.55 }),
    );
    this.eye.name = 'eye-trajectory';
    this.eye.frustumCulled = false;
    this.scene.add(this.eye);
  }

  /**
   * The band over the whole program as a ribbon on the mandrel (in its
   * link's frame), of which `showLaid` draws the part laid.
   */
  addBand(b: Band): void {
    const g = this.links[b.link];
    const n = b.points.length;
    if (!g || n < 2) return;
    const pos = new Float32Array(6 * n);
    const half = b.width_mm / 2;
    const p = new THREE.Vector3();
    const t = new THREE.Vector3();
    const radial = new THREE.Vector3();
    const side = new THREE.Vector3();
    for (let i = 0; i < n; i++) {
      const a = b.points[Math.max(i - 1, 0)];
      const c = b.points[Math.min(i + 1, n - 1)];
      p.set(b.points[i][0], b.points[i][1], b.points[i][2]);
      t.set(c[0] - a[0], c[1] - a[1], c[2] - a[2]).normalize();
      // Lifted off the surface a little, the band's half width to each side.
      radial.set(p.x, p.y, 0).normalize();
      side.crossVectors(radial, t).normalize().multiplyScalar(half);
      p.addScaledVector(radial, 0.8);
      pos.set([p.x + side.x, p.y + side.y, p.z + side.z, p.x - side.x, p.y - side.y, p.z - side.z], 6 * i);
    }
    const starts = new Set(b.layers);
    const index: number[] = [];
    for (let i = 0; i + 1 < n; i++) {
      // No strip across a join of layers: a degenerate one keeps the stride.
      if (starts.has(i + 1)) index.push(2 * i, 2 * i, 2 * i, 2 * i, 2 * i, 2 * i);
      else index.push(2 * i, 2 * i + 1, 2 * i + 2, 2 * i + 1, 2 * i + 3, 2 * i + 2);
    }
    const geo = new THREE.BufferGeometry();
    geo.setAttribute('position', new THREE.BufferAttribute(pos, 3));
    geo.setIndex(index);
    geo.computeVertexNormals();
    geo.setDrawRange(0, 0);
    this.band = new THREE.Mesh(
      geo,
      new THREE.MeshStandardMaterial({ color: '#d9822b', side: THREE.DoubleSide, roughness: 0.8 }),
    );
    this.band.name = 'band';
    this.band.frustumCulled = false;
    this.bandTotal = n;
    g.add(this.band);
  }

  /** Draws the first `n` band points (the band laid so far). */
  showLaid(n: number): void {
    if (!this.band) return;
    this.bandShown = Math.min(Math.max(n, 0), this.bandTotal);
    this.band.geometry.setDrawRange(0, 6 * Math.max(this.bandShown - 1, 0));
  }

  /** Shows or hides the band, the eye trajectory and the mesh solids (tests compare the pixels). */
  overlays(show: { band?: boolean; eye?: boolean; meshes?: boolean }): void {
    this.dirty = true;
    if (this.band && show.band !== undefined) this.band.visible = show.band;
    if (this.eye && show.eye !== undefined) this.eye.visible = show.eye;
    if (show.meshes !== undefined) for (const m of this.meshSolids) m.visible = show.meshes;
  }

  /** Draws the background only (for measuring the floor of a frame's cost), or everything. */
  bare(on: boolean): void {
    this.dirty = true;
    for (const o of this.scene.children) o.visible = !on;
  }

  /** Band points drawn, band points in all, eye trajectory points. */
  counts(): { band_points: number; band_total: number; eye_points: number } {
    const eye = this.eye?.geometry.getAttribute('position').count ?? 0;
    return { band_points: this.bandShown, band_total: this.bandTotal, eye_points: eye };
  }

  /** Colours the solids of the links named (a collision), the others as they are. */
  highlight(names: Set<string>): void {
    const now = new Set<number>();
    this.links.forEach((g, i) => { if (names.has(g.name)) now.add(i); });
    if (now.size === this.highlighted.size && [...now].every((i) => this.highlighted.has(i))) return;
    this.solids.forEach((meshes, i) => {
      for (const m of meshes) {
        const mat = m.material as THREE.MeshStandardMaterial;
        mat.emissive.copy(now.has(i) ? ALARM : new THREE.Color(0, 0, 0));
        mat.emissiveIntensity = now.has(i) ? 0.8 : 1;
      }
    });
    this.highlighted = now;
  }

  /** The names of the links highlighted. */
  highlightedLinks(): string[] {
    return [...this.highlighted].map((i) => this.links[i].name);
  }

  /** Shows or hides the payout point's marker (hidden where nothing places it). */
  showPayout(visible: boolean): void {
    this.payout.visible = visible;
    this.dirty = true;
  }

  /** Places every link and the payout point as `s` says. */
  show(s: Sample): void {
    this.dirty = true;
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
      // Only the point written goes to the GPU, not the whole trail.
      const attr = this.trail.geometry.attributes.position as THREE.BufferAttribute;
      attr.clearUpdateRanges();
      attr.addUpdateRange(3 * n, 3);
      attr.needsUpdate = true;
    }
  }

  /** Forgets the payout point's trail (after a jump). */
  clearTrail(): void {
    this.trailCount = 0;
    this.trail.geometry.setDrawRange(0, 0);
  }

  render(): void {
    this.dirty = false;
    if (this.follow) {
      // Camera and target move with the payout point: it stays centred.
      const d = this.payout.position.clone().sub(this.controls.target);
      this.camera.position.add(d);
      this.controls.target.add(d);
    }
    this.controls.update();
    this.renderer.render(this.scene, this.camera);
  }

  /**
   * Looks from `view` (front, top, along the mandrel's axis) at the machine
   * and the mandrel, framed to fill the picture: the moving links' solids,
   * the mandrel and the band (the base's bed only where nothing else is).
   */
  look(view: View): void {
    this.dirty = true;
    const box = this.frame();
    const centre = box.getCenter(new THREE.Vector3());
    const mandrel = this.scene.getObjectByName('mandrel');
    let dir = new THREE.Vector3(0, -1, 0.35);
    // From straight above, a hair to the front: the orbit keeps z up.
    if (view === 'top') dir = new THREE.Vector3(0, -0.001, 1);
    else if (view === 'axis' && mandrel) {
      // From the mandrel's far end (+z of its link), away from the spindle's drive.
      dir = new THREE.Vector3(0, 0, 1).applyQuaternion(mandrel.getWorldQuaternion(new THREE.Quaternion()));
      new THREE.Box3().setFromObject(mandrel).getCenter(centre);
    }
    dir.normalize();
    this.follow = false;
    this.controls.target.copy(centre);
    this.camera.position.copy(centre).addScaledVector(dir, 1);
    this.camera.lookAt(centre);
    this.camera.updateMatrixWorld();
    // The distance at which every corner of the box lies within the view.
    const inv = this.camera.matrixWorldInverse;
    const tanV = Math.tan(THREE.MathUtils.degToRad(this.camera.fov / 2));
    const tanH = tanV * this.camera.aspect;
    let dist = 0;
    for (const x of [box.min.x, box.max.x]) {
      for (const y of [box.min.y, box.max.y]) {
        for (const z of [box.min.z, box.max.z]) {
          const c = new THREE.Vector3(x, y, z).applyMatrix4(inv);
          // Camera at the centre + dir: depth -c.z from there; move back until it fits.
          const depth = -c.z - 1;
          dist = Math.max(dist, Math.abs(c.x) / tanH - depth, Math.abs(c.y) / tanV - depth);
        }
      }
    }
    this.camera.position.copy(centre).addScaledVector(dir, Math.max(dist * 1.08, 50));
    this.camera.lookAt(centre);
    this.controls.update();
  }

  /** What the views frame: the moving links' solids, the mandrel and the band. */
  private frame(): THREE.Box3 {
    const box = new THREE.Box3();
    this.scene.updateMatrixWorld(true);
    this.links.forEach((g, i) => {
      if (i === 0) return;
      for (const child of g.children) {
        if (child.name === 'band' && this.band) {
          // The whole band, laid or not.
          this.band.geometry.computeBoundingBox();
          const b = this.band.geometry.boundingBox;
          if (b) box.union(b.clone().applyMatrix4(g.matrixWorld));
        } else if (child.name !== 'path') box.expandByObject(child);
      }
    });
    if (box.isEmpty()) box.setFromObject(this.scene);
    return box;
  }

  /** Turns following the payout point on or off (centring it now). */
  setFollow(on: boolean): void {
    this.dirty = true;
    this.follow = on;
    if (on) {
      const d = this.payout.position.clone().sub(this.controls.target);
      this.camera.position.add(d);
      this.controls.target.add(d);
      this.controls.update();
    }
  }

  /** The camera's position and target, world mm. */
  view(): { camera: number[]; target: number[] } {
    return { camera: this.camera.position.toArray(), target: this.controls.target.toArray() };
  }

  /** Where the payout point is drawn, in pixels from the canvas's centre. */
  payoutOffset(): [number, number] {
    const p = this.payout.position.clone().project(this.camera);
    const c = this.renderer.domElement;
    return [(p.x * c.clientWidth) / 2, (-p.y * c.clientHeight) / 2];
  }

  private resize(): void {
    const w = Math.max(this.host.clientWidth, 1);
    const h = Math.max(this.host.clientHeight, 1);
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.dirty = true;
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
    case 'mesh':
      // Empty until its triangles arrive (`Scene.loadMeshes`).
      geo = new THREE.BufferGeometry();
      break;
  }
  // A mesh file's triangles may face either way: both sides drawn.
  const side = s.shape === 'mesh' ? THREE.DoubleSide : THREE.FrontSide;
  const m = new THREE.Mesh(geo, new THREE.MeshStandardMaterial({ color: s.color, roughness: 0.7, side }));
  const o = s.origin;
  m.position.set(o[0], o[1], o[2]);
  m.quaternion.set(o[3], o[4], o[5], o[6]);
  return m;
}

/**
 * The points of the polyline `pts` (z, r) to draw it within `tol` mm
 * (Douglas–Peucker): the ends always, and the point farthest from each
 * chord while it is farther than `tol`.
 */
export function simplified(pts: [number, number][], tol: number): [number, number][] {
  if (pts.length <= 2) return pts;
  const keep = new Uint8Array(pts.length);
  keep[0] = 1;
  keep[pts.length - 1] = 1;
  const stack: [number, number][] = [[0, pts.length - 1]];
  while (stack.length > 0) {
    const [a, b] = stack.pop() as [number, number];
    const [az, ar] = pts[a];
    const dz = pts[b][0] - az;
    const dr = pts[b][1] - ar;
    const len = Math.hypot(dz, dr);
    let far = -1;
    let worst = tol;
    for (let i = a + 1; i < b; i++) {
      const ez = pts[i][0] - az;
      const er = pts[i][1] - ar;
      const d = len > 0 ? Math.abs(ez * dr - er * dz) / len : Math.hypot(ez, er);
      if (d > worst) {
        worst = d;
        far = i;
      }
    }
    if (far >= 0) {
      keep[far] = 1;
      stack.push([a, far], [far, b]);
    }
  }
  return pts.filter((_, i) => keep[i] === 1);
}
