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
import { openPath } from './pathview';

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
  /** Shows or hides the band and the eye trajectory, drawn at once. */
  overlays(show: { band?: boolean; eye?: boolean }): void;
}

declare global {
  interface Window { formcam: FormcamApi }
}

/** Timeline samples asked for drawing (decimated; numbers shown at a seek are exact). */
const SAMPLES = 4000;

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
  const [result, machine, mandrel, tl, blocks, program] = await Promise.all([
    api.json<Record<string, unknown>>('/api/result'),
    api.json<api.MachineScene>('/api/machine'),
    api.mandrel(),
    api.json<TimelineBody>(`/api/timeline?samples=${SAMPLES}`),
    api.json<Blocks>('/api/blocks'),
    api.text('/api/program'),
  ]);
  // The overlays after the result (no more than six requests at once),
  // only those the result has: no request fails on a normal load.
  const has = await api.json<{ violations: boolean; eye: boolean; band: boolean }>('/api/overlays');
  const [violations, eye, band] = await Promise.all([
    has.violations ? api.optional<api.Violations>('/api/violations') : null,
    has.eye ? api.optional<api.EyeTrajectory>('/api/eye') : null,
    has.band ? api.optional<api.Band>('/api/band') : null,
  ]);
  const job = cleanPath(String(result.job ?? ''));
  $('title').textContent = `formcam view: ${job.split('/').pop() ?? ''} on ${machine.name}`;
  $('title').title = job;
  $('status').textContent = `${tl.blocks} blocks, ${tl.duration_s.toFixed(2)} s` +
    (mandrel ? `, path ${mandrel.path_points} points` : '');

  const scene = new Scene($('stage'), machine, mandrel, tl.payout);
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

  let alarm = { axes: new Set<string>(), links: new Set<string>() };
  const show = (s: Sample, t: number) => {
    shown = s;
    time = t;
    scene.show(s);
    if (s.laid !== undefined) scene.showLaid(s.laid);
    alarm = checks?.at(s, tl.axes) ?? alarm;
    scene.highlight(alarm.links);
    readouts(s, alarm.axes);
    programView.mark(s.line);
    plot?.at(s.t, s.axes);
    plots.at(s.t);
    ($('scrub') as HTMLInputElement).value = String(Math.round((t / Math.max(duration, 1e-9)) * 100000));
    ($('block') as HTMLInputElement).value = String(s.block);
    $('clock').textContent = `${clock(t)} / -${clock(duration - t)}`;
    $('program-line').textContent = s.line > 0 ? `line ${s.line}, block ${s.block}` : `block ${s.block}`;
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
  const blockStart = (b: number) => blocks.starts[Math.min(Math.max(b, 0), blocks.starts.length - 1)] ?? 0;

  const programView = new ProgramView($('program'), program, (line) => {
    // The block on that line, or the first after it.
    let lo = 0;
    let hi = blocks.lines.length;
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      if (blocks.lines[mid] < line) lo = mid + 1;
      else hi = mid;
    }
    void seek(blockStart(lo));
  });

  const setPlaying = (p: boolean) => {
    playing = p;
    $('play').textContent = p ? 'pause' : 'play';
  };
  $('play').addEventListener('click', () => {
    if (!playing && time >= duration) time = 0;
    setPlaying(!playing);
  });
  $('prev').addEventListener('click', () => { setPlaying(false); void seek(blockStart(shown.block - 1)); });
  $('next').addEventListener('click', () => { setPlaying(false); void seek(blockStart(shown.block + 1)); });
  $('scrub').addEventListener('input', (e) => {
    setPlaying(false);
    void seek((Number((e.target as HTMLInputElement).value) / 100000) * duration);
  });
  $('block').addEventListener('change', (e) => {
    setPlaying(false);
    void seek(blockStart(Number((e.target as HTMLInputElement).value)));
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
    const dt = (now - last) / 1000;
    last = now;
    if (playing) {
      const t = Math.min(time + dt * speed, duration);
      const s = held(t);
      if (s !== shown) show(s, t);
      else {
        time = t;
        $('clock').textContent = `${clock(t)} / -${clock(duration - t)}`;
      }
      if (t >= duration) setPlaying(false);
    }
    // Drawn only when something changed: a paused page costs nothing.
    if (playing || scene.dirty) {
      scene.render();
      frames++;
    }
    requestAnimationFrame(frame);
  };

  show(tl.samples[0], 0);
  scene.look('front');
  scene.render();
  requestAnimationFrame(frame);

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
  return (s, red) => cells.forEach((c, k) => {
    c.textContent = s.axes[k].toFixed(3);
    c.classList.toggle('alarm', red.has(tl.axes[k].name));
  });
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
 * view of a dressing or correction result in place of it. */
async function start(): Promise<void> {
  const { kind } = await api.json<{ kind: string }>('/api/kind');
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
