"""A Monte Carlo study across a dask.distributed cluster.

The study (here 3 speeds × 40 roughness samples on a 2 × 25 m beam bridge) is split into shards,
`vbi.study(study, shard="i/n")` runs each shard on a worker, and the shards' case tables are
concatenated in order: the same table as `vbi study` writes to cases.csv, or as one
`vbi.study(study)` returns, because each case's road seed derives from the study seed and the
case alone. A LocalCluster stands for the cluster here; give `Client` the address of an
existing scheduler instead (for example one started by dask-jobqueue on Slurm).

    pip install ./crates/vbi-py "dask[distributed]" pandas
    python examples/python/monte_carlo_dask.py
"""

from __future__ import annotations

import pandas as pd
from dask.distributed import Client, LocalCluster

import vbi

STUDY = {
    "study": {
        "name": "monte-carlo",
        "seed": 2026,
        "samples": 40,
        "axes": {"speed_kmh": [60, 90, 120]},
    },
    "scenario": {
        "bridge": "paper-2x25",
        "vehicle": "three-axle-truck-36t",
        "road": "medium",
        "modes": 8,
        "element_length_m": 2.5,
    },
}


def distributed_study(client, study=STUDY, shards=None):
    """The study's case table, its shards run on the cluster's workers (each shard on one
    thread: a worker here is one core). The task is `vbi.study` itself, which every worker
    imports, so nothing of this script needs to travel to the workers."""
    count = shards or max(1, len(client.scheduler_info()["workers"])) * 2
    futures = [
        client.submit(vbi.study, study, shard=f"{i}/{count}", threads=1, pure=False)
        for i in range(1, count + 1)
    ]
    return pd.concat(client.gather(futures), ignore_index=True)


def main():
    with LocalCluster(n_workers=2, threads_per_worker=1) as cluster, Client(cluster) as client:
        cases = distributed_study(client)
    summary = cases.groupby("speed_kmh")[["daf_u", "daf_m"]].describe(percentiles=[0.95])
    print(f"{len(cases)} cases")
    print(summary.loc[:, (slice(None), ["mean", "std", "95%", "max"])].round(4))


if __name__ == "__main__":
    main()
