// A correction result (`/api/correction`): the deviation map — every
// measured point at its nominal place in plan view (X, Y), coloured by its
// deviation, with a colour bar — and the deviation per section and per run
// of the report's history. A closed-loop simulation shows the map of each
// round (the last first, a button per round), the deviations per round and
// the section-spacing study. `window.formcam.state().points` is the number
// of points drawn, `round(k)` shows round k.
import uPlot from 'uplot';
import * as api from './api';
import { View2d, boundsOf, esc } from './view2d';
import { COLOURS, align, chart, counts, cursorHook, legendAt } from './plots';

/** One CMM report's points and deviations (DeviationMap in
 * crates/formcam-view/src/correction.rs). */
interface DeviationMap {
  x: number[];
  y: number[];
  z: number[];
  deviation: number[];
  section: number[];
  sections: { name: string; points: number; min: number; max: number; rms: number }[];
}

/** `/api/correction` (crates/formcam-view/src/correction.rs). */
interface CorrectionBody extends DeviationMap {
  measurements: string;
  scenario: string | null;
  program: string | null;
  rounds: (DeviationMap & { iteration: number; measurements: string; program: string })[];
  report: Record<string, unknown>;
}

type Row = Record<string, unknown>;

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
  const loop = c.rounds.length > 0;
  const maps: (DeviationMap & { measurements: string; label: string })[] = loop
    ? c.rounds.map((r) => ({ ...r, label: `round ${r.iteration}` }))
    : [{ ...c, label: c.measurements }];
  // A closed loop's rounds, or a correction's runs (its report's history).
  const history = (Array.isArray(loop ? c.report.rounds : c.report.history)
    ? (loop ? c.report.rounds : c.report.history) : []) as Row[];
  const study = (Array.isArray(c.report.section_study) ? c.report.section_study : []) as Row[];
  const title = loop ? `correction loop, ${esc(c.scenario ?? '')}` : `correction, ${esc(c.measurements)}`;
  host.innerHTML = `
    <header><strong>${api.PAGE_NAME}: ${title}</strong>
      <span class="status"></span></header>
    <main class="drawing"></main>
    <aside>${loop ? `<section><h2>Round shown</h2><div class="rounds">${maps.map((m, k) =>
    `<button data-round="${k}">${esc(m.label)}</button>`).join(' ')}</div></section>` : ''}
      <section><h2>Deviation (mm)</h2><canvas class="colourbar" width="300" height="46"></canvas></section>
      <section><h2>Deviation per section</h2><div class="sections"></div></section>
      ${history.length > 0 ? `<section><h2>${loop ? 'Deviation per round' : 'Deviation per run'}</h2><div class="history"></div></section>` : ''}
      ${study.length > 0 ? '<section><h2>After one correction, per section spacing</h2><div class="study"></div></section>' : ''}
      <section><h2>Report</h2><table class="report"></table></section></aside>`;
  const q = <T extends HTMLElement>(sel: string) => host.querySelector(sel) as T;
  let shown = maps.length - 1;
  let m = maps[shown];
  let limit = 1e-9;
  let drawnPoints = 0;
  const view = new View2d(q('.drawing'), (v, ctx) => {
    drawnPoints = 0;
    const pts = m.x.map((x, i) => [x, m.y[i]]);
    // Sections as thin lines through their points, in measuring order.
    m.sections.forEach((_, k) => {
      v.line(ctx, pts.filter((_, i) => m.section[i] === k), '#c9ccd4', 1);
    });
    for (let i = 0; i < m.x.length; i++) {
      ctx.fillStyle = diverging(m.deviation[i] / limit);
      ctx.strokeStyle = '#555';
      ctx.lineWidth = 0.5;
      ctx.beginPath();
      ctx.arc(v.px(m.x[i]), v.py(m.y[i]), 5, 0, 2 * Math.PI);
      ctx.fill();
      ctx.stroke();
      drawnPoints++;
    }
  }, ['X (mm)', 'Y (mm)']);

  // The colour bar: -limit .. +limit of the map shown.
  const colourBar = () => {
    const bar = q<HTMLCanvasElement>('.colourbar');
    const bctx = bar.getContext('2d');
    if (!bctx) return;
    bctx.clearRect(0, 0, bar.width, bar.height);
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
  };

  // Per section: least, largest and RMS deviation.
  const sectionData = () => [m.sections.map((_, k) => k), m.sections.map((s) => s.min),
    m.sections.map((s) => s.max), m.sections.map((s) => s.rms)] as uPlot.AlignedData;
  const sectionPlot = chart(q('.sections'), '', {
    scales: { x: { time: false } },
    series: [
      { label: 'section', value: (_u: uPlot, v: number | null) => (v === null ? '' : m.sections[Math.round(v)]?.name ?? '') },
      { label: 'min', stroke: COLOURS[0], width: 1.5 },
      { label: 'max', stroke: COLOURS[1], width: 1.5 },
      { label: 'RMS', stroke: COLOURS[2], width: 1.5 },
    ],
    axes: [{
      label: 'section',
      values: (_u: uPlot, ticks: number[]) => ticks.map((t) => (Number.isInteger(t) ? m.sections[t]?.name ?? '' : '')),
    }, { label: 'mm' }],
  }, sectionData(), 220);

  // Per round (or run): the deviations, a marker at the round shown.
  const whole = (_u: uPlot, ticks: number[]) => ticks.map((t) => (Number.isInteger(t) ? String(t) : ''));
  const num = (r: Row, k: string) => (typeof r[k] === 'number' ? (r[k] as number) : null);
  const iterations = history.map((h, k) => num(h, 'iteration') ?? k);
  let historyPlot: uPlot | null = null;
  if (history.length > 0) {
    const series: [string, string][] = loop
      ? [['true max', 'true_max_mm'], ['true RMS', 'true_rms_mm'], ['measured max', 'measured_max_mm'], ['measured RMS', 'measured_rms_mm']]
      : [['max', 'max_deviation_mm'], ['RMS', 'rms_deviation_mm']];
    const at = () => (loop ? shown : history.length - 1);
    historyPlot = chart(q('.history'), '', {
      scales: { x: { time: false } },
      series: [{ label: loop ? 'round' : 'run' }, ...series.map(([label], k) => ({
        label: `${label} (mm)`, stroke: COLOURS[k], width: 1.5, dash: k >= 2 ? [4, 3] : undefined,
        points: { show: true, size: 5 },
      }))],
      axes: [{ label: loop ? 'round (0: before correcting)' : 'run', values: whole }, { label: 'mm' }],
      hooks: { draw: [cursorHook(() => iterations[at()] ?? null)] },
    }, [iterations, ...series.map(([, key]) => history.map((h) => num(h, key)))] as uPlot.AlignedData, 220, at);
  }

  // The section-spacing study: the residual after one correction against
  // the spacing of the sections, per interpolation.
  let studyPlot: uPlot | null = null;
  if (study.length > 0) {
    const kinds = [...new Set(study.map((r) => String(r.interpolation)))];
    const of = (k: string) => study.filter((r) => String(r.interpolation) === k);
    const xs = kinds.map((k) => of(k).map((r) => num(r, 'section_spacing_mm') ?? 0));
    const ys = kinds.flatMap((k) => [of(k).map((r) => num(r, 'true_max_mm') ?? 0), of(k).map((r) => num(r, 'true_rms_mm') ?? 0)]);
    studyPlot = chart(q('.study'), '', {
      scales: { x: { time: false } },
      series: [{ label: 'spacing (mm)' }, ...kinds.flatMap((k, i) => [
        { label: `${k} max (mm)`, stroke: COLOURS[i], width: 1.5, spanGaps: true, points: { show: true, size: 5 } },
        { label: `${k} RMS (mm)`, stroke: COLOURS[i], width: 1, dash: [4, 3], spanGaps: true, points: { show: true, size: 4 } },
      ])],
      axes: [{ label: 'section spacing (mm)' }, { label: 'true deviation (mm)' }],
    }, align(kinds.flatMap((_, i) => [xs[i], xs[i]]), ys) as uPlot.AlignedData, 220);
  }

  const rows: [string, unknown][] = loop
    ? [
      ['rounds of correction', c.report.iterations],
      ['interpolation', c.report.interpolation],
      ['sections x points', `${String(c.report.sections)} x ${String(c.report.points_per_section)}`],
      ['CMM noise (mm)', c.report.noise_mm],
      ['warp amplitude (mm)', c.report.warp_amplitude_mm],
      ['true max deviation before (mm)', c.report.max_deviation_before_mm],
      ['true max deviation after (mm)', c.report.max_deviation_after_mm],
      ['true RMS deviation after (mm)', c.report.rms_deviation_after_mm],
    ]
    : [
      ['max deviation (mm)', c.report.max_deviation_mm],
      ['RMS deviation (mm)', c.report.rms_deviation_mm],
      ['max displacement (mm)', c.report.max_displacement_mm],
      ['nodes corrected', c.report.nodes_corrected],
      ['interpolation', c.report.interpolation],
    ];
  const pair = (a: unknown, b: unknown) => `${Number(a).toFixed(4)} / ${Number(b).toFixed(4)}`;
  history.forEach((h) => rows.push(loop
    ? [`round ${String(h.iteration)}: true max / RMS (mm)`, pair(h.true_max_mm, h.true_rms_mm)]
    : [`run ${String(h.iteration)}: max / RMS deviation (mm)`, pair(h.max_deviation_mm, h.rms_deviation_mm)]));
  q('.report').innerHTML = rows.map(([k, v]) => `<tr><td>${k}</td><td>${typeof v === 'number' ? (Number.isInteger(v) ? String(v) : v.toFixed(4)) : esc(String(v ?? ''))}</td></tr>`).join('');

  /** Shows map `k` (a round of a loop): the drawing, colour bar, plots. */
  const show = (k: number) => {
    shown = Math.min(Math.max(Math.round(k), 0), maps.length - 1);
    m = maps[shown];
    limit = Math.max(1e-9, ...m.deviation.map(Math.abs));
    q('.status').textContent = `${loop ? `${m.label}, ${m.measurements}: ` : ''}${m.x.length} points in ${m.sections.length} sections` +
      `${!loop && c.program ? `, ${c.program}` : ''}`;
    host.querySelectorAll<HTMLButtonElement>('.rounds button').forEach((b) => {
      const on = Number(b.dataset.round) === shown;
      b.style.fontWeight = on ? 'bold' : '';
      b.style.outline = on ? '2px solid #1f77b4' : '';
    });
    colourBar();
    sectionPlot.setData(sectionData());
    legendAt(sectionPlot, null);
    if (historyPlot) {
      historyPlot.redraw(false, false);
      legendAt(historyPlot, loop ? shown : history.length - 1);
    }
    view.draw();
  };
  host.querySelectorAll<HTMLButtonElement>('.rounds button').forEach((b) => {
    b.addEventListener('click', () => show(Number(b.dataset.round)));
  });
  view.fit(boundsOf(maps.map((mm) => mm.x.map((x, i) => [x, mm.y[i]]))));
  show(shown);

  window.formcam = {
    ready,
    duration_s: 0,
    seek: async () => { await ready; },
    round: async (k: number) => { show(k); await ready; },
    state: () => ({
      time_s: 0,
      points: drawnPoints,
      sections: m.sections.length,
      round: loop ? shown : null,
      rounds: c.rounds.length,
      series: {
        sections: counts(sectionPlot.data as (number | null)[][]),
        ...(historyPlot ? { history: counts(historyPlot.data as (number | null)[][]) } : {}),
        ...(studyPlot ? { study: counts(studyPlot.data as (number | null)[][]) } : {}),
      },
    }),
    play: () => {},
    pause: () => {},
    frames: () => 0,
  } as unknown as Window['formcam'];
}
