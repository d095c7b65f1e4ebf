"""The parts of the API: bridges, modes, vehicles, roads, scenarios; arrays without copies;
crossings in Python threads giving the same numbers as one after the other."""

from __future__ import annotations

import re
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pytest

import vbi
from conftest import EXAMPLES

BEAM = EXAMPLES / "bridges" / "ss-beam-25m.toml"


def test_a_bridge_from_a_file_and_from_its_dict_have_the_same_modes():
    import tomllib

    with open(BEAM, "rb") as handle:
        document = tomllib.load(handle)
    from_file = vbi.modes(vbi.Bridge(str(BEAM)), 6)
    from_dict = vbi.modes(vbi.Bridge(document), 6)
    assert np.array_equal(from_file.frequencies_hz, from_dict.frequencies_hz)
    assert np.array_equal(from_file.shapes, from_dict.shapes)


def test_modes_have_frequencies_kinds_and_shapes_of_consistent_sizes():
    bridge = vbi.modes(vbi.Bridge(str(BEAM)), 4)
    n = bridge.mode_count
    assert bridge.frequencies_hz.shape == (n,)
    assert np.all(np.diff(bridge.frequencies_hz) > 0)
    assert bridge.kinds == ["vertical_bending"] * n
    assert bridge.shapes.shape == (bridge.deck_x_m.size, n)
    assert bridge.station_deflection.shape == (len(bridge.station_names), n)
    # A simply supported beam: f1 = (π / 2 L²) √(EI / m) (docs/verification.md).
    ei, m, length = 35e9 * 1.3901, 18358.0, 25.0
    f1 = np.pi / (2 * length**2) * np.sqrt(ei / m)
    assert abs(bridge.frequencies_hz[0] / f1 - 1) < 1e-3


def test_a_vehicle_preset_assembles_to_square_matrices():
    assert "sprung-mass" in vbi.vehicle_presets()
    model = vbi.Vehicle("tractor-semitrailer-5axle").model()
    d = len(model["dof_names"])
    assert model["mass_matrix"].shape == (d, d)
    assert np.array_equal(model["stiffness_matrix"], model["stiffness_matrix"].T)


def test_a_road_profile_is_reproducible_from_its_seed():
    road = vbi.Road("poor")
    x, left, right = road.profile(-10.0, 50.0, seed=4)
    assert x[0] == -10.0 and x[-1] == 50.0
    again = road.profile(-10.0, 50.0, seed=4)
    assert np.array_equal(left, again[1]) and np.array_equal(right, again[2])


def test_large_histories_are_handed_to_numpy_without_copies():
    scenario = vbi.Scenario(str(EXAMPLES / "scenarios" / "inline-beam-quarter-car.toml"))
    result = vbi.run(scenario)
    q = result.modal_displacement
    assert q.shape == (len(result.front_axle_x_m), result.mode_count)
    # The array owns no buffer of its own: Rust's vector is its memory, and every access
    # returns that same array.
    assert not q.flags.owndata
    assert result.modal_displacement is q
    assert result.histories["front_axle_x_m"] is result.front_axle_x_m


def test_crossings_in_python_threads_equal_crossings_one_after_the_other():
    scenario = vbi.Scenario(str(EXAMPLES / "scenarios" / "inline-beam-quarter-car.toml"))
    bridge = vbi.prepare(scenario)
    scenarios = [scenario.copy().set("seed", seed) for seed in range(1, 5)]
    one_by_one = [vbi.run(s, bridge).rdm for s in scenarios]
    with ThreadPoolExecutor(max_workers=2) as pool:
        in_threads = list(pool.map(lambda s: vbi.run(s, bridge).rdm, scenarios))
    assert in_threads == one_by_one
    assert len(set(one_by_one)) == len(one_by_one)


def test_the_histories_dataframe_has_units_in_its_column_names():
    scenario = vbi.Scenario(str(EXAMPLES / "scenarios" / "inline-beam-quarter-car.toml"))
    frame = vbi.run(scenario).to_dataframe()
    assert frame.columns[0] == "time_s"
    assert all(c.endswith(("_s", "_m", "_n_m", "_n", "_m_s2")) for c in frame.columns)


def test_a_skewed_grillage_reports_its_deck_extent_beyond_its_length():
    """examples/bridges/skewed-2x20.toml: 2 x 20 m along the girders; the outer girders'
    supports are 2 x 2.9 m x tan 30 degrees apart, so the deck reaches that much further; the
    deck nodes of the outer girder start there."""
    bridge = vbi.Bridge(str(EXAMPLES / "bridges" / "skewed-2x20.toml"))
    assert bridge.length_m == 40.0
    offset = 5.8 * np.tan(np.radians(30.0))
    assert abs(bridge.deck_length_m - (40.0 + offset)) < 1e-9
    prepared = vbi.modes(bridge, 6)
    assert abs(prepared.deck_x_m.max() - bridge.deck_length_m) < 1e-9


def test_station_outputs_are_the_station_daf_attributes_and_its_typed_stub():
    """The table of station outputs is what a StationDaf answers (and only that), and the type
    stub _vbi.pyi declares exactly its rows, in order, so that editors see every output."""
    rows = vbi.station_outputs()
    names = [row["name"] for row in rows]
    assert names[:2] == ["name", "quantity"] and "daf" in names and "daf_paper" in names
    for row in rows:
        assert row["label"] and row["meaning"], row
    entry = vbi.run(vbi.Scenario()).stations[0]
    assert sorted(dir(entry)) == sorted(names)
    for name in names:
        getattr(entry, name)
    with pytest.raises(AttributeError):
        entry.no_such_output
    stub = (Path(vbi.__file__).parent / "_vbi.pyi").read_text()
    block = stub.split("class StationDaf:")[1].split("\nclass ")[0]
    declared = re.findall(r"def (\w+)\(self\)", block)
    assert declared == names


def test_every_daf_carries_its_check_modes_and_the_change_covers_them():
    """Issue 46, item 5: the default run's entries are continued over the check modes (modes
    above N up to twice the N-th frequency), and the convergence indicator is at least twice
    their largest change from the DAF (docs/theory.md, "Convergence indicator")."""
    result = vbi.run(vbi.Scenario())
    counts = set()
    for entry in result.stations:
        if entry.daf is None:
            continue
        check = list(entry.daf_by_check_modes)
        counts.add(len(check))
        largest = max(abs(d - entry.daf) for d in check)
        assert entry.daf_change >= 2 * largest - 1e-15, entry.name
    assert len(counts) == 1 and counts.pop() > 0


def test_a_run_checks_its_time_step_and_names_its_static_reference():
    """Issue 46: every DAF at the default step carries DAF(Δt) − DAF(2Δt), within 0.1 % for
    deflections and moments (the check holds), none when the check is off; with two trucks each
    deflection and moment entry has the heaviest single vehicle's static extreme and the DAF
    against it (docs/theory.md)."""
    scenario = vbi.Scenario(str(EXAMPLES / "scenarios" / "two-trucks-opposite-lanes.toml"))
    result = vbi.run(scenario)
    checked = [
        e for e in result.stations
        if str(e.quantity) in ("deflection", "bending_moment") and e.daf is not None
    ]
    assert checked
    for e in checked:
        assert abs(e.daf_change_dt) <= 1e-3 * e.daf, (e.name, e.daf_change_dt)
        assert e.static_max_single_vehicle is not None
        assert e.daf_single_vehicle == pytest.approx(
            e.dynamic_max / e.static_max_single_vehicle, rel=1e-12
        )
    unchecked = vbi.run(scenario.copy().set("time_step_check", False))
    assert all(e.daf_change_dt is None for e in unchecked.stations)
