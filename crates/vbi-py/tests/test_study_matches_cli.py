"""`vbi.study` gives the case table of `vbi study` for the same study file, cell for cell (the
CSV's text read back exactly), and a study split into shards gives the whole study's table."""

from __future__ import annotations

import math

import pandas as pd
import pytest

import vbi
from conftest import read_csv, run_command

# A small study: a 25 m beam, two speeds, two roughness samples each, 6 modes.
STUDY = {
    "study": {
        "name": "small",
        "seed": 11,
        "samples": 2,
        "axes": {"speed_kmh": [60, 100]},
    },
    "scenario": {
        "bridge": "paper-1x25",
        "vehicle": "two-axle-truck-vbi2d",
        "road": "good",
        "modes": 6,
        "element_length_m": 2.5,
    },
}


def write_toml(path, document) -> None:
    """The study document as TOML (the tables used here are flat or one level deep)."""

    def value(v):
        if isinstance(v, str):
            return '"' + v + '"'
        if isinstance(v, list):
            return "[" + ", ".join(value(x) for x in v) + "]"
        return repr(v)

    lines = []
    for table, keys in [("study", STUDY["study"]), ("scenario", STUDY["scenario"])]:
        lines.append(f"[{table}]")
        lines += [f"{k} = {value(v)}" for k, v in keys.items() if not isinstance(v, dict)]
        for k, v in keys.items():
            if isinstance(v, dict):
                lines.append(f"[{table}.{k}]")
                lines += [f"{kk} = {value(vv)}" for kk, vv in v.items()]
    path.write_text("\n".join(lines) + "\n")


@pytest.fixture(scope="module")
def cli_tables(tmp_path_factory):
    directory = tmp_path_factory.mktemp("study")
    path = directory / "small.toml"
    write_toml(path, STUDY)
    out = directory / "out"
    completed = run_command("study", str(path), "--out", str(out), "--no-figures")
    assert completed.returncode == 0, completed.stderr
    return path, {
        name: read_csv(out / f"{name}.csv")
        for name in ("cases", "daf_by_modes", "participation", "design_codes")
    }


def cell_of(value) -> str:
    """A DataFrame value as its CSV cell (exact: repr of a float is its shortest text)."""
    if value is None or value is pd.NA or (isinstance(value, float) and math.isnan(value)):
        return ""
    if isinstance(value, float):
        text = repr(value)
        return text[:-2] if text.endswith(".0") else text
    return str(value)


def assert_frame_equals_rows(frame: pd.DataFrame, rows) -> None:
    assert list(frame.columns) == list(rows[0])
    assert len(frame) == len(rows)
    for index, row in enumerate(rows):
        for column, cell in row.items():
            value = frame[column].iloc[index]
            text = ("case", "rdm_station", "warnings", "error", "kind", "quantity", "code")
            if cell and column not in text + ("provision", "basis"):
                # Compare numbers as numbers, exactly.
                assert float(value) == float(cell), (index, column)
            else:
                assert cell_of(value) == cell, (index, column)


def test_the_study_case_table_equals_the_cli_cases_csv(cli_tables):
    path, tables = cli_tables
    assert_frame_equals_rows(vbi.study(str(path)), tables["cases"])


def test_the_study_tables_of_a_dict_equal_the_cli_tables(cli_tables):
    _, tables = cli_tables
    frames = vbi.study_tables(STUDY)
    for name, rows in tables.items():
        if name == "cases":
            # The study's name comes from the document, its cases' ids from the spec.
            assert list(frames[name]["case"]) == [r["case"] for r in rows]
        assert_frame_equals_rows(frames[name], rows)


def test_shards_together_give_the_whole_study(cli_tables):
    path, tables = cli_tables
    count = vbi.study_case_count(str(path))
    parts = [vbi.study(str(path), shard=f"{i}/3", threads=1) for i in range(1, 4)]
    assert sum(len(p) for p in parts) == count
    assert_frame_equals_rows(pd.concat(parts, ignore_index=True), tables["cases"])
