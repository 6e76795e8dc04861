// Drives the 2-D parts of the page `formcam view` serves in headless
// Chromium (Debian's, through playwright-core): a winding result's plots
// (and which checks its violations are of),
// a dressing result's animation (and the region removed so far), a
// correction result's deviation map (each round's, for a closed loop) and
// its surface in 3-D before and after the correction, and
// every plot's legend before the pointer comes. It writes what it saw as
// JSON (the Rust test asserts on it) and screenshots.
//
//   node viewer/tests/results.mjs KIND URL SCREENSHOT_DIR OUT_JSON
//   KIND: plots | dressing | correction | loop (a closed-loop simulation)
//         | path (a winding result without a program)
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { frames, launch, recordErrors } from './driver.mjs';
import { canvases } from './canvas.mjs';

const [kind, url, shots, out] = process.argv.slice(2);
if (!kind || !url || !shots || !out) {
  console.error('usage: node results.mjs plots|dressing|correction|loop|path URL SCREENSHOT_DIR OUT_JSON');
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

/** The value cells of every plot's legend, as shown (uPlot writes `--`
 * where it has no value). */
const legends = (page) => page.evaluate(() => [...document.querySelectorAll('.u-legend .u-value')]
  .map((c) => c.textContent));

/** The pixels of `rgb` (within 2 per channel) on the canvases matching `selector`. */
const pixelsOf = (page, selector, rgb) => page.evaluate(([sel, [r, g, b]]) => {
  let n = 0;
  for (const c of document.querySelectorAll(sel)) {
    const data = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    for (let i = 0; i < data.length; i += 4) {
      if (Math.abs(data[i] - r) <= 2 && Math.abs(data[i + 1] - g) <= 2 && Math.abs(data[i + 2] - b) <= 2) n++;
    }
  }
  return n;
}, [selector, rgb]);

try {
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  page.setDefaultTimeout(120_000);
  recordErrors(page, errors, url);
  step = 'open';
  await page.goto(url);
  await page.evaluate(() => window.formcam.ready);
  const report = { kind, errors };

  if (kind === 'plots') {
    step = 'plots';
    await page.click('#plots-toggle');
    await page.evaluate(() => window.formcamPlots.open());
    const duration = await page.evaluate(() => window.formcam.duration_s);
    await page.evaluate((t) => window.formcam.seek(t), 0.4 * duration);
    await frames(page);
    report.series = await page.evaluate(() => window.formcamPlots.series());
    // What the server sent, counted the same way.
    report.expected = await page.evaluate(async () => {
      const b = await (await fetch('/api/plots')).json();
      const e = {};
      if (b.meridian.length) {
        e.alpha = b.meridian.map((m) => m.alpha_deg.length);
        e.thickness = b.meridian.map((m) => m.thickness.length);
      }
      if (b.pull.length) e.pull = b.pull.map((p) => p.u.length);
      if (b.axes) {
        b.axes.names.forEach((n, k) => {
          e[`axis ${n}`] = [b.axes.position[k].length, b.axes.velocity[k].filter((v) => v !== null).length];
        });
        e.blocks = [b.axes.block_s.length];
      }
      return e;
    });
    report.legends = await legends(page);
    report.canvases = await canvases(page, '#plots-panel canvas');
    // Which checks the violations are of, as the section says.
    report.checks = await page.evaluate(async () => ({
      api: await (await fetch('api/violations')).json(),
      shown: document.querySelector('#violations-section .checks')?.textContent ?? null,
      unchecked: document.querySelector('#violations-section .unchecked')?.textContent ?? null,
    }));
    await page.screenshot({ path: join(shots, 'plots.png') });
    await page.evaluate(() => { document.querySelector('#plots-panel').scrollTop = 1e6; });
    await frames(page);
    await page.screenshot({ path: join(shots, 'plots-axes.png') });
  } else if (kind === 'path') {
    step = 'path';
    await frames(page);
    report.scene = await canvases(page, '#stage > canvas');
    await page.screenshot({ path: join(shots, 'path.png') });
    // Half the circuits of the band, then the plots.
    const circuits = await page.evaluate(() => window.formcam.state().circuits);
    await page.evaluate((c) => window.formcam.grow(c), Math.floor(circuits / 2));
    report.half = await page.evaluate(() => window.formcam.state());
    report.half_scene = await canvases(page, '#stage > canvas');
    await page.screenshot({ path: join(shots, 'path-half.png') });
    await page.evaluate((c) => window.formcam.grow(c), circuits);
    await page.click('#plots-toggle');
    await page.evaluate(() => window.formcamPlots.open());
    await frames(page);
    report.state = await page.evaluate(() => window.formcam.state());
    report.canvases = await canvases(page, '#plots-panel canvas');
    await page.screenshot({ path: join(shots, 'path-plots.png') });
    report.expected = await page.evaluate(async () => {
      const b = await (await fetch('/api/path')).json();
      const m = await (await fetch('/api/mandrel')).json();
      return { band: b.band.points.length, circuits: b.band.circuits, eye: b.eye ? b.eye.length : 0, path: m.path.length };
    });
  } else if (kind === 'dressing') {
    step = 'dressing';
    const duration = await page.evaluate(() => window.formcam.duration_s);
    const server = (t) => page.evaluate(async (tt) => (await (await fetch(`/api/dressing/sample?t=${tt}`)).json()), t);
    report.duration_s = duration;
    report.start = await page.evaluate(() => window.formcam.state());
    report.legends = await legends(page);
    report.first = await canvases(page, '#app2d canvas.view2d');
    const removed = () => pixelsOf(page, '#app2d canvas.view2d', report.start.removed_rgb);
    report.start.removed_px = await removed();
    await page.screenshot({ path: join(shots, 'dressing-start.png') });
    report.seeks = [];
    for (const f of [0.2, 0.45, 0.8]) {
      await page.evaluate((t) => window.formcam.seek(t), f * duration);
      const shown = await page.evaluate(() => window.formcam.state());
      report.seeks.push({ shown, server: await server(shown.time_s), removed_px: await removed() });
    }
    report.after = await canvases(page, '#app2d canvas.view2d');
    await page.screenshot({ path: join(shots, 'dressing-seek.png') });
    // Playing: the time and the dresser move on by themselves.
    step = 'play';
    await page.evaluate((t) => window.formcam.seek(t), 0.1 * duration);
    const before = await page.evaluate(() => window.formcam.state());
    await page.evaluate(() => window.formcam.play(5));
    await page.waitForTimeout(1500);
    const playing = await page.evaluate(() => window.formcam.state());
    await page.screenshot({ path: join(shots, 'dressing-playing.png') });
    await page.evaluate(() => window.formcam.pause());
    report.play = { before, playing };
    report.mrr = await canvases(page, '#app2d .mrr canvas');
  } else if (kind === 'correction' || kind === 'loop') {
    step = kind;
    await frames(page);
    report.state = await page.evaluate(() => window.formcam.state());
    report.legends = await legends(page);
    report.title = await page.evaluate(() => document.querySelector('#app2d header strong')?.textContent ?? '');
    report.map = await canvases(page, '#app2d canvas.view2d');
    report.sections = await canvases(page, '#app2d .sections canvas');
    report.history = await canvases(page, '#app2d .history canvas');
    report.study = await canvases(page, '#app2d .study canvas');
    await page.screenshot({ path: join(shots, `${kind}.png`) });
    if (kind === 'correction') {
      // The 3-D surface before and after the correction: the pixel at the
      // surface's centre, the canvases, the state.
      const seen = async (which) => {
        step = `3-D ${which}`;
        await page.evaluate((w) => window.formcam.show(w), which);
        const state = await page.evaluate(() => window.formcam.state());
        const centre = await page.evaluate(([x, y]) => {
          const c = document.querySelector('#app2d .surface3d canvas');
          const d = document.createElement('canvas');
          d.width = c.width;
          d.height = c.height;
          const g = d.getContext('2d');
          g.drawImage(c, 0, 0);
          return [...g.getImageData(x, y, 1, 1).data.slice(0, 3)];
        }, state.surface.centre_px);
        const surface = await canvases(page, '#app2d .surface3d canvas');
        const bar = await canvases(page, '#app2d canvas.colourbar');
        const map = await canvases(page, '#app2d canvas.view2d');
        await page.screenshot({ path: join(shots, `correction-${which}.png`) });
        return { state, centre, surface, bar, map };
      };
      report.before = await seen('before');
      report.after = await seen('after');
      report.back = await seen('before');
    }
    if (kind === 'loop') {
      // The first round's map: the deviations before correcting.
      step = 'round 0';
      await page.evaluate(() => window.formcam.round(0));
      await frames(page);
      report.round0 = { state: await page.evaluate(() => window.formcam.state()), map: await canvases(page, '#app2d canvas.view2d') };
      await page.screenshot({ path: join(shots, 'loop-round0.png') });
      // Round 0's after: round 1, the part of the first corrected program.
      step = 'round 0 after';
      await page.evaluate(() => window.formcam.show('after'));
      report.round0_after = { state: await page.evaluate(() => window.formcam.state()), surface: await canvases(page, '#app2d .surface3d canvas') };
      await page.screenshot({ path: join(shots, 'loop-round0-after.png') });
    }
  } else {
    errors.push(`driver: unknown kind ${kind}`);
  }
  writeFileSync(out, JSON.stringify(report, null, 1));
} catch (e) {
  errors.push(`driver: ${e}`);
  writeFileSync(out, JSON.stringify({ errors }, null, 1));
} finally {
  clearTimeout(watchdog);
  await browser.close();
}
