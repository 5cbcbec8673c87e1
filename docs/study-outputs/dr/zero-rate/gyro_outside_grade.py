"""A gyro outside its grade (stops 35 and 43, issue 23): the analogs of seed 0 with a rate bias of 0.3 or 0.7
deg/s, run with the phone grade (0.05 deg/s; its calibration bound three prior sigmas, 0.15), then again as
the filter's warning tells.

Run from the repository root, one BLAS thread::

    python docs/study-outputs/dr/zero-rate/gyro_outside_grade.py phone,one_hz,city 0.3,0.7 > docs/study-outputs/dr/zero-rate/gyro_outside_grade.txt

Per drive: dead reckoning alone from the true start; the EKF-8 (median / max at the ends of the 20
outages of 30 s, as ``filterwnn study dr --drive FILE --grade phone`` scores it) with the stops'
re-acquisition (``zero_rate_reacquire_after``, the default: 3 until stop 59, then 2; the stop-58 output is
``gyro_outside_grade_three_stops.txt``) and without (0), with the stops used /
rejected / re-acquisitions and how many different warnings the filter gave (their first 60 characters); then the
default's UKF-8 and SUKF-8, the values the re-acquisitions' warnings name (``--gyro-bias X``, read from their text), and the three
kinds run again with the largest (``grade={"gyro_bias_deg_s": X}``, what ``--gyro-bias X`` passes). The analogs are
drawn with the gyro's rate bias changed (``columns(name, 0, rate_bias=...)``, the same draws); nothing here
is used by the package.
"""
import os, re, sys, tempfile, warnings, numpy as np
ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", "..", ".."))
sys.path[:0] = [ROOT, os.path.join(ROOT, "tests")]
import _held_out_drives as h
from filterwnn.navigation.drives import read_drive_csv
from filterwnn.navigation import gpsdr
from filterwnn.studies.dr import real_drive_outages

KINDS = ("EKF-8", "UKF-8", "SUKF-8")


def score(run, filters, grade="phone"):
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        res = real_drive_outages(run, filters=filters, use_gps_sigma=True, grade=grade)
    return res, [str(x.message) for x in w]


def cell(res, k):
    return f"{np.median(res[k]):.2f}/{res[k].max():.2f}"


tmp = tempfile.mkdtemp()
for name in sys.argv[1].split(","):
    for bias in [float(b) for b in sys.argv[2].split(",")]:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            run = read_drive_csv(h.write_csv(os.path.join(tmp, "d.csv"), h.columns(name, 0, rate_bias=bias)))
        cells, said = [], []
        for n in (gpsdr.ZERO_RATE_REACQUIRE_AFTER, 0):
            gpsdr.GPSDRFilter.__init__.__kwdefaults__["zero_rate_reacquire_after"] = n
            res, msgs = score(run, ("DR-mech", "EKF-8"))
            ig = res["integrity"]["EKF-8"]
            cells.append(f"reacq {n}: EKF-8 {cell(res, 'EKF-8')} stops {ig['n_zero_rate']}/{ig['n_zero_rate_rejected']}/"
                         f"{ig['n_zero_rate_reacquired']} warns {len({m[:60] for m in msgs})}")
            if n:
                said, default = msgs, res
        gpsdr.GPSDRFilter.__init__.__kwdefaults__["zero_rate_reacquire_after"] = gpsdr.ZERO_RATE_REACQUIRE_AFTER
        res, msgs = score(run, KINDS[1:])
        default.update(res)
        said += msgs
        reacquired = " ".join(m for m in said if "re-acquires from them" in m)  # the stops' measured bias
        told = sorted({float(m) for m in re.findall(r"--gyro-bias ([0-9.]+)\)", reacquired)})
        line = f"{name} {bias} DR {cell(default, 'DR-mech')} " + " | ".join(cells)
        line += " | default UKF-8 " + cell(default, "UKF-8") + " SUKF-8 " + cell(default, "SUKF-8")
        if told:
            res, _ = score(run, KINDS, grade={"gyro_bias_deg_s": told[-1]})
            line += f" | told --gyro-bias {','.join(f'{v:g}' for v in told)}: " + " ".join(f"{k} {cell(res, k)}" for k in KINDS)
        else:
            line += " | no --gyro-bias named"
        print(line, flush=True)
