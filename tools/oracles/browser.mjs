// What the browser oracles (console_e2e.mjs, report_e2e.mjs, replay_e2e.mjs) share: headless
// Chromium driven by npm `playwright-core` (tools/oracles/node_modules, setup.sh) with WebGL by
// software rendering (SwiftShader), a page that records console errors, page errors and failed
// requests, a whole-run watchdog that turns a hang into a failure naming the step, and the
// canvas check (how much of the WebGL canvas is not the scene's background #1d2127).
// CHROMIUM names the browser (default /usr/bin/chromium).
import { mkdir } from 'node:fs/promises';
import { createRequire } from 'node:module';

const require = createRequire(import.meta.url);
const { chromium } = require('playwright-core');

/**
 * A browser session for the oracle `name`: `run(async (s) => ...)` launches Chromium, gives
 * `s.page` (1280x800), `s.mark(step)`, `s.errors` (console and page errors, failed requests)
 * and `s.timings`, prints the JSON the callback returns (with `ok: true`), and exits 1 naming
 * the step on any failure, on any error the page logged, or after `totalMs`.
 */
export async function run(name, outDir, totalMs, body) {
  const s = { step: 'launch', errors: [], timings: {}, browser: null, page: null };
  const t0 = Date.now();
  s.mark = (step) => { s.timings[step] = (Date.now() - t0) / 1000; s.step = step; };
  const fail = async (message) => {
    console.error(`${name}: FAILED at step "${s.step}": ${message}`);
    if (s.errors.length) console.error(`console errors:\n  ${s.errors.join('\n  ')}`);
    try { if (s.browser) await s.browser.close(); } catch { /* already gone */ }
    process.exit(1);
  };
  const watchdog = setTimeout(() => fail(`gave up after ${totalMs / 1000} s`), totalMs);
  try {
    await mkdir(outDir, { recursive: true });
    s.browser = await launch();
    s.page = await s.browser.newPage({ viewport: { width: 1280, height: 800 } });
    s.page.setDefaultTimeout(60_000);
    s.page.on('console', (m) => { if (m.type() === 'error') s.errors.push(`console: ${m.text()}`); });
    s.page.on('pageerror', (e) => s.errors.push(`page error: ${e.message}`));
    s.page.on('requestfailed', (r) => s.errors.push(`request failed: ${r.url()} ${r.failure()?.errorText}`));
    const result = await body(s);
    s.mark('done');
    if (s.errors.length) throw new Error(`${s.errors.length} console error(s)`);
    console.log(JSON.stringify({ ok: true, console_errors: s.errors, ...result, timings_s: s.timings }));
    clearTimeout(watchdog);
    await s.browser.close();
  } catch (e) {
    await fail(e && e.message ? e.message : String(e));
  }
}

/** Headless Chromium with software WebGL. */
export function launch() {
  return chromium.launch({
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    headless: true,
    timeout: 60_000,
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'],
  });
}

/**
 * Evaluated in the page: the WebGL canvas's size, its number of distinct colours and the
 * fraction of its pixels off the background #1d2127 (the last frame: preserveDrawingBuffer).
 */
export const canvasStats = () => {
  const gl = document.querySelector('#view canvas');
  const c = document.createElement('canvas');
  c.width = gl.width;
  c.height = gl.height;
  const ctx = c.getContext('2d');
  ctx.drawImage(gl, 0, 0);
  const px = ctx.getImageData(0, 0, c.width, c.height).data;
  const colours = new Set();
  let other = 0;
  for (let i = 0; i < px.length; i += 4) {
    colours.add((px[i] << 16) | (px[i + 1] << 8) | px[i + 2]);
    if (Math.abs(px[i] - 0x1d) + Math.abs(px[i + 1] - 0x21) + Math.abs(px[i + 2] - 0x27) > 12) other++;
  }
  return { width: c.width, height: c.height, colours: colours.size, nonBackground: other / (px.length / 4) };
};

/** Evaluated in the page: the WebGL canvas's pixels, to compare two frames (`pixelsDiffer`). */
export const canvasPixels = () => {
  const gl = document.querySelector('#view canvas');
  const c = document.createElement('canvas');
  c.width = 320;
  c.height = 200;
  const ctx = c.getContext('2d');
  ctx.drawImage(gl, 0, 0, c.width, c.height);
  return Array.from(ctx.getImageData(0, 0, c.width, c.height).data);
};

/** The fraction of pixels whose colour differs by more than 24 (sum of |dR|+|dG|+|dB|). */
export function pixelsDiffer(a, b) {
  let n = 0;
  for (let i = 0; i < a.length; i += 4) {
    if (Math.abs(a[i] - b[i]) + Math.abs(a[i + 1] - b[i + 1]) + Math.abs(a[i + 2] - b[i + 2]) > 24) n++;
  }
  return n / (a.length / 4);
}

/**
 * Polls the canvas until its picture differs from `reference` in more than `fraction` of the
 * pixels (the frame with the change has been drawn) or `timeoutMs` passes; returns the last
 * pixels either way, for the caller to judge. A fixed wait is not enough: software WebGL on a
 * loaded machine can draw fewer than two frames a second.
 */
export async function pixelsOnceChanged(page, reference, fraction, timeoutMs = 20_000) {
  const t0 = Date.now();
  for (;;) {
    const px = await page.evaluate(canvasPixels);
    if (pixelsDiffer(reference, px) > fraction || Date.now() - t0 > timeoutMs) return px;
    await sleep(200);
  }
}

/** Throws unless the canvas stats show a rendered world (not blank). */
export function assertNotBlank(canvas) {
  if (canvas.width < 100 || canvas.height < 100) throw new Error(`the canvas is ${canvas.width}x${canvas.height}`);
  if (canvas.colours <= 16 || canvas.nonBackground < 0.05) {
    throw new Error(`the canvas looks blank: ${canvas.colours} colours, ${(canvas.nonBackground * 100).toFixed(1)}% not background`);
  }
}

export const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
