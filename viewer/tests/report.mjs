// Opens reports of `formcam report` from file:// URLs in headless Chromium
// (Debian's, through playwright-core) with every request that is not a
// file: aborted, and compares what each shows with what `formcam view`
// serves for the same result (fetched by node, not by the page). Writes
// what it saw as JSON (the Rust test asserts on it) and screenshots.
//
//   node viewer/tests/report.mjs SCREENSHOT_DIR OUT_JSON KIND=FILE=URL...
//   KIND: winding | dressing | correction; FILE: the report's path;
//   URL: `formcam view` of the same result.
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { frames, launch } from './driver.mjs';
import { pathToFileURL } from 'node:url';
import { canvases } from './canvas.mjs';

const [shots, out, ...runs] = process.argv.slice(2);
if (!shots || !out || runs.length === 0) {
  console.error('usage: node report.mjs SCREENSHOT_DIR OUT_JSON KIND=FILE=URL...');
  process.exit(2);
}
mkdirSync(shots, { recursive: true });

const browser = await launch();
const errors = [];
const report = { errors, results: {} };
let step = 'launch';
const watchdog = setTimeout(() => {
  errors.push(`driver: no answer from the page within 240 s (at: ${step})`);
  writeFileSync(out, JSON.stringify(report, null, 1));
  process.exit(1);
}, 240_000);

const server = async (url, path) => (await fetch(new URL(path, url))).json();

try {
  for (const run of runs) {
    const [kind, file, url] = run.split('=');
    step = `open ${kind}`;
    const r = { blocked: [] };
    report.results[kind] = r;
    const context = await browser.newContext({ viewport: { width: 1280, height: 800 } });
    const page = await context.newPage();
    page.setDefaultTimeout(120_000);
    // No network: anything but the file itself is aborted (and noted).
    await page.route('**/*', (route) => {
      const u = route.request().url();
      if (u.startsWith('file:')) return route.continue();
      r.blocked.push(u);
      return route.abort();
    });
    page.on('console', (m) => { if (m.type() === 'error') errors.push(`${kind} console: ${m.text()}`); });
    page.on('pageerror', (e) => errors.push(`${kind} page: ${e}`));
    await page.goto(pathToFileURL(file).href);
    await page.evaluate(() => window.formcam.ready);
    r.title = await page.title();
    r.heading = await page.evaluate(() => document.querySelector('#app:not([hidden]) header strong, #app2d:not([hidden]) header strong')?.textContent ?? '');
    const duration = await page.evaluate(() => window.formcam.duration_s);
    r.duration_s = duration;
    if (kind === 'winding') {
      step = 'winding';
      r.first = await canvases(page, '#stage canvas');
      r.seeks = [];
      for (const f of [0.13, 0.37, 0.71, 0.93]) {
        await page.evaluate((t) => window.formcam.seek(t), f * duration);
        await frames(page);
        const shown = await page.evaluate(() => window.formcam.state());
        r.seeks.push({ shown, server: await server(url, `/api/sample?t=${shown.time_s}`) });
      }
      r.axes = (await server(url, '/api/timeline?samples=2')).axes.map((a) => a.name);
      r.payout = (await server(url, '/api/timeline?samples=2')).payout;
      r.after = await canvases(page, '#stage canvas');
      await page.screenshot({ path: join(shots, 'report-winding.png') });
      step = 'plots';
      await page.click('#plots-toggle');
      await page.evaluate(() => window.formcamPlots.open());
      await frames(page);
      r.plots = await canvases(page, '#plots-panel canvas');
      await page.screenshot({ path: join(shots, 'report-plots.png') });
    } else if (kind === 'dressing') {
      step = 'dressing';
      r.first = await canvases(page, '#app2d canvas.view2d');
      r.seeks = [];
      for (const f of [0.2, 0.45, 0.8]) {
        await page.evaluate((t) => window.formcam.seek(t), f * duration);
        const shown = await page.evaluate(() => window.formcam.state());
        r.seeks.push({ shown, server: await server(url, `/api/dressing/sample?t=${shown.time_s}`) });
      }
      r.after = await canvases(page, '#app2d canvas.view2d');
      r.mrr = await canvases(page, '#app2d .mrr canvas');
      await page.screenshot({ path: join(shots, 'report-dressing.png') });
    } else if (kind === 'correction') {
      step = 'correction';
      await frames(page);
      r.state = await page.evaluate(() => window.formcam.state());
      const c = await server(url, '/api/correction');
      r.server_points = c.x.length;
      r.first = await canvases(page, '#app2d canvas.view2d');
      r.sections = await canvases(page, '#app2d .sections canvas');
      r.surface = await canvases(page, '#app2d .surface3d canvas');
      // After: the prediction inlined too.
      await page.evaluate(() => window.formcam.show('after'));
      r.after_state = await page.evaluate(() => window.formcam.state());
      r.after_surface = await canvases(page, '#app2d .surface3d canvas');
      await page.evaluate(() => window.formcam.show('before'));
      await page.screenshot({ path: join(shots, 'report-correction.png') });
    } else {
      errors.push(`driver: unknown kind ${kind}`);
    }
    await context.close();
  }
  writeFileSync(out, JSON.stringify(report, null, 1));
} catch (e) {
  errors.push(`driver: ${e}`);
  writeFileSync(out, JSON.stringify(report, null, 1));
} finally {
  clearTimeout(watchdog);
  await browser.close();
}
