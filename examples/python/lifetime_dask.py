"""A lifetime with dynamics across a dask.distributed cluster.

The record's blocks are split into shards; `vbi.lifetime(source, shard=(i, n))` runs each shard
on a worker (its blocks' static maxima, and the crossings of its events that can govern), and
`vbi.merge_lifetime` makes the shards' frames the single run's: the same block maxima, totals,
fits and assessment DAFs as one `vbi.lifetime(source)` (or `vbi lifetime`) gives, f64 for f64,
because each event's road seed derives from its number in the whole record. A LocalCluster
stands for the cluster here; give `Client` the address of an existing scheduler instead (for
example one started by dask-jobqueue on Slurm). From a shell, the same is
`vbi lifetime FILE --shard I/N --out DIR-I` per task and `vbi lifetime merge FILE --out DIR
DIR-*` (docs/lifetime.md, "Shards, clusters and resuming").

    pip install ./crates/vbi-py "dask[distributed]" pandas
    python examples/python/lifetime_dask.py
"""

from __future__ import annotations

from pathlib import Path

from dask.distributed import Client, LocalCluster

import vbi

#: Three days of Auxerre traffic on a 30 m span, with dynamics (screening ratio 0.9).
LIFETIME = Path(__file__).resolve().parents[1] / "lifetime" / "auxerre-3-days-dynamics-1x30.toml"


def distributed_lifetime(client, source=LIFETIME, shards=None):
    """The lifetime's frame (as `vbi.lifetime(source)` returns it), its shards run on the
    cluster's workers. The task is `vbi.lifetime` itself, which every worker imports."""
    count = shards or max(1, len(client.scheduler_info()["workers"])) * 2
    futures = [
        client.submit(vbi.lifetime, str(source), shard=(i, count), pure=False)
        for i in range(1, count + 1)
    ]
    return vbi.merge_lifetime(str(source), client.gather(futures))


def main():
    with LocalCluster(n_workers=2, threads_per_worker=1) as cluster, Client(cluster) as client:
        frame = distributed_lifetime(client, shards=3)
    print(f"{frame.attrs['blocks']} blocks, {frame.attrs['events']} events, "
          f"{frame.attrs['dynamic_events']['integrated']} integrated with dynamics")
    print(frame[["block", "station", "quantity", "static", "total", "daf"]].to_string(index=False))


if __name__ == "__main__":
    main()
