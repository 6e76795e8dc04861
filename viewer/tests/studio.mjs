// Drives `formcam studio` in headless Chromium (Debian's, through
// playwright-core): a field edited and the job run twice (the result shown
// changes: its summary and its pictures), a value out of range (the error
// at that field, the previous result left shown), the job saved, a run
// cancelled. It writes what it saw as JSON (the Rust test asserts on it,
// and runs the saved file through the CLI) and screenshots
// `studio-*.png`.
//
//   node viewer/tests/studio.mjs URL SCREENSHOT_DIR OUT_JSON FIELD FIRST SECOND BAD SLOW
//   FIELD: the field edited (`winding.winding_angle_deg`); FIRST, SECOND:
//   two good values run in turn; BAD: one out of its range; SLOW: fields
//   set for the run cancelled (`winding.band_width=0.5;mandrel.length=1000`),
//   one that takes seconds.
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { frames, launch, recordErrors } from './driver.mjs';
import { canvases } from './canvas.mjs';

const [url, shots, out, field, first, second, bad, slow] = process.argv.slice(2);
if (!url || !shots || !out || !field || first === undefined || second === undefined || bad === undefined || slow === undefined) {
  console.error('usage: node studio.mjs URL SCREENSHOT_DIR OUT_JSON FIELD FIRST SECOND BAD SLOW');
  process.exit(2);
}
mkdirSync(shots, { recursive: true });

const browser = await launch();
const errors = [];
const report = { errors };
let step = 'launch';
const watchdog = setTimeout(() => {
  errors.push(`driver: no answer from the page within 270 s (at: ${step})`);
  writeFileSync(out, JSON.stringify(report, null, 1));
  process.exit(1);
}, 270_000);

/** A number typed as the test was given it (`55` a number, `auto` a word). */
const value = (v) => (Number.isFinite(Number(v)) && v.trim() !== '' ? Number(v) : v);
const state = (page) => page.evaluate(() => window.formcamStudio.state());

/** The result frame showing run `name`. */
const resultFrame = (page, name) => page.frames().find((f) => f.url().includes(`/runs/${encodeURIComponent(name)}/`));

/** What a run's result page shows: its summary (`api/result`) and its pictures. */
async function shownResult(page, name) {
  const frame = resultFrame(page, name);
  if (!frame) throw new Error(`no frame shows the run ${name}: ${page.frames().map((f) => f.url()).join(', ')}`);
  await frame.evaluate(() => window.formcam.ready);
  const result = await frame.evaluate(async () => (await fetch('api/result')).json());
  const view = await frame.evaluate(() => window.formcam.state());
  // The plots opened: drawn from this run's tables.
  await frame.evaluate(async () => {
    document.querySelector('#plots-toggle')?.click();
    await window.formcamPlots?.open();
  });
  await frames(page);
  const plots = await canvases(frame, '#plots-panel canvas');
  await frame.evaluate(() => document.querySelector('#plots-toggle')?.click());
  const scene = await canvases(frame, '#stage > canvas');
  const src = await page.evaluate(() => document.querySelector('iframe.result-frame')?.getAttribute('src'));
  return { name, src, result, view, plots, scene };
}

/** The field's row as drawn: marked invalid, its message, its input's border colour. */
const fieldShown = (page, f) => page.evaluate((path) => {
  const row = document.querySelector(`.field[data-field="${path}"]`);
  if (!row) return null;
  const input = row.querySelector('input, select');
  const rect = row.getBoundingClientRect();
  return {
    invalid: row.classList.contains('invalid'),
    message: row.querySelector('.message')?.textContent ?? '',
    message_shown: !row.querySelector('.message')?.hidden,
    border: input ? getComputedStyle(input).borderTopColor : '',
    visible: rect.width > 0 && rect.height > 0,
    value: input?.value ?? null,
  };
}, f);

try {
  const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
  page.setDefaultTimeout(120_000);
  recordErrors(page, errors, url);
  step = 'open';
  await page.goto(url);
  await page.waitForFunction(() => window.formcamStudio !== undefined);
  await page.evaluate(() => window.formcamStudio.ready);
  report.opened = await state(page);
  report.form_rows = await page.evaluate(() => document.querySelectorAll('#studio .field').length);
  await page.screenshot({ path: join(shots, 'studio-form.png') });

  // Edited and run: the first value, then the second; each result shown.
  step = 'first run';
  report.set_first = await page.evaluate(([f, v]) => window.formcamStudio.set(f, v), [field, value(first)]);
  report.first_run = await page.evaluate(() => window.formcamStudio.run());
  report.after_first = await state(page);
  report.first = await shownResult(page, report.first_run);
  step = 'second run';
  await page.evaluate(([f, v]) => window.formcamStudio.set(f, v), [field, value(second)]);
  report.second_run = await page.evaluate(() => window.formcamStudio.run());
  report.after_second = await state(page);
  report.second = await shownResult(page, report.second_run);
  await page.screenshot({ path: join(shots, 'studio-run.png') });

  // The two runs ticked in the list and compared side by side, then back.
  step = 'compare';
  for (const name of [report.first_run, report.second_run]) {
    await page.check(`#studio li[data-run="${name}"] input[type=checkbox]`);
  }
  await page.click('#studio button.compare');
  await page.waitForTimeout(500);
  report.compare = {
    selected: (await state(page)).selected,
    shown: await page.evaluate(() => !document.querySelector('#studio .compare-host').hidden),
    frame_hidden: await page.evaluate(() => document.querySelector('#studio iframe.result-frame').hidden),
  };
  await page.screenshot({ path: join(shots, 'studio-compare.png') });
  await page.click('#studio button.back');
  report.compare.back = await page.evaluate(() => !document.querySelector('#studio iframe.result-frame').hidden);

  // Out of range: the error at the field in the CLI's words; Enter in the
  // field applies; nothing runs and the second result stays.
  step = 'bad value';
  await page.evaluate(([f, v]) => window.formcamStudio.set(f, v), [field, value(bad)]);
  await page.focus(`.field[data-field="${field}"] input, .field[data-field="${field}"] select`);
  await page.keyboard.press('Enter');
  await page.waitForFunction((f) => f in window.formcamStudio.state().errors, field, { timeout: 20_000 });
  report.bad_state = await state(page);
  report.bad_field = await fieldShown(page, field);
  report.bad_run = await page.evaluate(() => window.formcamStudio.run());
  report.after_bad = await state(page);
  report.after_bad_src = await page.evaluate(() => document.querySelector('iframe.result-frame')?.getAttribute('src'));
  report.after_bad_result = await resultFrame(page, report.second_run)?.evaluate(async () => (await fetch('api/result')).json());
  await page.screenshot({ path: join(shots, 'studio-error.png') });

  // Saved with the second value: the file the CLI then runs.
  step = 'save';
  await page.evaluate(([f, v]) => window.formcamStudio.set(f, v), [field, value(second)]);
  report.applied = await page.evaluate(() => window.formcamStudio.apply());
  report.cleared_field = await fieldShown(page, field);
  report.before_save = await state(page);
  report.saved = await page.evaluate(() => window.formcamStudio.save());
  report.after_save = await state(page);

  // Reset: an edit undone back to the saved file.
  step = 'reset';
  await page.evaluate(([f, v]) => window.formcamStudio.set(f, v), [field, value(first)]);
  await page.evaluate(() => window.formcamStudio.apply());
  report.edited = await state(page);
  await page.evaluate(() => window.formcamStudio.reset());
  report.reset = await state(page);

  // Pause: the result's animation played, paused from the studio, then
  // played on by the same button.
  step = 'pause';
  const view = resultFrame(page, report.second_run);
  const time = () => view.evaluate(() => window.formcam.state().time_s);
  await view.evaluate(() => window.formcam.play(1));
  await page.waitForTimeout(400);
  await page.click('#studio button.pause');
  const paused = await time();
  const pausedState = (await state(page)).paused;
  await page.waitForTimeout(400);
  const later = await time();
  await page.click('#studio button.pause');
  await page.waitForTimeout(400);
  report.pause = { paused, pausedState, later, resumed: await time(), label: await page.textContent('#studio button.pause') };
  await page.click('#studio button.pause');

  // Cancel: a run stopped while it goes.
  step = 'cancel';
  const slowFields = slow.split(';').filter((p) => p !== '').map((p) => p.split('=')).map(([f, v]) => [f, value(v)]);
  await page.evaluate((fields) => {
    for (const [f, v] of fields) window.formcamStudio.set(f, v);
    window.cancelled = window.formcamStudio.run();
  }, slowFields);
  await page.waitForFunction((prev) => {
    const s = window.formcamStudio.state();
    return s.run !== prev && s.runState !== 'idle';
  }, report.second_run, { polling: 20, timeout: 60_000 });
  report.cancel_seen = await state(page);
  if (report.cancel_seen.runState === 'running') await page.click('#studio button.cancel', { timeout: 10_000 });
  report.cancel_run = await page.evaluate(() => window.cancelled);
  report.after_cancel = await state(page);
  await page.screenshot({ path: join(shots, 'studio-cancel.png') });
} catch (e) {
  errors.push(`driver: at ${step}: ${e}`);
} finally {
  writeFileSync(out, JSON.stringify(report, null, 1));
  clearTimeout(watchdog);
  await browser.close();
}
