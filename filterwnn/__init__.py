"""filterwnn: reduced sigma points, particle filters, filter-trained wavelet networks
and GPS/DR navigation, on top of filterpy.

The package reads like filterpy, one subpackage per family::

    filterwnn.kalman        sigma-point sets, the UKF, the adaptive EKF, the batched Kalman step
    filterwnn.monte_carlo   resampling, proposals, particle filters, the Gaussian-sum filter, SMC
    filterwnn.wnn           the wavelet network, its weights as a state, trainers, WNNRegressor
    filterwnn.navigation    dead-reckoning models, the GPS/DR filter, the neural filter, drives
    filterwnn.studies       the two papers' studies, their runner and plots

over root primitives (``angles``, ``models``, ``datasets``, ``metrics``). Every public name is
also exported here (``filterwnn.MinimalSkewSigmaPoints``), imported on first use so that
``import filterwnn`` stays cheap. The flat module paths of earlier versions
(``filterwnn.kalman.sigma_points``, ``filterwnn.monte_carlo.particle_filter``, ...) still import, with a
``DeprecationWarning`` naming the new path.
"""

__version__ = "0.2.0"

from ._lazy import install_moved, lazy_exports
from ._validation import NumericalError

#: Old flat module -> its home in the subpackages (``scenarios``: its readers went to ``drives``).
MOVED_MODULES = {
    "sigma_points": "kalman.sigma_points",
    "unscented": "kalman.unscented",
    "adaptive": "kalman.adaptive",
    "resampling": "monte_carlo.resampling",
    "proposals": "monte_carlo.proposals",
    "particle_filter": "monte_carlo.particle_filter",
    "gaussian_sum": "monte_carlo.gaussian_sum",
    "smc": "monte_carlo.smc",
    "weight_model": "wnn.weight_model",
    "trainers": "wnn.trainers",
    "regressor": "wnn.regressor",
    "dead_reckoning": "navigation.dead_reckoning",
    "gpsdr": "navigation.gpsdr",
    "neural_filter": "navigation.neural_filter",
    "scenarios": ("navigation.scenarios", "navigation.drives"),
    "plotting": "studies.plotting",
}
install_moved(__name__, MOVED_MODULES)

_EXPORTS = {
    # subpackages and root modules
    "kalman": "kalman",
    "monte_carlo": "monte_carlo",
    "wnn": "wnn",
    "navigation": "navigation",
    "studies": "studies",
    "angles": "angles",
    "models": "models",
    "datasets": "datasets",
    "metrics": "metrics",
    "smc": "monte_carlo.smc",
    # primitives
    "angle_mean": "angles:angle_mean",
    "angle_residual": "angles:angle_residual",
    "MinimalSkewSigmaPoints": "kalman.sigma_points:MinimalSkewSigmaPoints",
    "SphericalSimplexSigmaPoints": "kalman.sigma_points:SphericalSimplexSigmaPoints",
    "resample": "monte_carlo.resampling:resample",
    "POINT_PRESETS": "kalman.presets:POINT_PRESETS",
    "make_points": "kalman.presets:make_points",
    # models
    "StateSpaceModel": "models:StateSpaceModel",
    "from_model": "models:from_model",
    "wire": "models:wire",
    "GammaNoiseModel": "models:GammaNoiseModel",
    "LinearGaussianModel": "models:LinearGaussianModel",
    "DR_SCENARIOS": "navigation.scenarios:SCENARIOS",
    "DRModel": "navigation.dead_reckoning:DRModel",
    "GPSDRModel": "navigation.dead_reckoning:GPSDRModel",
    "Scenario": "navigation.scenarios:Scenario",
    "dr_residual": "navigation.dead_reckoning:dr_residual",
    "dr_z_mean": "navigation.dead_reckoning:dr_z_mean",
    "simulate_scenario": "navigation.scenarios:simulate_scenario",
    "wrap_angle": "navigation.dead_reckoning:wrap_angle",
    "DRRun": "navigation.scenarios:DRRun",
    "read_drive_csv": "navigation.drives:read_drive_csv",
    "WNNWeightModel": "wnn.weight_model:WNNWeightModel",
    # algorithms
    "UnscentedKalmanFilter": "kalman.unscented:UnscentedKalmanFilter",
    "AdaptiveExtendedKalmanFilter": "kalman.adaptive:AdaptiveExtendedKalmanFilter",
    "UnscentedKalmanFilterBank": "kalman.bank:UnscentedKalmanFilterBank",
    "ExtendedKalmanFilterBank": "kalman.bank:ExtendedKalmanFilterBank",
    "KalmanFilterBank": "kalman.bank:KalmanFilterBank",
    "ParticleFilter": "monte_carlo.particle_filter:ParticleFilter",
    "DegeneracyWarning": "monte_carlo.particle_filter:DegeneracyWarning",
    "GaussianSumFilter": "monte_carlo.gaussian_sum:GaussianSumFilter",
    "BootstrapParticleFilter": "monte_carlo.particle_filter:BootstrapParticleFilter",
    "ExtendedKalmanParticleFilter": "monte_carlo.particle_filter:ExtendedKalmanParticleFilter",
    "UnscentedParticleFilter": "monte_carlo.particle_filter:UnscentedParticleFilter",
    "SimplexUnscentedParticleFilter": "monte_carlo.particle_filter:SimplexUnscentedParticleFilter",
    "PriorProposal": "monte_carlo.proposals:PriorProposal",
    "ExtendedKalmanProposal": "monte_carlo.proposals:ExtendedKalmanProposal",
    "UnscentedKalmanProposal": "monte_carlo.proposals:UnscentedKalmanProposal",
    "RowsTarget": "monte_carlo.smc:RowsTarget",
    "MALAMove": "monte_carlo.smc:MALAMove",
    "HMCMove": "monte_carlo.smc:HMCMove",
    "smc_sampler": "monte_carlo.smc:smc_sampler",
    "WNNRegressor": "wnn.regressor:WNNRegressor",
    "NeuralFilter": "navigation.neural_filter:NeuralFilter",
    "GPSDRFilter": "navigation.gpsdr:GPSDRFilter",
    # data
    "make_siso_benchmark": "datasets:make_siso_benchmark",
}

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)

__all__ = ["__version__", "NumericalError", *(k for k in _EXPORTS if k not in ("studies", "models", "datasets", "metrics", "monte_carlo", "kalman", "navigation"))]
