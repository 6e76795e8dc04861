// A dressing result (`/api/dressing`): the wheel's profile, the contour
// before dressing (profile and allowance) and after, the dresser's path per
// pass, and the dresser (point A, its dressing corner) moving along its
// path in the program's own time, the region it has removed so far growing
// behind it; the removal rate and feed against Z.
// `window.formcam` plays and seeks it; a seek shows the point the server
// computes (`/api/dressing/sample`).
import uPlot from 'uplot';
import * as api from './api';
import { View2d, boundsOf, esc } from './view2d';
import { COLOURS, align, chart, counts } from './plots';

/** `/api/dressing` (crates/formcam-view/src/dressing.rs). */
interface DressingBody {
  profile: number[][];
  initial: number[][];
  final_contour: number[][];
  passes: { pass: number; path: number[][]; corner_offset: [number, number]; corner_radius: number }[];
  mrr: { pass: number[]; z: number[]; mrr: number[]; feed: number[] };
  duration_s: number;
  t: number[];
  points: number[][];
  lines: number[];
  program: string;
}

/** `/api/dressing/sample`. */
interface DresserSample { t: number; block: number; line: number; dresser: [number, number] }

/** What `window.formcam.state()` returns for a dressing result. */
export interface DressingState {
  time_s: number;
  block: number;
  line: number;
  /** Point A: [x (radial), z (axial)], mm. */
  dresser: [number, number];
  /** Plots and the points each series draws. */
  series: Record<string, number[]>;
  /** The colour of the region removed so far (opaque, drawn under the lines). */
  removed_rgb: [number, number, number];
}

/** The region removed so far: opaque, so that it can be told by its pixels. */
const REMOVED_RGB: [number, number, number] = [246, 178, 92];

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
    <main class="drawing"></main>
    <aside><section><h2>Removal rate and feed against Z</h2><div class="mrr"></div></section>
      <section><h2>Dresser</h2><table class="readout"></table></section>
      <section class="legend"></section></aside>
    <footer>
      <button class="play" title="Play or pause">play</button>
      <input class="scrub" type="range" min="0" max="100000" value="0" step="1" />
      <label>speed <select class="speed">
        <option value="0.1">0.1x</option><option value="1" selected>1x</option>
        <option value="10">10x</option><option value="100">100x</option></select></label>
      <span class="clock"></span>
    </footer>`;
  const q = <T extends HTMLElement>(sel: string) => host.querySelector(sel) as T;
  const blocks = d.lines.length;
  const duration = d.duration_s;
  let shown: DresserSample = { t: 0, block: 0, line: d.lines[0] ?? 0, dresser: [d.points[0][1], d.points[0][0]] };
  let playing = false;
  let speed = 1;
  let frames = 0;
  const passOf = (block: number) => {
    // The pass whose path holds point A at the block's end (nearest start).
    const [z, x] = d.points[Math.min(block + 1, d.points.length - 1)];
    let best = 0;
    let dist = Infinity;
    d.passes.forEach((p, k) => p.path.forEach(([pz, px]) => {
      const e = (pz - z) ** 2 + (px - x) ** 2;
      if (e < dist) { dist = e; best = k; }
    }));
    return best;
  };
  const passCache = new Map<number, number>();
  const pass = (block: number) => {
    let p = passCache.get(block);
    if (p === undefined) { p = passOf(block); passCache.set(block, p); }
    return p;
  };

  const colours = {
    profile: '#1b1f27', initial: '#8a6d3b', final: '#2ca02c',
    toRemove: 'rgba(255, 170, 60, 0.15)', removed: `rgb(${REMOVED_RGB.join(', ')})`,
  };
  /** The region to remove: between the contour before and after. */
  const removal = (v: View2d, ctx: CanvasRenderingContext2D) => {
    const poly = [...d.initial, ...[...d.final_contour].reverse()];
    ctx.beginPath();
    if (poly.length < 3) return false;
    ctx.moveTo(v.px(poly[0][0]), v.py(poly[0][1]));
    for (const [z, x] of poly) ctx.lineTo(v.px(z), v.py(x));
    ctx.closePath();
    return true;
  };
  /** What the dressing corner has swept up to the time shown (the blocks
   * that take time: feed moves; a rapid move cuts nothing), as strokes as
   * wide as the corner with round ends: the corner's disc moved along. */
  const swept = (v: View2d, ctx: CanvasRenderingContext2D) => {
    const s = shown;
    const [az, ax] = [s.dresser[1], s.dresser[0]];
    ctx.strokeStyle = colours.removed;
    ctx.fillStyle = colours.removed;
    ctx.lineCap = 'round';
    ctx.lineJoin = 'round';
    // Block b's move of the corner's centre (point A plus the corner's
    // offset in the block's pass), from its start to `to` (point A).
    const stroke = (b: number, to: [number, number]) => {
      const p = d.passes[pass(b)];
      const [oz, ox] = p ? p.corner_offset : [0, 0];
      ctx.lineWidth = Math.max(2 * (p?.corner_radius ?? 0) * v.pixelsPerMm, 1);
      ctx.beginPath();
      ctx.moveTo(v.px(d.points[b][0] + oz), v.py(d.points[b][1] + ox));
      ctx.lineTo(v.px(to[0] + oz), v.py(to[1] + ox));
      ctx.stroke();
    };
    for (let b = 0; b < s.block && b < blocks; b++) {
      if (d.t[b + 1] > d.t[b]) stroke(b, [d.points[b + 1][0], d.points[b + 1][1]]);
    }
    if (s.block < blocks && d.t[s.block + 1] > d.t[s.block] && s.t > d.t[s.block]) stroke(s.block, [az, ax]);
  };
  const view = new View2d(q('.drawing'), (v, ctx) => {
    // The region to remove, and within it what is removed so far.
    if (removal(v, ctx)) {
      ctx.fillStyle = colours.toRemove;
      ctx.fill();
      ctx.save();
      ctx.clip();
      swept(v, ctx);
      ctx.restore();
    }
    v.line(ctx, d.initial, colours.initial, 1.2);
    v.line(ctx, d.final_contour, colours.final, 1.2);
    v.line(ctx, d.profile, colours.profile, 1.5);
    d.passes.forEach((p, k) => v.line(ctx, p.path, COLOURS[(k + 3) % COLOURS.length], 1));
    // The dresser at point A: its dressing corner and periphery.
    const [x, z] = shown.dresser;
    const p = d.passes[pass(shown.block)];
    if (p) {
      const [oz, ox] = p.corner_offset;
      const r = p.corner_radius * v.pixelsPerMm;
      ctx.strokeStyle = '#d62728';
      ctx.fillStyle = 'rgba(214, 39, 40, 0.15)';
      ctx.lineWidth = 2;
      ctx.beginPath();
      ctx.arc(v.px(z + oz), v.py(x + ox), Math.max(r, 1), 0, 2 * Math.PI);
      ctx.fill();
      ctx.stroke();
      ctx.beginPath();
      ctx.moveTo(v.px(z + oz), v.py(x));
      ctx.lineTo(v.px(z), v.py(x));
      ctx.stroke();
    }
    ctx.fillStyle = '#d62728';
    ctx.beginPath();
    ctx.arc(v.px(z), v.py(x), 4, 0, 2 * Math.PI);
    ctx.fill();
  }, ['Z (mm)', 'X (mm)']);
  view.fit(boundsOf([d.profile, d.initial]));
  q('.legend').innerHTML =
    `<span style="color:${colours.profile}">— profile</span> ` +
    `<span style="color:${colours.initial}">— before (allowance)</span> ` +
    `<span style="color:${colours.final}">— dressed</span> ` +
    `<span style="color:${colours.removed}">■ removed so far</span> ` +
    `<span style="color:#d62728">● point A, dressing corner</span><br>` +
    d.passes.map((p, k) => `<span style="color:${COLOURS[(k + 3) % COLOURS.length]}">— pass ${p.pass}</span>`).join(' ') +
    '<br><small>wheel: zoom, drag: pan, double-click: fit</small>';

  // The removal rate and feed against Z, one series per pass.
  const passes = [...new Set(d.mrr.pass)];
  const per = (vals: number[]) => passes.map((p) => vals.filter((_, i) => d.mrr.pass[i] === p));
  const xs = per(d.mrr.z);
  const series: uPlot.Series[] = [{ label: 'Z (mm)' }];
  passes.forEach((p, k) => {
    series.push({ label: `MRR pass ${p}`, stroke: COLOURS[k % COLOURS.length], width: 1, scale: 'mrr', spanGaps: true });
  });
  passes.forEach((p, k) => {
    series.push({ label: `feed pass ${p}`, stroke: COLOURS[(k + 4) % COLOURS.length], width: 1, dash: [4, 3], scale: 'feed', spanGaps: true });
  });
  const mrrData = align([...xs, ...xs], [...per(d.mrr.mrr), ...per(d.mrr.feed)]);
  const mrrHost = q('.mrr');
  const mrrPlot = chart(mrrHost, '', {
    scales: { x: { time: false } },
    series,
    axes: [{ label: 'Z (mm)' }, { scale: 'mrr', label: 'MRR (mm²/min)' },
      { scale: 'feed', label: 'feed (mm/min)', side: 1, grid: { show: false } }],
  }, mrrData as uPlot.AlignedData, 260);
  const probe = { mrr: counts(mrrPlot.data as (number | null)[][]), passes: d.passes.map((p) => p.path.length) };

  const readout = q('.readout');
  const show = (s: DresserSample) => {
    shown = s;
    readout.innerHTML = `<tr><td>Z</td><td>${s.dresser[1].toFixed(4)}</td><td>mm</td></tr>` +
      `<tr><td>X</td><td>${s.dresser[0].toFixed(4)}</td><td>mm</td></tr>` +
      `<tr><td>block</td><td>${s.block}</td><td>line ${s.line}</td></tr>`;
    (q('.scrub') as HTMLInputElement).value = String(Math.round((s.t / Math.max(duration, 1e-9)) * 100000));
    q('.clock').textContent = `${s.t.toFixed(2)} s / -${(duration - s.t).toFixed(2)} s`;
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
    playing = p;
    q('.play').textContent = p ? 'pause' : 'play';
  };
  q('.play').addEventListener('click', () => {
    if (!playing && shown.t >= duration) show(local(0));
    setPlaying(!playing);
  });
  q('.scrub').addEventListener('input', (e) => {
    setPlaying(false);
    void seek((Number((e.target as HTMLInputElement).value) / 100000) * duration);
  });
  q('.speed').addEventListener('change', (e) => { speed = Number((e.target as HTMLSelectElement).value); });

  let last = performance.now();
  const frame = (now: number) => {
    const dt = (now - last) / 1000;
    last = now;
    if (playing) {
      const t = Math.min(shown.t + dt * speed, duration);
      show(local(t));
      frames++;
      if (t >= duration) setPlaying(false);
    }
    requestAnimationFrame(frame);
  };
  show(local(0));
  requestAnimationFrame(frame);

  window.formcam = {
    ready,
    duration_s: duration,
    seek,
    state: () => ({
      time_s: shown.t, block: shown.block, line: shown.line, dresser: shown.dresser, series: probe, removed_rgb: REMOVED_RGB,
    }),
    play: (s?: number) => {
      if (s) speed = s;
      if (shown.t >= duration) show(local(0));
      setPlaying(true);
    },
    pause: () => setPlaying(false),
    frames: () => frames,
  } as unknown as Window['formcam'];
}
