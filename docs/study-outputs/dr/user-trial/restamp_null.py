"""The arrival stamps' warning (stop 75) over drive files nobody wrote for it: every user trial's drives (their
generators, run into a temporary folder), the three held-out analogs' seeds 0-4 and the shipped sample, each read by
the drive reader; which tell fixes stamped on arrival (``filterwnn.navigation.scenarios._arrival_stamps``), with the
test's figures for those that do.

    python docs/study-outputs/dr/user-trial/restamp_null.py > docs/study-outputs/dr/user-trial/restamp_null.txt
"""

from null_files import print_told

print_told('stamped when the logger received them', ':')
