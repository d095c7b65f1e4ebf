"""Fatigue in Python (issue 51): vbi's rainflow counting against the `rainflow` package (3.2,
the ASTM E1049-85 §5.4.4 rule with the residue as half cycles) on 1,000 random histories, count
for count; and `vbi.run`'s fatigue details against `vbi run --out`'s summary.json, bit for bit."""

from __future__ import annotations

import math

import numpy as np
import pytest

import vbi
from conftest import EXAMPLES, read_json, run_command

rainflow = pytest.importorskip("rainflow")


def histories():
    """1,000 seeded histories of 3 to 400 samples: Gaussian, integer-valued (repeats and equal
    reversals), and random walks (long residues)."""
    generator = np.random.default_rng(51)
    for i in range(1000):
        length = int(generator.integers(3, 401))
        kind = i % 3
        if kind == 0:
            series = generator.normal(size=length)
        elif kind == 1:
            series = generator.integers(-5, 6, size=length).astype(float)
        else:
            series = np.cumsum(generator.normal(size=length))
        yield series.tolist()


def test_rainflow_counts_equal_the_rainflow_package_on_1000_random_histories():
    for series in histories():
        assert vbi.count_cycles(series) == rainflow.count_cycles(series)


def test_rainflow_cycles_come_in_the_rainflow_package_s_order():
    """Not only the counts: each cycle's range, mean and count, in the order counted."""
    for series in list(histories())[:200]:
        expected = [
            (rng, mean, count)
            for rng, mean, count, _, _ in rainflow.extract_cycles(series)
        ]
        assert vbi.rainflow(series) == expected


def test_astm_e1049_worked_example():
    series = [-2, 1, -3, 5, -1, 3, -4, 4, -2]
    assert vbi.count_cycles([float(x) for x in series]) == [
        (3.0, 0.5),
        (4.0, 1.5),
        (6.0, 0.5),
        (8.0, 1.0),
        (9.0, 0.5),
    ]


def test_run_fatigue_equals_the_cli_summary_bit_for_bit(tmp_path):
    path = EXAMPLES / "fatigue" / "composite-girder-30m.toml"
    completed = run_command("run", str(path), "--out", str(tmp_path))
    assert completed.returncode == 0, completed.stderr
    entries = read_json(tmp_path / "summary.json")["fatigue"]
    result = vbi.run(vbi.Scenario(str(path)))
    assert len(result.fatigue) == len(entries) == 3
    names = [row["name"] for row in vbi.fatigue_outputs()]
    for detail, entry in zip(result.fatigue, entries):
        assert sorted(entry) == sorted(names)
        for name in names:
            value = getattr(detail, name)
            expected = entry[name]
            if expected is None:
                assert value is None, name
            else:
                assert value == expected, f"{detail.detail}.{name}: {value!r} != {expected!r}"
    flange = result.fatigue[0]
    # One legal truck's static range is below category 71's cut-off: no fatigue DAF on the
    # curve, and the straight-line one is defined.
    assert flange.fatigue_daf is None
    assert 1.0 < flange.fatigue_daf_straight_line < 1.5
    assert math.isclose(flange.cut_off, 71e6 * (0.4 ** (1 / 3)) * (0.05**0.2), rel_tol=1e-12)


def test_lifetime_fatigue_equals_the_cli_tables_f64_for_f64(tmp_path):
    """``vbi.lifetime_fatigue`` gives ``vbi lifetime``'s fatigue.csv and fatigue_blocks.csv:
    each number read back from the CSV's shortest round-trip text equals Python's."""
    import csv

    path = EXAMPLES / "fatigue" / "auxerre-3-days-composite-30m.toml"
    completed = run_command("lifetime", str(path), "--out", str(tmp_path))
    assert completed.returncode == 0, completed.stderr
    frame = vbi.lifetime_fatigue(str(path))
    with open(tmp_path / "fatigue.csv", newline="") as handle:
        rows = list(csv.DictReader(handle))
    assert list(frame.columns) == list(rows[0].keys())
    assert len(frame) == len(rows) == 3
    for i, row in enumerate(rows):
        for name, text in row.items():
            value = frame.iloc[i][name]
            if text == "":
                assert value is None or (isinstance(value, float) and math.isnan(value)), name
            elif isinstance(value, str):
                assert value == text, name
            else:
                assert float(value) == float(text), f"{row['detail']}.{name}"
    with open(tmp_path / "fatigue_blocks.csv", newline="") as handle:
        blocks = list(csv.DictReader(handle))
    python_blocks = frame.attrs["blocks"]
    assert len(python_blocks) == len(blocks) == 3
    for b, row in enumerate(blocks):
        for name, text in row.items():
            if name != "block":
                assert python_blocks.iloc[b][name] == float(text), name
