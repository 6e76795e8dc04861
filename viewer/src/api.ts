// The data `formcam view` sends (see crates/formcam-view): the page draws
// these poses and points as they come; it does no kinematics.

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

async function get(url: string): Promise<Response> {
  const r = await fetch(url);
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
  const r = await fetch('/api/mandrel');
  return r.ok ? ((await r.json()) as MandrelScene) : null;
}
