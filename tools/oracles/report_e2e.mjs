// The static HTML report of a run (`semsim report RUN_DIR --html FILE`) in a real browser:
// headless Chromium with software WebGL (browser.mjs).
// It opens the file from disk (file://, no server; every other request is blocked and counts
// as an error), waits for the embedded world to load, checks that the canvas is not blank,
// moves the time slider and checks that the robot marker moved, clicks the last timeline
// event and checks the slider jumped, saving OUT_DIR/report_start.png and report_moved.png.
// Prints one JSON line with the results; exits 1 (with the failing step's message on stderr)
// on any failure, any console error or any uncaught page error.
// Used by crates/cli/tests/console_replay.rs. Usage:
//
//     node tools/oracles/report_e2e.mjs FILE OUT_DIR
import path from 'node:path';
import { pathToFileURL } from 'node:url';
import { run, canvasStats, assertNotBlank } from './browser.mjs';

const [file, outDir] = process.argv.slice(2);
if (!file || !outDir) {
  console.error('usage: node report_e2e.mjs FILE OUT_DIR');
  process.exit(2);
}

await run('report_e2e', outDir, 200_000, async (s) => {
  const { page } = s;
  const outside = [];
  // The report must need nothing from a network.
  await page.route(/^https?:/, (route) => { outside.push(route.request().url()); route.abort(); });

  s.mark('load');
  await page.goto(pathToFileURL(path.resolve(file)).href, { waitUntil: 'load' });
  await page.waitForFunction(() => window.report && window.report.ready, null, { timeout: 120_000 })
    .catch(async () => {
      const status = await page.evaluate(() => document.getElementById('status').textContent);
      throw new Error(`the world did not load (status: ${status})`);
    });
  await page.waitForTimeout(500);

  s.mark('canvas');
  const canvas = await page.evaluate(canvasStats);
  await page.screenshot({ path: path.join(outDir, 'report_start.png') });
  assertNotBlank(canvas);
  const verdict = await page.evaluate(() => document.getElementById('verdict').textContent);
  const events = await page.evaluate(() => document.querySelectorAll('#timeline li').length);

  s.mark('slider');
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

  s.mark('timeline');
  const last = page.locator('#timeline li:not([hidden])').last();
  const lastTime = Number(await last.getAttribute('data-time'));
  await last.click();
  const clock = await page.evaluate(() => document.getElementById('clock').textContent);
  if (!clock.startsWith(`t = ${lastTime.toFixed(2)} s`)) {
    throw new Error(`clicking the event at ${lastTime} s shows "${clock}"`);
  }

  if (outside.length) throw new Error(`the report asked the network for ${outside.join(', ')}`);
  const minimap = await page.evaluate(() => Boolean(document.getElementById('minimap')?.dataset.robotPx));
  if (!minimap) throw new Error('the minimap is not drawn');
  return {
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
    minimap,
    screenshots: ['report_start.png', 'report_moved.png'],
  };
});
