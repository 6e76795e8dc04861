// A correction's deviation on the nominal surface in 3-D: the mesh the
// server sent (the measured sections' grid, two triangles per facet)
// coloured per vertex by the deviation, the measured sections as lines
// with their points as dots, and the program's nodes marked by what the
// correction did with them (moved, extrapolated, outside, unknown). An
// orbit camera (drag turns, wheel zooms, right drag pans, double-click
// fits); a frame is drawn only when something changed.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import type { NodeMarks, Placement, SurfaceMesh } from './api';

/** The measured points and their sections. */
export interface MeasuredPoints {
  x: number[];
  y: number[];
  z: number[];
  section: number[];
}

/** The node markers' kinds in the legend's order, with their colours. */
export const NODE_KINDS: { kind: Placement; label: string; colour: string }[] = [
  { kind: 'inside', label: 'moved (inside)', colour: '#2ca02c' },
  { kind: 'extrapolated', label: 'extrapolated (within the margin)', colour: '#ff7f0e' },
  { kind: 'outside', label: 'left outside', colour: '#d62728' },
  { kind: 'unknown', label: 'unknown coordinate, left', colour: '#9467bd' },
];

/** The 3-D view's background. */
export const BACKGROUND = '#dfe4ea';

export class DeviationSurface {
  readonly renderer: THREE.WebGLRenderer;
  private readonly scene = new THREE.Scene();
  private readonly camera: THREE.PerspectiveCamera;
  private readonly controls: OrbitControls;
  private readonly mesh: THREE.Mesh;
  private readonly dots: THREE.Points;
  private readonly nodes: THREE.Points | null = null;
  private readonly centre = new THREE.Vector3();
  private readonly radius: number;
  private dirty = true;
  /** Markers drawn per legend kind. */
  readonly markers: Record<string, number> = {};

  constructor(
    private readonly host: HTMLElement,
    surface: SurfaceMesh,
    points: MeasuredPoints,
    nodes: NodeMarks | null,
  ) {
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
    host.appendChild(this.renderer.domElement);
    this.scene.background = new THREE.Color(BACKGROUND);
    this.scene.add(new THREE.HemisphereLight('#ffffff', '#9aa0a8', 2.2));
    const sun = new THREE.DirectionalLight('#ffffff', 0.9);
    sun.position.set(-1, -2, 4);
    this.scene.add(sun);

    // The surface, coloured per vertex, pushed back a little so the lines
    // and dots on it stay in front.
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.Float32BufferAttribute(surface.vertices.flat(), 3));
    g.setAttribute('color', new THREE.Float32BufferAttribute(new Float32Array(3 * surface.vertices.length), 3));
    g.setIndex(surface.triangles.flat());
    g.computeVertexNormals();
    g.computeBoundingSphere();
    this.mesh = new THREE.Mesh(g, new THREE.MeshLambertMaterial({
      vertexColors: true, side: THREE.DoubleSide, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
    }));
    this.scene.add(this.mesh);
    const sphere = g.boundingSphere ?? new THREE.Sphere(new THREE.Vector3(), 1);
    this.centre.copy(sphere.center);
    this.radius = Math.max(sphere.radius, 1e-3);

    // The measured sections: a line through each one's points, the points as dots.
    const bySection = new Map<number, number[]>();
    points.section.forEach((s, i) => { const l = bySection.get(s) ?? []; l.push(i); bySection.set(s, l); });
    const lineMat = new THREE.LineBasicMaterial({ color: '#3a4250' });
    for (const idx of bySection.values()) {
      const lg = new THREE.BufferGeometry().setFromPoints(idx.map((i) => new THREE.Vector3(points.x[i], points.y[i], points.z[i])));
      this.scene.add(new THREE.Line(lg, lineMat));
    }
    const dg = new THREE.BufferGeometry();
    dg.setAttribute('position', new THREE.Float32BufferAttribute(points.x.flatMap((x, i) => [x, points.y[i], points.z[i]]), 3));
    this.dots = new THREE.Points(dg, new THREE.PointsMaterial({ color: '#1d2330', size: 5, sizeAttenuation: false }));
    this.scene.add(this.dots);

    // The program's nodes, coloured by what happened to them.
    if (nodes && nodes.x.length > 0) {
      const colours: number[] = [];
      const pos: number[] = [];
      const c = new THREE.Color();
      for (let k = 0; k < nodes.x.length; k++) {
        const kind = nodes.placement[k];
        this.markers[kind] = (this.markers[kind] ?? 0) + 1;
        c.set(NODE_KINDS.find((n) => n.kind === kind)?.colour ?? '#000000');
        colours.push(c.r, c.g, c.b);
        pos.push(nodes.x[k], nodes.y[k], nodes.z[k]);
      }
      const ng = new THREE.BufferGeometry();
      ng.setAttribute('position', new THREE.Float32BufferAttribute(pos, 3));
      ng.setAttribute('color', new THREE.Float32BufferAttribute(colours, 3));
      this.nodes = new THREE.Points(ng, new THREE.PointsMaterial({ vertexColors: true, size: 2, sizeAttenuation: false }));
      this.scene.add(this.nodes);
    }

    this.camera = new THREE.PerspectiveCamera(35, 1, this.radius / 100, this.radius * 100);
    this.camera.up.set(0, 0, 1);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.addEventListener('change', () => { this.dirty = true; });
    this.renderer.domElement.addEventListener('dblclick', () => this.fit());
    this.fit();
    this.resize();
    new ResizeObserver(() => this.resize()).observe(host);
    const loop = () => {
      if (this.dirty) this.render();
      requestAnimationFrame(loop);
    };
    requestAnimationFrame(loop);
  }

  /** The whole surface in sight, seen from the front left and above. */
  fit(): void {
    // The bounding sphere's silhouette is wider than the surface seen from
    // above at a slant: come a little nearer than the sphere needs.
    const d = (0.8 * this.radius) / Math.sin((this.camera.fov * Math.PI) / 360);
    this.camera.position.copy(this.centre).add(new THREE.Vector3(-0.45, -0.75, 0.55).normalize().multiplyScalar(d));
    this.controls.target.copy(this.centre);
    this.controls.update();
    this.dirty = true;
  }

  /** Colours the surface by `vertexRgb` (0..1 per channel, sRGB). */
  colour(vertexRgb: [number, number, number][]): void {
    const attr = this.mesh.geometry.getAttribute('color') as THREE.BufferAttribute;
    const c = new THREE.Color();
    vertexRgb.forEach(([r, g, b], i) => {
      c.setRGB(r, g, b, THREE.SRGBColorSpace);
      attr.setXYZ(i, c.r, c.g, c.b);
    });
    attr.needsUpdate = true;
    this.dirty = true;
  }

  /** Shows or hides the node markers. */
  showNodes(on: boolean): void {
    if (this.nodes) this.nodes.visible = on;
    this.dirty = true;
  }

  /** Draws a frame now. */
  render(): void {
    this.dirty = false;
    this.renderer.render(this.scene, this.camera);
  }

  /** The surface's centre on the canvas, in the canvas's pixels. */
  centrePixel(): [number, number] {
    const p = this.centre.clone().project(this.camera);
    const c = this.renderer.domElement;
    return [Math.round(((p.x + 1) / 2) * c.width), Math.round(((1 - p.y) / 2) * c.height)];
  }

  /** The vertices, triangles and dots drawn. */
  counts(): { vertices: number; triangles: number; dots: number } {
    const g = this.mesh.geometry;
    return {
      vertices: g.getAttribute('position').count,
      triangles: (g.getIndex()?.count ?? 0) / 3,
      dots: this.dots.geometry.getAttribute('position').count,
    };
  }

  private resize(): void {
    const w = Math.max(1, this.host.clientWidth);
    const h = Math.max(1, this.host.clientHeight);
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.dirty = true;
  }
}
