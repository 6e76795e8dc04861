// A correction result (`/api/correction`): the deviation on the nominal
// surface in 3-D (the measured sections' grid coloured per vertex, the
// sections and their points on it, the program's nodes marked by what the
// correction did: `surface3d.ts`), the same map in plan view (X, Y), a
// colour bar in mm, before and after the correction on one colour scale
// (after: the next part predicted from the corrected program; in a closed
// loop, the next round), the deviation per section and per run of the
// report's history. A closed-loop simulation shows the map of each round
// (the last first, a button per round, or a click on the history plot),
// the deviations per round and the section-spacing study.
// `window.formcam.state()` says what is drawn (`points`, `view`,
// `max_abs_deviation`, `surface`, `nodes`), `round(k)` shows round k and
// `show('before' | 'after')` flips the map.
import uPlot from 'uplot';
import * as api from './api';
import { View2d, boundsOf, esc } from './view2d';
import { COLOURS, align, chart, counts, cursorHook, legendAt } from './plots';
import { DeviationSurface, NODE_KINDS } from './surface3d';

/** `/api/correction` (generated from crates/formcam-view/src/correction.rs). */
type CorrectionBody = api.CorrectionBody;
type DeviationMap = api.DeviationMap;

type Row = Record<string, unknown>;
type Which = 'before' | 'after';
type Shown = DeviationMap & { measurements: string; label: string };

/** Blue (negative) through white to red (positive), `f` in [-1, 1]: 0..255 per channel. */
export function divergingRgb(f: number): [number, number, number] {
  const c = Math.max(-1, Math.min(1, Number.isFinite(f) ? f : 0));
  const mix = (a: number, b: number, t: number) => Math.round(a + (b - a) * t);
  return c < 0
    ? [mix(247, 33, -c), mix(247, 102, -c), mix(247, 172, -c)]
    : [mix(247, 178, c), mix(247, 24, c), mix(247, 43, c)];
}

/** [`divergingRgb`] as a CSS colour. */
export function diverging(f: number): string {
  const [r, g, b] = divergingRgb(f);
  return `rgb(${r}, ${g}, ${b})`;
}

/** The largest |v| of the lists (0 for none). */
const maxAbs = (...lists: number[][]) => lists.reduce((m, l) => l.reduce((a, v) => Math.max(a, Math.abs(v)), m), 0);

/** Opens the correction view in `host`; resolves once drawn. */
export async function openCorrection(host: HTMLElement, ready: Promise<void>): Promise<void> {
  const c = await api.json<CorrectionBody>('/api/correction');
  const loop = c.rounds.length > 0;
  const maps: Shown[] = loop
    ? c.rounds.map((r) => ({ ...r, label: `round ${r.iteration}` }))
    : [{ ...c, label: c.measurements }];
  // A correction's after: the next part predicted from the corrected program.
  const predicted: Shown | null = !loop && c.after
    ? { ...c.after, measurements: 'predicted-cmm.csv', label: 'after: the next part predicted' } : null;
  /** Map `k` and what follows it: the next round, or the prediction. */
  const pairOf = (k: number): { before: Shown; after: Shown | null } => ({
    before: maps[k],
    after: loop ? maps[k + 1] ?? null : predicted,
  });
  // A closed loop's rounds, or a correction's runs (its report's history).
  const history = (Array.isArray(loop ? c.report.rounds : c.report.history)
    ? (loop ? c.report.rounds : c.report.history) : []) as Row[];
  const study = (Array.isArray(c.report.section_study) ? c.report.section_study : []) as Row[];
  const title = loop ? `correction loop, ${esc(c.scenario ?? '')}` : `correction, ${esc(c.measurements)}`;
  host.innerHTML = `
    <header><strong>${api.PAGE_NAME}: ${title}</strong>
      <span class="status"></span></header>
    <main class="drawing${c.surface ? '' : ' flat'}">${c.surface ? '<div class="surface3d"></div>' : ''}<div class="plan"></div></main>
    <aside>${loop ? `<section><h2>Round shown</h2><div class="rounds">${maps.map((m, k) =>
    `<button data-round="${k}">${esc(m.label)}</button>`).join(' ')}</div></section>` : ''}
      <section><h2>Deviation (mm)</h2>
        <div class="which"><button data-which="before">before</button> <button data-which="after">after</button>
          <span class="which-note"></span></div>
        <canvas class="colourbar" width="380" height="50"></canvas></section>
      ${c.nodes ? `<section><h2>Program nodes (${esc(c.nodes.file)})</h2><div class="node-legend"></div>
        <label><input type="checkbox" class="show-nodes" checked> marked in 3-D</label></section>` : ''}
      <section><h2>Deviation per section</h2><div class="sections"></div></section>
      ${history.length > 0 ? `<section><h2>${loop ? 'Deviation per round' : 'Deviation per run'}</h2><div class="history"></div></section>` : ''}
      ${study.length > 0 ? '<section><h2>After one correction, per section spacing</h2><div class="study"></div></section>' : ''}
      <section><h2>Report</h2><table class="report"></table></section></aside>`;
  const q = <T extends HTMLElement>(sel: string) => host.querySelector(sel) as T;
  let shown = maps.length - 1;
  let which: Which = 'before';
  let m: Shown = maps[shown];
  let limit = 1e-9;
  let drawnPoints = 0;
  const surface = c.surface
    ? new DeviationSurface(q('.surface3d'), c.surface, maps[maps.length - 1], c.nodes) : null;
  const view = new View2d(q('.plan'), (v, ctx) => {
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

  // The colour bar: -limit .. +limit (mm) of the pair shown, before and
  // after on the same scale, ticks at the ends, the halves and 0.
  const colourBar = () => {
    const bar = q<HTMLCanvasElement>('.colourbar');
    const bctx = bar.getContext('2d');
    if (!bctx) return;
    bctx.clearRect(0, 0, bar.width, bar.height);
    const [x0, x1] = [4, bar.width - 34];
    for (let px = x0; px <= x1; px++) {
      bctx.fillStyle = diverging(((px - x0) / (x1 - x0)) * 2 - 1);
      bctx.fillRect(px, 0, 1, 22);
    }
    bctx.fillStyle = '#223';
    bctx.font = '11px system-ui, sans-serif';
    const decimals = limit >= 1 ? 2 : limit >= 0.01 ? 3 : 4;
    [-1, -0.5, 0, 0.5, 1].forEach((f) => {
      const x = x0 + ((f + 1) / 2) * (x1 - x0);
      bctx.fillRect(Math.round(x), 22, 1, 5);
      const t = f === 0 ? '0' : (f * limit).toFixed(decimals);
      const w = bctx.measureText(t).width;
      bctx.fillText(t, Math.min(Math.max(x - w / 2, 0), x1 - w), 40);
    });
    bctx.fillText('mm', x1 + 8, 16);
  };

  // The program's nodes: a swatch and a count per kind (every node counted;
  // the 3-D view marks the ones sent).
  if (c.nodes) {
    const n = c.nodes;
    q('.node-legend').innerHTML = `<table>${NODE_KINDS.map((k) => `<tr data-kind="${k.kind}"><td><span class="swatch" style="background:${k.colour}"></span> ${k.label}</td><td>${n.counts[k.kind]}</td></tr>`).join('')}
      <tr><td>moved in all (inside or extrapolated)</td><td>${n.counts.moved}</td></tr>
      <tr><td>feed nodes of the program</td><td>${n.counts.nodes}</td></tr></table>${n.every > 1 ? `<p>one node in ${n.every} marked</p>` : ''}`;
    q<HTMLInputElement>('.show-nodes').addEventListener('change', (e) => surface?.showNodes((e.target as HTMLInputElement).checked));
  }

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
      : [['max', 'max_deviation_mm'], ['RMS', 'rms_deviation_mm'], ['predicted max after', 'predicted_max_deviation_mm']];
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
      ['predicted max deviation after (mm)', c.report.predicted_max_deviation_mm],
      ['predicted RMS deviation after (mm)', c.report.predicted_rms_deviation_mm],
      ['max displacement (mm)', c.report.max_displacement_mm],
      ['nodes corrected', c.report.nodes_corrected],
      ['interpolation', c.report.interpolation],
    ];
  const pair = (a: unknown, b: unknown) => `${Number(a).toFixed(4)} / ${Number(b).toFixed(4)}`;
  history.forEach((h) => rows.push(loop
    ? [`round ${String(h.iteration)}: true max / RMS (mm)`, pair(h.true_max_mm, h.true_rms_mm)]
    : [`run ${String(h.iteration)}: max / RMS deviation (mm)`, pair(h.max_deviation_mm, h.rms_deviation_mm)]));
  q('.report').innerHTML = rows.map(([k, v]) => `<tr><td>${k}</td><td>${typeof v === 'number' ? (Number.isInteger(v) ? String(v) : v.toFixed(4)) : esc(String(v ?? ''))}</td></tr>`).join('');

  /** Shows map `k` (a round of a loop), before or after (`w`; before
   * where there is no after): the 3-D surface, the plan, the colour bar
   * (one scale for the pair), the plots. */
  const show = (k: number, w: Which = which) => {
    shown = Math.min(Math.max(Math.round(k), 0), maps.length - 1);
    const pair = pairOf(shown);
    which = w === 'after' && pair.after ? 'after' : 'before';
    m = which === 'after' && pair.after ? pair.after : pair.before;
    limit = Math.max(1e-9, maxAbs(pair.before.deviation, pair.before.vertex_deviation,
      pair.after?.deviation ?? [], pair.after?.vertex_deviation ?? []));
    q('.status').textContent = `${loop ? `${maps[shown].label}, ` : ''}${which === 'after' && pair.after ? `${loop ? 'after: ' : ''}${pair.after.label}, ` : ''}` +
      `${m.measurements}: ${m.x.length} points in ${m.sections.length} sections` +
      `${!loop && c.program ? `, ${c.program}` : ''}`;
    host.querySelectorAll<HTMLButtonElement>('.rounds button').forEach((b) => {
      const on = Number(b.dataset.round) === shown;
      b.style.fontWeight = on ? 'bold' : '';
      b.style.outline = on ? '2px solid #1f77b4' : '';
    });
    host.querySelectorAll<HTMLButtonElement>('.which button').forEach((b) => {
      const on = b.dataset.which === which;
      b.disabled = b.dataset.which === 'after' && !pair.after;
      b.style.fontWeight = on ? 'bold' : '';
      b.style.outline = on ? '2px solid #1f77b4' : '';
    });
    q('.which-note').textContent = pair.after
      ? (loop ? `after: ${pair.after.label}, the part the corrected program made` : 'after: the next part, predicted from the corrected program')
      : (loop ? 'the last round: no after' : 'no prediction in this result');
    surface?.colour(m.vertex_deviation.map((d) => divergingRgb(d / limit).map((v) => v / 255) as [number, number, number]));
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
  host.querySelectorAll<HTMLButtonElement>('.which button').forEach((b) => {
    b.addEventListener('click', () => show(shown, b.dataset.which as Which));
  });
  // A click on the history plot shows that round.
  if (historyPlot && loop) {
    const hp = historyPlot;
    hp.over.addEventListener('click', () => {
      const idx = hp.cursor.idx;
      if (idx !== null && idx !== undefined) show(idx);
    });
  }
  view.fit(boundsOf(maps.map((mm) => mm.x.map((x, i) => [x, mm.y[i]]))));
  show(shown);

  /** Two frames, so what `show` changed is on the canvases. */
  const settled = async () => {
    await ready;
    surface?.render();
    await new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)));
  };
  window.formcam = {
    ready,
    duration_s: 0,
    seek: async () => { await ready; },
    round: async (k: number) => { show(k); await settled(); },
    show: async (w: Which) => { show(shown, w); await settled(); },
    state: () => ({
      time_s: 0,
      points: drawnPoints,
      sections: m.sections.length,
      round: loop ? shown : null,
      rounds: c.rounds.length,
      view: which,
      after_available: pairOf(shown).after !== null,
      max_abs_deviation: maxAbs(m.deviation),
      limit,
      surface: surface ? { ...surface.counts(), centre_px: surface.centrePixel() } : null,
      nodes: c.nodes ? { markers: { ...surface?.markers }, counts: c.nodes.counts, every: c.nodes.every } : null,
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
