#!/bin/bash
# What a user sees: the 1 Hz analog (seed 0) with a fault, written as a drive CSV and run through the command
# as the held-out check runs it (phone grade, nothing tuned).
# usage: bash command.sh [GENERATOR_KEYWORDS [COMMAND_OPTIONS...]]
#   bash command.sh > command.txt                                         (the fixes 1 s late, the default)
#   bash command.sh odometer_latency=0.5 > speed_command.txt              (the speed 0.5 s late)
#   bash command.sh odometer_latency=0.5 --odometer-latency 0.54 > speed_command_read.txt   (read at its estimate)
set -e
here=$(cd "$(dirname "$0")" && pwd)
fault=${1:-gps_latency=1.0}
shift || true
work=$(mktemp -d)
python -c "
import sys; sys.path.insert(0, '$here/../../../../tests'); import _held_out_drives as h
h.write_csv('$work/one_hz_late.csv', h.columns('one_hz', 0, $fault))"
OPENBLAS_NUM_THREADS=1 filterwnn study dr --drive "$work/one_hz_late.csv" --grade phone --out "$work/out" \
    --no-figures --no-progress "$@" 2>&1 | grep -v '^wrote:'
rm -rf "$work"
