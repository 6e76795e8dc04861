// A 2-D drawing in millimetres on a canvas: fitted to its contents, the
// wheel zooms about the pointer, a drag pans, a grid with labelled lines.
// The dressing and correction views draw into it.

export interface Bounds { x0: number; x1: number; y0: number; y1: number }

/** Draws with `ctx` in world coordinates through `px`/`py`. */
export type Painter = (v: View2d, ctx: CanvasRenderingContext2D) => void;

export class View2d {
  readonly canvas: HTMLCanvasElement;
  private readonly ctx: CanvasRenderingContext2D;
  /** Pixels per mm. */
  private scale = 1;
  /** The world point at the canvas's centre. */
  private cx = 0;
  private cy = 0;
  private bounds: Bounds = { x0: -1, x1: 1, y0: -1, y1: 1 };

  constructor(
    host: HTMLElement,
    private readonly paint: Painter,
    private readonly labels: [string, string],
  ) {
    this.canvas = document.createElement('canvas');
    this.canvas.className = 'view2d';
    host.appendChild(this.canvas);
    const ctx = this.canvas.getContext('2d');
    if (!ctx) throw new Error('no 2-D canvas');
    this.ctx = ctx;
    this.canvas.addEventListener('wheel', (e) => {
      e.preventDefault();
      const r = this.canvas.getBoundingClientRect();
      const [wx, wy] = this.world(e.clientX - r.left, e.clientY - r.top);
      const f = Math.exp(-e.deltaY * 0.0015);
      this.scale *= f;
      // Keep the world point under the pointer where it is.
      this.cx = wx - (wx - this.cx) / f;
      this.cy = wy - (wy - this.cy) / f;
      this.draw();
    }, { passive: false });
    let drag: [number, number] | null = null;
    this.canvas.addEventListener('pointerdown', (e) => {
      drag = [e.clientX, e.clientY];
      this.canvas.setPointerCapture(e.pointerId);
    });
    this.canvas.addEventListener('pointermove', (e) => {
      if (!drag) return;
      this.cx -= (e.clientX - drag[0]) / this.scale;
      this.cy += (e.clientY - drag[1]) / this.scale;
      drag = [e.clientX, e.clientY];
      this.draw();
    });
    this.canvas.addEventListener('pointerup', () => { drag = null; });
    this.canvas.addEventListener('dblclick', () => this.reset());
    new ResizeObserver(() => this.draw()).observe(host);
  }

  /** Back to the bounds last fitted (undoes zoom and pan). */
  reset(): void {
    this.fit(this.bounds);
  }

  /** The world rectangle in sight, mm. */
  visible(): Bounds {
    const { w, h } = this.size();
    const [x0, y1] = this.world(0, 0);
    const [x1, y0] = this.world(w, h);
    return { x0, x1, y0, y1 };
  }

  /** Shows `b` whole, with a margin. */
  fit(b: Bounds): void {
    this.bounds = b;
    const { w, h } = this.size();
    const dx = Math.max(b.x1 - b.x0, 1e-9);
    const dy = Math.max(b.y1 - b.y0, 1e-9);
    this.scale = 0.9 * Math.min(w / dx, h / dy);
    this.cx = (b.x0 + b.x1) / 2;
    this.cy = (b.y0 + b.y1) / 2;
    this.draw();
  }

  private size(): { w: number; h: number } {
    return { w: Math.max(this.canvas.clientWidth, 100), h: Math.max(this.canvas.clientHeight, 100) };
  }

  /** Canvas x (CSS pixels) of world `x`. */
  px(x: number): number { return this.size().w / 2 + (x - this.cx) * this.scale; }
  /** Canvas y (CSS pixels) of world `y` (up). */
  py(y: number): number { return this.size().h / 2 - (y - this.cy) * this.scale; }
  /** Pixels per mm. */
  get pixelsPerMm(): number { return this.scale; }

  private world(sx: number, sy: number): [number, number] {
    const { w, h } = this.size();
    return [this.cx + (sx - w / 2) / this.scale, this.cy - (sy - h / 2) / this.scale];
  }

  /** A polyline through `pts` ([x, y] in mm). */
  line(ctx: CanvasRenderingContext2D, pts: ArrayLike<number[]>, colour: string, width = 1.5): void {
    if (pts.length < 2) return;
    ctx.strokeStyle = colour;
    ctx.lineWidth = width;
    ctx.beginPath();
    ctx.moveTo(this.px(pts[0][0]), this.py(pts[0][1]));
    for (let i = 1; i < pts.length; i++) ctx.lineTo(this.px(pts[i][0]), this.py(pts[i][1]));
    ctx.stroke();
  }

  /** Redraws: the grid, then the painter's drawing. */
  draw(): void {
    const dpr = window.devicePixelRatio || 1;
    const { w, h } = this.size();
    if (this.canvas.width !== Math.round(w * dpr) || this.canvas.height !== Math.round(h * dpr)) {
      this.canvas.width = Math.round(w * dpr);
      this.canvas.height = Math.round(h * dpr);
    }
    const ctx = this.ctx;
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    ctx.fillStyle = '#ffffff';
    ctx.fillRect(0, 0, w, h);
    this.grid(ctx, w, h);
    this.paint(this, ctx);
  }

  private grid(ctx: CanvasRenderingContext2D, w: number, h: number): void {
    const [x0, y1] = this.world(0, 0);
    const [x1, y0] = this.world(w, h);
    const step = niceStep(80 / this.scale);
    ctx.font = '11px system-ui, sans-serif';
    ctx.lineWidth = 1;
    ctx.fillStyle = '#778';
    for (let x = Math.ceil(x0 / step) * step; x <= x1; x += step) {
      const sx = Math.round(this.px(x)) + 0.5;
      ctx.strokeStyle = Math.abs(x) < step / 2 ? '#b8bcc8' : '#eceef2';
      ctx.beginPath(); ctx.moveTo(sx, 0); ctx.lineTo(sx, h); ctx.stroke();
      ctx.fillText(label(x, step), sx + 2, h - 4);
    }
    for (let y = Math.ceil(y0 / step) * step; y <= y1; y += step) {
      const sy = Math.round(this.py(y)) + 0.5;
      ctx.strokeStyle = Math.abs(y) < step / 2 ? '#b8bcc8' : '#eceef2';
      ctx.beginPath(); ctx.moveTo(0, sy); ctx.lineTo(w, sy); ctx.stroke();
      // Not under the axis's name in the top corner.
      if (sy > 26) ctx.fillText(label(y, step), 2, sy - 2);
    }
    ctx.fillStyle = '#445';
    ctx.fillText(`${this.labels[0]} →`, w - 70, h - 18);
    ctx.fillText(`↑ ${this.labels[1]}`, 6, 14);
  }
}

/** 1, 2 or 5 times a power of ten, at least `raw`. */
export function niceStep(raw: number): number {
  const p = 10 ** Math.floor(Math.log10(Math.max(raw, 1e-12)));
  for (const m of [1, 2, 5, 10]) if (m * p >= raw) return m * p;
  return 10 * p;
}

function label(v: number, step: number): string {
  const d = Math.max(0, -Math.floor(Math.log10(step)));
  return (Math.abs(v) < step / 1e6 ? 0 : v).toFixed(d);
}

/** The bounds of every point of `sets`. */
export function boundsOf(sets: ArrayLike<number[]>[]): Bounds {
  const b = { x0: Infinity, x1: -Infinity, y0: Infinity, y1: -Infinity };
  for (const s of sets) {
    for (let i = 0; i < s.length; i++) {
      const [x, y] = s[i];
      b.x0 = Math.min(b.x0, x); b.x1 = Math.max(b.x1, x);
      b.y0 = Math.min(b.y0, y); b.y1 = Math.max(b.y1, y);
    }
  }
  return Number.isFinite(b.x0) ? b : { x0: -1, x1: 1, y0: -1, y1: 1 };
}

/** `s` with the characters HTML gives meaning to escaped. */
export function esc(s: string): string {
  return s.replace(/[&<>"']/g, (c) => `&#${c.charCodeAt(0)};`);
}
