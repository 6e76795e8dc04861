// Compares two runs of `formcam studio` in headless Chromium (Debian's,
// through playwright-core). Through the studio's HTTP API it runs the job
// FILE as it is and again with one value changed (`TABLE.FIELD=VALUE`),
// polling the status until each is done, and, given OTHER, runs that job
// (of another kind) too, and again with its value changed when one is
// given; then it opens the page, compares the two winding
// runs (`window.formcamStudio.compare`, as ticking both in the runs list
// does) and reads what the comparison shows (`window.formcamCompare`): the
// table's rows and the differing ones, each plot's series, and the pixels
// of the first plot's colour with only run A's series shown (solid), only
// run B's (dashed) and both; then the first run against OTHER's (the table
// only), OTHER's two runs, and THIRD's two (a third kind) when given. It
// writes what it saw as JSON (the Rust test asserts on it) and
// screenshots.
//
//   node viewer/tests/compare.mjs URL SCREENSHOT_DIR OUT_JSON FILE TABLE.FIELD=VALUE
//     [OTHER [TABLE.FIELD=VALUE [THIRD TABLE.FIELD=VALUE]]]
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { frames, launch } from './driver.mjs';

const [url, shots, out, file, change, other, otherChange, third, thirdChange] = process.argv.slice(2);
if (!url || !shots || !out || !file || !change?.includes('=')) {
  console.error('usage: node compare.mjs URL SCREENSHOT_DIR OUT_JSON FILE TABLE.FIELD=VALUE [OTHER [TABLE.FIELD=VALUE [THIRD TABLE.FIELD=VALUE]]]');
  process.exit(2);
}
mkdirSync(shots, { recursive: true });

/** Seconds a run may take before the driver gives up on it. */
const RUN_S = 180;
const errors = [];
let step = 'start';
const report = { errors };
const watchdog = setTimeout(() => {
  errors.push(`driver: not done within 280 s (at: ${step})`);
  writeFileSync(out, JSON.stringify(report, null, 1));
  process.exit(1);
}, 280_000);

/** `path` on the studio as JSON; a status other than 200 is an error naming it. */
const api = async (path, body) => {
  const r = await fetch(url + path, body === undefined ? {} : {
    method: 'POST', headers: { 'content-type': 'application/json' }, body: JSON.stringify(body),
  });
  const text = await r.text();
  if (r.status !== 200) throw new Error(`${path}: ${r.status} ${text.trim()}`);
  return JSON.parse(text);
};

/** Runs `job` (as `/api/studio/job` answers it) and waits until it is done: the run's name. */
const run = async (job) => {
  const { run: name } = await api('api/studio/run', { file: job.file, kind: job.kind, text: job.text, values: job.values });
  const t0 = Date.now();
  for (;;) {
    const s = await api('api/studio/status');
    if (s.run === name && s.state === 'done') return name;
    if (s.run === name && (s.state === 'failed' || s.state === 'cancelled')) {
      throw new Error(`run ${name} ${s.state}: ${s.error ?? ''}`);
    }
    if (Date.now() - t0 > RUN_S * 1000) throw new Error(`run ${name} not done within ${RUN_S} s: ${JSON.stringify(s)}`);
    await new Promise((r) => setTimeout(r, 200));
  }
};

/** `job` with `TABLE.FIELD=VALUE` set in its form values. */
const edited = (job, set) => {
  const [key, value] = set.split('=');
  const [table, field] = key.split('.');
  const values = structuredClone(job.values);
  values[table] = { ...(values[table] ?? {}), [field]: Number.isNaN(Number(value)) ? value : Number(value) };
  return { ...job, values };
};

/** The pixels near `rgb` (channel differences summing to at most 60) on the canvases matching `sel`. */
const pixelsNear = (page, sel, rgb) => page.evaluate(([s, [r, g, b]]) => {
  let n = 0;
  for (const c of document.querySelectorAll(s)) {
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    for (let i = 0; i < d.length; i += 4) {
      if (Math.abs(d[i] - r) + Math.abs(d[i + 1] - g) + Math.abs(d[i + 2] - b) <= 60) n++;
    }
  }
  return n;
}, [sel, rgb]);

const browser = await launch();
try {
  step = 'runs';
  const job = await api(`api/studio/job?file=${encodeURIComponent(file)}`);
  const a = await run(job);
  const b = await run(edited(job, change));
  report.runs = [a, b];
  const [table, field] = change.split('=')[0].split('.');
  report.changed = { table, field, from: job.values[table]?.[field] ?? null, to: edited(job, change).values[table][field] };
  let c = null;
  let d = null;
  if (other) {
    const otherJob = await api(`api/studio/job?file=${encodeURIComponent(other)}`);
    c = await run(otherJob);
    report.runs.push(c);
    if (otherChange) {
      d = await run(edited(otherJob, otherChange));
      report.runs.push(d);
    }
  }
  const pair = [];
  if (third && thirdChange) {
    const thirdJob = await api(`api/studio/job?file=${encodeURIComponent(third)}`);
    pair.push(await run(thirdJob), await run(edited(thirdJob, thirdChange)));
    report.runs.push(...pair);
  }
  report.listed = (await api('api/studio/runs')).map((r) => r.name);

  step = 'open';
  const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
  page.setDefaultTimeout(60_000);
  page.on('console', (m) => { if (m.type() === 'error') errors.push(`console: ${m.text()}`); });
  page.on('pageerror', (e) => errors.push(`page: ${e}`));
  page.on('requestfailed', (r) => errors.push(`request failed: ${r.url()}`));
  page.on('response', (r) => { if (r.status() >= 400) errors.push(`${r.status()}: ${r.request().method()} ${r.url()}`); });
  page.on('request', (r) => { if (!r.url().startsWith(url)) errors.push(`outside request: ${r.url()}`); });
  await page.goto(url);
  // Set once the page knows it is the studio's (`api/kind`).
  await page.waitForFunction(() => window.formcamStudio !== undefined);
  await page.evaluate(() => window.formcamStudio.ready);

  step = 'compare';
  report.state = await page.evaluate((names) => window.formcamStudio.compare(...names), [a, b]);
  await frames(page);
  report.dom = await page.evaluate(() => ({
    rows: document.querySelectorAll('#studio .compare .values tbody tr').length,
    differ: [...document.querySelectorAll('#studio .compare .values tr.differ')].map((tr) => [...tr.cells].map((td) => td.textContent)),
    note: document.querySelector('#studio .compare header .note')?.textContent ?? '',
    canvases: document.querySelectorAll('#studio .compare .plots canvas').length,
    legend: [...document.querySelectorAll('#studio .compare .plots .cell:first-child .u-legend .u-series th')].map((th) => th.textContent),
  }));
  await page.screenshot({ path: join(shots, 'compare-winding.png') });
  // Only the differing rows, as the box shows them.
  await page.click('#studio .compare header .only-differ');
  report.dom.visible_rows = await page.evaluate(() => [...document.querySelectorAll('#studio .compare .values tbody tr')]
    .filter((tr) => tr.getClientRects().length > 0).length);
  await page.screenshot({ path: join(shots, 'compare-differences.png') });
  await page.click('#studio .compare header .only-differ');
  await page.evaluate(() => document.querySelector('#studio .compare .plots').scrollIntoView());
  await frames(page);
  await page.screenshot({ path: join(shots, 'compare-winding-plots.png') });

  // The first plot's first series colour: run A's curve solid, run B's
  // dashed, each alone and both.
  step = 'pixels';
  const first = '#studio .compare .plots .cell:first-child canvas';
  const hex = report.state.plots[0].colours[0];
  const rgb = [1, 3, 5].map((i) => parseInt(hex.slice(i, i + 2), 16));
  const pixels = {};
  for (const [name, k] of [['a', 0], ['b', 1], ['both', null]]) {
    await page.evaluate((kk) => window.formcamCompare.only(kk), k);
    await frames(page);
    pixels[name] = await pixelsNear(page, first, rgb);
  }
  report.pixels = pixels;

  if (c) {
    step = 'other kind';
    report.other = await page.evaluate((names) => window.formcamStudio.compare(...names), [a, c]);
    await frames(page);
    report.other_dom = await page.evaluate(() => ({
      note: document.querySelector('#studio .compare header .note')?.textContent ?? '',
      canvases: document.querySelectorAll('#studio .compare .plots canvas').length,
    }));
    await page.screenshot({ path: join(shots, 'compare-kinds.png') });
  }
  if (d) {
    step = 'dressing';
    report.dressing = await page.evaluate((names) => window.formcamStudio.compare(...names), [c, d]);
    await frames(page);
    report.dressing_canvases = await page.evaluate(() => document.querySelectorAll('#studio .compare .plots canvas').length);
    await page.screenshot({ path: join(shots, 'compare-dressing.png') });
  }
  if (pair.length === 2) {
    step = 'third kind';
    report.third = await page.evaluate((names) => window.formcamStudio.compare(...names), pair);
    await frames(page);
    report.third_canvases = await page.evaluate(() => document.querySelectorAll('#studio .compare .plots canvas').length);
    await page.screenshot({ path: join(shots, 'compare-correction.png') });
  }
} catch (e) {
  errors.push(`driver: ${e instanceof Error ? e.message : e} (at: ${step})`);
  process.exitCode = 1;
} finally {
  writeFileSync(out, JSON.stringify(report, null, 1));
  clearTimeout(watchdog);
  await browser.close();
}
