"""The table of bad inputs (issue 8, part 1): every public entry point, each bad input
under a test.

Each row is ``(call, exception, pattern)``: calling ``call()`` must raise ``exception``
(``ValueError`` or ``TypeError``; :class:`filterwnn.NumericalError` is a ``ValueError``)
with a message matching ``pattern``, which names the argument, the rule and the value.
Filters are also checked to be left as they were by a failed call.

Rows that the library does not yet satisfy are marked ``GAP(...)`` (a strict xfail):
each states what happens now and what should happen, so that fixing the library turns
the row into an XPASS failure and the marker must be removed.
"""

import importlib
import pickle

import numpy as np
import pytest

from filterwnn import (
    LinearGaussianModel,
    MinimalSkewSigmaPoints,
    NumericalError,
    SphericalSimplexSigmaPoints,
    UnscentedKalmanFilter,
    datasets,
    metrics,
    wnn,
)
from filterwnn import _validation as val
from filterwnn.kalman.sigma_points import sigma_deviations, unit_sigma_points
from filterwnn.navigation import dead_reckoning as dr
from filterwnn.navigation import scenarios
from filterwnn.navigation.gpsdr import GPSDRFilter
from filterwnn.navigation import neural_filter as nfm
from filterwnn.monte_carlo import particle_filter as pfm
from filterwnn.monte_carlo import resampling
from filterwnn.wnn.regressor import WNNRegressor
from filterwnn.studies import dr as dr_study
from filterwnn.studies import wnn as wnn_study
from filterwnn.wnn.weight_model import WNNWeightModel

RNG_MSG = r"(rng|random_state) must be None, an int seed, a SeedSequence, a BitGenerator or a numpy\.random\.Generator, got "
BAD_RNGS = [
    pytest.param("seed", "str", id="str"),
    pytest.param(1.5, "float", id="float"),
    pytest.param([1, 2], "list", id="list"),
    pytest.param(np.random.RandomState(0), "RandomState", id="RandomState"),
]


def GAP(reason):
    """Mark a row the library does not yet satisfy (strict: a fix makes it XPASS-fail)."""
    return pytest.mark.xfail(strict=True, reason=reason)


def row(call, exc, match, id, gap=None):
    return pytest.param(call, exc, match, id=id, marks=() if gap is None else GAP(gap))


def _optional(name):
    """A module still being written by another helper: skip its rows until it lands."""
    try:
        return importlib.import_module(name)
    except ImportError:
        return None


# --------------------------------------------------------------------------- fixtures
I2, I3 = np.eye(2), np.eye(3)
MODEL = LinearGaussianModel.random(dim_x=3, dim_z=2, rng=0)
NONSYM3 = np.array([[1.0, 0.5, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
NONSYM2 = np.array([[1.0, 0.5], [0.0, 1.0]])


def fx_lin(x, dt):
    """Module-level (picklable) linear transition of MODEL, rows or one state."""
    return np.asarray(x) @ MODEL.F.T


def hx_lin(x):
    return np.asarray(x) @ MODEL.H.T


def make_ukf(vectorized=True, points=None):
    points = SphericalSimplexSigmaPoints(3) if points is None else points
    ukf = UnscentedKalmanFilter(3, 2, 1.0, hx_lin, fx_lin, points, vectorized=vectorized)
    ukf.Q, ukf.R = MODEL.Q.copy(), MODEL.R.copy()
    return ukf


def predicted_ukf(vectorized=True):
    ukf = make_ukf(vectorized)
    ukf.predict()
    ukf.update(np.array([0.3, -0.2]))
    ukf.predict()
    return ukf


def _with(vectorized, **attrs):
    ukf = predicted_ukf(vectorized)
    for k, v in attrs.items():
        setattr(ukf, k, v)
    return ukf


# --------------------------------------------------------------------------- _validation
VALIDATION_ROWS = [
    row(lambda: val.as_state([[1.0, 2.0], [3.0, 4.0]], "x"), ValueError, r"x must be 1-D, got shape \(2, 2\)", "as_state-2d"),
    row(lambda: val.as_state([1.0, 2.0], "x", dim=3), ValueError, r"x must have length 3, got shape \(2,\)", "as_state-len"),
    row(lambda: val.as_state([1.0, np.nan], "x"), ValueError, r"x must be finite, got \[ 1. nan\]", "as_state-nan"),
    row(lambda: val.as_state([1.0, np.inf], "x"), ValueError, r"x must be finite, got \[ 1. inf\]", "as_state-inf"),
    row(lambda: val.as_state(object(), "x"), TypeError, r"x must be array-like of numbers, got object", "as_state-type"),
    row(lambda: val.as_measurement([1.0, 2.0, 3.0], 2), ValueError, r"z must have 2 entries, got shape \(3,\)", "as_measurement-len"),
    row(lambda: val.as_measurement([1.0, np.nan], 2), ValueError, r"z must be finite \(use z=None for a missing measurement\)", "as_measurement-nan"),
    row(lambda: val.as_measurement("ab", 2), TypeError, r"z must be array-like of numbers or None, got str", "as_measurement-type"),
    row(lambda: val.check_covariance(np.eye(3), "P", dim=2), ValueError, r"P must have shape \(2, 2\), got shape \(3, 3\)", "cov-dim"),
    row(lambda: val.check_covariance(np.ones((2, 3)), "P"), ValueError, r"P must be a square matrix, got shape \(2, 3\)", "cov-nonsquare"),
    row(lambda: val.check_covariance(1.0, "P"), ValueError, r"P must be a square matrix, got scalar 1.0", "cov-scalar-no-dim"),
    row(lambda: val.check_covariance(np.full((2, 2), np.nan), "P"), ValueError, "P must be finite, got non-finite entries", "cov-nan"),
    row(lambda: val.check_covariance(np.diag([1.0, np.inf]), "P"), ValueError, "P must be finite, got non-finite entries", "cov-inf"),
    row(lambda: val.check_covariance(NONSYM2, "P"), ValueError, r"P must be symmetric; max \|P - P.T\| = 0.5", "cov-nonsym"),
    row(lambda: val.check_covariance(np.diag([1.0, -2.0]), "P"), ValueError, r"P must be positive definite \(Cholesky failed\); smallest eigenvalue -2", "cov-not-pd"),
    row(lambda: val.check_covariance(np.diag([1.0, 0.0]), "P"), ValueError, r"P must be positive definite \(Cholesky failed\); smallest eigenvalue 0", "cov-singular"),
    row(lambda: val.check_covariance(np.diag([1.0, -2.0]), "Q", require_pd=False), ValueError, r"Q must be positive semi-definite; smallest eigenvalue -2", "cov-not-psd"),
    row(lambda: val.check_covariance([["a", "b"], ["c", "d"]], "P"), TypeError, r"P must be a matrix of numbers, got list", "cov-type"),
    row(lambda: val.check_rng(-1), ValueError, r"rng seed must be >= 0, got -1", "rng-negative-seed"),
    row(lambda: val.check_positive_int(0, "n_particles"), ValueError, r"n_particles must be >= 1, got 0", "posint-zero"),
    row(lambda: val.check_positive_int(-3, "n_hidden"), ValueError, r"n_hidden must be >= 1, got -3", "posint-neg"),
    row(lambda: val.check_positive_int(2.0, "epochs"), TypeError, r"epochs must be an integer, got float 2.0", "posint-float"),
    row(lambda: val.check_positive_int(True, "epochs"), TypeError, r"epochs must be an integer, got bool True", "posint-bool"),
    row(lambda: val.check_positive(0.0, "dt"), ValueError, r"dt must be finite and > 0, got 0.0", "pos-zero"),
    row(lambda: val.check_positive(-1, "dt"), ValueError, r"dt must be finite and > 0, got -1.0", "pos-neg"),
    row(lambda: val.check_positive(np.nan, "dt"), ValueError, r"dt must be finite and > 0, got nan", "pos-nan"),
    row(lambda: val.check_positive(np.inf, "dt"), ValueError, r"dt must be finite and > 0, got inf", "pos-inf"),
    row(lambda: val.check_positive(-1.0, "q", strict=False), ValueError, r"q must be finite and >= 0, got -1.0", "nonneg-neg"),
    row(lambda: val.check_positive("1", "dt"), TypeError, r"dt must be a real number, got str '1'", "pos-type"),
    row(lambda: val.check_choice("foo", "resampling", {"systematic", "stratified"}), ValueError, r"unknown resampling 'foo'; valid: 'stratified', 'systematic'", "choice"),
]

# --------------------------------------------------------------------------- models
LGM = LinearGaussianModel
MODEL_ROWS = [
    row(lambda: LGM(np.ones((2, 3)), np.ones((1, 2)), I2, 1.0), ValueError, r"F must be square, got shape \(2, 3\)", "lgm-F-shape"),
    row(lambda: LGM(np.full((2, 2), np.nan), np.ones((1, 2)), I2, 1.0), ValueError, "F must be finite", "lgm-F-nan"),
    row(lambda: LGM(I2, np.ones((1, 3)), I2, 1.0), ValueError, r"H must have shape \(dim_z, 2\), got \(1, 3\)", "lgm-H-shape"),
    row(lambda: LGM(I2, np.full((1, 2), np.inf), I2, 1.0), ValueError, "H must be finite", "lgm-H-inf"),
    row(lambda: LGM(I2, np.ones((1, 2)), I3, 1.0), ValueError, r"Q must have shape \(2, 2\), got shape \(3, 3\)", "lgm-Q-shape"),
    row(lambda: LGM(I2, np.ones((1, 2)), np.full((2, 2), np.nan), 1.0), ValueError, "Q must be finite", "lgm-Q-nan"),
    row(lambda: LGM(I2, np.ones((1, 2)), NONSYM2, 1.0), ValueError, r"Q must be symmetric; max \|Q - Q.T\| = 0.5", "lgm-Q-nonsym"),
    row(lambda: LGM(I2, np.ones((1, 2)), -I2, 1.0), ValueError, "Q must be positive semi-definite; smallest eigenvalue -1", "lgm-Q-not-psd"),
    row(lambda: LGM(I2, np.ones((1, 2)), I2, I2), ValueError, r"R must have shape \(1, 1\), got shape \(2, 2\)", "lgm-R-shape"),
    row(lambda: LGM(I2, np.ones((1, 2)), I2, -1.0), ValueError, "R must be positive definite .*smallest eigenvalue -1", "lgm-R-not-pd"),
    row(lambda: LGM(I2, np.ones((1, 2)), I2, 1.0, x0=np.zeros(3)), ValueError, r"x0 must have length 2, got shape \(3,\)", "lgm-x0-shape"),
    row(lambda: LGM(I2, np.ones((1, 2)), I2, 1.0, x0=[np.nan, 0.0]), ValueError, "x0 must be finite", "lgm-x0-nan"),
    row(lambda: LGM(I2, np.ones((1, 2)), I2, 1.0, P0=-I2), ValueError, "P0 must be positive definite", "lgm-P0-not-pd"),
    row(lambda: LGM(I2, np.ones((1, 2)), I2, 1.0, P0=NONSYM2), ValueError, "P0 must be symmetric", "lgm-P0-nonsym"),
    row(lambda: LGM(I2, np.ones((1, 2)), I2, 1.0, dt=0.0), ValueError, r"dt must be finite and > 0, got 0.0", "lgm-dt-zero"),
    row(lambda: LGM(I2, np.ones((1, 2)), I2, 1.0, dt=-0.1), ValueError, r"dt must be finite and > 0, got -0.1", "lgm-dt-neg"),
    row(lambda: MODEL.simulate(0, rng=0), ValueError, r"n_steps must be >= 1, got 0", "simulate-n-zero"),
    row(lambda: MODEL.simulate(-5, rng=0), ValueError, r"n_steps must be >= 1, got -5", "simulate-n-neg"),
    row(lambda: MODEL.simulate(2.5, rng=0), TypeError, r"n_steps must be an integer, got float 2.5", "simulate-n-float"),
    row(lambda: MODEL.simulate(3, rng=0, x0=np.zeros(4)), ValueError, r"x0 must have length 3, got shape \(4,\)", "simulate-x0-shape"),
    row(lambda: MODEL.simulate(3, rng=0, x0=[0.0, np.nan, 0.0]), ValueError, "x0 must be finite", "simulate-x0-nan"),
    row(lambda: LGM.random(0, 2, rng=0), ValueError, r"dim_x must be >= 1, got 0", "random-dim_x"),
    row(lambda: LGM.random(2, 0, rng=0), ValueError, r"dim_z must be >= 1, got 0", "random-dim_z"),
    row(lambda: LGM.random(2, 1, rng=0, q=-1.0), ValueError, r"q must be finite and > 0, got -1.0", "random-q"),
    row(lambda: LGM.random(2, 1, rng=0, r=0.0), ValueError, r"r must be finite and > 0, got 0.0", "random-r"),
]

# --------------------------------------------------------------------------- metrics
METRIC_ROWS = [
    row(lambda: metrics.nees(np.zeros(3), np.ones(3), I2), ValueError, r"P must have shape \(\.\.\., 3, 3\) to match .* got \(2, 2\)", "nees-shape"),
    row(lambda: metrics.nees(np.zeros(2), np.ones(3), I2), ValueError, r"x_true and x_hat must have the same shape, got \(2,\) and \(3,\)", "nees-x-shapes"),
    row(lambda: metrics.nees(np.zeros(2), [np.nan, 0.0], I2), ValueError, "x_hat must be finite", "nees-nan"),
    row(lambda: metrics.nees([np.inf, 0.0], np.zeros(2), I2), ValueError, "x_true must be finite", "nees-inf"),
    row(lambda: metrics.nees(np.zeros(2), np.ones(2), -I2), ValueError, "P must be positive definite .*smallest eigenvalue -1", "nees-not-pd"),
    row(lambda: metrics.nees(np.zeros(2), np.ones(2), NONSYM2), ValueError, r"P must be symmetric; max \|P - P.T\| = 0.5", "nees-nonsym"),
    row(lambda: metrics.nees(np.zeros(2), np.ones(2), np.full((2, 2), np.nan)), ValueError, "P must be finite", "nees-P-nan"),
    row(lambda: metrics.nis(np.ones(2), -I2), ValueError, "S must be positive definite", "nis-not-pd"),
    row(lambda: metrics.nis(np.ones(2), I3), ValueError, r"S must have shape \(\.\.\., 2, 2\)", "nis-shape"),
    row(lambda: metrics.nis([np.nan, 1.0], I2), ValueError, "y must be finite", "nis-nan"),
    row(lambda: metrics.chi2_bounds(0, 10), ValueError, r"dof must be >= 1, got 0", "chi2-dof"),
    row(lambda: metrics.chi2_bounds(2, 0), ValueError, r"n_runs must be >= 1, got 0", "chi2-runs"),
    row(lambda: metrics.chi2_bounds(2, 10, alpha=1.5), ValueError, r"alpha must satisfy 0 < alpha < 1, got 1.5", "chi2-alpha-big"),
    row(lambda: metrics.chi2_bounds(2, 10, alpha=0.0), ValueError, r"alpha must be finite and > 0, got 0.0", "chi2-alpha-zero"),
    row(lambda: metrics.effective_sample_size([]), ValueError, r"weights must be a non-empty 1-D array, got shape \(0,\)", "ess-empty"),
    row(lambda: metrics.effective_sample_size([np.nan, 1.0]), ValueError, "weights must be finite, got non-finite entries", "ess-nan"),
    row(lambda: metrics.effective_sample_size([-1.0, 2.0]), ValueError, "weights must be non-negative, got min -1", "ess-neg"),
    row(lambda: metrics.effective_sample_size([0.0, 0.0]), ValueError, "weights must have a positive sum, got 0", "ess-zero"),
    row(lambda: metrics.mse([1.0, 2.0], [1.0, 2.0, 3.0]), ValueError, r"y_true and y_pred must have the same .*shapes, got \(2,\) and \(3,\)", "mse-len"),
    row(lambda: metrics.rmse(np.zeros((4, 2)), np.zeros((3, 2))), ValueError, r"y_true and y_pred .* got \(4, 2\) and \(3, 2\)", "rmse-len"),
]

# --------------------------------------------------------------------------- sigma points
# (test_sigma_points.py already covers n, alpha, beta, w0 and sigma_points(x, P); the
# rows here are the entry points it does not.)
SIGMA_ROWS = [
    row(lambda: SphericalSimplexSigmaPoints(3, alpha=np.inf), ValueError, "alpha must be a finite real number, got inf", "simplex-alpha-inf"),
    row(lambda: MinimalSkewSigmaPoints(-2), ValueError, r"n must be >= 1, got -2", "minskew-n-neg"),
    row(lambda: SphericalSimplexSigmaPoints(3).sigma_points(np.zeros(3), NONSYM3), ValueError, "P must be symmetric", "simplex-P-nonsym"),
    row(lambda: unit_sigma_points(object()), TypeError, "points must follow filterpy's sigma-point protocol", "unit-points-type"),
    row(lambda: sigma_deviations(SphericalSimplexSigmaPoints(3), I2), ValueError, r"U must have shape \(\.\.\., 3, 3\)", "deviations-U-shape"),
]

# --------------------------------------------------------------------------- unscented filter
UKF_ROWS = [
    row(lambda: UnscentedKalmanFilter(3, 2, 1.0, None, fx_lin, SphericalSimplexSigmaPoints(3)), TypeError, "hx must be callable, got NoneType", "ukf-hx-type"),
    row(lambda: UnscentedKalmanFilter(3, 2, 1.0, hx_lin, 3, SphericalSimplexSigmaPoints(3)), TypeError, r"fx must be callable or None \(random walk\), got int", "ukf-fx-type"),
    row(lambda: UnscentedKalmanFilter(3, 2, 1.0, hx_lin, fx_lin, "simplex"), TypeError, "points must follow filterpy's sigma-point protocol .*got str", "ukf-points-type"),
    row(lambda: UnscentedKalmanFilter(3, 2, np.nan, hx_lin, fx_lin, SphericalSimplexSigmaPoints(3)), ValueError, "dt must be finite and > 0, got nan", "ukf-dt-nan"),
    row(lambda: UnscentedKalmanFilter(3.0, 2, 1.0, hx_lin, fx_lin, SphericalSimplexSigmaPoints(3)), TypeError, "dim_x must be an integer, got float 3.0", "ukf-dim_x-float"),
    row(lambda: UnscentedKalmanFilter(-1, 2, 1.0, hx_lin, fx_lin, SphericalSimplexSigmaPoints(3)), ValueError, "dim_x must be >= 1, got -1", "ukf-dim_x-neg"),
]
for _vec in (False, True):
    _v = "vec" if _vec else "loop"
    UKF_ROWS += [
        row(lambda v=_vec: _with(v, x=np.zeros(4)).predict(), ValueError, r"x must have shape \(3,\), got \(4,\)", f"ukf-{_v}-x-shape"),
        row(lambda v=_vec: _with(v, x=np.zeros((3, 1))).update(np.zeros(2)), ValueError, r"x must have shape \(3,\), got \(3, 1\)", f"ukf-{_v}-x-column"),
        row(lambda v=_vec: _with(v, P=I2).predict(), ValueError, r"P must have shape \(3, 3\), got \(2, 2\)", f"ukf-{_v}-P-shape"),
        row(lambda v=_vec: _with(v, Q=I2).predict(), ValueError, r"Q must have shape \(3, 3\), got \(2, 2\)", f"ukf-{_v}-Q-shape"),
        row(lambda v=_vec: _with(v, x=np.array([0.0, np.nan, 0.0])).predict(), NumericalError, "x and P must be finite before step 3", f"ukf-{_v}-x-nan"),
        row(lambda v=_vec: _with(v, P=np.full((3, 3), np.inf)).update(np.zeros(2)), NumericalError, r"x and P must be finite at step 2 \(update\)", f"ukf-{_v}-P-inf"),
        row(lambda v=_vec: _with(v, P=-I3).predict(), NumericalError, r"P is not positive definite at step 3; smallest eigenvalue -1; set P to a symmetric positive definite matrix, e.g. P = np.diag\(variances\)", f"ukf-{_v}-P-not-pd"),
        row(lambda v=_vec: predicted_ukf(v).update(np.array([0.0, np.nan])), ValueError, r"z must be finite \(use z=None for a missing measurement\), got \[ 0. nan\]", f"ukf-{_v}-z-nan"),
        row(lambda v=_vec: predicted_ukf(v).update(np.array([np.inf, 0.0])), ValueError, "z must be finite", f"ukf-{_v}-z-inf"),
        row(lambda v=_vec: predicted_ukf(v).update("ab"), TypeError, "z must be array-like of numbers or None, got str", f"ukf-{_v}-z-type"),
        row(lambda v=_vec: predicted_ukf(v).update(np.zeros(2), R=np.full((2, 2), np.nan)), ValueError, "R must be finite", f"ukf-{_v}-R-nan"),
        row(lambda v=_vec: predicted_ukf(v).batch_filter(np.zeros((4, 3))), TypeError, "each element in zs must be a 1D array of length 2", f"ukf-{_v}-zs-shape"),
        row(lambda v=_vec: predicted_ukf(v).update(np.zeros(3)), ValueError, r"z must have 2 entries, got shape \(3,\)", f"ukf-{_v}-z-len3"),
        row(lambda v=_vec: predicted_ukf(v).update(np.zeros(2), R=I3), ValueError, r"R must have shape \(2, 2\), got shape \(3, 3\)", f"ukf-{_v}-R-shape"),
        row(lambda v=_vec: predicted_ukf(v).update(np.zeros(2), R=NONSYM2), ValueError, "R must be symmetric", f"ukf-{_v}-R-nonsym"),
        row(lambda v=_vec: _with(v, Q=NONSYM3).predict(), ValueError, "Q must be symmetric", f"ukf-{_v}-Q-nonsym"),
        row(lambda v=_vec: _with(v, P=NONSYM3).predict(), ValueError, "P must be symmetric", f"ukf-{_v}-P-nonsym"),
        row(lambda v=_vec: predicted_ukf(v).predict(dt=0.0), ValueError, r"dt must be finite and > 0, got 0.0", f"ukf-{_v}-predict-dt-zero"),
        row(lambda v=_vec: predicted_ukf(v).predict(dt=-1.0), ValueError, r"dt must be finite and > 0, got -1.0", f"ukf-{_v}-predict-dt-neg"),
        # issue 15: the fix is in the message; Q is checked at predict in both modes
        row(lambda v=_vec: _with(v, Q=0.1).predict(), ValueError, r"Q must have shape \(3, 3\), got \(\); .*use Q = q \* np.eye\(3\)", f"ukf-{_v}-Q-scalar"),
        row(lambda v=_vec: _with(v, P=0.1).update(np.zeros(2)), ValueError, r"P must have shape \(3, 3\), got \(\); .*use P = p \* np.eye\(3\)", f"ukf-{_v}-P-scalar"),
        row(lambda v=_vec: _with(v, Q=-I3).predict(), ValueError, r"Q must be positive semi-definite; smallest eigenvalue -1; Q must be a covariance", f"ukf-{_v}-Q-negative"),
        row(lambda v=_vec: _with(v, Q=NONSYM3).predict(), ValueError, r"symmetrise it: Q = 0.5 \* \(Q \+ Q.T\)", f"ukf-{_v}-Q-nonsym-fix"),
        row(lambda v=_vec: predicted_ukf(v).update(np.zeros(2), R=np.zeros(3)), ValueError, r"R must have shape \(2, 2\), got shape \(3,\); use R = np.diag\(variances\)", f"ukf-{_v}-R-vector"),
    ]
UKF_ROWS += [
    row(lambda: predicted_ukf(False).update(np.zeros(1)), ValueError, r"z must have 2 entries, got shape \(1,\)", "ukf-loop-z-len1"),
    row(lambda: predicted_ukf(True).update(np.zeros(1)), ValueError, r"z must have 2 entries, got shape \(1,\)", "ukf-vec-z-len1"),
    row(lambda: predicted_ukf(True).update(np.zeros(2), R=-100.0), ValueError, r"R must be positive definite .*smallest eigenvalue -100 at step 2", "ukf-vec-R-negative"),
    row(lambda: predicted_ukf(False).update(np.zeros(2), R=-100.0), ValueError, "(R must be positive definite|S is not positive definite)", "ukf-loop-R-negative"),
    row(lambda: _with(True, Q=np.full((3, 3), np.nan)).predict(), ValueError, "Q must be finite", "ukf-vec-Q-nan"),
    row(lambda: _with(False, Q=np.full((3, 3), np.nan)).predict(), ValueError, "must be finite", "ukf-loop-Q-nan"),
    row(lambda: UnscentedKalmanFilter(3, 2, 1.0, hx_lin, None, SphericalSimplexSigmaPoints(3)).predict(dt=0.0), ValueError, "dt must be finite and > 0", "ukf-randomwalk-dt-zero"),
]

# --------------------------------------------------------------------------- wnn, weight model, datasets
X3 = np.linspace(-1.0, 1.0, 6).reshape(3, 2)
THETA = np.linspace(0.1, 1.0, wnn.n_params(2, 2))
WNN_ROWS = [
    row(lambda: wnn.forward(np.zeros(7), np.zeros((3, 1))), ValueError, r"theta's last axis must be a multiple of n_inputs \+ 3 = 4, got shape \(7,\)", "forward-theta-len"),
    row(lambda: wnn.forward(THETA, X3, wavelet="haar"), ValueError, r"unknown wavelet 'haar'; valid: 'mexican_hat', 'morlet'", "forward-wavelet"),
    row(lambda: wnn.jacobian(THETA, X3, wavelet="haar"), ValueError, r"unknown wavelet 'haar'", "jacobian-wavelet"),
    row(lambda: wnn.jacobian(np.zeros(7), np.zeros((3, 1))), ValueError, r"theta's last axis must be a multiple of n_inputs \+ 3 = 4", "jacobian-theta-len"),
    row(lambda: wnn.unpack(np.zeros(7), 1), ValueError, "7", "unpack-len"),
    row(lambda: wnn.n_params(2, 0), ValueError, r"n_hidden must be >= 1, got 0", "n_params-hidden-zero"),
    row(lambda: wnn.n_params(0, 2), ValueError, r"n_inputs must be >= 1, got 0", "n_params-inputs-zero"),
    row(lambda: wnn.n_params(2, -4), ValueError, r"n_hidden must be >= 1, got -4", "n_params-hidden-neg"),
    row(lambda: wnn.init_paper(2, 0, rng=0), ValueError, r"n_hidden must be >= 1, got 0", "init_paper-hidden"),
    row(lambda: wnn.init_scaled(X3, 0, rng=0), ValueError, r"n_hidden must be >= 1, got 0", "init_scaled-hidden"),
    row(lambda: wnn.forward(THETA, np.array([[np.nan, 0.0], [0.0, 0.0]])), ValueError, "X must be finite", "forward-X-nan"),
    row(lambda: wnn.init_scaled(np.array([[np.nan, 0.0], [1.0, 0.0]]), 2, rng=0), ValueError, "X must be finite", "init_scaled-X-nan"),
    row(lambda: WNNWeightModel(2, 0), ValueError, r"n_hidden must be >= 1, got 0", "wm-hidden"),
    row(lambda: WNNWeightModel(0, 2), ValueError, r"n_inputs must be >= 1, got 0", "wm-inputs"),
    row(lambda: WNNWeightModel(2, 2, wavelet="haar"), ValueError, r"unknown wavelet 'haar'", "wm-wavelet"),
    row(lambda: WNNWeightModel(2, 2, R=-1.0), ValueError, "R must be positive definite .*-1", "wm-R-neg"),
    row(lambda: WNNWeightModel(2, 2, R=np.nan), ValueError, "R must be finite", "wm-R-nan"),
    row(lambda: WNNWeightModel(2, 2, Q=-1.0), ValueError, "Q must be positive semi-definite; smallest eigenvalue -1", "wm-Q-neg"),
    row(lambda: WNNWeightModel(2, 2, P0=-1.0), ValueError, "P0 must be positive semi-definite", "wm-P0-neg"),
    row(lambda: WNNWeightModel(2, 2).simulate(0, rng=0), ValueError, r"n_steps must be >= 1, got 0", "wm-simulate-n"),
    row(lambda: WNNWeightModel(2, 2, x0=np.zeros(3)), ValueError, r"x0 must have length 10, got shape \(3,\)", "wm-x0-shape"),
    row(lambda: WNNWeightModel(2, 2, dt=0.0), ValueError, r"dt must be finite and > 0, got 0.0", "wm-dt-zero"),
    row(lambda: WNNWeightModel(2, 2).simulate(3, rng=0, X=np.zeros((4, 2))), ValueError, r"X must have shape \(3, 2\), got \(4, 2\)", "wm-simulate-X-shape"),
]

# --------------------------------------------------------------------------- particle filters, resampling
def make_pf(**kw):
    args = dict(dim_x=3, dim_z=2, dt=1.0, hx=hx_lin, fx=fx_lin, n_particles=10, vectorized=True, rng=0)
    args.update(kw)
    return pfm.ParticleFilter(**args)


def pf_run_with(**attrs):
    pf = make_pf(proposal=attrs.pop("proposal", "prior"))
    pf.Q, pf.R = MODEL.Q.copy(), MODEL.R.copy()
    for k, v in attrs.items():
        setattr(pf, k, v)
    pf.predict()
    pf.update(np.zeros(2))


PF_ROWS = [
    row(lambda: make_pf(n_particles=0), ValueError, r"n_particles must be >= 1, got 0", "pf-n-zero"),
    row(lambda: make_pf(n_particles=-5), ValueError, r"n_particles must be >= 1, got -5", "pf-n-neg"),
    row(lambda: make_pf(n_particles=2.5), TypeError, r"n_particles must be an integer, got float 2.5", "pf-n-float"),
    row(lambda: make_pf(dt=0.0), ValueError, r"dt must be finite and > 0, got 0.0", "pf-dt-zero"),
    row(lambda: make_pf(dt=-1.0), ValueError, r"dt must be finite and > 0, got -1.0", "pf-dt-neg"),
    row(lambda: make_pf(proposal="optimal"), ValueError, r"unknown proposal 'optimal'; valid: 'extended', 'prior', 'unscented'", "pf-proposal"),
    row(lambda: make_pf(proposal=3), TypeError, "proposal must be a name or a proposal object .*got int", "pf-proposal-type"),
    row(lambda: make_pf(resampling="foo"), ValueError, r"unknown resampling scheme 'foo'; valid: 'multinomial', 'residual', 'stratified', 'systematic'", "pf-resampling"),
    row(lambda: make_pf(weighting="bank"), TypeError, "unexpected keyword argument 'weighting'", "pf-bank-gone"),
    row(lambda: make_pf(proposal="unscented", points=SphericalSimplexSigmaPoints(2)), ValueError, r"points.n must equal dim_x=3, got 2", "pf-points-size"),
    row(lambda: make_pf(move=3), TypeError, "move must be callable or None, got int", "pf-move"),
    row(lambda: make_pf(ess_threshold=2), ValueError, r"ess_threshold must be a number in \[0, 1\], got 2", "pf-ess"),
    row(lambda: make_pf(tempering=0.0), ValueError, r"tempering must be finite and > 0, got 0.0", "pf-tempering"),
    row(lambda: make_pf(hx=None), TypeError, "hx must be callable, got NoneType", "pf-hx"),
    row(lambda: make_pf(proposal="extended"), ValueError, "the extended Kalman proposal needs HJacobian, got None", "pf-epf-jacobian"),
    row(lambda: pf_run_with(x=np.zeros(4)), ValueError, r"x must have length 3, got shape \(4,\)", "pf-x-shape"),
    row(lambda: pf_run_with(x=np.array([np.nan, 0.0, 0.0])), ValueError, "x must be finite", "pf-x-nan"),
    row(lambda: pf_run_with(P=-I3), ValueError, "P must be positive definite .*smallest eigenvalue -1", "pf-P-not-pd"),
    row(lambda: pf_run_with(P=NONSYM3), ValueError, r"P must be symmetric; max \|P - P.T\| = 0.5", "pf-P-nonsym"),
    row(lambda: pf_run_with(Q=I2), ValueError, r"Q must have shape \(3, 3\), got shape \(2, 2\)", "pf-Q-shape"),
    row(lambda: pf_run_with(Q=np.full((3, 3), np.nan)), ValueError, "Q must be finite", "pf-Q-nan"),
    row(lambda: pf_run_with(Q=-I3), ValueError, "Q must be positive semi-definite, smallest eigenvalue -1", "pf-Q-not-psd"),
    row(lambda: pf_run_with(R=I3), ValueError, r"R must have shape \(2, 2\), got shape \(3, 3\)", "pf-R-shape"),
    row(lambda: pf_run_with(R=np.full((2, 2), np.inf)), ValueError, "R must be finite", "pf-R-inf"),
    row(lambda: pf_run_with(R=-I2), ValueError, "R must be positive definite.*smallest eigenvalue -1", "pf-R-not-pd"),
    row(lambda: pf_run_with(Q=NONSYM3), ValueError, "Q must be symmetric", "pf-Q-nonsym"),
    row(lambda: pf_run_with(R=NONSYM2), ValueError, "R must be symmetric", "pf-R-nonsym"),
    row(lambda: pf_run_with(proposal="unscented", Q=NONSYM3), ValueError, "Q must be symmetric", "upf-Q-nonsym"),
    row(lambda: make_pf().update(np.zeros(3)), ValueError, r"z must have 2 entries, got shape \(3,\)", "pf-z-len"),
    row(lambda: make_pf().update([np.nan, 0.0]), ValueError, "z must be finite .*use z=None", "pf-z-nan"),
    row(lambda: make_pf().update("ab"), TypeError, "z must be array-like of numbers or None, got str", "pf-z-type"),
    row(lambda: make_pf().batch_filter(np.zeros((4, 3))), ValueError, r"z must have 2 entries, got shape \(3,\)", "pf-zs-shape"),
    row(lambda: make_pf().initialize(np.zeros((5, 3))), ValueError, r"particles must have shape \(10, 3\), got shape \(5, 3\)", "pf-init-shape"),
    row(lambda: make_pf().initialize(np.full((10, 3), np.nan)), ValueError, "particles must be finite", "pf-init-nan"),
    row(lambda: make_pf(proposal="unscented").initialize(np.zeros((10, 3)), -I3), ValueError, "covariances must be positive definite .*-1", "upf-init-cov"),
    row(lambda: make_pf(proposal="unscented").initialize(np.zeros((10, 3)), np.zeros((4, 3, 3))), ValueError, r"covariances must have shape", "upf-init-cov-shape"),
    row(lambda: resampling.resample([0.5, 0.5], "foo", rng=0), ValueError, "unknown resampling scheme 'foo'; valid:", "resample-name"),
    row(lambda: resampling.resample([0.5, 0.5], "systematic", rng=0, n=0), ValueError, r"n must be >= 1, got 0", "resample-n"),
    row(lambda: resampling.normalize_log_weights([np.nan, 0.0]), ValueError, "log_weights must not contain NaN", "log-weights-nan"),
]

# --------------------------------------------------------------------------- regressor
X_REG, Y_REG = datasets.make_siso_benchmark(rng=0)[:2]
X_REG, Y_REG = X_REG[:20], Y_REG[:20]


def fit_reg(X=None, y=None, **kw):
    kw = {"n_hidden": 2, "n_epochs": 1, **kw}
    return WNNRegressor(**kw).fit(X_REG if X is None else X, Y_REG if y is None else y)


REGRESSOR_ROWS = [
    row(lambda: fit_reg(n_hidden=0), ValueError, r"n_hidden must be >= 1, got 0", "reg-hidden-zero"),
    row(lambda: fit_reg(n_hidden=-2), ValueError, r"n_hidden must be >= 1, got -2", "reg-hidden-neg"),
    row(lambda: fit_reg(n_epochs=0), ValueError, r"n_epochs must be >= 1, got 0", "reg-epochs-zero"),
    row(lambda: fit_reg(n_epochs=-1), ValueError, r"n_epochs must be >= 1, got -1", "reg-epochs-neg"),
    row(lambda: fit_reg(n_epochs=2.5), TypeError, r"n_epochs must be an integer, got float 2.5", "reg-epochs-float"),
    row(lambda: fit_reg(trainer="adam"), ValueError, r"unknown trainer 'adam'; valid: 'bp', 'ekf', 'ekf-ensemble', 'epf', 'gsf-ekf', 'gsf-sukf', 'gsf-ukf', 'smc', 'smc-noise', 'smc-noise-10x10', 'smc-student-10x10', 'spf', 'sukf', 'supf', 'ukf', 'upf'", "reg-trainer"),
    row(lambda: fit_reg(wavelet="haar"), ValueError, r"unknown wavelet 'haar'; valid: 'mexican_hat', 'morlet'", "reg-wavelet"),
    row(lambda: fit_reg(init="zeros"), ValueError, r"unknown init 'zeros'; valid: 'paper', 'scaled'", "reg-init"),
    row(lambda: fit_reg(trainer="spf", n_particles=0), ValueError, r"n_particles must be >= 1, got 0", "reg-particles"),
    row(lambda: fit_reg(weighting="bank"), TypeError, "unexpected keyword argument 'weighting'", "reg-weighting-gone"),
    row(lambda: fit_reg(trainer="upf", move="gibbs"), ValueError, r"unknown move 'gibbs'; valid: None, 'hmc', 'mala'", "reg-move"),
    row(lambda: fit_reg(ekf_backend="foo"), ValueError, r"unknown ekf_backend 'foo'; valid: 'filterpy', 'rank1'", "reg-backend"),
    row(lambda: fit_reg(process_noise=-1.0), ValueError, r"process_noise must be finite and >= 0, got -1.0", "reg-Q-neg"),
    row(lambda: fit_reg(initial_covariance=0.0), ValueError, r"initial_covariance must be finite and > 0, got 0.0", "reg-P0-zero"),
    row(lambda: fit_reg(measurement_noise=0.0), ValueError, r"measurement_noise must be finite and > 0, got 0.0", "reg-R-zero"),
    row(lambda: fit_reg(trainer="bp", learning_rate=-1.0), ValueError, r"learning_rate must be finite and > 0, got -1.0", "reg-lr"),
    row(lambda: fit_reg(trainer="spf", tempering=0.0), ValueError, r"tempering must be finite and > 0, got 0.0", "reg-tempering"),
    row(lambda: fit_reg(trainer="spf", ess_threshold=2.0), ValueError, r"ess_threshold must be a number in \[0, 1\], got 2.0", "reg-ess"),
    row(lambda: fit_reg(early_stopping=True, validation_fraction=1.5), ValueError, r"validation_fraction must be in \(0, 1\), got 1.5", "reg-valfrac"),
    row(lambda: fit_reg(early_stopping=True, n_iter_no_change=0), ValueError, r"n_iter_no_change must be >= 1, got 0", "reg-patience"),
    row(lambda: fit_reg(y=Y_REG[:-1]), ValueError, r"inconsistent numbers of samples: \[20, 19\]", "reg-X-y-lengths"),
    row(lambda: WNNRegressor(n_hidden=2).partial_fit(X_REG, Y_REG[:-2]), ValueError, r"inconsistent numbers of samples: \[20, 18\]", "reg-partial-X-y-lengths"),
    row(lambda: fit_reg(X=np.where(X_REG > 0.5, np.nan, X_REG)), ValueError, "Input X contains NaN", "reg-X-nan"),
    row(lambda: fit_reg(y=np.where(Y_REG > 0, np.inf, Y_REG)), ValueError, "Input y contains infinity", "reg-y-inf"),
    row(lambda: fit_reg(X=Y_REG, y=Y_REG), ValueError, "Expected 2D array, got 1D array", "reg-X-1d"),
    row(lambda: fit_reg().predict(np.zeros((3, 7))), ValueError, "X has 7 features, but WNNRegressor is expecting 5 features", "reg-predict-features"),
    row(lambda: fit_reg().predict(np.full((3, 5), np.nan)), ValueError, "Input X contains NaN", "reg-predict-nan"),
    row(lambda: fit_reg(verbose="yes"), TypeError, r"verbose must be an integer, got str 'yes'", "reg-verbose-str"),
    row(lambda: fit_reg(verbose=-1), ValueError, r"verbose must be >= 0, got -1", "reg-verbose-neg"),
    row(lambda: fit_reg(random_state=-1), ValueError, r"random_state seed must be >= 0, got -1", "reg-random-state-neg"),
]

# --------------------------------------------------------------------------- dead reckoning and the neural filter
GPS = dr.GPSDRModel()
NF_DATA = nfm.make_training_set(nfm.paper_training_states(), dr.DRModel(), rng=0)
NF = nfm.NeuralFilter(n_epochs=1, rng=0).fit(*NF_DATA)
DR_ROWS = [
    row(lambda: dr.DRModel(dt=0.0), ValueError, r"dt must be finite and > 0, got 0.0", "drm-dt"),
    row(lambda: dr.DRModel(sigma_heading=-1.0), ValueError, r"sigma_heading must be finite and > 0, got -1.0", "drm-sigma"),
    row(lambda: dr.DRModel(q=-1.0), ValueError, r"q must be finite and >= 0, got -1.0", "drm-q"),
    row(lambda: dr.DRModel(accel_term="foo"), ValueError, r"unknown accel_term 'foo'; valid: 'kinematic', 'paper'", "drm-accel"),
    row(lambda: dr.DRModel(x0=np.zeros(5)), ValueError, r"x0 must have length 6, got shape \(5,\)", "drm-x0"),
    row(lambda: dr.DRModel(P0=-np.eye(6)), ValueError, "P0 must be positive definite .*-1", "drm-P0"),
    row(lambda: dr.DRModel(zeta=0.0), ValueError, r"zeta must be finite and > 0, got 0.0", "drm-zeta"),
    row(lambda: dr.DRModel().simulate(0, rng=0), ValueError, r"n_steps must be >= 1, got 0", "drm-simulate-n"),
    row(lambda: dr.DRModel().ekf(R=-np.eye(2)), ValueError, "R must be positive definite", "drm-ekf-R"),
    row(lambda: dr.GPSDRModel(sigma_gps=0.0), ValueError, r"sigma_gps must be finite and > 0, got 0.0", "gps-sigma"),
    row(lambda: dr.GPSDRModel(dt=-1.0), ValueError, r"dt must be finite and > 0, got -1.0", "gps-dt"),
    row(lambda: dr.GPSDRModel(augmented=True, x0=np.zeros(6)), ValueError, r"x0 must have length 8, got shape \(6,\)", "gps-x0"),
    row(lambda: GPSDRFilter(GPS).update(np.zeros(3)), ValueError, r"z_dr must have length 2, got shape \(3,\)", "gps-update-zdr-len"),
    row(lambda: GPSDRFilter(GPS).update([np.nan, 1.0]), ValueError, r"z_dr must be finite, got \[nan  1.\]", "gps-update-zdr-nan"),
    row(lambda: GPSDRFilter(GPS).update([0.0, 1.0], [np.nan, 0.0]), ValueError, "z_gps must be finite", "gps-update-zgps-nan"),
    row(lambda: GPSDRFilter(GPS).update([0.0, 1.0], [0.0, 0.0, 0.0]), ValueError, r"z_gps must have length 2, got shape \(3,\)", "gps-update-zgps-len"),
    row(lambda: dr.transition_matrix(0.0), ValueError, r"dt must be finite and > 0, got 0.0", "transition-dt"),
    row(lambda: scenarios.simulate_scenario("straight"), TypeError, "scenario must be a Scenario, got str", "scenario-type"),
    row(lambda: scenarios.simulate_scenario(scenarios.SCENARIOS["straight"](dt=0.0)), ValueError, r"dt must be finite and > 0, got 0.0", "scenario-dt"),
    row(lambda: scenarios.simulate_scenario(scenarios.SCENARIOS["straight"](duration=-1.0)), ValueError, r"duration must be finite and > 0, got -1.0", "scenario-duration"),
    row(lambda: scenarios.simulate_scenario(scenarios.SCENARIOS["gpsdr"](sigma_gps=-1.0)), ValueError, r"sigma_gps must be finite and >= 0, got -1.0", "scenario-sigma-gps"),
    row(lambda: nfm.NeuralFilter(n_hidden=0), ValueError, r"n_hidden must be >= 1, got 0", "nf-hidden"),
    row(lambda: nfm.NeuralFilter(n_epochs=0), ValueError, r"n_epochs must be >= 1, got 0", "nf-epochs"),
    row(lambda: nfm.NeuralFilter(n_epochs=-3), ValueError, r"n_epochs must be >= 1, got -3", "nf-epochs-neg"),
    row(lambda: nfm.NeuralFilter(form="foo"), ValueError, r"unknown form 'foo'; valid: 'absolute', 'passthrough', 'relative'", "nf-form"),
    row(lambda: nfm.NeuralFilter(features="foo"), ValueError, r"unknown features 'foo'; valid: 'angle', 'velocity'", "nf-features"),
    row(lambda: nfm.NeuralFilter(learning_rate=0.0), ValueError, r"learning_rate must be finite and > 0, got 0.0", "nf-lr"),
    row(lambda: nfm.NeuralFilter(learning_rate_online=-1.0), ValueError, r"learning_rate_online must be finite and >= 0, got -1.0", "nf-lr-online"),
    row(lambda: nfm.NeuralFilter(model=MODEL), ValueError, "model must be a 6-state DR model, got dim_x=3", "nf-model"),
    row(lambda: nfm.NeuralFilter(n_epochs=1).fit(NF_DATA[0], NF_DATA[1][:-1], NF_DATA[2]), ValueError, r"X_prior, Z, X_true must have shapes \(n, 6\), \(n, 2\), \(n, 6\); got \(30, 6\), \(29, 2\), \(30, 6\)", "nf-fit-lengths"),
    row(lambda: nfm.NeuralFilter(n_epochs=1).fit(NF_DATA[0], np.full_like(NF_DATA[1], np.nan), NF_DATA[2]), ValueError, "X_prior, Z and X_true must be finite", "nf-fit-nan"),
    row(lambda: nfm.NeuralFilter().update([0.0, 1.0]), ValueError, r"NeuralFilter is not fitted; call fit\(X_prior, Z, X_true\) first", "nf-unfitted"),
    row(lambda: pickle.loads(pickle.dumps(NF)).update([np.nan, 1.0]), ValueError, r"z must be finite .*got \[nan  1.\]", "nf-z-nan"),
    row(lambda: pickle.loads(pickle.dumps(NF)).update([0.0, 1.0, 2.0]), ValueError, r"z must have 2 entries, got shape \(3,\)", "nf-z-len"),
    row(lambda: pickle.loads(pickle.dumps(NF)).batch_filter(np.zeros((5, 3))), ValueError, r"zs must have shape \(n_steps, 2\), got \(5, 3\)", "nf-zs-shape"),
    row(lambda: pickle.loads(pickle.dumps(NF)).reset(np.zeros(5)), ValueError, r"x0 must have length 6, got shape \(5,\)", "nf-reset-x0"),
    row(lambda: nfm.make_training_set(np.zeros((5, 5))), ValueError, r"states must have shape \(n_states, 6\), got \(5, 5\)", "nf-training-states"),
    row(lambda: nfm.paper_training_states(0), ValueError, r"n_points must be >= 2, got 0", "nf-paper-states"),
    row(lambda: nfm.random_motion_states(0, rng=0), ValueError, r"n must be >= 1, got 0", "nf-random-states"),
]

# --------------------------------------------------------------------------- studies
WNN_STUDY = dict(n_runs=1, n_epochs=1, pf_epochs=1, n_particles=2, trainers=["bp"], paper_table=False,
                 references=(), sweep_particles=(), sweep_runs=1, seed=7)
STUDY_ROWS = [
    row(lambda: wnn_study.run_study(**{**WNN_STUDY, "n_runs": 0}), ValueError, r"n_runs must be >= 1, got 0", "study-wnn-runs"),
    row(lambda: wnn_study.run_study(**{**WNN_STUDY, "n_epochs": -1}), ValueError, r"n_epochs must be >= 1, got -1", "study-wnn-epochs"),
    row(lambda: wnn_study.run_study(**{**WNN_STUDY, "n_particles": 0}), ValueError, r"n_particles must be >= 1, got 0", "study-wnn-particles"),
    row(lambda: wnn_study.run_study(**{**WNN_STUDY, "trainers": ["adam"]}), ValueError, r"unknown trainer 'adam'; valid:", "study-wnn-trainer"),
    row(lambda: wnn_study.run_study(**{**WNN_STUDY, "seed": -1}), ValueError, r"seed must be >= 0, got -1", "study-wnn-seed"),
    row(lambda: wnn_study.run_study(**{**WNN_STUDY, "seed": "x"}), TypeError, r"seed must be an integer", "study-wnn-seed-type"),
]

DR_STUDY = dict(scenarios=["straight"], n_runs=1, filters=["EKF"])
STUDY_ROWS += [
    row(lambda: dr_study.run_study(**{**DR_STUDY, "n_runs": 0}), ValueError, r"n_runs must be >= 1, got 0", "study-dr-runs"),
    row(lambda: dr_study.run_study(**{**DR_STUDY, "jobs": 0}), ValueError, r"jobs must be >= 1, or negative \(-1: all cores\), got 0", "study-dr-jobs"),
    row(lambda: dr_study.run_study(**{**DR_STUDY, "filters": ["KF9"]}), ValueError, r"unknown filters \['KF9'\]; valid:", "study-dr-filters"),
    row(lambda: dr_study.run_study(**{**DR_STUDY, "scenarios": ["moon"]}), ValueError, r"unknown scenario 'moon'; valid:", "study-dr-scenario"),
    row(lambda: dr_study.run_study(**{**DR_STUDY, "seed": -1}), ValueError, r"seed must be >= 0, got -1", "study-dr-seed"),
    row(lambda: dr_study.run_study(**{**DR_STUDY, "scenarios": []}), ValueError, r"scenarios must name at least one of .*got \[\]", "study-dr-no-scenarios"),
]

ROWS = (VALIDATION_ROWS + MODEL_ROWS + METRIC_ROWS + SIGMA_ROWS + UKF_ROWS + WNN_ROWS + PF_ROWS + REGRESSOR_ROWS
        + DR_ROWS + STUDY_ROWS)


@pytest.mark.parametrize("call, exc, match", ROWS)
def test_bad_input_raises_a_clear_error(call, exc, match):
    with pytest.raises(exc, match=match):
        call()


# --------------------------------------------------------------------------- rng of the wrong type
RNG_ENTRY_POINTS = {
    "check_rng": lambda rng: val.check_rng(rng),
    "LinearGaussianModel.random": lambda rng: LGM.random(2, 1, rng=rng),
    "LinearGaussianModel.simulate": lambda rng: MODEL.simulate(3, rng=rng),
    "wnn.init_paper": lambda rng: wnn.init_paper(2, 2, rng=rng),
    "wnn.init_scaled": lambda rng: wnn.init_scaled(X3, 2, rng=rng),
    "WNNWeightModel.simulate": lambda rng: WNNWeightModel(2, 2).simulate(3, rng=rng),
    "datasets.make_siso_benchmark": lambda rng: datasets.make_siso_benchmark(rng=rng),
    "resampling.resample": lambda rng: resampling.resample([0.5, 0.5], "systematic", rng=rng),
    "ParticleFilter": lambda rng: make_pf(rng=rng),
    "WNNRegressor.fit": lambda rng: fit_reg(random_state=rng),  # scikit-learn's name
    "NeuralFilter": lambda rng: nfm.NeuralFilter(rng=rng),
    "neural_filter.make_training_set": lambda rng: nfm.make_training_set(nfm.paper_training_states(), rng=rng),
    "neural_filter.random_motion_states": lambda rng: nfm.random_motion_states(5, rng=rng),
    "scenarios.simulate_scenario": lambda rng: scenarios.simulate_scenario(scenarios.SCENARIOS["straight"](duration=1.0),
                                                                           rng=rng),
    "DRModel.simulate": lambda rng: dr.DRModel().simulate(3, rng=rng),
}


@pytest.mark.parametrize("bad, typename", BAD_RNGS)
@pytest.mark.parametrize("entry", sorted(RNG_ENTRY_POINTS))
def test_rng_of_the_wrong_type_raises_type_error(entry, bad, typename):
    with pytest.raises(TypeError, match=RNG_MSG + typename):
        RNG_ENTRY_POINTS[entry](bad)


# --------------------------------------------------------------------------- state left as it was
def _state(f, with_step=False):
    state = {k: np.array(getattr(f, k), copy=True) for k in ("x", "P", "x_prior", "P_prior", "x_post", "P_post")}
    return state | {"step": f.step} if with_step else state


def _assert_same(f, before):
    after = _state(f, with_step="step" in before)
    for k, v in before.items():
        assert np.array_equal(after[k], v), k


FAILING_UPDATES = {
    "z-nan": lambda f: f.update(np.array([np.nan, 0.0])),
    "z-len3": lambda f: f.update(np.zeros(3)),
    "R-shape": lambda f: f.update(np.zeros(2), R=I3),
    "R-nan": lambda f: f.update(np.zeros(2), R=np.full((2, 2), np.nan)),
    "z-type": lambda f: f.update("ab"),
}


@pytest.mark.parametrize("vectorized", [False, True])
@pytest.mark.parametrize("how", sorted(FAILING_UPDATES))
def test_failed_ukf_update_leaves_state_unchanged(vectorized, how):
    f = predicted_ukf(vectorized)
    before = _state(f)
    with pytest.raises((ValueError, TypeError)):
        FAILING_UPDATES[how](f)
    _assert_same(f, before)
    # and the filter still works afterwards, exactly as an untouched twin
    g = predicted_ukf(vectorized)
    f.update(np.array([0.1, 0.2])); g.update(np.array([0.1, 0.2]))
    assert np.array_equal(f.x, g.x) and np.array_equal(f.P, g.P)


def _NOT_PD_UT(sigmas, Wm, Wc, *args, **kwargs):
    """An unscented transform whose ``S`` is not positive definite (an ``R`` that is not is refused before it)."""
    return Wm @ sigmas, -1e3 * I2


@pytest.mark.parametrize("vectorized", [
    False,
    True,
])
def test_failed_ukf_update_with_negative_S_leaves_state_unchanged(vectorized):
    f = predicted_ukf(vectorized)
    before = _state(f)
    with pytest.raises(NumericalError):
        f.update(np.zeros(2), UT=_NOT_PD_UT)  # (an R not positive definite is refused before)
    _assert_same(f, before)


@pytest.mark.parametrize("vectorized", [False, True])
def test_failed_ukf_predict_leaves_state_unchanged(vectorized):
    f = predicted_ukf(vectorized)
    f.update(np.array([0.1, 0.2]))
    f.P = np.diag([1.0, -1.0, 1.0])
    before = _state(f)
    with pytest.raises(NumericalError, match="P is not positive definite at step 3"):
        f.predict()
    _assert_same(f, before)


@pytest.mark.parametrize("vectorized", [False, True])
def test_failed_ukf_update_does_not_advance_the_step_counter(vectorized):
    f = predicted_ukf(vectorized)
    before = _state(f, with_step=True)
    with pytest.raises(NumericalError):
        f.update(np.zeros(2), UT=_NOT_PD_UT)  # (an R not positive definite is refused before)
    _assert_same(f, before)


PF_FAILING_UPDATES = {
    "z-nan": lambda f: f.update(np.array([np.nan, 0.0])),
    "z-len3": lambda f: f.update(np.zeros(3)),
    "z-type": lambda f: f.update("ab"),
    "R-shape": lambda f: (setattr(f, "R", I3), f.update(np.zeros(2))),
    "R-not-pd": lambda f: (setattr(f, "R", -I2), f.update(np.zeros(2))),
    "R-nan": lambda f: (setattr(f, "R", np.full((2, 2), np.nan)), f.update(np.zeros(2))),
}


@pytest.mark.parametrize("proposal", ["prior", "unscented"])
@pytest.mark.parametrize("how", sorted(PF_FAILING_UPDATES))
def test_failed_particle_filter_update_leaves_state_unchanged(proposal, how):
    def fresh():
        f = make_pf(proposal=proposal, rng=3)
        f.Q, f.R = MODEL.Q.copy(), MODEL.R.copy()
        f.predict()
        return f

    f = fresh()
    keys = ("x", "P", "x_post", "P_post", "particles", "log_weights", "step", "log_marginal_likelihood")
    before = {k: np.array(getattr(f, k), copy=True) for k in keys}
    rng_state = f.rng.bit_generator.state
    with pytest.raises((ValueError, TypeError)):
        PF_FAILING_UPDATES[how](f)
    for k in keys:
        np.testing.assert_array_equal(getattr(f, k), before[k], err_msg=k)
    assert f.rng.bit_generator.state == rng_state
    # the filter goes on exactly as an untouched twin
    f.R = MODEL.R.copy()
    g = fresh()
    f.update(np.array([0.1, 0.2])); g.update(np.array([0.1, 0.2]))
    np.testing.assert_array_equal(f.particles, g.particles)


def test_failed_neural_filter_update_leaves_state_unchanged():
    nf = pickle.loads(pickle.dumps(NF))
    nf.predict()
    before = (nf.x.copy(), nf.x_prior.copy(), {k: v.copy() for k, v in nf.params_.items()})
    for bad in ([np.nan, 1.0], [0.0, 1.0, 2.0], "ab"):
        with pytest.raises((ValueError, TypeError)):
            nf.update(bad)
        np.testing.assert_array_equal(nf.x, before[0])
        np.testing.assert_array_equal(nf.x_prior, before[1])
        for k, v in before[2].items():
            np.testing.assert_array_equal(nf.params_[k], v)
