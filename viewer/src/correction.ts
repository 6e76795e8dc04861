// A correction result (`/api/correction`): the deviation map — every
// measured point at its nominal place in plan view (X, Y), coloured by its
// deviation, with a colour bar — and the deviation per section and per run
// of the report's history. `window.formcam.state().points` is the number of
// points drawn.
import uPlot from 'uplot';
import * as api from './api';
import { View2d, boundsOf, esc } from './view2d';
import { COLOURS, chart } from './plots';

/** `/api/correction` (crates/formcam-view/src/correction.rs). */
interface CorrectionBody {
  measurements: string;
  program: string | null;
  x: number[];
  y: number[];
  z: number[];
  deviation: number[];
  section: number[];
  sections: { name: string; points: number; min: number; max: number; rms: number }[];
  report: Record<string, unknown>;
}

/** Blue (negative) through white to red (positive), `f` in [-1, 1]. */
export function diverging(f: number): string {
  const c = Math.max(-1, Math.min(1, f));
  const mix = (a: number, b: number, t: number) => Math.round(a + (b - a) * t);
  const [r, g, b] = c < 0
    ? [mix(247, 33, -c), mix(247, 102, -c), mix(247, 172, -c)]
    : [mix(247, 178, c), mix(247, 24, c), mix(247, 43, c)];
  return `rgb(${r}, ${g}, ${b})`;
}

/** Opens the correction view in `host`; resolves once drawn. */
export async function openCorrection(host: HTMLElement, ready: Promise<void>): Promise<void> {
  const c = await api.json<CorrectionBody>('/api/correction');
  const n = c.x.length;
  const limit = Math.max(1e-9, ...c.deviation.map(Math.abs));
  host.innerHTML = `
    <header><strong>${api.PAGE_NAME}: correction, ${esc(c.measurements)}</strong>
      <span class="status">${n} points in ${c.sections.length} sections${c.program ? `, ${esc(c.program)}` : ''}</span></header>
    <main class="drawing"></main>
    <aside><section><h2>Deviation (mm)</h2><canvas class="colourbar" width="300" height="46"></canvas></section>
      <section><h2>Deviation per section</h2><div class="sections"></div></section>
      <section><h2>Report</h2><table class="report"></table></section></aside>`;
  const q = <T extends HTMLElement>(sel: string) => host.querySelector(sel) as T;
  const pts = c.x.map((x, i) => [x, c.y[i]]);
  let drawnPoints = 0;
  const view = new View2d(q('.drawing'), (v, ctx) => {
    drawnPoints = 0;
    // Sections as thin lines through their points, in measuring order.
    c.sections.forEach((_, k) => {
      v.line(ctx, pts.filter((_, i) => c.section[i] === k), '#c9ccd4', 1);
    });
    for (let i = 0; i < n; i++) {
      ctx.fillStyle = diverging(c.deviation[i] / limit);
      ctx.strokeStyle = '#555';
      ctx.lineWidth = 0.5;
      ctx.beginPath();
      ctx.arc(v.px(c.x[i]), v.py(c.y[i]), 5, 0, 2 * Math.PI);
      ctx.fill();
      ctx.stroke();
      drawnPoints++;
    }
  }, ['X (mm)', 'Y (mm)']);
  view.fit(boundsOf([pts]));

  // The colour bar: -limit .. +limit.
  const bar = q<HTMLCanvasElement>('.colourbar');
  const bctx = bar.getContext('2d');
  if (bctx) {
    for (let px = 0; px < bar.width; px++) {
      bctx.fillStyle = diverging((px / (bar.width - 1)) * 2 - 1);
      bctx.fillRect(px, 0, 1, 24);
    }
    bctx.fillStyle = '#223';
    bctx.font = '11px system-ui, sans-serif';
    bctx.fillText((-limit).toFixed(4), 0, 40);
    bctx.fillText('0', bar.width / 2 - 3, 40);
    const right = limit.toFixed(4);
    bctx.fillText(right, bar.width - bctx.measureText(right).width, 40);
  }

  // Per section: least, largest and RMS deviation.
  const idx = c.sections.map((_, k) => k);
  const sectionPlot = chart(q('.sections'), '', {
    scales: { x: { time: false } },
    series: [
      { label: 'section' },
      { label: 'min', stroke: COLOURS[0], width: 1.5 },
      { label: 'max', stroke: COLOURS[1], width: 1.5 },
      { label: 'RMS', stroke: COLOURS[2], width: 1.5 },
    ],
    axes: [{
      label: 'section',
      values: (_u: uPlot, ticks: number[]) => ticks.map((t) => c.sections[Math.round(t)]?.name ?? ''),
    }, { label: 'mm' }],
  }, [idx, c.sections.map((s) => s.min), c.sections.map((s) => s.max), c.sections.map((s) => s.rms)] as uPlot.AlignedData, 220);

  const rows: [string, unknown][] = [
    ['max deviation (mm)', c.report.max_deviation_mm],
    ['RMS deviation (mm)', c.report.rms_deviation_mm],
    ['max displacement (mm)', c.report.max_displacement_mm],
    ['nodes corrected', c.report.nodes_corrected],
    ['interpolation', c.report.interpolation],
  ];
  const history = Array.isArray(c.report.history) ? (c.report.history as Record<string, unknown>[]) : [];
  history.forEach((h) => rows.push([`run ${String(h.iteration)}: max / RMS deviation (mm)`,
    `${Number(h.max_deviation_mm).toFixed(4)} / ${Number(h.rms_deviation_mm).toFixed(4)}`]));
  q('.report').innerHTML = rows.map(([k, v]) => `<tr><td>${k}</td><td>${typeof v === 'number' ? (Number.isInteger(v) ? String(v) : v.toFixed(4)) : esc(String(v ?? ''))}</td></tr>`).join('');

  window.formcam = {
    ready,
    duration_s: 0,
    seek: async () => { await ready; },
    state: () => ({ time_s: 0, points: drawnPoints, sections: c.sections.length, series: { sections: sectionPlot.data.length - 1 } }),
    play: () => {},
    pause: () => {},
    frames: () => 0,
  } as unknown as Window['formcam'];
}
