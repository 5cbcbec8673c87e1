"""The latency monitor's false alarm on a clean random drive (stop 66): protocol 2's drive 238 (no fault drawn) through
``filterwnn study dr --drive FILE --grade phone`` (every 8-state kind), as it is and with the monitor's latency gate
out of reach (``_TESTED["latency"]`` patched in memory; nothing here is used by the package). Prints the command's
latency warnings and its table rows (median all, p90, max all, ...) for each. Run from the repository root::

    OPENBLAS_NUM_THREADS=1 python docs/study-outputs/dr/log-faults/false_latency_s238.py > docs/study-outputs/dr/log-faults/false_latency_s238.txt
"""
import contextlib
import io
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from at_hand import drives_at_hand, held_out  # noqa: E402  (puts tests/ on the path)
import filterwnn.navigation.gpsdr as gpsdr  # noqa: E402
from filterwnn import cli  # noqa: E402

with tempfile.TemporaryDirectory() as tmp:
    path = held_out.write_csv(os.path.join(tmp, "p2_s238.csv"), drives_at_hand()["p2 s238"]())
    gate = gpsdr._TESTED["latency"]
    for label, z in (("as shipped (gate 6.1)", gate[0]), ("latency gate out of reach", float("inf"))):
        gpsdr._TESTED["latency"] = (z, gate[1])
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            rc = cli.main(["study", "dr", "--drive", path, "--grade", "phone", "--no-figures", "--no-progress",
                           "--jobs", "1", "--out", os.path.join(tmp, "out"), "--filters", "EKF-8,UKF-8,SUKF-8"])
        print(f"## {label}: exit {rc}")
        for line in err.getvalue().splitlines():
            if "latency" in line:
                print(line[:220])
        for line in out.getvalue().splitlines():
            if line.startswith(("| filter", "| EKF-8", "| UKF-8", "| SUKF-8")):
                print(line[:120])
    gpsdr._TESTED["latency"] = gate
