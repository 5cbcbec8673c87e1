#!/bin/bash
# The phone analog (seed 0) with its fixes stamped L s late, read back at L (and the 18 s one at the 17.5 s the
# reader names), scored by the command (phone grade, EKF-8): each is the honest drive with its fix errors taken
# L fixes along the same error process.  usage: bash clock_offset_read.sh > clock_offset_read.txt
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
for pair in "1 1" "2 2" "5 5" "10 10" "18 18" "18 17.5" "25 25"; do
    set -- $pair
    python -c "
import sys; sys.path.insert(0, '$here/../../../../tests'); import _held_out_drives as h
h.write_csv('$work/d.csv', h.columns('phone', 0, gps_latency=$1))"
    line=$(OPENBLAS_NUM_THREADS=1 filterwnn study dr --drive "$work/d.csv" --grade phone --out "$work/out" --no-figures \
        --no-progress --filters DR-mech,EKF-8 --gps-latency "$2" 2>/dev/null | grep '^| EKF-8')
    echo "stamped $1 s late, read at $2 s: $line"
done
rm -rf "$work"
