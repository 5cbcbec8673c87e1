r"""An adaptive extended Kalman filter: measurement noise learned from the innovations.

:class:`AdaptiveExtendedKalmanFilter` is filterpy's
:class:`~filterpy.kalman.ExtendedKalmanFilter` (same constructor, attributes, ``predict``
and ``update(z, HJacobian, Hx, R=None, args=(), hx_args=(), residual=np.subtract)``)
with a diagonal ``R`` that follows the sensor noise, for sensors whose noise changes
while the filter runs (a gyro on a rough road, an odometer on gravel, a receiver in a
street canyon).

Covariance matching (Mehra 1972, Myers and Tapley 1976; the windowed "innovation-based
adaptive estimation" of Mohamed and Schwarz 1999). For a consistent filter the
innovation :math:`y_k = z_k - h(x_k^-)` has covariance :math:`H_k P_k^- H_k^T + R`, so
over the last ``window`` updates (the current one included)

.. math::
    \hat R_{ii} = \overline{y_i^2} - \overline{(H P^- H^T)_{ii}}, \qquad
    T_i = \frac{\overline{y_i^2}}{\overline{(H P^- H^T)_{ii}} + R_{ii}}
    \;\sim\; \chi^2_n / n \quad \text{while } R \text{ is right}

(``n`` innovations in the window). ``R`` is left alone while every :math:`T_i` stays
within the two-sided :math:`\chi^2_n/n` quantiles at level ``alpha`` (Bar-Shalom, Li and
Kirubarajan 2001, ch. 5, the NIS test), so with the right noise the filter *is* the
plain EKF. A plain moving window lags a step change by up to its length, which is what
broke the first version of this filter. So when the test rejects, the filter finds the
change point, the newest ``m`` innovations whose variance ratio
:math:`\lambda_m = \overline{u}_{\text{newest } m}`, :math:`u_j = y_j^2 / ((H P^- H^T)_j +
R)`, maximises the generalised likelihood ratio :math:`\tfrac m2(\lambda_m - 1 - \ln
\lambda_m)` of a variance change (summed over the rejecting components; Basseville and
Nikiforov 1993, ch. 2), drops the older innovations, and sets
:math:`R_{ii} = \max(\hat R_{ii}, R^{min}_{ii})` from the newest ``m``. Until the window
has refilled, ``R`` is re-estimated at every update (plain covariance matching over the
innovations since the change); then the test takes over again. A x20 rise is caught
after one innovation and ``R`` is near its new value within a few.

Adding to ``P`` what the mis-weighted measurements added. Until the test rejects, the
filter takes noisier measurements with the old ``R``; the error they put into the state is
missing from ``P``, and once ``R`` is raised the gain collapses and that error is never
corrected (in the dead-reckoning study a lagging 30-sample estimate gave 17.2 m at 200 s
on the straight road with the noise x20, against 13.3 m for the nominal EKF). By the Joseph form, an
update with gain :math:`K_j` computed with :math:`R_j` when the noise was
:math:`R^{true}_j` leaves the actual covariance larger than the filter's by
:math:`K_j (R^{true}_j - R_j) K_j^T`, carried forward by :math:`G_j = \prod_i F_i (I -
K_i H_i) K_j` (the sensitivity analysis of a suboptimal filter, Gelb 1974, ch. 7). The
filter keeps :math:`G_j` for every update in the window, and when ``R`` rises it adds

.. math::
    P \mathrel{+}= \sum_j G_j \,\mathrm{diag}\big(\max(y_j^2 - (H P^- H^T)_j - R_j, 0)\big)\, G_j^T

over the updates in the window not yet accounted for (each once), with the one-sample
covariance-matching estimate of :math:`R^{true}_j - R_j` (clipped at 0, so conservative).
A rise caught after one sample adds one sample's worth; a rise caught late adds the whole
lag's. Falling ``R`` never shrinks ``P``. ``inflate=False`` leaves ``P`` alone.

(A simpler remedy, ``P`` multiplied by the ratio of the new ``R`` to the old one,
suits a late estimate only: scaling ``P`` and ``R`` together keeps the old gain, so with
the rise caught after one sample it kept taking the x20 noise at the nominal gain, and
on separate seeds it was worse than no inflation.)

Settings from first principles, not fitted: ``alpha = 1e-4`` (a false alarm about once
per 10^4 updates and component with the right noise), ``window = 30`` (3 s at 10 Hz; the
estimate's relative standard deviation is :math:`\sqrt{2/30}` = 26 %), ``min_samples =
10`` before the first test. ``R_min`` (default: ``R`` at the first update, the sensor's
specification) floors the estimate, so the filter never trusts a sensor more than its
specification. Only the diagonal of ``R`` adapts: ``R = R_min + diag(d)``, ``d >= 0``,
which stays positive definite.

What it costs: per update one ring-buffer write, a few length-``dim_z`` operations and
the products ``F G`` and ``(I - K H) G`` over the window's ``(window, dim_x, dim_z)``
sensitivities (``H`` and ``h(x)`` are evaluated once, as in the plain EKF); the change
point and the ``P`` correction only when the test rejects. On the 6-state DR model that
is about 0.1 ms of Python per step, 2-2.5x filterpy's EKF (``benchmarks/bench_aekf.py``).

What it cannot do: it takes innovations from manoeuvres the model does not follow for
measurement noise (on a turning road ``R`` and ``P`` rise during the turns), and a
single wild outlier can raise ``R`` for up to a window.

References
----------
Mehra, R. K. (1972). Approaches to adaptive filtering. IEEE Trans. Automatic Control
17(5), 693-698.
Myers, K. A. and Tapley, B. D. (1976). Adaptive sequential estimation with unknown noise
statistics. IEEE Trans. Automatic Control 21(4), 520-523.
Mohamed, A. H. and Schwarz, K. P. (1999). Adaptive Kalman filtering for INS/GPS.
Journal of Geodesy 73, 193-203.
Basseville, M. and Nikiforov, I. V. (1993). Detection of Abrupt Changes: Theory and
Application. Prentice Hall.
Gelb, A. (ed.) (1974). Applied Optimal Estimation, ch. 7 (suboptimal filter design and
sensitivity analysis). MIT Press.
Bar-Shalom, Y., Li, X. R. and Kirubarajan, T. (2001). Estimation with Applications to
Tracking and Navigation. Wiley.

Examples
--------
A constant observed with noise of standard deviation 1 that becomes 5 at step 300:

>>> import numpy as np
>>> rng = np.random.default_rng(0)
>>> kf = AdaptiveExtendedKalmanFilter(1, 1)
>>> kf.x, kf.P, kf.Q, kf.R = np.zeros(1), np.eye(1), np.eye(1) * 1e-4, np.eye(1)
>>> sd = np.where(np.arange(600) < 300, 1.0, 5.0)
>>> for k in range(600):
...     kf.predict()
...     kf.update(np.array([2.0 + sd[k] * rng.standard_normal()]), lambda x: np.eye(1), lambda x: x)
...     if k == 299:
...         print(f"R before: {kf.R[0, 0]:.0f}")
R before: 1
>>> bool(15 < kf.R[0, 0] < 40), kf.n_inflations > 0
(True, True)
"""

from __future__ import annotations

import numpy as np
from filterpy.kalman import ExtendedKalmanFilter
from scipy.stats import chi2

from .._validation import check_covariance, check_positive, check_positive_int

__all__ = ["AdaptiveExtendedKalmanFilter"]


class AdaptiveExtendedKalmanFilter(ExtendedKalmanFilter):
    r"""filterpy's EKF with a diagonal ``R`` matched to its innovations, and ``P`` grown when ``R`` rises.

    See the module docstring for the equations and references.

    Parameters
    ----------
    dim_x, dim_z : int
        State and measurement sizes (filterpy's).
    dim_u : int
        Control input size (filterpy's).
    window : int
        Innovations in the moving window (30 = 3 s at 10 Hz).
    alpha : float
        Level of the two-sided :math:`\chi^2` test on each component of the window's
        normalised innovations; ``R`` changes only when it rejects, and then follows the
        innovations since the change until the window refills (``0 < alpha < 0.5``).
    min_samples : int, optional
        Innovations recorded before the first test; default ``min(10, window)``.
    inflate : bool
        When ``R`` rises, add to ``P`` the covariance that the window's measurements,
        processed with the old ``R``, put into the state (module docstring).
    adapt : bool
        ``False`` turns the adaptation off: the plain EKF.
    R_min : array-like of shape (dim_z, dim_z), optional
        Floor of ``R`` (positive definite); default ``R`` at the first update.

    Attributes
    ----------
    R : ndarray of shape (dim_z, dim_z)
        The noise in use, ``R_min + diag(d)`` with ``d >= 0`` once adapting.
    inflation : float
        ``trace(P)`` after the last update's inflation over ``trace(P)`` before (1.0 when none).
    n_inflations : int
        Updates at which ``P`` was inflated.
    nis : ndarray of shape (dim_z,)
        The last window statistic :math:`T_i` (NaN before ``min_samples`` innovations).

    Notes
    -----
    ``predict`` uses ``F`` as filterpy's does (``P = F P F^T + Q``), and the filter
    carries its window sensitivities with the same ``F``. ``predict_update`` is
    ``predict`` then ``update``.

    Examples
    --------
    >>> import numpy as np
    >>> kf = AdaptiveExtendedKalmanFilter(2, 1, window=20)
    >>> kf.x = np.array([0.0, 1.0]); kf.F = np.array([[1.0, 1.0], [0.0, 1.0]])
    >>> kf.predict()
    >>> kf.update(np.array([1.1]), lambda x: np.array([[1.0, 0.0]]), lambda x: x[:1])
    >>> kf.x.shape, kf.R.shape, kf.inflation
    ((2,), (1, 1), 1.0)
    """

    def __init__(self, dim_x, dim_z, dim_u=0, *, window=30, alpha=1e-4, min_samples=None,
                 inflate=True, adapt=True, R_min=None):
        super().__init__(dim_x, dim_z, dim_u)
        self.window = check_positive_int(window, "window")
        alpha = check_positive(alpha, "alpha")
        if not alpha < 0.5:
            raise ValueError(f"alpha must satisfy 0 < alpha < 0.5, got {alpha}")
        self.alpha = alpha
        if min_samples is None:
            min_samples = min(10, self.window)
        self.min_samples = check_positive_int(min_samples, "min_samples")
        if self.min_samples > self.window:
            raise ValueError(f"min_samples must be <= window ({self.window}), got {self.min_samples}")
        self.inflate = bool(inflate)
        self.adapt = bool(adapt)
        self.R_min = None if R_min is None else check_covariance(R_min, "R_min", dim_z)
        n = np.arange(1, self.window + 1)
        # upper/lower quantiles of chi2_n / n for n = 1..window innovations in the window
        self._hi = chi2.ppf(1.0 - alpha / 2.0, n) / n
        self._lo = chi2.ppf(alpha / 2.0, n) / n
        self.reset_window()
        self.inflation = 1.0
        self.n_inflations = 0

    def reset_window(self):
        """Forget the recorded innovations (e.g. after a known change of sensor)."""
        W, dz = self.window, self.dim_z
        self._buf = np.zeros((W, 2, dz))     # y_j^2 and diag(H P- H^T)_j
        self._r = np.full((W, dz), np.inf)   # diag(R) the update used (inf: not yet processed)
        self._due = np.zeros((W, dz), bool)  # excess not yet added to P
        self._G = np.zeros((W, self.dim_x, dz))
        self._sum = np.zeros((2, dz))        # sums of _buf over the valid slots
        self._count = 0                      # innovations recorded
        self._n = 0                          # of which in the window (the newest ones)
        self._settling = False               # re-estimating R after a detected change
        self.nis = np.full(dz, np.nan)

    def _newest(self, m):
        """Ring-buffer slots of the ``m`` newest innovations, newest first."""
        return (self._count - 1 - np.arange(m)) % self.window

    def predict(self, u=0):
        """filterpy's predict; the window's sensitivities are carried by ``F`` too."""
        super().predict(u)
        if self.adapt and self.inflate and self._count:
            self._G = np.matmul(self.F, self._G)

    def predict_update(self, z, HJacobian, Hx, args=(), hx_args=(), u=0):
        """``predict(u)`` then ``update(z, HJacobian, Hx, args=args, hx_args=hx_args)``."""
        self.predict(u)
        self.update(z, HJacobian, Hx, args=args, hx_args=hx_args)

    def update(self, z, HJacobian, Hx, R=None, args=(), hx_args=(), residual=np.subtract):
        """filterpy's EKF update, after matching ``R`` to the innovations (see the class).

        ``H`` and ``h(x)`` are evaluated once. An ``R`` passed here is used for this
        update as in filterpy and no adaptation is done; ``z=None`` skips the update.
        """
        self.inflation = 1.0
        if z is None:
            return super().update(None, HJacobian, Hx)
        if not isinstance(args, tuple):
            args = (args,)
        if not isinstance(hx_args, tuple):
            hx_args = (hx_args,)
        if np.isscalar(z) and self.dim_z == 1:
            z = np.asarray([z], float)
        H = HJacobian(self.x, *args)
        hx = Hx(self.x, *hx_args)
        if not self.adapt:
            return super().update(z, lambda *_: H, lambda *_: hx, R=R, residual=residual)
        r = residual(z, hx)
        y = np.reshape(r, -1)
        H2 = np.reshape(H, (self.dim_z, -1))
        i = self._count % self.window
        row = np.empty((2, self.dim_z))
        row[0] = y * y
        row[1] = ((H2 @ self.P) * H2).sum(axis=1)  # diag(H P- H^T)
        if self._n == self.window:  # the oldest leaves
            self._sum += row - self._buf[i]
        else:
            self._sum += row
            self._n += 1
        self._buf[i] = row
        self._r[i] = np.inf
        self._due[i] = False
        self._count += 1
        if i == self.window - 1 and self._n == self.window:  # refresh the sums (no drift)
            self._sum = self._buf.sum(axis=0)
        if R is None:
            self._adapt()
        super().update(z, lambda *_: H, lambda *_: hx, R=R, residual=lambda *_: r)
        R_used = self.R if R is None else (np.eye(self.dim_z) * R if np.isscalar(R) else R)
        self._r[i] = np.diag(R_used)
        self._due[i] = True
        if self.inflate:
            K = np.reshape(self.K, (-1, self.dim_z))
            self._G = np.matmul(self._I - K @ H2, self._G)
            self._G[i] = K

    def _adapt(self):
        if self.R_min is None:
            self.R_min = check_covariance(self.R, "R", self.dim_z)
        if self._count < self.min_samples:
            return
        n = self._n
        y2, hph = self._sum / n
        r_old = np.diag(self.R)
        r_min = np.diag(self.R_min)
        self.nis = nis = y2 / (hph + r_old)
        if self._settling:  # after a change: plain covariance matching until the window refills
            move = np.ones(self.dim_z, bool)
            self._settling = n < self.window
        else:
            up, down = nis > self._hi[n - 1], nis < self._lo[n - 1]
            move = up | down
            if not move.any():
                return
            # the change point: the newest m innovations that best explain the rejection
            # (generalised likelihood ratio of a variance change, summed over components)
            slots = self._newest(n)
            u = self._buf[slots, 0] / (self._buf[slots, 1] + r_old)
            m_ = np.arange(1, n + 1)[:, None]
            lam = np.maximum(np.cumsum(u, axis=0) / m_, 1e-300)
            ok = np.where(up, lam > 1.0, lam < 1.0) & move
            llr = np.where(ok, 0.5 * m_ * (lam - 1.0 - np.log(lam)), 0.0).sum(axis=1)
            m = int(np.argmax(llr)) + 1
            keep = self._buf[slots[:m]].sum(axis=0)
            y2, hph = keep / m
            r_new = np.where(move, np.maximum(y2 - hph, r_min), r_old)
            if np.array_equal(r_new, r_old):
                return
            self._n, self._sum = m, keep
            self._settling = m < self.window
        r_new = np.where(move, np.maximum(y2 - hph, r_min), r_old)
        if np.array_equal(r_new, r_old):
            return
        rise = r_new > r_old
        self.R = self.R_min + np.diag(r_new - r_min)
        if self.inflate and rise.any():
            slots = self._newest(self._n)
            due = self._due[slots] & rise  # processed, not yet accounted for, rising components
            b = self._buf[slots]
            excess = np.where(due, np.maximum(b[:, 0] - b[:, 1] - self._r[slots], 0.0), 0.0)
            self._due[slots] &= ~rise
            if np.any(excess > 0):
                G = self._G[slots]
                tr = np.trace(self.P)
                self.P = self.P + np.einsum("wik,wk,wjk->ij", G, excess, G)
                self.inflation = float(np.trace(self.P) / tr)
                self.n_inflations += 1
