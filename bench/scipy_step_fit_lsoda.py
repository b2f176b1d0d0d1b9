#!/usr/bin/python3
"""Second peer for scripts/benchmark (not part of driveid), written apart
from scipy_step_fit.py with the choices a SciPy user who knows the library

from peer_common import GEAR, INERTIA_GEAR, STIFF_GEAR, STIFF_LINK, fit_and_print, read_log
makes for this problem (issue 22 item 4):
  - LSODA (switches to BDF when the elastic mode makes the problem stiff),
    max_step one sample so that the zero-order-held torque is never stepped
    over, tight tolerances;
  - least_squares with bounds, the trust-region reflective method and
    x_scale='jac' (scaled by the Jacobian's columns), 2-point Jacobian.
Model: docs/models.md#drive-train (reduced eq. 16, or full eqs. 13-14), Coulomb
friction that sticks (events at stick and slip, not a smoothed sign), the
strain gauge's constant offset. Free d_g, Theta_motor, tau_c, offset, start as
data/paper000_start.yaml. Prints one line of estimates for the benchmark.
Usage: scipy_step_fit_lsoda.py LOG.csv [reduced|full]"""
import sys

import numpy as np
from scipy.integrate import solve_ivp

from peer_common import GEAR, INERTIA_GEAR, STIFF_GEAR, STIFF_LINK, fit_and_print, read_log


class DriveTrain:
    """Simulates the link torque from the held motor torque. Coulomb friction
    sticks: the motor either slides (friction -sign * tau_c, an event where
    its rate crosses zero) or sticks (rate 0, an event where the torque on it
    exceeds tau_c); solve_ivp restarts at each such event only."""

    def __init__(self, time, torque, full):
        self.time, self.torque, self.full = time, torque, full
        self.max_step = float(np.min(np.diff(time)))

    def input_at(self, when):
        index = np.searchsorted(self.time, when, side="right") - 1
        return self.torque[min(max(index, 0), len(self.torque) - 1)]

    def link_torque(self, theta):
        damping_g, inertia_m, coulomb, offset = theta
        mass, viscous = GEAR * GEAR * inertia_m, GEAR * GEAR * damping_g
        if self.full:
            spring, gain, size, shown = STIFF_GEAR, STIFF_LINK, 4, 2
        else:
            spring, gain, size, shown = STIFF_LINK * STIFF_GEAR / (STIFF_LINK + STIFF_GEAR), STIFF_LINK * STIFF_GEAR / (
                STIFF_LINK + STIFF_GEAR), 2, 0

        def load(when, x):  # torque on the motor besides friction and damping
            deflection = x[0] - x[2] if self.full else x[0]
            return GEAR * self.input_at(when) - spring * deflection

        def rhs(when, x, direction):
            rate = 0.0 if direction == 0 else x[1]
            accel = 0.0 if direction == 0 else (load(when, x) - viscous * rate - direction * coulomb) / mass
            if not self.full:
                return [rate, accel]
            link = (STIFF_GEAR * x[0] - (STIFF_LINK + STIFF_GEAR) * x[2]) / (GEAR * GEAR * INERTIA_GEAR)
            return [rate, accel, x[3], link]

        def mode_at(when, x):
            torque = load(when, x)
            return 0 if abs(torque) <= coulomb else int(np.sign(torque))

        output = np.empty(len(self.time))
        x, now, done, restarts = np.zeros(size), self.time[0], 0, 0
        direction = mode_at(now, x)
        while done < len(self.time):
            if direction == 0:
                event = lambda when, y, _: abs(load(when, y)) - coulomb  # noqa: E731
                event.direction = 1.0
            else:
                event = lambda when, y, _: y[1]  # noqa: E731
                event.direction = -float(direction)
            event.terminal = True
            try:
                result = solve_ivp(rhs, (now, self.time[-1]), x, method="LSODA", t_eval=self.time[done:],
                                   events=event, args=(direction,), max_step=self.max_step, rtol=1e-7, atol=1e-10)
            except ValueError:  # SciPy's event search failed (a bracket that is not one)
                return np.full(len(self.time), 1e6)
            restarts += 1
            if result.status < 0 or restarts > 10000:
                return np.full(len(self.time), 1e6)
            count = len(result.t)
            if count:
                output[done:done + count] = gain * np.asarray(result.y)[shown] + offset
            done += count
            if result.status == 0:
                break
            now, x = result.t_events[0][0], result.y_events[0][0].copy()
            # An event at a step of the held torque is found just before the
            # sample: the mode after it follows the new torque.
            following = np.searchsorted(self.time, now)
            if following < len(self.time) and self.time[following] - now < 1e-6 * self.max_step:
                now = self.time[following]
            if direction != 0:
                x[1] = 0.0
            direction = mode_at(now, x)
        return output


def main():
    time, torque, measured = read_log(sys.argv[1])
    model = DriveTrain(time, torque, len(sys.argv) > 2 and sys.argv[2] == "full")
    fit_and_print(model.link_torque, measured)


if __name__ == "__main__":
    main()
