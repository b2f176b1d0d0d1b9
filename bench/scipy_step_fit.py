#!/usr/bin/python3
"""Peer for scripts/benchmark (not part of driveid): the plain SciPy fit the
benchmark compares against -- solve_ivp + least_squares of the drive train
(docs/models.md#drive-train) with tanh-smoothed Coulomb friction, free d_g,
Theta_motor, tau_c, offset, starting 2-3x off (as data/paper000_start.yaml).
Usage: scipy_step_fit.py LOG.csv [reduced|full]"""
import sys

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import least_squares

N_G, K_TL, K_TG, THETA_G = 80.0, 15000.0, 18375.0, 6.71875e-06
K_EQ = K_TL * K_TG / (K_TL + K_TG)
SMOOTHING = 1e-3  # rad/s: width of the tanh


def load(path):
    rows = [line for line in open(path) if line.strip() and not line.startswith("#")]
    data = np.array([[float(x) for x in line.split(",")] for line in rows[1:]])
    return data[:, 0], data[:, 1], data[:, 2]


def simulate(params, t, u, full):
    d_g, theta_motor, tau_c, offset = params
    inertia, damping = N_G**2 * theta_motor, N_G**2 * d_g

    def held(time):  # zero-order hold of the logged torque
        return u[max(0, np.searchsorted(t, time, side="right") - 1)]

    def reduced_rhs(time, x):
        force = N_G * held(time) - K_EQ * x[0] - damping * x[1] - tau_c * np.tanh(x[1] / SMOOTHING)
        return [x[1], force / inertia]

    def full_rhs(time, x):  # x = phi, phi', Delta, Delta' (eqs. 13-14)
        force = N_G * held(time) - K_TG * (x[0] - x[2]) - damping * x[1] - tau_c * np.tanh(x[1] / SMOOTHING)
        link = (K_TG * x[0] - (K_TL + K_TG) * x[2]) / (N_G**2 * THETA_G)
        return [x[1], force / inertia, x[3], link]

    if full:
        solution = solve_ivp(full_rhs, (t[0], t[-1]), [0.0] * 4, t_eval=t, rtol=1e-6, atol=1e-9)
        return K_TL * solution.y[2] + offset
    solution = solve_ivp(reduced_rhs, (t[0], t[-1]), [0.0, 0.0], t_eval=t, rtol=1e-6, atol=1e-9)
    return K_EQ * solution.y[0] + offset


def main():
    t, u, y = load(sys.argv[1])
    full = len(sys.argv) > 2 and sys.argv[2] == "full"
    start = [0.005, 1.6e-4, 12.0, 0.0]
    fit = least_squares(lambda p: simulate(p, t, u, full) - y, start, x_scale=np.abs(start) + [0, 0, 0, 1],
                        bounds=([0, 1e-9, 0, -np.inf], [np.inf] * 4))
    d_g, theta_motor, tau_c, offset = fit.x
    print(f"d_g {d_g:.6g} ({100 * (d_g / 0.016 - 1):+.1f} %), Theta_motor {theta_motor:.6g} "
          f"({100 * (theta_motor / (0.413 / 6400) - 1):+.1f} %), tau_c {tau_c:.6g} ({100 * (tau_c / 5 - 1):+.1f} %), "
          f"offset {offset:.4g}, evaluations {fit.nfev}")
    print(f"estimates: d_g={d_g:.8g} Theta_motor={theta_motor:.8g} tau_c={tau_c:.8g} offset={offset:.8g} "
          f"nfev={fit.nfev}")


if __name__ == "__main__":
    main()
