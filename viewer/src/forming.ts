// The wheel's contour as cut so far, on a grid of Z: within pass k, the
// contour before it (the server's contour after pass k - 1, or the initial
// one) lowered to the lower envelope of the dressing corner's disc swept
// along the blocks run so far, never below the server's contour after pass
// k (formcam-dress's exact simulation, which the dresser's whole periphery
// cuts); once a pass's last feed move is done, that contour itself.

/** A polyline of `[z, x]` with `z` non-decreasing. */
export type Polyline = number[][];

/** What the swept discs need of `/api/dressing`. */
export interface FormingInput {
  initial: Polyline;
  /** The contour after each pass (may be empty: then computed here). */
  contours: Polyline[];
  /** Each block's start, then the end, s. */
  t: number[];
  /** Point A at the start and at each block's end: `[z, x]`. */
  points: number[][];
  /** Each block's pass (1-based, 0 before the first). */
  block_pass: number[];
  /** Per pass (1-based numbers), the corner's centre relative to point A and its radius. */
  passes: { pass: number; corner_offset: [number, number]; corner_radius: number }[];
}

/** Grid points across the contour's width. */
const GRID = 3000;

/** `c` at each of `zs` (ascending): linear between vertices, the end values beyond. */
export function sampleAt(c: Polyline, zs: Float64Array): Float64Array {
  const out = new Float64Array(zs.length);
  let j = 0;
  for (let i = 0; i < zs.length; i++) {
    const z = zs[i];
    while (j + 1 < c.length - 1 && c[j + 1][0] <= z) j++;
    if (c.length === 0) out[i] = 0;
    else if (c.length === 1 || z <= c[0][0]) out[i] = c[0][1];
    else if (z >= c[c.length - 1][0]) out[i] = c[c.length - 1][1];
    else {
      const [z0, x0] = c[j];
      const [z1, x1] = c[j + 1];
      out[i] = z1 > z0 ? x0 + ((z - z0) / (z1 - z0)) * (x1 - x0) : x1;
    }
  }
  return out;
}

export class CutSoFar {
  /** The grid's Z, ascending, mm. */
  readonly z: Float64Array;
  /** The contour before dressing on the grid. */
  readonly initial: Float64Array;
  /** The contour as cut at the time last asked. */
  readonly current: Float64Array;
  private readonly dz: number;
  /** The server's contour after each pass on the grid (index pass - 1). */
  private readonly after: Float64Array[];
  /** Contours after each pass computed here when the server sent none. */
  private readonly computed = new Map<number, Float64Array>();
  /** The swept discs' lower envelope within the pass `envPass`, blocks
   * before `envBlock` whole, up to the time `envT`. */
  private readonly env: Float64Array;
  private envPass = -1;
  private envBlock = 0;
  private envT = -Infinity;
  /** Per pass (1-based): its first block and the end of its last feed move. */
  private readonly first = new Map<number, number>();
  private readonly end = new Map<number, number>();

  constructor(private readonly d: FormingInput) {
    const zs = d.initial.map((p) => p[0]);
    const z0 = Math.min(...zs);
    const z1 = Math.max(...zs);
    this.dz = (z1 - z0) / (GRID - 1);
    this.z = new Float64Array(GRID);
    for (let i = 0; i < GRID; i++) this.z[i] = z0 + i * this.dz;
    this.initial = sampleAt(d.initial, this.z);
    this.after = d.contours.map((c) => sampleAt(c, this.z));
    this.current = this.initial.slice();
    this.env = new Float64Array(GRID);
    const blocks = d.block_pass.length;
    for (let b = 0; b < blocks; b++) {
      const p = d.block_pass[b];
      if (!this.first.has(p)) this.first.set(p, b);
      if (d.t[b + 1] > d.t[b]) this.end.set(p, d.t[b + 1]);
    }
  }

  /** The number of passes. */
  get passes(): number {
    return this.end.size;
  }

  /** The contour at `t` s, with the running block `block`, into `current`. */
  at(t: number, block: number): Float64Array {
    const p = this.d.block_pass[block] ?? 0;
    if (p === 0) {
      this.current.set(this.initial);
      return this.current;
    }
    // Both contours first: computing one (no contours sent) sweeps a pass.
    const before = p > 1 ? this.afterPass(p - 1) ?? this.initial : this.initial;
    const done = this.afterPass(p);
    if (t >= (this.end.get(p) ?? Infinity)) {
      this.current.set(done ?? this.initial);
      return this.current;
    }
    this.sweep(p, block, t);
    for (let i = 0; i < GRID; i++) {
      const cut = Math.min(before[i], this.env[i]);
      this.current[i] = done ? Math.max(done[i], cut) : cut;
    }
    return this.current;
  }

  /** The area between the contour before dressing and `current`, mm². */
  removed(): number {
    let a = 0;
    for (let i = 1; i < GRID; i++) {
      a += 0.5 * this.dz * (this.initial[i - 1] - this.current[i - 1] + this.initial[i] - this.current[i]);
    }
    return a;
  }

  /** The contour after pass `p`: the server's, else computed by sweeping its blocks. */
  private afterPass(p: number): Float64Array | undefined {
    const sent = this.after[p - 1];
    if (sent) return sent;
    if (this.d.contours.length > 0 || p < 1 || !this.first.has(p)) return undefined;
    let c = this.computed.get(p);
    if (!c) {
      const before = p > 1 ? this.afterPass(p - 1) ?? this.initial : this.initial;
      const last = this.d.block_pass.lastIndexOf(p);
      this.envPass = -1;
      this.sweep(p, last, Infinity);
      c = new Float64Array(GRID);
      for (let i = 0; i < GRID; i++) c[i] = Math.min(before[i], this.env[i]);
      this.computed.set(p, c);
      this.envPass = -1;
    }
    return c;
  }

  /** The envelope of pass `p` swept up to `t` in block `block`: blocks
   * added as time moves on, started again when it moves back. */
  private sweep(p: number, block: number, t: number): void {
    const d = this.d;
    if (p !== this.envPass || t < this.envT || block < this.envBlock) {
      this.env.fill(Infinity);
      this.envPass = p;
      this.envBlock = this.first.get(p) ?? 0;
    }
    this.envT = t;
    const pass = d.passes.find((q) => q.pass === p);
    if (!pass || !(pass.corner_radius > 0)) return;
    const [oz, ox] = pass.corner_offset;
    const r = pass.corner_radius;
    const corner = (q: number[]): [number, number] => [q[0] + oz, q[1] + ox];
    for (; this.envBlock < block; this.envBlock++) {
      const b = this.envBlock;
      if (d.t[b + 1] > d.t[b]) this.stadium(corner(d.points[b]), corner(d.points[b + 1]), r);
    }
    // The running block up to point A now.
    const [s, e] = [d.t[block], d.t[block + 1]];
    if (e > s && t > s) {
      const f = Math.min((t - s) / (e - s), 1);
      const [z0, x0] = d.points[block];
      const [z1, x1] = d.points[block + 1];
      this.stadium(corner(d.points[block]), corner([z0 + f * (z1 - z0), x0 + f * (x1 - x0)]), r);
    }
  }

  /** Lowers the envelope to the lower boundary of the disc of radius `r`
   * moved from `a` to `b` (two end caps and the side line between them). */
  private stadium(a: [number, number], b: [number, number], r: number): void {
    const [ax, ay] = a;
    const [bx, by] = b;
    const len = Math.hypot(bx - ax, by - ay);
    // The side's outward normal, downwards.
    let nx = 0;
    let ny = 0;
    if (len > 0) {
      nx = (by - ay) / len;
      ny = -(bx - ax) / len;
      if (ny > 0) { nx = -nx; ny = -ny; }
    }
    const [sx0, sy0, sx1, sy1] = [ax + r * nx, ay + r * ny, bx + r * nx, by + r * ny];
    const lo = Math.max(0, Math.floor((Math.min(ax, bx) - r - this.z[0]) / this.dz));
    const hi = Math.min(GRID - 1, Math.ceil((Math.max(ax, bx) + r - this.z[0]) / this.dz));
    const r2 = r * r;
    for (let i = lo; i <= hi; i++) {
      const z = this.z[i];
      let y = this.env[i];
      const ua = z - ax;
      if (ua * ua <= r2) y = Math.min(y, ay - Math.sqrt(r2 - ua * ua));
      const ub = z - bx;
      if (ub * ub <= r2) y = Math.min(y, by - Math.sqrt(r2 - ub * ub));
      if (ny < 0 && sx1 !== sx0 && z >= Math.min(sx0, sx1) && z <= Math.max(sx0, sx1)) {
        y = Math.min(y, sy0 + ((z - sx0) * (sy1 - sy0)) / (sx1 - sx0));
      }
      this.env[i] = y;
    }
  }
}
