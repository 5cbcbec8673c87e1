"""filterwnn: reduced sigma points, particle filters, filter-trained wavelet networks
and GPS/DR navigation, on top of filterpy.

The public API is the names in ``__all__``; everything else is private or lives in its
module (``filterwnn.sigma_points``, ``filterwnn.particle_filter``, ...).
"""

__version__ = "0.1.0"

from ._validation import NumericalError
from .models import GammaNoiseModel, LinearGaussianModel, StateSpaceModel

# --- sigma points and the unscented filter (issue 3) ---
from . import angles
from .angles import angle_mean, angle_residual
from .sigma_points import MinimalSkewSigmaPoints, SphericalSimplexSigmaPoints
from .unscented import UnscentedKalmanFilter

# --- particle filters (issue 4) ---
from .gaussian_sum import GaussianSumFilter
from .particle_filter import (
    BootstrapParticleFilter,
    DegeneracyWarning,
    ExtendedKalmanParticleFilter,
    ParticleFilter,
    SimplexUnscentedParticleFilter,
    UnscentedParticleFilter,
)
from .proposals import ExtendedKalmanProposal, PriorProposal, UnscentedKalmanProposal
from .resampling import resample

# --- wavelet networks (issue 5) ---
from . import wnn
from .datasets import make_siso_benchmark
from .regressor import WNNRegressor
from .weight_model import WNNWeightModel

# --- posterior samples of static weights (issue 13) ---
from . import smc
from .smc import HMCMove, MALAMove, RowsTarget, smc_sampler

# --- dead reckoning (issue 6) ---
from .dead_reckoning import (
    SCENARIOS as DR_SCENARIOS,
    DRModel,
    GPSDRModel,
    Scenario,
    dr_residual,
    dr_z_mean,
    simulate_scenario,
    wrap_angle,
)
from .neural_filter import NeuralFilter

# --- adaptive EKF (issue 14) ---
from .adaptive import AdaptiveExtendedKalmanFilter
# --- GPS/DR on one's own drive (issue 14) ---
from .gpsdr import GPSDRFilter
from .scenarios import DRRun, read_drive_csv

__all__ = [
    "__version__",
    "NumericalError",
    "StateSpaceModel",
    "GammaNoiseModel",
    "LinearGaussianModel",
    # --- issue 3 ---
    "MinimalSkewSigmaPoints",
    "SphericalSimplexSigmaPoints",
    "UnscentedKalmanFilter",
    "angles",
    "angle_residual",
    "angle_mean",
    # --- issue 4 ---
    "ParticleFilter",
    "DegeneracyWarning",
    "GaussianSumFilter",
    "BootstrapParticleFilter",
    "ExtendedKalmanParticleFilter",
    "UnscentedParticleFilter",
    "SimplexUnscentedParticleFilter",
    "PriorProposal",
    "ExtendedKalmanProposal",
    "UnscentedKalmanProposal",
    "resample",
    # --- issue 5 ---
    "wnn",
    "make_siso_benchmark",
    "WNNRegressor",
    "WNNWeightModel",
    # --- issue 13 ---
    "smc",
    "RowsTarget",
    "MALAMove",
    "HMCMove",
    "smc_sampler",
    # --- issue 6 ---
    "DR_SCENARIOS",
    "DRModel",
    "GPSDRModel",
    "Scenario",
    "dr_residual",
    "dr_z_mean",
    "simulate_scenario",
    "wrap_angle",
    "NeuralFilter",
    # --- issue 14 ---
    "AdaptiveExtendedKalmanFilter",
    "GPSDRFilter",
    "DRRun",
    "read_drive_csv",
]
