"""The convergence indicator against four times the modes (issue 46, item 5;
docs/verification.md §30).

Runs each scenario with N modes and with 4 N modes at the fixed step 1e-4 s (so that only the
modal truncation differs), and scores every entry's printed `daf_change` against
|DAF(N) − DAF(4N)|: how many it bounds, how many entries moved by more than 1 % and were left
marked converged, how many it flags. Beside it, the indicator before the check modes (the
change over the last ⌈N/5⌉ modes kept, from `daf_by_modes`).

    python3 scripts/convergence_replay --vbi target/release/vbi [--work DIR]

Standard library only; about a minute with a release build.
"""

import argparse
import json
import math
import re
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCENARIOS = ROOT / "examples" / "scenarios"
CASES = [
    ("paper-3x30-medium-80kmh", [20, 30, 40, 57, 80]),
    ("two-span-sprung-mass", [6, 10, 20]),
    ("i-girder-two-trucks", [20, 40]),
    ("skewed-bridge", [15, 30]),
]


def scenario_text(name: str, modes: int) -> str:
    """The example scenario with `modes` modes, at the fixed step 1e-4 s, without re-runs."""
    text = (SCENARIOS / f"{name}.toml").read_text()
    text = re.sub(r"(?m)^modes = \d+", f"modes = {modes}", text)
    text = re.sub(r"(?m)^(time_step_s|rerun_modes).*\n", "", text)
    text = text.replace("[scenario]\n", "[scenario]\ntime_step_s = 1e-4\n", 1)
    return text.replace('"../', f'"{(SCENARIOS / "..").resolve().as_posix()}/')


def run(vbi: str, path: Path) -> dict:
    done = subprocess.run([vbi, "run", str(path), "--format", "json"], capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"{path}: {done.stderr}")
    return json.loads(done.stdout)


def largest_change(series, last):
    return max((abs(x - last) for x in series), default=0.0)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--vbi", default=str(ROOT / "target" / "release" / "vbi"))
    parser.add_argument("--work", default=None, help="directory for the scenarios (default: a temporary one)")
    args = parser.parse_args()
    work = Path(args.work or tempfile.mkdtemp(prefix="convergence_replay_"))
    work.mkdir(parents=True, exist_ok=True)
    print("| scenario (examples/scenarios) | N (kept) | check modes | entries | moved > 1 % "
          "| old: bounded / > 1 % unflagged | new: bounded / > 1 % unflagged | new: flagged | largest excess (new) |")
    print("|---|---|---|---|---|---|---|---|---|")
    totals = {"entries": 0, "moved": 0, "old": 0, "new": 0, "old_unflagged": 0, "new_unflagged": 0}
    for name, counts in CASES:
        reference_path = work / f"{name}-{4 * max(counts)}.toml"
        reference_path.write_text(scenario_text(name, 4 * max(counts)))
        reference = {(s["name"], s["quantity"]): s["daf"] for s in run(args.vbi, reference_path)["stations"]}
        for modes in counts:
            path = work / f"{name}-{modes}.toml"
            path.write_text(scenario_text(name, modes))
            rows = []
            for s in run(args.vbi, path)["stations"]:
                exact = reference.get((s["name"], s["quantity"]))
                series = s["daf_by_modes"]
                if s["daf"] is None or exact is None or len(series) < 2:
                    continue
                n, last = len(series), series[-1]
                old = largest_change(series[n - 1 - max(1, min(n - 1, math.ceil(n / 5))):n - 1], last)
                rows.append((abs(s["daf"] - exact), old, s["daf_change"], abs(s["daf"]),
                             len(s.get("daf_by_check_modes") or []), n))
            moved = sum(1 for e, _, _, d, _, _ in rows if e > 0.01 * d)
            old_bounded = sum(1 for e, o, _, _, _, _ in rows if e <= o)
            new_bounded = sum(1 for e, _, c, _, _, _ in rows if e <= c)
            old_unflagged = sum(1 for e, o, _, d, _, _ in rows if e > 0.01 * d and o <= 0.01 * d)
            new_unflagged = sum(1 for e, _, c, d, _, _ in rows if e > 0.01 * d and c <= 0.01 * d)
            flagged = sum(1 for _, _, c, d, _, _ in rows if c > 0.01 * d)
            excess = max([e - c for e, _, c, _, _, _ in rows] + [0.0])
            kept, check = rows[0][5], rows[0][4]
            label = f"{modes} ({kept})" if kept != modes else f"{modes}"
            print(f"| {name} | {label} | {check} | {len(rows)} | {moved} | {old_bounded} / {old_unflagged} "
                  f"| {new_bounded} / {new_unflagged} | {flagged} | {excess:.4f} |")
            for key, value in [("entries", len(rows)), ("moved", moved), ("old", old_bounded), ("new", new_bounded),
                               ("old_unflagged", old_unflagged), ("new_unflagged", new_unflagged)]:
                totals[key] += value
    print(f"\nall: {totals['entries']} entries; bounded: old {totals['old']}, new {totals['new']}; "
          f"moved > 1 %: {totals['moved']}, left marked converged: old {totals['old_unflagged']}, "
          f"new {totals['new_unflagged']}")


if __name__ == "__main__":
    main()
