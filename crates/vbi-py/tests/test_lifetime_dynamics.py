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


def frames_equal(merged, whole):
    """Two lifetime frames equal f64 for f64, their attrs and events too."""
    import pandas as pd

    merged_events = merged.attrs.pop("event_totals", None)
    whole_events = whole.attrs.pop("event_totals", None)
    pd.testing.assert_frame_equal(merged, whole, check_exact=True)
    assert merged.attrs == whole.attrs
    if whole_events is not None:
        pd.testing.assert_frame_equal(merged_events, whole_events, check_exact=True)


def test_shards_merged_are_the_single_run_s_frame_and_the_commands_merge(tmp_path):
    """`vbi.lifetime(source, shard=(I, N))` for N = 4 in hourly blocks (the twenty trucks'
    two days: some shards hold no event), merged by `vbi.merge_lifetime` in any order: the
    frame of `vbi.lifetime(source)`, f64 for f64, with its attrs and events; and the shards'
    shard.json texts are the command's (`vbi lifetime --shard`)."""
    source = dynamics_toml(tmp_path)
    text = source.read_text().replace("block_days = 1\n", "block_days = 0.041666666666666664\n")
    source.write_text(text)
    whole = vbi.lifetime(str(source))
    shards = [vbi.lifetime(str(source), shard=(i, 4)) for i in (3, 1, 4, 2)]
    assert [s.attrs["shard"] for s in shards] == ["3/4", "1/4", "4/4", "2/4"]
    assert "total" not in shards[0].columns
    frames_equal(vbi.merge_lifetime(str(source), shards), whole)
    out = tmp_path / "shard-2"
    done = run_command("lifetime", str(source), "--out", str(out), "--shard", "2/4")
    assert done.returncode == 0, done.stderr
    assert json.loads(shards[3].attrs["shard_json"]) == read_json(out / "shard.json")
    try:
        vbi.merge_lifetime(str(source), shards[:3])
    except vbi.InputError as error:
        assert "shards 1 to N" in str(error)
    else:
        raise AssertionError("three of four shards merged")
