// Each axis against time (uPlot), from the timeline's samples, with a
// marker at the time shown and the legend at that time (unless hovered).
import uPlot from 'uplot';
import { cursorHook } from './plots';
import 'uplot/dist/uPlot.min.css';
import type { TimelineBody } from './api';

const COLOURS = ['#1f77b4', '#d62728', '#2ca02c', '#9467bd', '#ff7f0e', '#8c564b', '#e377c2', '#17becf'];

export class AxesPlot {
  private readonly plot: uPlot;
  private time = 0;
  /** The sample index the legend shows when the pointer is elsewhere. */
  private idx = 0;
  private readonly times: number[];
  /** The axes at the time shown, exact (the legend's values then). */
  private exact: number[] | null = null;

  constructor(host: HTMLElement, tl: TimelineBody) {
    const t = tl.samples.map((s) => s.t);
    this.times = t;
    const series: uPlot.Series[] = [{ label: 't (s)' }];
    const data: number[][] = [t];
    tl.axes.forEach((a, k) => {
      series.push({
        label: `${a.name} (${a.unit})`,
        stroke: COLOURS[k % COLOURS.length],
        width: 1,
        scale: a.unit,
        value: (u: uPlot, v: number | null, _s: number, i: number | null) => {
          const x = u.cursor.idx == null && i === this.idx && this.exact ? this.exact[k] : v;
          return x == null ? '' : x.toFixed(3);
        },
      });
      data.push(tl.samples.map((s) => s.axes[k]));
    });
    const units = [...new Set(tl.axes.map((a) => a.unit))];
    const marker = cursorHook(() => this.time);
    this.plot = new uPlot(
      {
        width: Math.max(host.clientWidth, 300),
        height: 200,
        scales: { x: { time: false } },
        series,
        axes: [
          { label: 't (s)' },
          // Wide enough for the ticks, written compactly (-20k, not -20,000).
          ...units.map((u, i) => ({
            scale: u,
            label: u,
            side: i === 0 ? 3 : 1,
            size: 52,
            labelSize: 16,
            values: (_: uPlot, ticks: number[]) => ticks.map(compact),
          })),
        ] as uPlot.Axis[],
        legend: { show: true },
        hooks: {
          draw: [marker],
          // Drawn, or the pointer gone: the legend shows the time shown.
          ready: [(u: uPlot) => u.setLegend({ idx: this.idx }, false)],
          setCursor: [(u: uPlot) => { if (u.cursor.idx == null) u.setLegend({ idx: this.idx }, false); }],
        },
      },
      data as uPlot.AlignedData,
      host,
    );
  }

  /** Moves the marker to `t` s; the legend shows `axes` (exact) there. */
  at(t: number, axes?: number[]): void {
    this.exact = axes ?? null;
    // Redrawn only when the marker moves by a pixel: playing stays cheap.
    const moved = Math.round(this.plot.valToPos(t, 'x')) !== Math.round(this.plot.valToPos(this.time, 'x'));
    this.time = t;
    if (moved) this.plot.redraw(false, false);
    // The legend's values: the last sample at or before `t`.
    let lo = 0;
    let hi = this.times.length;
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      if (this.times[mid] <= t) lo = mid + 1;
      else hi = mid;
    }
    this.idx = Math.max(lo - 1, 0);
    if (this.plot.cursor.idx == null) this.plot.setLegend({ idx: this.idx }, false);
  }
}

/** A tick value in few characters: 20k, -1.5k, 250, 0.25. */
function compact(v: number): string {
  const a = Math.abs(v);
  if (a >= 1e6) return `${+(v / 1e6).toPrecision(3)}M`;
  if (a >= 1e4) return `${+(v / 1e3).toPrecision(3)}k`;
  return String(+v.toPrecision(4));
}
