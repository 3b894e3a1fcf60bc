// semsim's point-cloud layer (console page and run report): the registered cloud, downsampled
// by the server, as points coloured by class (the world's class colours; the PCD `class`
// field) or by height. The body is binary: n x (f32 x, y, z) little-endian in semsim's frame,
// then n class codes (u8); `meta` is /api/cloud.json: {info: {points, classes, z_min_m,
// z_max_m, ...}, class_codes: [[code, name], ...]}.
import * as THREE from 'three';

const UNKNOWN = new THREE.Color(0x9aa4ad);

/** Builds the layer (hidden until shown) and adds it to `scene`. */
export function createCloudLayer(scene, world, meta, buffer) {
  const n = meta.info.points;
  if (buffer.byteLength !== n * 13) throw new Error(`cloud body: ${buffer.byteLength} bytes for ${n} points`);
  const xyz = new DataView(buffer, 0, n * 12);
  const codes = new Uint8Array(buffer, n * 12, n);
  const positions = new Float32Array(n * 3);
  for (let i = 0; i < n; i++) {
    const x = xyz.getFloat32(i * 12, true), y = xyz.getFloat32(i * 12 + 4, true), z = xyz.getFloat32(i * 12 + 8, true);
    positions[i * 3] = x;
    positions[i * 3 + 1] = z;
    positions[i * 3 + 2] = -y;
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  const colours = new Float32Array(n * 3);
  geometry.setAttribute('color', new THREE.BufferAttribute(colours, 3));
  const material = new THREE.PointsMaterial({ size: 3, sizeAttenuation: false, vertexColors: true });
  const points = new THREE.Points(geometry, material);
  points.visible = false;
  scene.add(points);

  const names = new Map(meta.class_codes);
  const byClass = (i) => world.classColours.get(names.get(codes[i])) || UNKNOWN;
  const lo = meta.info.z_min_m, span = Math.max(meta.info.z_max_m - lo, 1e-6);
  const hue = new THREE.Color();
  const byHeight = (i) => hue.setHSL(0.7 * (1 - (positions[i * 3 + 1] - lo) / span), 0.85, 0.55);

  /** Colours every point: 'class' or 'height'. */
  function setMode(mode) {
    const pick = mode === 'height' || !meta.info.classes ? byHeight : byClass;
    for (let i = 0; i < n; i++) pick(i).toArray(colours, i * 3);
    geometry.attributes.color.needsUpdate = true;
  }
  setMode(meta.info.classes ? 'class' : 'height');
  return {
    points,
    setMode,
    setVisible: (on) => { points.visible = on; },
    count: n,
  };
}
