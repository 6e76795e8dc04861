// Drives a dressing result's page (`formcam view OUT`) in headless Chromium
// (Debian's, through playwright-core): pausing and resuming the animation
// (by `window.formcam` and by the button), the contour as cut so far
// through the program, zoom, pan and the view's reset, the plots' pointer
// marking its Z on the profile, the program line marked, and the series
// with and without feed control. It writes what it saw as JSON (the Rust
// test, crates/formcam-cli/tests/view.rs, asserts on it) and screenshots
// `dressing-*.png`.
//
//   node viewer/tests/dressing.mjs URL SCREENSHOT_DIR OUT_JSON
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { frames, launch, recordErrors } from './driver.mjs';
import { canvases } from './canvas.mjs';

const [url, shots, out] = process.argv.slice(2);
if (!url || !shots || !out) {
  console.error('usage: node dressing.mjs URL SCREENSHOT_DIR OUT_JSON');
  process.exit(2);
}
mkdirSync(shots, { recursive: true });

const browser = await launch();
const errors = [];
let step = 'launch';
const watchdog = setTimeout(() => {
  errors.push(`driver: no answer from the page within 240 s (at: ${step})`);
  writeFileSync(out, JSON.stringify({ errors }, null, 1));
  process.exit(1);
}, 240_000);

const state = (page) => page.evaluate(() => window.formcam.state());
const server = async (path) => (await fetch(new URL(path, url))).json();

/** Pixels within `tol` per channel of `rgb` on the canvases matching
 * `selector`, in all and per column (CSS px, the canvas's own columns
 * divided by the device pixel ratio). */
const pixelsOf = (page, selector, rgb, tol = 2) => page.evaluate(([sel, [r, g, b], t]) => {
  let n = 0;
  const columns = {};
  for (const c of document.querySelectorAll(sel)) {
    const data = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    const ratio = c.width / Math.max(c.clientWidth, 1);
    for (let i = 0; i < data.length; i += 4) {
      if (Math.abs(data[i] - r) <= t && Math.abs(data[i + 1] - g) <= t && Math.abs(data[i + 2] - b) <= t) {
        n++;
        const col = Math.round(((i / 4) % c.width) / ratio);
        columns[col] = (columns[col] ?? 0) + 1;
      }
    }
  }
  return { n, columns };
}, [selector, rgb, tol]);

try {
  const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
  page.setDefaultTimeout(120_000);
  recordErrors(page, errors, url);
  step = 'open';
  await page.goto(url);
  await page.evaluate(() => window.formcam.ready);
  const report = { errors };
  const body = await server('api/dressing');
  const summary = await server('api/result');
  const duration = body.duration_s;
  // What the server sent: the steps of each pass, the passes' contours.
  const passes = [...new Set(body.mrr.pass)];
  report.sent = {
    duration_s: duration,
    steps: Object.fromEntries(passes.map((p) => [p, body.mrr.pass.filter((q) => q === p).length])),
    all_steps: body.mrr.z.length,
    contours: body.contours.length,
    feed_uncontrolled: body.mrr.feed_uncontrolled,
    target: body.mrr.target,
    area_between_mm2: summary.area_between_contours_mm2,
    z: body.mrr.z,
  };
  await frames(page);
  report.start = await state(page);
  await page.screenshot({ path: join(shots, 'dressing-open.png') });

  // Pause and resume: by `window.formcam`, then by the button.
  step = 'pause';
  await page.evaluate((t) => window.formcam.seek(t), 0.1 * duration);
  const started = (await state(page)).time_s;
  /** Waits until the time shown has moved past `t` (a loaded machine draws few frames). */
  const after = (t) => page.waitForFunction((tt) => window.formcam.state().time_s > tt, t, { timeout: 30_000 });
  await page.evaluate((s) => window.formcam.play(s), duration / 30);
  await after(started);
  const running = await state(page);
  await page.evaluate(() => window.formcam.pause());
  const paused = await state(page);
  await page.waitForTimeout(300);
  const still = await state(page);
  await page.evaluate(() => window.formcam.play());
  await after(still.time_s);
  const resumed = await state(page);
  await page.screenshot({ path: join(shots, 'dressing-resumed.png') });
  await page.click('#app2d button.play');
  const buttonPaused = await state(page);
  await page.waitForTimeout(300);
  const buttonStill = await state(page);
  await page.click('#app2d button.play');
  await after(buttonStill.time_s);
  const buttonResumed = await state(page);
  await page.evaluate(() => window.formcam.pause());
  report.pause = { started, running, paused, still, resumed, buttonPaused, buttonStill, buttonResumed };

  // The contour as cut so far, through the program.
  step = 'forming';
  const removedRgb = report.start.removed_rgb;
  report.forming = [];
  for (const f of [0, 0.1, 0.25, 0.4, 0.55, 0.7, 0.85, 1]) {
    await page.evaluate((t) => window.formcam.seek(t), f * duration);
    const s = await state(page);
    report.forming.push({
      f, time_s: s.time_s, pass: s.pass, removed_mm2: s.removed_mm2,
      removed_px: (await pixelsOf(page, '#app2d canvas.view2d', removedRgb)).n,
    });
    if (f === 0.25) await page.screenshot({ path: join(shots, 'dressing-forming.png') });
  }

  // At each pass's end: the area removed by then, and the simulation's
  // (the sum of `mrr.csv`'s step areas of the passes so far).
  step = 'pass ends';
  const mrrCsv = (await (await fetch(new URL('files/mrr.csv', url))).text()).trim().split('\n');
  const head = mrrCsv[0].split(',');
  const [ai, pi] = [head.indexOf('area'), head.indexOf('pass')];
  const rows = mrrCsv.slice(1).map((l) => l.split(','));
  report.pass_ends = [];
  for (const p of passes) {
    let end = -1;
    body.block_pass.forEach((q, b) => { if (q === p && body.t[b + 1] > body.t[b]) end = b; });
    await page.evaluate((t) => window.formcam.seek(t), body.t[end + 1]);
    const s = await state(page);
    const simulated = rows.filter((r) => Number(r[pi]) <= p).reduce((a, r) => a + Number(r[ai]), 0);
    report.pass_ends.push({ pass: p, time_s: s.time_s, removed_mm2: s.removed_mm2, simulated_mm2: simulated });
  }

  // The program's line of the block shown, marked and in sight; a click
  // on a line goes there.
  step = 'program';
  report.program = [];
  for (const f of [0.3, 0.9, 0.05]) {
    await page.evaluate((t) => window.formcam.seek(t), f * duration);
    await frames(page);
    const s = await state(page);
    const text = await page.evaluate(() => document.querySelector('#app2d .program .row.current')?.textContent ?? '');
    report.program.push({ line: s.line, marked_line: s.marked_line, marked_in_sight: s.marked_in_sight, text });
  }
  const programRows = await page.$$('#app2d .program .row');
  const pick = programRows[Math.min(programRows.length - 1, 12)];
  const picked = Number(await pick.getAttribute('data-line'));
  await pick.click();
  await page.waitForFunction((l) => window.formcam.state().line >= l, picked);
  report.clicked = { picked, state: await state(page) };

  // Zoom (the wheel over the profile), pan (a drag), reset.
  step = 'zoom';
  await page.evaluate((t) => window.formcam.seek(t), 0.3 * duration);
  await frames(page);
  const canvas = await page.$('#app2d canvas.view2d');
  const box = await canvas.boundingBox();
  const fitted = { view: (await state(page)).view, canvas: (await canvases(page, '#app2d canvas.view2d'))[0] };
  await page.mouse.move(box.x + box.width * 0.6, box.y + box.height * 0.4);
  await page.mouse.wheel(0, -600);
  await frames(page);
  const zoomed = { view: (await state(page)).view, canvas: (await canvases(page, '#app2d canvas.view2d'))[0] };
  await page.screenshot({ path: join(shots, 'dressing-zoom.png') });
  await page.mouse.move(box.x + box.width * 0.5, box.y + box.height * 0.5);
  await page.mouse.down();
  await page.mouse.move(box.x + box.width * 0.5 + 120, box.y + box.height * 0.5 + 40, { steps: 5 });
  await page.mouse.up();
  await frames(page);
  const panned = { view: (await state(page)).view };
  await page.click('#app2d button.fit');
  await frames(page);
  const reset = { view: (await state(page)).view, canvas: (await canvases(page, '#app2d canvas.view2d'))[0] };
  report.zoom = { fitted, zoomed, panned, reset, width_px: box.width };

  // Hovering a plot marks its Z on the profile; the dresser moves the plots' cursor.
  step = 'linked';
  await page.evaluate((t) => window.formcam.seek(t), 0.4 * duration);
  await frames(page);
  report.cursor = await state(page);
  const over = await page.$('#app2d .mrr .u-over');
  await over.scrollIntoViewIfNeeded();
  const ob = await over.boundingBox();
  report.hover = [];
  for (const f of [0.3, 0.7]) {
    await page.mouse.move(ob.x + f * ob.width, ob.y + ob.height / 2);
    await frames(page);
    const s = await state(page);
    const column = s.marker ? await pixelsOf(page, '#app2d canvas.view2d', [0x7b, 0x32, 0x94], 6) : { n: 0, columns: {} };
    const near = s.marker ? Object.entries(column.columns)
      .filter(([c]) => Math.abs(Number(c) - s.marker.px) <= 1.5).reduce((a, [, n]) => a + n, 0) : 0;
    report.hover.push({ f, width_px: ob.width, marker: s.marker, plot_z: s.plot_z, marker_px_column: near });
    if (f === 0.3) await page.screenshot({ path: join(shots, 'dressing-linked.png') });
  }
  await page.mouse.move(box.x + 5, box.y + 5);
  await frames(page);
  report.hover_off = (await state(page)).marker;

  // Both control series drawn: their colours on the plots.
  step = 'series';
  report.plots = (await state(page)).plots;
  report.colours = {
    controlled: (await pixelsOf(page, '#app2d .mrr canvas', [0x1f, 0x77, 0xb4], 40)).n,
    uncontrolled: (await pixelsOf(page, '#app2d .mrr canvas', [0xff, 0x7f, 0x0e], 40)).n,
    feed_controlled: (await pixelsOf(page, '#app2d .feed canvas', [0x1f, 0x77, 0xb4], 40)).n,
    feed_uncontrolled: (await pixelsOf(page, '#app2d .feed canvas', [0xff, 0x7f, 0x0e], 40)).n,
  };
  report.legends = await page.evaluate(() => [...document.querySelectorAll('#app2d .u-legend .u-value')].map((c) => c.textContent));
  await page.screenshot({ path: join(shots, 'dressing-plots.png') });
  writeFileSync(out, JSON.stringify(report, null, 1));
} catch (e) {
  errors.push(`driver: ${e}`);
  writeFileSync(out, JSON.stringify({ errors }, null, 1));
} finally {
  clearTimeout(watchdog);
  await browser.close();
}
