"""examples/import/sap2000/sap2000_to_vbi.py on tables in SAP2000's layout, without SAP2000.

vbi's own six modes of examples/bridges/two-span-beam.toml (`vbi modes --out`) and the modal
moments of examples/bridges/imported/station_moments.csv (the same FE modes) are written as the
SAP2000 database tables "Modal Periods And Frequencies", "Joint Coordinates", "Joint
Displacements" and "Element Forces - Frames" (field names, a units row under them, a title row
on one table), in N,m and in KN,mm. The converter's bridge must pass `vbi check`, list the same
frequencies, and give the same static deflection at span1_mid_section as the imported example
with the same six modes. This tests the converter on the documented layout, not on files written
by SAP2000 itself.
"""

from __future__ import annotations

import csv
import math
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import EXAMPLES, read_csv, read_json, run_command

CONVERTER = EXAMPLES / "import" / "sap2000" / "sap2000_to_vbi.py"
IMPORTED = EXAMPLES / "bridges" / "imported"
MODES = 6
PIER_JOINT = "100"  # a joint below the deck, left out by the --deck-z rule

UNIT_SETS = {
    # (force name, length name): newtons per force unit, metres per length unit
    ("N", "m"): (1.0, 1.0),
    ("KN", "mm"): (1.0e3, 1.0e-3),
}


def write_table(path: Path, title, fields, units, rows) -> None:
    with open(path, "w", newline="") as handle:
        writer = csv.writer(handle)
        if title:
            writer.writerow([f"TABLE:  {title}"])
        writer.writerow(fields)
        writer.writerow(units)
        for row in rows:
            writer.writerow(row)


def imported_moments():
    rows = [row for row in csv.reader(open(IMPORTED / "station_moments.csv")) if row and not row[0].startswith("#")]
    header, body = rows[0], rows[1:]
    return {row[0]: (float(row[1]), [float(v) for v in row[4:4 + MODES]]) for row in body}, header


def sap2000_tables(directory: Path, force: str, length: str):
    """vbi's modes of the two-span beam written as SAP2000 tables in units force, length."""
    f, l = UNIT_SETS[(force, length)]
    modes_dir = directory / "vbi_modes"
    result = run_command("modes", str(EXAMPLES / "bridges" / "two-span-beam.toml"), "--modes", str(MODES),
                         "--format", "json", "--out", str(modes_dir))
    assert result.returncode == 0, result.stderr
    modes = read_csv(modes_dir / "modes.csv")
    shapes = read_csv(modes_dir / "mode_shapes.csv")
    # A mass-normalised shape in kg, m becomes phi [L] = phi [m] * sqrt(f / l) in F, L, s units.
    shape_scale = math.sqrt(f / l)
    moment_scale = 1.0 / (f * l / math.sqrt(f * l))

    periods = directory / "modal_periods_and_frequencies.csv"
    write_table(periods, None,
                ["OutputCase", "StepType", "StepNum", "Period", "Frequency", "CircFreq", "Eigenval"],
                ["Text", "Text", "Unitless", "Sec", "Cyc/sec", "rad/sec", "rad2/sec2"],
                [["MODAL", "Mode", f"{k}", repr(1.0 / float(m["frequency_hz"])), m["frequency_hz"],
                  repr(2 * math.pi * float(m["frequency_hz"])), repr((2 * math.pi * float(m["frequency_hz"])) ** 2)]
                 for k, m in enumerate(modes, start=1)])

    joints = [(str(int(row["node"]) + 1), float(row["x_m"]), row) for row in shapes]
    coordinates = directory / "joint_coordinates.csv"
    write_table(coordinates, "Joint Coordinates",
                ["Joint", "CoordSys", "CoordType", "XorR", "Y", "Z", "SpecialJt", "GlobalX", "GlobalY", "GlobalZ"],
                ["Text", "Text", "Text", length, length, length, "Yes/No", length, length, length],
                [[name, "GLOBAL", "Cartesian", repr(x / l), "0", "0", "No", repr(x / l), "0", "0"]
                 for name, x, _ in joints]
                + [[PIER_JOINT, "GLOBAL", "Cartesian", repr(20.0 / l), "0", repr(-5.0 / l), "No",
                    repr(20.0 / l), "0", repr(-5.0 / l)]])

    displacements = directory / "joint_displacements.csv"
    rows = []
    for k in range(1, MODES + 1):
        for name, _, row in joints:
            rows.append([name, "MODAL", "LinModal", "Mode", f"{k}", "0", "0",
                         repr(float(row[f"mode_{k}"]) * shape_scale), "0", "0", "0"])
        rows.append([PIER_JOINT, "MODAL", "LinModal", "Mode", f"{k}", "0", "0", "0", "0", "0", "0"])
    write_table(displacements, None,
                ["Joint", "OutputCase", "CaseType", "StepType", "StepNum", "U1", "U2", "U3", "R1", "R2", "R3"],
                ["Text", "Text", "Text", "Text", "Unitless", length, length, length, "Radians", "Radians", "Radians"],
                rows)

    # Modal moments at x = 10 m and 30 m: Station 0 of the 1 m frames "11" and "31" (joints 11-12, 31-32).
    moments, _ = imported_moments()
    frames = directory / "element_forces_frames.csv"
    rows = []
    for name, frame in (("span1_mid_section", "11"), ("span2_mid_section", "31")):
        _, values = moments[name]
        for k in range(1, MODES + 1):
            rows.append([frame, "0", "MODAL", "LinModal", "Mode", f"{k}", "0", "0", "0", "0", "0",
                         repr(values[k - 1] * moment_scale), f"{frame}-1", "0"])
    write_table(frames, None,
                ["Frame", "Station", "OutputCase", "CaseType", "StepType", "StepNum", "P", "V2", "V3", "T",
                 "M2", "M3", "FrameElem", "ElemStation"],
                ["Text", length, "Text", "Text", "Text", "Unitless", force, force, force, f"{force}-{length}",
                 f"{force}-{length}", f"{force}-{length}", "Text", length],
                rows)
    return modes, periods, coordinates, displacements, frames


def convert(directory: Path, force: str, length: str):
    modes, periods, coordinates, displacements, frames = sap2000_tables(directory, force, length)
    out = directory / "bridge"
    result = subprocess.run(
        [sys.executable, "-B", str(CONVERTER), "--periods", str(periods), "--displacements", str(displacements),
         "--coordinates", str(coordinates), "--frame-forces", str(frames), "--units", f"{force},{length}",
         "--deck-z", "0", "--span-lengths-m", "20,20", "--damping-ratio", "0.0",
         "--station", "span1_mid_section", "11", "0", "10",
         "--station", "span2_mid_section", "31", "0", "30", "--out", str(out)],
        capture_output=True, text=True, check=False)
    assert result.returncode == 0, result.stderr
    return modes, out / "bridge.toml"


def crossing(directory: Path, bridge: Path, name: str):
    scenario = directory / f"{name}.toml"
    scenario.write_text(
        f'[scenario]\nbridge = "{bridge.as_posix()}"\nvehicle = "three-axle-truck-36t"\nroad = "good"\n'
        f"speed_kmh = 80\nmodes = {MODES}\n")
    out = directory / f"{name}_out"
    result = run_command("run", str(scenario), "--format", "json", "--out", str(out))
    assert result.returncode == 0, result.stderr
    summary = read_json(out / "summary.json")
    return {(s["name"], s["quantity"]): s for s in summary["stations"]}


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    return crossing(tmp_path_factory.mktemp("sap_reference"), IMPORTED / "two-span-imported.toml", "imported")


@pytest.mark.parametrize("units", [("N", "m"), ("KN", "mm")], ids=["N-m", "KN-mm"])
def test_sap2000_tables_become_the_same_bridge(tmp_path, units, reference):
    modes, bridge = convert(tmp_path, *units)

    # (a) vbi check accepts the bridge (and its CSV files).
    checked = run_command("check", str(bridge))
    assert checked.returncode == 0, checked.stderr + checked.stdout

    # (b) the same frequencies as vbi's own modes, to 1e-9 relative.
    listed = run_command("modes", str(bridge), "--modes", str(MODES), "--format", "json")
    assert listed.returncode == 0, listed.stderr
    import json
    frequencies = [m["frequency_hz"] for m in json.loads(listed.stdout)["modes"]]
    expected = [float(m["frequency_hz"]) for m in modes]
    assert len(frequencies) == MODES
    for got, want in zip(frequencies, expected):
        assert abs(got - want) <= 1e-9 * want

    # The pier joint below the deck is not a deck node: one line of 41 nodes, 0..40 m.
    shapes = [row for row in csv.reader(open(bridge.parent / "shapes.csv")) if row and not row[0].startswith("#")]
    assert len(shapes) == 1 + 41 and {row[0] for row in shapes[1:]} == {"0.0"}

    # (c) a crossing on it: the static deflection at span1_mid_section equals that on the imported
    # example with the same 6 modes (same truncated modal flexibility) to 1e-3 relative.
    stations = crossing(tmp_path, bridge, "sap2000")
    for key in (("span1_mid_section", "deflection"), ("span1_mid_section", "bending_moment")):
        got, want = stations[key], reference[key]
        assert abs(got["static_max"] - want["static_max"]) <= 1e-3 * abs(want["static_max"]), key
        assert abs(got["dynamic_max"] - want["dynamic_max"]) <= 1e-3 * abs(want["dynamic_max"]), key


def test_units_row_must_match_the_model_units(tmp_path):
    """Tables exported in mm while --units says m: refused, since phi^T M phi = 1 holds in the
    model's units and the script cannot rescale a shape from its length unit alone."""
    _, periods, coordinates, displacements, _ = sap2000_tables(tmp_path, "KN", "mm")
    result = subprocess.run(
        [sys.executable, "-B", str(CONVERTER), "--periods", str(periods), "--displacements", str(displacements),
         "--coordinates", str(coordinates), "--units", "KN,m", "--deck-z", "0",
         "--span-lengths-m", "20,20", "--out", str(tmp_path / "bad")],
        capture_output=True, text=True, check=False)
    assert result.returncode == 2 and "'mm'" in result.stderr
