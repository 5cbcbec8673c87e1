#!/bin/bash
# A/B in turn: main vs h22, the bank step alone and right after the NumPy floor's call
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 MKL_NUM_THREADS=1
for B in 1000 10000; do for m in alone after; do
  for i in 1 2 3 4 5 6; do for t in main h22; do
    echo "$B $m $t $(PYTHONPATH=/work/$t python /tmp/h22/prof.py $B $m 40 | tail -1)"
  done; done
done; done
