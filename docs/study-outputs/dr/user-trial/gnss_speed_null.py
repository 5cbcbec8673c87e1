"""The GNSS speed's warning (stop 75: a speed that reads 0 where the receiver has no fix either, between samples of a
car moving) over drive files nobody wrote for it: every user trial's drives (their generators, run into a temporary
folder), the three held-out analogs' seeds 0-4 and the shipped sample, each read by the drive reader; which tell it,
with the warning's first words.

    python docs/study-outputs/dr/user-trial/gnss_speed_null.py > docs/study-outputs/dr/user-trial/gnss_speed_null.txt
"""

from null_files import print_told

print_told('where the GPS receiver has no fix', ': a car braking')
