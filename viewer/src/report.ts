// A report (`formcam report OUT -o report.html`): the page with its data
// inlined, opened from a file with no server. Every answer the page would
// fetch is a `<script type="application/json" data-formcam-url=...>`
// element; what the page asks with a free parameter it computes here from
// inlined tables, as the server does (crates/formcam-view/src/report.rs):
// `/api/sample?t=T` (the axes, block, line and band laid exactly; the poses
// and key points interpolated between knots within the tolerance the
// report states) and `/api/dressing/sample?t=T` (exact: linear per block).
import type { SampleTables } from './generated';

/** Whether this page is a report (its answers inlined). */
export function isReport(): boolean {
  return document.querySelector('script[data-formcam-url]') !== null;
}

let entries: Map<string, HTMLElement> | null = null;

function entry(url: string): HTMLElement | undefined {
  if (!entries) {
    entries = new Map();
    for (const e of document.querySelectorAll<HTMLElement>('script[data-formcam-url]')) {
      entries.set(e.dataset.formcamUrl ?? '', e);
    }
  }
  return entries.get(url);
}

/** An inlined answer's body as the server sent it. */
function body(e: HTMLElement): BodyInit {
  const raw = e.textContent ?? '';
  switch (e.dataset.encoding) {
    case 'json': return raw;
    case 'text': return JSON.parse(raw) as string;
    default: return bytes(JSON.parse(raw) as string);
  }
}

function bytes(b64: string): Uint8Array<ArrayBuffer> {
  const s = atob(b64);
  const out = new Uint8Array(s.length);
  for (let i = 0; i < s.length; i++) out[i] = s.charCodeAt(i);
  return out;
}

function floats(b64: string): Float64Array {
  return new Float64Array(bytes(b64).buffer);
}

function reply(status: number, type: string, content: BodyInit): Response {
  return new Response(content, { status, headers: { 'content-type': type } });
}

function jsonReply(value: unknown): Response {
  return reply(200, 'application/json', JSON.stringify(value));
}

function inlinedJson<T>(url: string): T {
  const e = entry(url);
  if (!e) throw new Error(`${url}: not in this report`);
  return JSON.parse(String(body(e))) as T;
}

/** The answer to `url` from the data inlined in the report. */
export async function answer(url: string): Promise<Response> {
  const e = entry(url);
  if (e) return reply(Number(e.dataset.status ?? 200), e.dataset.contentType ?? '', body(e));
  const u = new URL(url, 'http://report.invalid/');
  const t = Number(u.searchParams.get('t'));
  switch (u.pathname) {
    // The head inlined, the samples computed as `/api/sample` is.
    case '/api/timeline': {
      const asked = u.searchParams.get('samples');
      const n = Math.min(Math.max(asked === null ? 2000 : Math.floor(Number(asked)), 2), 100000);
      if (!Number.isFinite(n)) break;
      return jsonReply(winding().timeline(n));
    }
    case '/api/sample': return jsonReply(winding().at(t));
    case '/api/dressing/sample': return jsonReply(dresserAt(t));
  }
  return reply(404, 'text/plain', `${url}: not in this report\n`);
}

/** The first index in the sorted `a[from..n]` where `pred` fails. */
function partition(a: ArrayLike<number>, n: number, pred: (x: number) => boolean, from = 0): number {
  let lo = from;
  let hi = n;
  while (lo < hi) {
    const mid = (lo + hi) >> 1;
    if (pred(a[mid])) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

/** A winding result's state at any time, from the inlined tables. */
class WindingSamples {
  private starts: Float64Array;
  private values: Float64Array;
  private width: number;
  private ends: number[];
  private lines: number[];
  private kt: Float64Array;
  private kv: Float64Array;
  private first: number[];
  private columns: number[];
  private head: Record<string, unknown>;
  private links: number;
  private points: number;
  private band: SampleTables['band'];

  constructor() {
    const s = inlinedJson<SampleTables>('report:samples');
    const b = inlinedJson<{ ends: number[]; lines: number[] }>('/api/blocks');
    this.starts = floats(s.axes.starts);
    this.values = floats(s.axes.values);
    this.width = s.axes.width;
    this.ends = b.ends;
    this.lines = b.lines;
    this.kt = floats(s.knots.t);
    this.kv = floats(s.knots.values);
    this.first = s.knots.first;
    this.columns = s.knots.columns;
    this.head = inlinedJson<Record<string, unknown>>('/api/timeline?samples=2');
    this.links = s.knots.links;
    this.points = s.knots.points;
    this.band = s.band;
  }

  /** The sample at `t` s, as `/api/sample?t=T` answers. */
  at(time: number): Record<string, unknown> {
    const n = this.starts.length - 1;
    const duration = this.starts[n];
    const t = Number.isFinite(time) ? Math.min(Math.max(time, 0), duration) : 0;
    // The block shown: the first ending at or after `t`.
    const block = Math.min(partition(this.ends, this.ends.length, (e) => e < t), this.ends.length - 1);
    // The axes: linear within the last block starting at or before `t`.
    const i = Math.max(partition(this.starts, n, (s) => s <= t) - 1, 0);
    const [s, e] = [this.starts[i], this.starts[i + 1]];
    const f = t <= s ? 0 : t >= e ? 1 : (t - s) / (e - s);
    const w = this.width;
    const axes: number[] = [];
    for (let j = 0; j < w; j++) {
      const p = this.values[i * w + j];
      const q = this.values[(i + 1) * w + j];
      axes.push(p + f * (q - p));
    }
    const row = this.row(t);
    const poses: number[][] = [];
    for (let l = 0; l < this.links; l++) poses.push(row.slice(7 * l, 7 * l + 7));
    const points: number[][] = [];
    for (let p = 0; p < this.points; p++) {
      const k = 7 * this.links + 3 * p;
      points.push(row.slice(k, k + 3));
    }
    const out: Record<string, unknown> = { t, block, line: this.lines[block] ?? 0, axes, poses, points };
    if (this.band) out.laid = this.laid(axes);
    return out;
  }

  /** `/api/timeline?samples=n`: the head, and `n` samples at equal steps. */
  timeline(n: number): Record<string, unknown> {
    const d = this.starts[this.starts.length - 1];
    const samples = [];
    for (let i = 0; i < n; i++) samples.push(this.at((d * i) / (n - 1)));
    return { ...this.head, samples };
  }

  /** Knot `k`'s whole row: the first row with its changing columns. */
  private knot(k: number): number[] {
    const row = this.first.slice();
    const w = this.columns.length;
    this.columns.forEach((c, j) => { row[c] = this.kv[k * w + j]; });
    return row;
  }

  /** Poses and key points at `t`: between the knots around it. */
  private row(t: number): number[] {
    const count = this.kt.length;
    const k = Math.max(partition(this.kt, count, (x) => x <= t) - 1, 0);
    const a = this.knot(k);
    if (k + 1 >= count || this.kt[k + 1] <= this.kt[k]) return a;
    const b = this.knot(k + 1);
    const f = (t - this.kt[k]) / (this.kt[k + 1] - this.kt[k]);
    const out = a.map((x, j) => x + f * (b[j] - x));
    for (let l = 0; l < this.links; l++) {
      const q = slerp(a.slice(7 * l + 3, 7 * l + 7), b.slice(7 * l + 3, 7 * l + 7), f);
      out.splice(7 * l + 3, 4, ...q);
    }
    return out;
  }

  /** Band points laid with the axes at `axes` (the server's `Band::laid`). */
  private laid(axes: number[]): number {
    const band = this.band;
    if (!band || band.spindle >= axes.length) return 0;
    const a = axes[band.spindle];
    let laid = 0;
    for (const [from, to, direction] of band.spans) {
      const end = partition(band.keys, to, (k) => k <= a * direction + band.slack_deg, from);
      laid = end;
      if (end < to) break;
    }
    return laid;
  }
}

/** Spherical interpolation of unit quaternions [x, y, z, w] along the
 * shorter arc (the formula of report.rs). */
function slerp(a: number[], b0: number[], f: number): number[] {
  let dot = a[0] * b0[0] + a[1] * b0[1] + a[2] * b0[2] + a[3] * b0[3];
  let b = b0;
  if (dot < 0) {
    dot = -dot;
    b = b0.map((x) => -x);
  }
  let wa = 1 - f;
  let wb = f;
  if (dot <= 0.999999999) {
    const th = Math.acos(Math.min(dot, 1));
    const s = Math.sin(th);
    wa = Math.sin((1 - f) * th) / s;
    wb = Math.sin(f * th) / s;
  }
  const q = a.map((x, j) => wa * x + wb * b[j]);
  const norm = Math.hypot(...q);
  return q.map((x) => x / norm);
}

let windingSamples: WindingSamples | null = null;

function winding(): WindingSamples {
  windingSamples ??= new WindingSamples();
  return windingSamples;
}

/** `/api/dressing`'s timing: each block's start then the end, point A `[z, x]` at each. */
interface DressingTiming { t: number[]; points: [number, number][]; lines: number[] }

let dressing: DressingTiming | null = null;

/** The dresser at `t` s, as `/api/dressing/sample?t=T` answers. */
function dresserAt(time: number): Record<string, unknown> {
  dressing ??= inlinedJson<DressingTiming>('/api/dressing');
  const d = dressing;
  const n = d.lines.length;
  const duration = d.t[n];
  const t = Number.isFinite(time) ? Math.min(Math.max(time, 0), duration) : 0;
  const i = Math.max(partition(d.t, n, (s) => s <= t) - 1, 0);
  const [s, e] = [d.t[i], d.t[i + 1]];
  const f = t <= s ? 0 : t >= e ? 1 : (t - s) / (e - s);
  const [z0, x0] = d.points[i];
  const [z1, x1] = d.points[i + 1];
  return { t, block: i, line: d.lines[i] ?? 0, dresser: [x0 + f * (x1 - x0), z0 + f * (z1 - z0)] };
}
