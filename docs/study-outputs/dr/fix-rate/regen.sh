#!/bin/bash
# Every stored output of this folder, from the repository root: bash docs/study-outputs/dr/fix-rate/regen.sh
# (two chains at once, one BLAS thread each; about 15-20 minutes on a 2-core machine)
set -e
D=docs/study-outputs/dr/fix-rate
R="env OPENBLAS_NUM_THREADS=1 python $D/fix_rate.py --rate 5"
( $R --seeds 0-9 > $D/city_5hz_seeds_0_9.txt
  $R --seeds 0-9 --whiteness-window 12 > $D/city_5hz_seeds_0_9_window_12s.txt
  $R --seeds 0-9 --keep-every 5 > $D/city_5hz_seeds_0_9_keep_every_5.txt
  $R --seeds 0-9 --min-fix-interval 1 > $D/city_5hz_seeds_0_9_min_fix_interval_1.txt ) 2>/dev/null &
( $R --seeds 0-9 --correlated-fixes inflate > $D/city_5hz_seeds_0_9_inflate.txt
  $R --seeds 10-19 > $D/city_5hz_seeds_10_19.txt
  $R --seeds 10-19 --min-fix-interval 1 > $D/city_5hz_seeds_10_19_min_fix_interval_1.txt
  $R --seeds 0-4 --white 5 > $D/white_5hz_seeds_0_4.txt
  $R --seeds 0-4 --white 5 --min-fix-interval 1 > $D/white_5hz_seeds_0_4_min_fix_interval_1.txt ) 2>/dev/null &
wait
python $D/summarise.py > $D/summary.txt
