#!/bin/bash
# Build the low-speed speed-sensor variants of the phone and city analogs (seed 0), run
# `filterwnn study dr --drive FILE --grade phone` on each (two at a time), and print the summary.
# usage: bash run_sensor_faults.sh [WORKDIR] > summary.md     (WORKDIR default /tmp/sensor-faults)
set -e
here=$(cd "$(dirname "$0")" && pwd)
work=${1:-/tmp/sensor-faults}
mkdir -p "$work/drives" "$work/runs"
python "$here/make_variants.py" "$work/drives" > "$work/drives/make_variants.log"
python "$here/make_extra.py" "$work/drives" > "$work/drives/make_extra.log"
run_one() {
  v=$1; d=$2/runs/$v; mkdir -p "$d"
  env OPENBLAS_NUM_THREADS=1 filterwnn study dr --drive "$2/drives/$v.csv" --grade phone --out "$d" \
      --no-figures --no-progress > "$d/stdout" 2> "$d/stderr" || echo "rc=$?" >> "$d/stderr"
}
export -f run_one
ls "$work"/drives/*.csv | xargs -n1 basename | sed 's/\.csv$//' | xargs -P 2 -I{} bash -c "run_one {} '$work'"
python "$here/summarize.py" "$work/runs"
