#!/usr/bin/env python3
"""Writes a large ROS 2 bag for scripts/benchmark (Python's sqlite3 and
struct, from rosbag2's schema, the CDR rules and the published MCAP record
layout; independent of driveid's readers).

A 6-joint arm's /joint_states (sensor_msgs/msg/JointState, CDR) at 500 Hz:
every joint's position, velocity and effort (sines), header stamps on the
2 ms grid, receive times 1 ms later; beside it a /camera/compressed topic
of 4 KiB blobs at 10 Hz (bytes the reader must pass over, as real bags
hold). Messages are written until the file reaches SIZE_MB megabytes.

usage: write_big_bag.py OUT SIZE_MB db3|mcap
  mcap: chunks of about 1 MB compressed with zstd level 1 (libzstd through
  ctypes), a DataEnd and a Footer without a summary.
"""
import ctypes
import math
import os
import sqlite3
import struct
import sys
import zlib

JOINTS = ["shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint", "wrist_2_joint", "wrist_3_joint"]
PERIOD_NS = 2_000_000
START_NS = 1_700_000_000 * 1_000_000_000


def template():
    """A JointState in CDR with the doubles' offsets: (bytes, stamp offset, [value offsets])."""
    buf = bytearray(b"\x00\x01\x00\x00")

    def align(n):
        while (len(buf) - 4) % n:
            buf.append(0)

    def u32(v):
        align(4)
        buf.extend(struct.pack("<I", v))

    def string(s):
        b = s.encode() + b"\x00"
        u32(len(b))
        buf.extend(b)

    align(4)
    stamp_at = len(buf)
    buf.extend(b"\x00" * 8)
    string("base_link")
    u32(len(JOINTS))
    for j in JOINTS:
        string(j)
    offsets = []
    for _ in range(3):
        u32(len(JOINTS))
        align(8)
        for _ in JOINTS:
            offsets.append(len(buf))
            buf.extend(b"\x00" * 8)
    return buf, stamp_at, offsets


def messages():
    """(receive ns, stamp ns, CDR bytes) for ever."""
    buf, stamp_at, offsets = template()
    k = 0
    while True:
        stamp = START_NS + k * PERIOD_NS
        struct.pack_into("<iI", buf, stamp_at, stamp // 1_000_000_000, stamp % 1_000_000_000)
        t = k * PERIOD_NS * 1e-9
        values = [math.sin(0.5 * t + j) for j in range(6)] + [0.5 * math.cos(0.5 * t + j) for j in range(6)] + \
                 [10.0 * math.sin(0.7 * t + j) for j in range(6)]
        for at, v in zip(offsets, values):
            struct.pack_into("<d", buf, at, v)
        yield stamp + 1_000_000, stamp, bytes(buf)
        k += 1


def camera(k):
    return bytes(((k * 7 + i) & 0xFF for i in range(4096)))


def write_db3(out, size):
    db = sqlite3.connect(out)
    db.execute("CREATE TABLE schema(schema_version INTEGER PRIMARY KEY, ros_distro TEXT NOT NULL)")
    db.execute("INSERT INTO schema VALUES (3, 'humble')")
    db.execute("CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, "
               "serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL)")
    db.execute("CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, timestamp INTEGER NOT NULL, "
               "data BLOB NOT NULL)")
    db.execute("CREATE INDEX timestamp_idx ON messages (timestamp ASC)")
    db.execute("INSERT INTO topics VALUES (1, '/joint_states', 'sensor_msgs/msg/JointState', 'cdr', '')")
    db.execute("INSERT INTO topics VALUES (2, '/camera/compressed', 'sensor_msgs/msg/CompressedImage', 'cdr', '')")
    written = 0
    batch = []
    for k, (receive, stamp, data) in enumerate(messages()):
        batch.append((1, receive, data))
        written += len(data) + 40
        if k % 50 == 0:
            batch.append((2, receive + 1, camera(k)))
            written += 4096 + 40
        if len(batch) >= 20000:
            db.executemany("INSERT INTO messages(topic_id, timestamp, data) VALUES (?, ?, ?)", batch)
            batch = []
            db.commit()
            if os.path.getsize(out) >= size:
                break
    db.executemany("INSERT INTO messages(topic_id, timestamp, data) VALUES (?, ?, ?)", batch)
    db.commit()
    db.close()


def mcap_string(s):
    b = s.encode()
    return struct.pack("<I", len(b)) + b


def record(opcode, content):
    return struct.pack("<BQ", opcode, len(content)) + content


def write_mcap(out, size):
    zstd = ctypes.CDLL("libzstd.so.1")
    zstd.ZSTD_compressBound.restype = ctypes.c_size_t
    zstd.ZSTD_compressBound.argtypes = [ctypes.c_size_t]
    zstd.ZSTD_compress.restype = ctypes.c_size_t
    zstd.ZSTD_compress.argtypes = [ctypes.c_void_p, ctypes.c_size_t, ctypes.c_char_p, ctypes.c_size_t, ctypes.c_int]
    with open(out, "wb") as f:
        f.write(b"\x89MCAP0\r\n")
        f.write(record(0x01, mcap_string("ros2") + mcap_string("write_big_bag.py")))
        f.write(record(0x03, struct.pack("<H", 1) + mcap_string("sensor_msgs/msg/JointState") + mcap_string("ros2msg") +
                       struct.pack("<I", 0)))
        f.write(record(0x03, struct.pack("<H", 2) + mcap_string("sensor_msgs/msg/CompressedImage") +
                       mcap_string("ros2msg") + struct.pack("<I", 0)))
        for channel, schema, topic in ((1, 1, "/joint_states"), (2, 2, "/camera/compressed")):
            f.write(record(0x04, struct.pack("<HH", channel, schema) + mcap_string(topic) + mcap_string("cdr") +
                           struct.pack("<I", 0)))
        chunk = bytearray()
        first = last = 0

        def flush():
            bound = zstd.ZSTD_compressBound(len(chunk))
            dst = ctypes.create_string_buffer(bound)
            n = zstd.ZSTD_compress(dst, bound, bytes(chunk), len(chunk), 1)
            packed = dst.raw[:n]
            f.write(record(0x06, struct.pack("<QQQI", first, last, len(chunk), zlib.crc32(chunk)) + mcap_string("zstd") +
                           struct.pack("<Q", len(packed)) + packed))
            chunk.clear()

        for k, (receive, stamp, data) in enumerate(messages()):
            if not chunk:
                first = receive
            last = receive
            chunk += record(0x05, struct.pack("<HIQQ", 1, k, receive, receive) + data)
            if k % 50 == 0:
                chunk += record(0x05, struct.pack("<HIQQ", 2, k, receive + 1, receive + 1) + camera(k))
            if len(chunk) >= 1 << 20:
                flush()
                if f.tell() >= size:
                    break
        if chunk:
            flush()
        f.write(record(0x0F, struct.pack("<I", 0)))
        f.write(record(0x02, struct.pack("<QQI", 0, 0, 0)))
        f.write(b"\x89MCAP0\r\n")


def main():
    out, size, kind = sys.argv[1], int(float(sys.argv[2]) * 1e6), sys.argv[3]
    if os.path.exists(out):
        os.remove(out)
    {"db3": write_db3, "mcap": write_mcap}[kind](out, size)


if __name__ == "__main__":
    main()
