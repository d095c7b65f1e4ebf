#!/usr/bin/env python3
"""SAP2000 / CSiBridge modal database tables -> a vbi bridge of type "imported".

Reads the tables SAP2000 exports (Display > Show Tables, then File > Export to Excel/Access/text;
saved or exported as CSV) and writes frequencies.csv, shapes.csv, optionally
station_moments.csv, and bridge.toml (docs/input-format.md, "Imported modes" and "Imported modal
data").

Tables read (field names as CSI's database tables and OAPI name them; see README.md for the
sources and for what could not be confirmed from CSI's own documentation):

  "Modal Periods And Frequencies": OutputCase, StepType, StepNum, Period, Frequency, CircFreq,
      Eigenval (units row: Sec, Cyc/sec, rad/sec, rad2/sec2). The OAPI counterpart is
      SapModel.Results.ModalPeriod(NumberResults, LoadCase, StepType, StepNum, Period, Frequency,
      CircFreq, EigenValue).
  "Joint Displacements" of the modal case: Joint, OutputCase, CaseType, StepType, StepNum, U1,
      U2, U3, R1, R2, R3 (StepType "Mode", StepNum = mode number). U3 is the global Z
      translation, Z up in SAP2000's default global system, so U3 is vbi's upward deflection.
  "Joint Coordinates": Joint, ..., GlobalX, GlobalY, GlobalZ (or XorR, Y, Z in the GLOBAL
      Cartesian system when the Global* fields are absent).
  "Element Forces - Frames" (optional): Frame, Station, OutputCase, CaseType, StepType, StepNum,
      P, V2, V3, T, M2, M3, ... ; M3 is the moment about the frame's local 3 axis (major axis of
      a horizontal girder with the default local axes).

CSV handling: an optional title row ("TABLE:  Joint Displacements") before the field names is
skipped, and the units row CSI writes under the field names is read when present (and used to
check/convert lengths); without it the units given by --units apply.

Mass normalisation: CSI's eigenvectors are scaled so that phi^T M phi = 1 (CSI Analysis
Reference Manual, chapter "Modal Analysis"). This script assumes that this holds in the model's
consistent units F, L, s (mass unit F*s^2/L) given by --units, i.e. the units in which the tables
were exported. vbi wants phi^T M phi = 1 with M in kg and phi in m, so
    phi_vbi [m] = phi_table [L] * sqrt(l / f),   l = metres per L, f = newtons per F,
and a modal moment (per unit modal coordinate) M_vbi [N*m] = M3_table [F*L] * f * l * (1 / sqrt(l f)).
With --units N,m both factors are 1. Check the scale on one known static deflection before
trusting a conversion in other units (README.md).

Sources relied on (public, third-party copies where CSI's own page was not reachable):
  - field names of "Modal Periods And Frequencies": CSI OAPI cAnalysisResults.ModalPeriod
    (LoadCase, StepType, StepNum, Period, Frequency, CircFreq, EigenValue) as called in public
    OAPI scripts; table name as used by CSI table-export scripts. Not confirmed from a CSI page.
  - "Joint Displacements" / "Element Forces - Frames" names and the U1..R3, P..M3 fields: CSI
    OAPI JointDispl / FrameForce and wiki.csiamerica.com ("output database tables for joint
    displacements", https://wiki.csiamerica.com/pages/viewpage.action?pageId=6881449).
  - Text database: field data quoted, field names not (Getting Started with SAP2000, v14).
  - phi^T M phi = 1: CSI Analysis Reference Manual, "Modal Analysis" chapter (third-party copy;
    the sentence itself not retrieved verbatim).
  - Global axes: Z up by default; U1, U2, U3 translations along global X, Y, Z.

Usage (see README.md):
    python sap2000_to_vbi.py --periods periods.csv --displacements joint_displacements.csv \
        --coordinates joint_coordinates.csv --units N,m --deck-z 0 \
        --span-lengths-m 20,20 --out DIR \
        [--frame-forces frame_forces.csv --station span1_mid_section 11 0 10 ...]
"""

from __future__ import annotations

import argparse
import csv
import math
import sys
from pathlib import Path
from typing import Dict, List, Optional, Sequence, Tuple

LENGTH_UNITS = {"m": 1.0, "cm": 0.01, "mm": 0.001, "ft": 0.3048, "in": 0.0254}
FORCE_UNITS = {
    "n": 1.0, "kn": 1.0e3, "mn": 1.0e6, "kip": 4448.2216152605, "lb": 4.4482216152605,
    "kgf": 9.80665, "tonf": 9806.65,
}
TOLERANCE_M = 1.0e-6


class ConversionError(Exception):
    pass


def _norm(name: str) -> str:
    return name.strip().lower().replace(" ", "")


def _is_number(text: str) -> bool:
    try:
        float(text)
        return True
    except ValueError:
        return False


def read_table(path: Path, required: Sequence[str]) -> Tuple[List[Dict[str, str]], Dict[str, str]]:
    """Rows of a CSI table exported as CSV (keys normalised to lower case), and its units row
    (column -> unit text, empty when the file has none)."""
    with open(path, newline="", encoding="utf-8-sig") as handle:
        raw = [row for row in csv.reader(handle) if any(cell.strip() for cell in row)]
    wanted = {_norm(name) for name in required}
    header_index = None
    for index, row in enumerate(raw[:10]):
        if wanted <= {_norm(cell) for cell in row}:
            header_index = index
            break
    if header_index is None:
        raise ConversionError(f"{path}: no header row with the fields {', '.join(required)}")
    header = [_norm(cell) for cell in raw[header_index]]
    body = raw[header_index + 1:]
    units: Dict[str, str] = {}
    # CSI writes a units row under the field names ("Text", "m", "Sec", "Cyc/sec", "Unitless").
    if body:
        first = body[0]
        numeric_columns = [i for i, name in enumerate(header)
                           if name in {"stepnum", "u3", "period", "frequency", "globalx", "m3", "station"}
                           and i < len(first)]
        if numeric_columns and not any(_is_number(first[i]) for i in numeric_columns if first[i].strip()):
            units = {name: (first[i].strip() if i < len(first) else "") for i, name in enumerate(header)}
            body = body[1:]
    rows = [{name: (row[i].strip() if i < len(row) else "") for i, name in enumerate(header)} for row in body]
    return rows, units


def length_factor(unit_text: str, where: str) -> float:
    key = unit_text.strip().lower()
    if key not in LENGTH_UNITS:
        raise ConversionError(f"{where}: length unit {unit_text!r} not one of {', '.join(LENGTH_UNITS)}")
    return LENGTH_UNITS[key]


def parse_units(text: str) -> Tuple[float, float, str, str]:
    try:
        force, length = [part.strip() for part in text.split(",")]
    except ValueError:
        raise ConversionError(f"--units {text!r}: expected FORCE,LENGTH such as N,m or KN,mm")
    if force.lower() not in FORCE_UNITS:
        raise ConversionError(f"--units: force unit {force!r} not one of {', '.join(FORCE_UNITS)}")
    return FORCE_UNITS[force.lower()], length_factor(length, "--units"), force, length


def column_length_factor(units: Dict[str, str], column: str, model_length: str, where: str) -> float:
    """Metres per unit of a length column: from the units row when present (it must match the
    model units, since the mass normalisation holds in those), else the model length unit."""
    unit = units.get(column, "")
    if unit and unit.lower() != model_length.lower():
        raise ConversionError(
            f"{where}: column {column} is in {unit!r} but --units says {model_length!r}; export the "
            "tables in the model's units (the mass normalisation phi^T M phi = 1 holds in those)")
    return length_factor(model_length, where)


def is_mode_row(row: Dict[str, str], case: str) -> bool:
    if case and row.get("outputcase", "").lower() != case.lower():
        return False
    step = row.get("steptype", "")
    return step == "" or step.lower() == "mode"


def read_frequencies(path: Path, case: str) -> Dict[int, float]:
    rows, _ = read_table(path, ["OutputCase", "StepNum"])
    out: Dict[int, float] = {}
    for row in rows:
        if not is_mode_row(row, case):
            continue
        mode = int(round(float(row["stepnum"])))
        if row.get("frequency"):
            value = float(row["frequency"])
        elif row.get("circfreq"):
            value = float(row["circfreq"]) / (2.0 * math.pi)
        elif row.get("period"):
            value = 1.0 / float(row["period"])
        else:
            raise ConversionError(f"{path}: mode {mode} has no Frequency, CircFreq or Period")
        out[mode] = value
    if not out:
        raise ConversionError(f"{path}: no rows of OutputCase {case!r} with StepType Mode")
    return out


def read_coordinates(path: Path, model_length: str) -> Dict[str, Tuple[float, float, float]]:
    rows, units = read_table(path, ["Joint"])
    if rows and "globalx" in rows[0]:
        names = ("globalx", "globaly", "globalz")
    elif rows and "xorr" in rows[0]:
        names = ("xorr", "y", "z")
        for row in rows:
            if row.get("coordtype", "Cartesian").lower() != "cartesian" or \
                    row.get("coordsys", "GLOBAL").upper() != "GLOBAL":
                raise ConversionError(f"{path}: joint {row['joint']} is not in GLOBAL Cartesian "
                                      "coordinates and the table has no GlobalX/GlobalY/GlobalZ")
    else:
        raise ConversionError(f"{path}: no GlobalX/GlobalY/GlobalZ (or XorR/Y/Z) fields")
    scale = column_length_factor(units, names[0], model_length, str(path))
    return {row["joint"]: tuple(float(row[n]) * scale for n in names) for row in rows}


def read_displacements(path: Path, case: str) -> Tuple[Dict[Tuple[str, int], Tuple[float, float, float]], Dict[str, str]]:
    rows, units = read_table(path, ["Joint", "OutputCase", "StepNum", "U3"])
    out = {}
    for row in rows:
        if not is_mode_row(row, case):
            continue
        mode = int(round(float(row["stepnum"])))
        out[(row["joint"], mode)] = (float(row.get("u1") or 0.0), float(row.get("u2") or 0.0), float(row["u3"]))
    if not out:
        raise ConversionError(f"{path}: no rows of OutputCase {case!r} with StepType Mode")
    return out, units


def deck_lines(args, coordinates, displaced_joints) -> List[List[str]]:
    if args.line:
        lines = [[name.strip() for name in spec.split(",") if name.strip()] for spec in args.line]
    elif args.deck_z is not None:
        z0 = args.deck_z * LENGTH_UNITS[args.units_length.lower()]
        joints = [j for j in displaced_joints if j in coordinates and abs(coordinates[j][2] - z0) <= args.tolerance_m]
        groups: Dict[int, List[str]] = {}
        for joint in joints:
            groups.setdefault(int(round(coordinates[joint][1] / max(args.tolerance_m, 1e-3))), []).append(joint)
        lines = [groups[key] for key in sorted(groups)]
    else:
        raise ConversionError("give the deck lines: --line J1,J2,... per girder line, or --deck-z Z")
    for line in lines:
        missing = [j for j in line if j not in coordinates]
        if missing:
            raise ConversionError(f"joints {', '.join(missing[:5])} are not in the Joint Coordinates table")
        if len(line) < 2:
            raise ConversionError(f"a deck line needs at least 2 joints: {line}")
    return lines


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--periods", type=Path, required=True, help='"Modal Periods And Frequencies" CSV')
    parser.add_argument("--displacements", type=Path, required=True, help='"Joint Displacements" CSV (modal case)')
    parser.add_argument("--coordinates", type=Path, required=True, help='"Joint Coordinates" CSV')
    parser.add_argument("--frame-forces", type=Path, help='"Element Forces - Frames" CSV (modal case)')
    parser.add_argument("--case", default="MODAL", help="the modal load case name (OutputCase), default MODAL")
    parser.add_argument("--units", default="N,m", help="model units FORCE,LENGTH the tables are in (N,m; KN,m; KN,mm; Kip,in; ...)")
    parser.add_argument("--line", action="append", help="joints of one girder line, comma-separated (repeat per line)")
    parser.add_argument("--deck-z", type=float, help="rule instead of --line: every displaced joint at this GlobalZ "
                        "(model length unit) is a deck node; lines are grouped by GlobalY")
    parser.add_argument("--x-origin", type=float, help="GlobalX of the first support (model length unit); default the smallest deck x")
    parser.add_argument("--centreline-y", type=float, help="GlobalY of the deck centreline (model length unit); default midway between the outer lines")
    parser.add_argument("--span-lengths-m", required=True, help="spans in metres, comma-separated, adding up to the deck length")
    parser.add_argument("--modes", type=int, help="keep the first N modes")
    parser.add_argument("--damping-ratio", type=float, help="bridge damping_ratio for every mode (vbi's default 0.05 otherwise)")
    parser.add_argument("--station", nargs=4, action="append", metavar=("NAME", "FRAME", "STATION", "X_M"),
                        help="a station: its name, the frame and the Station value (model length unit) "
                        "of its M3 rows in the frame forces table, and its x along the deck in metres")
    parser.add_argument("--station-target", nargs=2, action="append", metavar=("NAME", "TARGET"),
                        help="target of a station: section (default) or girder_<k>")
    parser.add_argument("--moment-sign", type=float, default=1.0, choices=[1.0, -1.0],
                        help="multiply M3 by this to get vbi's sagging-positive moment (default +1)")
    parser.add_argument("--tolerance-m", type=float, default=TOLERANCE_M, help="position tolerance in metres")
    parser.add_argument("--out", type=Path, required=True, help="directory for the vbi files")
    args = parser.parse_args(argv)
    try:
        write(args)
    except ConversionError as error:
        print(f"sap2000_to_vbi: {error}", file=sys.stderr)
        return 2
    return 0


def write(args) -> None:
    f, l, force_name, length_name = parse_units(args.units)
    args.units_length = length_name
    shape_scale = math.sqrt(l / f)          # phi [L], normalised in F-L-s  ->  phi [m], normalised in kg
    moment_scale = f * l / math.sqrt(l * f)  # M3 [F*L] per CSI modal coordinate -> N*m per vbi's

    frequencies = read_frequencies(args.periods, args.case)
    modes = sorted(frequencies)
    if modes != list(range(1, len(modes) + 1)):
        raise ConversionError(f"{args.periods}: modes are not numbered 1..N: {modes[:10]}")
    if args.modes:
        modes = modes[: args.modes]
    coordinates = read_coordinates(args.coordinates, length_name)
    displacements, displacement_units = read_displacements(args.displacements, args.case)
    u_scale = column_length_factor(displacement_units, "u3", length_name, str(args.displacements)) / l * shape_scale
    displaced = sorted({joint for joint, _ in displacements})
    lines = deck_lines(args, coordinates, displaced)

    all_joints = [j for line in lines for j in line]
    x0 = args.x_origin * l if args.x_origin is not None else min(coordinates[j][0] for j in all_joints)
    line_ys = [sum(coordinates[j][1] for j in line) / len(line) for line in lines]
    yc = args.centreline_y * l if args.centreline_y is not None else 0.5 * (min(line_ys) + max(line_ys))

    rows = []
    energy = {m: [0.0, 0.0, 0.0] for m in modes}
    for line, y in sorted(zip(lines, line_ys), key=lambda item: item[1]):
        for joint in sorted(line, key=lambda j: coordinates[j][0]):
            x = coordinates[joint][0] - x0
            if x < -args.tolerance_m:
                raise ConversionError(f"joint {joint} lies before the x origin ({x:.6g} m)")
            values = []
            for mode in modes:
                if (joint, mode) not in displacements:
                    raise ConversionError(f"{args.displacements}: no row for joint {joint}, mode {mode}")
                u = displacements[(joint, mode)]
                for k in range(3):
                    energy[mode][k] += u[k] ** 2
                values.append(u[2] * u_scale)
            rows.append((y - yc, max(x, 0.0), values))
    deck_length = max(row[1] for row in rows)

    spans = [float(s) for s in args.span_lengths_m.split(",")]
    if any(s <= 0 for s in spans) or abs(sum(spans) - deck_length) > 1e-6 * max(1.0, deck_length):
        raise ConversionError(f"--span-lengths-m {spans} do not add up to the deck length {deck_length:.9g} m")
    supports = [sum(spans[:i]) for i in range(1, len(spans))]

    # A mode whose deck motion is mostly horizontal is lateral/longitudinal; vbi classifies the rest.
    kinds = {}
    for mode in modes:
        u1, u2, u3 = energy[mode]
        kinds[mode] = "" if u3 >= max(u1, u2) else ("lateral" if u2 >= u1 else "longitudinal")

    out = args.out
    out.mkdir(parents=True, exist_ok=True)
    note = (f"# Converted by examples/import/sap2000/sap2000_to_vbi.py from SAP2000 tables "
            f"(case {args.case}, units {force_name},{length_name}); shapes mass-normalised in kg, m.\n")
    with open(out / "frequencies.csv", "w", newline="") as handle:
        handle.write(note)
        handle.write("mode,frequency_hz,damping_ratio,kind\n")
        for index, mode in enumerate(modes, start=1):
            handle.write(f"{index},{frequencies[mode]!r},,{kinds[mode]}\n")
    header = ",".join(f"mode_{i}" for i in range(1, len(modes) + 1))
    with open(out / "shapes.csv", "w", newline="") as handle:
        handle.write(note)
        handle.write(f"line_y_m,x_m,{header}\n")
        for y, x, values in rows:
            handle.write(",".join([repr(y + 0.0), repr(x)] + [repr(v) for v in values]) + "\n")

    station_file = None
    if args.station:
        if not args.frame_forces:
            raise ConversionError("--station needs --frame-forces")
        forces, force_units = read_table(args.frame_forces, ["Frame", "Station", "OutputCase", "StepNum", "M3"])
        station_scale = column_length_factor(force_units, "station", length_name, str(args.frame_forces))
        m3_unit = force_units.get("m3", "")
        if m3_unit and m3_unit.replace(" ", "").lower() != f"{force_name}-{length_name}".lower():
            raise ConversionError(f"{args.frame_forces}: M3 is in {m3_unit!r}, not {force_name}-{length_name}")
        targets = dict(args.station_target or [])
        station_file = out / "station_moments.csv"
        with open(station_file, "w", newline="") as handle:
            handle.write(note)
            handle.write(f"station,x_m,target,over_support,{header}\n")
            for name, frame, station, x_text in args.station:
                s = float(station) * station_scale
                x = float(x_text)
                values = []
                for mode in modes:
                    hits = [row for row in forces if row["frame"] == frame and is_mode_row(row, args.case)
                            and int(round(float(row["stepnum"]))) == mode
                            and abs(float(row["station"]) * station_scale - s) <= args.tolerance_m]
                    if not hits:
                        raise ConversionError(f"{args.frame_forces}: no M3 of frame {frame} at Station {station}, mode {mode}")
                    values.append(args.moment_sign * float(hits[0]["m3"]) * moment_scale)
                over = any(abs(x - support) <= args.tolerance_m for support in supports)
                handle.write(",".join([name, repr(x), targets.get(name, "section"), "true" if over else "false"]
                                      + [repr(v) for v in values]) + "\n")

    lines_toml = [
        "# A bridge known by its SAP2000 modes, converted by examples/import/sap2000/sap2000_to_vbi.py",
        "# (docs/input-format.md, \"Imported modes\").",
        "[bridge]",
        'type = "imported"',
        'frequencies_csv = "frequencies.csv"',
        'shapes_csv = "shapes.csv"',
    ]
    if station_file:
        lines_toml.append('station_moments_csv = "station_moments.csv"')
    if args.damping_ratio is not None:
        lines_toml.append(f"damping_ratio = {args.damping_ratio!r}")
    lines_toml.append("span_lengths_m = [" + ", ".join(repr(s) for s in spans) + "]")
    (out / "bridge.toml").write_text("\n".join(lines_toml) + "\n")


if __name__ == "__main__":
    sys.exit(main())
