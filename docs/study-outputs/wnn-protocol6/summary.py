"""Protocol 6's RUN.md numbers from runs.csv, against protocol 4's n60 runs (same seeds)."""
import csv, sys
import numpy as np
new = [r for r in csv.DictReader(open(sys.argv[1])) if r["trainer"] == "smc-noise-10x10-recal"]
old = {r["run"]: r for r in csv.DictReader(open(sys.argv[2])) if r["trainer"] == "smc-noise-10x10"}
f = lambda rs, k: np.array([float(r[k]) for r in rs])
print("runs", len(new))
same = all(f([r], "test_mse")[0] == float(old[r["run"]]["test_mse"]) for r in new)
same_base = all(all(float(r[k + "_base"]) == float(old[r["run"]][k]) for k in ("coverage50", "coverage90", "coverage95", "nlpd")) for r in new)
print("test MSE equal to protocol 4 per run:", same, "; base scores equal:", same_base)
mse = f(new, "test_mse")
print("test MSE median %.4f (range %.4f-%.4f; %d of %d <= 0.02)" % (np.median(mse), mse.min(), mse.max(), (mse <= 0.02).sum(), len(mse)))
for k in ("coverage50", "coverage90", "coverage95", "nlpd"):
    v, b = f(new, k), f(new, k + "_base")
    print(f"{k}: recal median {np.median(v):.4f} (runs {v.min():.2f}-{v.max():.2f}); base median {np.median(b):.4f}")
c90 = f(new, "coverage90")
print("runs with 90 %% coverage in 0.85-0.95: %d of %d" % (((c90 >= 0.85) & (c90 <= 0.95)).sum(), len(c90)))
print("pooled 90 %% coverage (all test rows of all runs): %.4f" % np.mean(c90))
print("factor", sorted(set(r["recal_factor"] for r in new)))
