#!/usr/bin/env python3
"""A validation battery for `vbi measure` (issue 52, item 1): synthetic load-test records with
known truth, made by `vbi run`, measured with vbi's default settings, and scored per static
method, channel kind and information level (bias, RMS error, coverage of the stated 95 %
interval, results far off without a warning, f1 within 1 % or flagged).

    python3 scripts/measure_battery --vbi target/release/vbi --out out/battery
    python3 scripts/measure_battery --out out/battery --cases a01 c07    # some cases only
    python3 scripts/measure_battery --list                                # the cases, no runs

Stages (one module each): cases.py (the seeded list of cases), records.py (the `vbi run`
crossings, the logger's records and the [measurement] files, the truth), score.py (`vbi measure`
and the scores), report.py (OUT/battery.json, OUT/battery.md, the summary on standard output),
weighing.py (bridge weigh-in-motion of the records with a crawl run or a model: OUT/weighing.json
and a section of battery.md with the COST 323 classes per road class and speed band).
Each case's files stay in OUT/cases/<case>/ (record.csv, record.toml, crawl.*, scenario.toml,
run/summary.json, measure/, the commands' printouts in *.log), so a case can be looked at, or
measured again by hand: `vbi measure OUT/cases/<case>/record.toml`. A second call with the same
OUT reuses the finished simulations (their scenario unchanged) and measures again.

The battery reports; it does not fail on the issue's targets (today's defaults are known not to
meet them): a refused record is a result, and the exit code is non-zero only when a simulation
fails. Only the standard library is used; 1-1.5 min with a release build on two shared cores
(`--jobs 2`; about 400 MB in OUT). `--cases` writes the battery files of those cases only.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import cases as case_list  # noqa: E402
import records  # noqa: E402
import report  # noqa: E402
import score  # noqa: E402
import weighing  # noqa: E402
from common import ROOT, run_vbi  # noqa: E402


def process(sims: records.Simulations, case: case_list.Case) -> dict:
    """One case: its record (simulated), its measurement, its score."""
    record = records.make_record(sims, case, case_list.SEED)
    result = score.measure(sims.vbi, sims.out / record["directory"])
    scored = score.score_case(record, result, list(case.channels))
    print(f"  {case.name}: {one_line(scored)}", flush=True)
    return {"case": case.as_dict(), "record": record, "score": scored}


def one_line(scored: dict) -> str:
    if scored["returncode"] != 0:
        return "refused: " + (scored.get("refusal", "").splitlines() or [""])[-1][:120]
    parts = []
    for c in scored["channels"]:
        interval = "" if c["half_width_95"] is None else f" ± {c['half_width_95']:.4f}"
        parts.append(f"{c['channel']} {c['method']} {c['daf']:.4f}{interval} (exact {c['exact']:.4f})")
    f = scored["first_frequency"]
    if f["value_hz"] is not None:
        parts.append(f"f1 {f['value_hz']:.3f} Hz ({100 * f['relative_error']:+.1f} %)")
    return "; ".join(parts)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--vbi", default=str(ROOT / "target/release/vbi"), help="the vbi binary")
    parser.add_argument("--out", default="measure_battery_out", help="output directory")
    parser.add_argument("--cases", nargs="*", help="only these cases (names as --list gives them)")
    parser.add_argument("--jobs", type=int, default=2, help="cases processed at once")
    parser.add_argument("--list", action="store_true", help="print the cases and stop")
    parser.add_argument("--no-weighing", action="store_true",
                        help="skip the bridge weigh-in-motion of the records (weighing.py)")
    arguments = parser.parse_args()
    selected = case_list.all_cases()
    if arguments.cases:
        unknown = set(arguments.cases) - {c.name for c in selected}
        if unknown:
            print(f"measure_battery: no case {', '.join(sorted(unknown))}", file=sys.stderr)
            return 2
        selected = [c for c in selected if c.name in arguments.cases]
    if arguments.list:
        for case in selected:
            print(json.dumps(case.as_dict()))
        return 0
    vbi = Path(arguments.vbi).resolve()
    if not vbi.exists():
        print(f"measure_battery: no vbi binary at {vbi} (build it, or give --vbi)", file=sys.stderr)
        return 2
    out = Path(arguments.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    sims = records.Simulations(vbi, out)
    for bridge in sorted({c.bridge for c in selected}):  # shared by the cases: once, before them
        records.bridge_facts(vbi, out, case_list.BRIDGES[bridge], sims.bridges)
    for vehicle in sorted({c.vehicle for c in selected}):
        records.vehicle_axles(vbi, out, vehicle, sims.vehicles)
    print(f"measure_battery: {len(selected)} cases, {arguments.jobs} at once, in {out}", flush=True)
    with ThreadPoolExecutor(max_workers=max(1, arguments.jobs)) as pool:
        results = list(pool.map(lambda case: process(sims, case), selected))
    version = run_vbi(vbi, ["--version"], cwd=out).stdout.strip()
    battery = {
        "vbi": str(vbi),
        "vbi_version": version,
        "seed": case_list.SEED,
        "wall_time_s": time.perf_counter() - start,
        "cases": results,
    }
    summary = report.write(out, battery)
    print()
    print(summary)
    if not arguments.no_weighing:
        print("\nweighing the records with a crawl run or a bridge model ...", flush=True)
        print(weighing.write(out, weighing.run(vbi, out, results)))
    print(f"\nwrote {out / 'battery.json'}, {out / 'battery.md'} ({battery['wall_time_s']:.0f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
