#!/usr/bin/env python3
"""The peer of driveid's bag reader in scripts/benchmark: what a user writes
in Python without ROS installed (Python's sqlite3 and struct): one joint's
header stamps, receive times, position, velocity and effort from a rosbag2
SQLite3 bag's sensor_msgs/msg/JointState topic, decoded from CDR.

usage: python_bag_read.py BAG.db3 TOPIC JOINT   (prints the message count)
"""
import sqlite3
import struct
import sys


def decode(data, joint):
    """(stamp ns, position, velocity, effort) of `joint`, or None."""
    at = 4

    def align(n):
        nonlocal at
        at += (-(at - 4)) % n

    def u32():
        nonlocal at
        align(4)
        v = struct.unpack_from("<I", data, at)[0]
        at += 4
        return v

    sec, nanosec = struct.unpack_from("<iI", data, 4)
    at = 12
    n = u32()  # frame_id
    at += n
    names = []
    for _ in range(u32()):
        n = u32()
        names.append(data[at:at + n - 1].decode())
        at += n
    arrays = []
    for _ in range(3):
        n = u32()
        if n:
            align(8)
        arrays.append(struct.unpack_from("<%dd" % n, data, at))
        at += 8 * n
    if joint not in names:
        return None
    k = names.index(joint)
    return sec * 1_000_000_000 + nanosec, arrays[0][k], arrays[1][k], arrays[2][k]


def main():
    bag, topic, joint = sys.argv[1:4]
    db = sqlite3.connect("file:%s?immutable=1" % bag, uri=True)
    (topic_id,) = db.execute("SELECT id FROM topics WHERE name = ?", (topic,)).fetchone()
    stamps, receives, position, velocity, effort = [], [], [], [], []
    for receive, data in db.execute("SELECT timestamp, data FROM messages WHERE topic_id = ? ORDER BY id", (topic_id,)):
        row = decode(data, joint)
        if row is None:
            continue
        stamps.append(row[0] / 1e9)
        receives.append(receive / 1e9)
        position.append(row[1])
        velocity.append(row[2])
        effort.append(row[3])
    print(len(stamps))


if __name__ == "__main__":
    main()
