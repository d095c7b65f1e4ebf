"""Benchmark: a 200-sample study through the Python API against `vbi study`.

The study: the paper's 3 × 30 m bridge, 50 modes, the five-axle truck at 80 km/h on a 'medium'
road, 200 roughness samples (examples/studies/quick.toml's scenario, one bridge). Runs it with
`vbi.study` on every core and reports the wall time; `vbi study` on the same file is timed by
the shell, and its cases.csv compared with the DataFrame cell for cell.

    pip install ./crates/vbi-py
    python crates/vbi-py/benches/study.py --write target/bench-study/study.toml
    /usr/bin/time target/release/vbi study target/bench-study/study.toml \
        --out target/bench-study/cli --no-figures
    python crates/vbi-py/benches/study.py --compare target/bench-study/cli/cases.csv \
        target/bench-study/study.toml
"""

from __future__ import annotations

import argparse
import csv
import math
import time
from pathlib import Path

import pandas as pd

import vbi

STUDY = """[study]
name = "bench-200"
seed = 2026
samples = 200

[study.axes]
bridge = ["paper-3x30"]
road = ["medium"]
speed_kmh = [80]

[scenario]
vehicle = "tractor-semitrailer-5axle"
modes = 50
"""


def equal_cells(frame, path: Path) -> bool:
    with open(path, newline="") as handle:
        rows = list(csv.DictReader(handle))
    for index, row in enumerate(rows):
        for column, cell in row.items():
            value = frame[column].iloc[index]
            empty = value is None or value is pd.NA or (
                isinstance(value, float) and math.isnan(value)
            )
            if cell == "":
                if not empty:
                    return False
            elif column in ("case", "rdm_station", "warnings", "error", "bridge", "road"):
                if str(value) != cell:
                    return False
            elif float(value) != float(cell):
                return False
    return len(rows) == len(frame)


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("study", nargs="?", type=Path)
    parser.add_argument("--write", type=Path, help="write the study file and stop")
    parser.add_argument("--compare", type=Path, help="cases.csv of `vbi study` to compare with")
    args = parser.parse_args()
    if args.write:
        args.write.parent.mkdir(parents=True, exist_ok=True)
        args.write.write_text(STUDY)
        return
    if args.study is None:
        parser.error("give the study file (written by --write)")
    started = time.perf_counter()
    cases = vbi.study(str(args.study))
    wall = time.perf_counter() - started
    print(f"vbi.study: {len(cases)} cases in {wall:.1f} s ({len(cases) / wall:.2f} crossings/s)")
    if args.compare:
        print("cases.csv equal cell for cell:", equal_cells(cases, args.compare))


if __name__ == "__main__":
    main()
