// Drives the page `formcam view` serves in headless Chromium (Debian's,
// through playwright-core): console errors, the canvas drawn and changed by
// a seek, the state shown at several seeks, screenshots of each view, time
// to interactive and frames per second while playing.
//
//   node viewer/tests/browser.mjs URL SCREENSHOT_DIR OUT_JSON [PLAY_SPEED]
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { chromium } from 'playwright-core';

const [url, shots, out, speedArg] = process.argv.slice(2);
if (!url || !shots || !out) {
  console.error('usage: node browser.mjs URL SCREENSHOT_DIR OUT_JSON [PLAY_SPEED]');
  process.exit(2);
}
mkdirSync(shots, { recursive: true });

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
const errors = [];
let step = 'launch';
// A page that stops answering fails the test instead of holding it.
const watchdog = setTimeout(() => {
  errors.push(`driver: no answer from the page within 300 s (at: ${step})`);
  writeFileSync(out, JSON.stringify({ errors }, null, 1));
  process.exit(1);
}, 40_000);
try {
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  page.setDefaultTimeout(120_000);
  page.on('console', (m) => { if (m.type() === 'error') errors.push(`console: ${m.text()}`); });
  page.on('pageerror', (e) => errors.push(`page: ${e}`));
  page.on('request', (r) => console.log('req', Date.now()%100000, r.url())); page.on('requestfinished', (r) => console.log('fin', Date.now()%100000, r.url())); page.on('requestfailed', (r) => errors.push(`request failed: ${r.url()}`));
  // Nothing is fetched from anywhere but the server.
  page.on('request', (r) => { if (!r.url().startsWith(url)) errors.push(`outside request: ${r.url()}`); });

  const opened = Date.now();
  step = 'open';
  await page.goto(url);
  await page.evaluate(() => window.formcam.ready);
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
  writeFileSync(out, JSON.stringify({ errors, tti_s, fps, speed, duration_s, before, after, states }, null, 1));
} catch (e) {
  errors.push(`driver: ${e}`);
  writeFileSync(out, JSON.stringify({ errors }, null, 1));
} finally {
  clearTimeout(watchdog);
  await browser.close();
}
