"""Kalman-type filters, in ``filterpy.kalman``'s image.

``from filterwnn.kalman import MinimalSkewSigmaPoints`` as ``from filterpy.kalman import
MerweScaledSigmaPoints``: the reduced sigma-point sets (:mod:`.sigma_points`), the package's
named point-set presets, its one home of point settings (:mod:`.presets`), the unscented filter
with vectorized model calls and loud covariance errors (:mod:`.unscented`), the
innovation-adaptive EKF (:mod:`.adaptive`), the batched Kalman step of N Gaussians at once
(:mod:`.batched`) and the banks of independent filters built on it (:mod:`.bank`).
"""

from .._lazy import lazy_exports

_EXPORTS = {
    "sigma_points": "sigma_points",
    "unscented": "unscented",
    "adaptive": "adaptive",
    "presets": "presets",
    "batched": "batched",
    "bank": "bank",
    "MinimalSkewSigmaPoints": "sigma_points:MinimalSkewSigmaPoints",
    "SphericalSimplexSigmaPoints": "sigma_points:SphericalSimplexSigmaPoints",
    "POINT_PRESETS": "presets:POINT_PRESETS",
    "make_points": "presets:make_points",
    "UnscentedKalmanFilter": "unscented:UnscentedKalmanFilter",
    "AdaptiveExtendedKalmanFilter": "adaptive:AdaptiveExtendedKalmanFilter",
    "KalmanModel": "batched:KalmanModel",
    "UnscentedStep": "batched:UnscentedStep",
    "ExtendedStep": "batched:ExtendedStep",
    "LinearStep": "batched:LinearStep",
    "UnscentedKalmanFilterBank": "bank:UnscentedKalmanFilterBank",
    "ExtendedKalmanFilterBank": "bank:ExtendedKalmanFilterBank",
    "KalmanFilterBank": "bank:KalmanFilterBank",
}
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
__all__ = [k for k, v in _EXPORTS.items() if ":" in v]
