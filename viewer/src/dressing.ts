// A dressing result (`/api/dressing`): the wheel's profile, the contour
// before dressing (profile and allowance) and after, the dresser's path per
// pass, and the dresser (point A, its dressing corner) moving along its
// path in the program's own time, the contour as cut so far (`forming.ts`)
// and the region removed so far growing behind it; zoom (wheel), pan
// (drag) and a reset of the view. The removal rate and the feed against Z,
// with feed control and without, their cursor at the dresser's Z; hovering
// them marks that Z on the profile. The program's text with the running
// block's line marked. `window.formcam` plays, pauses and seeks it; a seek
// shows the point the server computes (`/api/dressing/sample`).
import uPlot from 'uplot';
import * as api from './api';
import { View2d, boundsOf, esc } from './view2d';
import { COLOURS, chart, counts, cursorHook, legendAt } from './plots';
import { CutSoFar, sampleAt } from './forming';
import { ProgramView } from './program';

/** `/api/dressing` and `/api/dressing/sample` (generated from crates/formcam-view/src/dressing.rs). */
type DressingBody = api.DressingBody;
type DresserSample = api.DresserSample;

/** Where hovering a plot puts the marker on the profile. */
interface Marker {
  /** The Z hovered (the row's), mm. */
  z: number;
  /** The profile's X at that Z, mm (null outside it). */
  profile_x: number | null;
  /** The step of that row (0-based, `mrr.csv`'s order) and its point A `[z, x]`. */
  step: number;
  point_a: [number, number];
  /** Where the dressing corner was nearest the profile at that step: `[z, x]`. */
  contact: [number, number] | null;
  /** The marker's line on the profile's canvas, CSS px from its left. */
  px: number;
}

/** What `window.formcam.state()` returns for a dressing result. */
export interface DressingState {
  time_s: number;
  block: number;
  line: number;
  /** The pass of the block running (1-based, 0 before the first). */
  pass: number;
  /** Point A: [x (radial), z (axial)], mm. */
  dresser: [number, number];
  playing: boolean;
  speed: number;
  /** Plots and the points each series draws. */
  series: Record<string, number[]>;
  /** Per plot, each series' label and its points drawn. */
  plots: Record<string, Record<string, number>>;
  /** The colour of the region removed so far (opaque, drawn under the lines). */
  removed_rgb: [number, number, number];
  /** The area between the contour before dressing and the contour as cut, mm². */
  removed_mm2: number;
  /** The profile view's world rectangle in sight, mm. */
  view: { x0: number; x1: number; y0: number; y1: number };
  /** The marker hovering a plot put on the profile, or null. */
  marker: Marker | null;
  /** The Z of the plots' cursor (the dresser's), mm; their legends' row at rest. */
  plot_cursor_z: number;
  plot_row: number | null;
  /** The plots' Z range shown, mm. */
  plot_z: [number, number];
  /** The program line marked, and whether it is within the text's box. */
  marked_line: number;
  marked_in_sight: boolean;
}

/** The region removed so far: opaque, so that it can be told by its pixels. */
const REMOVED_RGB: [number, number, number] = [246, 178, 92];
/** The marker a plot's pointer puts on the profile. */
const MARKER = '#7b3294';
const CONTROLLED = COLOURS[0];
const UNCONTROLLED = COLOURS[4];
/** The speeds offered, times the program's own time. */
const SPEEDS = [0.01, 0.02, 0.05, 0.1, 0.25, 1, 4, 10, 100];
/** While playing, the text and plots beside the picture follow at most this often, ms. */
const TEXT_MS = 100;

/** The block running at `t`: the last starting at or before it. */
function blockAt(starts: number[], blocks: number, t: number): number {
  let lo = 0;
  let hi = blocks;
  while (lo < hi) {
    const mid = (lo + hi) >> 1;
    if (starts[mid] <= t) lo = mid + 1;
    else hi = mid;
  }
  return Math.max(0, lo - 1);
}

/** Opens the dressing view in `host`; resolves once drawn. */
export async function openDressing(host: HTMLElement, ready: Promise<void>): Promise<void> {
  const [summary, d] = await Promise.all([
    api.json<Record<string, unknown>>('/api/result'),
    api.json<DressingBody>('/api/dressing'),
  ]);
  host.innerHTML = `
    <header><strong>${api.PAGE_NAME}: dressing ${esc(String(summary.job ?? ''))}</strong>
      <span class="status">${d.passes.length} passes, ${d.lines.length} blocks, ${d.duration_s.toFixed(2)} s</span></header>
    <main class="drawing with-program"><div class="section-view">
        <div class="tools"><button class="fit" title="Back to the whole wheel (or double-click)">reset view</button></div></div>
      <div class="program-section"><h2>Program (program.mpf)</h2><div class="program"></div></div></main>
    <aside><section><h2>Removal rate against Z</h2><div class="mrr"></div></section>
      <section><h2>Feed against Z</h2><div class="feed"></div></section>
      <section><h2>Dresser</h2><table class="readout"></table></section>
      <section class="legend"></section></aside>
    <footer>
      <button class="play" title="Play or pause">play</button>
      <input class="scrub" type="range" min="0" max="100000" value="0" step="1" />
      <label>speed <select class="speed">${SPEEDS.map((v) => `<option value="${v}">${v}x</option>`).join('')}</select></label>
      <span class="clock"></span>
    </footer>`;
  const q = <T extends HTMLElement>(sel: string) => host.querySelector(sel) as T;
  const blocks = d.lines.length;
  const duration = d.duration_s;
  let shown: DresserSample = { t: 0, block: 0, line: d.lines[0] ?? 0, dresser: [d.points[0][1], d.points[0][0]] };
  let playing = false;
  // At first the whole program plays in about 20 s.
  let speed = SPEEDS.reduce((a, b) => (Math.abs(Math.log(b * 20 / duration)) < Math.abs(Math.log(a * 20 / duration)) ? b : a));
  let frames = 0;
  let marker: Marker | null = null;
  const passOf = (block: number) => d.block_pass[block] ?? 0;
  const passData = (p: number) => d.passes.find((x) => x.pass === p);
  const cut = new CutSoFar(d);
  const removedTotal = Number(summary.area_between_contours_mm2 ?? NaN);

  const colours = {
    profile: '#1b1f27', initial: '#8a6d3b', final: '#2ca02c', current: '#c2185b',
    toRemove: 'rgba(255, 170, 60, 0.15)', removed: `rgb(${REMOVED_RGB.join(', ')})`,
  };
  /** The region to remove: between the contour before and after. */
  const removal = (v: View2d, ctx: CanvasRenderingContext2D) => {
    const poly = [...d.initial, ...[...d.final_contour].reverse()];
    ctx.beginPath();
    if (poly.length < 3) return;
    ctx.moveTo(v.px(poly[0][0]), v.py(poly[0][1]));
    for (const [z, x] of poly) ctx.lineTo(v.px(z), v.py(x));
    ctx.closePath();
    ctx.fillStyle = colours.toRemove;
    ctx.fill();
  };
  /** The region removed so far: between the contour before and as cut,
   * one polygon per run of the grid where they differ. */
  const removed = (v: View2d, ctx: CanvasRenderingContext2D) => {
    const { z, initial, current } = cut;
    ctx.fillStyle = colours.removed;
    let i = 0;
    while (i < z.length) {
      if (initial[i] - current[i] <= 1e-7) { i++; continue; }
      const a = Math.max(i - 1, 0);
      while (i < z.length && initial[i] - current[i] > 1e-7) i++;
      const b = Math.min(i, z.length - 1);
      ctx.beginPath();
      ctx.moveTo(v.px(z[a]), v.py(initial[a]));
      for (let k = a + 1; k <= b; k++) ctx.lineTo(v.px(z[k]), v.py(initial[k]));
      for (let k = b; k >= a; k--) ctx.lineTo(v.px(z[k]), v.py(current[k]));
      ctx.closePath();
      ctx.fill();
    }
  };
  /** The contour as cut so far. */
  const currentLine = (v: View2d, ctx: CanvasRenderingContext2D) => {
    const { z, current } = cut;
    ctx.strokeStyle = colours.current;
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    ctx.moveTo(v.px(z[0]), v.py(current[0]));
    for (let i = 1; i < z.length; i++) ctx.lineTo(v.px(z[i]), v.py(current[i]));
    ctx.stroke();
  };
  /** The dressing corner (pass `p`'s) with point A at `[z, x]`. */
  /** (Its circle is not filled: the region removed under it shows.) */
  const corner = (v: View2d, ctx: CanvasRenderingContext2D, p: number, z: number, x: number, stroke: string) => {
    const pd = passData(p) ?? passData(1);
    if (!pd) return;
    const [oz, ox] = pd.corner_offset;
    ctx.strokeStyle = stroke;
    ctx.lineWidth = 2;
    ctx.beginPath();
    ctx.arc(v.px(z + oz), v.py(x + ox), Math.max(pd.corner_radius * v.pixelsPerMm, 1), 0, 2 * Math.PI);
    ctx.stroke();
    ctx.beginPath();
    ctx.moveTo(v.px(z + oz), v.py(x));
    ctx.lineTo(v.px(z), v.py(x));
    ctx.stroke();
  };
  const view = new View2d(q('.section-view'), (v, ctx) => {
    removal(v, ctx);
    removed(v, ctx);
    v.line(ctx, d.initial, colours.initial, 1.2);
    ctx.setLineDash([5, 4]);
    v.line(ctx, d.final_contour, colours.final, 1.2);
    ctx.setLineDash([]);
    v.line(ctx, d.profile, colours.profile, 1.5);
    currentLine(v, ctx);
    d.passes.forEach((p, k) => v.line(ctx, p.path, COLOURS[(k + 3) % COLOURS.length], 1));
    if (marker) {
      const m = marker;
      m.px = v.px(m.z);
      ctx.strokeStyle = MARKER;
      ctx.lineWidth = 1.5;
      ctx.setLineDash([6, 4]);
      ctx.beginPath();
      ctx.moveTo(m.px, 0);
      ctx.lineTo(m.px, v.canvas.clientHeight);
      ctx.stroke();
      ctx.setLineDash([]);
      corner(v, ctx, d.mrr.pass[m.step], m.point_a[0], m.point_a[1], MARKER);
      if (m.profile_x !== null) {
        ctx.beginPath();
        ctx.arc(m.px, v.py(m.profile_x), 5, 0, 2 * Math.PI);
        ctx.stroke();
      }
      ctx.fillStyle = MARKER;
      for (const [z, x] of m.contact ? [m.point_a, m.contact] : [m.point_a]) {
        ctx.beginPath();
        ctx.arc(v.px(z), v.py(x), 4, 0, 2 * Math.PI);
        ctx.fill();
      }
    }
    // The dresser at point A: its dressing corner and periphery.
    const [x, z] = shown.dresser;
    corner(v, ctx, passOf(shown.block), z, x, '#d62728');
    ctx.fillStyle = '#d62728';
    ctx.beginPath();
    ctx.arc(v.px(z), v.py(x), 4, 0, 2 * Math.PI);
    ctx.fill();
  }, ['Z (mm)', 'X (mm)']);
  view.fit(boundsOf([d.profile, d.initial]));
  q('.fit').addEventListener('click', () => view.reset());
  q('.legend').innerHTML =
    `<span style="color:${colours.profile}">— profile</span> ` +
    `<span style="color:${colours.initial}">— before (allowance)</span> ` +
    `<span style="color:${colours.current}">— as cut so far</span> ` +
    `<span style="color:${colours.final}">- - dressed</span> ` +
    `<span style="color:${colours.removed}">■ removed so far</span> ` +
    `<span style="color:#d62728">● point A, dressing corner</span> ` +
    `<span style="color:${MARKER}">┆ Z hovered on a plot</span><br>` +
    d.passes.map((p, k) => `<span style="color:${COLOURS[(k + 3) % COLOURS.length]}">— pass ${p.pass}</span>`).join(' ') +
    '<br><small>wheel: zoom, drag: pan, double-click or reset view: the whole wheel</small>';

  // The plots: one row per step, in order of Z, a series per pass.
  const m = d.mrr;
  const steps = m.z.length;
  const order = [...Array(steps).keys()].sort((a, b) => m.z[a] - m.z[b] || a - b);
  const rowOf = new Int32Array(steps);
  order.forEach((k, row) => { rowOf[k] = row; });
  const xs = order.map((k) => m.z[k]);
  const passNos = [...new Set(m.pass)];
  const column = (vals: (k: number) => number, p: number | null) =>
    order.map((k) => (p === null || m.pass[k] === p ? vals(k) : null));
  /** Steps of each pass: `[first, end)` in `mrr.csv`'s order. */
  const stepRange = new Map<number, [number, number]>();
  m.pass.forEach((p, k) => {
    const r = stepRange.get(p);
    if (r) r[1] = k + 1;
    else stepRange.set(p, [k, k + 1]);
  });
  /** The step at point A `[z, x]` in pass `p`: the nearest of its ends. */
  const stepAt = (p: number, z: number, x: number): number | null => {
    const r = stepRange.get(p);
    if (!r) return null;
    let best = r[0];
    let dist = Infinity;
    for (let k = r[0]; k < r[1]; k++) {
      const e = (m.z[k] - z) ** 2 + (m.x[k] - x) ** 2;
      if (e < dist) { dist = e; best = k; }
    }
    return best;
  };
  /** The profile's point nearest the dressing corner of pass `p` with point A at `[z, x]`. */
  const contact = (p: number, z: number, x: number): [number, number] | null => {
    const pd = passData(p);
    if (!pd) return null;
    const [cz, cx] = [z + pd.corner_offset[0], x + pd.corner_offset[1]];
    let best: [number, number] | null = null;
    let dist = Infinity;
    for (const [pz, px] of d.profile) {
      const e = (pz - cz) ** 2 + (px - cx) ** 2;
      if (e < dist) { dist = e; best = [pz, px]; }
    }
    return best;
  };
  let restRow: number | null = null;
  const cursorZ = () => shown.dresser[1];
  const hover = (u: uPlot) => {
    const idx = u.cursor.idx;
    const was = marker;
    if (idx === null || idx === undefined || idx < 0 || idx >= steps) marker = null;
    else {
      const k = order[idx];
      const z = m.z[k];
      const at = sampleAt(d.profile, Float64Array.of(z))[0];
      const inside = d.profile.length > 1 && z >= d.profile[0][0] && z <= d.profile[d.profile.length - 1][0];
      marker = { z, profile_x: inside ? at : null, step: k, point_a: [z, m.x[k]], contact: contact(m.pass[k], z, m.x[k]), px: view.px(z) };
    }
    if (was !== marker) view.draw();
  };
  const sync = { key: `dressing-${Math.random()}` };
  const plotSeries = (name: string, label: (p: number) => string) =>
    passNos.map((p) => ({ label: label(p), scale: name, spanGaps: false }));
  const mrrSeries: uPlot.Series[] = [{ label: 'Z (mm)' }];
  const mrrCols: (number | null)[][] = [];
  plotSeries('mrr', (p) => `with control, pass ${p}`).forEach((s, k) => {
    mrrSeries.push({ ...s, stroke: CONTROLLED, width: 1.5 });
    mrrCols.push(column((j) => m.mrr[j], passNos[k]));
  });
  plotSeries('mrr', (p) => `without control, pass ${p}`).forEach((s, k) => {
    mrrSeries.push({ ...s, stroke: UNCONTROLLED, width: 1, dash: [4, 3] });
    mrrCols.push(column((j) => m.mrr_uncontrolled[j], passNos[k]));
  });
  if (m.target !== null) {
    const target = m.target;
    mrrSeries.push({ label: 'target', scale: 'mrr', stroke: '#888', width: 1, dash: [2, 4] });
    mrrCols.push(column(() => target, null));
  }
  const feedSeries: uPlot.Series[] = [{ label: 'Z (mm)' }];
  const feedCols: (number | null)[][] = [];
  plotSeries('feed', (p) => `with control, pass ${p}`).forEach((s, k) => {
    feedSeries.push({ ...s, stroke: CONTROLLED, width: 1.5 });
    feedCols.push(column((j) => m.feed[j], passNos[k]));
  });
  if (m.feed_uncontrolled !== null) {
    const f0 = m.feed_uncontrolled;
    feedSeries.push({ label: 'without control', scale: 'feed', stroke: UNCONTROLLED, width: 1, dash: [4, 3] });
    feedCols.push(column(() => f0, null));
  }
  const plotOpts = (series: uPlot.Series[], scale: string, label: string) => ({
    scales: { x: { time: false } },
    series,
    cursor: { sync },
    axes: [{ label: 'Z of point A (mm)' }, { scale, label }],
    hooks: { draw: [cursorHook(cursorZ)], setCursor: [hover] },
  });
  const plots = [
    chart(q('.mrr'), '', plotOpts(mrrSeries, 'mrr', 'MRR (mm²/min)'), [xs, ...mrrCols] as uPlot.AlignedData, 190, () => restRow),
    chart(q('.feed'), '', plotOpts(feedSeries, 'feed', 'feed (mm/min)'), [xs, ...feedCols] as uPlot.AlignedData, 190, () => restRow),
  ];
  const probe = {
    mrr: counts(plots[0].data as (number | null)[][]),
    feed: counts(plots[1].data as (number | null)[][]),
    passes: d.passes.map((p) => p.path.length),
  };
  const labelled = (u: uPlot) => Object.fromEntries(u.series.slice(1).map((s, k) => [String(s.label), counts(u.data as (number | null)[][])[k]]));
  const plotProbe = { mrr: labelled(plots[0]), feed: labelled(plots[1]) };
  let plotsAt = { z: NaN, row: null as number | null, when: -Infinity };
  /** The plots' cursor and legends at the time shown. */
  const plotsFollow = () => {
    const p = passOf(shown.block);
    const k = p > 0 ? stepAt(p, shown.dresser[1], shown.dresser[0]) : null;
    restRow = k === null ? null : rowOf[k];
    const z = cursorZ();
    if (plots.some((u) => Math.round(u.valToPos(z, 'x')) !== Math.round(u.valToPos(plotsAt.z, 'x')))) {
      for (const u of plots) u.redraw(false, false);
    }
    if (restRow !== plotsAt.row) for (const u of plots) legendAt(u, restRow);
    plotsAt = { z, row: restRow, when: performance.now() };
  };

  const programHost = q('.program');
  const program = new ProgramView(programHost, d.program, (line) => {
    // The first block on that line or after it, half way through.
    let lo = 0;
    let hi = blocks;
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      if (d.lines[mid] < line) lo = mid + 1;
      else hi = mid;
    }
    const b = Math.min(lo, blocks - 1);
    setPlaying(false);
    void seek((d.t[b] + d.t[b + 1]) / 2);
  });

  const readout = q('.readout');
  let removedNow = 0;
  const texts = (s: DresserSample) => {
    const p = passOf(s.block);
    const k = p > 0 ? stepAt(p, s.dresser[1], s.dresser[0]) : null;
    const total = Number.isFinite(removedTotal) ? ` of ${removedTotal.toFixed(4)}` : '';
    readout.innerHTML = `<tr><td>Z</td><td>${s.dresser[1].toFixed(4)}</td><td>mm</td></tr>` +
      `<tr><td>X</td><td>${s.dresser[0].toFixed(4)}</td><td>mm</td></tr>` +
      `<tr><td>block</td><td>${s.block}</td><td>line ${s.line}, pass ${p}</td></tr>` +
      (k === null ? '' : `<tr><td>feed</td><td>${m.feed[k].toFixed(1)}</td><td>mm/min (without control ${m.feed_uncontrolled?.toFixed(1) ?? '-'})</td></tr>` +
        `<tr><td>MRR</td><td>${m.mrr[k].toFixed(3)}</td><td>mm²/min (without control ${m.mrr_uncontrolled[k].toFixed(3)})</td></tr>`) +
      `<tr><td>removed</td><td>${removedNow.toFixed(4)}</td><td>mm²${total}</td></tr>`;
    (q('.scrub') as HTMLInputElement).value = String(Math.round((s.t / Math.max(duration, 1e-9)) * 100000));
    q('.clock').textContent = `${s.t.toFixed(2)} s / -${(duration - s.t).toFixed(2)} s`;
    plotsFollow();
  };
  const show = (s: DresserSample, all = true) => {
    shown = s;
    cut.at(s.t, s.block);
    removedNow = cut.removed();
    program.mark(s.line);
    if (all || performance.now() - plotsAt.when >= TEXT_MS) texts(s);
    view.draw();
  };
  /** Point A at `t` from the blocks sent (drawing while playing). */
  const local = (t: number): DresserSample => {
    const tc = Math.min(Math.max(t, 0), duration);
    const b = blockAt(d.t, blocks, tc);
    const s = d.t[b];
    const e = d.t[b + 1];
    const f = e > s ? Math.min(Math.max((tc - s) / (e - s), 0), 1) : 1;
    const [z0, x0] = d.points[b];
    const [z1, x1] = d.points[b + 1];
    return { t: tc, block: b, line: d.lines[b], dresser: [x0 + f * (x1 - x0), z0 + f * (z1 - z0)] };
  };
  const seek = async (t: number) => {
    const tc = Math.min(Math.max(t, 0), duration);
    show(await api.json<DresserSample>(`/api/dressing/sample?t=${tc}`));
  };
  const setPlaying = (p: boolean) => {
    const was = playing;
    playing = p;
    q('.play').textContent = p ? 'pause' : 'play';
    if (was && !p) texts(shown);
  };
  q('.play').addEventListener('click', () => {
    if (!playing && shown.t >= duration) show(local(0));
    setPlaying(!playing);
  });
  q('.scrub').addEventListener('input', (e) => {
    setPlaying(false);
    void seek((Number((e.target as HTMLInputElement).value) / 100000) * duration);
  });
  const speedSelect = q('.speed') as HTMLSelectElement;
  speedSelect.value = String(speed);
  speedSelect.addEventListener('change', () => { speed = Number(speedSelect.value); });

  let last = performance.now();
  const frame = (now: number) => {
    const dt = (now - last) / 1000;
    last = now;
    if (playing) {
      const t = Math.min(shown.t + dt * speed, duration);
      show(local(t), false);
      frames++;
      if (t >= duration) setPlaying(false);
    }
    requestAnimationFrame(frame);
  };
  show(local(0));
  requestAnimationFrame(frame);

  const markedRow = () => programHost.querySelector<HTMLElement>('.row.current');
  window.formcam = {
    ready,
    duration_s: duration,
    seek,
    state: (): DressingState => {
      const row = markedRow();
      const box = programHost.getBoundingClientRect();
      const r = row?.getBoundingClientRect();
      const scale = plots[0].scales.x;
      return {
        time_s: shown.t, block: shown.block, line: shown.line, pass: passOf(shown.block), dresser: shown.dresser,
        playing, speed, series: probe, plots: plotProbe, removed_rgb: REMOVED_RGB, removed_mm2: removedNow,
        view: view.visible(), marker, plot_cursor_z: cursorZ(), plot_row: restRow,
        plot_z: [scale.min ?? NaN, scale.max ?? NaN],
        marked_line: Number(row?.dataset.line ?? 0),
        marked_in_sight: !!r && r.top >= box.top - 1 && r.bottom <= box.bottom + 1,
      };
    },
    play: (s?: number) => {
      if (s) {
        speed = s;
        if (![...speedSelect.options].some((o) => Number(o.value) === s)) speedSelect.add(new Option(`${+s.toPrecision(3)}x`, String(s)));
        speedSelect.value = String(s);
      }
      if (shown.t >= duration) show(local(0));
      setPlaying(true);
    },
    pause: () => setPlaying(false),
    frames: () => frames,
    resetView: () => view.reset(),
  } as unknown as Window['formcam'];
}
