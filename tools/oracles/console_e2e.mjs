// The operator console (`semsim console`) in a real browser: headless Chromium driven by npm
// `playwright-core` (installed in tools/oracles/node_modules by setup.sh), WebGL by software
// rendering (SwiftShader). It loads the page, checks that the world rendered (the canvas is
// not blank), holds W and checks that the robot moved forwards, turns left and drives until
// the timeline shows a `wall_touched` event, saving screenshots on the way:
// OUT_DIR/console_loaded.png, console_after_drive.png, console_wall_event.png.
// Prints one JSON line with the results; exits 1 (with the failing step's message on stderr)
// on any failure, any console error or any uncaught page error.
// Used by crates/cli/tests/console_browser.rs, which starts the console with a scenario that
// puts the robot in the default building's corridor at (10, 0) facing east. Usage:
//
//     node tools/oracles/console_e2e.mjs URL OUT_DIR
//
// CHROMIUM names the browser (default /usr/bin/chromium).
import { mkdir } from 'node:fs/promises';
import path from 'node:path';
import { createRequire } from 'node:module';

const require = createRequire(import.meta.url);
const { chromium } = require('playwright-core');

const [url, outDir] = process.argv.slice(2);
if (!url || !outDir) {
  console.error('usage: node console_e2e.mjs URL OUT_DIR');
  process.exit(2);
}

// The whole run's limit: a hang becomes an explicit failure.
const TOTAL_MS = 200_000;
const watchdog = setTimeout(() => fail(`gave up after ${TOTAL_MS / 1000} s (step: ${step})`), TOTAL_MS);

let step = 'launch';
let browser = null;
const consoleErrors = [];
const t0 = Date.now();
const timings = {};

async function fail(message) {
  console.error(`console_e2e: FAILED at step "${step}": ${message}`);
  if (consoleErrors.length) console.error(`console errors:\n  ${consoleErrors.join('\n  ')}`);
  try { if (browser) await browser.close(); } catch { /* already gone */ }
  process.exit(1);
}

function mark(name) {
  timings[name] = (Date.now() - t0) / 1000;
  step = name;
}

const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

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

  // ---- load: the world, the connection (this tab drives) and the first states --------------
  mark('load');
  await page.goto(url, { waitUntil: 'load' });
  await page.waitForFunction(
    () => document.getElementById('status').textContent === 'connected: you drive',
    null, { timeout: 120_000 },
  ).catch((e) => { throw new Error(`the page did not connect as the driver (status: ${e.message})`); });
  await page.waitForSelector('#clock[data-x]', { state: 'attached', timeout: 60_000 });
  const clock = () => page.evaluate(() => {
    const d = document.getElementById('clock').dataset;
    return { x: Number(d.x), y: Number(d.y), yaw: Number(d.yaw), t: Number(d.time) };
  });
  // A few simulated tenths of a second, so that the robot has settled on its wheels.
  const tStart = (await clock()).t;
  await page.waitForFunction((t) => Number(document.getElementById('clock').dataset.time) > t + 0.5, tStart);

  // ---- 1. the canvas is not blank --------------------------------------------------------
  mark('canvas');
  const canvas = await page.evaluate(() => {
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
      // The scene's background is #1d2127.
      if (Math.abs(px[i] - 0x1d) + Math.abs(px[i + 1] - 0x21) + Math.abs(px[i + 2] - 0x27) > 12) other++;
    }
    return { width: c.width, height: c.height, colours: colours.size, nonBackground: other / (px.length / 4) };
  });
  await page.screenshot({ path: path.join(outDir, 'console_loaded.png') });
  if (canvas.width < 100 || canvas.height < 100) throw new Error(`the canvas is ${canvas.width}x${canvas.height}`);
  if (canvas.colours <= 16 || canvas.nonBackground < 0.05) {
    throw new Error(`the canvas looks blank: ${canvas.colours} colours, ${(canvas.nonBackground * 100).toFixed(1)}% not background`);
  }

  // ---- 2. W drives forwards --------------------------------------------------------------
  mark('drive');
  // The top-down camera, for the screenshots; then focus back on the page so that keys drive.
  await page.check('input[name=camera][value=top]');
  await page.evaluate(() => document.activeElement && document.activeElement.blur());
  const before = await clock();
  await page.keyboard.down('w');
  await sleep(1500);
  await page.keyboard.up('w');
  // Let the stop arrive and the robot come to rest.
  await sleep(700);
  const after = await clock();
  const dx = after.x - before.x, dy = after.y - before.y;
  const moved = Math.hypot(dx, dy);
  await page.screenshot({ path: path.join(outDir, 'console_after_drive.png') });
  if (!(moved > 0.2)) throw new Error(`holding W moved the robot ${moved.toFixed(3)} m (${JSON.stringify(before)} -> ${JSON.stringify(after)})`);

  // ---- 3. turn left (north) and drive into the corridor's wall ----------------------------
  mark('turn');
  await page.keyboard.down('a');
  await page.waitForFunction(() => Number(document.getElementById('clock').dataset.yaw) > 75, null, { timeout: 30_000 })
    .catch(async () => { throw new Error(`the robot did not turn left to 75 degrees: ${JSON.stringify(await clock())}`); });
  await page.keyboard.up('a');
  mark('wall');
  await page.keyboard.down('w');
  const wallEvent = await page.waitForSelector('#events li.wall_touched', { timeout: 30_000 })
    .catch(async () => { throw new Error(`no wall_touched event in the timeline: ${JSON.stringify(await clock())}`); });
  await page.keyboard.up('w');
  await page.keyboard.press('Space');
  const wallText = await wallEvent.textContent();
  const atWall = await clock();
  await sleep(300);
  await page.screenshot({ path: path.join(outDir, 'console_wall_event.png') });
  mark('done');

  if (consoleErrors.length) throw new Error(`${consoleErrors.length} console error(s)`);
  console.log(JSON.stringify({
    ok: true,
    console_errors: consoleErrors,
    canvas_width: canvas.width,
    canvas_height: canvas.height,
    canvas_colours: canvas.colours,
    canvas_non_background: Number(canvas.nonBackground.toFixed(4)),
    pose_before: before,
    pose_after: after,
    moved_m: Number(moved.toFixed(4)),
    moved_dx_m: Number(dx.toFixed(4)),
    wall_event: wallText,
    pose_at_wall: atWall,
    timings_s: timings,
  }));
  clearTimeout(watchdog);
  await browser.close();
} catch (e) {
  await fail(e && e.message ? e.message : String(e));
}
