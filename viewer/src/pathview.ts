// A winding result without a program (`/api/kind` = path): the mandrel
// with the pass of its path table, the band laid (the pass once per
// circuit) and the eye trajectory when the result has one, on the machine
// the result names at its first axes row (or alone), with the view
// buttons, the orbit, a slider that grows the band circuit by circuit and
// the winding plots. No timeline: nothing plays.
import './pathview.css';
import * as api from './api';
import { Scene } from './scene';
import type { View } from './scene';
import { WindingPlots } from './plots';

/** `/api/path` (generated from crates/formcam-view/src/pathview.rs). */
export type PathBody = api.PathBody;

/** What `window.formcam.state()` returns for this kind. */
export interface PathState {
  kind: 'path';
  /** Points of the path drawn on the mandrel, and in its table. */
  path_points: number;
  path_table_points: number;
  /** Band points drawn, of `band_total`. */
  band_points: number;
  band_total: number;
  /** Circuits of the band drawn, of `circuits`. */
  band_circuits: number;
  circuits: number;
  /** Points of the eye trajectory drawn. */
  eye_points: number;
  /** Links of the machine drawn (one bare link without a machine). */
  links: number;
  /** How the machine is posed. */
  pose: string;
  /** Plots drawn, by name, with the points of each series. */
  plots: Record<string, number[]>;
  camera: number[];
  target: number[];
}

const $ = <T extends HTMLElement>(id: string) => document.getElementById(id) as T;

/** Opens the path view in the 3-D page's frame; sets `window.formcam`. */
export async function openPath(ready: Promise<void>): Promise<void> {
  const [result, machine, mandrel, body] = await Promise.all([
    api.json<Record<string, unknown>>('/api/result'),
    api.json<api.MachineScene>('/api/machine'),
    api.mandrel(),
    api.json<PathBody>('/api/path'),
  ]);
  $('app').classList.add('path-only');
  const job = String(result.job ?? '').split(/[\\/]/).pop() ?? '';
  const on = body.pose === 'none' ? 'no machine' : `${machine.name} at ${body.pose}`;
  $('title').textContent = `${api.PAGE_NAME}: ${job} (path, no program), ${on}`;
  $('status').textContent = `path ${mandrel?.path_points ?? 0} points, ${body.band.circuits} circuits` +
    (body.eye ? `, eye ${body.eye.length} points` : '') +
    (body.pose === 'none' ? '' : '; machine shown still, not animated');

  const scene = new Scene($('stage'), machine, mandrel, machine.payout);
  const axes = machine.links.map(() => 0);
  scene.show({
    t: 0, block: 0, line: 0, axes, poses: body.poses,
    // The red marker at the eye's first point (where the circuit starts).
    points: machine.links.map(() => body.eye?.[0] ?? [0, 0, 0]),
  });
  if (body.eye) scene.addEye({ points: body.eye, times: [], ends: body.eye.length });
  // Without an eye nothing places the payout point: no marker.
  scene.showPayout(body.eye !== null);
  scene.addBand(body.band);
  const starts = body.band.layers;
  const total = body.band.points.length;
  let circuitsShown = body.band.circuits;
  const grow = (c: number) => {
    circuitsShown = Math.min(Math.max(Math.round(c), 0), body.band.circuits);
    scene.showLaid(circuitsShown >= starts.length ? total : starts[circuitsShown]);
    $('path-circuits').textContent = `${circuitsShown} / ${body.band.circuits} circuits`;
    ($('path-grow') as HTMLInputElement).value = String(circuitsShown);
    scene.dirty = true;
  };

  const bar = document.createElement('footer');
  bar.id = 'path-bar';
  bar.innerHTML = '<label>band <input id="path-grow" type="range" min="0" step="1" /></label>' +
    '<span id="path-circuits"></span>' +
    '<span id="path-note">the pass of path.csv laid once per circuit, each turned by 360°/circuits</span>';
  $('app').appendChild(bar);
  const slider = $('path-grow') as HTMLInputElement;
  slider.max = String(body.band.circuits);
  slider.value = String(body.band.circuits);
  slider.addEventListener('input', () => grow(Number(slider.value)));
  grow(body.band.circuits);

  const plots = new WindingPlots($('plots-panel'), $('plots-toggle'));
  for (const b of document.querySelectorAll<HTMLButtonElement>('#views button')) {
    b.addEventListener('click', () => scene.look(b.dataset.view as View));
  }
  scene.look('front');
  scene.render();
  let frames = 0;
  const frame = () => {
    if (scene.dirty) {
      scene.render();
      frames++;
    }
    requestAnimationFrame(frame);
  };
  requestAnimationFrame(frame);

  const state = (): PathState => {
    const c = scene.counts();
    return {
      kind: 'path',
      path_points: mandrel?.path.length ?? 0,
      path_table_points: mandrel?.path_points ?? 0,
      band_points: c.band_points,
      band_total: c.band_total,
      band_circuits: circuitsShown,
      circuits: body.band.circuits,
      eye_points: c.eye_points,
      links: machine.links.length,
      pose: body.pose,
      plots: window.formcamPlots?.series() ?? {},
      ...scene.view(),
    };
  };
  const none = async () => { await ready; };
  // The program view's calls that mean nothing here do nothing.
  Object.assign(window.formcam, {
    ready,
    duration_s: 0,
    seek: none,
    state,
    play: () => {},
    pause: () => {},
    frames: () => frames,
    follow: () => {},
    overlays: (show: { band?: boolean; eye?: boolean }) => {
      scene.overlays(show);
      scene.render();
    },
    /** Grows the band to its first `c` circuits (drawn at once). */
    grow: (c: number) => {
      grow(c);
      scene.render();
    },
    plots: () => plots.open(),
  });
}
