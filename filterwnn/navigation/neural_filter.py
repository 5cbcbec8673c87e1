r"""The second paper's neural filter: a BP network in place of the Kalman gain.

Zhang, Ma, Chen and Mastorakis replace the EKF's update by a network,

.. math::
    \hat X(k|k-1) = \Phi \hat X(k-1), \qquad
    \hat X(k) = K_{NN}\big(\hat X(k|k-1),\ Y(k)\big),

an 8-12-6 network (6 predicted states and 2 measurements in, sigmoid hidden layer,
linear output) trained in two phases:

phase 1 (:meth:`NeuralFilter.fit`)
    supervised back-propagation on simulated ``(prediction, measurement) -> state``
    triples (the paper: 30 states on the line from (-6, -6) to (0, 0), learning rate
    0.1, 300 epochs; :func:`paper_training_states`, :func:`random_motion_states` and
    :func:`make_training_set` build such sets);
phase 2 (``learning_rate_online > 0`` in :meth:`NeuralFilter.update`)
    on-line gradient descent on :math:`\tfrac12\|h(\hat X(k|k-1)) - Y(k)\|^2`
    (eqs. 9-11), differentiated through the recurrence
    :math:`\hat X(k|k-1) = \Phi K_{NN}(u_{k-1}; W)` with the previous network input
    held fixed (a one-step truncated recurrence); the heading residual is wrapped.

Three forms (``form=``):

``"absolute"`` (the paper, faithful)
    absolute states in and out. Trained on positions in [-6, 0] m, a sigmoid network
    cannot produce positions of kilometres: its error grows like the distance driven.
``"relative"``
    the predicted position is subtracted from the inputs and added back to the
    outputs (translation invariant), so the network outputs a position correction.
    Nothing observable corrects a small learned bias in that correction (``h`` does
    not depend on position), so the position drifts.
``"passthrough"`` (default)
    as ``"relative"``, but the position is taken from the prediction and the network
    only updates velocity and acceleration -- the only choice consistent with the
    observability of the DR model (see :mod:`filterwnn.navigation.dead_reckoning`). It is the
    default because it measures best (``filterwnn study dr``).

The measurement enters either as ``features="angle"`` (heading/pi and distance, as in
the paper; discontinuous at +-180 degrees) or ``features="velocity"`` (the measured
velocity vector ``s/T [sin theta, cos theta]``, continuous; the default).

The neural filter has **no covariance**: ``P`` is ``None``, it cannot be judged by NEES,
and it cannot be fused with GPS by a Kalman update. It knows only what its training set
showed it: trained on one trajectory it beats Kalman filters on that trajectory and
fails on others.

>>> import numpy as np
>>> from filterwnn.navigation.dead_reckoning import DRModel
>>> model = DRModel(dt=0.1)
>>> Xp, Z, X = make_training_set(paper_training_states(), model, rng=0, n_repeats=5)
>>> nf = NeuralFilter(model, rng=1).fit(Xp, Z, X)
>>> nf.x = model.x0.copy()
>>> nf.predict(); nf.update(model.hx(model.fx(model.x0)))
>>> nf.x.shape, nf.P is None
((6,), True)
>>> bool(abs(nf.x[1] - 10.0) < 0.5)
True
"""

from __future__ import annotations

import numpy as np

from .._validation import (
    NumericalError,
    as_measurement,
    as_state,
    check_choice,
    check_positive,
    check_positive_int,
    check_rng,
)
from .dead_reckoning import DRModel, dr_residual, wrap_angle

__all__ = ["NeuralFilter", "make_training_set", "paper_training_states", "random_motion_states"]

_FORMS = ("absolute", "relative", "passthrough")
_FEATURES = ("angle", "velocity")
_POS = np.array([True, False, False, True, False, False])


def _sigmoid(a):
    return 0.5 * (1.0 + np.tanh(0.5 * a))  # overflow-free logistic


def paper_training_states(n_points=30, speed=10.0 * np.sqrt(2.0), heading_deg=45.0,
                          start=(-6.0, -6.0), end=(0.0, 0.0)):
    """The paper's phase-1 states: ``n_points`` on the line ``start -> end``.

    Returns
    -------
    ndarray of shape (n_points, 6)
        ``[e, v_e, 0, n, v_n, 0]`` with the scenario velocity.
    """
    n_points = check_positive_int(n_points, "n_points", minimum=2)
    s = np.linspace(0.0, 1.0, n_points)
    h = np.deg2rad(heading_deg)
    X = np.zeros((n_points, 6))
    X[:, 0] = start[0] + s * (end[0] - start[0])
    X[:, 3] = start[1] + s * (end[1] - start[1])
    X[:, 1] = speed * np.sin(h)
    X[:, 4] = speed * np.cos(h)
    return X


def random_motion_states(n, rng=None, speed=(3.0, 25.0), accel_sd=0.5, position_sd=10.0):
    """Random states: uniform heading, uniform speed in ``speed``, Gaussian accelerations.

    Returns
    -------
    ndarray of shape (n, 6)
    """
    n = check_positive_int(n, "n")
    rng = check_rng(rng)
    h = rng.uniform(-np.pi, np.pi, n)
    v = rng.uniform(speed[0], speed[1], n)
    X = np.empty((n, 6))
    X[:, 0] = position_sd * rng.standard_normal(n)
    X[:, 3] = position_sd * rng.standard_normal(n)
    X[:, 1] = v * np.sin(h)
    X[:, 4] = v * np.cos(h)
    X[:, 2] = accel_sd * rng.standard_normal(n)
    X[:, 5] = accel_sd * rng.standard_normal(n)
    return X


def make_training_set(states, model=None, rng=None, perturb_sd=(0.2, 0.5, 0.1), n_repeats=1,
                      R=None):
    """Phase-1 triples from true previous states.

    For each true ``X(k-1)``: the target ``X(k) = Phi X(k-1)``, the network's
    prediction input ``Phi (X(k-1) + delta)`` with ``delta`` drawn with standard
    deviations ``perturb_sd`` (position, velocity, acceleration; without it the
    measurement input carries no information), and the measurement
    ``h(X(k)) + v`` with ``v ~ N(0, R)`` (heading wrapped).

    Parameters
    ----------
    states : array-like of shape (n_states, 6)
    model : DRModel, optional
    rng : seed or Generator
    perturb_sd : tuple of 3 floats
    n_repeats : int
        Draws per state.
    R : ndarray of shape (2, 2), optional
        Measurement noise (default ``model.R``).

    Returns
    -------
    X_prior : ndarray of shape (n_samples, 6)
    Z : ndarray of shape (n_samples, 2)
    X_true : ndarray of shape (n_samples, 6)
    """
    model = DRModel() if model is None else model
    rng = check_rng(rng)
    S = np.asarray(states, dtype=float)
    if S.ndim != 2 or S.shape[1] != 6:
        raise ValueError(f"states must have shape (n_states, 6), got {S.shape}")
    n_repeats = check_positive_int(n_repeats, "n_repeats")
    S = np.repeat(S, n_repeats, axis=0)
    sd = np.array([perturb_sd[0], perturb_sd[1], perturb_sd[2]] * 2)
    X_true = model.fx(S)
    X_prior = model.fx(S + sd * rng.standard_normal(S.shape))
    R = model.R if R is None else np.asarray(R, dtype=float)
    Z = model.hx(X_true) + rng.standard_normal((len(S), 2)) @ np.linalg.cholesky(R).T
    Z[:, 0] = wrap_angle(Z[:, 0])
    return X_prior, Z, X_true


class NeuralFilter:
    r"""The paper's recurrent neural filter :math:`\hat X(k) = K_{NN}(\Phi \hat X(k-1), Y(k))`.

    Parameters
    ----------
    model : DRModel, optional
        Supplies ``dt``, :math:`\Phi` (``fx``/``F``), ``hx``, ``HJacobian`` and the wrapped
        residual used by the on-line loss. Default ``DRModel()``.
    n_hidden : int
        Hidden sigmoid units (the paper: 12). The network is ``8 - n_hidden - 6``.
    form : {"passthrough", "relative", "absolute"}
        See the module docstring; ``"absolute"`` is the paper's faithful form,
        ``"passthrough"`` (position from the prediction) the default.
    features : {"velocity", "angle"}
        How the measurement enters the network.
    learning_rate, n_epochs, batch_size : float, int, int
        Phase-1 SGD (the paper: 0.1, 300 epochs; ``batch_size=1`` is per-sample); the
        names of :class:`filterwnn.WNNRegressor`.
    learning_rate_online : float
        Phase-2 learning rate (0 disables on-line training).
    state_scale : array-like of shape (6,)
        Fixed scaling of the states at the network's input and output.
    rng : seed or Generator
        Weight initialisation and shuffling.

    Attributes
    ----------
    step : int
        The time step since ``fit``/``reset``: ``predict`` advances it by one;
        ``update`` and its errors report the current step (as in every filter of the
        package).
    x, x_prior, x_post : ndarray of shape (6,)
        Estimate after ``update``, prediction after ``predict``; filterpy's names.
    P : None
        There is no covariance (see the module docstring).
    params_ : dict of ndarray
        Current weights ``W1 (n_hidden, 8)``, ``b1``, ``W2 (6, n_hidden)``, ``b2``
        (changed by phase 2).
    params_fit_ : dict of ndarray
        The weights after phase 1 (:meth:`reset` restores them).
    loss_curve_ : list of float
        Phase-1 loss per epoch.
    """

    #: The last step's network input, a tuple of arrays of several shapes, is a slot, out of the ``__dict__`` that
    #: filterpy's ``Saver`` copies at each ``save()`` and stacks in ``to_array()`` (it raised on it).
    __slots__ = ("_last", "__dict__", "__weakref__")

    def __init__(self, model=None, *, n_hidden=12, form="passthrough", features="velocity",
                 learning_rate=0.1, n_epochs=300, batch_size=1, learning_rate_online=1e-3,
                 state_scale=(10.0, 15.0, 1.0, 10.0, 15.0, 1.0), rng=None):
        self.model = DRModel() if model is None else model
        if getattr(self.model, "dim_x", None) != 6:
            raise ValueError(f"model must be a 6-state DR model, got dim_x={getattr(self.model, 'dim_x', None)}")
        self.n_hidden = check_positive_int(n_hidden, "n_hidden")
        self.form = check_choice(form, "form", _FORMS)
        self.features = check_choice(features, "features", _FEATURES)
        self.learning_rate = check_positive(learning_rate, "learning_rate")
        self.n_epochs = check_positive_int(n_epochs, "n_epochs")
        self.batch_size = check_positive_int(batch_size, "batch_size")
        self.learning_rate_online = check_positive(learning_rate_online, "learning_rate_online", strict=False)
        self.state_scale = as_state(state_scale, "state_scale", 6)
        self.rng = check_rng(rng)
        self.dt = self.model.dt
        self.dim_x, self.dim_z = 6, 2
        self.F = self.model.F
        self.x = np.array(self.model.x0, dtype=float)
        self.x_prior = self.x.copy()
        self.x_post = self.x.copy()
        self.P = None
        self._last = None
        self.params_ = None
        self.step = 0

    # ----------------------------------------------------------------- network pieces
    def _offset(self, Xp):
        if self.form == "absolute":
            return np.zeros_like(Xp)
        return Xp * _POS

    def _features(self, Z):
        Z = np.asarray(Z, dtype=float)
        if self.features == "angle":
            return np.stack([Z[..., 0] / np.pi, Z[..., 1] / 1.5], axis=-1)
        v = Z[..., 1] / self.dt
        return np.stack([v * np.sin(Z[..., 0]), v * np.cos(Z[..., 0])], axis=-1) / 15.0

    def _inputs(self, Xp, Z):
        off = self._offset(Xp)
        return np.concatenate([(Xp - off) / self.state_scale, self._features(Z)], axis=-1), off

    def _forward(self, U, p):
        Hh = _sigmoid(U @ p["W1"].T + p["b1"])
        return Hh @ p["W2"].T + p["b2"], Hh

    def _output_mask(self):
        return (~_POS).astype(float) if self.form == "passthrough" else np.ones(6)

    def _state(self, out, off, Xp):
        x = off + out * self.state_scale
        if self.form == "passthrough":
            x = np.where(_POS, Xp, x)
        return x

    def _init_params(self, n_in):
        r = self.rng
        return {
            "W1": r.standard_normal((self.n_hidden, n_in)) / np.sqrt(n_in),
            "b1": np.zeros(self.n_hidden),
            "W2": r.standard_normal((6, self.n_hidden)) / np.sqrt(self.n_hidden),
            "b2": np.zeros(6),
        }

    @staticmethod
    def _backward(U, Hh, g_out, p):
        """Gradients of a loss with output gradient ``g_out (n, 6)`` w.r.t. the weights."""
        gW2 = g_out.T @ Hh
        gb2 = g_out.sum(axis=0)
        g_h = (g_out @ p["W2"]) * Hh * (1.0 - Hh)
        return {"W1": g_h.T @ U, "b1": g_h.sum(axis=0), "W2": gW2, "b2": gb2}

    @staticmethod
    def _check_triples(X_prior, Z, X_true):
        """The phase-1 training triples as float arrays, with their count ``n``; a ``ValueError``
        names the shapes or the non-finite input."""
        Xp = np.asarray(X_prior, dtype=float)
        Z = np.asarray(Z, dtype=float)
        Xt = np.asarray(X_true, dtype=float)
        n = Xp.shape[0] if Xp.ndim == 2 else -1
        if Xp.shape != (n, 6) or Xt.shape != (n, 6) or Z.shape != (n, 2):
            raise ValueError(
                "X_prior, Z, X_true must have shapes (n, 6), (n, 2), (n, 6); "
                f"got {Xp.shape}, {Z.shape}, {Xt.shape}"
            )
        if not (np.all(np.isfinite(Xp)) and np.all(np.isfinite(Z)) and np.all(np.isfinite(Xt))):
            raise ValueError("X_prior, Z and X_true must be finite")
        return Xp, Z, Xt, n

    def _epoch(self, U, T, mask, p, order, bs):
        """One SGD pass over the inputs ``U`` and scaled targets ``T`` in ``order``, updating the
        weights ``p`` in place; returns the summed half squared error of the pass."""
        total = 0.0
        lr = self.learning_rate
        if bs == 1:  # per-sample SGD, written out (the hot loop of phase 1)
            W1, b1, W2, b2 = p["W1"], p["b1"], p["W2"], p["b2"]  # updated in place
            for i in order:
                u = U[i]
                h = 0.5 * (1.0 + np.tanh(0.5 * (W1 @ u + b1)))
                g = (W2 @ h + b2 - T[i]) * mask
                total += 0.5 * float(g @ g)
                gh = (g @ W2) * h * (1.0 - h)
                W2 -= lr * np.outer(g, h)
                b2 -= lr * g
                W1 -= lr * np.outer(gh, u)
                b1 -= lr * gh
            return total
        for i in range(0, len(order), bs):
            idx = order[i:i + bs]
            out, Hh = self._forward(U[idx], p)
            g = (out - T[idx]) * mask
            total += 0.5 * float(np.sum(g * g))
            grads = self._backward(U[idx], Hh, g / len(idx), p)
            for k in p:
                p[k] -= lr * grads[k]
        return total

    # ----------------------------------------------------------------- phase 1
    def fit(self, X_prior, Z, X_true):
        """Phase 1: supervised SGD on ``(prediction, measurement) -> state`` triples.

        Parameters
        ----------
        X_prior : array-like of shape (n_samples, 6)
        Z : array-like of shape (n_samples, 2)
        X_true : array-like of shape (n_samples, 6)

        Returns
        -------
        self
        """
        Xp, Z, Xt, n = self._check_triples(X_prior, Z, X_true)
        U, off = self._inputs(Xp, Z)
        T = (Xt - off) / self.state_scale
        mask = self._output_mask()
        p = self._init_params(U.shape[1])
        self.loss_curve_ = []
        bs = min(self.batch_size, n)
        for _ in range(self.n_epochs):
            order = self.rng.permutation(n)
            total = self._epoch(U, T, mask, p, order, bs)
            self.loss_curve_.append(total / n)
            if not (np.isfinite(total) and all(np.all(np.isfinite(v)) for v in p.values())):
                epoch = len(self.loss_curve_)
                raise NumericalError(
                    f"phase-1 training produced non-finite weights at epoch {epoch}; lower learning_rate "
                    f"(learning_rate={self.learning_rate})", matrix="weights", step=epoch)
        self.params_fit_ = {k: v.copy() for k, v in p.items()}
        self.params_ = {k: v.copy() for k, v in p.items()}
        self.n_features_in_ = U.shape[1]
        return self

    def reset(self, x0=None):
        """Restore the phase-1 weights and set the state (default ``model.x0``)."""
        self._check_fitted()
        self.params_ = {k: v.copy() for k, v in self.params_fit_.items()}
        self.x = (self.model.x0 if x0 is None else as_state(x0, "x0", 6)).astype(float).copy()
        self.x_prior = self.x.copy()
        self.x_post = self.x.copy()
        self._last = None
        self.step = 0
        return self

    def _check_fitted(self):
        if self.params_ is None:
            raise ValueError("NeuralFilter is not fitted; call fit(X_prior, Z, X_true) first")

    # ----------------------------------------------------------------- filtering
    def predict(self):
        r"""``x_prior = Phi x`` (no covariance); advances ``step`` by one."""
        self.x_prior = self.model.fx(self.x)
        self.x = self.x_prior.copy()
        self.step += 1

    def _online_step(self, z):
        U, off, Xp_prev = self._last
        p = self.params_
        out, Hh = self._forward(U[None, :], p)
        # r = h(x(k|k-1)) - y(k), x(k|k-1) = Phi x(k-1), x(k-1) = state(out)
        r = dr_residual(self.model.hx(self.x_prior), z)
        H = self.model.HJacobian(self.x_prior)
        g_state = (r @ H) @ self.F                       # d loss / d x(k-1)
        g_out = (g_state * self.state_scale * self._output_mask())[None, :]
        grads = self._backward(U[None, :], Hh, g_out, p)
        for k in p:
            p[k] -= self.learning_rate_online * grads[k]

    def update(self, z):
        """``x = K_NN(x_prior, z)``; with ``learning_rate_online > 0``, one phase-2 step first.

        Does not advance ``step`` (``predict`` does); its errors report the current step.

        Parameters
        ----------
        z : array-like of shape (2,) or None
            ``[heading (rad), odometer distance (m)]``; ``None`` keeps the prediction.
            NaN raises ``ValueError``.
        """
        self._check_fitted()
        if z is None:
            self.x_post = self.x.copy()
            return
        z = as_measurement(z, 2)
        saved = {k: v.copy() for k, v in self.params_.items()} if self.learning_rate_online > 0 else None
        if self.learning_rate_online > 0 and self._last is not None:
            self._online_step(z)
        U, off = self._inputs(self.x_prior, z)
        out, _ = self._forward(U[None, :], self.params_)
        x = self._state(out[0], off, self.x_prior)
        if not np.all(np.isfinite(x)):
            if saved is not None:
                self.params_ = saved
            raise NumericalError(
                f"the neural filter's estimate became non-finite at step {self.step} "
                f"(learning_rate_online={self.learning_rate_online}); x and the weights are left as before",
                matrix="x", step=self.step)
        self.x = x
        self.x_post = self.x.copy()
        self._last = (U, off, self.x_prior)

    def batch_filter(self, zs, x0=None):
        """Run ``predict``/``update`` over ``zs`` from ``x0`` (default: the current ``x``).

        The weights are not reset first (call :meth:`reset` for a fresh run).

        Parameters
        ----------
        zs : array-like of shape (n_steps, 2)

        Returns
        -------
        means : ndarray of shape (n_steps, 6)
            The estimates after each update (there are no covariances to return).
        """
        self._check_fitted()
        zs = np.asarray(zs, dtype=float)
        if zs.ndim != 2 or zs.shape[1] != 2:
            raise ValueError(f"zs must have shape (n_steps, 2), got {zs.shape}")
        if x0 is not None:
            self.x = as_state(x0, "x0", 6).copy()
        means = np.empty((len(zs), 6))
        for k, z in enumerate(zs):
            self.predict()
            self.update(z)
            means[k] = self.x
        return means
