// The console replaying a recorded run (`semsim console --run RUN_DIR`) in a real browser
// (browser.mjs: headless Chromium, software WebGL). It loads the page and checks, saving
// screenshots in OUT_DIR:
//   1. the replay panel shows, the canvas is not blank, the minimap is drawn
//      -> replay_start.png;
//   2. moving the time slider to the middle moves the robot (the pose the page reports, and
//      the picture) -> replay_middle.png;
//   3. clicking the last event of the timeline jumps to its moment (the clock's time);
//   4. the doors swing as recorded: the page's door angles at the moment the run's widest
//      recorded door angle was reached (EXPECT_DOOR: `ID:DEGREES`, from doors.csv) match it.
// Prints one JSON line with the results; exits 1 naming the failing step on any failure or
// console error. Used by crates/cli/tests/console_replay.rs. Usage:
//
//     node tools/oracles/replay_e2e.mjs URL OUT_DIR [ID:DEGREES@TIME_S]
import path from 'node:path';
import {
  run, canvasStats, canvasPixels, pixelsDiffer, pixelsOnceChanged, assertNotBlank, sleep,
} from './browser.mjs';

const [url, outDir, door] = process.argv.slice(2);
if (!url || !outDir) {
  console.error('usage: node replay_e2e.mjs URL OUT_DIR [ID:DEGREES@TIME_S]');
  process.exit(2);
}

await run('replay_e2e', outDir, 200_000, async (s) => {
  const { page } = s;
  s.mark('load');
  await page.goto(url, { waitUntil: 'load' });
  await page.waitForFunction(() => window.replay && !document.getElementById('replay').hidden, null, { timeout: 120_000 })
    .catch(async () => {
      const status = await page.evaluate(() => document.getElementById('status').textContent);
      throw new Error(`the replay did not start (status: ${status})`);
    });
  await sleep(500);
  const clock = () => page.evaluate(() => {
    const d = document.getElementById('clock').dataset;
    return { x: Number(d.x), y: Number(d.y), t: Number(d.time), doors: d.doors || '' };
  });

  s.mark('canvas');
  const canvas = await page.evaluate(canvasStats);
  await page.screenshot({ path: path.join(outDir, 'replay_start.png') });
  assertNotBlank(canvas);
  const minimap = await page.evaluate(() => document.getElementById('minimap')?.dataset.robotPx || null);
  if (!minimap) throw new Error('the minimap is not drawn');

  s.mark('slider');
  const start = await clock();
  const pixelsStart = await page.evaluate(canvasPixels);
  await page.evaluate(() => {
    const el = document.getElementById('replay-slider');
    el.value = String((Number(el.min) + Number(el.max)) / 2);
    el.dispatchEvent(new Event('input', { bubbles: true }));
  });
  const pixelsMiddle = await pixelsOnceChanged(page, pixelsStart, 0.001);
  const middle = await clock();
  await page.screenshot({ path: path.join(outDir, 'replay_middle.png') });
  const moved = Math.hypot(middle.x - start.x, middle.y - start.y);
  const changed = pixelsDiffer(pixelsStart, pixelsMiddle);
  if (!(moved > 0.5)) throw new Error(`the slider moved the robot ${moved.toFixed(3)} m`);
  if (!(changed > 0.001)) throw new Error(`the slider changed ${changed} of the pixels`);

  s.mark('timeline');
  const last = page.locator('#events li').last();
  const eventTime = Number(await last.getAttribute('data-time'));
  await last.click();
  await sleep(300);
  const atEvent = await clock();
  if (!(Math.abs(atEvent.t - eventTime) < 1e-6)) throw new Error(`clicking the event at ${eventTime} s shows t = ${atEvent.t}`);

  let doorCheck = null;
  if (door) {
    s.mark('doors');
    const [, id, deg, time] = door.match(/^(\d+):(-?[\d.]+)@([\d.]+)$/) || [];
    if (id === undefined) throw new Error(`bad door argument ${door}`);
    await page.evaluate((t) => window.replay.show(t), Number(time));
    await sleep(300);
    const shown = (await clock()).doors;
    const found = shown.split(' ').map((p) => p.split(':')).find(([d]) => d === id);
    if (!found) throw new Error(`the page shows no angle for door ${id}: "${shown}"`);
    const angle = Number(found[1]);
    if (!(Math.abs(angle - Number(deg)) < 0.5)) throw new Error(`door ${id} at ${time} s: ${angle} degrees shown, ${deg} recorded`);
    const closed = await page.evaluate(() => { window.replay.show(0); return document.getElementById('clock').dataset.doors; });
    doorCheck = { door: Number(id), recorded_deg: Number(deg), shown_deg: angle, at_start: closed };
    await page.screenshot({ path: path.join(outDir, 'replay_door.png') });
  }

  return {
    canvas_colours: canvas.colours,
    canvas_non_background: Number(canvas.nonBackground.toFixed(4)),
    minimap_robot_px: minimap,
    pose_start: start,
    pose_middle: middle,
    slider_moved_m: Number(moved.toFixed(4)),
    slider_pixels_changed: Number(changed.toFixed(4)),
    event_time_s: eventTime,
    clock_after_click_s: atEvent.t,
    door: doorCheck,
  };
});
