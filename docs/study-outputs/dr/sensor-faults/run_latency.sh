#!/bin/bash
# The two `delay` drives (speed 0.5 s late) with --odometer-latency 0.5 (stop 40); prints each 8-state kind's
# table row (median / max at the outage ends are its 2nd and 4th cells).
# usage: bash run_latency.sh [WORKDIR] > latency.txt     (WORKDIR default /tmp/sensor-faults-latency)
set -e
here=$(cd "$(dirname "$0")" && pwd)
work=${1:-/tmp/sensor-faults-latency}
mkdir -p "$work/drives"
python "$here/make_variants.py" "$work/drives" > "$work/drives/make_variants.log"
for v in phone_delay city_delay; do
  echo "## $v, --odometer-latency 0.5"
  env OPENBLAS_NUM_THREADS=1 filterwnn study dr --drive "$work/drives/$v.csv" --grade phone --out "$work/$v" \
      --no-figures --no-progress --odometer-latency 0.5 2>/dev/null | grep -E '^\| (filter|EKF-8|UKF-8|SUKF-8) '
done
