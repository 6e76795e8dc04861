// The data `formcam view` sends (see crates/formcam-view): the page draws
// these poses and points as they come; it does no kinematics. Every answer
// comes through `answer`: fetched from the server, or in a report
// (`formcam report`) looked up in the data inlined in the page.
import * as report from './report';
import type { BlocksBody, MandrelScene, OverlaysBody, Shown, SolidShape, Violations as ViolationsBody } from './generated';

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

// The types of the JSON the server sends are generated from its Rust types
// (crates/formcam-view/src/typescript.rs, by ts-rs) into `generated/`;
// exported below under the names the page uses.

export type {
  AxisHead,
  AxisPlots,
  AxisRange,
  Band,
  CorrectionBody,
  DeviationMap,
  DresserPass,
  DresserSample,
  DressingBody,
  EyeTrajectory,
  KindBody,
  Knots,
  LaidTable,
  LinkScene,
  MachineScene,
  MandrelScene,
  MeridianPlot,
  MrrPlot,
  NodeCounts,
  NodeMarks,
  PathBand,
  PathBody,
  Placement,
  PullPlot,
  ResultKind,
  RoundMap,
  SampleTables,
  SectionStats,
  Solid,
  SurfaceMesh,
  TimelineBody,
  TimelineHead,
  WindingPlots,
} from './generated';

/** The state at one time (`/api/sample`, `/api/timeline`'s samples), with the band laid then. */
export type Sample = Shown;

/** `/api/blocks`. */
export type Blocks = BlocksBody;

/** `/api/overlays`: which of `violations`, `eye` and `band` the result has. */
export type Overlays = OverlaysBody;

/**
 * A mesh solid of `/api/machine`: the file the machine names, its
 * triangles at `/api/mesh/N` (`mesh`), or why it could not be read.
 */
export type MeshShape = Extract<SolidShape, { shape: 'mesh' }>;

/**
 * A violation as the check reports it (the server passes each on as
 * `check.json` or formcam-sim's check writes it, with its `spans`): kinds
 * the page does not know (a collision naming `links`, say) are still listed.
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

/** `/api/violations`: the generated type, each violation as [`Violation`]. */
export type Violations = Omit<ViolationsBody, 'violations'> & { violations: Violation[] };

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
