r"""Recorded drives: one's own CSV, the onavdata car drives, the shipped sample.

Each reader returns a :class:`~filterwnn.navigation.scenarios.DRRun` built by
:meth:`~filterwnn.navigation.scenarios.DRRun.from_arrays`, which validates it.

* :func:`read_drive_csv`: a CSV in the columns of :data:`DRIVE_CSV_COLUMNS`;
* :func:`sample_drive_path`: the simulated town drive shipped with the package;
* :func:`load_car_drive`: the onavdata HGuide n380 car drives (optional ``data`` extra).
"""

from __future__ import annotations

import contextlib
import csv
import datetime
import os
import re
import sys
import warnings

import numpy as np

from .._validation import check_positive, check_rng
from ._plausibility import HDOP_AS_METRES_MIN, HDOP_METRES_REMEDY, _run_bounds, hdop_as_metres
from .dead_reckoning import wrap_angle
from .scenarios import HEADING_ROUNDING, MAX_YAW_RATE, DRRun, Scenario, earth_radii, latlon_to_en, _null_fixes

__all__ = ["DRIVE_CSV_COLUMNS", "PROGRESS_BYTES", "read_drive_csv", "sample_drive_path", "load_car_drive", "CAR_DRIVE", "CAR_DRIVES",
           "MIN_ODOMETER_SPEED"]

#: The columns :func:`read_drive_csv` reads: ``{column: (unit, meaning)}``. ``time``, one of
#: ``heading``/``heading_deg``/``yaw_rate``/``yaw_rate_deg`` and one of ``speed``/``odometer`` are required; GPS columns
#: are empty on rows without a fix. Names are read whatever their case (``Time``, ``GPS_Lat``).
DRIVE_CSV_COLUMNS = {
    "time": ("s", "DR sample time, strictly increasing, evenly spaced (on a row with a fix alone, its heading and "
                  "speed empty: the fix's time); seconds, or ISO 8601 date-times (2021-04-27T10:00:00.1Z)"),
    "heading": ("rad", "heading from north, clockwise (or heading_deg in degrees)"),
    "heading_deg": ("deg", "heading from north, clockwise (instead of heading)"),
    "yaw_rate": ("rad/s", "the gyro's yaw rate, clockwise (a right turn) positive, instead of a heading: integrated by "
                          "the reader, its start the fixes' course (or yaw_rate_deg in deg/s)"),
    "yaw_rate_deg": ("deg/s", "the gyro's yaw rate, clockwise positive (instead of yaw_rate)"),
    "speed": ("m/s", "odometer / CAN speed (or odometer)"),
    "odometer": ("m", "cumulative odometer distance (instead of speed); each increment is the mean speed over its "
                      "interval, and each sample's speed is read between the two beside it"),
    "gps_east": ("m", "GPS fix east in a local frame (with gps_north), empty without a fix"),
    "gps_north": ("m", "GPS fix north"),
    "gps_lat": ("deg", "GPS fix latitude, WGS84 (with gps_lon; instead of gps_east/gps_north)"),
    "gps_lon": ("deg", "GPS fix longitude"),
    "gps_sigma": ("m", "optional: the fix's horizontal accuracy (standard deviation per axis: a phone's 68 % "
                       "radius over 1.51); a column empty on every fix is taken as absent, with a warning; empty, 0 or a "
                       "placeholder (a 99.9 repeated) on some fixes, those take their neighbours' accuracy, with a "
                       "warning"),
    "gps_hdop": ("dimensionless", "optional, instead of gps_sigma: the fix's horizontal dilution of precision (NMEA GGA's HDOP, "
                     "no unit); its sigma is the HDOP times read_drive_csv's hdop_sigma (m at HDOP 1)"),
    "true_east": ("m", "optional: reference east (with true_north), same frame as the fixes; a pair of truth "
                       "columns empty on every row is taken as absent, with a warning"),
    "true_north": ("m", "optional: reference north"),
    "true_lat": ("deg", "optional: reference latitude (with true_lon; needs gps_lat/gps_lon)"),
    "true_lon": ("deg", "optional: reference longitude"),
}


_DELIMITERS = (",", ";", "\t")
#: Files at least this large (bytes) show a progress bar while read when ``progress`` is None.
PROGRESS_BYTES = 20_000_000
_CHUNK = 8192  # rows per block of the growing column buffer


def _delimiter(path, first):
    """The header line's delimiter: comma, else semicolon, else tab (the first one present)."""
    for d in _DELIMITERS:
        if d in first:
            return d
    if len(first.split()) > 1 or "|" in first:
        raise ValueError(f"{path}: the header {first.strip()!r} is not split by a comma, semicolon or tab; "
                         "save the file as CSV with one of those delimiters")
    return ","


#: An ISO 8601 date and time (a logger's time stamp): date, time of day, its fraction, and Z or an offset.
_ISO_TIME = re.compile(r"^(\d{4}-\d\d-\d\d)[T ](\d\d:\d\d:\d\d)(?:[.,](\d+))?(Z|[+-]\d\d:?\d\d)?$")


def _iso_seconds(cell):
    """An ISO 8601 date and time (``2021-04-27T10:00:00.1Z``, ``2021-04-27 12:00:00.1+02:00``; without a zone
    taken as UTC) as seconds since 1970 UTC, or None when the cell is not one."""
    m = _ISO_TIME.match(cell)
    if m is None:
        return None
    date, clock, frac, zone = m.groups()
    try:
        stamp = datetime.datetime.fromisoformat(f"{date}T{clock}")
    except ValueError:
        return None
    if zone and zone != "Z":
        sign = 1 if zone[0] == "+" else -1
        stamp -= sign * datetime.timedelta(hours=int(zone[1:3]), minutes=int(zone[-2:]))
    whole = (stamp - datetime.datetime(1970, 1, 1)).total_seconds()
    return whole + (float("0." + frac) if frac else 0.0)


def _cell(path, h, cell, row, line):
    """One cell as a float (NaN when empty; in the time column an ISO 8601 date and time as seconds since
    1970 UTC); ValueError naming the file, column, row, line and rule."""
    cell = cell.strip()
    if cell == "":
        return np.nan
    try:
        v = float(cell)
    except ValueError:
        if h == "time" and (v := _iso_seconds(cell)) is not None:
            return v
        hint = ""
        if "," in cell:
            with contextlib.suppress(ValueError):
                float(cell.replace(",", "."))
                hint = " (a decimal comma? write 0.1, not 0,1)"
        raise ValueError(f"{path}: column {h!r} must hold numbers; data row {row} (line {line}) "
                         f"has {cell!r}{hint}") from None
    if not np.isfinite(v):
        raise ValueError(f"{path}: column {h!r} must hold finite numbers; data row {row} (line {line}) "
                         f"has {cell!r} (leave the "
                         "cell empty where a row has no value, e.g. no GPS fix)")
    return v


def _lines(fh, path, progress):
    """The file's lines, with a tqdm bar over its bytes when ``progress`` (None: large files on a terminal)."""
    size = os.path.getsize(path)
    if progress is None:
        progress = size >= PROGRESS_BYTES and sys.stderr.isatty()
    if not progress:
        yield from fh
        return
    from tqdm.auto import tqdm

    with tqdm(total=size, desc=f"reading {os.path.basename(path)}", unit="B", unit_scale=True) as bar:
        done = 0
        for k, line in enumerate(fh):
            done += len(line)
            if k % 4096 == 4095:
                bar.update(done)
                done = 0
            yield line
        bar.update(done)


def _read_columns(path, progress=None):
    """``(header, {column: floats, NaN where empty}, line numbers)`` of a drive CSV's known
    columns, read row by row (memory: the columns' floats); ValueError naming the file, the
    column, the line and the rule for an empty file, a repeated column or a bad cell."""
    try:
        with open(path, newline="", encoding="utf-8-sig") as fh:  # utf-8-sig: a BOM (Excel) is dropped
            first = fh.readline()
            if not first.strip():
                raise ValueError(f"{path}: the file is empty (expected a header row)")
            delim = _delimiter(path, first)
            header = [h.strip().lower() for h in next(csv.reader([first], delimiter=delim))]  # Time, GPS_Lat: as named
            named = [h for h in header if h]  # a trailing delimiter's unnamed columns are not read
            if len(set(named)) != len(named):
                raise ValueError(f"{path}: duplicated column names in the header {header}")
            known = [(i, h) for i, h in enumerate(header) if h in DRIVE_CSV_COLUMNS]
            idx = [i for i, _ in known]
            width = len(known) + 1  # the known columns and the line number
            chunks, buf, n, rows = [], np.empty((_CHUNK, width)), 0, 0
            for line, row in enumerate(csv.reader(_lines(fh, path, progress), delimiter=delim), start=2):
                if not any(c.strip() for c in row):
                    continue
                rows += 1
                try:  # the common row: every known cell a number or empty, no nan/inf spelled out
                    if any("n" in row[i] or "N" in row[i] for i in idx):
                        raise ValueError
                    buf[n, :-1] = [float(row[i]) if row[i].strip() else np.nan for i in idx]
                except (ValueError, IndexError):  # the slow path names the first bad cell, or pads
                    buf[n, :-1] = [_cell(path, h, row[i] if i < len(row) else "", rows, line) for i, h in known]
                buf[n, -1] = line
                n += 1
                if n == _CHUNK:
                    chunks.append(buf)
                    buf, n = np.empty((_CHUNK, width)), 0
    except UnicodeDecodeError as exc:
        raise ValueError(f"{path}: not UTF-8 text ({exc.reason} at byte {exc.start}); save it as CSV UTF-8") from None
    except csv.Error as exc:
        raise ValueError(f"{path}: not a readable CSV file ({exc})") from None
    data = np.concatenate(chunks + [buf[:n]]) if chunks else buf[:n]
    return header, {h: data[:, j] for j, (_, h) in enumerate(known)}, data[:, -1].astype(int)


def _csv_column(path, cols, lines, h, allow_empty=False):
    """Column ``h``; ValueError naming the line of its first empty cell unless ``allow_empty``."""
    out = cols[h]
    if not allow_empty and np.isnan(out).any():
        r = int(np.argmax(np.isnan(out)))
        raise ValueError(f"{path}: column {h!r} is empty on data row {r + 1} (line {lines[r]})")
    return out


def _located(path, exc, lines):
    """``exc``'s message prefixed by ``path``, with each ``t[k]``-style sample index given its line."""
    def line_of(m):
        k = int(m.group(2))
        return f"{m.group(0)} (line {lines[k]})" if k < len(lines) else m.group(0)

    msg = str(exc).replace("pass np.deg2rad(heading)", "name the column heading_deg, or write it in radians")
    msg = msg.replace("pass np.deg2rad(yaw_rate)", "name the column yaw_rate_deg, or write it in rad/s")
    return ValueError(f"{path}: " + re.sub(r"\b(t|heading|speed|distance)\[(\d+)\]", line_of, msg))


def read_drive_csv(path, *, origin=None, name=None, max_jitter=0.2, checks=True, progress=None, fill_gaps=0.0,
                   gps_latency=0.0, intervals="auto", odometer_latency=0.0, heading_offset=0.0, speed_scale=1.0,
                   hdop_sigma=None, heading_latency=0.0, heading_deviation=None, drop_fixes=None,
                   restamp_fixes=False):
    """Read one's own drive from a CSV file with the columns of :data:`DRIVE_CSV_COLUMNS`.

    One row per DR sample, a header row with the column names; a GPS fix is the row's
    ``gps_east``/``gps_north`` (or ``gps_lat``/``gps_lon``) at the row's ``time``, empty
    cells where there is none. A log with a row per sensor message is read too: rows with a
    fix alone (their heading and speed cells empty) are fixes at their own times, placed on
    the DR sample nearest each, and the rows with a heading and a speed are the DR samples; where the
    heading and the speed (or odometer) each come on rows of their own, the DR samples are the rows of the
    one with fewer, and the other is interpolated to their times (a heading along the shorter arc). With ``gps_lat``/``gps_lon`` and ``true_east``/``true_north``
    the truth must be about ``origin`` (default the first fix). Unknown columns are ignored.
    The delimiter is the header's comma, semicolon or tab; a UTF-8 byte-order mark (Excel's
    "CSV UTF-8") is dropped; decimal commas, ``nan`` and ``inf`` cells are refused (an empty
    cell is "no value"). The file is read row by row into the known columns' floats, so
    memory grows with the rows kept, not the text.

    >>> run = read_drive_csv(sample_drive_path())
    >>> run.z_dr.shape[1], run.scenario.dt, run.gps_sigma is not None
    (2, 0.1, True)

    Parameters
    ----------
    path : str or path-like
    origin, name, max_jitter, checks, fill_gaps, gps_latency, intervals, odometer_latency, heading_offset,
    speed_scale, heading_latency, heading_deviation, drop_fixes, restamp_fixes
        As :meth:`DRRun.from_arrays` (``checks``: the plausibility checks against the fixes;
        ``fill_gaps``: the longest gap of dropped DR samples, in s, to fill by interpolation;
        ``gps_latency``: the receiver's latency, s, by which each fix is older than its time;
        ``odometer_latency``: the same for the speed or odometer column; ``heading_latency``: for the heading
        (a heading averaged over each sample's interval is half an interval late);
        ``heading_offset``: degrees by which the heading reads clockwise of the car's course, subtracted;
        ``heading_deviation``: a compass's deviation card ``(B, C, D, E)``, degrees, subtracted after the offset;
        ``speed_scale``: the factor by which the speed or odometer reads more than the car drove, divided out;
        ``drop_fixes``: spans ``[(start, end), ...]``, s from the first row, whose fixes are dropped (fixes the
        plausibility check found dragged away from the dead-reckoned track: a spoofer's walk);
        ``restamp_fixes``: fixes stamped when the logger received them (the reader warns of them) placed on the
        receiver's regular grid of epochs, at the earliest arrivals;
        ``intervals``: the interval each speed sample covers, its stamped one or the stamps'
        regular grid's, ``"auto"`` choosing).
    progress : bool, optional
        A tqdm bar over the file's bytes; default one for files of :data:`PROGRESS_BYTES`
        or more when stderr is a terminal.
    hdop_sigma : float, optional
        With a ``gps_hdop`` column (a receiver's horizontal dilution of precision, as NMEA's GGA gives it, without
        a unit): the sigma per axis (m) of a fix at HDOP 1, the receiver's UERE / sqrt(2); each fix's
        ``gps_sigma`` is its HDOP times it. Required with that column (``filterwnn study dr --drive`` passes the
        grade's ``gps_sigma_m``); not used without it.

    Returns
    -------
    DRRun
        As :meth:`DRRun.from_arrays`.

    Raises
    ------
    ValueError
        Each naming the file and, where it applies, the column, the line and the rule: a
        missing or duplicated column, a cell that is not a finite number, fewer than 3
        rows, a latitude/longitude truth without a fix, or anything
        :meth:`DRRun.from_arrays` refuses (a failed plausibility check names its likely
        cause).
    """
    caught = []
    try:  # the reader's warnings, issued where they arise, are shown at the caller's line, not at one of ours
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            return _read_drive_csv(path, origin, name, max_jitter, checks, progress, fill_gaps, gps_latency, intervals,
                                   odometer_latency, heading_offset, speed_scale, hdop_sigma, heading_latency,
                                   heading_deviation, drop_fixes, restamp_fixes)
    finally:
        for w in caught:
            warnings.warn(w.message, w.category, stacklevel=2)


def _read_drive_csv(path, origin, name, max_jitter, checks, progress, fill_gaps, gps_latency, intervals,
                    odometer_latency, heading_offset, speed_scale, hdop_sigma, heading_latency, heading_deviation,
                    drop_fixes=None, restamp_fixes=False):
    """:func:`read_drive_csv`'s body."""
    path = str(path)
    header, cols, lines = _read_columns(path, progress)
    col, hname, dname = _csv_layout(path, header, lines)

    def column(h, allow_empty=False):
        return _csv_column(path, cols, lines, h, allow_empty)

    every_t = column("time")
    dr, fill = _dr_rows(path, cols, lines, hname, dname)
    if dr is not None:  # one row per sensor message: the DR samples are the rows with a heading and a speed
        rows, cols = cols, {h: v[dr] for h, v in cols.items()}
        every_lines, lines = lines, lines[dr]
        if fill is not None:  # the heading and the speed on rows of their own: the other read at these rows' times
            cols[fill] = _at_times(every_t[dr], every_t, rows[fill], fill)
        for h in _TRUTH:  # a reference with cells off the samples' rows (its own rows): read at the samples' times
            if h in rows and not np.isfinite(cols[h]).all() and np.isfinite(rows[h]).sum() >= 2:
                cols[h] = _at_times(every_t[dr], every_t, rows[h], h)

        def every(h, allow_empty=False):
            return _csv_column(path, rows, every_lines, h, allow_empty)
    else:
        every, every_lines = column, lines
    t = every_t if dr is None else every_t[dr]
    heading = np.deg2rad(_degrees(path, column(hname), hname)) if hname.endswith("_deg") else column(hname)
    kw = {"distance" if dname == "odometer" else "speed": column(dname)}
    if hname.startswith("yaw_rate"):  # integrated by the arrays' reader, started at the fixes' course
        kw["yaw_rate"], heading = heading, None
    kw.update(_csv_fixes(path, header, col, every, every_t, origin, every_lines,
                          None if hdop_sigma is None else check_positive(hdop_sigma, "hdop_sigma")))
    _csv_truth(path, header, col, column, origin, kw)
    try:
        run = DRRun.from_arrays(t, heading, name=name or os.path.splitext(os.path.basename(path))[0],
                                max_jitter=max_jitter, checks=checks, fill_gaps=fill_gaps, gps_latency=gps_latency,
                                intervals=intervals, odometer_latency=odometer_latency,
                                heading_offset=heading_offset, speed_scale=speed_scale,
                                heading_latency=heading_latency, heading_deviation=heading_deviation,
                                drop_fixes=drop_fixes, restamp_fixes=restamp_fixes, **kw)
    except ValueError as exc:
        hdop = (float(np.median(kw["gps_sigma"])) / hdop_sigma
                if "gps_hdop" in col and kw.get("gps_sigma") is not None and len(kw["gps_sigma"]) else 0.0)
        if str(exc).startswith("plausibility:") and hdop >= HDOP_AS_METRES_MIN:  # (the checks' stretches: 8 sigmas)
            exc = ValueError(f"{exc}. The fixes' gps_hdop has a median of {hdop:.3g}: read as an HDOP it makes each "
                             f"fix claim {hdop * hdop_sigma:.3g} m, and the checks measure stretches between fixes of "
                             f"eight times that; {HDOP_METRES_REMEDY}")
        raise _located(path, exc, lines) from None
    if checks and "gps_hdop" in col and kw.get("gps_sigma") is not None:
        words = hdop_as_metres(run, hdop_sigma)
        if words:
            warnings.warn(f"{path}: {words}", RuntimeWarning, stacklevel=3)
    return run


#: The share of the rows with a heading or a speed that have both, at least, for a log whose other rows hold one of
#: them to be warned of as cells left empty rather than a row per sensor message (:func:`_dr_rows`).
EMPTY_CELLS_BOTH = 0.9


def _dr_rows(path, cols, lines, hname, dname):
    """The rows that are DR samples when a drive CSV has one row per sensor message, and the column to read at
    their times, else ``(None, None)`` (every row has a heading and a speed, or no row is a fix alone and no
    sensor has rows of its own: the column checks name the first empty cell).

    A fix on a row of its own (its heading and speed cells empty) keeps its own time
    (:meth:`DRRun.from_arrays` places it on the DR sample nearest it). The DR samples are the rows with a
    heading and a speed; where the heading and the speed each come on rows of their own, they are the rows of the
    one with fewer, the other column read at their times (:func:`_at_times`) and returned as the second item. In
    such a log a row with a truth alone is a reference's (read at the samples' times); a row with no heading, no
    speed, no fix and no truth is refused, naming its line; in a log whose DR rows hold both, so is a row with one
    of them."""
    have_h, have_d = np.isfinite(cols[hname]), np.isfinite(cols[dname])
    dr = have_h & have_d
    if dr.all():
        return None, None
    fix = np.zeros_like(dr)
    for a, b in (("gps_east", "gps_north"), ("gps_lat", "gps_lon")):
        if a in cols and b in cols:
            fix |= np.isfinite(cols[a]) & np.isfinite(cols[b])
    alone = fix & ~have_h & ~have_d
    apart = (have_h & ~have_d).any() and (have_d & ~have_h).any()
    if not alone.any() and not apart:
        return None, None
    ref = _truth_alone(cols, have_h | have_d | fix)  # a reference on rows of its own, read at the samples' times
    if apart:  # each sensor on rows of its own: the samples are the rows of the one with fewer
        bad = ~have_h & ~have_d & ~fix & ~ref
        if bad.any():
            r = int(np.argmax(bad))
            raise ValueError(f"{path}: data row {r + 1} (line {lines[r]}) has no {hname!r}, no {dname!r} and no fix: "
                             f"in a log with a row per sensor message (the {hname!r} and the {dname!r} each on rows of "
                             "their own), every row is one of them, a fix or a truth")
        rows, other = (have_h, dname) if have_h.sum() <= have_d.sum() else (have_d, hname)
        only_h, only_d = have_h & ~have_d, have_d & ~have_h
        if dr.sum() >= EMPTY_CELLS_BOTH * (have_h | have_d).sum():  # nearly every row has both: cells left empty
            first = int(np.argmax(only_h | only_d))
            kept = hname if other == dname else dname
            warnings.warn(f"{path}: {int(only_h.sum())} row(s) have a {hname!r} but no {dname!r} and "
                          f"{int(only_d.sum())} a {dname!r} but no {hname!r}, among {int(dr.sum())} with both (the first "
                          f"at data row {first + 1}, line {lines[first]}): read as a log with a row per sensor message, "
                          f"the DR samples are the rows with a {kept!r}, the {other!r} read at their times (interpolated "
                          f"from the rows beside them), and the rows without a {kept!r} are not samples (a gap the "
                          "reader refuses or --fill-gaps fills). Empty cells of a logger that missed a value are read so "
                          "too: fill them in the file, or give each row both", RuntimeWarning, stacklevel=4)
        return rows, other
    bad = ~dr & ~alone & ~ref
    if bad.any():
        r = int(np.argmax(bad))
        what = (f"a {hname!r} but no {dname!r}" if have_h[r] else f"a {dname!r} but no {hname!r}" if have_d[r]
                else f"no {hname!r}, no {dname!r} and no fix")
        raise ValueError(f"{path}: data row {r + 1} (line {lines[r]}) has {what}: in a log with a row per sensor "
                         f"message (rows with a fix alone, as data row {int(np.argmax(alone)) + 1}), every other row is "
                         "a DR sample with both")
    return dr, None


_TRUTH = ("true_east", "true_north", "true_lat", "true_lon")


def _truth_alone(cols, other):
    """The rows with a truth cell and nothing ``other`` marks (a reference, an INS's, logged on rows of its own)."""
    have = np.zeros(len(other), dtype=bool)
    for h in _TRUTH:
        if h in cols:
            have |= np.isfinite(cols[h])
    return have & ~other


#: Heading units of loggers past degrees, the smallest factor first: (factor, the words).
_HEADING_SCALES = ((100.0, "centidegrees: divide by 100"),
                   (1e5, "1e-5 degrees (u-blox's headMot and headVeh): divide by 1e5"))


#: u-blox ESF-MEAS's gyro field: a signed 24-bit integer of 2^-12 deg/s, so its negative rates read unsigned lie
#: just under 4096 deg/s.
_ESF_GYRO_LSB = 2.0**-12
_ESF_GYRO_WRAP = 2.0**24 * _ESF_GYRO_LSB


def _rate_degrees(path, values, big):
    """``values`` of a ``yaw_rate_deg`` column, whose largest magnitude is ``big``; a ``ValueError`` past what a car
    turns (``MAX_YAW_RATE``, 3 rad/s), naming u-blox ESF-MEAS's raw gyro field (2^-12 deg/s) or its negative rates
    read unsigned where they fit."""
    limit = np.degrees(MAX_YAW_RATE)
    if big <= limit:
        return values
    v = values[np.isfinite(values)]
    if _ESF_GYRO_WRAP - limit <= big <= _ESF_GYRO_WRAP and abs(float(np.median(v))) <= limit:  # (mostly a car's)
        unit = (f"a signed 24-bit field (u-blox ESF-MEAS's gyro, 2^-12 deg/s) read unsigned: its negative rates lie "
                f"just under {_ESF_GYRO_WRAP:g} deg/s; subtract {_ESF_GYRO_WRAP:g} from the values past "
                f"{_ESF_GYRO_WRAP / 2:g}")
    elif big * _ESF_GYRO_LSB <= limit:
        unit = f"u-blox ESF-MEAS's raw gyro field, in 2^-12 deg/s: divide by {1 / _ESF_GYRO_LSB:g}"
    else:
        unit = None
    raise ValueError(f"{path}: column 'yaw_rate_deg' is in deg/s, and a car turns at under {limit:.0f} deg/s "
                     f"({MAX_YAW_RATE:g} rad/s); got max {big:g}" + (f": it reads as {unit}" if unit else ""))


def _degrees(path, values, name):
    """``values`` of the ``*_deg`` column ``name``; a ``ValueError`` where a heading's exceed 360 degrees (and
    their rounding), or a yaw rate's what a car turns (:func:`_rate_degrees`), naming a logger's scaled integers
    where they fit."""
    big = float(np.nanmax(np.abs(values))) if np.isfinite(values).any() else 0.0
    if name == "yaw_rate_deg":
        return _rate_degrees(path, values, big)
    if big <= 360.0 + np.degrees(HEADING_ROUNDING):
        return values
    unit = next((words for factor, words in _HEADING_SCALES if big / factor <= 360.0 + 1e-9), None)
    raise ValueError(f"{path}: column 'heading_deg' must be degrees (|heading_deg| <= 360), got max {big:g}"
                     + (f": it reads as {unit}" if unit else "")
                     + "; a heading unwrapped past a turn is given modulo 360")


def _at_times(t, every_t, values, name):
    """Column ``name`` (``values`` on every row, NaN where a row lacks it) read at the times ``t``: linearly
    interpolated between its own rows (a heading along the shorter arc; a cumulative odometer's distance, so
    that each step is what it counted), held beyond its first and last."""
    have = np.isfinite(values)
    src_t, src = every_t[have], values[have]
    if name in ("heading", "heading_deg"):
        period = 360.0 if name == "heading_deg" else 2 * np.pi
        return np.mod(np.interp(t, src_t, np.unwrap(src, period=period)), period)
    return np.interp(t, src_t, src)


#: Names loggers give the drive CSV's columns, for the reader's suggestions (:func:`_unread`); lowercase.
_ALIASES = {"latitude": "gps_lat", "longitude": "gps_lon", "lng": "gps_lon", "long": "gps_lon",
            "accuracy": "gps_sigma", "hacc": "gps_sigma", "horizontal_accuracy": "gps_sigma",
            "hdop": "gps_hdop", "dop": "gps_hdop",
            "velocity": "speed", "yaw": "heading", "timestamp": "time", "t": "time", "distance": "odometer"}


def _unread(header):
    """``{unread column: the known column it may be}``: a column of ``header`` the reader does not know whose name
    is a logger's usual one for a known column (:data:`_ALIASES`), a known GPS column's without its prefix
    (``east`` for ``gps_east``), or contains a known name (``speed_kmh``), where the header lacks that column."""
    known = [k for k in DRIVE_CSV_COLUMNS if k not in header]
    out = {}
    for h in header:
        if not h or h in DRIVE_CSV_COLUMNS:
            continue
        guess = _ALIASES.get(h) or ("gps_" + h if "gps_" + h in DRIVE_CSV_COLUMNS else None)
        if guess is None:
            inside = [k for k in known if k in h and len(k) >= 4]
            guess = max(inside, key=len) if inside else None
        if guess in known:
            out[h] = guess
    return out


def _suggest(unread, wanted):
    """The words a refusal or warning adds for the unread columns that may be ``wanted`` (known names)."""
    hits = [(h, k) for h, k in unread.items() if k in wanted]
    if not hits:
        return ""
    said = ", ".join(f"{h!r} may be {k!r} ({DRIVE_CSV_COLUMNS[k][0]}: {DRIVE_CSV_COLUMNS[k][1]}){_UNITS_OF.get(h, '')}"
                     for h, k in hits)
    return f"; the header's {said}: rename {'it' if len(hits) == 1 else 'them'} so"


#: What a logger's column named so holds, for :func:`_suggest`.
_UNITS_OF = {"hacc": " (u-blox's hAcc is in millimetres: divide by 1000)"}


def _csv_layout(path, header, lines):
    """``{column: index}`` of a drive CSV's ``header`` and the names of its heading and odometer
    columns; a ``ValueError`` when a required column is missing or doubled, or under 3 rows (naming a
    column that may be the missing one). Warns of unread columns that may be the fixes, their accuracy or
    the truth."""
    col = {h: i for i, h in enumerate(header)}
    unread = _unread(header)

    def need(*alts):
        have = [a for a in alts if a in col]
        if len(have) != 1:
            raise ValueError(f"{path}: needs exactly one of the columns {list(alts)}, found {have} in {header}"
                             + _suggest(unread, alts))
        return have[0]

    need("time")
    hname = need("heading", "heading_deg", "yaw_rate", "yaw_rate_deg")
    dname = need("speed", "odometer")
    if len(lines) < 3:
        raise ValueError(f"{path}: {len(lines)} data row{'s' * (len(lines) != 1)}; a drive needs at least 3 "
                         "(one row per DR sample, after the header)")
    # the fixes, their accuracy and the truth, but not the other form of a pair the header has
    pairs = (("gps_east", "gps_north"), ("gps_lat", "gps_lon"), ("true_east", "true_north"), ("true_lat", "true_lon"))
    given = {p[0][:4] for p in pairs if p[0] in col or p[1] in col}
    accuracy = [] if "gps_sigma" in col or "gps_hdop" in col else ["gps_sigma", "gps_hdop"]
    optional = accuracy + [k for p in pairs if p[0][:4] not in given for k in p]
    said = _suggest(unread, optional)
    if said:
        warnings.warn(f"{path}: columns the reader does not know are not read{said}", RuntimeWarning, stacklevel=3)
    return col, hname, dname


def _csv_fixes(path, header, col, column, t, origin, lines, hdop_sigma=None):
    """The GPS keywords of :meth:`DRRun.from_arrays` from a drive CSV's columns (none without
    GPS columns); ``column(name, allow_empty)`` reads one column. Each fix's accuracy is its ``gps_sigma`` (m), or its
    ``gps_hdop`` times ``hdop_sigma`` (m at HDOP 1)."""
    kw = {}
    pair = [p for p in (("gps_east", "gps_north"), ("gps_lat", "gps_lon")) if p[0] in col or p[1] in col]
    if len(pair) > 1:
        raise ValueError(f"{path}: give the fixes as gps_east/gps_north or gps_lat/gps_lon, not both")
    if not pair:
        return kw
    a, b = pair[0]
    if a not in col or b not in col:
        raise ValueError(f"{path}: the columns {a!r} and {b!r} go together; found only one in {header}")
    ga, gb = column(a, True), column(b, True)
    fix = np.isfinite(ga) & np.isfinite(gb)
    if np.any(np.isfinite(ga) != np.isfinite(gb)):
        r = int(np.argmax(np.isfinite(ga) != np.isfinite(gb)))
        raise ValueError(f"{path}: {a!r} and {b!r} must be both given or both empty; data row {r + 1} has one")
    kw["gps_t"] = t[fix]
    if a == "gps_east":
        kw["east"], kw["north"] = ga[fix], gb[fix]
    else:
        kw["lat"], kw["lon"] = ga[fix], gb[fix]
        kw["origin"] = origin
        _warn_coarse_coordinates(path, ga[fix], gb[fix])
    acc = [h for h in ("gps_sigma", "gps_hdop") if h in col]
    if len(acc) > 1:
        raise ValueError(f"{path}: give each fix's accuracy as 'gps_sigma' (m) or as 'gps_hdop' (no unit), not both")
    acc = acc[0] if acc else None
    gs = column(acc, True)[fix] if acc else None
    if gs is not None and gs.size and not np.any(np.isfinite(gs)):  # a logger's column the receiver never filled
        warnings.warn(f"{path}: column {acc!r} is empty on every fix: taken as absent, every fix gets the "
                      "grade's sigma (the filters' gps_sigma_m)", RuntimeWarning, stacklevel=4)
        gs = None
    if gs is not None:
        unit = "m" if acc == "gps_sigma" else "no unit"
        if a == "gps_lat":  # a receiver's null fixes (dropped, with a warning) need no accuracy: a tunnel's rows
            gs = np.where(_null_fixes(ga[fix], gb[fix]) & ~(gs > 0), 1.0, gs)  # written 0,0 with it empty (stop 59)
        gs = _unknown_accuracy(path, acc, gs, t[fix])
        if np.any(~np.isfinite(gs)):
            r = int(np.flatnonzero(fix)[np.argmax(~np.isfinite(gs))])
            raise ValueError(f"{path}: column {acc!r} is empty on data row {r + 1}, which has a fix (give "
                             "every fix its accuracy, or drop the column to give every fix the grade's sigma)")
        if np.any(gs <= 0):
            r = int(np.flatnonzero(fix)[np.argmax(gs <= 0)])
            raise ValueError(f"{path}: column {acc!r} must be > 0 ({unit}) where there is a fix; data row {r + 1} "
                             f"(line {lines[r]}) has {gs[gs <= 0][0]:g} (0 is how some receivers write 'unknown': "
                             "give that fix its accuracy, or drop the column to give every fix the grade's sigma)")
        if acc == "gps_hdop":
            if hdop_sigma is None:
                raise ValueError(
                    f"{path}: column 'gps_hdop' is a dilution of precision, without a unit: pass hdop_sigma, the "
                    "sigma per axis (m) of a fix at HDOP 1 (the receiver's UERE / sqrt(2)), and each fix's sigma is "
                    "its HDOP times it; `filterwnn study dr --drive` takes the grade's gps_sigma_m (5 m for "
                    "'phone') unless --hdop-sigma says otherwise")
            gs = gs * hdop_sigma
        kw["gps_sigma"] = gs
    return kw


#: The most decimals of a degree the drive reader looks for in the fixes' coordinates; written with this many or
#: fewer (10^-4 degree: 11.1 m of latitude), their rounding is warned of (stop 74: a seventh user's export wrote
#: '%.4f', and a fix repeated the last whenever the car drove less than a step, read as a receiver re-sending).
COARSE_DECIMALS = 4


def _decimals(values):
    """The fewest decimals (0-7) with which every one of ``values`` is written, or None past 7."""
    v = np.asarray(values, dtype=float)
    for d in range(8):
        scaled = v * 10.0**d
        if np.all(np.abs(scaled - np.round(scaled)) <= 1e-6 * np.maximum(1.0, np.abs(scaled) * 1e-9)):
            return d
    return None


def _warn_coarse_coordinates(path, lat, lon):
    """Warn where the fixes' latitudes and longitudes are written with :data:`COARSE_DECIMALS` decimals or fewer
    (20 fixes or more): a grid whose steps, in metres, the fixes' errors then carry as a uniform rounding."""
    lat, lon = np.asarray(lat, dtype=float), np.asarray(lon, dtype=float)
    ok = (lat != 0.0) | (lon != 0.0)  # (a receiver's null fixes, dropped with their own warning)
    if ok.sum() < 20:
        return
    d = max((_decimals(a[ok]) for a in (lat, lon)), key=lambda x: 8 if x is None else x)
    if d is None or d > COARSE_DECIMALS:
        return
    lat0 = np.radians(float(np.median(lat[ok])))
    rn, rm = earth_radii(lat0)
    north, east = np.radians(10.0**-d) * np.array([rm, rn * np.cos(lat0)])
    warnings.warn(f"{path}: the fixes' gps_lat and gps_lon are written with {d} decimals (steps of {north:.3g} m north "
                  f"and {east:.3g} m east here): their rounding adds {north / np.sqrt(12):.2g} m north and "
                  f"{east / np.sqrt(12):.2g} m east (standard deviations) to each fix's error, which no reported "
                  "accuracy includes, and a fix repeats the last one to the bit while the car moves less than a "
                  "step (the filters then drop it as a receiver's re-sent fix). Export the coordinates with 7 "
                  "decimals (1 cm) or more", RuntimeWarning, stacklevel=5)


#: The least share of the fixes (and number) whose accuracy cell reads a value for the others, empty, 0 or a
#: placeholder, to take their neighbours' (:func:`_unknown_accuracy`); fewer, and an empty or 0 cell is refused.
ACCURACY_KNOWN_SHARE = 0.5
ACCURACY_KNOWN_MIN = 10
#: A value the accuracy column repeats exactly on runs of at least this many fixes in a row ...
PLACEHOLDER_RUN = 10
#: ... at least this many times the median of its other values, and at least three times their largest, is a
#: placeholder (a logger's 99.9 where the NMEA or Android record had no accuracy), not a measurement: a receiver's
#: accuracy changes from fix to fix. The sixth user trial's drive with 99.9 on 37 % of its fixes, as good as the
#: others (1.8 m): EKF-8 4.90 / 30.46 m at the outage ends, the twin with the real sigmas 3.64 / 19.42, and the
#: same drive with those cells filled by hand 3.54 / 19.45 (stop 72).
PLACEHOLDER_FACTOR = 10.0


def _unknown_accuracy(path, acc, gs, tf):
    """The fixes' accuracy ``gs`` (at the fix times ``tf``) with the cells that say nothing (empty, 0 or less, or a
    placeholder: :data:`PLACEHOLDER_RUN`, :data:`PLACEHOLDER_FACTOR`) given their neighbours' (interpolated in time,
    in logarithms: the nearest known before and after), with one warning, where at least
    :data:`ACCURACY_KNOWN_SHARE` (and :data:`ACCURACY_KNOWN_MIN`) of the fixes read a value; otherwise ``gs`` as it
    is, which the caller refuses (stop 72: refused, a user dropped the column and every fix took the grade's 5 m)."""
    known = np.isfinite(gs) & (gs > 0)
    placeholder = np.zeros(len(gs), dtype=bool)
    vals, counts = np.unique(gs[known], return_counts=True)
    for v in vals[counts >= PLACEHOLDER_RUN]:
        others = known & (gs != v)
        if others.sum() < ACCURACY_KNOWN_MIN or not (v >= PLACEHOLDER_FACTOR * np.median(gs[others])
                                                     and v >= 3.0 * np.max(gs[others])):
            continue
        starts, ends = _run_bounds(gs == v)
        if np.max(ends - starts) >= PLACEHOLDER_RUN:
            placeholder |= gs == v
    good = known & ~placeholder
    bad = ~good
    if not bad.any() or good.sum() < max(ACCURACY_KNOWN_MIN, ACCURACY_KNOWN_SHARE * len(gs)):
        return gs
    filled = gs.copy()
    filled[bad] = np.exp(np.interp(tf[bad], tf[good], np.log(gs[good])))
    said = []
    if placeholder.any():
        v = float(gs[placeholder][0])
        starts, ends = _run_bounds(placeholder)
        said.append(f"reads {v:g} on {int(placeholder.sum())} fixes ({len(starts)} stretch(es), the first from t = "
                    f"{tf[starts[0]]:.10g} s to {tf[ends[0] - 1]:.10g} s), {v / np.median(gs[good]):.0f} times the "
                    f"median of its other values ({np.median(gs[good]):.3g}) and never near it: a placeholder a logger "
                    "writes where the receiver's record had no accuracy, not a measurement")
    empty = ~known
    if empty.any():
        said.append(f"is empty or 0 on {int(empty.sum())} fixes (the first at t = {tf[np.argmax(empty)]:.10g} s): "
                    "the receiver gave none")
    warnings.warn(f"{path}: column {acc!r} " + "; it ".join(said) + f". Those {int(bad.sum())} fixes take the "
                  "accuracy of the fixes beside them (interpolated in time), as good as their neighbours' (taken as "
                  "written, a placeholder's far larger sigma makes the filters all but ignore good fixes; dropping "
                  "the column gives every fix the grade's sigma). Fixes that really were that poor: give their "
                  "accuracy", RuntimeWarning, stacklevel=4)
    return filled


def _csv_truth(path, header, col, column, origin, kw):
    """Add the ``truth`` (and, for latitude/longitude, the ``origin``) of a drive CSV to the
    keywords ``kw`` of :meth:`DRRun.from_arrays`, when the CSV has truth columns."""
    for a, b in (("true_east", "true_north"), ("true_lat", "true_lon")):
        if (a in col) != (b in col):
            raise ValueError(f"{path}: the columns {a!r} and {b!r} go together; found only one in {header}")
        if a in col and not np.isfinite(column(a, True)).any() and not np.isfinite(column(b, True)).any():
            warnings.warn(f"{path}: the columns {a!r} and {b!r} are empty on every row: taken as absent (a drive "
                          "without a truth is scored against its own fixes)", RuntimeWarning, stacklevel=4)
            del col[a], col[b]  # a template's truth the logger never filled
    if "true_east" in col and "true_lat" in col:
        raise ValueError(f"{path}: give the truth as true_east/true_north or true_lat/true_lon, not both")
    if "true_east" in col:
        kw["truth"] = np.stack([column("true_east"), column("true_north")], axis=1)
    elif "true_lat" in col:
        if "lat" not in kw:
            raise ValueError(f"{path}: true_lat/true_lon need the fixes as gps_lat/gps_lon (one origin)")
        if origin is None and not len(kw["lat"]):
            raise ValueError(f"{path}: true_lat/true_lon are converted to metres about the first GPS fix, and the "
                             "file has none: give fixes, an origin, or the truth as true_east/true_north")
        if origin is None:  # the first fix that is not a receiver's null fix (dropped by DRRun.from_arrays)
            real = np.flatnonzero(~_null_fixes(kw["lat"], kw["lon"]))
            first = int(real[0]) if len(real) else 0
            kw["origin"] = origin = (kw["lat"][first], kw["lon"][first])
        kw["truth"] = np.stack(latlon_to_en(column("true_lat"), column("true_lon"), *origin), axis=1)


def sample_drive_path():
    """Path of the sample drive shipped with the package (``filterwnn/navigation/data/sample_drive.csv``).

    A simulated 3-minute town drive at 10 Hz: it starts from rest, stops at a light,
    turns, with 1 Hz GPS fixes as latitude/longitude and their accuracy (phone-like,
    3-6 m) and the truth, in the columns of :data:`DRIVE_CSV_COLUMNS`.
    """
    from importlib import resources

    return str(resources.files("filterwnn.navigation") / "data" / "sample_drive.csv")


# --------------------------------------------------------------------------- real drives

CAR_DRIVE = "2021-04-27C-car-hill-drive"
#: Reference speeds below this (m/s) give an odometer reading of 0 (standstill).
MIN_ODOMETER_SPEED = 0.05
#: The onavdata HGuide n380 car drives: the first is the development drive, the second is
#: kept back to check that settings carry over (see ``filterwnn.studies.dr``).
CAR_DRIVES = (CAR_DRIVE, "2021-03-29-automotive-stoplight-to-stoplight")


def _onav_dir(drive):
    try:
        import importlib.resources as resources

        root = resources.files("onavdata")
    except (ImportError, ModuleNotFoundError) as exc:
        raise ImportError(
            "the real-drive part needs the optional 'onavdata' package: pip install 'filterwnn[data]' "
            "(or pip install onavdata)"
        ) from exc
    d = root / "data" / "HGuide n380" / drive
    if not d.is_dir():
        raise ValueError(f"drive {drive!r} not found in onavdata (looked in {d})")
    return d


def _read_zipped_csv(folder, name):
    import io
    import zipfile

    with (folder / f"{name}.csv.zip").open("rb") as fh:
        zf = zipfile.ZipFile(io.BytesIO(fh.read()))
        with zf.open(zf.namelist()[0]) as f:
            header = [h.strip() for h in f.readline().decode().strip().split(",")]
            data = np.loadtxt(io.TextIOWrapper(f), delimiter=",", usecols=range(len(header)), ndmin=2)
    return {h: data[:, i] for i, h in enumerate(header)}


def load_car_drive(drive=CAR_DRIVE, dt=0.1, odometer_scale=1.02, odometer_noise=0.02, rng=0):
    """A real car drive from ``onavdata`` as a :class:`~filterwnn.navigation.scenarios.DRRun`.

    The HGuide n380 drives ship 100 Hz IMU increments, 1 Hz GNSS fixes and the
    INS/GNSS reference solution, as zipped CSV files read here through
    :mod:`importlib.resources` (``pip install onavdata``, the ``data`` extra).

    * truth: the reference INS position (latitude/longitude to local east/north metres
      about the first valid sample) and velocity, on a ``dt`` grid, rows with
      ``InsMode == 4`` only;
    * heading: the gyro's yaw, ``DeltaTheta[0]`` (the body down axis per the package's
      meta file; an angle increment per 100 Hz sample), integrated from the reference
      heading at the start -- so it drifts like a real DR gyro;
    * odometer: the car has none, so ``dt * odometer_scale * |v_ref| + noise`` (clipped
      at 0), a stated 2 % scale error by default -- never the GNSS speed, which an
      outage would take away too;
    * GPS: the receiver's 1 Hz fixes, each on its nearest grid step.

    Returns
    -------
    DRRun
        ``scenario`` describes the drive (``gps_rate=1``, no outages: cut them in with
        :func:`~filterwnn.navigation.scenarios.with_outage`).
    """
    rng = check_rng(rng)
    folder = _onav_dir(drive)
    pos = _read_zipped_csv(folder, "n380-position")
    vel = _read_zipped_csv(folder, "n380-velocity")
    att = _read_zipped_csv(folder, "n380-attitude")
    imu = _read_zipped_csv(folder, "n380-imu-nav")
    gnss = _read_zipped_csv(folder, "n380-gnss-pvt")
    ok = (pos["SystemTov"] > 0) & (pos["InsGnssBIT.InsMode"] == 4)
    tp = pos["SystemTov"][ok]
    lat, lon = pos["Latitude"][ok], pos["Longitude"][ok]
    en = _local_frame(lat, lon, pos["AltitudeAboveEllipsoid"][ok])
    t0 = tp[0]
    n = int((tp[-1] - t0) / dt) - 1
    t = t0 + dt * np.arange(1, n + 1)
    x_true, x0 = _car_truth(en(lat, lon), tp, vel, t, t0, dt)
    ve, vn = x_true[:, 1], x_true[:, 4]
    heading0, theta = _gyro_heading(att, imu, t, t0)
    speed = np.hypot(ve, vn)
    moving = speed > MIN_ODOMETER_SPEED  # a wheel odometer reads exactly 0 at standstill
    dist = np.where(moving, np.maximum(dt * odometer_scale * speed + odometer_noise * rng.standard_normal(n), 0.0), 0.0)
    z_dr = np.stack([wrap_angle(theta), dist], axis=1)
    steps, z_gps, gsig = _car_fixes(gnss, en, t0, dt, n)
    sc = Scenario(name=drive, duration=n * dt, dt=dt, speed=float(np.hypot(x0[1], x0[4])),
                  heading=float(np.degrees(heading0)), t_switch=np.inf, factor=1.0,
                  odometer_scale=odometer_scale, sigma_odometer=odometer_noise, gps_rate=1.0,
                  sigma_gps=1.0)
    R_true = np.tile([np.deg2rad(1.0) ** 2, odometer_noise**2], (n, 1))
    return DRRun(t - t0, x0, x_true, z_dr, steps, z_gps, R_true, sc, gsig)


def _local_frame(lat, lon, h):
    """``en(lat, lon)``: radians to local east/north metres about the first of ``lat, lon, h``."""
    lat0, lon0, h0 = lat[0], lon[0], h[0]
    rn, rm = earth_radii(lat0)

    def en(la, lo):
        return (lo - lon0) * (rn + h0) * np.cos(lat0), (la - lat0) * (rm + h0)

    return en


def _car_truth(ref_en, tp, vel, t, t0, dt):
    """The reference states on the grid ``t`` (positions ``ref_en`` at the times ``tp``, the
    velocity file's INS rows, accelerations by finite differences) and the state at ``t0``."""
    e_ref, n_ref = ref_en
    okv = (vel["SystemTov"] > 0) & (vel["InsGnssBIT.InsMode"] == 4)
    tv = vel["SystemTov"][okv]
    ve = np.interp(t, tv, vel["VelocityNED[1]"][okv])
    vn = np.interp(t, tv, vel["VelocityNED[0]"][okv])
    x_true = np.zeros((len(t), 6))
    x_true[:, 0] = np.interp(t, tp, e_ref)
    x_true[:, 3] = np.interp(t, tp, n_ref)
    x_true[:, 1], x_true[:, 4] = ve, vn
    x_true[:, 2] = np.gradient(ve, dt)
    x_true[:, 5] = np.gradient(vn, dt)
    x0 = np.array([np.interp(t0, tp, e_ref), np.interp(t0, tv, vel["VelocityNED[1]"][okv]), 0.0,
                   np.interp(t0, tp, n_ref), np.interp(t0, tv, vel["VelocityNED[0]"][okv]), 0.0])
    return x_true, x0


def _gyro_heading(att, imu, t, t0):
    """The reference heading at ``t0`` and the gyro heading on ``t``: the yaw increments
    integrated from it (so it drifts like a real DR gyro)."""
    oka = (att["SystemTov"] > 0) & (att["InsGnssBIT.InsMode"] == 4)
    heading0 = np.interp(t0, att["SystemTov"][oka], np.unwrap(att["EulerAttitude[2]"][oka]))
    ti = imu["SystemTov"]
    cum = np.cumsum(imu["DeltaTheta[0]"])
    return heading0, heading0 + np.interp(t, ti, cum) - np.interp(t0, ti, cum)


def _car_fixes(gnss, en, t0, dt, n):
    """The receiver's fixes, each on its nearest grid step (one per step): the steps, the
    fixes in local metres and each fix's reported accuracy per axis."""
    okg = (gnss["SystemTov"] > t0) & (gnss["InsGnssBIT.GpsMode"] > 0)
    tg = gnss["SystemTov"][okg]
    steps = np.round((tg - t0) / dt).astype(int) - 1
    keep = (steps >= 0) & (steps < n)
    steps, idx = np.unique(steps[keep], return_index=True)
    ge, gn = en(gnss["GnssLatitude"][okg][keep][idx], gnss["GnssLongitude"][okg][keep][idx])
    z_gps = np.stack([ge, gn], axis=1)
    # the receiver's reported accuracy, per axis: the RMS of its latitude and longitude sigmas
    gsig = np.sqrt(0.5 * (gnss["GnssStdvLat"][okg][keep][idx] ** 2 + gnss["GnssStdvLon"][okg][keep][idx] ** 2))
    gsig = np.maximum(np.where(np.isfinite(gsig), gsig, 1.0), 0.01)
    return steps, z_gps, gsig
