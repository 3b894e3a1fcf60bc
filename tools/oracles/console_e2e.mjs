// The operator console (`semsim console`) in a real browser (browser.mjs: headless Chromium,
// software WebGL). It loads the page and checks, saving screenshots in OUT_DIR:
//   1. the world rendered (the canvas is not blank) and the minimap is drawn with the robot;
//   2. with --cloud: the point-cloud layer renders (turning it on changes the picture, and so
//      does its colour mode) -> console_cloud.png;
//   3. holding W drives the robot forwards -> console_after_drive.png;
//   4. the on-screen drive buttons drive it (pointer down on the forward button);
//   5. a gamepad's left stick drives it: a gamepad cannot be plugged into headless Chromium,
//      so an init script (playwright's addInitScript) replaces navigator.getGamepads with a
//      fake pad whose axes the test sets; the page's own polling code path then reads it;
//   6. turning left and driving into the corridor's wall shows a `wall_touched` event
//      -> console_wall_event.png; the follow camera, behind a robot whose back is to the
//      corridor's other wall, is pulled in in front of that wall -> console_follow.png.
// Prints one JSON line with the results; exits 1 naming the failing step on any failure,
// console error or uncaught page error. Used by crates/cli/tests/console_browser.rs, which
// starts the console with a scenario that puts the robot in the default building's corridor
// at (10, 0) facing east. Usage:
//
//     node tools/oracles/console_e2e.mjs URL OUT_DIR [--expect-cloud]
import path from 'node:path';
import {
  run, canvasStats, canvasPixels, pixelsDiffer, pixelsOnceChanged, assertNotBlank, sleep,
} from './browser.mjs';

const [url, outDir, flag] = process.argv.slice(2);
if (!url || !outDir) {
  console.error('usage: node console_e2e.mjs URL OUT_DIR [--expect-cloud]');
  process.exit(2);
}
const expectCloud = flag === '--expect-cloud';

await run('console_e2e', outDir, 240_000, async (s) => {
  const { page } = s;
  // The fake gamepad (see 5. above): null until the test plugs it in.
  await page.addInitScript(() => {
    window.__fakePad = null;
    navigator.getGamepads = () => [window.__fakePad];
  });

  // ---- load: the world, the connection (this tab drives) and the first states -------------
  s.mark('load');
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
  // Waits for the simulation's clock to advance `secs` simulated seconds: the page's waits are
  // on the simulation and the picture, never on the wall clock alone (on a loaded machine the
  // page may see only a few states a second).
  const simWait = async (secs) => {
    const t = (await clock()).t;
    await page.waitForFunction((end) => Number(document.getElementById('clock').dataset.time) >= end, t + secs,
      { timeout: 60_000, polling: 100 })
      .catch(async () => {
        const shown = await page.evaluate(() => `${document.getElementById('status').textContent}; ${document.getElementById('clock').textContent}`);
        throw new Error(`the simulation did not advance ${secs} s: ${JSON.stringify(await clock())} (page: ${shown})`);
      });
  };
  // Holds an input until the robot is `metres` from `from` (up to 30 s; the step's own check
  // then judges how far and which way it went).
  const untilMoved = (from, metres) => page.waitForFunction(([x, y, m]) => {
    const d = document.getElementById('clock').dataset;
    return Math.hypot(Number(d.x) - x, Number(d.y) - y) > m;
  }, [from.x, from.y, metres], { timeout: 30_000, polling: 100 }).catch(() => {});
  // A few simulated tenths of a second, so that the robot has settled on its wheels.
  await simWait(0.5);

  // ---- 1. the canvas is not blank; the minimap is drawn ------------------------------------
  s.mark('canvas');
  const canvas = await page.evaluate(canvasStats);
  await page.screenshot({ path: path.join(outDir, 'console_loaded.png') });
  assertNotBlank(canvas);
  const minimap = await page.evaluate(() => {
    const c = document.getElementById('minimap');
    if (!c) return null;
    const px = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    const colours = new Set();
    let robot = 0;
    for (let i = 0; i < px.length; i += 4) {
      colours.add((px[i] << 16) | (px[i + 1] << 8) | px[i + 2]);
      if (px[i] === 0x00 && px[i + 1] === 0xe6 && px[i + 2] === 0x76) robot++; // the robot's arrow
    }
    return { width: c.width, colours: colours.size, robot_pixels: robot, robot_px: c.dataset.robotPx };
  });
  if (!minimap) throw new Error('no minimap');
  if (minimap.colours < 3 || minimap.robot_pixels < 10) throw new Error(`the minimap looks empty: ${JSON.stringify(minimap)}`);

  // ---- 2. the cloud layer ----------------------------------------------------------------
  let cloud = null;
  if (expectCloud) {
    s.mark('cloud');
    await page.waitForSelector('#cloud-section:not([hidden])', { timeout: 60_000 });
    // Each change is waited for (up to 20 s) rather than slept on; then judged below.
    const off = await page.evaluate(canvasPixels);
    await page.check('#cloud');
    const on = await pixelsOnceChanged(page, off, 0.02);
    await page.screenshot({ path: path.join(outDir, 'console_cloud.png') });
    await page.selectOption('#cloud-mode', 'height');
    const height = await pixelsOnceChanged(page, on, 0.02);
    await page.uncheck('#cloud');
    const offAgain = await pixelsOnceChanged(page, height, 0.02);
    cloud = {
      info: await page.evaluate(() => document.getElementById('cloud-info').textContent),
      toggle_changed: Number(pixelsDiffer(off, on).toFixed(4)),
      mode_changed: Number(pixelsDiffer(on, height).toFixed(4)),
      off_again_changed: Number(pixelsDiffer(off, offAgain).toFixed(4)),
    };
    // The robot idles while this runs: only the layer changes the picture.
    if (!(cloud.toggle_changed > 0.02)) throw new Error(`showing the cloud changed ${cloud.toggle_changed} of the pixels`);
    if (!(cloud.mode_changed > 0.02)) throw new Error(`colouring by height changed ${cloud.mode_changed} of the pixels`);
  }

  // ---- 3. W drives forwards --------------------------------------------------------------
  s.mark('drive');
  // The top-down camera, for the screenshots; then focus back on the page so that keys drive.
  await page.check('input[name=camera][value=top]');
  await page.evaluate(() => document.activeElement && document.activeElement.blur());
  const before = await clock();
  await page.keyboard.down('w');
  await untilMoved(before, 0.4);
  await page.keyboard.up('w');
  await simWait(0.7); // the stop arrives, the robot comes to rest
  const after = await clock();
  const dx = after.x - before.x, dy = after.y - before.y;
  const moved = Math.hypot(dx, dy);
  await page.screenshot({ path: path.join(outDir, 'console_after_drive.png') });
  if (!(moved > 0.2)) throw new Error(`holding W moved the robot ${moved.toFixed(3)} m (${JSON.stringify(before)} -> ${JSON.stringify(after)})`);

  // ---- 4. the on-screen forward button -----------------------------------------------------
  s.mark('buttons');
  const forward = page.locator('[data-drive=forward]');
  await forward.dispatchEvent('pointerdown');
  await untilMoved(after, 0.4);
  await forward.dispatchEvent('pointerup');
  await simWait(0.7);
  const afterButton = await clock();
  const buttonDx = afterButton.x - after.x;
  if (!(buttonDx > 0.2)) throw new Error(`the forward button moved the robot ${buttonDx.toFixed(3)} m east`);

  // ---- 5. the (fake) gamepad: stick back, the robot reverses --------------------------------
  s.mark('gamepad');
  await page.evaluate(() => {
    window.__fakePad = { id: 'semsim test pad', index: 0, connected: true, axes: [0, 0.8, 0, 0], buttons: [] };
  });
  await untilMoved(afterButton, 0.4);
  await page.evaluate(() => { window.__fakePad.axes = [0, 0, 0, 0]; });
  await simWait(0.7);
  const afterPad = await clock();
  const padDx = afterPad.x - afterButton.x;
  const padLabel = await page.evaluate(() => document.getElementById('gamepad').textContent);
  if (!(padDx < -0.2)) throw new Error(`the gamepad's stick (back) moved the robot ${padDx.toFixed(3)} m east`);
  if (!padLabel.includes('semsim test pad')) throw new Error(`the page does not name the gamepad: "${padLabel}"`);
  await page.evaluate(() => { window.__fakePad = null; });

  // ---- 6. turn left (north) and drive into the corridor's wall; the follow camera ---------
  s.mark('turn');
  await page.evaluate(() => document.activeElement && document.activeElement.blur());
  await page.keyboard.down('a');
  await page.waitForFunction(() => Number(document.getElementById('clock').dataset.yaw) > 75, null, { timeout: 30_000 })
    .catch(async () => { throw new Error(`the robot did not turn left to 75 degrees: ${JSON.stringify(await clock())}`); });
  await page.keyboard.up('a');
  s.mark('wall');
  await page.keyboard.down('w');
  const wallEvent = await page.waitForSelector('#events li.wall_touched', { timeout: 30_000 })
    .catch(async () => { throw new Error(`no wall_touched event in the timeline: ${JSON.stringify(await clock())}`); });
  await page.keyboard.up('w');
  await page.keyboard.press('Space');
  const wallText = await wallEvent.textContent();
  const atWall = await clock();
  await sleep(300);
  await page.screenshot({ path: path.join(outDir, 'console_wall_event.png') });
  s.mark('follow');
  await page.check('input[name=camera][value=follow]');
  // The page writes the follow camera's distance when it first places it; one more frame after.
  await page.waitForFunction(() => document.getElementById('view').dataset.followDistance !== undefined,
    null, { timeout: 60_000, polling: 100 });
  await simWait(0.2);
  const followDistance = await page.evaluate(() => document.getElementById('view').dataset.followDistance);
  await page.screenshot({ path: path.join(outDir, 'console_follow.png') });
  const followCanvas = await page.evaluate(canvasStats);
  assertNotBlank(followCanvas);

  return {
    canvas_width: canvas.width,
    canvas_height: canvas.height,
    canvas_colours: canvas.colours,
    canvas_non_background: Number(canvas.nonBackground.toFixed(4)),
    minimap,
    cloud,
    pose_before: before,
    pose_after: after,
    moved_m: Number(moved.toFixed(4)),
    moved_dx_m: Number(dx.toFixed(4)),
    button_dx_m: Number(buttonDx.toFixed(4)),
    gamepad_dx_m: Number(padDx.toFixed(4)),
    gamepad_label: padLabel,
    wall_event: wallText,
    pose_at_wall: atWall,
    follow_distance: followDistance,
  };
});
