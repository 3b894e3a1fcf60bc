// semsim console: the world from /world.glb (scene.js), the optional point-cloud layer
// (/api/cloud.json + /api/cloud.bin, cloud.js), the minimap (minimap.js), and the live session
// from the WebSocket /ws (protocol: crates/console/src/protocol.rs) or, with --run, the
// recorded run (replay.js). glTF is +Y up: semsim (x, y, z) = (x, z, -y).
import * as THREE from 'three';
import {
  DEG, createView, loadWorldUrl, showClass, setRobotPose, setDoorAngles, placeFollowCamera,
  placeTopCamera, visibleInScene,
} from 'semsim/scene.js';
import { createCloudLayer } from 'semsim/cloud.js';
import { createMinimap } from 'semsim/minimap.js';
import { startReplay } from 'semsim/replay.js';

const $ = (id) => document.getElementById(id);
const QUIET_EVENTS = new Set(['movement', 'collision_continued']);

// ---- scene -------------------------------------------------------------------------------
const view = $('view');
const v = createView(view);
const { renderer, scene, camera, controls } = v;

// ---- the world ---------------------------------------------------------------------------
let world = null;
const entities = new Map();
let minimap = null;

async function loadWorld() {
  const info = await (await fetch('/api/world.json')).json();
  for (const e of info.entities) entities.set(e.id, e);
  world = await loadWorldUrl(v, '/world.glb');
  showClass(world, 'ceiling', $('ceiling').checked);
  showClass(world, 'free_space_for_door', $('freespace').checked);
  minimap = createMinimap(view, world);
  await loadCloud();
}
$('ceiling').addEventListener('change', (e) => world && showClass(world, 'ceiling', e.target.checked));
$('freespace').addEventListener('change', (e) => world && showClass(world, 'free_space_for_door', e.target.checked));

// ---- the point-cloud layer (semsim console --cloud) --------------------------------------
let cloud = null;
async function loadCloud() {
  const meta = await (await fetch('/api/cloud.json')).json();
  if (!meta) return; // no --cloud: the controls stay hidden
  const body = await (await fetch('/api/cloud.bin')).arrayBuffer();
  cloud = createCloudLayer(scene, world, meta, body);
  $('cloud-section').hidden = false;
  $('cloud-info').textContent = `${meta.info.source}: ${meta.info.points} of ${meta.info.points_in_file} points (voxel ${meta.info.voxel_m.toFixed(3)} m)`;
  if (!meta.info.classes) $('cloud-mode').querySelector('option[value=class]').disabled = true;
  $('cloud-mode').value = meta.info.classes ? 'class' : 'height';
  cloud.setVisible($('cloud').checked);
}
$('cloud').addEventListener('change', (e) => cloud && cloud.setVisible(e.target.checked));
$('cloud-mode').addEventListener('change', (e) => cloud && cloud.setMode(e.target.value));

// ---- labels on hover ---------------------------------------------------------------------
const raycaster = new THREE.Raycaster();
const pointer = new THREE.Vector2();
const label = $('label');

function entityOf(o) {
  for (; o; o = o.parent) if (o.userData && o.userData.entity !== undefined) return o.userData.entity;
  return undefined;
}

function describe(id) {
  const e = entities.get(id);
  if (!e) return `entity ${id}`;
  const lines = [`${e.class} ${e.id}${e.name ? '  (' + e.name + ')' : ''}`];
  if (e.label) lines.push(e.label);
  for (const r of e.relations.slice(0, 8)) {
    const other = entities.get(r.other);
    const name = other ? `${other.class} ${other.id}` : r.other;
    lines.push(r.role === 'subject' ? `${r.type} ${name}` : `${name} ${r.type} this`);
  }
  if (e.relations.length > 8) lines.push(`... ${e.relations.length - 8} more relations`);
  return lines.join('\n');
}

renderer.domElement.addEventListener('pointermove', (ev) => {
  if (!world) return;
  const rect = renderer.domElement.getBoundingClientRect();
  pointer.set(((ev.clientX - rect.left) / rect.width) * 2 - 1, -((ev.clientY - rect.top) / rect.height) * 2 + 1);
  raycaster.setFromCamera(pointer, camera);
  const hit = raycaster.intersectObject(world.root, true).find((h) => visibleInScene(h.object));
  const id = hit ? entityOf(hit.object) : undefined;
  label.hidden = id === undefined;
  if (id !== undefined) {
    label.textContent = describe(id);
    label.style.left = `${ev.clientX - rect.left + 14}px`;
    label.style.top = `${ev.clientY - rect.top + 14}px`;
  }
});

// ---- cameras -----------------------------------------------------------------------------
let cameraMode = 'orbit';
for (const r of document.querySelectorAll('input[name=camera]')) {
  r.addEventListener('change', () => {
    cameraMode = r.value;
    controls.enabled = cameraMode === 'orbit';
    camera.up.set(0, 1, 0);
    if (cameraMode === 'orbit') controls.update();
  });
}

function placeCamera() {
  if (cameraMode === 'orbit' || !world || !world.robot) return;
  if (cameraMode === 'follow') {
    // How far the camera was pulled in by a wall behind the robot (m; none: not pulled in),
    // as data for tests.
    const pulled = placeFollowCamera(v, world, robotYaw);
    view.dataset.followDistance = pulled === null ? 'free' : pulled.toFixed(2);
  } else placeTopCamera(v, world);
}

// ---- live state --------------------------------------------------------------------------
let robotYaw = 0;
let session = 0;
let hello = null;
let role = 'watcher';

function applyState(s) {
  const r = s.robot;
  if (r && world && world.robot) {
    const p = r.pose;
    setRobotPose(world, p, r.rotation_xyzw);
    robotYaw = p.yaw_deg * DEG;
    // The pose as data, for tests and tools (tools/oracles/console_e2e.mjs).
    Object.assign($('clock').dataset, { x: p.x_m, y: p.y_m, yaw: p.yaw_deg });
    r.wheel_angles_rad.forEach((a, i) => world.wheels[i] && world.wheels[i].rotation.set(0, 0, -a));
    r.arm_angles_deg.forEach((deg, i) => {
      if (deg !== null && world.arm[i]) world.arm[i].node.quaternion.setFromAxisAngle(world.arm[i].axis, deg * DEG);
    });
  }
  if (world) setDoorAngles(world, s.doors.map((d) => [d.entity, d.angle_deg]));
  const limit = hello ? hello.scenario.time_limit_s : 0;
  const who = s.operator ? `operator (${s.operator.linear_m_s.toFixed(2)} m/s, ${s.operator.angular_rad_s.toFixed(2)} rad/s)` : 'scenario';
  const touching = s.contacts.map((id) => (entities.get(id) || { class: 'entity' }).class + ' ' + id);
  $('clock').textContent = `t = ${s.time_s.toFixed(2)} / ${limit} s, x${s.speed}` +
    `${s.finished ? ', ended' : s.paused ? ', paused' : ''}\ndriven by ${who}` +
    (touching.length ? `\ntouching ${touching.join(', ')}` : '');
  $('pause').textContent = s.paused ? 'Resume' : 'Pause';
  $('clock').dataset.time = s.time_s;
}

function newSession(n) {
  if (n === session) return;
  session = n;
  $('events').replaceChildren();
  $('verdict').hidden = true;
}

function addEvent(ev) {
  if (QUIET_EVENTS.has(ev.kind)) return;
  const li = document.createElement('li');
  li.className = ev.kind;
  const who = ev.entities.slice(1).map((e) => `${e.class} ${e.id}`).join(', ');
  li.textContent = `${ev.time_s.toFixed(2)} s  ${ev.kind.replaceAll('_', ' ')}${who ? ': ' + who : ''}${ev.detail ? ' (' + ev.detail + ')' : ''}`;
  const list = $('events');
  list.prepend(li);
  while (list.childElementCount > 500) list.lastElementChild.remove();
}

function showRules(rules) {
  $('rules').replaceChildren(...rules.map((r) => {
    const li = document.createElement('li');
    li.className = r.state;
    li.textContent = `${r.rule}: ${r.state}`;
    const why = document.createElement('span');
    why.className = 'reason';
    why.textContent = r.reason;
    li.append(why);
    return li;
  }));
}

function showVerdict(m) {
  const v = m.verdict, el = $('verdict');
  el.hidden = false;
  el.className = v.passed ? 'passed' : 'failed';
  const how = v.interrupted_at_s != null ? `saved at ${v.interrupted_at_s.toFixed(2)} s (not finished)` : `at ${v.end_time_s.toFixed(2)} s`;
  el.textContent = `verdict: ${v.passed ? 'PASSED' : 'FAILED'} ${how}${m.saved_as ? ', saved as ' + m.saved_as : ''}`;
  showRules(v.rules.map((r) => ({ rule: r.rule, state: r.passed ? 'passed' : 'failed', reason: r.reason })));
}

function setStatus(text, error = false) {
  $('status').textContent = text;
  $('status').className = error ? 'error' : '';
}

function setRole(r) {
  role = r;
  setStatus(r === 'driver' ? 'connected: you drive' : 'connected: you watch (another tab drives)');
  for (const b of document.querySelectorAll('#panel button, #speed')) b.disabled = r !== 'driver';
}

// ---- the connection ----------------------------------------------------------------------
let socket = null;

function connect() {
  socket = new WebSocket(`ws://${location.host}/ws`);
  socket.addEventListener('message', (e) => {
    const m = JSON.parse(e.data);
    switch (m.type) {
      case 'hello':
        hello = m;
        newSession(m.session);
        showRules(m.scenario.rules);
        setRole(m.role);
        break;
      case 'state': newSession(m.session); applyState(m); break;
      case 'event': newSession(m.session); addEvent(m.event); break;
      case 'rules': newSession(m.session); showRules(m.rules); break;
      case 'verdict': newSession(m.session); showVerdict(m); break;
      case 'role': setRole(m.role); break;
      case 'error': setStatus(`refused: ${m.message}`, true); break;
    }
  });
  socket.addEventListener('close', () => {
    setStatus('disconnected: reconnecting...', true);
    setTimeout(connect, 2000);
  });
}

function send(message) {
  if (socket && socket.readyState === WebSocket.OPEN && role === 'driver') socket.send(JSON.stringify(message));
}

// ---- driving: keys, buttons, gamepad -----------------------------------------------------
const KEYS = {
  KeyW: 'forward', ArrowUp: 'forward', KeyS: 'back', ArrowDown: 'back',
  KeyA: 'left', ArrowLeft: 'left', KeyD: 'right', ArrowRight: 'right',
};
const held = new Set();
let lastDrive = null;

function drive(v, w) {
  const round = (x) => Math.round(x * 1000) / 1000 + 0; // + 0: no -0
  v = round(v);
  w = round(w);
  const key = `${v.toFixed(3)},${w.toFixed(3)}`;
  if (key === lastDrive) return;
  lastDrive = key;
  if (v === 0 && w === 0) send({ type: 'stop' });
  else send({ type: 'drive', linear_m_s: v, angular_rad_s: w });
}

function driveFromHeld() {
  if (!hello) return;
  const r = hello.world.robot;
  const f = (held.has('forward') ? 1 : 0) - (held.has('back') ? 1 : 0);
  const t = (held.has('left') ? 1 : 0) - (held.has('right') ? 1 : 0);
  drive(f * r.max_speed_mps * 0.8, t * r.max_yaw_rate_radps * 0.6);
}

function stop() {
  held.clear();
  lastDrive = null;
  drive(0, 0);
}

window.addEventListener('keydown', (e) => {
  if (e.target.closest && e.target.closest('select, input')) return;
  if (e.code === 'Space') { e.preventDefault(); stop(); return; }
  const dir = KEYS[e.code];
  if (!dir) return;
  e.preventDefault();
  if (e.repeat) return;
  held.add(dir);
  driveFromHeld();
});
window.addEventListener('keyup', (e) => {
  const dir = KEYS[e.code];
  if (dir && held.delete(dir)) driveFromHeld();
});
window.addEventListener('blur', () => { if (held.size) { held.clear(); driveFromHeld(); } });

for (const b of document.querySelectorAll('[data-drive]')) {
  const dir = b.dataset.drive;
  b.addEventListener('pointerdown', () => { held.add(dir); driveFromHeld(); });
  for (const end of ['pointerup', 'pointerleave']) {
    b.addEventListener(end, () => { if (held.delete(dir)) driveFromHeld(); });
  }
}
$('stop').addEventListener('click', stop);
$('pause').addEventListener('click', () => send({ type: $('pause').textContent === 'Pause' ? 'pause' : 'resume' }));
$('step').addEventListener('click', () => send({ type: 'step' }));
$('save').addEventListener('click', () => send({ type: 'save' }));
$('reset').addEventListener('click', () => send({ type: 'reset' }));
$('speed').addEventListener('change', (e) => send({ type: 'speed', factor: Number(e.target.value) }));

let padActive = false;
let padSentAt = 0;
function pollGamepad(now) {
  const pad = navigator.getGamepads ? [...navigator.getGamepads()].find((p) => p) : null;
  $('gamepad').textContent = pad ? `Gamepad: ${pad.id}` : '';
  if (!pad || !hello || held.size || now - padSentAt < 50) return;
  const dead = (a) => (Math.abs(a) < 0.15 ? 0 : a);
  const x = dead(pad.axes[0] || 0), y = dead(pad.axes[1] || 0);
  if (x === 0 && y === 0 && !padActive) return;
  padActive = x !== 0 || y !== 0;
  padSentAt = now;
  const r = hello.world.robot;
  drive(-y * r.max_speed_mps, -x * r.max_yaw_rate_radps);
}

// ---- go ----------------------------------------------------------------------------------
renderer.setAnimationLoop((now) => {
  pollGamepad(now);
  placeCamera();
  if (minimap) minimap.draw(robotYaw);
  renderer.render(scene, camera);
});

// A console started with --run serves a recorded run (/api/run.json) to replay; a live one
// answers null there, and the page connects to the simulation.
loadWorld()
  .then(() => fetch('/api/run.json'))
  .then((r) => r.json())
  .then((run) => {
    if (run) startReplay(run, scene, world, (p) => { robotYaw = p.yaw_deg * DEG; });
    else connect();
  })
  .catch((e) => setStatus(`cannot load the world: ${e}`, true));
