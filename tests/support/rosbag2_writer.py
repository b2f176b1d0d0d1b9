#!/usr/bin/env python3
"""An independent rosbag2 SQLite3 writer for the tests (Python's sqlite3 and
struct, from rosbag2's schema and the CDR rules; not driveid's reader).

Takes a CSV log (t, q, tau) and writes a bag whose /joint_states topic
carries sensor_msgs/msg/JointState messages: joint "axis" with the CSV's
position and effort (velocity empty), joint "wheel" beside it, header stamps
the CSV's t exactly, receive times 3 ms later with jitter; a few messages
recorded out of order; extra messages holding only "wheel" (to be left
out); a second topic /rosout of another type.

usage: rosbag2_writer.py LOG.csv OUT [--elastic] [--old-schema] [--folder] [--mcap zstd|lz4|none] [--ros1 bz2|lz4|none]
  --old-schema: the Foxy/Galactic tables (no type_description_hash, no
  message_definitions); --folder: OUT is a folder with metadata.yaml;
  --mcap: the same messages as an MCAP file (the published record layout),
  in chunks of 500 messages compressed with the zstd or lz4 command-line
  tools (Debian's zstd, lz4), or not compressed;
  --ros1: the same messages in a ROS 1 bag (format 2.0: records of
  "name=value" header fields and data; ROS serialisation; chunks of 500
  messages compressed with Python's bz2, the lz4 tool, or not), with a
  second JointState topic /gripper/joint_states;
  --elastic: LOG.csv is an elastic joint's (t, q_motor, q_link, tau): the
  joints "motor" (q_motor, effort tau) and "link" (q_link, effort 0).
  --arm: LOG.csv is a serial arm's (t, q_<joint>, tau_<joint> per joint, as
  tests/support/serial_arm_log_main.cc writes it): one message per row
  naming every joint, its position and effort (velocity empty).
"""
import csv
import os
import random
import sqlite3
import struct
import subprocess
import sys
import zlib
import bz2


class Cdr:
    def __init__(self):
        self.buf = bytearray(b"\x00\x01\x00\x00")  # CDR, little-endian

    def align(self, n):
        while (len(self.buf) - 4) % n:
            self.buf.append(0)

    def u32(self, v):
        self.align(4)
        self.buf += struct.pack("<I", v)

    def i32(self, v):
        self.align(4)
        self.buf += struct.pack("<i", v)

    def string(self, s):
        b = s.encode() + b"\x00"
        self.u32(len(b))
        self.buf += b

    def doubles(self, values):
        self.u32(len(values))
        if values:
            self.align(8)
            for v in values:
                self.buf += struct.pack("<d", v)


def joint_state(stamp_ns, names, position, velocity, effort):
    c = Cdr()
    c.i32(stamp_ns // 1_000_000_000)
    c.u32(stamp_ns % 1_000_000_000)
    c.string("base")
    c.u32(len(names))
    for n in names:
        c.string(n)
    c.doubles(position)
    c.doubles(velocity)
    c.doubles(effort)
    return bytes(c.buf)


def mcap_string(s):
    b = s.encode()
    return struct.pack("<I", len(b)) + b


def mcap_record(opcode, content):
    return bytes([opcode]) + struct.pack("<Q", len(content)) + content


def compress(kind, data):
    if kind == "none":
        return "", data
    tool = {"zstd": ["zstd", "-q", "-c"], "lz4": ["lz4", "-q", "-c"]}[kind]
    return kind, subprocess.run(tool, input=data, stdout=subprocess.PIPE, check=True).stdout


def write_mcap(out, messages, kind):
    """messages: (receive_ns, topic_id, data) in recording order."""
    f = bytearray(b"\x89MCAP0\r\n")
    f += mcap_record(0x01, mcap_string("ros2") + mcap_string("driveid test writer"))
    f += mcap_record(0x03, struct.pack("<H", 1) + mcap_string("sensor_msgs/msg/JointState") + mcap_string("ros2msg")
                     + mcap_string("# the message definition"))
    f += mcap_record(0x04, struct.pack("<HH", 2, 1) + mcap_string("/joint_states") + mcap_string("cdr")
                     + struct.pack("<I", 0))
    # The other topic's schema and channel inside the first chunk.
    inside = (mcap_record(0x03, struct.pack("<H", 2) + mcap_string("rcl_interfaces/msg/Log") + mcap_string("ros2msg")
                          + mcap_string(""))
              + mcap_record(0x04, struct.pack("<HH", 1, 2) + mcap_string("/rosout") + mcap_string("cdr")
                            + struct.pack("<I", 0)))
    for start in range(0, len(messages), 500):
        part = messages[start:start + 500]
        records = bytearray(inside if start == 0 else b"")
        for seq, (receive, topic, data) in enumerate(part):
            channel = 2 if topic == 2 else 1
            records += mcap_record(0x05, struct.pack("<HIQQ", channel, seq, receive, receive) + data)
        compression, packed = compress(kind, bytes(records))
        times = [m[0] for m in part]
        f += mcap_record(0x06, struct.pack("<QQQI", min(times), max(times), len(records), zlib.crc32(records))
                         + mcap_string(compression) + struct.pack("<Q", len(packed)) + packed)
    f += mcap_record(0x0F, struct.pack("<I", 0))
    f += mcap_record(0x02, struct.pack("<QQI", 0, 0, 0))
    f += b"\x89MCAP0\r\n"
    with open(out, "wb") as stream:
        stream.write(f)


def make_messages(rows, rng):
    messages = []
    for k, (t, q, tau) in enumerate(rows):
        stamp = round(t * 1e9)
        receive = stamp + 3_000_000 + rng.randrange(0, 500_000)
        data = joint_state(stamp, ["wheel", "axis"], [0.5 * q, q], [], [0.0, tau])
        messages.append((receive, 2, data))
        if k % 500 == 7:  # a message of the other joint only
            messages.append((receive + 1, 2, joint_state(stamp + 1, ["wheel"], [0.0], [0.0], [0.0])))
        if k % 700 == 3:
            messages.append((receive + 2, 1, b"\x00\x01\x00\x00not a joint state"))
    # A few swapped pairs: recorded out of order.
    for k in range(100, len(messages) - 1, 900):
        messages[k], messages[k + 1] = messages[k + 1], messages[k]
    return messages


def ros1_record(fields, data):
    header = b"".join(struct.pack("<I", len(k) + 1 + len(v)) + k + b"=" + v for k, v in fields)
    return struct.pack("<I", len(header)) + header + struct.pack("<I", len(data)) + data


def ros1_string(s):
    b = s.encode()
    return struct.pack("<I", len(b)) + b


def ros1_joint_state(seq, stamp_ns, names, position, velocity, effort):
    out = struct.pack("<III", seq, stamp_ns // 1_000_000_000, stamp_ns % 1_000_000_000) + ros1_string("base")
    out += struct.pack("<I", len(names)) + b"".join(ros1_string(n) for n in names)
    for values in (position, velocity, effort):
        out += struct.pack("<I", len(values)) + b"".join(struct.pack("<d", v) for v in values)
    return out


def cdr_to_ros1(seq, data):
    """Re-serialises one of make_messages' CDR JointStates for ROS 1."""
    at = 4
    def align(n):
        nonlocal at
        while (at - 4) % n:
            at += 1
    def u32():
        nonlocal at
        align(4)
        v = struct.unpack_from("<I", data, at)[0]
        at += 4
        return v
    def string():
        nonlocal at
        n = u32()
        v = data[at:at + n - 1].decode()
        at += n
        return v
    def doubles():
        nonlocal at
        n = u32()
        if n:
            align(8)
        v = list(struct.unpack_from("<%dd" % n, data, at))
        at += 8 * n
        return v
    sec = u32()
    nsec = u32()
    string()
    names = [string() for _ in range(u32())]
    return ros1_joint_state(seq, sec * 1_000_000_000 + nsec, names, doubles(), doubles(), doubles())


def write_ros1(out, messages, kind):
    connections = [(0, "/joint_states"), (1, "/gripper/joint_states")]
    def connection(conn, topic):
        info = b"".join(struct.pack("<I", len(k) + 1 + len(v)) + k + b"=" + v for k, v in [
            (b"topic", topic.encode()), (b"type", b"sensor_msgs/JointState"),
            (b"md5sum", b"3066dcd76a6cfaef579bd0f34173e9fd"), (b"message_definition", b"# JointState")])
        return ros1_record([(b"op", b"\x07"), (b"conn", struct.pack("<I", conn)), (b"topic", topic.encode())], info)
    f = bytearray(b"#ROSBAG V2.0\n")
    f += ros1_record([(b"op", b"\x03"), (b"index_pos", struct.pack("<Q", 0)), (b"conn_count", struct.pack("<I", 2)),
                      (b"chunk_count", struct.pack("<I", 0))], b" " * 4000)
    joint = [m for m in messages if m[1] == 2]
    for start in range(0, len(joint), 500):
        records = bytearray(b"".join(connection(c, t) for c, t in connections) if start == 0 else b"")
        for seq, (receive, _, data) in enumerate(joint[start:start + 500], start):
            time = struct.pack("<II", receive // 1_000_000_000, receive % 1_000_000_000)
            records += ros1_record([(b"op", b"\x02"), (b"conn", struct.pack("<I", 0)), (b"time", time)], cdr_to_ros1(seq, data))
            if seq % 250 == 0:  # the gripper's own topic
                gripper = ros1_joint_state(seq, receive, ["finger"], [0.01], [0.0], [0.5])
                records += ros1_record([(b"op", b"\x02"), (b"conn", struct.pack("<I", 1)), (b"time", time)], gripper)
        if kind == "bz2":
            packed = bz2.compress(bytes(records))
        elif kind == "lz4":
            packed = subprocess.run(["lz4", "-q", "-c"], input=bytes(records), stdout=subprocess.PIPE, check=True).stdout
        else:
            packed = bytes(records)
        f += ros1_record([(b"op", b"\x05"), (b"compression", kind.encode()), (b"size", struct.pack("<I", len(records)))],
                         packed)
    for c, t in connections:  # the index section repeats the connections
        f += connection(c, t)
    with open(out, "wb") as stream:
        stream.write(f)


def write_joint_states_db3(out, messages):
    """A db3 with one /joint_states topic: `messages` are (receive_ns, CDR data)."""
    if os.path.exists(out):
        os.remove(out)
    db = sqlite3.connect(out)
    db.execute("CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, "
               "serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL, type_description_hash TEXT NOT NULL)")
    db.execute("CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, timestamp INTEGER NOT NULL, "
               "data BLOB NOT NULL)")
    db.execute("INSERT INTO topics VALUES (1, '/joint_states', 'sensor_msgs/msg/JointState', 'cdr', '', '')")
    db.executemany("INSERT INTO messages (topic_id, timestamp, data) VALUES (1, ?, ?)", messages)
    db.commit()
    db.close()


def write_elastic(out, rows):
    """An elastic joint's log as a db3 of JointState messages (motor, link)."""
    write_joint_states_db3(out, [(round(t * 1e9) + 2_000_000,
                                  joint_state(round(t * 1e9), ["motor", "link"], [qm, ql], [], [tau, 0.0]))
                                 for t, qm, ql, tau in rows])


def write_arm(out, header, rows):
    """A serial arm's log as a db3 of JointState messages, every joint in each."""
    joints = [name[2:] for name in header[1::2]]
    write_joint_states_db3(out, [(round(r[0] * 1e9) + 2_000_000,
                                  joint_state(round(r[0] * 1e9), joints, list(r[1::2]), [], list(r[2::2])))
                                 for r in rows])


def main():
    source, out = sys.argv[1], sys.argv[2]
    old = "--old-schema" in sys.argv
    folder = "--folder" in sys.argv
    rng = random.Random(7)
    rows = []
    header = []
    with open(source) as f:
        for row in csv.reader(line for line in f if not line.startswith("#")):
            if row[0] == "t":
                header = row
                continue
            rows.append(tuple(float(x) for x in row))
    if "--arm" in sys.argv:
        write_arm(out, header, rows)
        return
    if "--elastic" in sys.argv:
        write_elastic(out, rows)
        return
    mcap = sys.argv[sys.argv.index("--mcap") + 1] if "--mcap" in sys.argv else None
    messages = make_messages(rows, rng)
    if mcap:
        write_mcap(out, messages, mcap)
        return
    if "--ros1" in sys.argv:
        write_ros1(out, messages, sys.argv[sys.argv.index("--ros1") + 1])
        return
    db_path = out
    if folder:
        os.makedirs(out, exist_ok=True)
        db_path = os.path.join(out, os.path.basename(out.rstrip("/")) + "_0.db3")
    if os.path.exists(db_path):
        os.remove(db_path)
    db = sqlite3.connect(db_path)
    hash_column = "" if old else ", type_description_hash TEXT NOT NULL"
    db.execute("CREATE TABLE schema(schema_version INTEGER PRIMARY KEY, ros_distro TEXT NOT NULL)")
    db.execute("INSERT INTO schema VALUES (?, ?)", (3 if old else 4, "foxy" if old else "jazzy"))
    db.execute("CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, "
               f"serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL{hash_column})")
    db.execute("CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, timestamp INTEGER NOT NULL, "
               "data BLOB NOT NULL)")
    if not old:
        db.execute("CREATE TABLE message_definitions(id INTEGER PRIMARY KEY, topic_type TEXT NOT NULL, "
                   "encoding TEXT NOT NULL, encoded_message_definition TEXT NOT NULL, type_description_hash TEXT NOT NULL)")
    extra = () if old else ("",)
    db.execute(f"INSERT INTO topics VALUES (1, '/rosout', 'rcl_interfaces/msg/Log', 'cdr', ''{', ?' if extra else ''})", extra)
    db.execute(f"INSERT INTO topics VALUES (2, '/joint_states', 'sensor_msgs/msg/JointState', 'cdr', ''{', ?' if extra else ''})",
               extra)
    db.executemany("INSERT INTO messages (topic_id, timestamp, data) VALUES (?, ?, ?)",
                   [(topic, receive, data) for receive, topic, data in messages])
    db.commit()
    db.close()
    if folder:
        with open(os.path.join(out, "metadata.yaml"), "w") as f:
            f.write("rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: sqlite3\n"
                    f"  relative_file_paths:\n    - {os.path.basename(db_path)}\n")


if __name__ == "__main__":
    main()
