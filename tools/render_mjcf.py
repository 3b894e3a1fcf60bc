"""Renders an MJCF file (as `semsim export --format mjcf` writes it) with MuJoCo's own renderer,
offscreen (MUJOCO_GL=osmesa, Debian's libosmesa6), to a PNG: the picture of an exported world in
the README.

usage: MUJOCO_GL=osmesa target/oracles/venv/bin/python tools/render_mjcf.py WORLD.xml OUT.png
       [--seconds S] [--width W] [--height H]
"""
import argparse
import struct
import zlib

import mujoco
import numpy as np


def write_png(path, rgb):
    """A minimal PNG writer (8-bit RGB), so no imaging package is needed."""
    h, w, _ = rgb.shape
    raw = b"".join(b"\x00" + rgb[y].tobytes() for y in range(h))

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("world")
    ap.add_argument("out")
    ap.add_argument("--seconds", type=float, default=0.5)
    ap.add_argument("--width", type=int, default=960)
    ap.add_argument("--height", type=int, default=540)
    a = ap.parse_args()
    model = mujoco.MjModel.from_xml_path(a.world)
    model.vis.global_.offwidth = max(model.vis.global_.offwidth, a.width)
    model.vis.global_.offheight = max(model.vis.global_.offheight, a.height)
    data = mujoco.MjData(model)
    while data.time < a.seconds:
        mujoco.mj_step(model, data)
    # Ceilings hidden (made transparent), so the picture looks into the rooms.
    for g in range(model.ngeom):
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, g) or ""
        if name.startswith("ceiling"):
            model.geom_rgba[g, 3] = 0.0
    # A free camera looking down at the whole world from one corner.
    camera = mujoco.MjvCamera()
    mujoco.mjv_defaultFreeCamera(model, camera)
    camera.elevation = -50.0
    camera.azimuth = 235.0
    camera.distance *= 0.55
    # With a robot: a closer view from behind it, looking down the way it faces.
    chassis = [b for b in range(model.nbody)
               if (mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, b) or "").endswith("_chassis")]
    if chassis:
        camera.lookat[:] = data.xpos[chassis[0]] + np.array([3.0, 0.0, 0.0])
        camera.distance = 9.0
        camera.azimuth = 25.0
        camera.elevation = -42.0
    model.vis.headlight.ambient[:] = [0.45, 0.45, 0.45]
    model.vis.headlight.diffuse[:] = [0.6, 0.6, 0.6]
    option = mujoco.MjvOption()
    renderer = mujoco.Renderer(model, a.height, a.width)
    renderer.update_scene(data, camera=camera, scene_option=option)
    image = renderer.render()
    renderer.close()
    write_png(a.out, np.ascontiguousarray(image))
    print(f"{a.out}: {a.width}x{a.height}, mean {image.mean():.1f}")


if __name__ == "__main__":
    main()
