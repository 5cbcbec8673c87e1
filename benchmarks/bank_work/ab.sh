#!/bin/bash
# A/B in turn: two checkouts (A, B: e.g. main and f1fa75c), the bank step alone and right after the NumPy floor's call
# usage: bash ab.sh /path/to/checkout-A /path/to/checkout-B
A=$1; B_=$2; here=$(dirname "$0")
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 MKL_NUM_THREADS=1
for B in 1000 10000; do for m in alone after; do
  for i in 1 2 3 4 5 6; do for t in "$A" "$B_"; do
    echo "$B $m $t $(PYTHONPATH=$t python "$here/prof.py" $B $m 40 | tail -1)"
  done; done
done; done
