import sys, time
sys.path.insert(0, "/work/h22/benchmarks")
import numpy as np
from threadpoolctl import threadpool_limits
import bench_peers as bp
import filterwnn
print(filterwnn.__file__)
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
    dyn = bp._dynamax_bank(prob, x, z)["dynamax jit(vmap)"]
    row = {"kept": (st(kept), B), "fresh": (st(fresh), B), "loop": (loop, bp.LOOP_SAMPLE), "floor": (floor, B), "dynamax": (dyn.fn, B)}
    for f, _ in row.values(): f()
    wall = {k: [] for k in row}; cpu = {k: [] for k in row}
    for r in range(reps):
        keys = list(row) if r % 2 == 0 else ["fresh", "kept", "loop", "floor", "dynamax"]
        for k in keys:
            f, per = row[k]
            t0 = time.perf_counter(); c0 = time.process_time(); f(); c1 = time.process_time(); t1 = time.perf_counter()
            wall[k].append((t1 - t0) / per * 1e6); cpu[k].append((c1 - c0) / per * 1e6)
    w = {k: np.median(v) for k, v in wall.items()}
    pr = np.median(np.array(wall["kept"]) / np.array(wall["fresh"]))
    print(f"B={B}: wall us/filter-step " + ", ".join(f"{k} {v:.2f}" for k, v in w.items() if k != "loop")
          + f"; kept/fresh paired {pr:.3f}; kept/dynamax {w['kept']/w['dynamax']:.2f} fresh/dynamax {w['fresh']/w['dynamax']:.2f}"
          + f"; cpu kept {np.median(cpu['kept']):.2f} fresh {np.median(cpu['fresh']):.2f}")
