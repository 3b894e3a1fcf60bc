// The static HTML report of a run (`semsim report RUN_DIR --html FILE`) in a real browser:
// headless Chromium driven by npm `playwright-core`, WebGL by software rendering (SwiftShader).
// It opens the file from disk (file://, no server; every other request is blocked and counts
// as an error), waits for the embedded world to load, checks that the canvas is not blank,
// moves the time slider and checks that the robot marker moved, clicks the last timeline
// event and checks the slider jumped, saving OUT_DIR/report_start.png and report_moved.png.
// Prints one JSON line with the results; exits 1 (with the failing step's message on stderr)
// on any failure, any console error or any uncaught page error.
// Used by crates/cli/tests/console_replay.rs. Usage:
//
//     node tools/oracles/report_e2e.mjs FILE OUT_DIR
//
// CHROMIUM names the browser (default /usr/bin/chromium).
import { mkdir } from 'node:fs/promises';
import path from 'node:path';
import { pathToFileURL } from 'node:url';
import { createRequire } from 'node:module';

const require = createRequire(import.meta.url);
const { chromium } = require('playwright-core');

const [file, outDir] = process.argv.slice(2);
if (!file || !outDir) {
  console.error('usage: node report_e2e.mjs FILE OUT_DIR');
  process.exit(2);
}

const TOTAL_MS = 200_000;
const watchdog = setTimeout(() => fail(`gave up after ${TOTAL_MS / 1000} s (step: ${step})`), TOTAL_MS);

let step = 'launch';
let browser = null;
const consoleErrors = [];
const outside = [];

async function fail(message) {
  console.error(`report_e2e: FAILED at step "${step}": ${message}`);
  if (consoleErrors.length) console.error(`console errors:\n  ${consoleErrors.join('\n  ')}`);
  try { if (browser) await browser.close(); } catch { /* already gone */ }
  process.exit(1);
}

/** Counts the pixels of the WebGL canvas that are not the scene's background (#1d2127). */
const canvasStats = () => {
  const gl = document.querySelector('#view canvas');
  const c = document.createElement('canvas');
  c.width = gl.width;
  c.height = gl.height;
  const ctx = c.getContext('2d');
  ctx.drawImage(gl, 0, 0); // preserveDrawingBuffer: the last frame
  const px = ctx.getImageData(0, 0, c.width, c.height).data;
  const colours = new Set();
  let other = 0;
  for (let i = 0; i < px.length; i += 4) {
    colours.add((px[i] << 16) | (px[i + 1] << 8) | px[i + 2]);
    if (Math.abs(px[i] - 0x1d) + Math.abs(px[i + 1] - 0x21) + Math.abs(px[i + 2] - 0x27) > 12) other++;
  }
  return { width: c.width, height: c.height, colours: colours.size, nonBackground: other / (px.length / 4) };
};

try {
  await mkdir(outDir, { recursive: true });
  browser = await chromium.launch({
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    headless: true,
    timeout: 60_000,
    args: [
      '--no-sandbox',
      '--use-angle=swiftshader',
      '--enable-unsafe-swiftshader',
      '--ignore-gpu-blocklist',
    ],
  });
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  page.setDefaultTimeout(60_000);
  page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(`console: ${m.text()}`); });
  page.on('pageerror', (e) => consoleErrors.push(`page error: ${e.message}`));
  page.on('requestfailed', (r) => consoleErrors.push(`request failed: ${r.url()} ${r.failure()?.errorText}`));
  // The report must need nothing from a network.
  await page.route(/^https?:/, (route) => { outside.push(route.request().url()); route.abort(); });

  step = 'load';
  await page.goto(pathToFileURL(path.resolve(file)).href, { waitUntil: 'load' });
  await page.waitForFunction(() => window.report && window.report.ready, null, { timeout: 120_000 })
    .catch(async () => {
      const status = await page.evaluate(() => document.getElementById('status').textContent);
      throw new Error(`the world did not load (status: ${status})`);
    });
  await page.waitForTimeout(500);

  step = 'canvas';
  const canvas = await page.evaluate(canvasStats);
  await page.screenshot({ path: path.join(outDir, 'report_start.png') });
  if (canvas.width < 100 || canvas.height < 100) throw new Error(`the canvas is ${canvas.width}x${canvas.height}`);
  if (canvas.colours <= 16 || canvas.nonBackground < 0.05) {
    throw new Error(`the canvas looks blank: ${canvas.colours} colours, ${(canvas.nonBackground * 100).toFixed(1)}% not background`);
  }
  const verdict = await page.evaluate(() => document.getElementById('verdict').textContent);
  const events = await page.evaluate(() => document.querySelectorAll('#timeline li').length);

  step = 'slider';
  const before = await page.evaluate(() => window.report.markerPosition());
  const robotBefore = await page.evaluate(() => window.report.robotPosition());
  await page.evaluate(() => {
    const s = document.getElementById('slider');
    s.value = String(Math.floor(Number(s.max) / 2));
    s.dispatchEvent(new Event('input', { bubbles: true }));
  });
  await page.waitForTimeout(500);
  const after = await page.evaluate(() => window.report.markerPosition());
  const robotAfter = await page.evaluate(() => window.report.robotPosition());
  const moved = Math.hypot(after[0] - before[0], after[2] - before[2]);
  const robotMoved = robotBefore && robotAfter
    ? Math.hypot(robotAfter[0] - robotBefore[0], robotAfter[2] - robotBefore[2]) : 0;
  await page.screenshot({ path: path.join(outDir, 'report_moved.png') });
  if (!(moved > 0.5)) throw new Error(`the slider moved the marker ${moved.toFixed(3)} m`);
  if (!(robotMoved > 0.5)) throw new Error(`the slider moved the robot ${robotMoved.toFixed(3)} m`);

  step = 'timeline';
  const last = page.locator('#timeline li:not([hidden])').last();
  const lastTime = Number(await last.getAttribute('data-time'));
  await last.click();
  const clock = await page.evaluate(() => document.getElementById('clock').textContent);
  if (!clock.startsWith(`t = ${lastTime.toFixed(2)} s`)) {
    throw new Error(`clicking the event at ${lastTime} s shows "${clock}"`);
  }

  step = 'done';
  if (outside.length) throw new Error(`the report asked the network for ${outside.join(', ')}`);
  if (consoleErrors.length) throw new Error(`${consoleErrors.length} console error(s)`);
  console.log(JSON.stringify({
    ok: true,
    canvas_width: canvas.width,
    canvas_height: canvas.height,
    canvas_colours: canvas.colours,
    canvas_non_background: Number(canvas.nonBackground.toFixed(4)),
    verdict,
    timeline_items: events,
    marker_before: before,
    marker_after: after,
    marker_moved_m: Number(moved.toFixed(4)),
    robot_moved_m: Number(robotMoved.toFixed(4)),
    clicked_event_time_s: lastTime,
    screenshots: ['report_start.png', 'report_moved.png'],
  }));
  clearTimeout(watchdog);
  await browser.close();
} catch (e) {
  await fail(e && e.message ? e.message : String(e));
}
