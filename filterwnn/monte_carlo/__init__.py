"""Monte Carlo filters, in ``filterpy.monte_carlo``'s image.

Resampling schemes (:mod:`.resampling`), the proposal protocol and its Kalman proposals
(:mod:`.proposals`), the particle filter and its presets (:mod:`.particle_filter`), the
Gaussian-sum filter, a weighted bank of Kalman filters (:mod:`.gaussian_sum`), and the SMC
sampler of static parameters with its MCMC moves (:mod:`.smc`).
"""

from .._lazy import lazy_exports

_EXPORTS = {
    "resampling": "resampling",
    "proposals": "proposals",
    "particle_filter": "particle_filter",
    "gaussian_sum": "gaussian_sum",
    "smc": "smc",
    "resample": "resampling:resample",
    "systematic_resample": "resampling:systematic_resample",
    "stratified_resample": "resampling:stratified_resample",
    "residual_resample": "resampling:residual_resample",
    "multinomial_resample": "resampling:multinomial_resample",
    "effective_sample_size": "resampling:effective_sample_size",
    "ParticleFilter": "particle_filter:ParticleFilter",
    "BootstrapParticleFilter": "particle_filter:BootstrapParticleFilter",
    "ExtendedKalmanParticleFilter": "particle_filter:ExtendedKalmanParticleFilter",
    "UnscentedParticleFilter": "particle_filter:UnscentedParticleFilter",
    "SimplexUnscentedParticleFilter": "particle_filter:SimplexUnscentedParticleFilter",
    "DegeneracyWarning": "particle_filter:DegeneracyWarning",
    "PriorProposal": "proposals:PriorProposal",
    "ExtendedKalmanProposal": "proposals:ExtendedKalmanProposal",
    "UnscentedKalmanProposal": "proposals:UnscentedKalmanProposal",
    "GaussianSumFilter": "gaussian_sum:GaussianSumFilter",
    "RowsTarget": "smc:RowsTarget",
    "MALAMove": "smc:MALAMove",
    "HMCMove": "smc:HMCMove",
    "smc_sampler": "smc:smc_sampler",
}
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
__all__ = [k for k in _EXPORTS if k not in ("resampling", "proposals", "particle_filter", "gaussian_sum", "smc")]
