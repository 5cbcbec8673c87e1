import os, sys, time, resource
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import numpy as np
from bench_peers import _six, _bank, numpy_ukf_step, _merwe6
import filterwnn
print(filterwnn.__file__)
B = int(sys.argv[1]); mode = sys.argv[2]; reps = int(sys.argv[3]) if len(sys.argv) > 3 else 30
prob, x, z = _six(B)
bank = _bank(prob, x)
pts = _merwe6(); c = np.sqrt(6.0); P0 = np.broadcast_to(prob["P0"], (B, 6, 6)).copy()
def ours():
    bank.predict(); bank.update(z)
def floor():
    numpy_ukf_step(x, P0, prob["Q"], prob["R"], z, pts.Wm, pts.Wc, c)
ours(); floor()
ts = []; flts = []
for _ in range(reps):
    if mode == "after": floor()
    r0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
    t0 = time.process_time(); ours(); t1 = time.process_time()
    flts.append(resource.getrusage(resource.RUSAGE_SELF).ru_minflt - r0)
    ts.append(t1 - t0)
print(f"B={B} {mode}: {np.median(ts)/B*1e6:.2f} us/filter-step, minflt/step {np.median(flts)}")
