"""Peak finite-length film pressure along an orbit (checker.calc.film_pressure) against the
finite-difference Reynolds solver (checker.calc.reynolds)."""

from __future__ import annotations

import numpy as np
import pytest

from checker.calc import film_pressure as fp
from checker.calc import reynolds as ry


def _solver_peak(w, load, d, ln, c, mu):
    """Peak film pressure of the finite-difference Reynolds solver (checker.calc.reynolds,
    Swift-Stieber cavitation) at the mobility-method state of load-frame eccentricity ``w``
    under ``load`` (complex, N): the squeeze velocity from the solver's own mobility."""
    e = w * load / abs(load)
    mz, mk = ry.mobility_reynolds(w.real, w.imag, ln / d)
    m = complex(float(mz), float(mk)) * load / abs(load)
    psi = 2 * c / d
    vs = abs(load) * psi**2 / (mu * ln * d) * m  # V_s / c
    st = ry.film_force(e.real, e.imag, vs.real, vs.imag, d, ln, c, mu)
    assert complex(float(st.force_x), float(st.force_y)) == pytest.approx(load, rel=1e-6)
    return float(st.p_max)


@pytest.mark.parametrize("full_groove", [False, True])
def test_peak_film_pressure_finite_against_the_solver(full_groove):
    """An orbit whose eccentricity turns with a rotating, pulsating load (fixed state in the
    load's frame): the peak lies at the largest load (crank angle 0) and equals the Reynolds
    solver's peak there within 1 % (the map's accuracy); a full groove splits the bearing
    into two lands of half the length, each carrying half the load."""
    d, c, mu, x = 0.048, 24e-6, 0.004, 0.37
    ln = (2 if full_groove else 1) * x * d
    w = 0.7 * np.exp(0.5j)
    theta = np.linspace(0.0, 4.0 * np.pi, 48, endpoint=False)
    load = 12e3 * (1.0 + 0.5 * np.cos(theta)) * np.exp(1j * theta)
    e = w * load / np.abs(load)
    p, th = fp.peak_film_pressure_finite(load.real, load.imag, e.real, e.imag, theta, d, ln, c,
                                         mu, full_groove)
    assert float(th) == 0.0
    share = 0.5 if full_groove else 1.0
    ref = _solver_peak(w, complex(18e3 * share), d, x * d, c, mu)
    assert float(p) == pytest.approx(ref, rel=0.01)
