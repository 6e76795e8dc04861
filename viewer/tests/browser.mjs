// Drives the page `formcam view` serves in headless Chromium (Debian's,
// through playwright-core): console errors, the canvas drawn and changed by
// a seek, the state shown at several seeks, screenshots of each view, time
// to interactive and frames per second while playing. Every request the
// page makes is followed to its end: a page not ready within READY_S fails
// naming the requests that never finished, and the whole run is bounded by
// TOTAL_S, so a stalled load fails instead of holding its caller.
//
//   node viewer/tests/browser.mjs URL SCREENSHOT_DIR OUT_JSON [PLAY_SPEED]
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { chromium } from 'playwright-core';

/** Seconds the page has to become ready (`window.formcam.ready`). */
const READY_S = Number(process.env.FORMCAM_READY_S ?? 45);
/** Seconds the whole run may take. */
const TOTAL_S = 150;

const [url, shots, out, speedArg] = process.argv.slice(2);
if (!url || !shots || !out) {
  console.error('usage: node browser.mjs URL SCREENSHOT_DIR OUT_JSON [PLAY_SPEED]');
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
const pathOf = (u) => (u.startsWith(url) ? `/${u.slice(url.length)}` : u);
const unfinished = () => requests.filter((r) => r.end === null)
  .map((r) => `${r.path} (asked at ${(r.start / 1000).toFixed(1)} s${r.status ? `, status ${r.status} received` : ', no answer'})`);
const report = (extra) => writeFileSync(out, JSON.stringify({ errors, requests, ...extra }, null, 1));

// A run that stops answering fails instead of holding its caller.
const watchdog = setTimeout(() => {
  const open = unfinished();
  errors.push(`driver: not done within ${TOTAL_S} s (at: ${step})` +
    (open.length ? `; never finished: ${open.join(', ')}` : ''));
  report({});
  console.error(errors.at(-1));
  process.exit(1);
}, TOTAL_S * 1000);

const browser = await chromium.launch({
  executablePath: process.env.FORMCAM_CHROMIUM ?? '/usr/bin/chromium',
  headless: true,
  args: [
    '--no-sandbox',
    '--disable-background-networking',
    '--use-angle=swiftshader',
    '--enable-unsafe-swiftshader',
    '--ignore-gpu-blocklist',
  ],
});
try {
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  page.setDefaultTimeout(60_000);
  page.on('console', (m) => { if (m.type() === 'error') errors.push(`console: ${m.text()}`); });
  page.on('pageerror', (e) => errors.push(`page: ${e}`));
  page.on('request', (r) => {
    // Nothing is fetched from anywhere but the server.
    if (!r.url().startsWith(url)) errors.push(`outside request: ${r.url()}`);
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

const opened = Date.now();
  step = 'open';
  let timer;
  const late = new Promise((_, reject) => {
    timer = setTimeout(() => {
      const open = unfinished();
      reject(new Error(`the page was not ready within ${READY_S} s; ` +
        (open.length ? `never finished: ${open.join(', ')}` : 'every request finished')));
    }, READY_S * 1000);
  });
  try {
    await Promise.race([
      (async () => {
        await page.goto(url);
        await page.evaluate(() => window.formcam.ready);
      })(),
      late,
    ]);
  } finally {
    clearTimeout(timer);
  }
  const tti_s = (Date.now() - opened) / 1000;

  // The canvas as drawn: how many colours, and a hash of its pixels.
  const pixels = () => page.evaluate(() => {
    const c = document.querySelector('#stage canvas');
    const d = document.createElement('canvas');
    d.width = c.width;
    d.height = c.height;
    const x = d.getContext('2d');
    x.drawImage(c, 0, 0);
    const data = x.getImageData(0, 0, d.width, d.height).data;
    const colours = new Set();
    let hash = 0;
    for (let i = 0; i < data.length; i += 4) {
      const v = (data[i] << 16) | (data[i + 1] << 8) | data[i + 2];
      if (i % 28 === 0) colours.add(v);
      hash = (Math.imul(hash, 31) + v) >>> 0;
    }
    return { colours: colours.size, hash };
  });

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
  report({ tti_s, fps, speed, duration_s, before, after, states });
} catch (e) {
  errors.push(`driver: ${e instanceof Error ? e.message : e} (at: ${step})`);
  report({});
  console.error(errors.at(-1));
  process.exitCode = 1;
} finally {
  step = 'close';
  await browser.close();
  clearTimeout(watchdog);
}
