"""Argument types and shared options of the ``filterwnn`` command line.

Each function here is an argparse ``type=`` (or builds one): it turns the option's text
into a value or raises :class:`argparse.ArgumentTypeError`, which argparse prints as one
usage line and exit status 2, with no traceback. The study modules' ``add_arguments`` use
them so that a bad value (``--runs 0``, a misspelled ``--filters`` name) is refused
before any work starts, with the rule and the valid names in the message.

>>> positive_int("3")
3
>>> name_list(("ekf", "ukf"))("ukf, ekf")
['ukf', 'ekf']
>>> int_list()("")
[]
"""

from __future__ import annotations

import argparse
import math
import warnings

__all__ = [
    "HelpFormatter",
    "positive_int",
    "nonnegative_int",
    "seed",
    "joblib_jobs",
    "positive_float",
    "nonnegative_float",
    "float_list",
    "joblib_backend",
    "name_list",
    "int_list",
    "add_progress_flag",
]


class HelpFormatter(argparse.RawDescriptionHelpFormatter):
    """Help that shows each option's default unless its text already says it.

    Like :class:`argparse.ArgumentDefaultsHelpFormatter`, but it skips flags (default
    ``False``), options without a default (``None``) and help texts that already name
    their default, so no option shows two defaults; descriptions keep their line breaks.
    """

    def _get_help_string(self, action):
        text = action.help or ""
        default = action.default
        if (
            "default" in text
            or default is None
            or default is False
            or default is argparse.SUPPRESS
            or not action.option_strings
        ):
            return text
        return f"{text} (default: %(default)s)" if text else "default: %(default)s"


def _number(text, convert, ok, rule):
    """``convert(text)`` (``int`` or ``float``) when ``ok`` of it, else an argparse error naming the rule."""
    try:
        value = convert(text)
    except (TypeError, ValueError):
        noun = "an integer" if convert is int else "a number"
        raise argparse.ArgumentTypeError(f"must be {noun}, got {text!r}") from None
    if not ok(value):
        raise argparse.ArgumentTypeError(f"must be {rule}, got {text!r}")
    return value


def positive_int(text):
    """An integer ``>= 1``."""
    return _number(text, int, lambda v: v >= 1, "an integer >= 1")


def nonnegative_int(text):
    """An integer ``>= 0``."""
    return _number(text, int, lambda v: v >= 0, "an integer >= 0")


def seed(text):
    """A root seed for :class:`numpy.random.SeedSequence`: an integer ``>= 0``."""
    return nonnegative_int(text)


def joblib_jobs(text):
    """A joblib ``n_jobs``: ``>= 1`` workers, or negative (``-1``: all cores, ``-2``: all but one)."""
    return _number(text, int, lambda v: v != 0, ">= 1, or negative (-1: all cores)")


def positive_float(text):
    """A finite number ``> 0``."""
    return _number(text, float, lambda v: math.isfinite(v) and v > 0, "a finite number > 0")


def nonnegative_float(text):
    """A finite number ``>= 0``."""
    return _number(text, float, lambda v: math.isfinite(v) and v >= 0, "a finite number >= 0")


def fraction(text):
    """A number from 0 to 1."""
    return _number(text, float, lambda v: 0.0 <= v <= 1.0, "a number from 0 to 1")


def finite_float(text):
    """A finite number, of either sign."""
    return _number(text, float, math.isfinite, "a finite number")


def spans(text):
    """Comma-separated pairs of numbers ``>= 0``, each start before its end: spans of time ``start,end,...`` (s).

    >>> spans("240,480,900,960")
    [(240.0, 480.0), (900.0, 960.0)]
    """
    values = [nonnegative_float(s.strip()) for s in str(text).split(",") if s.strip()]
    if not values or len(values) % 2:
        raise argparse.ArgumentTypeError(f"expected comma-separated pairs of times start,end,... (s), got {text!r}")
    pairs = list(zip(values[::2], values[1::2]))
    for start, end in pairs:
        if start >= end:
            raise argparse.ArgumentTypeError(f"each span's start must come before its end, got {start:g},{end:g}")
    return pairs


def deviation_card(text):
    """Four comma-separated finite numbers, of either sign: a compass's deviation card ``B,C,D,E`` (deg).

    >>> deviation_card("3.9,2.3,-2.7,3.9")
    [3.9, 2.3, -2.7, 3.9]
    """
    values = [s.strip() for s in str(text).split(",")]
    if len(values) != 4:
        raise argparse.ArgumentTypeError(f"expected four comma-separated numbers B,C,D,E (degrees), got {text!r}")
    return [finite_float(v) for v in values]


def float_list(text):
    """Comma-separated finite numbers ``>= 0`` (``''``: an empty list).

    >>> float_list("40, 120.5")
    [40.0, 120.5]
    """
    return [nonnegative_float(s.strip()) for s in str(text).split(",") if s.strip()]


def output_folder(text):
    """A folder to write into: any path but an existing file, or one under an existing file (refused before a
    study runs, not when it writes its outputs)."""
    import os

    path = os.path.abspath(os.path.expanduser(str(text)))
    probe = path
    while probe and not os.path.exists(probe):
        parent = os.path.dirname(probe)
        if parent == probe:
            break
        probe = parent
    if os.path.exists(probe) and not os.path.isdir(probe):
        raise argparse.ArgumentTypeError(f"must be a folder, got {text!r}, and {probe!r} is a file")
    return str(text)


def remember_defaults(parser):
    """Keep the parser's defaults, as parsed (a list option's default is its text), with the options it gives
    (``args._defaults``): :func:`given` tells an option given from one left alone. Call it after the last
    option is added."""
    parser.set_defaults(_defaults=vars(parser.parse_args([])))


def given(args, dest):
    """Whether option ``dest`` was given a value other than its default (:func:`remember_defaults`; False for
    arguments that do not carry their defaults)."""
    defaults = getattr(args, "_defaults", {})
    return dest in defaults and getattr(args, dest) != defaults[dest]


def joblib_backend(text):
    """A joblib backend name registered with joblib (``loky``, ``threading``, ``dask``, ...)."""
    from joblib import parallel

    known = set(getattr(parallel, "BACKENDS", {})) | set(getattr(parallel, "EXTERNAL_BACKENDS", {}))
    if known and text not in known:
        raise argparse.ArgumentTypeError(f"unknown joblib backend {text!r}; valid: {', '.join(sorted(known))}")
    return text


def name_list(valid, allow_empty=False):
    """An argparse type for a comma-separated subset of ``valid`` (a list, in the given order).

    Parameters
    ----------
    valid : iterable of str
        The names accepted; the error message lists them.
    allow_empty : bool
        Accept an empty list (``''``).

    Returns
    -------
    callable
        ``str -> list of str``; raises :class:`argparse.ArgumentTypeError` for an unknown
        or repeated name.
    """
    valid = tuple(valid)

    def parse(text):
        names = [s.strip() for s in str(text).split(",") if s.strip()]
        if not names and not allow_empty:
            raise argparse.ArgumentTypeError(f"must name at least one of {', '.join(valid)}; got {text!r}")
        bad = [n for n in names if n not in valid]
        if bad:
            raise argparse.ArgumentTypeError(
                f"unknown name{'s' if len(bad) > 1 else ''} {', '.join(map(repr, bad))}; valid: {', '.join(valid)}")
        dup = sorted({n for n in names if names.count(n) > 1})
        if dup:
            raise argparse.ArgumentTypeError(f"names must not repeat, got {', '.join(map(repr, dup))} twice")
        return names

    parse.__name__ = "name list"  # argparse names the type in "invalid ... value" messages
    return parse


def int_list(minimum=1):
    """An argparse type for comma-separated integers ``>= minimum`` (``''``: an empty list)."""

    def parse(text):
        out = []
        for s in str(text).split(","):
            if not s.strip():
                continue
            try:
                value = int(s)
            except ValueError:
                raise argparse.ArgumentTypeError(
                    f"must be comma-separated integers, got {s.strip()!r} in {text!r}") from None
            if value < minimum:
                raise argparse.ArgumentTypeError(f"each value must be >= {minimum}, got {value} in {text!r}")
            out.append(value)
        return out

    parse.__name__ = "integer list"
    return parse


class _DeprecatedFlag(argparse.Action):
    """A hidden old spelling of a flag: sets the same destination and warns once."""

    def __init__(self, option_strings, dest, new=None, **kwargs):
        self.new = new
        super().__init__(option_strings, dest, nargs=0, default=argparse.SUPPRESS, **kwargs)

    def __call__(self, parser, namespace, values, option_string=None):
        warnings.warn(f"{option_string} is deprecated; use {self.new}", FutureWarning, stacklevel=2)
        setattr(namespace, self.dest, True)


def add_progress_flag(parser, *aliases):
    """Add ``--no-progress`` (the one progress flag of every command) to ``parser``.

    ``aliases`` are old spellings (``"--quiet"``) kept working but hidden from the help;
    they warn with a :class:`FutureWarning`. The parsed value is ``args.no_progress``.
    """
    parser.add_argument("--no-progress", action="store_true", help="no progress bar on stderr")
    for alias in aliases:
        parser.add_argument(alias, dest="no_progress", action=_DeprecatedFlag, new="--no-progress",
                            help=argparse.SUPPRESS)
