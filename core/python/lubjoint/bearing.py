"""lubjoint.bearing: a journal bearing alone, as ``lubbearing`` computes it.

``force`` evaluates a film force law over NumPy arrays, ``steady_bearing`` finds the
equilibrium of a steadily loaded bearing; both check their arguments with lubbearing's rules
(lub/bearing/bearing_inputs.hpp) in the compiled ``_lubjoint``.
"""

import warnings
from typing import NamedTuple

import numpy as np

from . import _lubjoint
from .run import PlausibilityWarning

#: The force laws a scene or ``force`` can name.
FORCE_LAWS = tuple(n.strip() for n in _lubjoint.force_law_names().split(","))


class FilmForce(NamedTuple):
    """Film force on the journal [N], arrays of the broadcast shape of the inputs.

    ``radial_N`` along the eccentricity e (outward; < 0 pushes the journal towards the
    centre), ``tangential_N`` along e rotated +90 deg (same sign as the wedge speed).
    """

    radial_N: np.ndarray
    tangential_N: np.ndarray


def force(law, eps, eps_dot, wedge_rad_s, *, radius_m, clearance_m, length_m, viscosity_Pa_s,
          cavitation=None, n_theta=None, n_z=None, groove_at_max_film=False):
    """Film force of a journal bearing, vectorised: the computation of ``lubbearing force``.

    Parameters
    ----------
    law : str
        A force law (``FORCE_LAWS``): ``pinkus_sternlicht``, ``frene_long``,
        ``frene_short``, ``gumbel_long``, ``gumbel_short``,
        ``pinkus_sternlicht_continuous``, ``finite_reynolds``.
    eps : array_like
        Eccentricity ratio ε = ``|e|``/c, dimensionless, 0 <= ε < 1.
    eps_dot : array_like
        Its rate ε̇ [1/s], > 0 when the journal moves towards the wall.
    wedge_rad_s : array_like
        Wedge speed w = ω_J + ω_B − 2γ̇ [rad/s] (lubbearing: ``--omega − 2 --gamma-dot``).
        ``eps``, ``eps_dot`` and ``wedge_rad_s`` are broadcast together (NumPy rules).
    radius_m : float
        Journal radius R_J [m] > 0 (the bearing radius is R_J + c, as in lubbearing).
    clearance_m : float
        Radial clearance c [m] > 0.
    length_m : float
        Bearing length L [m] > 0.
    viscosity_Pa_s : float
        Dynamic viscosity μ [Pa s] > 0.
    cavitation, n_theta, n_z, groove_at_max_film
        ``finite_reynolds`` only: cavitation condition (``gumbel``, ``reynolds``
        (default), ``sommerfeld``), cells around the circumference (default 48), axial
        nodes over half the length (default 8), ambient pressure along the line of maximum
        film thickness.

    Returns
    -------
    FilmForce
        ``(radial_N, tangential_N)``, float64 arrays of the broadcast shape (0-d for scalar
        inputs) [N]; the force on the journal (the bearing feels the opposite).

    Raises
    ------
    InputError
        (a ``ValueError``) naming the argument, its value and the rule; for ε, ε̇ and w the
        index is into the broadcast arrays, flattened (C order).

    The GIL is released while the law is evaluated.
    """
    e, ed, w = np.broadcast_arrays(*(np.asarray(x, dtype=np.float64) for x in (eps, eps_dot, wedge_rad_s)))
    shape = e.shape
    f = _lubjoint.force(law, e.ravel(), ed.ravel(), w.ravel(), float(radius_m), float(clearance_m),
                        float(length_m), float(viscosity_Pa_s), cavitation, n_theta, n_z, bool(groove_at_max_film))
    return FilmForce(f["radial_N"].reshape(shape), f["tangential_N"].reshape(shape))


def pressure(law, theta_rad, eps, eps_dot, wedge_rad_s, *, radius_m, clearance_m, length_m, viscosity_Pa_s,
             cavitation=None, n_theta=None, n_z=None, groove_at_max_film=False):
    """Film pressure [Pa] in the bearing's mid-plane at the angles ``theta_rad``, one state.

    The field the law's force integrates (docs/theory/bearing-outputs.md): Eq. (3) for the short
    laws, Eq. (5) for the long ones, the π film for the Pinkus–Sternlicht laws (negative values
    included for the full-film Frêne laws, 0 where a cavitated film has ruptured); for
    ``finite_reynolds`` the solver's grid at the mid-plane cell centres, interpolated linearly
    and periodically in θ.

    Parameters
    ----------
    law : str
        A force law (``FORCE_LAWS``).
    theta_rad : array_like
        Angles θ [rad] from the line of maximum film thickness (h = c (1 + ε cos θ)), in the
        direction of the wedge speed.
    eps, eps_dot, wedge_rad_s : float
        The state, as ``force`` takes it (ε, ε̇ [1/s], w [rad/s]).
    radius_m, clearance_m, length_m, viscosity_Pa_s, cavitation, n_theta, n_z, groove_at_max_film
        As ``force``.

    Returns
    -------
    numpy.ndarray
        float64, the shape of ``theta_rad`` [Pa].

    Raises
    ------
    InputError
        (a ``ValueError``) naming the argument, its value and the rule.
    """
    th = np.asarray(theta_rad, dtype=np.float64)
    p = _lubjoint.pressure(law, th.ravel(), float(eps), float(eps_dot), float(wedge_rad_s), float(radius_m),
                           float(clearance_m), float(length_m), float(viscosity_Pa_s), cavitation, n_theta, n_z,
                           bool(groove_at_max_film))
    return p.reshape(th.shape)


def steady_bearing(law, *, load_N, speed_rpm, radius_m, clearance_m, length_m, viscosity_Pa_s,
                   cavitation=None, n_theta=None, n_z=None, groove_at_max_film=False):
    """Equilibrium of a steadily loaded journal bearing: the computation of ``lubbearing steady``.

    A journal turning at ``speed_rpm`` [rev/min] (≠ 0; bearing at rest) under a constant
    load ``load_N`` [N] > 0; the geometry and ``law`` as in ``force`` (R_J = ``radius_m``,
    R_B = R_J + ``clearance_m``, L = ``length_m``, μ = ``viscosity_Pa_s``).

    Returns
    -------
    dict
        The keys of lubbearing's JSON: ``model``, the inputs, ``sommerfeld_number``
        (S = (R_J/c)² μ N/P, N [rev/s], P = W/(L D)), ``converged``; if converged ``eps``,
        ``attitude_angle_deg`` [deg] (load line to line of centres),
        ``min_film_thickness_m`` [m], ``radial_N``, ``tangential_N`` [N] (``|F|`` = W),
        ``friction_torque_Nm`` (on the journal), ``friction_coefficient``,
        ``friction_variable`` ((R/c) f), ``power_loss_W``, ``peak_pressure_Pa``,
        ``peak_pressure_angle_deg`` (from the line of maximum film), ``load_over_peak_pressure``
        (P/p_max); for ``finite_reynolds`` and the short-bearing laws also ``inflow_m3_s``,
        ``side_flow_m3_s``, ``flow_variable`` (Q/(R c N L)), ``side_flow_ratio`` (Q_s/Q);
        ``force_law_evaluations``; if not, ``message`` (lubbearing's exit status 3);
        ``warnings``: the plausibility warnings (a list of str; each also issued as a
        ``PlausibilityWarning``).

    Raises
    ------
    InputError
        (a ``ValueError``) naming the argument, its value and the rule.
    """
    r = _lubjoint.steady_bearing(law, float(load_N), float(speed_rpm), float(radius_m), float(clearance_m),
                                 float(length_m), float(viscosity_Pa_s), cavitation, n_theta, n_z,
                                 bool(groove_at_max_film))
    for w in r["warnings"]:
        warnings.warn(w, PlausibilityWarning, stacklevel=2)
    return r
