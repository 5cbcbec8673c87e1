"""filterwnn: reduced sigma points, particle filters, filter-trained wavelet networks
and GPS/DR navigation, on top of filterpy.

The public API is the names in ``__all__``; everything else is private or lives in its
module (``filterwnn.sigma_points``, ``filterwnn.particle_filter``, ...).
"""

__version__ = "0.1.0"

# Primitives: errors, angles, sigma points, resampling, the wavelet network.
from . import angles, wnn
from ._validation import NumericalError
from .angles import angle_mean, angle_residual
from .resampling import resample
from .sigma_points import MinimalSkewSigmaPoints, SphericalSimplexSigmaPoints

# Models: the state-space protocol, the benchmarks, dead reckoning and its scenarios,
# the WNN weights as a state.
from .dead_reckoning import DRModel, GPSDRModel, dr_residual, dr_z_mean, wrap_angle
from .models import GammaNoiseModel, LinearGaussianModel, StateSpaceModel
from .scenarios import SCENARIOS as DR_SCENARIOS, DRRun, Scenario, read_drive_csv, simulate_scenario
from .weight_model import WNNWeightModel

# Algorithms: Kalman-type filters, particle filters and their proposals, SMC samplers
# of static weights, the trained filters and the WNN estimator.
from . import smc
from .adaptive import AdaptiveExtendedKalmanFilter
from .gaussian_sum import GaussianSumFilter
from .gpsdr import GPSDRFilter
from .neural_filter import NeuralFilter
from .particle_filter import (
    BootstrapParticleFilter,
    DegeneracyWarning,
    ExtendedKalmanParticleFilter,
    ParticleFilter,
    SimplexUnscentedParticleFilter,
    UnscentedParticleFilter,
)
from .proposals import ExtendedKalmanProposal, PriorProposal, UnscentedKalmanProposal
from .regressor import WNNRegressor
from .smc import HMCMove, MALAMove, RowsTarget, smc_sampler
from .unscented import UnscentedKalmanFilter

# Data for the studies.
from .datasets import make_siso_benchmark

__all__ = [
    "__version__",
    # primitives
    "NumericalError",
    "angles",
    "angle_residual",
    "angle_mean",
    "MinimalSkewSigmaPoints",
    "SphericalSimplexSigmaPoints",
    "resample",
    "wnn",
    # models
    "StateSpaceModel",
    "GammaNoiseModel",
    "LinearGaussianModel",
    "DR_SCENARIOS",
    "DRModel",
    "GPSDRModel",
    "Scenario",
    "dr_residual",
    "dr_z_mean",
    "simulate_scenario",
    "wrap_angle",
    "DRRun",
    "read_drive_csv",
    "WNNWeightModel",
    # algorithms
    "UnscentedKalmanFilter",
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
    "smc",
    "RowsTarget",
    "MALAMove",
    "HMCMove",
    "smc_sampler",
    "WNNRegressor",
    "NeuralFilter",
    "AdaptiveExtendedKalmanFilter",
    "GPSDRFilter",
    # data
    "make_siso_benchmark",
]
