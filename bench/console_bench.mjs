// Figures for the operator console (issue 14), measured against the real binary on loopback:
//   1. the server's CPU (utime + stime from /proc/PID/stat, % of one core) while one WebSocket
//      client watches the simulation run at x1, and whether simulated time kept up with wall
//      time (>= 0.95x) at the scenario's fixed step;
//   2. `state` messages: mean and max bytes, messages per second;
//   3. headless Chromium: time from page.goto to the first frame with the world in it (the page
//      has no "loaded" hook, so the canvas is polled for non-background pixels);
//   4. headless Chromium (SwiftShader software WebGL): frames per second over 5 s
//      (requestAnimationFrame counting in page.evaluate), with the point-cloud layer shown
//      when the console has one (--cloud).
// Run by bench/console.sh, which starts `semsim console` and passes its URL and PID:
//
//     node --experimental-websocket bench/console_bench.mjs URL PID RESULTS_DIR
//
// Node 20 needs --experimental-websocket for the global WebSocket (Node 22 has it by default).
// CHROMIUM names the browser (default /usr/bin/chromium); WS_SECONDS (default 20) and
// FPS_SECONDS (default 5) the windows; CONSOLE_CMD the console's command line (for the
// results' header).
import { readFileSync, writeFileSync, mkdirSync } from 'node:fs';
import { execSync } from 'node:child_process';
import os from 'node:os';
import path from 'node:path';

import { launch } from '../tools/oracles/browser.mjs';

const [url, pidArg, resultsDir] = process.argv.slice(2);
if (!url || !pidArg || !resultsDir) {
  console.error('usage: node --experimental-websocket console_bench.mjs URL PID RESULTS_DIR');
  process.exit(2);
}
if (typeof WebSocket !== 'function') {
  console.error('console_bench: no global WebSocket (Node >= 22, or Node 20 with --experimental-websocket)');
  process.exit(2);
}
const pid = Number(pidArg);
const WS_SECONDS = Number(process.env.WS_SECONDS || 20);
const FPS_SECONDS = Number(process.env.FPS_SECONDS || 5);
const CLK_TCK = Number(execSync('getconf CLK_TCK').toString().trim());
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
const round = (x, d = 3) => (Number.isFinite(x) ? Number(x.toFixed(d)) : null);

/** utime + stime of the server (s). */
function cpuSeconds() {
  const stat = readFileSync(`/proc/${pid}/stat`, 'utf8');
  // The command name may hold spaces: the fields start after its closing parenthesis.
  const f = stat.slice(stat.lastIndexOf(')') + 2).split(' ');
  // After the name: state is field 3 (index 0 here), utime field 14, stime field 15.
  return (Number(f[11]) + Number(f[12])) / CLK_TCK;
}
const loadavg = () => os.loadavg().map((x) => round(x, 2));

/** CPU % of one core over `seconds` of wall time, with nothing else happening. */
async function cpuOver(seconds) {
  const c0 = cpuSeconds(), w0 = performance.now();
  await sleep(seconds * 1000);
  const c1 = cpuSeconds(), w1 = performance.now();
  return { wall_s: round((w1 - w0) / 1000), cpu_s: round(c1 - c0), cpu_pct_one_core: round(100 * (c1 - c0) / ((w1 - w0) / 1000), 1) };
}

const results = {
  date: new Date().toISOString(),
  url,
  machine: { cpus: os.cpus().length, cpu_model: os.cpus()[0]?.model, loadavg_start: loadavg(), node: process.version },
};

// ---- 0. baseline: the simulation stepping with no client connected --------------------------
results.server_no_client = await cpuOver(5);

// ---- 1 + 2. one WebSocket client, x1, WS_SECONDS ----------------------------------------------
const wsUrl = url.replace(/^http/, 'ws').replace(/\/?$/, '/ws');
const ws = new WebSocket(wsUrl);
const states = []; // { wall_ms, bytes, time_s, finished }
const counts = {};
let hello = null;
let finishedAt = null;
await new Promise((resolve, reject) => {
  ws.addEventListener('open', resolve, { once: true });
  ws.addEventListener('error', (e) => reject(new Error(`WebSocket ${wsUrl}: ${e.message || 'error'}`)), { once: true });
});
let recording = false;
ws.addEventListener('message', (e) => {
  const text = typeof e.data === 'string' ? e.data : Buffer.from(e.data).toString('utf8');
  const m = JSON.parse(text);
  counts[m.type] = (counts[m.type] || 0) + 1;
  if (m.type === 'hello') hello = m;
  if (m.type === 'state' && recording) {
    states.push({ wall_ms: performance.now(), bytes: Buffer.byteLength(text, 'utf8'), time_s: m.time_s, finished: m.finished, speed: m.speed });
    if (m.finished && finishedAt === null) finishedAt = performance.now();
  }
});
while (!hello) await sleep(10);
ws.send(JSON.stringify({ type: 'speed', factor: 1 }));
await sleep(500); // the speed applied, the connection settled
recording = true;
const c0 = cpuSeconds(), w0 = performance.now();
while (performance.now() - w0 < WS_SECONDS * 1000 && finishedAt === null) await sleep(20);
const c1 = cpuSeconds(), w1 = performance.now();
recording = false;
ws.close();

const wallS = (w1 - w0) / 1000;
const running = states.filter((s) => !s.finished);
const first = running[0], last = running[running.length - 1];
const simS = last && first ? last.time_s - first.time_s : NaN;
const simWallS = last && first ? (last.wall_ms - first.wall_ms) / 1000 : NaN;
const bytes = states.map((s) => s.bytes);
const dt = hello.scenario.dt_secs;
results.scenario = {
  name: hello.scenario.name,
  time_limit_s: hello.scenario.time_limit_s,
  dt_secs: dt,
  step_hz: round(1 / dt, 2),
  robot: hello.world.robot.model,
  world: hello.world.name,
};
results.server_one_client = {
  wall_s: round(wallS),
  cpu_s: round(c1 - c0),
  cpu_pct_one_core: round(100 * (c1 - c0) / wallS, 1),
  sim_time_s: round(simS),
  sim_time_at_window_start_s: first ? round(first.time_s) : null,
  sim_time_at_window_end_s: last ? round(last.time_s) : null,
  wall_between_first_and_last_state_s: round(simWallS),
  realtime_factor: round(simS / simWallS, 4),
  real_time_held: simS / simWallS >= 0.95,
  scenario_finished_in_window: finishedAt !== null,
  role: hello.role,
};
results.state_messages = {
  count: states.length,
  per_s: round(states.length / wallS, 2),
  mean_bytes: round(bytes.reduce((a, b) => a + b, 0) / bytes.length, 1),
  max_bytes: Math.max(...bytes),
  min_bytes: Math.min(...bytes),
  kbit_per_s: round(bytes.reduce((a, b) => a + b, 0) * 8 / 1000 / wallS, 1),
  messages_by_type: counts,
};

// ---- 3 + 4. headless Chromium ----------------------------------------------------------------
const browser = await launch();
const consoleErrors = [];
try {
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  page.setDefaultTimeout(120_000);
  page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
  page.on('pageerror', (e) => consoleErrors.push(e.message));
  const cb0 = cpuSeconds(), wb0 = performance.now();
  const tGoto = performance.now();
  await page.goto(url, { waitUntil: 'commit' });
  // Polls the canvas (preserveDrawingBuffer: the last frame), shrunk to 160x100, for pixels
  // that are not the scene's background #1d2127: the world is drawn when >= 5% are not.
  const firstWorld = await page.waitForFunction(() => {
    const gl = document.querySelector('#view canvas');
    if (!gl || gl.width < 100) return false;
    const c = (window.__benchCanvas ||= Object.assign(document.createElement('canvas'), { width: 160, height: 100 }));
    const ctx = c.getContext('2d', { willReadFrequently: true });
    ctx.drawImage(gl, 0, 0, c.width, c.height);
    const px = ctx.getImageData(0, 0, c.width, c.height).data;
    let other = 0;
    for (let i = 0; i < px.length; i += 4) {
      if (Math.abs(px[i] - 0x1d) + Math.abs(px[i + 1] - 0x21) + Math.abs(px[i + 2] - 0x27) > 12) other++;
    }
    const frac = other / (px.length / 4);
    return frac >= 0.05 ? { since_navigation_ms: performance.now(), non_background: frac } : false;
  }, null, { polling: 'raf', timeout: 120_000 }).then((h) => h.jsonValue());
  const tFirst = performance.now();
  const nav = await page.evaluate(() => {
    const n = performance.getEntriesByType('navigation')[0];
    const r = performance.getEntriesByType('resource').find((e) => e.name.endsWith('/world.glb'));
    return {
      dom_content_loaded_ms: n ? n.domContentLoadedEventEnd : null,
      load_event_ms: n ? n.loadEventEnd : null,
      glb_fetched_ms: r ? r.responseEnd : null,
      glb_bytes: r ? r.transferSize || r.encodedBodySize : null,
    };
  });
  await page.waitForFunction(() => /connected/.test(document.getElementById('status').textContent), null, { timeout: 60_000 });
  const tConnected = performance.now();
  results.browser_first_world = {
    from_goto_ms: round(tFirst - tGoto, 0),
    since_navigation_start_ms: round(firstWorld.since_navigation_ms, 0),
    non_background_fraction: round(firstWorld.non_background, 3),
    glb_fetched_since_navigation_ms: round(nav.glb_fetched_ms, 0),
    glb_bytes: nav.glb_bytes,
    dom_content_loaded_ms: round(nav.dom_content_loaded_ms, 0),
    goto_to_websocket_connected_ms: round(tConnected - tGoto, 0),
    method: 'page.goto (waitUntil commit) to the first requestAnimationFrame poll whose canvas, drawn into a 160x100 2D canvas, has >= 5% pixels off the background #1d2127 (no loaded hook in app.js)',
  };
  const measureFps = () => page.evaluate((seconds) => new Promise((resolve) => {
    const times = [];
    const t0 = performance.now();
    const tick = (t) => {
      times.push(t);
      if (t - t0 < seconds * 1000) requestAnimationFrame(tick);
      else {
        const gaps = times.slice(1).map((x, i) => x - times[i]).sort((a, b) => a - b);
        resolve({
          frames: times.length - 1,
          seconds: (times[times.length - 1] - times[0]) / 1000,
          median_frame_ms: gaps[Math.floor(gaps.length / 2)],
          p95_frame_ms: gaps[Math.floor(gaps.length * 0.95)],
          max_frame_ms: gaps[gaps.length - 1],
          canvas: [document.querySelector('#view canvas').width, document.querySelector('#view canvas').height],
          dpr: window.devicePixelRatio,
        });
      }
    };
    requestAnimationFrame(tick);
  }), FPS_SECONDS);
  // The cloud layer: its size on the wire and in points, shown for the frame rate.
  const cloudMeta = await page.evaluate(() => fetch('/api/cloud.json').then((r) => r.json()));
  if (cloudMeta) {
    await page.waitForSelector('#cloud-section:not([hidden])', { timeout: 120_000 });
    const tCloud = performance.now();
    const res = await page.evaluate(() => {
      const r = performance.getEntriesByType('resource').find((e) => e.name.endsWith('/api/cloud.bin'));
      return r ? { bytes: r.transferSize || r.encodedBodySize, fetched_ms: r.responseEnd } : null;
    });
    await sleep(1000);
    const hidden = await measureFps();
    results.browser_fps_cloud_hidden = { fps: round(hidden.frames / hidden.seconds, 1), median_frame_ms: round(hidden.median_frame_ms, 1) };
    await page.check('#cloud');
    results.cloud_layer = {
      ...cloudMeta.info,
      body_bytes: res ? res.bytes : null,
      body_fetched_since_navigation_ms: res ? round(res.fetched_ms, 0) : null,
      goto_to_layer_ready_ms: round(tCloud - tGoto, 0),
      shown_for_frame_rate: true,
    };
  }
  await sleep(1000); // settle

  const fps = await measureFps();
  const cb1 = cpuSeconds(), wb1 = performance.now();
  results.browser_fps = {
    fps: round(fps.frames / fps.seconds, 1),
    frames: fps.frames,
    seconds: round(fps.seconds),
    median_frame_ms: round(fps.median_frame_ms, 1),
    p95_frame_ms: round(fps.p95_frame_ms, 1),
    max_frame_ms: round(fps.max_frame_ms, 1),
    canvas_px: fps.canvas,
    device_pixel_ratio: fps.dpr,
    renderer: 'headless Chromium, --use-angle=swiftshader (software WebGL)',
  };
  results.server_with_browser = {
    wall_s: round((wb1 - wb0) / 1000),
    cpu_pct_one_core: round(100 * (cb1 - cb0) / ((wb1 - wb0) / 1000), 1),
  };
  results.browser_console_errors = consoleErrors;
  results.chromium_version = browser.version();
} finally {
  await browser.close();
}
results.machine.loadavg_end = loadavg();

// ---- out ----------------------------------------------------------------------------------
mkdirSync(resultsDir, { recursive: true });
writeFileSync(path.join(resultsDir, 'console.json'), JSON.stringify(results, null, 2) + '\n');
const s1 = results.server_one_client, sm = results.state_messages, bf = results.browser_first_world, fp = results.browser_fps;
const rows = [
  ['server CPU, sim at x1, no client (5 s)', `${results.server_no_client.cpu_pct_one_core} % of one core`],
  [`server CPU, sim at x1, 1 WebSocket client (${s1.wall_s} s)`, `${s1.cpu_pct_one_core} % of one core`],
  [`real time held at ${results.scenario.step_hz} Hz step (sim/wall >= 0.95)`, `${s1.real_time_held ? 'yes' : 'NO'} (${s1.realtime_factor}x: ${s1.sim_time_s} s sim in ${s1.wall_between_first_and_last_state_s} s wall)`],
  ['state messages per second', `${sm.per_s} (${sm.count} in ${s1.wall_s} s)`],
  ['state message size, mean / max', `${sm.mean_bytes} / ${sm.max_bytes} bytes (${sm.kbit_per_s} kbit/s)`],
  ['Chromium: page.goto to first frame with the world', `${bf.from_goto_ms} ms (GLB ${bf.glb_bytes} bytes fetched at ${bf.glb_fetched_since_navigation_ms} ms)`],
  ['Chromium: goto to WebSocket connected', `${bf.goto_to_websocket_connected_ms} ms`],
  [`Chromium frame rate, software WebGL, ${fp.canvas_px.join('x')} (${fp.seconds} s)`, `${fp.fps} fps (median ${fp.median_frame_ms} ms, p95 ${fp.p95_frame_ms} ms)`],
  ...(results.browser_fps_cloud_hidden ? [[
    'Chromium frame rate, same, cloud layer hidden',
    `${results.browser_fps_cloud_hidden.fps} fps (median ${results.browser_fps_cloud_hidden.median_frame_ms} ms)`,
  ]] : []),
  ...(results.cloud_layer ? [[
    'cloud layer (shown during the frame rate)',
    `${results.cloud_layer.points} of ${results.cloud_layer.points_in_file} points (voxel ${round(results.cloud_layer.voxel_m, 3)} m, classes ${results.cloud_layer.classes ? 'yes' : 'no'}), ${results.cloud_layer.body_bytes} bytes binary, ready ${results.cloud_layer.goto_to_layer_ready_ms} ms after goto`,
  ]] : []),
  ['server CPU while the browser loads and renders', `${results.server_with_browser.cpu_pct_one_core} % of one core`],
  ['load average (1/5/15 min), start -> end', `${results.machine.loadavg_start.join(' ')} -> ${results.machine.loadavg_end.join(' ')} on ${results.machine.cpus} CPUs`],
];
const md = [
  '# Operator console figures',
  '',
  `\`bash bench/console.sh\` on ${results.date}: \`${process.env.CONSOLE_CMD || 'semsim console'}\` (scenario "${results.scenario.name}", ${results.scenario.world}, robot ${results.scenario.robot}, step ${results.scenario.dt_secs} s), loopback, ${results.machine.cpus} CPUs (${results.machine.cpu_model}), Chromium ${results.chromium_version}.`,
  '',
  '| measure | value |',
  '|---|---|',
  ...rows.map(([k, v]) => `| ${k} | ${v} |`),
  '',
  'Method: CPU is utime + stime of the server process from `/proc/PID/stat` over the window (% of one core). The WebSocket client is Node\'s global WebSocket (no `Origin` header, so the server accepts it); it sends `speed {factor: 1}` and records every `state` message (bytes = UTF-8 length of the JSON text). Real time: simulated `time_s` advanced between the first and last `state` of the window over the wall time between their arrivals. First world: `page.goto` (waitUntil commit) to the first animation frame whose canvas has >= 5% pixels off the background colour (app.js has no loaded hook). Frame rate: requestAnimationFrame callbacks counted in the page for ' + FPS_SECONDS + ' s, the simulation running.',
  '',
  'Caveat: figures are from one run on a shared machine; the load average above says how busy it was (other jobs compete for the same cores, which inflates the browser\'s times and lowers its frame rate more than the server\'s figures).',
  '',
];
writeFileSync(path.join(resultsDir, 'console.md'), md.join('\n'));
const w = Math.max(...rows.map(([k]) => k.length));
console.log(rows.map(([k, v]) => `${k.padEnd(w)}  ${v}`).join('\n'));
if (consoleErrors.length) console.log(`browser console errors: ${consoleErrors.join(' | ')}`);
