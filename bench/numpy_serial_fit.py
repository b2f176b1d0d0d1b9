#!/usr/bin/python3
"""Peer for scripts/benchmark (not part of driveid): a serial arm's
identification the way a NumPy/SciPy pipeline does it (FIGAROH-like, written
here from the textbook method): the URDF read with xml.etree (revolute and
prismatic joints in a chain or tree, no fixed-joint merging), positions
smoothed and differentiated by Savitzky-Golay (scipy.signal, cubic, the
window driveid uses, on the median sample time), the inertial-parameter
regressor by recursive Newton-Euler vectorised over all samples (10
parameters per body, then armature, viscous, Coulomb and offset per joint),
base parameters by QR with column pivoting on random motions, and two
weighted least-squares solves (per-joint noise) with the covariance.
Prints the number of base parameters, samples and the seconds taken.
Usage: numpy_serial_fit.py ARM.urdf LOG.csv [half_window_s]"""
import sys
import time
import xml.etree.ElementTree as ET

import numpy as np
from scipy.linalg import qr
from scipy.signal import savgol_filter


def rpy_matrix(r, p, y):
    cr, sr, cp, sp, cy, sy = np.cos(r), np.sin(r), np.cos(p), np.sin(p), np.cos(y), np.sin(y)
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def floats(text, default):
    return np.array([float(v) for v in text.split()]) if text else np.array(default, dtype=float)


def read_urdf(path):
    root = ET.parse(path).getroot()
    joints = []
    for j in root.findall("joint"):
        kind = j.get("type")
        if kind not in ("revolute", "continuous", "prismatic"):
            raise SystemExit(f"peer: joint {j.get('name')} is {kind}: only revolute and prismatic here")
        origin = j.find("origin")
        xyz = floats(origin.get("xyz") if origin is not None else None, [0, 0, 0])
        rpy = floats(origin.get("rpy") if origin is not None else None, [0, 0, 0])
        axis = floats(j.find("axis").get("xyz") if j.find("axis") is not None else None, [1, 0, 0])
        joints.append(dict(name=j.get("name"), parent=j.find("parent").get("link"), child=j.find("child").get("link"),
                           rotation=rpy_matrix(*rpy), translation=xyz, axis=axis / np.linalg.norm(axis),
                           prismatic=kind == "prismatic"))
    # Preorder from the root: a joint after the one that moves its parent link.
    by_child = {j["child"]: i for i, j in enumerate(joints)}
    order, placed = [], set()
    while len(order) < len(joints):
        for i, j in enumerate(joints):
            parent = by_child.get(j["parent"])
            if i not in placed and (parent is None or parent in placed):
                order.append(i)
                placed.add(i)
    joints = [joints[i] for i in order]
    index = {j["child"]: k for k, j in enumerate(joints)}
    for j in joints:
        j["parent_index"] = index.get(j["parent"], -1)
    return joints


def skew(v):  # N x 3 -> N x 3 x 3
    z = np.zeros(v.shape[0])
    return np.stack([np.stack([z, -v[:, 2], v[:, 1]], -1), np.stack([v[:, 2], z, -v[:, 0]], -1),
                     np.stack([-v[:, 1], v[:, 0], z], -1)], 1)


def lift(v):  # I w = lift(w) [Ixx Ixy Ixz Iyy Iyz Izz]
    z = np.zeros(v.shape[0])
    x, y, w = v[:, 0], v[:, 1], v[:, 2]
    return np.stack([np.stack([x, y, w, z, z, z], -1), np.stack([z, x, z, y, w, z], -1),
                     np.stack([z, z, x, z, y, w], -1)], 1)


def axis_rotation(axis, angle):  # N rotations about a unit axis
    k = skew(np.tile(axis, (angle.size, 1)))
    s, c = np.sin(angle)[:, None, None], np.cos(angle)[:, None, None]
    return np.eye(3) + s * k + (1 - c) * k @ k


def regressor(joints, q, qd, qdd, gravity=np.array([0, 0, -9.81])):
    """Rows per joint: returns Y with shape (N, n, 14 n)."""
    n, count = len(joints), q.shape[0]
    rot, trans, w, dw, a = [], [], [], [], []
    for i, j in enumerate(joints):
        s = j["axis"]
        if j["prismatic"]:
            r = np.tile(j["rotation"], (count, 1, 1))
            t = j["translation"] + (j["rotation"] @ s)[None, :] * q[:, i:i + 1]
        else:
            r = j["rotation"] @ axis_rotation(s, q[:, i])
            t = np.tile(j["translation"], (count, 1))
        p = j["parent_index"]
        wp = w[p] if p >= 0 else np.zeros((count, 3))
        dwp = dw[p] if p >= 0 else np.zeros((count, 3))
        ap = a[p] if p >= 0 else np.tile(-gravity, (count, 1))
        rt = np.transpose(r, (0, 2, 1))
        wi = np.einsum("nij,nj->ni", rt, wp)
        dwi = np.einsum("nij,nj->ni", rt, dwp)
        ai = np.einsum("nij,nj->ni", rt, ap + np.cross(dwp, t) + np.cross(wp, np.cross(wp, t)))
        if j["prismatic"]:
            ai = ai + 2 * np.cross(wi, s[None, :] * qd[:, i:i + 1]) + s[None, :] * qdd[:, i:i + 1]
        else:
            dwi = dwi + s[None, :] * qdd[:, i:i + 1] + np.cross(wi, s[None, :] * qd[:, i:i + 1])
            wi = wi + s[None, :] * qd[:, i:i + 1]
        rot.append(r)
        trans.append(t)
        w.append(wi)
        dw.append(dwi)
        a.append(ai)
    y = np.zeros((count, n, 14 * n))
    for i in range(n):
        bf = np.zeros((count, 3, 10))
        bn = np.zeros((count, 3, 10))
        bf[:, :, 0] = a[i]
        sw = skew(w[i])
        bf[:, :, 1:4] = skew(dw[i]) + sw @ sw
        bn[:, :, 1:4] = -skew(a[i])
        bn[:, :, 4:10] = lift(dw[i]) + sw @ lift(w[i])
        k = i
        while True:
            j = joints[k]
            y[:, k, 14 * i:14 * i + 10] = np.einsum("j,njc->nc", j["axis"], bf if j["prismatic"] else bn)
            if j["parent_index"] < 0:
                break
            moved = rot[k] @ bf
            bn = rot[k] @ bn + skew(trans[k]) @ moved
            bf = moved
            k = j["parent_index"]
        y[:, i, 14 * i + 10] = qdd[:, i]
        y[:, i, 14 * i + 11] = qd[:, i]
        y[:, i, 14 * i + 12] = np.sign(qd[:, i])
        y[:, i, 14 * i + 13] = 1.0
    return y


def main():
    urdf, log = sys.argv[1], sys.argv[2]
    half_window = float(sys.argv[3]) if len(sys.argv) > 3 else 0.05
    started = time.perf_counter()
    joints = read_urdf(urdf)
    n = len(joints)
    lines = [line for line in open(log) if line.strip() and not line.startswith("#")]
    header = lines[0].strip().split(",")
    data = np.loadtxt(lines[1:], delimiter=",", ndmin=2)
    column = {name: data[:, k] for k, name in enumerate(header)}
    t = column["t"]
    dt = np.median(np.diff(t))
    window = 2 * int(round(half_window / dt)) + 1
    q = np.stack([savgol_filter(column["q_" + j["name"]], window, 3) for j in joints], 1)
    qd = np.stack([savgol_filter(column["q_" + j["name"]], window, 3, deriv=1, delta=dt) for j in joints], 1)
    qdd = np.stack([savgol_filter(column["q_" + j["name"]], window, 3, deriv=2, delta=dt) for j in joints], 1)
    tau = np.stack([column["tau_" + j["name"]] for j in joints], 1)
    keep = slice(window // 2, -(window // 2))
    q, qd, qdd, tau = q[keep], qd[keep], qdd[keep], tau[keep]
    # Base parameters: QR with column pivoting on random motions.
    rng = np.random.default_rng(20260528)
    samples = 8 * 14 * n // n + 8
    w = regressor(joints, rng.uniform(-np.pi, np.pi, (samples, n)), rng.normal(size=(samples, n)),
                  rng.normal(size=(samples, n))).reshape(samples * n, 14 * n)
    _, r, pivots = qr(w, mode="economic", pivoting=True)
    rank = int(np.sum(np.abs(np.diag(r)) > 1e-8 * abs(r[0, 0])))
    base = np.sort(pivots[:rank])
    # Two weighted solves (per-joint noise), the covariance.
    yb = regressor(joints, q, qd, qdd)[:, :, base]
    sigma = np.ones(n)
    for _ in range(2):
        rows = (yb / sigma[None, :, None]).reshape(-1, rank)
        rhs = (tau / sigma[None, :]).reshape(-1)
        beta, *_ = np.linalg.lstsq(rows, rhs, rcond=None)
        residual = tau - np.einsum("nkc,c->nk", yb, beta)
        sigma = np.sqrt(np.mean(residual ** 2, axis=0))
    covariance = np.linalg.inv(rows.T @ rows) * np.mean((rhs - rows @ beta) ** 2)
    elapsed = time.perf_counter() - started
    print(f"base {rank} samples {q.shape[0]} std_min {np.sqrt(np.diag(covariance)).min():.3g} seconds {elapsed:.3f}")


if __name__ == "__main__":
    main()
