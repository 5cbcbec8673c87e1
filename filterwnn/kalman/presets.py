r"""Named sigma-point presets: the package's one home of point-set settings.

A sigma-point set is a class and three numbers: the spread ``alpha``, the centre's extra
covariance weight ``beta`` (2 is optimal for a Gaussian prior, 0 the unscaled transform)
and either ``kappa`` (van der Merwe's symmetric ``2n + 1`` set) or the centre weight ``w0``
(the ``n + 2`` spherical simplex). Every filter, trainer and study of the package that
builds points builds them here, by name, so that one setting has one definition and a
table row names the set it ran. The registry, printed from the code:

>>> for name, preset in POINT_PRESETS.items():
...     print(f"{name:12s} {preset.describe()}\n{'':12s} {preset.doc}")
merwe        MerweScaledSigmaPoints(alpha=1.0, beta=2.0, kappa=0.0)
             the UPF's (van der Merwe et al. 2000); Gaussian-sum UKFs; WNN ukf, upf, gsf-ukf
supf         SphericalSimplexSigmaPoints(alpha=1.0, beta=2.0, w0=0.0)
             the papers' SUPF (SimplexUnscentedParticleFilter); Gaussian-sum SUKFs
simplex      SphericalSimplexSigmaPoints(alpha=1.0, beta=0.0, w0=0.0)
             the unscaled set of Julier (2003); WNN sukf, supf, gsf-sukf
gpsdr-ukf    MerweScaledSigmaPoints(alpha=0.5, beta=2.0, kappa=0.0)
             GPSDRFilter kind "ukf"; the DR study's UKF and UPF
gpsdr-sukf   SphericalSimplexSigmaPoints(alpha=0.5, beta=2.0, kappa=0.0)
             GPSDRFilter kind "sukf"; the DR study's SUKF: gpsdr-ukf's sphere and weights
merwe-kappa  MerweScaledSigmaPoints(alpha=0.5, beta=2.0, kappa=3 - n)
             Julier and Uhlmann's n + kappa = 3; the command line's tour

The WNN trainers' simplex is the unscaled set (``beta = 0``), not the SUPF preset
(``beta = 2``): it is the set their searched settings and the WNN study's numbers were
measured with, and a trainer that used ``"supf"`` would be a new row of the study, not the
same one.

The GPS/DR SUKF takes the UKF's settings on ``n + 2`` points: with ``kappa = 0`` the
simplex's centre weight is ``w0 = 0`` (:func:`~filterwnn.kalman.sigma_points.centre_weight`),
so its centre weights are Merwe's and its outer points lie on Merwe's sphere, radius
``alpha sqrt(n)`` (1.5 sigma in the 9-state phone-grade filter). The earlier setting,
``alpha=1, beta=0, w0=0.2``, put them at ``sqrt(n / 0.8)`` (3.35 sigma): through the heading
model, points that far out gave the 1 Hz drive analog's filter (seed 1) a mean NIS of 3.21 on
its accepted fixes and 113 down-weighted ones (the EKF's and UKF's: 2.02 and none), its odometer
scale ran to 1.037 (true 1.015) and its outages ended 8.79 / 33.79 m off (median / max).

>>> import numpy as np
>>> pts = make_points("gpsdr-sukf", 3)
>>> type(pts).__name__, pts.num_sigmas(), pts.w0
('SphericalSimplexSigmaPoints', 5, 0.0)
>>> make_points("merwe", 2, alpha=0.5).alpha   # a setting the preset names may be overridden
0.5
>>> float(make_points("merwe-kappa", 4).kappa)
-1.0
>>> sorted(POINT_PRESETS)
['gpsdr-sukf', 'gpsdr-ukf', 'merwe', 'merwe-kappa', 'simplex', 'supf']

References
----------
R. van der Merwe, A. Doucet, N. de Freitas and E. Wan, "The unscented particle filter",
CUED/F-INFENG/TR 380, 2000.
S. J. Julier, "The spherical simplex unscented transformation", ACC 2003.
S. J. Julier and J. K. Uhlmann, "A new extension of the Kalman filter to nonlinear systems",
SPIE AeroSense 1997 (``kappa = 3 - n``).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from types import MappingProxyType

from filterpy.kalman import MerweScaledSigmaPoints

from .sigma_points import SphericalSimplexSigmaPoints

__all__ = ["PointPreset", "POINT_PRESETS", "make_points"]


@dataclass(frozen=True)
class PointPreset:
    """One named point set: its class and settings (a value may be a function of ``n``).

    Parameters
    ----------
    name : str
        The registry key.
    cls : type
        A filterpy-protocol sigma-point class, built as ``cls(n, **settings)``.
    settings : dict
        Keyword settings (``alpha``, ``beta``, ``kappa`` or ``w0``); a callable value is
        called with ``n``.
    doc : str
        Who uses the set (the module docstring lists it).
    """

    name: str
    cls: type
    settings: dict = field(default_factory=dict)
    doc: str = ""

    def __call__(self, n, **overrides):
        unknown = sorted(set(overrides) - set(self.settings))
        if unknown:
            raise TypeError(
                f"preset {self.name!r} sets {sorted(self.settings)}; {unknown} cannot be overridden "
                f"(build {self.cls.__name__} directly for other settings)"
            )
        kw = {k: (v(n) if callable(v) else v) for k, v in self.settings.items()}
        kw.update(overrides)
        return self.cls(n, **kw)

    def describe(self):
        """``Class(settings)``, one line (a setting that depends on ``n`` shows its rule)."""
        settings = ", ".join(f"{k}={v.__doc__ if callable(v) else v}" for k, v in self.settings.items())
        return f"{self.cls.__name__}({settings})"


def _three_minus_n(n):
    """3 - n"""
    return 3.0 - n


#: What each preset is for: the paper or filter that specifies it, and its users in the package.
_USES = {
    "merwe": "the UPF's (van der Merwe et al. 2000); Gaussian-sum UKFs; WNN ukf, upf, gsf-ukf",
    "supf": "the papers' SUPF (SimplexUnscentedParticleFilter); Gaussian-sum SUKFs",
    "simplex": "the unscaled set of Julier (2003); WNN sukf, supf, gsf-sukf",
    "gpsdr-ukf": 'GPSDRFilter kind "ukf"; the DR study\'s UKF and UPF',
    "gpsdr-sukf": 'GPSDRFilter kind "sukf"; the DR study\'s SUKF: gpsdr-ukf\'s sphere and weights',
    "merwe-kappa": "Julier and Uhlmann's n + kappa = 3; the command line's tour",
}

#: ``{name: PointPreset}``, read-only: every point set the package builds (module docstring).
POINT_PRESETS = MappingProxyType({name: PointPreset(name, cls, settings, _USES[name]) for name, cls, settings in (
    ("merwe", MerweScaledSigmaPoints, dict(alpha=1.0, beta=2.0, kappa=0.0)),
    ("supf", SphericalSimplexSigmaPoints, dict(alpha=1.0, beta=2.0, w0=0.0)),
    ("simplex", SphericalSimplexSigmaPoints, dict(alpha=1.0, beta=0.0, w0=0.0)),
    ("gpsdr-ukf", MerweScaledSigmaPoints, dict(alpha=0.5, beta=2.0, kappa=0.0)),
    ("gpsdr-sukf", SphericalSimplexSigmaPoints, dict(alpha=0.5, beta=2.0, kappa=0.0)),
    ("merwe-kappa", MerweScaledSigmaPoints, dict(alpha=0.5, beta=2.0, kappa=_three_minus_n)),
)})


def make_points(name, n, **overrides):
    """The sigma points of preset ``name`` for an ``n``-dimensional state.

    Parameters
    ----------
    name : str
        A key of :data:`POINT_PRESETS`.
    n : int
        State dimension.
    **overrides
        New values for settings the preset names (e.g. a searched ``alpha``).

    Returns
    -------
    points : sigma-point object
        ``MerweScaledSigmaPoints`` or :class:`~filterwnn.kalman.sigma_points.SphericalSimplexSigmaPoints`.

    Raises
    ------
    ValueError
        For an unknown name (the message lists the presets).
    TypeError
        For an override of a setting the preset does not name.
    """
    try:
        preset = POINT_PRESETS[name]
    except (KeyError, TypeError):
        raise ValueError(f"points preset must be one of {sorted(POINT_PRESETS)} (see "
                         f"filterwnn.kalman.presets), got {name!r}") from None
    return preset(n, **overrides)
