// semsim run report: the world (GLB embedded as base64), the run's trajectory as a line, its
// events marked on it and listed, the verdict and rules, and a time slider that moves the
// robot. Everything is in this one file; nothing is fetched. glTF is +Y up: semsim (x, y, z)
// is (x, z, -y).
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const $ = (id) => document.getElementById(id);
const DEG = Math.PI / 180;
const run = JSON.parse($('run').textContent);
const track = run.trajectory;
const toScene = (p, lift = 0) => new THREE.Vector3(p.x_m, p.z_m + lift, -p.y_m);

// ---- scene -------------------------------------------------------------------------------
const view = $('view');
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
view.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x1d2127);
scene.add(new THREE.HemisphereLight(0xffffff, 0x445566, 2.2));
const sun = new THREE.DirectionalLight(0xffffff, 1.6);
sun.position.set(8, 20, 6);
scene.add(sun);
const camera = new THREE.PerspectiveCamera(55, 1, 0.05, 1000);
const controls = new OrbitControls(camera, renderer.domElement);
function resize() {
  const w = view.clientWidth, h = view.clientHeight;
  renderer.setSize(w, h);
  camera.aspect = w / Math.max(h, 1);
  camera.updateProjectionMatrix();
}
window.addEventListener('resize', resize);
resize();

// ---- the run: trajectory, event marks, robot marker --------------------------------------
function poseAt(t) {
  if (t <= track[0].time_s) return track[0];
  let lo = 0, hi = track.length - 1;
  if (t >= track[hi].time_s) return track[hi];
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (track[mid].time_s <= t) lo = mid; else hi = mid;
  }
  const a = track[lo], b = track[hi];
  const f = (t - a.time_s) / Math.max(b.time_s - a.time_s, 1e-9);
  const mix = (k) => a[k] + (b[k] - a[k]) * f;
  return { time_s: t, x_m: mix('x_m'), y_m: mix('y_m'), z_m: mix('z_m'),
    roll_deg: a.roll_deg, pitch_deg: a.pitch_deg, yaw_deg: a.yaw_deg };
}

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
let robot = null;

function showTime(t) {
  const p = poseAt(t);
  marker.position.copy(toScene(p, 1.0));
  if (robot) {
    robot.position.copy(toScene(p));
    const q = new THREE.Quaternion().setFromEuler(
      new THREE.Euler(p.roll_deg * DEG, p.pitch_deg * DEG, p.yaw_deg * DEG, 'ZYX'));
    robot.quaternion.set(q.x, q.z, -q.y, q.w);
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

// ---- the world ---------------------------------------------------------------------------
const ceilings = [];
function loadWorld() {
  const text = $('glb').textContent.trim();
  const bytes = Uint8Array.from(atob(text), (c) => c.charCodeAt(0));
  new GLTFLoader().parse(bytes.buffer, '', (gltf) => {
    scene.add(gltf.scene);
    gltf.scene.traverse((o) => {
      const x = o.userData || {};
      if (x.class === 'robot' && x.model !== undefined) robot = o;
      if (x.class === 'ceiling') ceilings.push(o);
    });
    for (const c of ceilings) c.visible = $('ceiling').checked;
    const box = new THREE.Box3().setFromObject(gltf.scene);
    const center = box.getCenter(new THREE.Vector3());
    const size = Math.max(box.max.x - box.min.x, box.max.z - box.min.z, 4);
    controls.target.copy(center);
    camera.position.set(center.x, center.y + size * 0.8, center.z + size * 0.45);
    controls.update();
    showTime(track[Number(slider.value)].time_s);
    $('status').textContent = `${track.length} trajectory points, ${run.events.length} events`;
    window.report.ready = true;
  }, (err) => {
    $('status').textContent = `could not load the world: ${err && err.message ? err.message : err}`;
    $('status').className = 'error';
    console.error(err);
  });
}
$('ceiling').addEventListener('change', (e) => { for (const c of ceilings) c.visible = e.target.checked; });

// For tests and the curious: the marker's scene position and a way to set the time.
window.report = {
  markerPosition: () => marker.position.toArray(),
  robotPosition: () => (robot ? robot.position.toArray() : null),
  jumpTo,
  ready: false,
};

showTime(track[0].time_s);
loadWorld();
renderer.setAnimationLoop(() => {
  controls.update();
  renderer.render(scene, camera);
});
