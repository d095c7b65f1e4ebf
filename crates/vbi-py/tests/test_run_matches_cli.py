"""`vbi.run` gives the numbers of `vbi run --out DIR --format json` for the same scenario file,
bit for bit: every number of summary.json, histories.csv, daf_by_modes.csv and
participation.csv compared with `==` (the CSV's shortest round-trip text reads back as the
exact f64)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import vbi
from conftest import EXAMPLES, read_csv, read_json, run_command

# Scenarios of the examples that run in seconds: a two-span beam with a sprung mass and
# re-runs with fewer modes; an inline beam with a quarter-car; a beam modelled in OpenSees,
# imported as its matrices; two trucks on five I-girders with barriers, diaphragms and
# elastomeric bearings; a skewed grillage; imported modes with their influence lines.
SCENARIOS = [
    EXAMPLES / "scenarios" / "two-span-sprung-mass.toml",
    EXAMPLES / "scenarios" / "inline-beam-quarter-car.toml",
    EXAMPLES / "scenarios" / "opensees-two-span-beam.toml",
    EXAMPLES / "scenarios" / "i-girder-two-trucks.toml",
    EXAMPLES / "scenarios" / "skewed-bridge.toml",
    EXAMPLES / "scenarios" / "imported-modes-with-lines.toml",
]


def same(python_value, cli_value) -> bool:
    """Exact equality, None for JSON null, NaN for a missing array element."""
    if cli_value is None:
        return python_value is None or (
            isinstance(python_value, float) and math.isnan(python_value)
        )
    return python_value == cli_value


def assert_same_list(python_values, cli_values, what: str) -> None:
    python_values = list(python_values)
    assert len(python_values) == len(cli_values), what
    for k, (p, c) in enumerate(zip(python_values, cli_values)):
        assert same(p, c), f"{what}[{k}]: python {p!r} != cli {c!r}"


@pytest.fixture(scope="module", params=SCENARIOS, ids=lambda p: p.stem)
def both(request, tmp_path_factory):
    """The CLI's output directory and Python's result for one scenario file."""
    path: Path = request.param
    out = tmp_path_factory.mktemp(path.stem)
    completed = run_command("run", str(path), "--out", str(out), "--format", "json")
    assert completed.returncode == 0, completed.stderr
    return out, vbi.run(vbi.Scenario(str(path)))


def test_station_dafs_equal_the_cli_summary_bit_for_bit(both):
    """Every row of the library's table of station outputs that summary.json carries, read as
    a StationDaf attribute, equals the command's entry bit for bit; the entry has no other key."""
    out, result = both
    summary = read_json(out / "summary.json")
    rows = [row["name"] for row in vbi.station_outputs() if row["in_run_summary"]]
    assert len(result.stations) == len(summary["stations"])
    for python, cli in zip(result.stations, summary["stations"]):
        assert list(cli) == rows
        assert (python.name, python.quantity) == (cli["name"], cli["quantity"])
        for field in rows[2:]:
            value = getattr(python, field)
            if isinstance(value, np.ndarray):
                assert_same_list(value, cli[field], f"{cli['name']} {field}")
            else:
                assert same(value, cli[field]), f"{cli['name']} {field}"


def test_rdm_frequencies_participation_and_provenance_equal_the_cli_summary(both):
    out, result = both
    summary = read_json(out / "summary.json")
    assert result.rdm_station == summary["rdm_station"]
    assert same(result.rdm, summary["rdm"])
    assert same(result.rdm_paper, summary["rdm_paper"])
    assert_same_list(result.rdm_by_modes, summary["rdm_by_modes"], "rdm_by_modes")
    assert_same_list(
        result.rdm_paper_by_modes, summary["rdm_paper_by_modes"], "rdm_paper_by_modes"
    )
    assert_same_list(result.frequencies_hz, summary["frequencies_hz"], "frequencies_hz")
    deck = summary["deck_participation"]
    for key in ("deflection", "deflection_cumulative", "moment", "moment_cumulative"):
        assert_same_list(result.deck_participation[key], deck[key], key)
    cutoffs = result.cutoff_modes
    for key in ("deflection_k1", "deflection_k2", "moment_k1", "moment_k2"):
        assert cutoffs[key] == deck[key], key
    for key, value in deck["vertical_bending"].items():
        assert cutoffs[f"bending_{key}"] == value, key
    assert [
        [loss["contact"], loss["start_time_s"], loss["end_time_s"], loss["minimum_force_n"]]
        for loss in result.contact_losses
    ] == [
        [loss["contact"], loss["start_time"], loss["end_time"], loss["minimum_force"]]
        for loss in summary["contact_losses"]
    ]
    provenance = summary["provenance"]
    assert result.time_step_s == provenance["time_step_s"]
    assert result.mode_count == provenance["modes"]
    assert result.dof_count == provenance["dof_count"]
    assert result.scenario_name == provenance["scenario"]
    assert result.vehicle_name == provenance["vehicle"]


def test_truncated_reruns_equal_the_cli_summary(both):
    out, result = both
    cli_runs = read_json(out / "summary.json")["truncated_runs"]
    assert len(result.truncated_runs) == len(cli_runs)
    for python, cli in zip(result.truncated_runs, cli_runs):
        assert python["mode_count"] == cli["mode_count"]
        assert same(python["rdm"], cli["rdm"])
        assert [(s["name"], s["quantity"], s["daf"]) for s in python["stations"]] == [
            (s["name"], s["quantity"], s["daf"]) for s in cli["stations"]
        ]


def test_design_codes_equal_the_cli_design_codes_csv(both):
    out, result = both
    rows = read_csv(out / "design_codes.csv")
    assert len(result.design_codes) == len(rows)
    for python, cli in zip(result.design_codes, rows):
        for key in ("station", "quantity", "code", "provision", "clause", "basis"):
            assert python[key] == cli[key], key
        assert python["impact_factor"] == float(cli["impact_factor"])
        assert python["code_daf"] == float(cli["code_daf"])
        computed = float(cli["computed_daf"]) if cli["computed_daf"] else None
        assert python["computed_daf"] == computed


def assert_columns_equal_the_csv(columns, path: Path) -> None:
    """Same column names in the same order, every value equal with `==`."""
    rows = read_csv(path)
    assert list(columns) == list(rows[0])
    for column, values in columns.items():
        expected = np.array([float(row[column]) for row in rows])
        assert values.shape == expected.shape, column
        assert np.array_equal(values, expected), column


def test_histories_equal_the_cli_histories_csv_bit_for_bit(both):
    out, result = both
    assert_columns_equal_the_csv(result.histories, out / "histories.csv")


def test_vehicle_histories_equal_the_cli_vehicles_csv_bit_for_bit(both):
    out, result = both
    assert_columns_equal_the_csv(result.vehicle_histories, out / "vehicles.csv")


def test_oncoming_traffic_from_a_dict_equals_the_cli_bit_for_bit(tmp_path):
    """A crossing event with a second vehicle in the opposite lane, given as a dict with a
    `traffic` list, gives the numbers of the same scenario file run by the command."""
    text = (
        '[scenario]\nbridge = "paper-1x20"\nvehicle = "quarter-car"\nroad = "good"\n'
        'modes = 6\nlateral_position_m = 1.5\n\n[[traffic]]\nvehicle = "quarter-car"\n'
        'direction = "backward"\nlateral_position_m = -1.5\nentry_time_s = 1.0\n'
    )
    path = tmp_path / "meeting.toml"
    path.write_text(text)
    out = tmp_path / "out"
    completed = run_command("run", str(path), "--out", str(out), "--format", "json")
    assert completed.returncode == 0, completed.stderr
    scenario = vbi.Scenario(
        {
            "scenario": {
                "bridge": "paper-1x20",
                "vehicle": "quarter-car",
                "road": "good",
                "modes": 6,
                "lateral_position_m": 1.5,
            },
            "traffic": [
                {
                    "vehicle": "quarter-car",
                    "direction": "backward",
                    "lateral_position_m": -1.5,
                    "entry_time_s": 1.0,
                }
            ],
        }
    )
    result = vbi.run(scenario)
    summary = read_json(out / "summary.json")
    for entry, station in zip(summary["stations"], result.stations):
        assert same(station.daf, entry["daf"]), entry["name"]
    rows = read_csv(out / "vehicles.csv")
    force = np.array([float(row["v2_contact1_force_n"]) for row in rows])
    assert np.array_equal(result.vehicle_histories["v2_contact1_force_n"], force)


def test_daf_by_modes_and_participation_equal_the_cli_tables(both):
    out, result = both
    rows = read_csv(out / "daf_by_modes.csv")
    expected = [
        (r["station"], r["quantity"], int(r["modes"]), float(r["daf"])) for r in rows
    ]
    actual = [
        (s.name, s.quantity, k + 1, daf)
        for s in result.stations
        for k, daf in enumerate(s.daf_by_modes)
    ]
    assert actual == expected
    rows = read_csv(out / "participation.csv")
    deck = result.deck_participation
    assert [float(r["mps_deflection"]) for r in rows] == list(deck["deflection"])
    assert [float(r["mps_moment"]) for r in rows] == list(deck["moment"])
    assert [float(r["frequency_hz"]) for r in rows] == list(result.frequencies_hz)


def test_the_same_scenario_as_a_dict_gives_the_same_result():
    import tomllib

    path = EXAMPLES / "scenarios" / "inline-beam-quarter-car.toml"
    with open(path, "rb") as handle:
        document = tomllib.load(handle)
    from_file = vbi.run(vbi.Scenario(str(path)))
    from_dict = vbi.run(vbi.Scenario(document))
    assert [s.daf for s in from_dict.stations] == [s.daf for s in from_file.stations]
    assert np.array_equal(from_dict.modal_displacement, from_file.modal_displacement)
