r"""Vehicle dead reckoning (DR) and GPS/DR navigation models (the simulation is in :mod:`filterwnn.navigation.scenarios`).

The model of Zhang, Ma, Chen and Mastorakis (the second paper, eqs. 1-3). The state is

.. math::
    X = [e,\ v_e,\ a_e,\ n,\ v_n,\ a_n]^T

(east and north position, velocity and acceleration, in m, m/s, m/s^2), the transition
is :math:`X_k = \Phi X_{k-1} + W_{k-1}` with :math:`\Phi = \mathrm{diag}(A, A)`,

.. math::
    A = \begin{bmatrix} 1 & T & c \\ 0 & 1 & T \\ 0 & 0 & 1 \end{bmatrix},\qquad
    c = T^2/2 \ \text{(default, ``accel_term="kinematic"``)}\quad\text{or}\quad
    c = T^2 \ \text{(``accel_term="paper"``)},

and the DR measurement is the gyro heading and the odometer distance per sample

.. math::
    Y = [\theta,\ s]^T,\qquad \theta = \operatorname{atan2}(v_e, v_n),\qquad
    s = T \zeta \sqrt{v_e^2 + v_n^2}.

Choices and their reasons:

* ``T^2/2`` is the exact constant-acceleration kinematics and matches the white-jerk
  process noise of :func:`filterpy.common.Q_continuous_white_noise`; the paper prints
  ``T^2``, which we read as a typo and offer only as ``accel_term="paper"``.
* The heading is measured from north, clockwise positive, with ``atan2``: the paper's
  ``arctan(v_e / v_n)`` loses the quadrant when ``v_n < 0``. Heading residuals are
  wrapped to ``[-pi, pi)`` by :func:`dr_residual` and the unscented filters average
  headings with :func:`dr_z_mean` (a circular mean); every filter in the package uses
  these two, the neural filter's online loss included. Without the wrap, a vehicle
  driving through heading 180 degrees makes an EKF diverge by kilometres.
* The heading is undefined at zero speed. The analytic Jacobian guards it by using
  ``max(|v|, min_speed)`` in the denominators (so it stays finite), and
  :meth:`GPSDRModel.R_for` inflates the heading variance for a standing vehicle.
* Position is **not observable** from ``[theta, s]`` (``H`` has zero columns for
  ``e`` and ``n``): a DR-only position is the known start plus the integrated velocity
  estimate, and its error is a random walk for every filter. GPS fixes make it
  observable; :class:`GPSDRModel` adds them, and its 8-state form also estimates the
  odometer scale ``zeta`` and a heading bias ``b`` (real sensors have both; a 6-state
  filter is tens of metres off with a 2 % scale error).

Missing GPS is said explicitly, never with NaN: :meth:`GPSDRModel.measurement_for` takes
``z_gps=None`` and then gives the DR-only measurement, ``hx`` arguments and ``R``. The
models only describe (``fx``, ``hx``, Jacobians, noise); the filter that drives them
through starts, stops and GPS outages is :class:`filterwnn.navigation.gpsdr.GPSDRFilter`.

Every function is written on the last axis, so it accepts one state ``(dim_x,)`` or a
stack of points ``(n_points, dim_x)`` (what ``vectorized=True`` unscented filters pass).

>>> import numpy as np
>>> m = DRModel(dt=0.1)
>>> x = np.array([0.0, 10.0, 0.0, 0.0, 10.0, 0.0])      # 45 degrees, 14.14 m/s
>>> np.round(m.hx(x), 4)                                 # [heading rad, distance m]
array([0.7854, 1.4142])
>>> m.fx(np.stack([x, x])).shape                         # vectorized: rows are points
(2, 6)
>>> float(dr_residual(np.array([np.pi - 0.01, 1.0]), np.array([-np.pi + 0.01, 1.0]))[0])
-0.02

References
----------
Zhang L., Ma H., Chen Y., Mastorakis N. E., "Recurrent neural network approaches for
nonlinear filters of navigation systems".
"""

from __future__ import annotations

import copy

import numpy as np
from filterpy.common import Q_continuous_white_noise

from .._linalg import insert_state
from .._validation import (
    as_state,
    check_choice,
    check_covariance,
    check_positive,
)
from ..angles import angle_mean, angle_residual, wrap
from ..models import StateSpaceModel, from_model

__all__ = [
    "wrap_angle",
    "transition_matrix",
    "dr_fx",
    "dr_hx",
    "dr_HJacobian",
    "dr_residual",
    "dr_z_mean",
    "gps_hx",
    "gps_H",
    "DRModel",
    "GPSDRModel",
    "SENSOR_GRADES",
]

_ACCEL_TERMS = ("kinematic", "paper")


# --------------------------------------------------------------------------- pure maths


#: :func:`filterwnn.angles.wrap` (angles in rad to ``[-pi, pi)``, any shape) under its DR name.
wrap_angle = wrap

#: How far past ``2 pi`` a heading in radians may read: a heading just under ``2 pi`` written
#: with a few decimals rounds up past it (6.2832 to four decimals, 6.3 to one: 0.017 over).
HEADING_ROUNDING = 0.02


def transition_matrix(dt, accel_term="kinematic", dim_x=6, rate_bias=None):
    r"""The transition matrix :math:`\Phi` of shape ``(dim_x, dim_x)``.

    ``dim_x = 6`` is the kinematic state; ``dim_x = 8`` appends the odometer scale and
    the heading bias, both constant (random walks through ``Q``); ``dim_x = 9`` also a
    gyro rate bias ``r`` that the heading bias integrates (``b_k = b_{k-1} + T r``);
    ``dim_x = 10`` also the gyro's scale factor error, constant here (the measured turns
    that carry it into the heading bias are inputs: ``GPSDRFilter`` applies them).
    ``accel_term="kinematic"`` puts ``T^2/2`` in the position-acceleration entries (exact
    constant-acceleration kinematics); ``"paper"`` puts the paper's printed ``T^2``.
    ``rate_bias``: whether state 8 is a rate bias (default: ``dim_x >= 9``); a model whose ninth state
    is something else (the fixes' latency of an 8-state model) passes False. States past them are
    constant.
    """
    dt = check_positive(dt, "dt")
    check_choice(accel_term, "accel_term", _ACCEL_TERMS)
    c = 0.5 * dt * dt if accel_term == "kinematic" else dt * dt
    A = np.array([[1.0, dt, c], [0.0, 1.0, dt], [0.0, 0.0, 1.0]])
    F = np.eye(dim_x)
    F[0:3, 0:3] = A
    F[3:6, 3:6] = A
    if dim_x >= 9 if rate_bias is None else rate_bias:
        F[7, 8] = dt
    return F


def dr_fx(x, dt, accel_term="kinematic", rate_bias=None):
    """Noise-free transition ``Phi x`` on the last axis: ``(dim_x,)`` or ``(n, dim_x)``.

    Works for the 6-state model and for the 8-state one (scale and bias unchanged). ``rate_bias``: whether
    state 8 is a gyro rate bias that the heading bias integrates, as in :func:`transition_matrix` (default:
    ``dim_x >= 9``); a model whose ninth state is something else (the fixes' latency of an 8-state model)
    passes False.
    """
    x = np.asarray(x, dtype=float)
    c = 0.5 * dt * dt if accel_term == "kinematic" else dt * dt
    out = x.copy()
    out[..., 0] = x[..., 0] + dt * x[..., 1] + c * x[..., 2]
    out[..., 1] = x[..., 1] + dt * x[..., 2]
    out[..., 3] = x[..., 3] + dt * x[..., 4] + c * x[..., 5]
    out[..., 4] = x[..., 4] + dt * x[..., 5]
    if x.shape[-1] >= 9 if rate_bias is None else rate_bias:  # the heading bias integrates the gyro rate bias
        out[..., 7] = x[..., 7] + dt * x[..., 8]
    return out


def _scale_bias(x, zeta, augmented):
    if augmented:
        return x[..., 6], x[..., 7]
    return zeta, 0.0


def dr_hx(x, dt, zeta=1.0, augmented=False):
    """DR measurement ``[heading, odometer distance]`` on the last axis.

    Parameters
    ----------
    x : ndarray of shape (dim_x,) or (n_points, dim_x)
    dt : float
        Sample interval ``T`` (s).
    zeta : float
        Odometer scale (6-state model).
    augmented : bool
        8-state model: ``zeta = x[..., 6]`` and the measured heading is
        ``atan2(v_e, v_n) + x[..., 7]`` (a heading bias), wrapped.

    Returns
    -------
    ndarray of shape (2,) or (n_points, 2)
        Heading in ``[-pi, pi)`` (rad, from north, clockwise) and distance (m).
    """
    x = np.asarray(x, dtype=float)
    ve, vn = x[..., 1], x[..., 4]
    z_scale, bias = _scale_bias(x, zeta, augmented)
    theta = wrap_angle(np.arctan2(ve, vn) + bias)  # atan2 gives (-pi, pi]; we use [-pi, pi)
    s = dt * z_scale * np.hypot(ve, vn)
    return np.stack([theta, s], axis=-1)


def dr_HJacobian(x, dt, zeta=1.0, augmented=False, min_speed=0.1):
    r"""Analytic Jacobian of :func:`dr_hx`, shape ``(2, dim_x)`` or ``(n_points, 2, dim_x)``.

    :math:`\partial\theta/\partial v_e = v_n/v^2`, :math:`\partial\theta/\partial v_n = -v_e/v^2`,
    :math:`\partial s/\partial v_e = T\zeta v_e/v`, :math:`\partial s/\partial v_n = T\zeta v_n/v`;
    8-state: :math:`\partial s/\partial\zeta = T v`, :math:`\partial\theta/\partial b = 1`.
    Zero-speed guard: ``v`` is replaced by ``max(v, min_speed)`` in the denominators, so
    the Jacobian stays finite (the heading itself is undefined at ``v = 0``).
    """
    x = np.asarray(x, dtype=float)
    ve, vn = x[..., 1], x[..., 4]
    z_scale, _ = _scale_bias(x, zeta, augmented)
    v_true = np.hypot(ve, vn)
    v = np.maximum(v_true, min_speed)
    v2 = v * v
    H = np.zeros(x.shape[:-1] + (2, x.shape[-1]))
    H[..., 0, 1] = vn / v2
    H[..., 0, 4] = -ve / v2
    H[..., 1, 1] = dt * z_scale * ve / v
    H[..., 1, 4] = dt * z_scale * vn / v
    if augmented:
        H[..., 1, 6] = dt * v_true
        H[..., 0, 7] = 1.0
    return H


def dr_residual(a, b):
    """Measurement residual ``a - b`` with the heading (entry 0) wrapped to ``[-pi, pi)``.

    Works for the DR measurement ``[theta, s]`` and the GPS/DR one ``[theta, s, e, n]``,
    on the last axis (``(dim_z,)`` or ``(n_points, dim_z)`` broadcast against a row):
    :func:`filterwnn.angles.angle_residual` of column 0.
    """
    return _heading_residual(a, b)


def dr_z_mean(sigmas, Wm):
    """Weighted mean of measurement sigma points with a circular mean for the heading.

    Parameters
    ----------
    sigmas : ndarray of shape (n_sigmas, dim_z)
        Entry 0 is the heading (rad); the rest are averaged linearly.
    Wm : ndarray of shape (n_sigmas,)

    Returns
    -------
    ndarray of shape (dim_z,)
        Heading ``atan2(sum W sin, sum W cos)``; the others ``sum W z``
        (:func:`filterwnn.angles.angle_mean` of column 0).
    """
    return _heading_mean(sigmas, Wm)


_heading_residual = angle_residual(0)
_heading_mean = angle_mean(0)


def gps_hx(x, latency=None):
    """GPS position ``[e, n]`` on the last axis: ``(2,)`` or ``(n_points, 2)``.

    ``latency``: the index of a latency state ``tau`` (s), when the state has one: a fix stamped at the
    DR sample's time is the position ``tau`` earlier, ``[e - v_e tau, n - v_n tau]`` (to first order).
    """
    x = np.asarray(x, dtype=float)
    if latency is None:
        return np.stack([x[..., 0], x[..., 3]], axis=-1)
    tau = x[..., latency]
    return np.stack([x[..., 0] - x[..., 1] * tau, x[..., 3] - x[..., 4] * tau], axis=-1)


def gps_H(x, dim_x, latency=None):
    """The Jacobian of :func:`gps_hx`: ``(2, dim_x)``, or ``(n_points, 2, dim_x)``."""
    x = np.asarray(x, dtype=float)
    G = np.zeros(x.shape[:-1] + (2, dim_x))
    G[..., 0, 0] = 1.0
    G[..., 1, 3] = 1.0
    if latency is not None:
        tau = x[..., latency]
        G[..., 0, 1] = G[..., 1, 4] = -tau
        G[..., 0, latency], G[..., 1, latency] = -x[..., 1], -x[..., 4]
    return G


# --------------------------------------------------------------------------- models


#: Sensor grades, each number a data-sheet-style specification (see :meth:`GPSDRModel.from_grade`
#: for how each becomes a model setting). Class figures, not one product's data sheet:
#:
#: ``survey``: a survey-grade GNSS/INS in a car (an HGuide n380-class unit, as in onavdata's drives):
#: GNSS about 1.5 m (the receiver reports each fix's accuracy), a tactical-grade gyro (angle random walk
#: about 0.1 deg/sqrt(h), bias instability about 1 deg/h, residual bias negligible), an odometer of
#: 2 cm per 0.1 s sample and a few per cent scale uncertainty.
#: ``phone``: a phone's 1 Hz GPS of about 5 m, a MEMS gyro (angle random walk about 0.3 deg/sqrt(h),
#: bias instability about 10 deg/h, a residual turn-on bias of up to about 0.05 deg/s after the phone's
#: own calibration), a CAN odometer (1 cm per 0.1 s sample, a few per cent scale from tyres).
#: ``gyro_bias_deg_s``: the gyro's residual rate bias (deg/s, one sigma; the rate-bias state's prior, and
#: three of it its calibration bound). A gyro outside it (an uncalibrated MEMS gyro's turn-on bias reaches
#: 0.7 deg/s) is followed once two stops it could not follow agree on it, and the filter warns with the value to give
#: (``{"gyro_bias_deg_s": 0.31}``, ``--gyro-bias 0.31``): given from the start, the outages before those
#: stops are right too (docs/study-outputs/dr/zero-rate/RUN.md).
#: ``gyro_scale_sd``: the gyro's scale factor error (its sensitivity tolerance, a fraction, one sigma),
#: estimated as a tenth state when above 0 (with a rate-bias state). 0 in both grades: a MEMS gyro's
#: data sheet gives a tolerance of up to +-3 % (0.01 read as three sigmas), and the state pays for
#: itself only when the error is there (docs/study-outputs/dr/gyro-scale/RUN.md: with 1-3 % it takes the
#: 1 Hz analog's worst outage end from 16-41 m to 7-11 m; without one it costs the shipped sample's
#: median 3.39 -> 4.36 m); pass ``{"gyro_scale_sd": 0.01}`` (``--gyro-scale-sd 0.01``) for a MEMS gyro
#: whose sensitivity was not calibrated. A tactical gyro's scale error is a few hundred ppm.
#: ``gps_latency_sd``: the fixes' latency against the DR samples (s, one sigma), estimated as a last state
#: from the start when above 0 (any calibrated model). 0 in both grades: a receiver that stamps its fixes
#: at their own time has none, and an unknown one is found by :class:`~filterwnn.navigation.gpsdr.GPSDRFilter`'s
#: monitor, which adds the state then; pass ``{"gps_latency_sd": 0.5}`` (``--gps-latency-sd 0.5``) when the
#: fixes and the DR samples were stamped by two clocks (a phone's and a car logger's), so that the outages
#: before the monitor fires are corrected too (docs/study-outputs/dr/latency/RUN.md).
#: Both: a passenger car's manoeuvres as white jerk of about 1.4 m/s^3 (comfortable driving stays
#: under about 2 m/s^3).
SENSOR_GRADES = {
    "survey": dict(gps_sigma_m=1.5, heading_noise_deg=0.2, gyro_arw_deg_rt_h=0.1, gyro_bias_deg_s=0.0,
                   gyro_bias_instability_deg_h=1.0, odometer_noise_m=0.02, odometer_scale_sd=0.03,
                   odometer_scale_drift=1e-8, heading_bias_sd_deg=2.0, vehicle_jerk_sd=1.4, rate_bias=False,
                   gyro_scale_sd=0.0, gps_latency_sd=0.0),
    "phone": dict(gps_sigma_m=5.0, heading_noise_deg=0.5, gyro_arw_deg_rt_h=0.3, gyro_bias_deg_s=0.05,
                  gyro_bias_instability_deg_h=10.0, odometer_noise_m=0.01, odometer_scale_sd=0.03,
                  odometer_scale_drift=1e-8, heading_bias_sd_deg=5.0, vehicle_jerk_sd=1.4, rate_bias=True,
                  gyro_scale_sd=0.0, gps_latency_sd=0.0),
}


def _grade(grade):
    if isinstance(grade, str):
        if grade not in SENSOR_GRADES:
            raise ValueError(f"grade must be one of {sorted(SENSOR_GRADES)} or a dict of specifications, "
                             f"got {grade!r}")
        return dict(SENSOR_GRADES[grade])
    if not isinstance(grade, dict):
        raise TypeError(f"grade must be a str or a dict, got {type(grade).__name__}")
    unknown = set(grade) - set(SENSOR_GRADES["phone"])
    if unknown:
        raise ValueError(f"grade has unknown keys {sorted(unknown)}; valid: {sorted(SENSOR_GRADES['phone'])}")
    spec = dict(SENSOR_GRADES["phone"], **grade)
    for k, v in spec.items():
        if k != "rate_bias":
            check_positive(v, f"grade[{k!r}]", strict=False)
    return spec


def _kinematic_Q(dt, q):
    return Q_continuous_white_noise(dim=3, dt=dt, spectral_density=q, block_size=2, order_by_dim=True)


class DRModel(StateSpaceModel):
    r"""The paper's DR-only model: 6 states, ``[heading, odometer]`` measurements.

    Parameters
    ----------
    dt : float
        Sample interval ``T`` (s), default 0.1 (10 Hz DR).
    zeta : float
        Odometer scale coefficient (known here; estimated by ``GPSDRModel(augmented=True)``).
    q : float
        Power spectral density of the white jerk (m^2/s^5); ``Q`` is filterpy's
        ``Q_continuous_white_noise(dim=3, block_size=2, order_by_dim=True)``.
    sigma_heading : float
        Heading noise standard deviation (rad), default 1 degree.
    sigma_odometer : float
        Odometer distance noise per sample (m), default 0.02.
    accel_term : {"kinematic", "paper"}
        ``T^2/2`` (default) or the paper's printed ``T^2`` in :math:`\Phi`.
    min_speed : float
        Zero-speed guard of the Jacobian (m/s).
    x0, P0 : array-like, optional
        Prior; default the paper's start: position (0, 0) known, velocity
        (10, 10) m/s with standard deviation 0.5 m/s, acceleration 0 (sd 0.1).

    Attributes
    ----------
    dim_x, dim_z : int
        6 and 2.
    F, Q, R : ndarray
        Transition matrix ``(6, 6)``, process noise ``(6, 6)``, measurement noise ``(2, 2)``.
    """

    dim_x = 6
    dim_z = 2

    def __init__(self, dt=0.1, *, zeta=1.0, q=0.1, sigma_heading=np.deg2rad(1.0), sigma_odometer=0.02,
                 accel_term="kinematic", min_speed=0.1, x0=None, P0=None):
        self.dt = check_positive(dt, "dt")
        self.zeta = check_positive(zeta, "zeta")
        self.q = check_positive(q, "q", strict=False)
        self.sigma_heading = check_positive(sigma_heading, "sigma_heading")
        self.sigma_odometer = check_positive(sigma_odometer, "sigma_odometer")
        self.accel_term = check_choice(accel_term, "accel_term", _ACCEL_TERMS)
        self.min_speed = check_positive(min_speed, "min_speed")
        self.F = transition_matrix(self.dt, accel_term, 6)
        self.Q = _kinematic_Q(self.dt, self.q)
        self.R = np.diag([self.sigma_heading**2, self.sigma_odometer**2])
        self.x0 = (
            np.array([0.0, 10.0, 0.0, 0.0, 10.0, 0.0]) if x0 is None else as_state(x0, "x0", 6)
        )
        self.P0 = (
            np.diag([1e-4, 0.25, 0.01, 1e-4, 0.25, 0.01])
            if P0 is None
            else check_covariance(P0, "P0", 6)
        )

    def fx(self, x, dt=None, **fx_args):
        """``Phi x`` for ``(6,)`` or ``(n_points, 6)``."""
        return dr_fx(x, self.dt if dt is None else dt, self.accel_term)

    def FJacobian(self, x=None, dt=None, **fx_args):
        """The (constant) transition matrix ``(6, 6)``."""
        return self.F if dt is None else transition_matrix(dt, self.accel_term, 6)

    def hx(self, x, **hx_args):
        """``[atan2(v_e, v_n), T zeta |v|]`` for ``(6,)`` or ``(n_points, 6)``."""
        return dr_hx(x, self.dt, self.zeta)

    def HJacobian(self, x, **hx_args):
        """Analytic ``(2, 6)`` Jacobian (``(n_points, 2, 6)`` for stacked states)."""
        return dr_HJacobian(x, self.dt, self.zeta, min_speed=self.min_speed)

    residual_z = staticmethod(dr_residual)
    z_mean_fn = staticmethod(dr_z_mean)

    def simulate(self, n_steps, rng=None, x0=None):
        """Simulate with process noise from ``Q`` and wrapped headings (see base class)."""
        xs, zs = super().simulate(n_steps, rng=rng, x0=x0)
        zs[:, 0] = wrap_angle(zs[:, 0])
        return xs, zs

    def ekf(self, x0=None, P0=None, R=None):
        """A filterpy :class:`~filterpy.kalman.ExtendedKalmanFilter` set up on this model.

        Update it with ``kf.update(z, model.HJacobian, model.hx, residual=model.residual_z)``.
        """
        from filterpy.kalman import ExtendedKalmanFilter

        return from_model(ExtendedKalmanFilter, self, x0=x0, P0=P0, R=R)


def _rate_walk(instability_deg_h):
    """The rate-bias state's random-walk density ``q_rate`` (rad^2/s^3) of a gyro whose bias instability is
    ``instability_deg_h``: ``(instability * pi/180 / 3600)^2 / 100 s``."""
    return (np.deg2rad(instability_deg_h) / 3600.0) ** 2 / 100.0


def _rate_walk_instability(q_rate):
    """The bias instability (deg/h) whose rate-bias random walk is ``q_rate``: the inverse of the grade's
    mapping (:meth:`GPSDRModel.from_grade`), for a warning to name the model's value."""
    return float(np.degrees(np.sqrt(q_rate * 100.0)) * 3600.0)


def _grade_settings(spec, rate, augmented=True):
    """:class:`GPSDRModel` keyword arguments from a grade's specification ``spec``, one line per
    number (the mapping of :meth:`GPSDRModel.from_grade`); ``rate``: with a rate-bias state;
    ``augmented``: with calibration states (a 6-state model takes neither a gyro scale nor a latency
    state, whatever the grade says)."""
    arw = np.deg2rad(spec["gyro_arw_deg_rt_h"]) / 60.0
    w = np.deg2rad(spec["gyro_bias_deg_s"])
    kw = dict(
        q=spec["vehicle_jerk_sd"] ** 2,
        sigma_heading=np.deg2rad(spec["heading_noise_deg"]),
        sigma_odometer=spec["odometer_noise_m"],
        sigma_gps=spec["gps_sigma_m"],
        sd_scale=spec["odometer_scale_sd"],
        q_scale=spec["odometer_scale_drift"],
        sd_bias=np.deg2rad(spec["heading_bias_sd_deg"]),
        q_bias=arw**2 + (0.0 if rate else w**2 * 30.0),
    )
    if rate:
        kw.update(sd_rate=max(w, 1e-9),
                  q_rate=_rate_walk(spec["gyro_bias_instability_deg_h"]))
    if not (augmented or rate):  # the 6-state model: no calibration states, so none of these
        return kw
    if spec["gyro_scale_sd"] > 0:
        if not rate:
            raise ValueError("grade['gyro_scale_sd'] > 0 needs a rate-bias state (a grade with rate_bias=True, "
                             "as the phone's): the gyro's scale factor error is the tenth state")
        kw.update(gyro_scale=True, sd_gyro_scale=spec["gyro_scale_sd"])
    if spec["gps_latency_sd"] > 0:
        kw.update(latency=True, sd_latency=spec["gps_latency_sd"])
    return kw


class GPSDRModel(StateSpaceModel):
    r"""GPS/DR: the DR model plus GPS position fixes, optionally with sensor calibration states.

    The full measurement is ``[theta, s, e, n]`` (``dim_z = 4``) when a GPS fix is there,
    and the DR-only ``[theta, s]`` when it is not: :meth:`hx`, :meth:`HJacobian` and
    :meth:`R_for` take ``gps=True/False``, and :meth:`measurement_for` picks them from
    ``z_gps=None``. NaN never enters (a missing fix is ``None``).

    With ``augmented=True`` the state is 8-dimensional,
    ``[e, v_e, a_e, n, v_n, a_n, zeta, b]``: the odometer scale ``zeta`` and a heading
    bias ``b`` (rad, measured heading = true heading + b) as random walks with
    spectral densities ``q_scale`` and ``q_bias``. They are observable only while GPS
    fixes arrive, and then remove the systematic DR error during outages.

    Parameters
    ----------
    dt : float
        DR sample interval (s).
    augmented : bool
        Estimate ``zeta`` and ``b`` (8 states) or not (6 states, ``zeta`` known).
    rate_bias : bool
        With ``augmented``: a ninth state, the gyro rate bias ``r`` (rad/s), integrated by
        the heading bias (``b_k = b_{k-1} + T r_{k-1}``). For MEMS gyros, whose residual
        rate bias makes the heading error grow linearly; a random-walk ``b`` cannot follow it.
    gyro_scale : bool
        With ``rate_bias``: a tenth state, the gyro's scale factor error ``k`` (the measured
        heading turns ``1 + k`` times the car), constant but for ``q_gyro_scale``. Each measured
        turn ``d`` adds ``k d`` to the heading bias: :class:`~filterwnn.navigation.gpsdr.GPSDRFilter`
        applies it from the DR samples (``fx`` alone does not).
    latency : bool
        With ``augmented``: a last state, the fixes' latency ``tau`` (s) against the DR samples (a
        receiver's latency, or the offset between the clocks that stamped the fixes and the DR samples):
        a fix stamped at a sample's time is the position ``tau`` earlier, ``p - v tau``
        (:func:`gps_hx`). Constant but for ``q_latency``. :class:`~filterwnn.navigation.gpsdr.GPSDRFilter`
        adds it when its latency monitor finds one (``latency_on_detection``).
    zeta : float
        Odometer scale assumed by the 6-state model, and the prior mean of the 8-state one.
    q, sigma_heading, sigma_odometer, accel_term, min_speed
        As in :class:`DRModel`.
    sigma_gps : float
        GPS position noise per axis (m).
    q_scale, q_bias : float
        Random-walk spectral densities of ``zeta`` (1/s) and ``b`` (rad^2/s).
    sd_scale, sd_bias : float
        Prior standard deviations of ``zeta`` and ``b``.
    q_rate, sd_rate : float
        Random-walk spectral density (rad^2/s^3) and prior standard deviation (rad/s) of ``r``.
    q_gyro_scale, sd_gyro_scale : float
        Random-walk spectral density (1/s) and prior standard deviation of ``k``.
    q_latency, sd_latency : float
        Random-walk spectral density (s^2/s) and prior standard deviation (s) of ``tau``. The default
        ``q_latency`` is two free-running clocks 20 ppm apart (a crystal's tolerance) taken as a random
        walk of that spread over an hour: ``(20e-6)^2 * 3600`` s.
    stationary_inflation : float
        Factor on the heading variance used by ``R_for(stationary=True)``.
    sigma_zupt : float
        Standard deviation (m/s) of the zero-velocity update (``measurement_for(zupt=True)``).
    sigma_low_speed : float
        Extra velocity noise (m/s, per axis) of the low-speed form (``measurement_for(low_speed=True)``):
        pulling away, a car's track and its gyro heading differ by tens of degrees.
    x0, P0 : array-like, optional
        Prior (default as :class:`DRModel`, extended by ``zeta``, ``b = 0``, ``r = 0`` and ``k = 0``).

    See Also
    --------
    GPSDRModel.from_grade : the settings from a sensor grade or one's own sensor specification.
    """

    def __init__(
        self,
        dt=0.1,
        *,
        augmented=False,
        rate_bias=False,
        gyro_scale=False,
        zeta=1.0,
        q=0.1,
        sigma_heading=np.deg2rad(1.0),
        sigma_odometer=0.02,
        sigma_gps=3.0,
        q_scale=1e-7,
        q_bias=1e-7,
        sd_scale=0.05,
        sd_bias=np.deg2rad(5.0),
        q_rate=1e-10,
        sd_rate=np.deg2rad(0.1),
        q_gyro_scale=1e-12,
        sd_gyro_scale=0.02,
        latency=False,
        q_latency=(20e-6) ** 2 * 3600.0,
        sd_latency=1.0,
        stationary_inflation=1e6,
        sigma_zupt=0.01,
        sigma_low_speed=0.5,
        accel_term="kinematic",
        min_speed=0.1,
        x0=None,
        P0=None,
    ):
        self.dt = check_positive(dt, "dt")
        self.augmented = bool(augmented)
        self.rate_bias = bool(rate_bias)
        if self.rate_bias and not self.augmented:
            raise ValueError("rate_bias=True needs augmented=True (the rate bias drives the heading bias state)")
        self.gyro_scale = bool(gyro_scale)
        if self.gyro_scale and not self.rate_bias:
            raise ValueError("gyro_scale=True needs rate_bias=True (the gyro's scale error is the tenth state)")
        self.latency = bool(latency)
        if self.latency and not self.augmented:
            raise ValueError("latency=True needs augmented=True (the fixes' latency is a calibration state)")
        self.q_latency = check_positive(q_latency, "q_latency", strict=False)
        self.sd_latency = check_positive(sd_latency, "sd_latency")
        self.dim_x = (10 if self.gyro_scale else 9 if self.rate_bias else 8 if self.augmented else 6) + self.latency
        self.q_rate = check_positive(q_rate, "q_rate", strict=False)
        self.q_gyro_scale = check_positive(q_gyro_scale, "q_gyro_scale", strict=False)
        self.sd_gyro_scale = check_positive(sd_gyro_scale, "sd_gyro_scale")
        self.dim_z = 4
        self.zeta = check_positive(zeta, "zeta")
        self.q = check_positive(q, "q", strict=False)
        self.sigma_heading = check_positive(sigma_heading, "sigma_heading")
        self.sigma_odometer = check_positive(sigma_odometer, "sigma_odometer")
        self.sigma_gps = check_positive(sigma_gps, "sigma_gps")
        self.q_scale = check_positive(q_scale, "q_scale", strict=False)
        self.q_bias = check_positive(q_bias, "q_bias", strict=False)
        self.stationary_inflation = check_positive(stationary_inflation, "stationary_inflation")
        self.sigma_zupt = check_positive(sigma_zupt, "sigma_zupt")
        self.sigma_low_speed = check_positive(sigma_low_speed, "sigma_low_speed", strict=False)
        self.accel_term = check_choice(accel_term, "accel_term", _ACCEL_TERMS)
        self.min_speed = check_positive(min_speed, "min_speed")
        self.F = transition_matrix(self.dt, accel_term, self.dim_x, self.rate_bias)
        self.Q = self._process_Q()
        self.R = np.diag(
            [self.sigma_heading**2, self.sigma_odometer**2, self.sigma_gps**2, self.sigma_gps**2]
        )
        self._set_prior(x0, P0, sd_scale, sd_bias, sd_rate)

    def _process_Q(self):
        """The process noise: the kinematic block, then the scale, heading-bias and rate-bias
        random walks (``q_* dt`` each) when those states are present."""
        n = self.dim_x
        Q = np.zeros((n, n))
        Q[:6, :6] = _kinematic_Q(self.dt, self.q)
        if self.augmented:
            Q[6, 6] = self.q_scale * self.dt
            Q[7, 7] = self.q_bias * self.dt
        if self.rate_bias:
            Q[8, 8] = self.q_rate * self.dt
        if self.gyro_scale:
            Q[9, 9] = self.q_gyro_scale * self.dt
        if self.latency:
            Q[-1, -1] = self.q_latency * self.dt
        return Q

    def _set_prior(self, x0, P0, sd_scale, sd_bias, sd_rate):
        """``x0`` and ``P0``: the given ones (checked), or the defaults, with the prior spreads
        ``sd_scale``, ``sd_bias``, ``sd_rate`` on the states the model has."""
        n = self.dim_x
        x0_default = ([0.0, 10.0, 0.0, 0.0, 10.0, 0.0] + ([self.zeta, 0.0] if self.augmented else [])
                      + ([0.0] if self.rate_bias else []) + ([0.0] if self.gyro_scale else [])
                      + ([0.0] if self.latency else []))
        self.x0 = np.array(x0_default) if x0 is None else as_state(x0, "x0", n)
        p0 = [1e-4, 0.25, 0.01, 1e-4, 0.25, 0.01]
        if self.augmented:
            p0 += [check_positive(sd_scale, "sd_scale") ** 2, check_positive(sd_bias, "sd_bias") ** 2]
        if self.rate_bias:
            p0 += [check_positive(sd_rate, "sd_rate") ** 2]
        if self.gyro_scale:
            p0 += [self.sd_gyro_scale ** 2]
        if self.latency:
            p0 += [self.sd_latency ** 2]
        self.P0 = np.diag(p0) if P0 is None else check_covariance(P0, "P0", n)

    @property
    def latency_index(self):
        """The row of the fixes' latency state, or None without one (the last row when there is)."""
        return self.dim_x - 1 if self.latency else None

    @property
    def state_names(self):
        """A short name per state row (``"e"``, ``"v_e"``, ..., ``"odometer scale"``, ``"latency"``)."""
        names = ["e", "v_e", "a_e", "n", "v_n", "a_n"]
        names += ["odometer scale", "heading bias"] if self.augmented else []
        names += ["gyro rate bias"] if self.rate_bias else []
        names += ["gyro scale factor"] if self.gyro_scale else []
        return names + (["latency"] if self.latency else [])

    def _with_state(self, index, prior_sd, **flags):
        """This model with one more state at row ``index`` (prior mean 0, sd ``prior_sd``): the same
        settings otherwise, ``x0``/``P0`` extended (a filter switching to it brings its own)."""
        m = copy.copy(self)
        for k, v in flags.items():
            setattr(m, k, v)
        m.dim_x = self.dim_x + 1
        m.F = transition_matrix(m.dt, m.accel_term, m.dim_x, m.rate_bias)
        m.Q = m._process_Q()
        m.x0, m.P0 = insert_state(self.x0, self.P0, index, 0.0, prior_sd ** 2)
        return m

    def with_gyro_scale(self, sd):
        """This model with the gyro's scale factor error as a state (row 9, prior mean 0, sd ``sd``):
        the same settings otherwise, and ``x0``/``P0`` extended (a filter switching to it brings its own)."""
        if not self.rate_bias or self.gyro_scale:
            raise ValueError("with_gyro_scale needs a model with a rate-bias state and no scale state")
        sd = check_positive(sd, "sd")
        return self._with_state(9, sd, gyro_scale=True, sd_gyro_scale=sd)

    def with_latency(self, sd):
        """This model with the fixes' latency as its last state (prior mean 0, sd ``sd`` s): the same
        settings otherwise, and ``x0``/``P0`` extended (a filter switching to it brings its own)."""
        if not self.augmented or self.latency:
            raise ValueError("with_latency needs an augmented model without a latency state")
        sd = check_positive(sd, "sd")
        return self._with_state(self.dim_x, sd, latency=True, sd_latency=sd)

    @classmethod
    def from_grade(cls, grade, dt=0.1, *, augmented=True, rate_bias=None, **overrides):
        """Model settings from a sensor grade or a specification, not from a drive.

        Parameters
        ----------
        grade : str or dict
            A key of :data:`SENSOR_GRADES` or a dict with the same keys (one's own
            sensors' data-sheet numbers; missing keys come from ``"phone"``).
        dt : float
            DR sample interval (s).
        augmented : bool
            Estimate the odometer scale and the heading bias online (8 states).
        rate_bias : bool, optional
            Estimate the gyro rate bias too (9 states; 10 with the gyro's scale factor error, when
            the grade's ``gyro_scale_sd`` is above 0); default the grade's ``rate_bias``.
        **overrides
            :class:`GPSDRModel` keyword arguments that win over the derived ones.

        Returns
        -------
        GPSDRModel

        Notes
        -----
        The mapping, each line from one specification number:

        * ``sigma_gps = gps_sigma_m`` (used for fixes that carry no accuracy of their own);
        * ``sigma_heading = heading_noise_deg`` (the white part of the heading);
        * ``q_bias = (gyro_arw_deg_rt_h * pi/180 / 60)^2`` (angle random walk, rad^2/s), plus,
          without a rate-bias state, ``(gyro_bias_deg_s * pi/180)^2 * 30 s``: a constant rate
          bias ``w`` gives a heading error ``w L`` after ``L`` s, and a random walk of that
          density gives the same spread at ``L = 30`` s (the outage length scored);
        * with a rate-bias state: ``sd_rate = gyro_bias_deg_s`` (prior), ``q_rate =
          (gyro_bias_instability_deg_h * pi/180 / 3600)^2 / 100 s`` (its drift);
        * with a rate-bias state and ``gyro_scale_sd > 0``: a gyro scale factor state,
          ``sd_gyro_scale = gyro_scale_sd`` (prior);
        * with calibration states and ``gps_latency_sd > 0``: the fixes' latency as the last state,
          ``sd_latency = gps_latency_sd`` (prior);
        * ``sigma_odometer = odometer_noise_m``, ``sd_scale = odometer_scale_sd``;
        * ``q = vehicle_jerk_sd^2 * 1 s`` (white jerk of the vehicle class, m^2/s^5).

        What no specification gives, the 8-state filter estimates online: the odometer
        scale and the heading bias (from GPS), and each fix's noise when the receiver
        reports its accuracy (``GPSDRFilter.update(gps_sigma=...)``).

        >>> m = GPSDRModel.from_grade("phone")
        >>> m.dim_x, m.sigma_gps
        (9, 5.0)
        >>> GPSDRModel.from_grade("survey").dim_x
        8
        """
        spec = _grade(grade)
        rate = bool(spec["rate_bias"]) if rate_bias is None else bool(rate_bias)
        kw = _grade_settings(spec, rate, augmented)
        kw.update(overrides)
        return cls(dt, augmented=augmented or rate, rate_bias=rate, **kw)

    def fx(self, x, dt=None, **fx_args):
        """``Phi x`` for ``(dim_x,)`` or ``(n_points, dim_x)``."""
        return dr_fx(x, self.dt if dt is None else dt, self.accel_term, self.rate_bias)

    def FJacobian(self, x=None, dt=None, **fx_args):
        """The (constant) transition matrix ``(dim_x, dim_x)``."""
        return self.F if dt is None else transition_matrix(dt, self.accel_term, self.dim_x, self.rate_bias)

    def hx(self, x, gps=True, velocity=False, **hx_args):
        """``[theta, s, e, n]`` (``gps=True``) or ``[theta, s]``, on the last axis.

        ``velocity=True``: the DR part is the velocity vector the sensors measure,
        ``zeta R(b) [v_e, v_n]`` (``R(b)`` rotates by the heading bias; the zero-velocity
        and low-speed forms of :meth:`measurement_for`).
        """
        if velocity:
            z = self._velocity_hx(x)
        else:
            z = dr_hx(x, self.dt, self.zeta, self.augmented)
        if not gps:
            return z
        return np.concatenate([z, gps_hx(x, self.latency_index)], axis=-1)

    def HJacobian(self, x, gps=True, velocity=False, **hx_args):
        """Analytic Jacobian ``(4, dim_x)`` (``gps=True``) or ``(2, dim_x)`` (``velocity`` as in :meth:`hx`)."""
        if velocity:
            H = self._velocity_H(x)
        else:
            H = dr_HJacobian(x, self.dt, self.zeta, self.augmented, self.min_speed)
        if not gps:
            return H
        return np.concatenate([H, gps_H(x, self.dim_x, self.latency_index)], axis=-2)

    def R_for(self, gps=True, stationary=False, zupt=False):
        """Measurement noise for the chosen measurement: ``(4, 4)`` or ``(2, 2)``.

        ``stationary=True`` multiplies the heading variance by ``stationary_inflation``:
        at (nearly) zero speed the heading says nothing about the velocity, and the
        linearisation at ``|v| ~ 0`` is meaningless. ``zupt=True``: the DR block is
        ``sigma_zupt^2 I`` for the zero-velocity pseudo-measurement.
        """
        R = self.R if gps else self.R[:2, :2]
        if zupt:
            R = R.copy()
            R[:2, :2] = self.sigma_zupt**2 * np.eye(2)
        elif stationary:
            R = R.copy()
            R[0, 0] *= self.stationary_inflation
        return R

    residual_z = staticmethod(dr_residual)
    z_mean_fn = staticmethod(dr_z_mean)

    @staticmethod
    def measurement(z_dr, z_gps=None):
        """Stack a DR measurement and an optional GPS fix: ``((4,) or (2,), has_gps)``."""
        z = as_state(z_dr, "z_dr", 2)
        if z_gps is None:
            return z, False
        return np.concatenate([z, as_state(z_gps, "z_gps", 2)]), True

    def _velocity_hx(self, x):
        """``zeta R(b) [v_e, v_n]``: the measured velocity vector ``s/T [sin theta, cos theta]``."""
        x = np.asarray(x, dtype=float)
        ve, vn = x[..., 1], x[..., 4]
        if not self.augmented:
            return self.zeta * np.stack([ve, vn], axis=-1)
        zeta, c, s = x[..., 6], np.cos(x[..., 7]), np.sin(x[..., 7])
        return zeta[..., None] * np.stack([ve * c + vn * s, vn * c - ve * s], axis=-1)

    def _velocity_H(self, x):
        x = np.asarray(x, dtype=float)
        H = np.zeros(x.shape[:-1] + (2, self.dim_x))
        if not self.augmented:
            H[..., 0, 1] = H[..., 1, 4] = self.zeta
            return H
        ve, vn, zeta = x[..., 1], x[..., 4], x[..., 6]
        c, s = np.cos(x[..., 7]), np.sin(x[..., 7])
        H[..., 0, 1], H[..., 0, 4] = zeta * c, zeta * s
        H[..., 1, 1], H[..., 1, 4] = -zeta * s, zeta * c
        H[..., 0, 6], H[..., 1, 6] = ve * c + vn * s, vn * c - ve * s
        H[..., 0, 7], H[..., 1, 7] = zeta * (vn * c - ve * s), -zeta * (ve * c + vn * s)
        return H

    def velocity_measurement(self, z_dr, noise_scale=None):
        """Polar to Cartesian: ``(w, R_w)`` from ``[theta, s]``, independent of the state.

        ``w = s / T [sin theta, cos theta]`` (the measured velocity vector; the model
        is ``w = zeta R(b) v``, see :meth:`hx` with ``velocity=True``) and its
        first-order covariance ``J diag(sigma_s^2 / T^2, sigma_heading^2) J^T``. Linear
        in the velocity, so it has no singularity at zero speed. ``noise_scale``: factors
        ``(heading, odometer)`` on the two variances (default none).
        """
        z_dr = np.asarray(z_dr, dtype=float)
        th = z_dr[0]
        w = z_dr[1] / self.dt
        J = np.array([[np.sin(th), w * np.cos(th)], [np.cos(th), -w * np.sin(th)]])
        var_h, var_s = self.sigma_heading**2, (self.sigma_odometer / self.dt) ** 2
        if noise_scale is not None:
            var_h, var_s = var_h * noise_scale[0], var_s * noise_scale[1]
        Rw = J @ np.diag([var_s, var_h]) @ J.T
        return w * np.array([np.sin(th), np.cos(th)]), Rw + 1e-12 * np.eye(2)

    def measurement_for(self, z_dr, z_gps=None, *, stationary=False, zupt=False, low_speed=False,
                        gps_sigma=None, R=None, velocity=False, dr_noise_scale=None):
        """The measurement a filter update uses, for a DR sample and an optional GPS fix.

        Parameters
        ----------
        z_dr : array-like of shape (2,)
            ``[heading (rad), odometer distance (m)]``, finite.
        z_gps : array-like of shape (2,) or None
            ``[e, n]`` fix (m), or ``None`` when there is none (a tunnel).
        stationary : bool
            (Nearly) zero speed: heading variance inflated (see :meth:`R_for`).
        zupt : bool
            The vehicle stands still: the DR measurement is replaced by the zero-velocity
            update ``[v_e, v_n] = 0`` (a range-only odometer cannot hold the velocity at
            zero: its Jacobian vanishes there).
        low_speed : bool
            Moving slowly (e.g. pulling away): the DR measurement enters as the measured
            velocity vector of :meth:`velocity_measurement`, modelled as
            ``zeta R(b) [v_e, v_n]`` (smooth, no singularity at zero speed), because the
            odometer's Jacobian vanishes at zero estimated speed.
        velocity : bool
            The DR measurement enters as the measured velocity vector, as with ``low_speed``, without its
            extra noise ``sigma_low_speed``: the same information as ``[theta, s]`` to first order, and
            linear in the velocity (what a filter uses where the measured heading is far from its own, see
            :class:`~filterwnn.navigation.gpsdr.GPSDRFilter`'s ``heading_linear_limit``).
        gps_sigma : float, optional
            This fix's standard deviation per axis (m), e.g. the receiver's reported
            horizontal accuracy; replaces ``sigma_gps`` in ``R`` for this fix.
        R : ndarray, optional
            Override of the whole measurement noise (shape to match).
        dr_noise_scale : array-like of shape (2,), optional
            Factors ``(heading, odometer)`` on the DR measurement's noise variances ``sigma_heading^2`` and
            ``sigma_odometer^2``, in whichever form it enters (not the zero-velocity update's): the DR noise
            estimated online (:class:`~filterwnn.navigation.gpsdr.GPSDRFilter`'s ``dr_noise_window``). Default
            none: the model's.

        Returns
        -------
        z : ndarray of shape (4,) or (2,)
        R : ndarray of shape (4, 4) or (2, 2)
        hx_args : dict
            ``{"gps": bool, "velocity": bool}``, the keyword arguments of :meth:`hx` and
            :meth:`HJacobian` for this measurement.
        """
        z, gps = self.measurement(z_dr, z_gps)
        as_velocity = bool(low_speed or velocity) and not zupt
        if zupt:
            z = z.copy()
            z[:2] = 0.0
        elif as_velocity:
            z = z.copy()
            z[:2], Rv = self.velocity_measurement(z[:2], dr_noise_scale)
        if R is None:
            R = self.R_for(gps, stationary, zupt)
            if dr_noise_scale is not None and not (zupt or as_velocity):
                R = R.copy()
                R[0, 0] *= dr_noise_scale[0]
                R[1, 1] *= dr_noise_scale[1]
            if as_velocity:
                R = R.copy()
                R[:2, :2] = Rv + (self.sigma_low_speed**2 * np.eye(2) if low_speed else 0.0)
            if gps and gps_sigma is not None:
                R = R.copy()
                R[2:, 2:] = check_positive(gps_sigma, "gps_sigma") ** 2 * np.eye(2)
        return z, R, {"gps": gps, "velocity": bool(zupt or as_velocity)}

    def ekf(self, x0=None, P0=None):
        """A filterpy ``ExtendedKalmanFilter`` on this model (or use :class:`filterwnn.navigation.gpsdr.GPSDRFilter`)."""
        from filterpy.kalman import ExtendedKalmanFilter

        return from_model(ExtendedKalmanFilter, self, x0=x0, P0=P0)
