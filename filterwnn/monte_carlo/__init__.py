"""Monte Carlo filters, in ``filterpy.monte_carlo``'s image.

Resampling schemes (:mod:`.resampling`), the proposal protocol and its Kalman proposals
(:mod:`.proposals`), the particle filter and its presets (:mod:`.particle_filter`), the
Gaussian-sum filter, a weighted bank of Kalman filters (:mod:`.gaussian_sum`), and the SMC
sampler of static parameters with its MCMC moves (:mod:`.smc`).
"""

from .._lazy import lazy_exports, module_exports

_EXPORTS = module_exports({
    "resampling": ("resample", "systematic_resample", "stratified_resample", "residual_resample",
                   "multinomial_resample", "effective_sample_size"),
    "proposals": ("PriorProposal", "ExtendedKalmanProposal", "UnscentedKalmanProposal"),
    "particle_filter": ("ParticleFilter", "BootstrapParticleFilter", "ExtendedKalmanParticleFilter",
                        "UnscentedParticleFilter", "SimplexUnscentedParticleFilter", "DegeneracyWarning"),
    "gaussian_sum": ("GaussianSumFilter",),
    "smc": ("RowsTarget", "MALAMove", "HMCMove", "smc_sampler"),
})
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
__all__ = [name for name, target in _EXPORTS.items() if ":" in target]
