// semsim console, replay mode (`semsim console --run RUN_DIR`): the recorded run from
// /api/run.json replayed on the world the page loaded: a time slider, play/pause and speed;
// the robot follows the slider and a click on a timeline event jumps to its moment. Nothing is
// driven: the page opens no WebSocket. The doors swing as `doors.csv` recorded them.
import * as THREE from 'three';
import { poseAt, doorAnglesAt, setRobotPose, setDoorAngles } from 'semsim/scene.js';

const $ = (id) => document.getElementById(id);

/**
 * Replays `run` ({title, verdict, passed, rules, trajectory, doors, events}) in `scene`,
 * moving the robot and swinging the doors of `world` (scene.js) as recorded (a run without
 * door angles leaves the doors at their initial angle); `onPose(p)` hears every pose shown.
 */
export function startReplay(run, scene, world, onPose) {
  const track = run.trajectory;
  const t0 = track[0].time_s, t1 = track[track.length - 1].time_s;
  for (const id of ['sim-section', 'drive-section']) $(id).hidden = true;
  $('replay').hidden = false;
  $('status').textContent = `replaying ${run.title}: ${track.length} trajectory points, ${run.events.length} events`;

  const line = new THREE.Line(
    new THREE.BufferGeometry().setFromPoints(track.map((p) => new THREE.Vector3(p.x_m, p.z_m + 0.05, -p.y_m))),
    new THREE.LineBasicMaterial({ color: 0x4fc3f7 }));
  scene.add(line);

  const v = $('verdict');
  v.hidden = false;
  v.className = run.passed ? 'passed' : 'failed';
  v.textContent = `verdict: ${run.verdict}`;
  $('rules').replaceChildren(...run.rules.map((r) => {
    const li = document.createElement('li');
    li.className = r.result === 'passed' ? 'passed' : r.result === 'FAILED' ? 'failed' : 'pending';
    li.textContent = `${r.rule}: ${r.result}`;
    const why = document.createElement('span');
    why.className = 'reason';
    why.textContent = r.reason;
    li.append(why);
    return li;
  }));

  const slider = $('replay-slider');
  slider.min = String(t0);
  slider.max = String(t1);
  slider.step = 'any';
  let t = t0, playing = false, last = null;

  function show(time) {
    t = Math.min(Math.max(time, t0), t1);
    slider.value = String(t);
    const p = poseAt(track, t);
    setRobotPose(world, p);
    const doors = doorAnglesAt(run.doors, t);
    setDoorAngles(world, doors);
    $('clock').textContent = `t = ${t.toFixed(2)} / ${t1.toFixed(2)} s (replay)`;
    Object.assign($('clock').dataset, {
      x: p.x_m, y: p.y_m, yaw: p.yaw_deg, time: t,
      doors: doors.map(([id, a]) => `${id}:${a.toFixed(2)}`).join(' '),
    });
    onPose(p);
  }

  const list = $('events');
  list.replaceChildren(...run.events.filter((ev) => ev.kind !== 'movement').map((ev) => {
    const li = document.createElement('li');
    li.className = ev.kind;
    li.dataset.time = String(ev.time_s);
    const who = (ev.entities || []).slice(1).map((e) => `${e.class} ${e.id}`).join(', ');
    li.textContent = `${Number(ev.time_s).toFixed(2)} s  ${ev.kind.replaceAll('_', ' ')}${who ? ': ' + who : ''}`;
    li.title = 'jump to this moment';
    li.style.cursor = 'pointer';
    li.addEventListener('click', () => { setPlaying(false); show(ev.time_s); });
    return li;
  }));

  function setPlaying(on) {
    playing = on;
    last = null;
    $('play').textContent = playing ? 'Pause' : 'Play';
  }
  $('play').addEventListener('click', () => {
    if (!playing && t >= t1) show(t0);
    setPlaying(!playing);
  });
  slider.addEventListener('input', () => { setPlaying(false); show(Number(slider.value)); });

  function tick(now) {
    if (playing) {
      if (last !== null) show(t + ((now - last) / 1000) * Number($('replay-speed').value));
      last = now;
      if (t >= t1) setPlaying(false);
    }
    requestAnimationFrame(tick);
  }
  requestAnimationFrame(tick);
  show(t0);
  // For tests and tools: the time shown and a way to set it.
  window.replay = { show, time: () => t };
}
