// semsim's three.js scene, shared by the console page (app.js, replay.js) and the static run
// report (report.js, which inlines this module): renderer, lights, cameras, the world from its
// GLB, posing the robot and the doors, the follow camera and the recorded run's
// interpolation. glTF is +Y up: semsim (x, y, z) is (x, z, -y) in the scene.
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

export const DEG = Math.PI / 180;
/** The scene's background; the browser tests count pixels that differ from it. */
export const BACKGROUND = 0x1d2127;

/** A semsim point (metres, z up) in the scene's frame. */
export const toScene = (x, y, z) => new THREE.Vector3(x, z, -y);

/** The renderer in `container`, the scene with its lights, a camera and orbit controls. */
export function createView(container) {
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio);
  container.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(BACKGROUND);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x445566, 2.2));
  const sun = new THREE.DirectionalLight(0xffffff, 1.6);
  sun.position.set(8, 20, 6);
  scene.add(sun);
  const camera = new THREE.PerspectiveCamera(55, 1, 0.05, 1000);
  const controls = new OrbitControls(camera, renderer.domElement);
  const resize = () => {
    const w = container.clientWidth, h = container.clientHeight;
    renderer.setSize(w, h);
    camera.aspect = w / Math.max(h, 1);
    camera.updateProjectionMatrix();
  };
  window.addEventListener('resize', resize);
  resize();
  return { renderer, scene, camera, controls, container };
}

/** The GLB's class of a node: its own, or its nearest ancestor's. */
function classOf(o) {
  for (; o; o = o.parent) if (o.userData && o.userData.class !== undefined) return o.userData.class;
  return undefined;
}

/**
 * Adds the world (a parsed glTF) to the view's scene and indexes it: the robot node, its
 * wheels and arm links, the doors by entity, the nodes by class, each class's colour (for the
 * cloud layer and the minimap), the solid meshes (for the follow camera's raycast), the
 * footprint's centre and size; frames the orbit camera on it.
 */
export function addWorld(v, gltf) {
  const world = {
    root: gltf.scene, robot: null, wheels: [], arm: [], doors: new Map(), byClass: new Map(),
    classColours: new Map(), solids: [], center: new THREE.Vector3(), size: 10,
    box: new THREE.Box3(),
  };
  v.scene.add(gltf.scene);
  gltf.scene.traverse((o) => {
    const x = o.userData || {};
    if (x.wheel !== undefined) world.wheels[x.wheel] = o;
    else if (x.arm_link !== undefined) {
      world.arm[x.arm_link] = { node: o, axis: new THREE.Vector3(...x.joint_axis) };
    } else if (x.class === 'robot' && x.model !== undefined) world.robot = o;
    else if (x.hinge) world.doors.set(x.entity, { node: o, sign: x.hinge.opening_sign });
    if (x.class && x.entity !== undefined && x.wheel === undefined && x.arm_link === undefined) {
      if (!world.byClass.has(x.class)) world.byClass.set(x.class, []);
      world.byClass.get(x.class).push(o);
    }
    if (o.isMesh) {
      const cls = classOf(o);
      if (cls && o.material && o.material.color && !world.classColours.has(cls)) {
        world.classColours.set(cls, o.material.color.clone());
      }
      if (SOLID.has(cls)) world.solids.push(o);
    }
  });
  world.box.setFromObject(gltf.scene);
  world.box.getCenter(world.center);
  world.size = Math.max(world.box.max.x - world.box.min.x, world.box.max.z - world.box.min.z, 4);
  v.controls.target.copy(world.center);
  v.camera.position.set(world.center.x, world.center.y + world.size * 0.8, world.center.z + world.size * 0.45);
  v.controls.update();
  return world;
}

/** What the follow camera cannot see through. */
const SOLID = new Set(['wall', 'wall_above_door', 'door', 'column', 'beam', 'furniture', 'stairs', 'obstacle', 'ramp']);

/** Loads the world from a URL. */
export async function loadWorldUrl(v, url) {
  return addWorld(v, await new GLTFLoader().loadAsync(url));
}

/** Loads the world from GLB bytes (an ArrayBuffer). */
export function loadWorldBytes(v, buffer) {
  return new Promise((resolve, reject) => {
    new GLTFLoader().parse(buffer, '', (gltf) => resolve(addWorld(v, gltf)), reject);
  });
}

/** Shows or hides every node of a class. */
export function showClass(world, cls, visible) {
  for (const o of world.byClass.get(cls) || []) o.visible = visible;
}

/** Puts the robot node at a pose (`x_m, y_m, z_m, roll_deg, pitch_deg, yaw_deg`), or with a
 * semsim quaternion `[x, y, z, w]` when one is given. */
export function setRobotPose(world, p, rotationXyzw) {
  if (!world.robot) return;
  world.robot.position.set(p.x_m, p.z_m, -p.y_m);
  let q = rotationXyzw;
  if (!q) {
    const e = new THREE.Quaternion().setFromEuler(
      new THREE.Euler(p.roll_deg * DEG, p.pitch_deg * DEG, p.yaw_deg * DEG, 'ZYX'));
    q = [e.x, e.y, e.z, e.w];
  }
  world.robot.quaternion.set(q[0], q[2], -q[1], q[3]);
}

/** Swings each door `[entity, angle_deg]` to its angle (0 = closed). */
export function setDoorAngles(world, angles) {
  for (const [entity, deg] of angles) {
    const door = world.doors.get(entity);
    if (door) door.node.rotation.set(0, door.sign * deg * DEG, 0);
  }
}

/** The index of the last row of `rows` (sorted by `time_s`) at or before `t` (0 if none). */
function rowAt(rows, t) {
  let lo = 0, hi = rows.length - 1;
  if (hi < 0 || t <= rows[0].time_s) return 0;
  if (t >= rows[hi].time_s) return hi;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (rows[mid].time_s <= t) lo = mid; else hi = mid;
  }
  return lo;
}

/** The recorded pose at time `t`, interpolated between the trajectory's rows (position only). */
export function poseAt(track, t) {
  const i = rowAt(track, t);
  const a = track[i], b = track[Math.min(i + 1, track.length - 1)];
  if (t <= a.time_s || a === b) return a;
  const f = Math.min((t - a.time_s) / Math.max(b.time_s - a.time_s, 1e-9), 1);
  const mix = (k) => a[k] + (b[k] - a[k]) * f;
  return { time_s: t, x_m: mix('x_m'), y_m: mix('y_m'), z_m: mix('z_m'),
    roll_deg: a.roll_deg, pitch_deg: a.pitch_deg, yaw_deg: a.yaw_deg };
}

/** The recorded doors' angles at time `t` as `[entity, angle_deg]` pairs, interpolated; none
 * for a run folder without `doors.csv` (the doors then stay at their initial angle). */
export function doorAnglesAt(doors, t) {
  if (!doors || !doors.samples || doors.samples.length === 0) return [];
  const s = doors.samples;
  const i = rowAt(s, t);
  const a = s[i], b = s[Math.min(i + 1, s.length - 1)];
  const f = a === b ? 0 : Math.min(Math.max((t - a.time_s) / Math.max(b.time_s - a.time_s, 1e-9), 0), 1);
  return doors.doors.map((id, k) => [id, a.angles_deg[k] + (b.angles_deg[k] - a.angles_deg[k]) * f]);
}

const raycaster = new THREE.Raycaster();

/**
 * Puts the camera behind the robot (3 m back, 1.8 m up, looking ahead along `yaw`), pulled in
 * towards the robot when a wall (any solid mesh) is between: a ray from the robot's head
 * height to the wanted place, the camera stopping 0.25 m short of the first hit.
 */
export function placeFollowCamera(v, world, yaw) {
  const p = world.robot.position;
  const heading = new THREE.Vector3(Math.cos(yaw), 0, -Math.sin(yaw));
  const eye = p.clone().add(new THREE.Vector3(0, 1.0, 0));
  const wanted = p.clone().addScaledVector(heading, -3).add(new THREE.Vector3(0, 1.8, 0));
  const dir = wanted.clone().sub(eye);
  const dist = dir.length();
  dir.normalize();
  raycaster.set(eye, dir);
  raycaster.far = dist;
  const hit = raycaster.intersectObjects(world.solids, false).find((h) => visibleInScene(h.object));
  const d = hit ? Math.max(hit.distance - 0.25, 0.3) : dist;
  v.camera.position.copy(eye).addScaledVector(dir, d);
  v.camera.lookAt(p.clone().addScaledVector(heading, 1.5));
  return hit ? d : null;
}

/** The top-down camera over the robot (semsim +y up on the screen). */
export function placeTopCamera(v, world) {
  const p = world.robot.position;
  v.camera.up.set(0, 0, -1);
  v.camera.position.set(p.x, p.y + Math.max(world.size * 0.6, 8), p.z);
  v.camera.lookAt(p);
}

/** Whether a node and all its ancestors are visible. */
export function visibleInScene(o) {
  for (; o; o = o.parent) if (!o.visible) return false;
  return true;
}
