#!/usr/bin/env python3
"""Reference results of SciPy's DOP853 for tests/dop853.rs.

Solves, with solve_ivp(method="DOP853", rtol=1e-10, atol=1e-12) and otherwise default settings,
  (a) Van der Pol, mu = 1:  y0' = y1,  y1' = mu (1 - y0^2) y1 - y0,  y(0) = [2, 0], t in [0, 5];
  (b) Lorenz (sigma, rho, beta) = (10, 28, 8/3),  y(0) = [1, 1, 1], t in [0, 1],
and prints, as JSON, each problem's final state, nfev, number of accepted steps (len(t) - 1),
the accepted step times (sol.t), SciPy's dense output (sol.sol) at DENSE_T, with the SciPy/NumPy/Python versions used.

Regenerate with:  python3 tests/data/scipy_dop853_reference.py > tests/data/scipy_dop853_reference.json
"""
import json
import platform

import numpy as np
import scipy
from scipy.integrate import solve_ivp

RTOL, ATOL = 1e-10, 1e-12
MU = 1.0
SIGMA, RHO, BETA = 10.0, 28.0, 8.0 / 3.0
# Times (fractions of the span) at which the dense output is recorded.
DENSE_FRACTIONS = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9]


def van_der_pol(t, y):
    return [y[1], MU * (1.0 - y[0] * y[0]) * y[1] - y[0]]


def lorenz(t, y):
    return [SIGMA * (y[1] - y[0]), y[0] * (RHO - y[2]) - y[1], y[0] * y[1] - BETA * y[2]]


def run(name, fun, t_span, y0):
    sol = solve_ivp(fun, t_span, y0, method="DOP853", rtol=RTOL, atol=ATOL)
    assert sol.success, sol.message
    # A second run for the interpolant: with dense_output=True SciPy also counts the 3 extra
    # stages of every step in nfev, so nfev above comes from the plain run.
    dense = solve_ivp(fun, t_span, y0, method="DOP853", rtol=RTOL, atol=ATOL, dense_output=True)
    assert np.array_equal(dense.t, sol.t)
    dense_t = [t_span[0] + x * (t_span[1] - t_span[0]) for x in DENSE_FRACTIONS]
    return {
        "name": name,
        "t0": t_span[0],
        "t_end": t_span[1],
        "y0": list(map(float, y0)),
        "y_end": [float(v) for v in sol.y[:, -1]],
        "nfev": int(sol.nfev),
        "steps": int(len(sol.t) - 1),
        "t_steps": [float(t) for t in sol.t],
        "dense_t": dense_t,
        "dense_y": [[float(v) for v in dense.sol(t)] for t in dense_t],
    }


def main():
    out = {
        "scipy_version": scipy.__version__,
        "numpy_version": np.__version__,
        "python_version": platform.python_version(),
        "method": "DOP853",
        "rtol": RTOL,
        "atol": ATOL,
        "problems": [
            run("van_der_pol_mu1", van_der_pol, (0.0, 5.0), [2.0, 0.0]),
            run("lorenz", lorenz, (0.0, 1.0), [1.0, 1.0, 1.0]),
        ],
    }
    print(json.dumps(out, indent=2))


if __name__ == "__main__":
    main()
