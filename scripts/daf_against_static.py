#!/usr/bin/env python3
"""The DAF of the integrated events against their static level, and the assessment DAF against
the worst single-event DAF, from one `vbi lifetime` run with dynamics (docs/lifetime.md, "The
published findings compared"): the trend that Kalin et al. and ARCHES D10 report from B-WIM
measurements (the DAF falls as the static effect grows), read off vbi's own events.

    python3 scripts/daf_against_static.py OUT_DIR [--bins 0 0.3 0.5 0.7 0.8 0.9 1.0]

OUT_DIR is the `--out` of `vbi lifetime` with `dynamics = true`; with `screening_ratio = 0` every
event that loads an effect is in events.csv, otherwise only those that can govern. For each
effect it prints, per bin of an event's static extreme over the record's largest static block
maximum: the events, the mean, 95th percentile and largest DAF; then the DAF of the event with
the largest static effect, the largest event DAF, and the assessment DAF of lifetime.json (the
characteristic total over the characteristic static, GEV and Gumbel). Standard library only."""

from __future__ import annotations

import argparse
import csv
import json
import math
from collections import defaultdict
from pathlib import Path


def percentile(values: list[float], q: float) -> float:
    """The q-quantile by linear interpolation between order statistics (numpy's default)."""
    ordered = sorted(values)
    position = q * (len(ordered) - 1)
    low = math.floor(position)
    high = min(low + 1, len(ordered) - 1)
    return ordered[low] + (position - low) * (ordered[high] - ordered[low])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", type=Path)
    parser.add_argument("--bins", type=float, nargs="+", default=[0.0, 0.3, 0.5, 0.7, 0.8, 0.9, 1.0])
    args = parser.parse_args()
    events: dict[tuple, list[tuple[float, float]]] = defaultdict(list)
    for row in csv.DictReader(open(args.out / "events.csv")):
        static = float(row["static"])
        if static != 0.0:
            events[(row["station"], row["quantity"])].append((abs(static), float(row["daf"])))
    summary = json.loads((args.out / "lifetime.json").read_text())
    print(f"{summary['events']} events, {summary['dynamic_events']['integrated']} integrated "
          f"(screening ratio {summary['dynamic_events']['screening_ratio']})")
    for effect in summary["effects"]:
        key = (effect["station"], effect["quantity"])
        if key not in events:
            continue
        largest = abs(effect["largest_block_maximum"])
        pairs = events[key]
        print(f"\n{key[0]} {key[1]}: largest static block maximum {largest:.6g} {effect['unit']}")
        print("| static / largest | events | mean DAF | 95th percentile | largest DAF |")
        print("|---|---|---|---|---|")
        for low, high in zip(args.bins, args.bins[1:]):
            dafs = [d for s, d in pairs if low < s / largest <= high or (low == 0.0 and s == 0.0)]
            if dafs:
                print(f"| {low:.2f}–{high:.2f} | {len(dafs)} | {sum(dafs) / len(dafs):.4f} | "
                      f"{percentile(dafs, 0.95):.4f} | {max(dafs):.4f} |")
        heaviest = max(pairs)
        print(f"DAF of the event with the largest static effect: {heaviest[1]:.4f}; "
              f"largest event DAF: {max(d for _, d in pairs):.4f}")
        for level in (effect.get("total") or {}).get("assessment_daf", []):
            gev, gumbel = level["gev"], level["gumbel"]
            print(f"assessment DAF at {level['period_years']:g} years: GEV "
                  f"{'–' if gev is None else f'{gev:.4f}'}, Gumbel "
                  f"{'–' if gumbel is None else f'{gumbel:.4f}'}")


if __name__ == "__main__":
    main()
