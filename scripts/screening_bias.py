#!/usr/bin/env python3
"""The screening's bias of `vbi lifetime` with dynamics (docs/lifetime.md, "Screening"),
measured from one run that integrates every event (`screening_ratio = 0`): each event's total
does not depend on which other events are integrated (its road's seed is its number's; tested),
so the block totals any ratio r would give are the largest totals of the events that r screens
in, and can be computed from that one run's events.csv.

    python3 scripts/screening_bias.py OUT_DIR [--block-days 1] [--ratios 0.5 0.7 0.8 0.9 0.95 1]
        [--fit --return-period 1000]

OUT_DIR is the `--out` of `vbi lifetime` run with `dynamics = true` and `screening_ratio = 0`.
For each ratio and effect it prints the blocks whose total differs from the every-event total,
the largest and the mean shortfall (relative), and the events integrated. With --fit (needs the
`vbi` Python package) it also fits each ratio's total block maxima as `vbi lifetime` does
(`vbi.fit_block_maxima`: GEV and Gumbel, no resamples) and prints the characteristic total
effect at the return period and its difference from the every-event one: the screening's bias
on the characteristic value. An event's block is
taken at its total's instant (events.csv's time_s; the static extreme's instant lies within the
same crossing, a block boundary apart at most for events that straddle midnight). For each
ratio and effect it also prints the command's screening check (docs/lifetime.md, "The
screening's check"), and how many of the blocks that differ it flags."""

from __future__ import annotations

import argparse
import csv
import math
from collections import defaultdict
from pathlib import Path


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", type=Path)
    parser.add_argument("--block-days", type=float, default=1.0)
    parser.add_argument("--ratios", type=float, nargs="+", default=[0.5, 0.7, 0.8, 0.9, 0.95, 1.0])
    parser.add_argument("--fit", action="store_true")
    parser.add_argument("--return-period", type=float, default=1000.0)
    args = parser.parse_args()
    block_seconds = args.block_days * 86_400.0
    rows = list(csv.DictReader(open(args.out / "events.csv")))
    effects = sorted({(r["station"], r["quantity"]) for r in rows})
    # Per event: its static magnitude and total per effect, and the block of each.
    events: dict[int, dict] = defaultdict(dict)
    sense = {}
    for r in rows:
        effect = (r["station"], r["quantity"])
        static, total = float(r["static"]), float(r["total"])
        sense[effect] = math.copysign(1.0, static)
        block = int(float(r["time_s"]) // block_seconds)
        events[int(r["event"])][effect] = (abs(static), sense[effect] * total, block)
    static_max: dict[tuple, dict[int, float]] = {e: defaultdict(float) for e in effects}
    for per_effect in events.values():
        for effect, (static, _, block) in per_effect.items():
            static_max[effect][block] = max(static_max[effect][block], static)

    def block_totals(ratio: float):
        totals = {e: defaultdict(float) for e in effects}
        integrated = 0
        for per_effect in events.values():
            screened = any(
                static > 0.0 and static >= ratio * static_max[effect][block]
                for effect, (static, _, block) in per_effect.items()
            )
            if not screened:
                continue
            integrated += 1
            for effect, (_, total, block) in per_effect.items():
                totals[effect][block] = max(totals[effect][block], total)
        return totals, integrated

    every, all_events = block_totals(0.0)
    print(f"{len(events)} events, every one integrated: {all_events}; blocks of {args.block_days} days")
    largest_daf = max(
        total / static for per in events.values() for (static, total, _) in per.values() if static > 0
    )
    print(f"largest event DAF of the record: {largest_daf:.4f}")
    def characteristic(totals: dict, effect: tuple) -> tuple[float, float]:
        """The GEV and Gumbel return levels (magnitudes) of one effect's block totals."""
        import vbi

        blocks = range(max(every[effect]) + 1)
        values = [totals[effect][b] for b in blocks]
        fits = vbi.fit_block_maxima(values, block_days=args.block_days,
                                    return_periods_years=[args.return_period],
                                    bootstrap_resamples=0)
        return tuple(abs(f["return_levels"][0]["value"]) for f in fits["fits"])

    reference = {e: characteristic(every, e) for e in effects} if args.fit else {}

    def screening_check(effect: tuple, ratio: float, totals: dict) -> str:
        """The command's screening check (lifetime.json's `screening_check`) at this ratio, and
        whether it flags the blocks whose total differs from the every-event one: the largest
        DAF of the events screened in whose static level lies in [r, r + 0.1) of the block's
        static maximum, and the blocks where r × the static maximum × that DAF exceeds the
        block's total."""
        band = [
            total / static
            for per in events.values()
            if any(s > 0 and s >= ratio * static_max[e][b] for e, (s, _, b) in per.items())
            for e, (static, total, block) in per.items()
            if e == effect and static > 0
            and ratio <= static / static_max[effect][block] < ratio + 0.1
        ]
        edge = max(band, default=None)
        blocks = [b for b in every[effect] if static_max[effect][b] > 0.0]
        at_risk = {
            b for b in blocks
            if edge is not None and ratio * static_max[effect][b] * edge > totals[effect][b]
        }
        missed = {b for b in blocks if totals[effect][b] != every[effect][b]}
        return (f"screening check: largest DAF in the band {edge if edge is None else round(edge, 4)}; "
                f"{len(at_risk)} of {len(blocks)} blocks at risk; of the {len(missed)} that differ, "
                f"{len(missed & at_risk)} flagged")
    for ratio in args.ratios:
        totals, integrated = block_totals(ratio)
        print(f"r = {ratio}: {integrated} events integrated ({100 * integrated / len(events):.2f} %)")
        for effect in reference:
            levels = characteristic(totals, effect)
            differences = [100 * (l / r - 1.0) for l, r in zip(levels, reference[effect])]
            print(f"  {effect[0]} {effect[1]}: characteristic total at {args.return_period:g} years "
                  f"GEV {levels[0]:.6g} ({differences[0]:+.3f} %), Gumbel {levels[1]:.6g} "
                  f"({differences[1]:+.3f} %)")
        for effect in effects:
            shortfalls = [
                1.0 - totals[effect][b] / every[effect][b]
                for b in every[effect]
                if every[effect][b] > 0.0
            ]
            differing = sum(1 for s in shortfalls if s != 0.0)
            print(
                f"  {effect[0]} {effect[1]}: {differing} of {len(shortfalls)} blocks differ; "
                f"largest shortfall {100 * max(shortfalls):.3f} %, mean {100 * sum(shortfalls) / len(shortfalls):.4f} %"
            )
            if ratio > 0.0:
                print("    " + screening_check(effect, ratio, totals))


if __name__ == "__main__":
    main()
