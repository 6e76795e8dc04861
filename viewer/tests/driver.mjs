// What the browser drivers share: Debian's Chromium started headless with
// software GL, the page's errors recorded, and waiting for frames.
import { chromium } from 'playwright-core';

/** Debian's Chromium (or `FORMCAM_CHROMIUM`), headless, no sandbox, no
 * background networking, WebGL by SwiftShader. */
export const launch = () => chromium.launch({
  executablePath: process.env.FORMCAM_CHROMIUM ?? '/usr/bin/chromium',
  headless: true,
  args: ['--no-sandbox', '--disable-background-networking', '--use-angle=swiftshader',
    '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'],
});

/**
 * Records on `errors` the page's console errors and uncaught exceptions, and
 * with `base` given every request outside it and every failed request.
 */
export const recordErrors = (page, errors, base) => {
  page.on('console', (m) => { if (m.type() === 'error') errors.push(`console: ${m.text()}`); });
  page.on('pageerror', (e) => errors.push(`page: ${e}`));
  if (base === undefined) return;
  page.on('requestfailed', (r) => errors.push(`request failed: ${r.url()}`));
  page.on('request', (r) => { if (!r.url().startsWith(base)) errors.push(`outside request: ${r.url()}`); });
};

/** Resolves after two animation frames of `page`: what was asked is drawn. */
export const frames = (page) => page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
