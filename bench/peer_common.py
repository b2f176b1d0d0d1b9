"""What the SciPy peers B and C of scripts/benchmark share (not part of
driveid): the drive train's known values, reading a step log and the fit with the choices of peer B
(bounded least_squares, trust-region reflective, x_scale='jac', 2-point
Jacobian, start as data/paper000_start.yaml), printed as one line."""
import numpy as np
from scipy.optimize import least_squares

# The drive train's known values (data/paper000_start.yaml).
GEAR = 80.0           # n_g
STIFF_LINK = 15000.0  # k_Tl [N m/rad]
STIFF_GEAR = 18375.0  # k_Tg [N m/rad]
INERTIA_GEAR = 6.71875e-06  # Theta_g [kg m^2]


def read_log(path):
    with open(path) as log:
        lines = [line for line in log if line.strip() and not line.startswith("#")]
    header = lines[0].strip().split(",")
    values = np.loadtxt(lines[1:], delimiter=",", ndmin=2)
    column = {name: values[:, k] for k, name in enumerate(header)}
    return column["t"], column["tau_motor"], column["tau_link"]


def fit_and_print(link_torque, measured):
    """Fits d_g, Theta_motor, tau_c, offset of link_torque(theta) to measured."""
    theta0 = np.array([0.005, 1.6e-4, 12.0, 0.0])
    fit = least_squares(lambda theta: link_torque(theta) - measured, theta0, method="trf", x_scale="jac",
                        bounds=([0.0, 1e-9, 0.0, -np.inf], [np.inf, np.inf, np.inf, np.inf]))
    names = ("d_g", "Theta_motor", "tau_c", "offset")
    print("estimates: " + " ".join(f"{n}={v:.8g}" for n, v in zip(names, fit.x)) + f" nfev={fit.nfev}")
