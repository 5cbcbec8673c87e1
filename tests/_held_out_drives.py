"""Seeded analogs of the three held-out drives of issue 23, as drive CSVs.

The issue describes three recorded drives we cannot see; each function here simulates one
as faithfully as its description allows (the truth known), and :func:`write_csv` writes it
in the columns of :data:`filterwnn.navigation.drives.DRIVE_CSV_COLUMNS` (with the truth), so
``filterwnn study dr --drive FILE`` scores it as the checkers will.

* :func:`phone_drive`: a car with a phone. 10 Hz CAN speed (2 % scale), the phone's
  calibrated gyro (a residual rate bias of 0.005 deg/s, 0.3 deg/sqrt(h) angle random walk,
  a 1 degree heading offset), 1 Hz phone fixes reporting 5-8 m whose true error has that
  sigma per axis but is correlated over tens of seconds (a phone's fixes come out of its own
  filter, and multipath persists), 15 minutes of town and arterial driving with stops.
* :func:`city_drive`: a city centre. 5 Hz odometry (1 % scale) with a real yaw-rate bias
  (0.015 deg/s, integrated into the heading), urban-canyon fixes at 1 Hz whose horizontal
  error has a median of about 21.5 m and a 95th percentile of about 55 m (a street's
  multipath bias, changing from street to street, plus jumps), reported sigmas that vary
  per fix and are optimistic (about 44 % of the errors inside 1 sigma), 12 minutes at
  3-10 m/s with stops.
* :func:`one_hz_drive`: 21 minutes at 1 Hz, 35 % standing still, a MEMS-like gyro (a
  0.05 deg/s rate bias), a 1.5 % odometer scale error, fixes of 3-5 m.

Each takes ``gyro_scale`` (the gyro's scale factor error), ``gps_latency`` (s: each fix is the
truth that long before its time stamp, a receiver's latency or the offset between two clocks) and
``odometer_latency`` (s: each speed sample is the one that long before its time stamp, a CAN bus's
latency or the offset between the car logger's clock and the phone's), faults none of the three was
described with; they draw nothing, so the other draws stay the same.

Nothing here is read by a filter: the filters are set from the sensor grade alone.
"""

import numpy as np


COLUMNS = ("time", "heading", "speed", "gps_east", "gps_north", "gps_sigma", "true_east", "true_north")


def route(rng, duration, dt, standing, speeds, accel=2.0, turn_every=40.0):
    """Speed and turn profiles of a drive with stops: ``(speed_changes, turns)``, windows
    ``(t_start, t_end, amount)`` as a :class:`~filterwnn.navigation.scenarios.Scenario`'s.

    Alternates a stop, pulling away to a cruise speed drawn from ``speeds`` (m/s) at about
    ``accel`` (m/s^2), cruising with a turn of 45-90 degrees every ``turn_every`` s or so, and
    braking to the next stop; the stops take about the fraction ``standing`` of the drive. Every
    window starts half a sample interval ``dt`` off the grid and lasts whole samples, so each
    speed change integrates exactly and the car stands at exactly zero speed.
    """
    def on_grid(a):
        return (np.floor(a / dt) + 0.5) * dt

    def whole(w):
        return max(1.0, np.round(w / dt)) * dt

    changes, turns, t = [], [], on_grid(5.0)
    while t < duration:
        v = rng.uniform(*speeds)
        ramp = whole(v / accel)
        cruise = whole(rng.uniform(30.0, 120.0))
        changes.append((t, t + ramp, v))
        a = on_grid(t + ramp + 3.0)
        while a + 12.0 < t + ramp + cruise:
            width = whole(rng.uniform(5.0, 9.0))
            turns.append((a, a + width, rng.choice([-1.0, 1.0]) * rng.uniform(45.0, 90.0)))
            a = on_grid(a + width + 2.0 + rng.exponential(turn_every))
        t += ramp + cruise
        changes.append((t, t + ramp, -v))
        t += ramp + whole(rng.exponential(standing / (1.0 - standing) * (cruise + 2 * ramp)))
    return tuple(c for c in changes if c[1] < duration), tuple(w for w in turns if w[1] < duration)


def gauss_markov(rng, n, dt, tau, shape=()):
    """Unit-variance first-order Gauss-Markov samples ``(n, *shape)`` with correlation time ``tau`` (s)."""
    phi = np.exp(-dt / tau) if tau > 0 else 0.0
    w = rng.standard_normal((n,) + shape)
    out = np.empty_like(w)
    out[0] = w[0]
    for k in range(1, n):
        out[k] = phi * out[k - 1] + np.sqrt(1.0 - phi * phi) * w[k]
    return out


def _truth(changes, turns, duration, dt, heading, fine=20, exact_stops=False):
    """The true states ``(n, 6)`` on ``t = 0, dt, ...`` of a car starting at rest: the speed
    and heading profiles (windows of :func:`route`) integrated on a grid ``fine`` times finer.

    A window's edges lie on that grid, so whether ``tf >= t0`` takes the point at an edge is a matter of
    rounding: a window that takes one fine step more or less than its length changes the speed by a
    twentieth of a sample's share of it, and every later stop keeps that remainder (the cumulative sum
    carries it): on some drives the car then creeps at up to 0.015 m/s through every later stop (city
    seeds 2, 3 and 5 on 97 % of their standing samples; phone seeds 0, 5 and 9), and the noisy speed read
    of a creeping car is not 0, so those stops look like crawling. ``exact_stops=True`` (not the default,
    which the stored outputs were made with) takes each window's fine steps by index, so each window
    integrates its amount exactly and the car stands at exactly zero speed."""
    h = dt / fine
    tf = h * np.arange(int(round(duration / h)) + 1)
    dv, om = np.zeros(len(tf)), np.zeros(len(tf))
    for rate, windows in ((dv, changes), (om, turns)):
        for t0, t1, amount in windows:
            if exact_stops:
                i0, i1 = int(round(t0 / h)), int(round(t1 / h))
                rate[i0:i1] += amount / ((i1 - i0) * h)
            else:
                rate[(tf >= t0) & (tf < t1)] += amount / (t1 - t0)
    v = np.maximum(np.concatenate([[0.0], np.cumsum(dv[:-1] * h)]), 0.0)
    v[v < 1e-9] = 0.0
    om = np.deg2rad(om) * (v > 0)
    psi = np.deg2rad(heading) + np.concatenate([[0.0], np.cumsum(om[:-1] * h)])
    e = np.concatenate([[0.0], np.cumsum((v * np.sin(psi))[:-1] * h)])
    nn = np.concatenate([[0.0], np.cumsum((v * np.cos(psi))[:-1] * h)])
    x = np.stack([e, v * np.sin(psi), dv * np.sin(psi) + v * om * np.cos(psi),
                  nn, v * np.cos(psi), dv * np.cos(psi) - v * om * np.sin(psi)], axis=1)
    return tf[::fine], x[::fine], psi[::fine], v[::fine]


def _drive(rng, dt, duration, standing, speeds, heading, sensors, exact_stops=False, **route_kw):
    """A drive with stops and its DR sensors: ``(t, x (n, 6), heading (n,), speed (n,))``.

    ``sensors``: ``scale`` (odometer), ``odo`` (m per sample), ``offset`` (deg), ``rate_bias``
    (deg/s, integrated), ``arw`` (deg/sqrt(h)) and ``white`` (deg) of the gyro heading, which
    is held while the car stands (a gyro keeps its heading); the speed is exactly 0 then (``exact_stops``;
    without it a stop may creep: see :func:`_truth`).
    ``gyro_scale`` (optional, default 0): the gyro's scale factor error, its heading turning
    ``1 + gyro_scale`` times the car (it draws nothing: the other draws stay the same).
    """
    changes, turns = route(rng, duration, dt, standing, speeds, **route_kw)
    t, x, psi, v = _truth(changes, turns, duration, dt, heading, exact_stops=exact_stops)
    n = len(t)
    err = (np.deg2rad(sensors["offset"] + sensors["rate_bias"] * t)
           + np.deg2rad(sensors["arw"] / 60.0) * np.sqrt(dt) * np.cumsum(rng.standard_normal(n))
           + np.deg2rad(sensors["white"]) * rng.standard_normal(n))
    noise = sensors["odo"] / dt * rng.standard_normal(n)
    speed = np.where(v > 0, np.maximum(sensors["scale"] * v + noise, 0.0), 0.0)
    psi = psi + sensors.get("gyro_scale", 0.0) * (psi - psi[0])
    return t, x, np.mod(psi + err, 2 * np.pi), speed


def _fix_rows(t, rate=1.0):
    every = int(round(1.0 / (rate * (t[1] - t[0]))))
    rows = np.zeros(len(t), dtype=bool)
    rows[every::every] = True
    return rows


def _columns(t, x, heading, speed, rows, err, sigma, gps_latency=0.0, odometer_latency=0.0):
    """The CSV columns: fixes (truth + ``err``) and their ``sigma`` on ``rows``, empty elsewhere.
    ``gps_latency`` (s): each fix is the truth that long before its row's time (linearly interpolated;
    the first position before the start), a receiver's latency or another clock's offset.
    ``odometer_latency`` (s): each speed sample is the one that long before (the same interpolation)."""
    nan = np.full(len(t), np.nan)
    if odometer_latency:
        speed = np.interp(t - odometer_latency, t, speed)
    ge, gn, gs = nan.copy(), nan.copy(), nan.copy()
    if gps_latency:
        at = t[rows] - gps_latency
        ge[rows], gn[rows] = np.interp(at, t, x[:, 0]) + err[:, 0], np.interp(at, t, x[:, 3]) + err[:, 1]
    else:
        ge[rows], gn[rows] = x[rows, 0] + err[:, 0], x[rows, 3] + err[:, 1]
    gs[rows] = sigma
    return {"time": t, "heading": heading, "speed": speed, "gps_east": ge, "gps_north": gn, "gps_sigma": gs,
            "true_east": x[:, 0], "true_north": x[:, 3]}


def phone_drive(rng, rate_bias=0.005, gyro_scale=0.0, gps_latency=0.0, odometer_latency=0.0, exact_stops=False,
                dt=0.1):
    """The car with a phone (see the module docstring): the CSV columns. ``rate_bias``: the gyro's (deg/s);
    ``gyro_scale``: its scale factor error; ``dt``: the CAN speed's and the gyro's sample interval (s; the
    speed's noise per sample scaled with it, 0.01 m a sample at 10 Hz: ``benchmarks/bench_drive_jobs.py`` writes
    the drive at 50 Hz)."""
    t, x, heading, speed = _drive(rng, dt, 900.0, 0.15, (8.0, 25.0), 70.0, dict(
        scale=1.02, odo=0.01 * dt / 0.1, offset=1.0, rate_bias=rate_bias, arw=0.3, white=0.3, gyro_scale=gyro_scale),
        accel=1.5, exact_stops=exact_stops)
    rows = _fix_rows(t)
    err, reported = phone_fixes(rng, int(rows.sum()))
    return _columns(t, x, heading, speed, rows, err, reported, gps_latency, odometer_latency)


def phone_fixes(rng, m):
    """The phone's ``m`` fixes at 1 Hz: their errors ``(m, 2)`` (m) and the sigmas they report, 5-8 m."""
    acc = 6.5 + 1.5 * np.tanh(gauss_markov(rng, m, 1.0, 60.0))  # reported 5-8 m, changing slowly
    # half the variance correlated over 20 s (the phone's own filter, lasting multipath), half white
    slow, white = gauss_markov(rng, m, 1.0, 20.0, (2,)), rng.standard_normal((m, 2))
    return acc[:, None] * np.sqrt(0.5) * (slow + white), np.round(acc, 1)


def city_drive(rng, rate_bias=0.015, gps_rate=1.0, gyro_scale=0.0, gps_latency=0.0, odometer_latency=0.0,
               exact_stops=False):
    """The city centre (see the module docstring): the CSV columns. ``rate_bias``: the gyro's (deg/s);
    ``gps_rate``: fixes per second (1 or 5; the same error process, in seconds, sampled that often;
    at 1 the same draws as before it was a parameter); ``gyro_scale``: the gyro's scale factor error."""
    t, x, heading, speed = _drive(rng, 0.2, 720.0, 0.25, (3.0, 10.0), 200.0, dict(
        scale=1.01, odo=0.01, offset=0.0, rate_bias=rate_bias, arw=0.5, white=0.2, gyro_scale=gyro_scale),
        accel=1.5, turn_every=25.0, exact_stops=exact_stops)
    rows = _fix_rows(t, gps_rate)
    err, reported = city_fixes(rng, int(rows.sum()), gps_rate)
    return _columns(t, x, heading, speed, rows, err, reported, gps_latency, odometer_latency)


def city_fixes(rng, m, gps_rate=1.0):
    """The city's ``m`` urban-canyon fixes, ``gps_rate`` a second: their errors ``(m, 2)`` (m) and the
    optimistic sigmas they report."""
    # a street's multipath: a per-axis sigma that changes every 20-60 s (log-normal), a bias
    # correlated over 15 s, and jumps of 20-80 m on 4 % of the fixes
    edges = np.cumsum(rng.uniform(20.0, 60.0, m))
    level = np.exp(rng.normal(np.log(18.5), 0.3, m))[np.searchsorted(edges, np.arange(m) / gps_rate)]
    err = level[:, None] * gauss_markov(rng, m, 1.0 / gps_rate, 15.0, (2,))
    jump = rng.random(m) < 0.04
    ang = rng.uniform(0.0, 2 * np.pi, m)
    err += (jump * rng.uniform(20.0, 80.0, m))[:, None] * np.stack([np.sin(ang), np.cos(ang)], axis=1)
    return err, np.round(1.05 * level * np.exp(rng.normal(0.0, 0.25, m)), 1)


def one_hz_drive(rng, rate_bias=0.05, gyro_scale=0.0, gps_latency=0.0, odometer_latency=0.0, exact_stops=False):
    """21 minutes at 1 Hz (see the module docstring): the CSV columns. ``rate_bias``: the gyro's (deg/s);
    ``gyro_scale``: its scale factor error."""
    t, x, heading, speed = _drive(rng, 1.0, 1260.0, 0.35, (8.0, 20.0), 320.0, dict(
        scale=1.015, odo=0.1, offset=0.0, rate_bias=rate_bias, arw=1.0, white=0.5, gyro_scale=gyro_scale),
        accel=2.0, exact_stops=exact_stops)
    rows = _fix_rows(t)
    err, reported = one_hz_fixes(rng, int(rows.sum()))
    return _columns(t, x, heading, speed, rows, err, reported, gps_latency, odometer_latency)


def one_hz_fixes(rng, m):
    """The 1 Hz drive's ``m`` fixes: their errors ``(m, 2)`` (m), white, and the sigmas they report, 3-5 m."""
    acc = rng.uniform(3.0, 5.0, m)
    return acc[:, None] * rng.standard_normal((m, 2)), np.round(acc, 1)


def parking_drive(rng, signed=False, laps=8):
    """A 15-minute drive that parks ``laps`` times, reversing 12 m into each space while turning 45 degrees (not
    one of the three held-out drives; stop 52's): 10 Hz heading with a 0.005 deg/s bias and 0.1 deg of noise, the
    speed unsigned (a CAN bus's; ``signed=True``: negative while reversing), 1 Hz fixes of 4 m with their sigma.
    The CSV columns."""
    dt = 0.1
    knots_t, knots_v, knots_r = [0.0], [0.0], [0.0]  # time, signed speed, turn rate (deg/s) up to each knot

    def add(duration, v_end, rate=0.0):
        knots_t.append(knots_t[-1] + duration)
        knots_v.append(v_end)
        knots_r.append(rate)

    for _ in range(laps):
        add(8.0, 12.0)  # pull away
        for _ in range(4):  # drive with turns
            add(12.0, 12.0, rng.uniform(-6.0, 6.0))
            add(6.0, 12.0)
        add(6.0, 0.0)  # stop
        add(8.0, 0.0)
        add(2.0, -1.5)  # reverse 12 m into a space, turning 45 degrees
        add(6.0, -1.5, 45.0 / 6.0 * np.sign(rng.uniform(-1, 1)))
        add(2.0, 0.0)
        add(10.0, 0.0)  # parked
    t = np.arange(0.0, knots_t[-1], dt)
    v = np.interp(t, knots_t, knots_v)
    rate = np.asarray(knots_r)[np.minimum(np.searchsorted(knots_t, t, side="right"), len(knots_t) - 1)]
    rate[np.abs(v) < 0.5] = 0.0
    psi = np.radians(30.0) + np.cumsum(np.radians(rate) * dt)
    x = np.zeros((len(t), 6))
    x[:, 0] = np.r_[0.0, np.cumsum(v[:-1] * np.sin(psi[:-1]) * dt)]
    x[:, 3] = np.r_[0.0, np.cumsum(v[:-1] * np.cos(psi[:-1]) * dt)]
    rows = np.isclose(t % 1.0, 0.0) | np.isclose(t % 1.0, 1.0)
    gyro = psi + np.radians(0.005) * t + np.radians(rng.normal(0.0, 0.1, len(t)))
    err = rng.normal(0.0, 4.0, (int(rows.sum()), 2))
    return _columns(t, x, np.arctan2(np.sin(gyro), np.cos(gyro)), v if signed else np.abs(v), rows, err, 4.0)


#: ``{name: generator}``; :func:`columns` calls each with its own seeded generator.
HELD_OUT = {"phone": phone_drive, "city": city_drive, "one_hz": one_hz_drive}


def columns(name, seed=0, **kw):
    """The CSV columns of analog ``name`` for ``seed``, drawn from ``SeedSequence([23, 100 + i, seed])``
    (``i`` its place in :data:`HELD_OUT`): seed 0 is the one the tests and the README quote. ``kw`` go to
    its generator (``rate_bias=0.3``: a gyro outside the phone grade; the same draws)."""
    i = list(HELD_OUT).index(name)
    return HELD_OUT[name](np.random.default_rng(np.random.SeedSequence([23, 100 + i, seed])), **kw)


def write_csv(path, cols, odometer=False, accuracy="gps_sigma"):
    """Write the columns ``cols`` as a drive CSV (empty cells where a row has no fix). ``odometer=True``: a
    cumulative odometer column in place of the speed, the trapezoid sum of the speed samples (the odometer of a
    logger that integrates its speed). ``accuracy``: the name under which ``cols["gps_sigma"]`` is written
    (``"gps_hdop"`` for an HDOP), None for none."""
    names = [c for c in COLUMNS if c != "gps_sigma" or accuracy]
    if accuracy and accuracy != "gps_sigma":
        cols = {**cols, accuracy: cols["gps_sigma"]}
        names[names.index("gps_sigma")] = accuracy
    if odometer:
        t, v = cols["time"], cols["speed"]
        cols = {**cols, "odometer": np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(t))])}
        names[names.index("speed")] = "odometer"
    with open(path, "w") as fh:
        fh.write(",".join(names) + "\n")
        for k in range(len(cols["time"])):
            fh.write(",".join("" if np.isnan(cols[c][k]) else f"{cols[c][k]:.6g}" if c in ("time", accuracy)
                              else f"{cols[c][k]:.4f}" for c in names) + "\n")
    return str(path)
