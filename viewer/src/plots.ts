// The plots of a winding result (`/api/plots`, uPlot): per layer the
// winding angle and the laminate thickness along the meridian and the pull
// speed over a circuit; each axis's position and velocity against time and
// each block's time, with a cursor at the time shown. Drawn in a panel over
// the 3-D view, opened by its button; `window.formcamPlots` tells tests what
// is drawn.
import uPlot from 'uplot';
import 'uplot/dist/uPlot.min.css';
import * as api from './api';

/** `/api/plots` (generated from crates/formcam-view/src/plots.rs). */
export type PlotsBody = api.WindingPlots;

/** What tests read: per plot, the points of each series drawn. */
export interface PlotsProbe {
  open(): Promise<void>;
  series(): Record<string, number[]>;
}

declare global {
  interface Window { formcamPlots?: PlotsProbe }
}

export const COLOURS = ['#1f77b4', '#d62728', '#2ca02c', '#9467bd', '#ff7f0e', '#8c564b', '#e377c2', '#17becf'];

/** Series with their own x joined on one ascending x (nulls elsewhere). */
export function align(xs: number[][], ys: number[][]): (number | null)[][] {
  const all: [number, number, number][] = [];
  xs.forEach((x, s) => x.forEach((v, i) => all.push([v, s, i])));
  all.sort((a, b) => a[0] - b[0]);
  const out: (number | null)[][] = [all.map((a) => a[0])];
  ys.forEach((_, s) => {
    const col: (number | null)[] = new Array(all.length).fill(null);
    all.forEach(([, k, i], row) => { if (k === s) col[row] = ys[s][i]; });
    out.push(col);
  });
  return out;
}

/** Non-null values per series (after x). */
export function counts(data: ArrayLike<(number | null)[] | ArrayLike<number | null>>): number[] {
  const out: number[] = [];
  for (let s = 1; s < data.length; s++) {
    let n = 0;
    const col = data[s];
    for (let i = 0; i < col.length; i++) if (col[i] !== null && col[i] !== undefined) n++;
    out.push(n);
  }
  return out;
}

/** A value range at least 1e-3 of the values' magnitude wide, so that a
 * constant (or nearly constant) series shows as the flat line it is. */
export function spanRange(_u: uPlot, min: number | null, max: number | null): uPlot.Range.MinMax {
  if (min === null || max === null || !Number.isFinite(min) || !Number.isFinite(max)) return [0, 1];
  const mid = (min + max) / 2;
  const half = Math.max((max - min) / 2, 1e-3 * Math.max(Math.abs(mid), 1e-9)) * 1.05;
  return [mid - half, mid + half];
}

/** A legend value: a number in few digits, blank where there is none
 * (uPlot would write `--`). */
export function legendValue(_u: uPlot, v: number | null): string {
  return v === null || v === undefined || !Number.isFinite(v) ? '' : String(+v.toPrecision(6));
}

/** The decimals that write `step` exactly (at most 12). */
export function decimalsOf(step: number): number {
  for (let d = 0; d < 12; d++) {
    const v = step * 10 ** d;
    if (Math.abs(v - Math.round(v)) <= 1e-6 * Math.max(v, 1)) return d;
  }
  return 12;
}

/** Tick labels with the decimals the step between ticks needs, so that
 * close ticks (a pull speed near 1) read apart. */
export function tickValues(_u: uPlot, splits: number[], _axis: number, _space: number, step: number): string[] {
  const d = decimalsOf(step);
  return splits.map((v) => v.toLocaleString('en', { minimumFractionDigits: d, maximumFractionDigits: d }));
}

/** A value axis wide enough for its longest tick label and its name. */
export function axisSize(_u: uPlot, values: string[] | null): number {
  const longest = Math.max(0, ...(values ?? []).map((v) => v.length));
  return Math.max(50, 7 * longest + 30);
}

/** Shows row `idx` in `u`'s legend (blank values with none) while the
 * pointer is off the plot; under the pointer uPlot shows its row. */
export function legendAt(u: uPlot, idx: number | null): void {
  if (u.cursor.idx !== null && u.cursor.idx !== undefined) return;
  if (idx === null) u.setLegend({ idxs: u.series.map(() => null) }, false);
  else u.setLegend({ idx }, false);
}

/** A titled uPlot in `host`; every value scale at least [`spanRange`] wide.
 * Its legend, while the pointer is off the plot, shows the row `rest()`
 * (the values at the time shown, say), or no values without one. */
export function chart(
  host: HTMLElement,
  title: string,
  opts: Omit<uPlot.Options, 'width' | 'height' | 'title'>,
  data: uPlot.AlignedData,
  height = 220,
  rest: () => number | null = () => null,
): uPlot {
  const div = document.createElement('div');
  div.className = 'chart';
  host.appendChild(div);
  const scales: uPlot.Scales = { ...(opts.scales ?? {}) };
  for (const s of opts.series.slice(1)) {
    const key = s.scale ?? 'y';
    scales[key] = { range: spanRange, ...(scales[key] ?? {}) };
  }
  const series = opts.series.map((s) => ({ value: legendValue, ...s }));
  const axes = opts.axes?.map((a, i) => ({ values: tickValues, ...(i > 0 ? { size: axisSize } : {}), ...a }));
  const atRest = (u: uPlot) => legendAt(u, rest());
  const hooks: uPlot.Hooks.Arrays = {
    ...(opts.hooks ?? {}),
    ready: [...(opts.hooks?.ready ?? []), atRest],
    setCursor: [...(opts.hooks?.setCursor ?? []), atRest],
  };
  return new uPlot(
    { width: Math.max(host.clientWidth - 24, 320), height, title, ...opts, series, scales, hooks, ...(axes ? { axes } : {}) },
    data,
    div,
  );
}

/** The last index of ascending `xs` at or before `x` (0 before the first). */
export function rowAt(xs: ArrayLike<number>, x: number): number {
  let lo = 0;
  let hi = xs.length;
  while (lo < hi) {
    const mid = (lo + hi) >> 1;
    if (xs[mid] <= x) lo = mid + 1;
    else hi = mid;
  }
  return Math.max(0, lo - 1);
}

/** A red vertical line at x value `at()` on every redraw. */
export function cursorHook(at: () => number | null): (u: uPlot) => void {
  return (u) => {
    const v = at();
    if (v === null) return;
    const x = u.valToPos(v, 'x', true);
    const ctx = u.ctx;
    ctx.save();
    ctx.strokeStyle = '#e0322b';
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    ctx.moveTo(x, u.bbox.top);
    ctx.lineTo(x, u.bbox.top + u.bbox.height);
    ctx.stroke();
    ctx.restore();
  };
}

export class WindingPlots {
  private time = 0;
  private readonly timed: uPlot[] = [];
  private blocksPlot: uPlot | null = null;
  private drawn: Promise<void> | null = null;
  private readonly probe: Record<string, number[]> = {};
  /** The axes' sample times (a block's start each, then the end). */
  private axesT: number[] | null = null;
  /** The row the timed legends show. */
  private legendRow: number | null = null;

  constructor(private readonly host: HTMLElement, toggle: HTMLElement) {
    toggle.addEventListener('click', () => {
      if (this.host.hidden) void this.open();
      else this.host.hidden = true;
    });
    window.formcamPlots = { open: () => this.open(), series: () => ({ ...this.probe }) };
  }

  /** Shows the panel, drawing the plots the first time. */
  open(): Promise<void> {
    this.host.hidden = false;
    this.drawn ??= api.json<PlotsBody>('/api/plots').then((b) => this.build(b));
    return this.drawn;
  }

  /** Moves the cursors (and the legends, at rest) to `t` s. */
  at(t: number): void {
    const moved = this.timed.some((u) => Math.round(u.valToPos(t, 'x')) !== Math.round(u.valToPos(this.time, 'x')));
    this.time = t;
    if (this.host.hidden) return;
    if (moved) for (const u of this.timed) u.redraw(false, false);
    this.blocksPlot?.redraw(false, false);
    const row = this.row();
    if (row !== this.legendRow) {
      this.legendRow = row;
      for (const u of this.timed) legendAt(u, row);
      if (this.blocksPlot) legendAt(this.blocksPlot, this.block());
    }
  }

  /** The row of the axes' times at the time shown. */
  private row(): number | null {
    return this.axesT ? rowAt(this.axesT, this.time) : null;
  }

  /** The block running at the time shown (the last starting at or before it). */
  private block(): number | null {
    const r = this.row();
    return r === null || !this.axesT ? null : Math.min(r, this.axesT.length - 2);
  }

  private add(name: string, u: uPlot): uPlot {
    this.probe[name] = counts(u.data as (number | null)[][]);
    return u;
  }

  private build(b: PlotsBody): void {
    const host = this.host;
    const layers = (ls: { layer: number }[]) => ls.map((l, k) => ({
      label: `layer ${l.layer}`, stroke: COLOURS[k % COLOURS.length], width: 1.5, spanGaps: true,
    }));
    if (b.meridian.length > 0) {
      const xs = b.meridian.map((m) => m.z);
      this.add('alpha', chart(host, 'Winding angle along the meridian', {
        scales: { x: { time: false } },
        series: [{ label: 'z (mm)' }, ...layers(b.meridian)],
        axes: [{ label: 'z (mm)' }, { label: 'winding angle (°)' }],
      }, align(xs, b.meridian.map((m) => m.alpha_deg)) as uPlot.AlignedData));
      this.add('thickness', chart(host, 'Laminate thickness along the meridian', {
        scales: { x: { time: false } },
        series: [{ label: 'z (mm)' }, ...layers(b.meridian)],
        axes: [{ label: 'z (mm)' }, { label: 'thickness (mm)' }],
      }, align(xs, b.meridian.map((m) => m.thickness)) as uPlot.AlignedData));
    }
    if (b.pull.length > 0) {
      this.add('pull', chart(host, 'Pull speed u(x) over a circuit', {
        scales: { x: { time: false } },
        series: [{ label: 'x (mm)' }, ...layers(b.pull)],
        axes: [{ label: 'laid band length x (mm)' }, { label: 'u' }],
      }, align(b.pull.map((p) => p.x), b.pull.map((p) => p.u)) as uPlot.AlignedData));
    }
    const a = b.axes;
    if (a) {
      this.axesT = a.t;
      const cursor = cursorHook(() => this.time);
      a.names.forEach((name, k) => {
        const u = chart(host, `${name}: position and velocity against time`, {
          scales: { x: { time: false } },
          series: [
            { label: 't (s)' },
            { label: `${name} (${a.units[k]})`, stroke: COLOURS[0], width: 1.5, scale: 'p' },
            {
              label: `${name} velocity (${a.velocity_units[k]})`, stroke: COLOURS[1], width: 1, scale: 'v',
              paths: uPlot.paths.stepped?.({ align: 1 }),
            },
          ],
          axes: [
            { label: 't (s)' },
            { scale: 'p', label: a.units[k] },
            { scale: 'v', label: a.velocity_units[k], side: 1, grid: { show: false } },
          ],
          hooks: { draw: [cursor] },
        }, [a.t, a.position[k], a.velocity[k]] as uPlot.AlignedData, 180, () => this.row());
        this.timed.push(this.add(`axis ${name}`, u));
      });
      const index = a.block_s.map((_, i) => i);
      const current = () => this.block() ?? 0;
      this.blocksPlot = this.add('blocks', chart(host, 'Block times', {
        scales: { x: { time: false } },
        series: [
          { label: 'block' },
          { label: 'time (s)', stroke: COLOURS[2], width: 1, paths: uPlot.paths.stepped?.({ align: 1 }) },
        ],
        axes: [{ label: 'block (0-based)' }, { label: 's' }],
        hooks: { draw: [cursorHook(current)] },
      }, [index, a.block_s] as uPlot.AlignedData, 180, () => this.block()));
    }
    if (host.childElementCount === 0) host.textContent = 'This result has no tables to plot.';
  }
}
