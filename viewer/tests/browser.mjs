// Drives the page `formcam view` serves in headless Chromium (Debian's,
// through playwright-core): console errors, the canvas drawn and changed by
// a seek, the state shown at several seeks, screenshots of each view, time
// to interactive and frames per second while playing; the eye trajectory
// and the band laid drawn (their pixels), the follow camera keeping the
// payout point centred; and, given a second view of a program that breaks a
// limit, its violations listed, marked and shown on the readouts, with the
// checks that ran (and why one did not) above them. Every
// request a page makes is followed to its end: a page not ready within
// READY_S fails naming the requests that never finished, and the whole run
// is bounded by TOTAL_S, so a stalled load fails instead of holding its
// caller.
//
//   node viewer/tests/browser.mjs URL SCREENSHOT_DIR OUT_JSON [PLAY_SPEED [VIOLATIONS_URL]]
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { launch } from './driver.mjs';
import { canvases } from './canvas.mjs';

/** Seconds the page has to become ready (`window.formcam.ready`). */
const READY_S = Number(process.env.FORMCAM_READY_S ?? 45);
/** Seconds the whole run may take. */
const TOTAL_S = 240;

const [url, shots, out, speedArg, violationsUrl] = process.argv.slice(2);
if (!url || !shots || !out) {
  console.error('usage: node browser.mjs URL SCREENSHOT_DIR OUT_JSON [PLAY_SPEED [VIOLATIONS_URL]]');
  process.exit(2);
}
mkdirSync(shots, { recursive: true });

const started = Date.now();
const errors = [];
let step = 'launch';
// Every request: its path, when it started and ended (ms from the start),
// its status and body size; `end` stays null for one that never finished.
const requests = [];
const byRequest = new Map();
const pathOf = (u) => (u.startsWith(url) ? `/${u.slice(url.length)}` : violationsUrl && u.startsWith(violationsUrl) ? `(violations) /${u.slice(violationsUrl.length)}` : u);
const unfinished = () => requests.filter((r) => r.end === null)
  .map((r) => `${r.path} (asked at ${(r.start / 1000).toFixed(1)} s${r.status ? `, status ${r.status} received` : ', no answer'})`);
const results = {};
const report = () => writeFileSync(out, JSON.stringify({ errors, requests, ...results }, null, 1));

// A run that stops answering fails instead of holding its caller.
const watchdog = setTimeout(() => {
  const open = unfinished();
  errors.push(`driver: not done within ${TOTAL_S} s (at: ${step})` +
    (open.length ? `; never finished: ${open.join(', ')}` : ''));
  report();
  console.error(errors.at(-1));
  process.exit(1);
}, TOTAL_S * 1000);

const browser = await launch();

/** A page whose every request is followed (see `requests`). */
const newPage = async (base) => {
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  page.setDefaultTimeout(60_000);
  page.on('console', (m) => { if (m.type() === 'error') errors.push(`console: ${m.text()}`); });
  page.on('pageerror', (e) => errors.push(`page: ${e}`));
  page.on('request', (r) => {
    // Nothing is fetched from anywhere but the server.
    if (!r.url().startsWith(base)) errors.push(`outside request: ${r.url()}`);
    const entry = { path: pathOf(r.url()), start: Date.now() - started, end: null, status: null, bytes: null };
    requests.push(entry);
    byRequest.set(r, entry);
  });
  page.on('response', (resp) => {
    const entry = byRequest.get(resp.request());
    if (entry) entry.status = resp.status();
  });
  page.on('requestfinished', async (r) => {
    const entry = byRequest.get(r);
    if (!entry) return;
    entry.end = Date.now() - started;
    try {
      entry.bytes = (await r.sizes()).responseBodySize;
    } catch {
      // The page may be gone; the size is only for the report.
    }
  });
  page.on('requestfailed', (r) => {
    const entry = byRequest.get(r);
    if (entry) entry.end = Date.now() - started;
    errors.push(`request failed: ${pathOf(r.url())} (${r.failure()?.errorText ?? 'no reason given'})`);
  });
  return page;
};

/** Opens `base` in `page` and waits for it to be ready, at most READY_S. */
const open = async (page, base) => {
  let timer;
  const late = new Promise((_, reject) => {
    timer = setTimeout(() => {
      const waiting = unfinished();
      reject(new Error(`the page was not ready within ${READY_S} s; ` +
        (waiting.length ? `never finished: ${waiting.join(', ')}` : 'every request finished')));
    }, READY_S * 1000);
  });
  try {
    await Promise.race([
      (async () => {
        await page.goto(base);
        await page.evaluate(() => window.formcam.ready);
      })(),
      late,
    ]);
  } finally {
    clearTimeout(timer);
  }
};

/** Seconds each case of `frameCosts` plays. */
const COST_S = 2;

/**
 * Where a frame's time goes while playing (measured, never asserted): per
 * phase of the page's animation loop (`window.formcamPerf`), the frames per
 * second with everything drawn, without the band and the eye trajectory,
 * with the 3-D scene bare (its background only), and the floor of this
 * browser's software GL: an empty WebGL canvas of the same size cleared
 * every frame in a page of its own.
 */
const frameCosts = async (page, speed) => {
  const play = (s) => page.evaluate(async ([s, ms]) => {
    const f = window.formcam;
    await f.seek(0);
    window.formcamPerf.reset();
    f.play(s);
    await new Promise((r) => setTimeout(r, ms));
    f.pause();
    const r = window.formcamPerf.report();
    return { fps: r.drawn / r.seconds, ...r };
  }, [s, COST_S * 1000]);
  const all = await play(speed);
  await page.evaluate(() => window.formcam.overlays({ band: false, eye: false }));
  const no_overlays = await play(speed);
  await page.evaluate(() => window.formcam.overlays({ band: true, eye: true }));
  await page.evaluate(() => window.formcamPerf.bare(true));
  const bare = await play(speed);
  await page.evaluate(() => window.formcamPerf.bare(false));
  const size = await page.evaluate(() => {
    const c = document.querySelector('#stage canvas');
    return [c.width, c.height];
  });
  const blank = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  const empty_webgl_fps = await blank.evaluate(async ([w, h, ms]) => {
    const c = document.createElement('canvas');
    c.width = w;
    c.height = h;
    document.body.appendChild(c);
    const gl = c.getContext('webgl2', { antialias: false, preserveDrawingBuffer: true });
    let n = 0;
    const t0 = performance.now();
    await new Promise((done) => {
      const tick = () => {
        gl.clearColor(0.87, 0.89, 0.92, 1);
        gl.clear(gl.COLOR_BUFFER_BIT);
        n++;
        if (performance.now() - t0 < ms) requestAnimationFrame(tick);
        else done();
      };
      requestAnimationFrame(tick);
    });
    return n / ((performance.now() - t0) / 1000);
  }, [size[0], size[1], COST_S * 1000]);
  await blank.close();
  return { canvas: size, all, no_overlays, bare, empty_webgl_fps };
};

try {
  const page = await newPage(url);

  const opened = Date.now();
  step = 'open';
  await open(page, url);
  const tti_s = (Date.now() - opened) / 1000;

  // The canvas as drawn: how many colours, and a hash of its pixels.
  const pixelsOf = async (p) => {
    const [{ colours, hash }] = await canvases(p, '#stage canvas');
    return { colours, hash };
  };
  const pixels = () => pixelsOf(page);
  const frame = (p) => p.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));

  const duration_s = await page.evaluate(() => window.formcam.duration_s);
  step = 'pixels';
  const before = await pixels();
  await page.screenshot({ path: join(shots, 'front-start.png') });
  step = 'seeks';
  const states = [];
  for (const f of [0.1, 0.37, 0.62, 0.9]) {
    await page.evaluate((t) => window.formcam.seek(t), f * duration_s);
    states.push(await page.evaluate(() => window.formcam.state()));
  }
  const after = await pixels();
  await page.screenshot({ path: join(shots, 'front-seek.png') });
  step = 'views';
  for (const view of ['top', 'axis']) {
    await page.click(`#views button[data-view="${view}"]`);
    await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
    await page.screenshot({ path: join(shots, `${view}.png`) });
  }
  step = 'overlays';
  // The band laid grows: little of it early, more late, all at the end.
  await page.click('#views button[data-view="front"]');
  const band = [];
  for (const f of [0.05, 0.5, 1]) {
    await page.evaluate((t) => window.formcam.seek(t), f * duration_s);
    const st = await page.evaluate(() => window.formcam.state());
    band.push({ at: f, band_points: st.band_points, band_total: st.band_total });
  }
  await page.evaluate((t) => window.formcam.seek(t), 0.5 * duration_s);
  await page.click('#views button[data-view="axis"]');
  await frame(page);
  await page.screenshot({ path: join(shots, 'band-half.png') });
  const drawn = await pixels();
  await page.evaluate(() => window.formcam.overlays({ band: false }));
  const noBand = await pixels();
  await page.evaluate(() => window.formcam.overlays({ band: true, eye: false }));
  const noEye = await pixels();
  await page.evaluate(() => window.formcam.overlays({ eye: true }));
  const overlays = {
    band,
    eye_points: (await page.evaluate(() => window.formcam.state())).eye_points,
    band_pixels_differ: drawn.hash !== noBand.hash,
    eye_pixels_differ: drawn.hash !== noEye.hash,
  };
  step = 'follow';
  // Following the payout point: it stays at the centre as the camera moves.
  await page.click('#views button[data-view="front"]');
  // Not at whole circuits: the payout point elsewhere at the two times.
  await page.evaluate((t) => window.formcam.seek(t), 0.23 * duration_s);
  const unfollowed = await page.evaluate(() => window.formcam.state());
  await page.evaluate(() => window.formcam.follow(true));
  await frame(page);
  const f1 = await page.evaluate(() => window.formcam.state());
  await page.evaluate((t) => window.formcam.seek(t), 0.71 * duration_s);
  await frame(page);
  const f2 = await page.evaluate(() => window.formcam.state());
  await page.screenshot({ path: join(shots, 'follow.png') });
  await page.evaluate(() => window.formcam.follow(false));
  const follow = {
    before_px: unfollowed.payout_px,
    px: [f1.payout_px, f2.payout_px],
    camera: [f1.camera, f2.camera],
    payout: [f1.payout, f2.payout],
    follow: f2.follow,
  };
  Object.assign(results, { overlays, follow });
  step = 'play';
  const speed = Number(speedArg ?? 10);
  const fps = await page.evaluate(async (s) => {
    const f = window.formcam;
    f.seek(0);
    f.play(s);
    const n0 = f.frames();
    const t0 = performance.now();
    await new Promise((r) => setTimeout(r, 3000));
    f.pause();
    return (f.frames() - n0) / ((performance.now() - t0) / 1000);
  }, speed);
  await page.screenshot({ path: join(shots, 'playing.png') });
  step = 'frame costs';
  const frame_costs = await frameCosts(page, speed);
  Object.assign(results, { tti_s, fps, speed, duration_s, before, after, states, frame_costs });
  // One page at a time: the first one's drawing would slow the second.
  await page.close();
  if (violationsUrl) {
    step = 'violations';
    const v = await newPage(violationsUrl);
    await open(v, violationsUrl);
    const listed = await v.$$eval('#violations li', (li) => li.map((x) => x.textContent));
    const marks = await v.$$eval('#marks .mark', (m) => m.length);
    // A mark goes to where its violation first happens.
    const api = await v.evaluate(async () => (await fetch('/api/violations')).json());
    const first = api.violations[0];
    // Which checks ran, and why one did not, as the section shows them.
    const ran = await v.evaluate(() => ({
      checks: document.querySelector('#violations-section .checks')?.textContent ?? null,
      unchecked: document.querySelector('#violations-section .unchecked')?.textContent ?? null,
    }));
    // Marks close in time overlap: the first one clicked as a user's click would.
    await v.evaluate(() => document.querySelector('#marks .mark').click());
    await v.waitForFunction((t) => Math.abs(window.formcam.state().time_s - t) < 1e-9, first.time_s);
    const at = await v.evaluate(() => window.formcam.state());
    const red = await v.$$eval('#readouts td.v.alarm', (c) => c.length);
    await v.screenshot({ path: join(shots, 'violations.png') });
    results.violations = {
      listed, marks, first, state: at, red_cells: red, ran, checks: api.checks, unchecked: api.unchecked,
    };
  }
  report();
} catch (e) {
  errors.push(`driver: ${e instanceof Error ? e.message : e} (at: ${step})`);
  report();
  console.error(errors.at(-1));
  process.exitCode = 1;
} finally {
  step = 'close';
  await browser.close();
  clearTimeout(watchdog);
}
