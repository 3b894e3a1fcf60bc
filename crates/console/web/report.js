// semsim run report: the world (GLB embedded as base64; scene.js), the run's trajectory as a
// line, its events marked on it and listed, the verdict and rules, a time slider that moves
// the robot and swings the doors as recorded, the minimap, and optionally a small downsampled
// point cloud. Everything is in this one file; nothing is fetched. glTF is +Y up: semsim
// (x, y, z) is (x, z, -y).
import * as THREE from 'three';
import {
  DEG, createView, loadWorldBytes, poseAt as poseOf, doorAnglesAt, setRobotPose, setDoorAngles,
  showClass,
} from 'semsim/scene.js';
import { createMinimap } from 'semsim/minimap.js';
import { createCloudLayer } from 'semsim/cloud.js';

const $ = (id) => document.getElementById(id);
const run = JSON.parse($('run').textContent);
const track = run.trajectory;
const toScene = (p, lift = 0) => new THREE.Vector3(p.x_m, p.z_m + lift, -p.y_m);
const poseAt = (t) => poseOf(track, t);

// ---- scene -------------------------------------------------------------------------------
const view = $('view');
const v = createView(view);
const { renderer, scene, camera, controls } = v;

// ---- the run: trajectory, event marks, robot marker --------------------------------------
const line = new THREE.Line(
  new THREE.BufferGeometry().setFromPoints(track.map((p) => toScene(p, 0.05))),
  new THREE.LineBasicMaterial({ color: 0x4fc3f7 }));
scene.add(line);

const SEVERE = new Set(['wall_touched', 'joint_broken', 'robot_tipped', 'robot_stuck', 'collision_started']);
const markGeometry = new THREE.SphereGeometry(0.09, 12, 8);
const movementMarks = [];
run.events.forEach((ev) => {
  const moving = ev.kind === 'movement';
  const color = moving ? 0x8a949f : SEVERE.has(ev.kind) ? 0xff7b72 : 0xffd54f;
  const mark = new THREE.Mesh(markGeometry, new THREE.MeshBasicMaterial({ color }));
  mark.position.copy(toScene(poseAt(ev.time_s), 0.05));
  if (moving) { mark.scale.setScalar(0.5); mark.visible = false; movementMarks.push(mark); }
  scene.add(mark);
});

const marker = new THREE.Mesh(new THREE.ConeGeometry(0.18, 0.45, 16),
  new THREE.MeshBasicMaterial({ color: 0x00e676 }));
marker.rotation.x = Math.PI;
scene.add(marker);
let world = null;
let minimap = null;

function showTime(t) {
  const p = poseAt(t);
  marker.position.copy(toScene(p, 1.0));
  if (world) {
    setRobotPose(world, p);
    setDoorAngles(world, doorAnglesAt(run.doors, t));
    if (minimap) minimap.draw(p.yaw_deg * DEG);
  }
  $('clock').textContent = `t = ${t.toFixed(2)} s  (x ${p.x_m.toFixed(2)}, y ${p.y_m.toFixed(2)}, z ${p.z_m.toFixed(2)} m)`;
  let current = null;
  for (const li of $('timeline').children) {
    li.classList.remove('current');
    if (Number(li.dataset.time) <= t + 1e-9) current = li;
  }
  if (current) current.classList.add('current');
}

// ---- the panel ---------------------------------------------------------------------------
$('title').textContent = run.title;
$('verdict').textContent = `Verdict: ${run.verdict}`;
$('verdict').className = run.passed ? 'passed' : 'failed';
for (const r of run.rules) {
  const tr = document.createElement('tr');
  tr.className = r.result === 'passed' ? 'passed' : r.result === 'FAILED' ? 'failed' : 'pending';
  for (const cell of [r.rule, r.result, r.decided_s ? `${r.decided_s} s` : '', r.reason]) {
    const td = document.createElement('td');
    td.textContent = cell;
    tr.appendChild(td);
  }
  $('rules').appendChild(tr);
}

const slider = $('slider');
slider.max = String(track.length - 1);
slider.addEventListener('input', () => showTime(track[Number(slider.value)].time_s));

function jumpTo(t) {
  let i = 0;
  while (i + 1 < track.length && track[i + 1].time_s <= t) i++;
  slider.value = String(i);
  showTime(t);
}

for (const ev of run.events) {
  const li = document.createElement('li');
  li.className = ev.kind;
  li.dataset.time = String(ev.time_s);
  const who = (ev.entities || []).filter((e) => e.class !== 'robot').map((e) => e.name).join(', ');
  li.textContent = `${Number(ev.time_s).toFixed(2)} s  ${ev.kind.replaceAll('_', ' ')}${who ? ': ' + who : ''}${ev.detail ? ' (' + ev.detail + ')' : ''}`;
  li.title = 'show this moment';
  li.addEventListener('click', () => jumpTo(ev.time_s));
  if (ev.kind === 'movement') li.hidden = true;
  $('timeline').appendChild(li);
}

function showMovement(on) {
  for (const m of movementMarks) m.visible = on;
  for (const li of $('timeline').querySelectorAll('li.movement')) li.hidden = !on;
}
$('movement').addEventListener('change', (e) => showMovement(e.target.checked));

// ---- the world and the optional cloud layer ----------------------------------------------
const base64Bytes = (id) => Uint8Array.from(atob($(id).textContent.trim()), (c) => c.charCodeAt(0));
let cloud = null;
async function loadWorld() {
  world = await loadWorldBytes(v, base64Bytes('glb').buffer);
  showClass(world, 'ceiling', $('ceiling').checked);
  minimap = createMinimap(view, world);
  const meta = JSON.parse($('cloud-meta').textContent);
  if (meta) {
    cloud = createCloudLayer(scene, world, meta, base64Bytes('cloud-bin').buffer);
    $('cloud-section').hidden = false;
    $('cloud-info').textContent = `${meta.info.source}: ${meta.info.points} of ${meta.info.points_in_file} points`;
    cloud.setVisible($('cloud').checked);
  }
  showTime(track[Number(slider.value)].time_s);
  $('status').textContent = `${track.length} trajectory points, ${run.events.length} events`;
  window.report.ready = true;
}
$('ceiling').addEventListener('change', (e) => world && showClass(world, 'ceiling', e.target.checked));
$('cloud').addEventListener('change', (e) => cloud && cloud.setVisible(e.target.checked));
$('cloud-mode').addEventListener('change', (e) => cloud && cloud.setMode(e.target.value));

// For tests and the curious: the marker's scene position and a way to set the time.
window.report = {
  markerPosition: () => marker.position.toArray(),
  robotPosition: () => (world && world.robot ? world.robot.position.toArray() : null),
  jumpTo,
  ready: false,
};

showTime(track[0].time_s);
loadWorld().catch((err) => {
  $('status').textContent = `could not load the world: ${err && err.message ? err.message : err}`;
  $('status').className = 'error';
  console.error(err);
});
renderer.setAnimationLoop(() => {
  controls.update();
  renderer.render(scene, camera);
});
