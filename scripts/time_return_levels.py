"""Times vbi.fit_block_maxima (the fits and return levels of `vbi lifetime`) on 250, 2,500 and
25,000 daily maxima of a GEV law, without and with the default 400 bootstrap resamples
(docs/performance.md, "Return levels of the lifetime block maxima"). Needs the vbi package,
numpy and scipy."""
import resource
import time

import numpy as np
import scipy.stats as st

import vbi

rng = np.random.default_rng(1)
for n in (250, 2500, 25000):
    values = st.genextreme.rvs(0.2, loc=5e6, scale=4e5, size=n, random_state=rng)  # xi = -0.2
    for resamples in (0, 400):
        t = time.perf_counter()
        fits = vbi.fit_block_maxima(values, block_days=1.0, return_periods_years=[1000], bootstrap_resamples=resamples, seed=1)
        dt = time.perf_counter() - t
        gev = fits["fits"][0]["return_levels"][0]
        print(f"n={n:6d} resamples={resamples:3d}: {dt:7.2f} s  GEV 1000-yr {gev['value']:.4e} [{gev['low']:.4e}, {gev['high']:.4e}]")
print("peak RSS MB", resource.getrusage(resource.RUSAGE_SELF).ru_maxrss/1024)
