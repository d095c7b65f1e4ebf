"""`vbi.lifetime` with dynamics (docs/lifetime.md, "Dynamics on the events that can govern"):
the frame's `total` and `daf` columns are the command's block_maxima.csv, `attrs["event_totals"]`
its events.csv, and the other attrs its lifetime.json, f64 for f64."""

from __future__ import annotations

import json
import math

import vbi
from conftest import EXAMPLES, read_csv, read_json, run_command

LIFETIME = EXAMPLES / "lifetime"


def dynamics_toml(directory) -> str:
    """examples/lifetime/pybtls-20-trucks-1x30.toml with dynamics, the default screening."""
    text = (LIFETIME / "pybtls-20-trucks-1x30.toml").read_text()
    traffic = LIFETIME / "traffic" / "pybtls_written_20_trucks.castor.txt"
    text = text.replace('"traffic/pybtls_written_20_trucks.castor.txt"', json.dumps(str(traffic)))
    text = text.replace("block_days = 1\n", "block_days = 1\ndynamics = true\n")
    path = directory / "twenty-dynamics.toml"
    path.write_text(text)
    return path


def cell(text: str) -> float:
    """A CSV cell as the f64 the command wrote (an empty cell: NaN)."""
    return float(text) if text else math.nan


def same(a: float, b: float) -> bool:
    return a == b or (math.isnan(a) and math.isnan(b))


def test_the_dynamic_frame_and_its_events_are_the_commands_csv_files(tmp_path):
    source = dynamics_toml(tmp_path)
    out = tmp_path / "out"
    done = run_command("lifetime", str(source), "--out", str(out), "--format", "json")
    assert done.returncode == 0, done.stderr
    frame = vbi.lifetime(str(source))
    rows = read_csv(out / "block_maxima.csv")
    assert list(frame.columns) == list(rows[0].keys())
    assert list(frame.columns)[-2:] == ["total", "daf"]
    for row, ours in zip(rows, frame.itertuples(index=False)):
        assert float(row["static"]) == ours.static
        assert float(row["total"]) == ours.total
        assert same(cell(row["daf"]), ours.daf)
    events = frame.attrs.pop("event_totals")
    assert frame.attrs == read_json(out / "lifetime.json")
    assert frame.attrs["dynamics"] is True
    assert frame.attrs["dynamic_events"]["refused"] == 0
    expected = read_csv(out / "events.csv")
    assert list(events.columns) == list(expected[0].keys())
    assert len(events) == len(expected) > 0
    for row, ours in zip(expected, events.itertuples(index=False)):
        assert (int(row["event"]), row["station"], row["quantity"]) == (
            ours.event, ours.station, ours.quantity)
        for name in ("static", "crossing_static", "total", "daf", "time_s"):
            assert same(cell(row[name]), getattr(ours, name)), name
