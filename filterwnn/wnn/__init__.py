"""Wavelet neural networks trained by filters.

The network itself (:mod:`.network`: wavelets, ``forward``, ``jacobian``, ``pack``/``unpack``,
initialisations; its functions are also exported here, so ``filterwnn.wnn.forward`` works as
it always has), its weight vector as a filter state (:mod:`.weight_model`), the trainers
(:mod:`.trainers`: how each filter trains the weights), their predictive distributions
(:mod:`.predictive`) and the scikit-learn estimator
:class:`~filterwnn.wnn.regressor.WNNRegressor` (:mod:`.regressor`; scikit-learn is imported
on first use).
"""

from .._lazy import lazy_exports
from .network import (  # the network's functions, here since filterwnn.wnn was one module
    DILATION_FLOOR,
    WAVELETS,
    forward,
    init_paper,
    init_scaled,
    jacobian,
    mexican_hat,
    mexican_hat_derivative,
    morlet,
    morlet_derivative,
    n_params,
    pack,
    unpack,
)

_EXPORTS = {
    "network": "network",
    "weight_model": "weight_model",
    "trainers": "trainers",
    "predictive": "predictive",
    "regressor": "regressor",
    "WNNWeightModel": "weight_model:WNNWeightModel",
    "WNNRegressor": "regressor:WNNRegressor",
    "TrainerSpec": "trainers:TrainerSpec",
    "register_trainer": "trainers:register_trainer",
    "get_trainer": "trainers:get_trainer",
}
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
__all__ = [
    "forward", "jacobian", "pack", "unpack", "n_params", "init_paper", "init_scaled", "morlet",
    "morlet_derivative", "mexican_hat", "mexican_hat_derivative", "WAVELETS", "DILATION_FLOOR",
    "WNNWeightModel", "WNNRegressor", "TrainerSpec", "register_trainer", "get_trainer",
]
