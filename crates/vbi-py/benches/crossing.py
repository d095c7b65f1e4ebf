"""Benchmark: one crossing called from Python against the same crossing in Rust.

The crossing of `cargo bench -p vbi --bench study_case`, benchmark
`one_paper_case_every_station_analysed` (crates/vbi/benches/study_case.rs): the built-in
scenario (`paper_bridge(3, 30.0)`, 50 modes of vertical bending and torsion, the 15-DOF
tractor–semitrailer at 80 km/h, 'medium' road), every station analysed, a new road seed each
iteration; the bridge prepared once, outside the timing. Each iteration here is
`vbi.run(scenario, bridge)`: the same `pipeline::run_crossing` plus what the binding adds (the
GIL released and taken back, the histories handed to numpy, the result object).

    pip install ./crates/vbi-py            # the release build that users get
    python crates/vbi-py/benches/crossing.py [--samples 20]
    cargo bench -p vbi --bench study_case -- one_paper_case_every_station_analysed

Prints fastest, median and mean over the samples, as divan does (one iteration per sample),
of the call from Python and of `run_crossing` inside it (`RunResult.crossing_time_s`, measured
in Rust in the same call): their difference is what Python adds, measured under the same
conditions (the machine's load changes both alike).
"""

from __future__ import annotations

import argparse
import statistics
import time

import vbi


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=20)
    args = parser.parse_args()
    scenario = vbi.Scenario()  # the built-in paper scenario; its road is 'medium'
    bridge = vbi.prepare(scenario)
    calls, inside = [], []
    for seed in range(1, args.samples + 2):
        scenario.set("seed", seed)
        started = time.perf_counter()
        result = vbi.run(scenario, bridge)
        elapsed = time.perf_counter() - started
        if seed > 1:  # the first crossing warms caches
            calls.append(elapsed * 1e3)
            inside.append(result.crossing_time_s * 1e3)
    print(
        f"paper 3x30 m, {bridge.mode_count} modes, every station "
        f"({len(result.stations) // 2} stations), {args.samples} samples"
    )
    for label, ms in (("vbi.run from Python", calls), ("run_crossing inside it", inside)):
        print(
            f"  {label:<24} fastest {min(ms):6.1f} ms, median {statistics.median(ms):6.1f} ms,"
            f" mean {statistics.mean(ms):6.1f} ms"
        )
    added = [c - i for c, i in zip(calls, inside)]
    share = [(c - i) / i * 100 for c, i in zip(calls, inside)]
    print(
        f"  added by Python: median {statistics.median(added):.3f} ms "
        f"({statistics.median(share):.2f} % of the crossing), largest {max(share):.2f} %"
    )


if __name__ == "__main__":
    main()
