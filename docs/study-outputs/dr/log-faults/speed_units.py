"""Which unit the reader names for a speed given in another (stop 65): the 250 drives at hand (``at_hand.py``),
each with its speed multiplied into km/h, ft/s, mph, knots, cm/s and mm/s, read as a user would
(``read_drive_csv``), and the refusal's cause classified: the right unit alone, the right unit first and another
beside it, another first and the right one beside it, another alone, or no unit named; or, where the drive is read,
whether the reader's speed-scale warning names the unit. Half the drives for
``part`` 0, the other half for 1 (two processes; a third argument starts at that drive of the part);
``summary`` totals their outputs. Run from the repository root::

    python docs/study-outputs/dr/log-faults/speed_units.py 0 > /tmp/su0.txt &
    python docs/study-outputs/dr/log-faults/speed_units.py 1 > /tmp/su1.txt
    python docs/study-outputs/dr/log-faults/speed_units.py summary /tmp/su0.txt /tmp/su1.txt > speed_units.txt

(``PYTHONPATH=<an older checkout>`` reads them with that version's reader.)
"""
import collections
import os
import re
import sys
import tempfile
import warnings

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

UNITS = {"km/h": 3.6, "ft/s": 1 / 0.3048, "mph": 1 / 0.44704, "knots": 1 / 0.514444, "cm/s": 100.0, "mm/s": 1000.0}


def named(message):
    """The units the refusal's cause names, in its order (those of ``UNITS``)."""
    cause = message.split("(expected", 1)[-1]
    found = [(m.start(), u) for u in UNITS for m in re.finditer(re.escape(u) + r"\b", cause)]
    return [u for _, u in sorted(found)]


def kind(unit, said):
    if said[:1] == ["(read)"]:
        return "read, warned of as this unit" if said[1:2] == [unit] else "read, not named"
    if not said:
        return "no unit named"
    if said == [unit]:
        return "right alone"
    if said[0] == unit:
        return "right first, another beside"
    if unit in said:
        return "another first, right beside"
    return "another alone"


def unit_ratio(path):
    """The length ratio the reader names a unit by (``_plausibility._unit_ratio``; None before stop 65) and
    whether it was measured again over stretches as long on the road."""
    from filterwnn.navigation import _plausibility as P
    from filterwnn.navigation.drives import read_drive_csv

    if not hasattr(P, "_unit_ratio"):
        return None, False
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        run = read_drive_csv(path, checks=False)
    heading, step = np.r_[run.z_dr[0, 0], run.z_dr[:, 0]], run.z_dr[:, 1]
    sigma = None if run.gps_sigma is None else float(np.median(run.gps_sigma))
    pairs = P._chord_pairs(run.gps_steps, run.z_gps, sigma, step)
    ratio = P._medians(*P._chord_angles(heading, step, run.gps_steps, run.z_gps, pairs)[:2])[1]
    again, tolerance = P._unit_ratio(step, run.gps_steps, run.z_gps, sigma, ratio, heading)
    return again, tolerance == P._DECADE_TOLERANCE_AGAIN


def scan(part, first=0):
    from at_hand import drives_at_hand, held_out
    from filterwnn.navigation.drives import read_drive_csv

    drives = drives_at_hand()
    with tempfile.TemporaryDirectory() as tmp:
        for key in list(drives)[part::2][first:]:
            cols = drives[key]()
            for unit, factor in UNITS.items():
                c = dict(cols)
                c["speed"] = np.asarray(cols["speed"], dtype=float) * factor
                path = held_out.write_csv(os.path.join(tmp, "d.csv"), c)
                try:
                    with warnings.catch_warnings(record=True) as caught:
                        warnings.simplefilter("always")
                        read_drive_csv(path)
                    scale = [str(w.message) for w in caught if "dead-reckoned distance is" in str(w.message)]
                    said, ratio = ["(read)"] + (named(scale[0].split("(median", 1)[1]) if scale else []), ""
                except ValueError as exc:
                    said = named(str(exc))
                    m = re.search(r"and ([0-9.e+]+) times their distance", str(exc))
                    ratio = m.group(1) if m else ""
                again, measured = unit_ratio(path)
                again = "" if again is None else f"{again / factor:.4g}{'' if measured else '?'}"
                print(f"{key}\t{unit}\t{ratio}\t{','.join(said) or '-'}\t{again}", flush=True)


def summary(paths):
    counts = collections.defaultdict(collections.Counter)
    measured = collections.defaultdict(list)
    wrong = []
    for path in paths:
        for line in open(path):
            key, unit, ratio, said, *again = line.rstrip("\n").split("\t")
            if again and again[0] and not again[0].endswith("?"):
                measured[unit].append(float(again[0]))
            said = [] if said == "-" else said.split(",")
            k = kind(unit, said)
            counts[unit][k] += 1
            if k in ("another alone", "another first, right beside", "no unit named", "read, not named"):
                wrong.append(f"  {key}: {unit} (ratio {ratio or '?'}) named {', '.join(said) or 'no unit'}")
    kinds = ["right alone", "right first, another beside", "another first, right beside", "another alone",
             "no unit named", "read, warned of as this unit", "read, not named"]
    print("| speed given in | " + " | ".join(kinds) + " |")
    print("|---|" + "---|" * len(kinds))
    for unit in UNITS:
        print(f"| {unit} | " + " | ".join(str(counts[unit][k]) for k in kinds) + " |")
    if measured:
        print("\nThe ratio measured again over stretches as long on the road (where at least 10 are), over the "
              "unit's factor: drives, and its 0, 2.5, 50, 97.5 and 100 % points")
        for unit in UNITS:
            if measured[unit]:
                q = np.percentile(measured[unit], [0, 2.5, 50, 97.5, 100])
                print(f"  {unit}: {len(measured[unit])}, " + " ".join(f"{v:.3f}" for v in q))
    print(f"\nThe right unit not named first ({len(wrong)}):")
    print("\n".join(wrong))


if __name__ == "__main__":
    if sys.argv[1] == "summary":
        summary(sys.argv[2:])
    else:
        scan(int(sys.argv[1]), *(int(a) for a in sys.argv[2:]))
