// The data `formcam view` sends (see crates/formcam-view): the page draws
// these poses and points as they come; it does no kinematics. Every answer
// comes through `answer`: fetched from the server, or in a report
// (`formcam report`) looked up in the data inlined in the page.
import * as report from './report';

/** How a URL's answer is obtained: `fetch` from `formcam view`, or the
 * report's inlined data. Call sites name `/api/...`; fetched relative to
 * the page (`api/...`), so a result shown at `/runs/<name>/` asks its own. */
const answer: (url: string) => Promise<Response> = report.isReport() ? report.answer : (url) => fetch(relative(url));

/** `url` relative to the page: its leading `/` taken off. */
export function relative(url: string): string {
  return url.replace(/^\/+/, '');
}

/** What the page is: `formcam view` (served) or `formcam report` (a file). */
export const PAGE_NAME = report.isReport() ? 'formcam report' : 'formcam view';

/** An axis of the timeline. */
export interface AxisHead { name: string; unit: 'deg' | 'mm' }

/** The state at one time, computed by the server. */
export interface Sample {
  t: number;
  block: number;
  line: number;
  /** Degrees for rotary axes, mm for linear ones (the machine's order). */
  axes: number[];
  /** Every link's world pose: [x, y, z, qx, qy, qz, qw]. */
  poses: number[][];
  /** Every key point's world position, mm. */
  points: number[][];
  /** Points of `/api/band` laid at this time (absent without a band). */
  laid?: number;
}

/** `/api/timeline`. */
export interface TimelineBody {
  duration_s: number;
  blocks: number;
  axes: AxisHead[];
  links: string[];
  points: string[];
  payout: number;
  samples: Sample[];
}

/** A solid in its link's frame. */
export type Solid = { origin: number[]; color: string } & (
  | { shape: 'box'; size: [number, number, number] }
  | { shape: 'cylinder'; radius: number; length: number }
  | { shape: 'sphere'; radius: number }
  | MeshShape
);

/** `/api/machine`. */
export interface MachineScene {
  name: string;
  links: { name: string; parent: number | null; solids: Solid[] }[];
  mandrel: number;
  payout: number;
}

/** `/api/mandrel`: in the mandrel link's frame, z along its axis. */
export interface MandrelScene {
  link: number;
  meridian: [number, number][];
  path: [number, number, number][];
  path_points: number;
}

/** `/api/blocks`. */
export interface Blocks { starts: number[]; ends: number[]; lines: number[] }

/**
 * A violation as the check reports it. Kinds the page does not know (a
 * collision naming `links`, say) are still listed.
 */
export interface Violation {
  kind: string;
  axis?: string;
  links?: string[];
  block?: number;
  line?: number;
  time_s?: number;
  value?: number;
  limit?: number;
  unit?: string;
  count?: number;
  worst_time_s?: number;
  worst_value?: number;
  /** [start, end] s of its first and worst block. */
  spans: [number, number][];
}

/** `/api/violations`. */
export interface Violations {
  source: string;
  /** The checks the view ran (`source` `check`); empty for `check.json`. */
  checks?: string[];
  /** Why the view left a check out, else null. */
  unchecked?: string | null;
  clean: boolean;
  violations: Violation[];
  limits: { axis: string; unit: string; min: number | null; max: number | null }[];
}

/** `/api/eye`: the payout point's path in the world, mm. */
export interface EyeTrajectory { points: [number, number, number][]; times: number[]; ends: number }

/** `/api/band`: the band's path over the whole program, in the mandrel link's frame. */
export interface Band {
  link: number;
  width_mm: number;
  points: [number, number, number][];
  /** Where each layer's points start. */
  layers: number[];
  table_points: number;
}

/** `url` as JSON, or null when the result has none (404). */
export async function optional<T>(url: string): Promise<T | null> {
  const r = await answer(url);
  if (r.status === 404) return null;
  if (!r.ok) throw new Error(`${url}: ${r.status} ${(await r.text()).trim()}`);
  return (await r.json()) as T;
}

async function get(url: string): Promise<Response> {
  const r = await answer(url);
  if (!r.ok) throw new Error(`${url}: ${r.status} ${(await r.text()).trim()}`);
  return r;
}

export async function json<T>(url: string): Promise<T> {
  return (await get(url)).json() as Promise<T>;
}

export async function text(url: string): Promise<string> {
  return (await get(url)).text();
}

/** `/api/mandrel`, or null when the result has no path table. */
export async function mandrel(): Promise<MandrelScene | null> {
  const r = await answer('/api/mandrel');
  return r.ok ? ((await r.json()) as MandrelScene) : null;
}

/**
 * A mesh solid of `/api/machine`: the file the machine names, its
 * triangles at `/api/mesh/N` (`mesh`), or why it could not be read.
 */
export interface MeshShape {
  shape: 'mesh';
  file: string;
  /** N of `/api/mesh/N`; absent when the file could not be read. */
  mesh?: number;
  /** The file's triangles, and those drawn (fewer past the server's cap). */
  triangles: number;
  drawn: number;
  /** Why it is not drawn, naming the file. */
  error?: string;
}

/** `/api/mesh/N`: positions (mm, the visual's frame) and triangles' corners. */
export interface MeshData { positions: Float32Array; indices: Uint32Array }

/**
 * `/api/mesh/N`, little-endian: the vertex and triangle counts (u32), the
 * positions (f32, three per vertex), the corners (u32, three per triangle).
 */
export async function meshData(n: number): Promise<MeshData> {
  const url = `/api/mesh/${n}`;
  const buf = await (await get(url)).arrayBuffer();
  const head = new DataView(buf, 0, Math.min(buf.byteLength, 8));
  const nv = buf.byteLength >= 8 ? head.getUint32(0, true) : 0;
  const nt = buf.byteLength >= 8 ? head.getUint32(4, true) : 0;
  if (buf.byteLength < 8 || buf.byteLength !== 8 + 12 * nv + 12 * nt) {
    throw new Error(`${url}: ${buf.byteLength} bytes, not a mesh of ${nv} vertices and ${nt} triangles`);
  }
  // Copied out: a typed array on the answer's bytes needs the platform's order.
  const positions = new Float32Array(3 * nv);
  const indices = new Uint32Array(3 * nt);
  const v = new DataView(buf);
  for (let k = 0; k < 3 * nv; k++) positions[k] = v.getFloat32(8 + 4 * k, true);
  for (let k = 0; k < 3 * nt; k++) indices[k] = v.getUint32(8 + 12 * nv + 4 * k, true);
  return { positions, indices };
}

/**
 * A POST of `body` as JSON to `url` (the studio's actions; never in a
 * report): the answer whatever its status, the caller reads its errors.
 */
export async function post(url: string, body: unknown): Promise<Response> {
  return fetch(relative(url), {
    method: 'POST',
    headers: { 'content-type': 'application/json' },
    body: JSON.stringify(body),
  });
}
