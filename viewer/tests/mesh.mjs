// Drives the page `formcam view` serves in headless Chromium to see that
// the machine's mesh solids are drawn: the triangles the page drew, where
// each mesh's centre is drawn and the pixel there with the meshes shown and
// hidden, what the page says about them; given a second view whose machine
// names a mesh file that is not there, what that page says. Screenshots:
// mesh.png (the front view), mesh-detail.png (around the first mesh),
// mesh-missing.png.
//
//   node viewer/tests/mesh.mjs URL SCREENSHOT_DIR OUT_JSON [MISSING_URL]
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { launch, recordErrors } from './driver.mjs';

/** Seconds the page has to become ready; the whole run's bound. */
const READY_S = Number(process.env.FORMCAM_READY_S ?? 45);
const TOTAL_S = 150;

const [url, shots, out, missingUrl] = process.argv.slice(2);
if (!url || !shots || !out) {
  console.error('usage: node mesh.mjs URL SCREENSHOT_DIR OUT_JSON [MISSING_URL]');
  process.exit(2);
}
mkdirSync(shots, { recursive: true });

const errors = [];
const results = {};
let step = 'launch';
const report = () => writeFileSync(out, JSON.stringify({ errors, ...results }, null, 1));
const watchdog = setTimeout(() => {
  errors.push(`driver: not done within ${TOTAL_S} s (at: ${step})`);
  report();
  console.error(errors.at(-1));
  process.exit(1);
}, TOTAL_S * 1000);

const browser = await launch();

/** `base` opened and ready, its console errors and outside requests recorded. */
const open = async (base) => {
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  page.setDefaultTimeout(READY_S * 1000);
  recordErrors(page, errors);
  page.on('request', (r) => { if (!r.url().startsWith(base)) errors.push(`outside request: ${r.url()}`); });
  await page.goto(base);
  await page.evaluate(() => window.formcam.ready);
  return page;
};

/** The canvas's pixel `[r, g, b]` at `px` (px from its centre, CSS pixels). */
const pixelAt = (page, px) => page.evaluate(([dx, dy]) => {
  const c = document.querySelector('#stage canvas');
  const d = document.createElement('canvas');
  d.width = c.width;
  d.height = c.height;
  const x = d.getContext('2d');
  x.drawImage(c, 0, 0);
  const k = c.width / c.clientWidth;
  const at = [Math.round((c.clientWidth / 2 + dx) * k), Math.round((c.clientHeight / 2 + dy) * k)];
  return [...x.getImageData(at[0], at[1], 1, 1).data.slice(0, 3)];
}, px);

/** Two animation frames: whatever changed is drawn. */
const frame = (p) => p.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));

try {
  step = 'open';
  const page = await open(url);
  await frame(page);
  const state = await page.evaluate(() => window.formcam.state());
  step = 'pixels';
  const shown = [];
  for (const px of state.mesh_px) shown.push(await pixelAt(page, px));
  await page.screenshot({ path: join(shots, 'mesh.png') });
  if (state.mesh_px.length > 0) {
    const box = await page.$eval('#stage canvas', (c) => {
      const r = c.getBoundingClientRect();
      return { x: r.left, y: r.top, w: r.width, h: r.height };
    });
    const [dx, dy] = state.mesh_px[0];
    const cx = box.x + box.w / 2 + dx;
    const cy = box.y + box.h / 2 + dy;
    const clip = { x: Math.max(box.x, cx - 200), y: Math.max(box.y, cy - 150), width: 400, height: 300 };
    await page.screenshot({ path: join(shots, 'mesh-detail.png'), clip });
  }
  await page.evaluate(() => window.formcam.overlays({ meshes: false }));
  await frame(page);
  const hidden = [];
  for (const px of state.mesh_px) hidden.push(await pixelAt(page, px));
  await page.evaluate(() => window.formcam.overlays({ meshes: true }));
  const background = await page.evaluate(() => {
    // The scene's background, from a corner of the sky above the machine.
    const c = document.querySelector('#stage canvas');
    const d = document.createElement('canvas');
    d.width = c.width;
    d.height = c.height;
    const x = d.getContext('2d');
    x.drawImage(c, 0, 0);
    return [...x.getImageData(2, 2, 1, 1).data.slice(0, 3)];
  });
  const notesShown = await page.$$eval('#stage .mesh-notes', (n) => n.map((x) => x.textContent));
  results.mesh = {
    triangles: state.mesh_triangles,
    notes: state.mesh_notes,
    notes_shown: notesShown,
    px: state.mesh_px,
    shown,
    hidden,
    background,
  };
  await page.close();
  if (missingUrl) {
    step = 'missing';
    const m = await open(missingUrl);
    await frame(m);
    const st = await m.evaluate(() => window.formcam.state());
    const shownNotes = await m.$$eval('#stage .mesh-notes', (n) => n.map((x) => x.textContent));
    await m.screenshot({ path: join(shots, 'mesh-missing.png') });
    results.missing = { triangles: st.mesh_triangles, notes: st.mesh_notes, notes_shown: shownNotes };
    await m.close();
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
