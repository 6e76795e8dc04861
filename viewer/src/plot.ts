// Each axis against time (uPlot), from the timeline's samples, with a
// marker at the time shown.
import uPlot from 'uplot';
import 'uplot/dist/uPlot.min.css';
import type { TimelineBody } from './api';

const COLOURS = ['#1f77b4', '#d62728', '#2ca02c', '#9467bd', '#ff7f0e', '#8c564b', '#e377c2', '#17becf'];

export class AxesPlot {
  private readonly plot: uPlot;
  private time = 0;

  constructor(host: HTMLElement, tl: TimelineBody) {
    const t = tl.samples.map((s) => s.t);
    const series: uPlot.Series[] = [{ label: 't (s)' }];
    const data: number[][] = [t];
    tl.axes.forEach((a, k) => {
      series.push({
        label: `${a.name} (${a.unit})`,
        stroke: COLOURS[k % COLOURS.length],
        width: 1,
        scale: a.unit,
      });
      data.push(tl.samples.map((s) => s.axes[k]));
    });
    const units = [...new Set(tl.axes.map((a) => a.unit))];
    const marker = (u: uPlot) => {
      const x = u.valToPos(this.time, 'x', true);
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
    this.plot = new uPlot(
      {
        width: Math.max(host.clientWidth, 300),
        height: 200,
        scales: { x: { time: false } },
        series,
        axes: [
          { label: 't (s)' },
          ...units.map((u, i) => ({ scale: u, label: u, side: i === 0 ? 3 : 1 })),
        ] as uPlot.Axis[],
        legend: { show: true },
        hooks: { draw: [marker] },
      },
      data as uPlot.AlignedData,
      host,
    );
  }

  /** Moves the marker to `t` s. */
  at(t: number): void {
    // Redrawn only when the marker moves by a pixel: playing stays cheap.
    const moved = Math.round(this.plot.valToPos(t, 'x')) !== Math.round(this.plot.valToPos(this.time, 'x'));
    this.time = t;
    if (moved) this.plot.redraw(false, false);
  }
}
