#!/usr/bin/python3
"""Baseline for scripts/benchmark (not part of driveid): the plain SciPy fit
the issue compares against -- solve_ivp + least_squares of the reduced drive
train (docs/models.md#drive-train) with tanh-smoothed Coulomb friction, free d_g, Theta_motor,
tau_c, offset, starting 2-3x off. Usage: scipy_step_fit.py LOG.csv"""
import sys

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import least_squares

N_G, K_TL, K_TG = 80.0, 15000.0, 18375.0
K_EQ = K_TL * K_TG / (K_TL + K_TG)
SMOOTHING = 1e-3  # rad/s: width of the tanh


def load(path):
    rows = [line for line in open(path) if line.strip() and not line.startswith("#")]
    data = np.array([[float(x) for x in line.split(",")] for line in rows[1:]])
    return data[:, 0], data[:, 1], data[:, 2]


def simulate(params, t, u):
    d_g, theta_motor, tau_c, offset = params
    inertia, damping = N_G**2 * theta_motor, N_G**2 * d_g

    def rhs(time, x):
        k = max(0, np.searchsorted(t, time, side="right") - 1)  # zero-order hold
        force = N_G * u[k] - K_EQ * x[0] - damping * x[1] - tau_c * np.tanh(x[1] / SMOOTHING)
        return [x[1], force / inertia]

    solution = solve_ivp(rhs, (t[0], t[-1]), [0.0, 0.0], t_eval=t, rtol=1e-6, atol=1e-9)
    return K_EQ * solution.y[0] + offset


def main():
    t, u, y = load(sys.argv[1])
    start = [0.016 / 3, 2.5 * 0.413 / 6400, 10.0, 0.0]
    fit = least_squares(lambda p: simulate(p, t, u) - y, start, x_scale=np.abs(start) + [0, 0, 0, 1],
                        bounds=([0, 1e-9, 0, -np.inf], [np.inf] * 4))
    d_g, theta_motor, tau_c, offset = fit.x
    print(f"scipy: d_g {d_g:.6g} ({100 * (d_g / 0.016 - 1):+.1f} %), Theta_motor {theta_motor:.6g} "
          f"({100 * (theta_motor / (0.413 / 6400) - 1):+.1f} %), tau_c {tau_c:.6g} ({100 * (tau_c / 5 - 1):+.1f} %), "
          f"offset {offset:.4g}, evaluations {fit.nfev}")


if __name__ == "__main__":
    main()
