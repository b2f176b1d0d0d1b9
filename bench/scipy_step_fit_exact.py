#!/usr/bin/python3
"""Third peer for scripts/benchmark (not part of driveid), for the full model
where SciPy's integrators with events do not reach the optimum (docs/
performance.md): the drive train is linear within a friction mode, so a
SciPy user who knows the problem solves each held sample exactly with
scipy.linalg.expm and finds stick, break-away and reversal with brentq on
that exact solution:
  - per mode m the augmented matrix [[A_m, c_m, b]; 0] of x' = A_m x + c_m + b u
    (u the held motor torque), its exponential over a sample and half a
    sample computed once per parameter point;
  - a sample whose end or midpoint leaves the mode (the sliding motor's rate
    reaching 0, the stuck motor's net torque beyond tau_c) is split at the
    event, found by brentq on the exact solution;
  - least_squares with bounds, trust-region reflective, x_scale='jac',
    2-point Jacobian (as bench/scipy_step_fit_lsoda.py).
Model: docs/models.md#drive-train (reduced eq. 16, or full eqs. 13-15),
written from the equations; free d_g, Theta_motor, tau_c, offset, start as
data/paper000_start.yaml. Prints one line of estimates for the benchmark.
Usage: scipy_step_fit_exact.py LOG.csv [reduced|full]"""
import sys

import numpy as np
from scipy.linalg import expm
from scipy.optimize import brentq

from peer_common import GEAR, INERTIA_GEAR, STIFF_GEAR, STIFF_LINK, fit_and_print, read_log

MAX_SWITCHES_PER_SAMPLE = 4


class ExactDriveTrain:
    """States phi, omega (motor angle and rate at the gear output) and, full
    model, Delta and its rate. Sliding (m = +-1): n^2 Theta_m omega' =
    n u - k (phi - Delta) - n^2 d_g omega - tau_c m; stuck (m = 0): phi,
    omega held while |n u - k (phi - Delta)| <= tau_c."""

    def __init__(self, time, torque, full):
        self.time, self.torque, self.full = time, torque, full
        self.size = 4 if full else 2
        self.step = float(np.median(np.diff(time)))
        self.uniform = bool(np.allclose(np.diff(time), self.step, rtol=1e-9, atol=0.0))

    def fields(self, theta):
        damping_g, inertia_m, coulomb, _ = theta
        mass, viscous = GEAR * GEAR * inertia_m, GEAR * GEAR * damping_g
        spring = STIFF_GEAR if self.full else STIFF_LINK * STIFF_GEAR / (STIFF_LINK + STIFF_GEAR)
        n = self.size
        matrices = {}
        for mode in (-1, 0, 1):
            m = np.zeros((n + 2, n + 2))  # columns: states, 1, u
            if mode != 0:
                m[0, 1] = 1.0
                m[1, 0] = -spring / mass
                m[1, 1] = -viscous / mass
                m[1, n] = -coulomb * mode / mass
                m[1, n + 1] = GEAR / mass
                if self.full:
                    m[1, 2] = spring / mass
            if self.full:
                gear_mass = GEAR * GEAR * INERTIA_GEAR
                m[2, 3] = 1.0
                m[3, 0] = STIFF_GEAR / gear_mass
                m[3, 2] = -(STIFF_LINK + STIFF_GEAR) / gear_mass
            matrices[mode] = m
        return matrices, spring, coulomb

    def link_torque(self, theta):
        matrices, spring, coulomb = self.fields(theta)
        n, offset = self.size, theta[3]
        whole = {mode: expm(m * self.step)[:n] for mode, m in matrices.items()}
        half = {mode: expm(m * 0.5 * self.step)[:n] for mode, m in matrices.items()}

        def net(x, u):  # torque the friction must hold
            return GEAR * u - spring * (x[0] - (x[2] if self.full else 0.0))

        def decide(x, u):
            force = net(x, u)
            return 0 if abs(force) <= coulomb else int(np.sign(force))

        def margin(x, u, mode):
            return mode * x[1] if mode != 0 else coulomb - abs(net(x, u))

        def clear(value, mode):  # a stuck drive holds at |net| = tau_c
            return value >= 0.0 if mode == 0 else value > 0.0

        output = np.empty(len(self.time))
        x = np.zeros(n)
        mode = decide(x, self.torque[0])
        output[0] = (STIFF_LINK * x[2] if self.full else spring * x[0]) + offset
        switches, budget = 0, 2000 + MAX_SWITCHES_PER_SAMPLE * len(self.time)
        for k in range(len(self.time) - 1):
            u = self.torque[k]
            if x[1] == 0.0:
                mode = decide(x, u)
            length = self.time[k + 1] - self.time[k]
            left = length
            while left > 0.0:
                z = np.concatenate((x, [1.0, u]))
                if left == length and self.uniform:
                    end, middle = whole[mode] @ z, half[mode] @ z
                else:
                    end, middle = expm(matrices[mode] * left)[:n] @ z, expm(matrices[mode] * 0.5 * left)[:n] @ z
                end_clear = clear(margin(end, u, mode), mode)
                if end_clear and clear(margin(middle, u, mode), mode):
                    x = end
                    break
                upper = 0.5 * left if end_clear else left
                field = matrices[mode]

                def event(tau, z=z, field=field, mode=mode):
                    if tau <= 0.0:
                        return 1.0  # the mode holds at the interval's start
                    value = margin(expm(field * tau)[:n] @ z, u, mode)
                    return max(value, 1e-300) if clear(value, mode) else min(value, -1e-300)

                hit = brentq(event, 0.0, upper, xtol=1e-15, rtol=1e-13)
                nudge = 1e-15  # the first time at or past the event
                while event(hit) > 0.0 and hit < upper:
                    hit = min(upper, hit + nudge)
                    nudge *= 2.0
                x = expm(field * hit)[:n] @ z
                if mode != 0:
                    x[1] = 0.0
                    mode = decide(x, u)
                else:
                    mode = int(np.sign(net(x, u)))
                switches += 1
                if switches > budget:
                    return np.full(len(self.time), 1e6)  # chattering at this trial point
                left -= hit
                if hit <= 0.0:
                    left = np.nextafter(left, 0.0)
            output[k + 1] = (STIFF_LINK * x[2] if self.full else spring * x[0]) + offset
        return output


def main():
    time, torque, measured = read_log(sys.argv[1])
    model = ExactDriveTrain(time, torque, len(sys.argv) > 2 and sys.argv[2] == "full")
    fit_and_print(model.link_torque, measured)


if __name__ == "__main__":
    main()
