// formcam view: the page. It loads the result from the server, draws the
// poses the server sent and plays the timeline; `window.formcam` lets tests
// seek and read what is shown.
import './style.css';
import * as api from './api';
import type { Blocks, Sample, TimelineBody } from './api';
import { Scene } from './scene';
import type { View } from './scene';
import { ViolationView } from './violations';
import { ProgramView } from './program';
import { AxesPlot } from './plot';
import { WindingPlots } from './plots';
import { openDressing } from './dressing';
import { openCorrection } from './correction';
import { FrameClock } from './perf';
import { openPath } from './pathview';
import { openStudio } from './studio';

/** What `window.formcam.state()` returns: the state shown. */
interface State {
  time_s: number;
  block: number;
  line: number;
  axes: Record<string, number>;
  payout: [number, number, number];
  /** Band points drawn (laid by then), of `band_total`. */
  band_points: number;
  band_total: number;
  /** Points of the eye trajectory drawn. */
  eye_points: number;
  /** Violations listed. */
  violations: number;
  /** Axes shown red (beyond a limit, or in a violation's block). */
  red_axes: string[];
  /** Links highlighted (a collision at the time shown). */
  highlighted: string[];
  /** Whether the camera follows the payout point. */
  follow: boolean;
  /** The camera's position and target, world mm. */
  camera: number[];
  target: number[];
  /** The payout point in the picture, px from the canvas's centre. */
  payout_px: [number, number];
  /** Triangles of the mesh solids drawn, what the page says about them
   * (unreadable, thinned), and each one's centre in the picture, px. */
  mesh_triangles: number;
  mesh_notes: string[];
  mesh_px: [number, number][];
}

interface FormcamApi {
  ready: Promise<void>;
  duration_s: number;
  seek(t_s: number): Promise<void>;
  state(): State | null;
  play(speed?: number): void;
  pause(): void;
  /** Frames drawn since the page opened (for measuring). */
  frames(): number;
  /** Turns following the payout point on or off. */
  follow(on: boolean): void;
  /** Shows or hides the band, the eye trajectory and the mesh solids, drawn at once. */
  overlays(show: { band?: boolean; eye?: boolean; meshes?: boolean }): void;
}

declare global {
  interface Window { formcam: FormcamApi }
}

/** Timeline samples asked for drawing (decimated; numbers shown at a seek are exact). */
const SAMPLES = 4000;
/**
 * While playing, the text beside the picture (readouts, program line and
 * text, plots' cursors, clock, timeline bar) follows at most this often, ms:
 * each change of it is repainted, in software without a GPU.
 */
const TEXT_MS = 100;
/**
 * While playing, the plots' cursors move at most this often, ms: a move
 * redraws the whole plot (every series), the costliest text beside the
 * picture.
 */
const PLOT_MS = 500;

const $ = <T extends HTMLElement>(id: string) => document.getElementById(id) as T;

let readyResolve: () => void = () => {};
let readyReject: (e: unknown) => void = () => {};
const ready = new Promise<void>((res, rej) => {
  readyResolve = res;
  readyReject = rej;
});

window.formcam = {
  ready,
  duration_s: 0,
  seek: async () => { await ready; },
  state: () => null,
  play: () => {},
  pause: () => {},
  frames: () => 0,
  follow: () => {},
  overlays: () => {},
};

async function main(): Promise<void> {
  const [result, machine, mandrel, tl, program] = await Promise.all([
    api.json<Record<string, unknown>>('/api/result'),
    api.json<api.MachineScene>('/api/machine'),
    api.mandrel(),
    api.json<TimelineBody>(`/api/timeline?samples=${SAMPLES}`),
    api.text('/api/program'),
  ]);
  // The overlays after the result (no more than six requests at once),
  // only those the result has: no request fails on a normal load.
  const has = await api.json<api.Overlays>('/api/overlays');
  const [violations, eye, band] = await Promise.all([
    has.violations ? api.optional<api.Violations>('/api/violations') : null,
    has.eye ? api.optional<api.EyeTrajectory>('/api/eye') : null,
    has.band ? api.optional<api.Band>('/api/band') : null,
  ]);
  const job = cleanPath(String(result.job ?? ''));
  $('title').textContent = `${api.PAGE_NAME}: ${job.split('/').pop() ?? ''} on ${machine.name}`;
  $('title').title = job;
  $('status').textContent = `${tl.blocks} blocks, ${tl.duration_s.toFixed(2)} s` +
    (mandrel ? `, path ${mandrel.path_points} points` : '');

  const scene = new Scene($('stage'), machine, mandrel, tl.payout);
  await scene.meshesLoaded;
  if (eye) scene.addEye(eye);
  if (band) scene.addBand(band);
  const readouts = readoutTable(tl);
  let plot: AxesPlot | null = null;
  try {
    plot = new AxesPlot($('plot'), tl);
  } catch (e) {
    console.warn('plot', e);
  }
  const plots = new WindingPlots($('plots-panel'), $('plots-toggle'));

  const duration = tl.duration_s;
  let shown: Sample = tl.samples[0];
  let time = 0;
  let playing = false;
  let speed = 1;
  let frames = 0;

  const perf = new FrameClock();
  let alarm = { axes: new Set<string>(), links: new Set<string>() };
  const put = changes();
  let texted = -Infinity;
  let plotted = -Infinity;
  /** The text beside the picture at the state shown (`now`: at once, else at most every TEXT_MS). */
  const texts = (now: boolean) => {
    const at = performance.now();
    if (!now && at - texted < TEXT_MS) return;
    texted = at;
    const s = shown;
    // The program's scroll first, while the page's layout is clean: moving
    // it after another write would make the browser lay the page out at once.
    programView.mark(s.line);
    perf.lap('program');
    readouts(s, alarm.axes);
    perf.lap('readouts');
    if (now || at - plotted >= PLOT_MS) {
      plotted = at;
      plot?.at(s.t, s.axes);
      plots.at(s.t);
    }
    perf.lap('plots');
    put.value('scrub', String(Math.round((time / Math.max(duration, 1e-9)) * 100000)));
    put.value('block', String(s.block));
    put.text('clock', `${clock(time)} / -${clock(duration - time)}`);
    put.text('program-line', s.line > 0 ? `line ${s.line}, block ${s.block}` : `block ${s.block}`);
  };
  /** Shows `s` at `t`; `animating`: a frame of the animation (the text may wait). */
  const show = (s: Sample, t: number, animating = false) => {
    shown = s;
    time = t;
    scene.show(s);
    perf.lap('poses');
    if (s.laid !== undefined) scene.showLaid(s.laid);
    perf.lap('band');
    alarm = checks?.at(s, tl.axes) ?? alarm;
    scene.highlight(alarm.links);
    perf.lap('checks');
    texts(!animating);
  };
  /** The sample held at `t` while playing: the last one at or before it. */
  const held = (t: number) => {
    const n = tl.samples.length;
    const k = Math.min(n - 1, Math.max(0, Math.floor((t / Math.max(duration, 1e-12)) * (n - 1) + 1e-9)));
    return tl.samples[k];
  };
  /** The exact state at `t`, computed by the server. */
  const seek = async (t: number) => {
    const tc = Math.min(Math.max(t, 0), duration);
    const s = await api.json<Sample>(`/api/sample?t=${tc}`);
    scene.clearTrail();
    show(s, tc);
    // Drawn now, not at the next animation frame (which a hidden page never gets).
    scene.render();
  };
  const checks = violations
    ? new ViolationView($('violations'), $('marks'), violations, duration, (t) => {
      setPlaying(false);
      void seek(t);
    })
    : null;
  // Every block's start and line (MB for 10^5 blocks): asked for when the
  // page is idle or a control first needs them, not before it is ready.
  let blocks: Promise<Blocks> | null = null;
  const blocksNow = () => (blocks ??= api.json<Blocks>('/api/blocks').catch((e) => {
    // Asked again next time.
    blocks = null;
    throw e;
  }));
  const toBlock = (b: number) => void blocksNow().then((bs) =>
    seek(bs.starts[Math.min(Math.max(b, 0), bs.starts.length - 1)] ?? 0));

  const programView = new ProgramView($('program'), program, (line) => {
    // The block on that line, or the first after it.
    void blocksNow().then((bs) => {
      let lo = 0;
      let hi = bs.lines.length;
      while (lo < hi) {
        const mid = (lo + hi) >> 1;
        if (bs.lines[mid] < line) lo = mid + 1;
        else hi = mid;
      }
      toBlock(lo);
    });
  });

  const setPlaying = (p: boolean) => {
    const was = playing;
    playing = p;
    $('play').textContent = p ? 'pause' : 'play';
    // Stopped: the text where the picture is (it may have lagged while playing).
    if (was && !p) texts(true);
  };
  $('play').addEventListener('click', () => {
    if (!playing && time >= duration) time = 0;
    setPlaying(!playing);
  });
  $('prev').addEventListener('click', () => { setPlaying(false); toBlock(shown.block - 1); });
  $('next').addEventListener('click', () => { setPlaying(false); toBlock(shown.block + 1); });
  // The value asked for is read before stopping (which writes the time shown).
  $('scrub').addEventListener('input', (e) => {
    const f = Number((e.target as HTMLInputElement).value) / 100000;
    setPlaying(false);
    void seek(f * duration);
  });
  $('block').addEventListener('change', (e) => {
    const b = Number((e.target as HTMLInputElement).value);
    setPlaying(false);
    toBlock(b);
  });
  $('speed').addEventListener('change', (e) => { speed = Number((e.target as HTMLSelectElement).value); });
  for (const b of document.querySelectorAll<HTMLButtonElement>('#views button')) {
    b.addEventListener('click', () => {
      scene.look(b.dataset.view as View);
      ($('follow') as HTMLInputElement).checked = false;
    });
  }
  $('follow').addEventListener('change', (e) => scene.setFollow((e.target as HTMLInputElement).checked));

  let last = performance.now();
  const frame = (now: number) => {
    perf.begin();
    const dt = (now - last) / 1000;
    last = now;
    if (playing) {
      const t = Math.min(time + dt * speed, duration);
      const s = held(t);
      perf.lap('sample');
      if (s !== shown) show(s, t, true);
      else {
        time = t;
        texts(false);
      }
      perf.lap('controls');
      if (t >= duration) setPlaying(false);
    }
    // Drawn only when something changed (a new sample, the camera moved):
    // a paused page, or one between samples, costs nothing.
    if (scene.dirty) {
      scene.render();
      frames++;
      perf.draw();
    }
    perf.lap('render');
    perf.end();
    requestAnimationFrame(frame);
  };
  window.formcamPerf = {
    reset: () => perf.reset(),
    report: () => perf.report(),
    bare: (on) => {
      scene.bare(on);
      scene.render();
    },
  };

  show(tl.samples[0], 0);
  scene.look('front');
  scene.render();
  requestAnimationFrame(frame);
  if ('requestIdleCallback' in window) requestIdleCallback(() => void blocksNow(), { timeout: 5000 });

  window.formcam = {
    ready,
    duration_s: duration,
    seek,
    state: () => ({
      time_s: shown.t,
      block: shown.block,
      line: shown.line,
      axes: Object.fromEntries(tl.axes.map((a, k) => [a.name, shown.axes[k]])),
      payout: shown.points[tl.payout] as [number, number, number],
      ...scene.counts(),
      violations: checks?.count ?? 0,
      red_axes: [...alarm.axes],
      highlighted: scene.highlightedLinks(),
      follow: scene.follow,
      ...scene.view(),
      payout_px: scene.payoutOffset(),
      ...scene.meshes(),
    }),
    follow: (on: boolean) => {
      ($('follow') as HTMLInputElement).checked = on;
      scene.setFollow(on);
      scene.render();
    },
    overlays: (show) => {
      scene.overlays(show);
      scene.render();
    },
    play: (s?: number) => {
      if (s) speed = s;
      if (time >= duration) time = 0;
      setPlaying(true);
    },
    pause: () => setPlaying(false),
    frames: () => frames,
  };
}

function readoutTable(tl: TimelineBody): (s: Sample, red: Set<string>) => void {
  const table = $('readouts');
  const cells = tl.axes.map((a) => {
    const tr = document.createElement('tr');
    const name = document.createElement('td');
    name.textContent = a.name;
    const v = document.createElement('td');
    v.className = 'v';
    const unit = document.createElement('td');
    unit.textContent = a.unit === 'deg' ? '°' : 'mm';
    tr.append(name, v, unit);
    table.appendChild(tr);
    return v;
  });
  // Written only where they change: no style or layout work for the rest.
  const text: string[] = [];
  const alarm: boolean[] = [];
  return (s, red) => cells.forEach((c, k) => {
    const v = s.axes[k].toFixed(3);
    if (v !== text[k]) c.textContent = text[k] = v;
    const r = red.has(tl.axes[k].name);
    if (r !== alarm[k]) c.classList.toggle('alarm', (alarm[k] = r));
  });
}

/** Writers of elements' text and inputs' values that touch the page only on a change. */
function changes(): { text(id: string, v: string): void; value(id: string, v: string): void } {
  const last = new Map<string, string>();
  const changed = (key: string, v: string) => {
    if (last.get(key) === v) return false;
    last.set(key, v);
    return true;
  };
  return {
    text: (id, v) => { if (changed(`t:${id}`, v)) $(id).textContent = v; },
    // An input's own value (a user may have moved it since).
    value: (id, v) => {
      const input = $(id) as HTMLInputElement;
      if (input.value !== v) input.value = v;
    },
  };
}

/** A path with `.` and `dir/..` steps taken out, `/` between names. */
function cleanPath(p: string): string {
  const abs = p.startsWith('/');
  const out: string[] = [];
  for (const part of p.split(/[\\/]+/)) {
    if (part === '' || part === '.') continue;
    if (part === '..' && out.length > 0 && out[out.length - 1] !== '..') out.pop();
    else if (part !== '..' || !abs) out.push(part);
  }
  return (abs ? '/' : '') + out.join('/');
}

function clock(t: number): string {
  const s = Math.max(0, t);
  const m = Math.floor(s / 60);
  return `${m}:${(s - 60 * m).toFixed(1).padStart(4, '0')}`;
}

/** The view of the result's kind: a winding result's 3-D view, or the 2-D
 * view of a dressing or correction result in place of it; or the studio. */
async function start(): Promise<void> {
  // `formcam studio` answers `studio`, a result's view its kind.
  const { kind } = await api.json<{ kind: api.ResultKind | 'studio' }>('/api/kind');
  if (kind === 'studio') {
    // `formcam studio`: the job editor, results shown in a frame of their own.
    $('app').hidden = true;
    return openStudio($('studio'));
  }
  if (kind === 'winding') return main();
  if (kind === 'path') return openPath(ready);
  $('app').hidden = true;
  const host = $('app2d');
  host.hidden = false;
  return kind === 'dressing' ? openDressing(host, ready) : openCorrection(host, ready);
}

start().then(readyResolve, (e) => {
  $('status').textContent = String(e);
  console.error(e);
  readyReject(e);
});
