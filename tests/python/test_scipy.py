"""Against SciPy's solve_ivp(method="DOP853") at the paper's settings, the way the paper's
own computations were done (NDBWSHCCM, eq:BWSHCCM_nd, written here independently)."""

import numpy as np
import pytest

import bwcl

scipy_integrate = pytest.importorskip(
    "scipy.integrate", reason="SciPy is not installed: the solve_ivp comparison is skipped"
)

SETS = {
    "SHC DSS": (1.43, -1.42, 0.632, 0.00715, 1.31, 1.27),
    "SHC DSA": (0.63, -0.611, 0.188, 0.00594, 1.0, 2.02),
}


def scipy_cor(B, G, kappa, sigma, n, p):
    kc = 1 - kappa

    def force(X, Z, V):
        return (-kappa * abs(X) ** (p - 1) * X - kc * abs(Z) ** (p - 1) * Z
                - sigma * abs(X) ** p * V)

    def f(t, y):
        X, Z, V = y
        return [V, V - B * abs(Z) ** (n - 1) * Z * abs(V) - G * abs(Z) ** n * V, force(X, Z, V)]

    def sep(t, y):
        return force(*y)

    sep.terminal, sep.direction = True, -1
    s = scipy_integrate.solve_ivp(f, (0, 100), [0.0, 0.0, -1.0], method="DOP853", rtol=1e-10,
                                  atol=1e-12, max_step=1e-2, events=sep)
    assert s.status == 1, s.message
    return s.t_events[0][0], s.y_events[0][0][2]


@pytest.mark.parametrize("name", list(SETS))
@pytest.mark.parametrize("v0", [0.5, 2.0])
def test_cor_matches_solve_ivp(name, v0):
    base = SETS[name]
    r = bwcl.cor("shc", base=base, v0=[v0])
    ts, e = scipy_cor(*r.params[0])
    # both are f64 DOP853 at the same tolerances: they agree to their error (≲ 1e-9)
    assert abs(r.e[0] - e) < 1e-8 and abs(r.ts[0] - ts) < 1e-8
    q = bwcl.cor_rigorous("shc", base=base, v0=[v0])
    assert q.e[0, 0] - 1e-8 < e < q.e[0, 1] + 1e-8
