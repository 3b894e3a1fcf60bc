"""Writes ROS 2 bags (MCAP, CDR messages) with mcap + mcap-ros2-support and dumps what
mcap-ros2-support decodes back.

    make_mcap.py OUT_DIR COMPRESSION      (COMPRESSION: zstd, lz4 or none)

OUT_DIR/bag_COMPRESSION.mcap holds, with deterministic pseudo-random values:
  /lidar/points  sensor_msgs/msg/PointCloud2, 3 messages:
    0  unorganised 1 x 200, FLOAT32 x y z at 0 4 8 and FLOAT32 intensity at 16, point_step 24,
       3 points NaN, frame base_link, stamp T0 + 0.1 s
    1  organised 8 x 16, FLOAT64 x y z at 0 8 16, UINT16 intensity at 24, point_step 32,
       row_step 16 * 32 + 8 (padded rows), 10 points NaN, frame base_link, stamp T0 + 0.15 s
    2  unorganised 1 x 50, FLOAT32 x y z, no intensity, frame odom, stamp T0 + 0.3 s
  /odom          nav_msgs/msg/Odometry, 5 messages at T0, T0 + 0.1 s ... T0 + 0.4 s, odom -> base_link
  /chatter       std_msgs/msg/String, 2 messages (not a cloud: ignored)
OUT_DIR/two_clouds.mcap holds two PointCloud2 topics, /front and /rear, one message each.
Beside each bag, NAME.json: per PointCloud2 message (log-time order) topic, log time, stamp,
frame id, height, width and the points decoded from `data` with numpy by the message's
fields (x y z, intensity where present; NaN as null); per Odometry message stamp, frames,
position and orientation (x y z w).
"""
import json
import sys
from pathlib import Path

import numpy as np
from mcap.writer import CompressionType
from mcap_ros2.reader import read_ros2_messages
from mcap_ros2.writer import Writer

T0 = 1_700_000_000 * 10**9

HEADER = """
================================================================================
MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id
================================================================================
MSG: builtin_interfaces/Time
int32 sec
uint32 nanosec
"""

POINTCLOUD2 = """std_msgs/Header header
uint32 height
uint32 width
PointField[] fields
bool is_bigendian
uint32 point_step
uint32 row_step
uint8[] data
bool is_dense""" + HEADER + """
================================================================================
MSG: sensor_msgs/PointField
string name
uint32 offset
uint8 datatype
uint32 count
"""

ODOMETRY = """std_msgs/Header header
string child_frame_id
geometry_msgs/PoseWithCovariance pose
geometry_msgs/TwistWithCovariance twist""" + HEADER + """
================================================================================
MSG: geometry_msgs/PoseWithCovariance
Pose pose
float64[36] covariance
================================================================================
MSG: geometry_msgs/Pose
Point position
Quaternion orientation
================================================================================
MSG: geometry_msgs/Point
float64 x
float64 y
float64 z
================================================================================
MSG: geometry_msgs/Quaternion
float64 x
float64 y
float64 z
float64 w
================================================================================
MSG: geometry_msgs/TwistWithCovariance
Twist twist
float64[36] covariance
================================================================================
MSG: geometry_msgs/Twist
Vector3 linear
Vector3 angular
================================================================================
MSG: geometry_msgs/Vector3
float64 x
float64 y
float64 z
"""

NUMPY_TYPES = {1: "i1", 2: "u1", 3: "i2", 4: "u2", 5: "i4", 6: "u4", 7: "f4", 8: "f8"}


def header(stamp_ns, frame_id):
    return {"stamp": {"sec": stamp_ns // 10**9, "nanosec": stamp_ns % 10**9}, "frame_id": frame_id}


def cloud_message(stamp_ns, frame_id, height, width, fields, point_step, row_step, values):
    """A PointCloud2 dict; `fields` is [(name, offset, datatype)], `values` {name: array}."""
    data = bytearray(row_step * height)
    for name, offset, datatype in fields:
        column = np.asarray(values[name]).astype("<" + NUMPY_TYPES[datatype]).reshape(height, width)
        size = column.dtype.itemsize
        for r in range(height):
            for c in range(width):
                start = r * row_step + c * point_step + offset
                data[start:start + size] = column[r, c].tobytes()
    return {
        "header": header(stamp_ns, frame_id),
        "height": height, "width": width,
        "fields": [{"name": n, "offset": o, "datatype": d, "count": 1} for n, o, d in fields],
        "is_bigendian": False, "point_step": point_step, "row_step": row_step,
        "data": bytes(data), "is_dense": False,
    }


def with_nans(rng, xyz, count):
    xyz = xyz.copy()
    xyz[rng.choice(len(xyz), size=count, replace=False)] = np.nan
    return xyz


def write_bag(path, compression):
    rng = np.random.default_rng(2)
    with open(path, "wb") as f:
        w = Writer(f, compression=compression)
        cloud_schema = w.register_msgdef("sensor_msgs/msg/PointCloud2", POINTCLOUD2)
        odom_schema = w.register_msgdef("nav_msgs/msg/Odometry", ODOMETRY)
        string_schema = w.register_msgdef("std_msgs/msg/String", "string data")
        for i in range(5):
            stamp = T0 + i * 100_000_000
            yaw = 0.1 * i
            w.write_message("/odom", odom_schema, {
                "header": header(stamp, "odom"), "child_frame_id": "base_link",
                "pose": {"pose": {"position": {"x": 1.0 * i, "y": 0.5 * i, "z": 0.0},
                                  "orientation": {"x": 0.0, "y": 0.0, "z": np.sin(yaw / 2),
                                                  "w": np.cos(yaw / 2)}},
                         "covariance": [0.0] * 36},
                "twist": {"twist": {"linear": {"x": 0.0, "y": 0.0, "z": 0.0},
                                    "angular": {"x": 0.0, "y": 0.0, "z": 0.0}},
                          "covariance": [0.0] * 36},
            }, log_time=stamp + 1000)
        xyz = with_nans(rng, rng.uniform(-10, 10, size=(200, 3)), 3)
        f4 = [("x", 0, 7), ("y", 4, 7), ("z", 8, 7)]
        m0 = cloud_message(T0 + 100_000_000, "base_link", 1, 200, f4 + [("intensity", 16, 7)], 24, 24 * 200,
                           {"x": xyz[:, 0], "y": xyz[:, 1], "z": xyz[:, 2],
                            "intensity": rng.uniform(0, 100, size=200)})
        xyz = with_nans(rng, rng.uniform(-30, 30, size=(128, 3)), 10)
        m1 = cloud_message(T0 + 150_000_000, "base_link", 8, 16,
                           [("x", 0, 8), ("y", 8, 8), ("z", 16, 8), ("intensity", 24, 4)], 32, 16 * 32 + 8,
                           {"x": xyz[:, 0], "y": xyz[:, 1], "z": xyz[:, 2],
                            "intensity": rng.integers(0, 65536, size=128)})
        xyz = rng.uniform(-5, 5, size=(50, 3))
        m2 = cloud_message(T0 + 300_000_000, "odom", 1, 50, f4, 12, 12 * 50,
                           {"x": xyz[:, 0], "y": xyz[:, 1], "z": xyz[:, 2]})
        for m in (m0, m1, m2):
            stamp = m["header"]["stamp"]["sec"] * 10**9 + m["header"]["stamp"]["nanosec"]
            w.write_message("/lidar/points", cloud_schema, m, log_time=stamp + 5000)
        for i in range(2):
            w.write_message("/chatter", string_schema, {"data": f"hello {i}"}, log_time=T0 + i)
        w.finish()


def write_two_clouds(path):
    rng = np.random.default_rng(3)
    with open(path, "wb") as f:
        w = Writer(f, compression=CompressionType.NONE)
        schema = w.register_msgdef("sensor_msgs/msg/PointCloud2", POINTCLOUD2)
        for k, topic in enumerate(["/front", "/rear"]):
            xyz = rng.uniform(-1, 1, size=(10, 3))
            m = cloud_message(T0 + k, topic.strip("/"), 1, 10, [("x", 0, 7), ("y", 4, 7), ("z", 8, 7)], 12, 120,
                              {"x": xyz[:, 0], "y": xyz[:, 1], "z": xyz[:, 2]})
            w.write_message(topic, schema, m, log_time=T0 + k)
        w.finish()


def as_list(values):
    return [None if not np.isfinite(v) else float(v) for v in np.asarray(values, dtype=np.float64)]


def decode_points(msg):
    """x y z (and intensity) of every point, decoded from `data` with numpy by the fields."""
    order = ">" if msg.is_bigendian else "<"
    data = bytes(msg.data)
    out = {}
    for field in msg.fields:
        if field.name not in ("x", "y", "z", "intensity"):
            continue
        dtype = np.dtype(order + NUMPY_TYPES[field.datatype])
        values = []
        for r in range(msg.height):
            for c in range(msg.width):
                start = r * msg.row_step + c * msg.point_step + field.offset
                values.append(np.frombuffer(data, dtype=dtype, count=1, offset=start)[0])
        out[field.name] = as_list(values)
    return out


def dump(path):
    clouds, odometry = [], []
    for m in read_ros2_messages(str(path)):
        msg = m.ros_msg
        schema = m.schema.name
        if schema == "sensor_msgs/msg/PointCloud2":
            stamp = msg.header.stamp.sec * 10**9 + msg.header.stamp.nanosec
            clouds.append({"topic": m.channel.topic, "log_time": m.log_time_ns, "stamp_ns": stamp,
                           "frame_id": msg.header.frame_id, "height": msg.height, "width": msg.width,
                           **decode_points(msg)})
        elif schema == "nav_msgs/msg/Odometry":
            p, q = msg.pose.pose.position, msg.pose.pose.orientation
            odometry.append({"stamp_ns": msg.header.stamp.sec * 10**9 + msg.header.stamp.nanosec,
                             "frame_id": msg.header.frame_id, "child_frame_id": msg.child_frame_id,
                             "position": [p.x, p.y, p.z], "orientation_xyzw": [q.x, q.y, q.z, q.w]})
    return {"clouds": clouds, "odometry": odometry}


def main():
    out = Path(sys.argv[1])
    compression = {"zstd": CompressionType.ZSTD, "lz4": CompressionType.LZ4,
                   "none": CompressionType.NONE}[sys.argv[2]]
    out.mkdir(parents=True, exist_ok=True)
    bag = out / f"bag_{sys.argv[2]}.mcap"
    write_bag(bag, compression)
    (out / (bag.name + ".json")).write_text(json.dumps(dump(bag)))
    two = out / "two_clouds.mcap"
    write_two_clouds(two)
    (out / (two.name + ".json")).write_text(json.dumps(dump(two)))


if __name__ == "__main__":
    main()
