import sys, time, resource
sys.path.insert(0, "/work/h22/benchmarks")
import numpy as np
from threadpoolctl import threadpool_limits
import bench_peers as bp
reps = int(sys.argv[1])
with threadpool_limits(1):
  for B in (1000, 10000):
    prob, x, z = bp._six(B)
    pts = bp._merwe6(); c = np.sqrt(6.0); P0 = np.broadcast_to(prob["P0"], (B, 6, 6)).copy()
    kept, fresh = bp._bank(prob, x), bp._bank(prob, x)
    fresh._workspace = lambda: None
    def st(bank):
        def one():
            bank.predict(); bank.update(z)
        return one
    def loop():
        for i in range(bp.LOOP_SAMPLE):
            f = bp._filterpy_six(prob, x[i]); f.predict(); f.update(z[i])
    def floor():
        bp.numpy_ukf_step(x, P0, prob["Q"], prob["R"], z, pts.Wm, pts.Wc, c)
    dyn = bp._dynamax_bank(prob, x, z)["dynamax jit(vmap)"].fn
    nb = {"none": lambda: None, "floor": floor, "loop": loop, "dynamax": dyn}
    for f in nb.values(): f()
    res = {}
    for r in range(reps):
        for name, g in nb.items():
            for bk, s in (("kept", st(kept)), ("fresh", st(fresh))) if r % 2 == 0 else (("fresh", st(fresh)), ("kept", st(kept))):
                g()
                f0 = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
                c0 = time.process_time(); s(); c1 = time.process_time()
                res.setdefault((name, bk), []).append(((c1 - c0) / B * 1e6, resource.getrusage(resource.RUSAGE_SELF).ru_minflt - f0))
    print(f"B={B}: " + "; ".join(f"after {n}: kept {np.median([a for a,_ in res[(n,'kept')]]):.2f} ({np.median([b for _,b in res[(n,'kept')]]):.0f} flt) fresh {np.median([a for a,_ in res[(n,'fresh')]]):.2f} ({np.median([b for _,b in res[(n,'fresh')]]):.0f} flt)" for n in nb))
