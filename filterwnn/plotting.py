"""Figures drawn from study results (the studies themselves never plot).

Every function takes a result object or plain arrays, draws with matplotlib's
object-oriented API on a new figure (or a given ``ax``), and returns the figure; saving
is the caller's business. Import matplotlib lazily so the package imports headless.
"""

from __future__ import annotations

__all__ = []

# --- sigma points and particle filters (issues 3-4) ---

# --- WNN study (issue 5) ---

# --- dead-reckoning study (issue 6) ---
