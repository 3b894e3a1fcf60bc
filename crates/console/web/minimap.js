// semsim's minimap (console page and run report): a top-down 2D overview of the world's
// footprint in a corner of the view, semsim +x right and +y up, with the robot's position and
// heading. The static layer (floor, walls, doors, stairs, furniture: every mesh's triangles
// projected onto the ground, in its class colour) is drawn once; the robot every frame.
import * as THREE from 'three';

const DRAWN = ['floor', 'ramp', 'stairs', 'furniture', 'column', 'obstacle', 'wall', 'wall_above_door', 'door'];
const SIZE_PX = 200;
const MARGIN_PX = 8;

/** Adds the minimap canvas to `container` (which must be positioned) for `world`. */
export function createMinimap(container, world) {
  const canvas = document.createElement('canvas');
  canvas.id = 'minimap';
  canvas.width = SIZE_PX;
  canvas.height = SIZE_PX;
  container.appendChild(canvas);
  const ctx = canvas.getContext('2d');

  // The scene's x and z (= -semsim y) footprint, square, with a margin.
  const b = world.box;
  const span = Math.max(b.max.x - b.min.x, b.max.z - b.min.z, 1);
  const scale = (SIZE_PX - 2 * MARGIN_PX) / span;
  const cx = (b.min.x + b.max.x) / 2, cz = (b.min.z + b.max.z) / 2;
  const px = (x) => SIZE_PX / 2 + (x - cx) * scale;
  const pz = (z) => SIZE_PX / 2 + (z - cz) * scale; // scene +z (semsim -y) is down on the map

  const background = document.createElement('canvas');
  background.width = SIZE_PX;
  background.height = SIZE_PX;
  const bg = background.getContext('2d');
  bg.fillStyle = 'rgba(20, 24, 30, 0.85)';
  bg.fillRect(0, 0, SIZE_PX, SIZE_PX);
  const v = new THREE.Vector3();
  for (const cls of DRAWN) {
    const colour = world.classColours.get(cls) || new THREE.Color(0x888888);
    bg.fillStyle = `#${colour.getHexString()}`;
    for (const node of world.byClass.get(cls) || []) {
      node.updateWorldMatrix(true, true);
      node.traverse((o) => {
        if (!o.isMesh || !o.geometry.attributes.position) return;
        const pos = o.geometry.attributes.position, index = o.geometry.index;
        const count = index ? index.count : pos.count;
        // One fill per triangle: a box's top and bottom faces project onto each other with
        // opposite windings, which one path would cancel out.
        for (let i = 0; i + 2 < count; i += 3) {
          bg.beginPath();
          for (let k = 0; k < 3; k++) {
            v.fromBufferAttribute(pos, index ? index.getX(i + k) : i + k).applyMatrix4(o.matrixWorld);
            if (k === 0) bg.moveTo(px(v.x), pz(v.z)); else bg.lineTo(px(v.x), pz(v.z));
          }
          bg.closePath();
          bg.fill();
        }
      });
    }
  }

  /** Redraws the map with the robot at its node's place, heading `yaw` (radians, semsim). */
  function draw(yaw) {
    ctx.clearRect(0, 0, SIZE_PX, SIZE_PX);
    ctx.drawImage(background, 0, 0);
    if (!world.robot) return;
    const p = world.robot.position;
    const x = px(p.x), y = pz(p.z);
    ctx.save();
    ctx.translate(x, y);
    ctx.rotate(-yaw);
    ctx.fillStyle = '#00e676';
    ctx.strokeStyle = '#0b0d10';
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    ctx.moveTo(9, 0);
    ctx.lineTo(-6, 6);
    ctx.lineTo(-3, 0);
    ctx.lineTo(-6, -6);
    ctx.closePath();
    ctx.fill();
    ctx.stroke();
    ctx.restore();
    canvas.dataset.robotPx = `${x.toFixed(1)},${y.toFixed(1)}`;
  }
  draw(0);
  return { canvas, draw };
}
