#!/usr/bin/env python3
"""Convert ANSYS Mechanical APDL's HBMAT output into a vbi `imported_matrices` bridge.

    python hbmat_to_vbi.py OUT_DIR --stiffness k.matrix --mass m.matrix \
        --mapping k.mapping --nodes nodes.txt --units N-m --vertical-axis z \
        --supports 0 20 40 --deck-line 1:41 --ei 4.86535e10 --mass-per-length 18358

writes OUT_DIR/stiffness.mtx, mass.mtx, dofs.csv, nodes.csv and bridge.toml, the files that
`vbi check`, `vbi modes` and a scenario's `bridge = "OUT_DIR/bridge.toml"` read
(docs/input-format.md, bridge type `imported_matrices`). export_matrices.mac beside this file
writes the four inputs from ANSYS; README.md says what is tested and what is not.

What is read, and the documents relied on:

* K and M: `HBMAT,Fname,Ext,,ASCII,STIFF|MASS,NO,YES` (ANSYS Command Reference, HBMAT:
  https://ansyshelp.ansys.com/public/Views/Secured/corp/v242/en/ans_cmd/Hlp_C_HBMAT.html). Its
  Notes say that a symmetric matrix from the .full file is written as its lower triangle only
  (Harwell-Boeing type RSA) and an unsymmetric one in full (RUA, transposed: ANSYS stores by
  row, Harwell-Boeing by column), and that constrained DOFs (D) and the DOFs eliminated by
  coupling/constraint equations (CP, CE) are removed from the matrix. The file layout is the
  Harwell-Boeing one (Duff, Grimes & Lewis, "User's Guide for the Harwell-Boeing Sparse Matrix
  Collection", 1992; summarised at https://people.sc.fsu.edu/~jburkardt/data/hb/hb.html):
      line 1  title (A72), key (A8)
      line 2  TOTCRD PTRCRD INDCRD VALCRD RHSCRD       (lines in the file and in each block)
      line 3  MXTYPE (A3: R/P, S/U/H/Z/R, A/E), NROW NCOL NNZERO NELTVL
      line 4  PTRFMT INDFMT (2A16) VALFMT RHSFMT (2A20): Fortran formats
      line 5  (only if RHSCRD > 0) RHSTYP NRHS NRHSIX
      then PTRCRD lines of NCOL+1 column pointers, INDCRD lines of NNZERO row indices and
      VALCRD lines of NNZERO values (column by column, 1-based), then the right-hand sides.
  Values are read field by field with the widths of the Fortran format (fields may touch:
  "-1.5D+03-2.5D+03"), with D exponents and the exponent letter Fortran drops above 99
  ("1.0+100"). scipy.io.hb_read is not used: it reads unsymmetric (RUA) matrices only
  (scipy issue #8797, "Only unsymmetric matrices supported for now"), and ANSYS writes RSA.
* The DOF of each equation: HBMAT's Mapping = YES file Fname.mapping, "to map the matrix
  equation numbers found in the .matrix file directly to the corresponding node numbers and
  degrees of freedom" (HBMAT Notes). It is a text table, one equation a line: equation number,
  node number, DOF label (UX UY UZ ROTX ROTY ROTZ), after a header line. Any line that is not
  `integer integer label` is taken as a header and skipped, so the exact header text and column
  widths do not matter. Labels are mapped UX->ux, UY->uy, UZ->uz, ROTX->rx, ROTY->ry,
  ROTZ->rz; any other label (WARP of a BEAM188/189 with warping, TEMP, PRES, ...) is refused.
* Node coordinates: any text file with one node a line, `node x y [z]`, separated by commas or
  blanks (export_matrices.mac writes one with *VWRITE; an NWRITE file with blanks between its
  columns also works, its rotation angles are ignored). Lines that do not start with a number
  are skipped; a node number written as `12.` (Fortran F format) is read as 12.

No conversion of units or axes is made here: vbi does that once, from `units` and
`vertical_axis` (the files stay in the model's own consistent units and axes). The deck lines'
EI [N*m^2], m-bar [kg/m], the support positions and the centreline [m] are SI, as vbi asks;
node lists by rule (--deck-line-at) are matched in the file's length unit.

Only numpy is needed.
"""

from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np

SCRIPT = "examples/import/ansys/hbmat_to_vbi.py"

# ANSYS DOF labels (Fname.mapping) -> vbi's DOF names, in the model's own axes.
DOF_NAMES = {"UX": "ux", "UY": "uy", "UZ": "uz", "ROTX": "rx", "ROTY": "ry", "ROTZ": "rz"}

# vbi's `units` -> metres per length unit of the files (for support positions vs node x).
LENGTH_M = {"N-m": 1.0, "kN-m": 1.0, "MN-m": 1.0, "N-mm": 1e-3, "kN-mm": 1e-3, "kip-in": 0.0254}


class ConversionError(Exception):
    """A problem with the input files or arguments; the message names the file and line."""


# --------------------------------------------------------------------------------------------
# Harwell-Boeing


def _top_level_groups(text: str) -> List[str]:
    """The parenthesised Fortran formats on line 4, e.g. ['(10I8)', '(10I8)', '(1P4D25.16)']."""
    groups, depth, start = [], 0, 0
    for i, char in enumerate(text):
        if char == "(":
            if depth == 0:
                start = i
            depth += 1
        elif char == ")" and depth > 0:
            depth -= 1
            if depth == 0:
                groups.append(text[start : i + 1])
    return groups


_SIMPLE_FORMAT = re.compile(
    r"^\(\s*(?:[+-]?\d+\s*P\s*,?\s*)?(\d*)\s*([IEDFG])\s*(\d+)(?:\s*\.\s*\d+)?(?:\s*[ED]\s*\d+)?\s*\)$",
    re.IGNORECASE,
)


def _field_width(fmt: str) -> Optional[Tuple[int, int]]:
    """(fields per line, width) of a simple format like (4E20.12) or (1P,4D25.16), else None."""
    match = _SIMPLE_FORMAT.match(fmt.replace(" ", ""))
    if not match:
        return None
    return int(match.group(1) or 1), int(match.group(3))


_NO_LETTER_EXPONENT = re.compile(r"^([+-]?(?:\d+\.?\d*|\.\d+))([+-]\d+)$")


def _number(token: str) -> float:
    text = token.strip().upper().replace("D", "E")
    match = _NO_LETTER_EXPONENT.match(text)
    if match:  # Fortran Ew.d drops the letter for 3-digit exponents: 1.0+100
        text = f"{match.group(1)}E{match.group(2)}"
    return float(text)


def _is_number(token: str) -> bool:
    try:
        _number(token)
        return True
    except ValueError:
        return False


def _fields(lines: Sequence[str], fmt: str, count: int, what: str, path: Path, first_line: int):
    """`count` numbers from `lines`, read with the widths of `fmt` (or blank-separated)."""
    layout = _field_width(fmt)
    tokens: List[str] = []
    for line in lines:
        line = line.rstrip("\r\n")
        split = line.split()
        if layout is None:
            tokens.extend(split)
            continue
        # Blank-separated when that gives the line's expected count of numbers (some writers,
        # scipy.io.hb_write among them, do not keep to their format's widths); otherwise the
        # fields touch ("-1.5D+03-2.5D+03") and are cut at the format's widths.
        per_line, width = layout
        expected = min(per_line, count - len(tokens))
        if len(split) == expected and all(_is_number(t) for t in split):
            tokens.extend(split)
        else:
            for k in range(per_line):
                field = line[k * width : (k + 1) * width]
                if field.strip():
                    tokens.append(field)
        if len(tokens) >= count:
            break
    if len(tokens) < count:
        raise ConversionError(
            f"{path}: the {what} block (from line {first_line}) holds {len(tokens)} numbers, "
            f"the header announces {count}"
        )
    try:
        return [_number(t) for t in tokens[:count]]
    except ValueError as error:
        raise ConversionError(f"{path}: a number in the {what} block (from line {first_line}): {error}")


def read_harwell_boeing(path) -> Tuple[int, np.ndarray, np.ndarray, np.ndarray, bool]:
    """(n, rows, cols, values, symmetric) of an assembled real square Harwell-Boeing matrix.

    rows and cols are 0-based. For a symmetric type (RSA) the entries are those of one triangle,
    returned as the lower one (row >= col); for RUA every stored entry.
    """
    path = Path(path)
    lines = path.read_text().splitlines()
    if len(lines) < 4:
        raise ConversionError(f"{path}: not a Harwell-Boeing file (fewer than 4 header lines)")
    try:
        cards = [int(x) for x in lines[1].split()]
        _, ptrcrd, indcrd, valcrd = cards[:4]
        rhscrd = cards[4] if len(cards) > 4 else 0
        mxtype = lines[2][:3].upper()
        nrow, ncol, nnz = (int(x) for x in lines[2][3:].split()[:3])
    except ValueError:
        raise ConversionError(f"{path}: lines 2-3 are not a Harwell-Boeing header")
    if mxtype[0] not in "R" or mxtype[2] != "A":
        raise ConversionError(
            f"{path}: matrix type {mxtype!r}: only assembled real matrices (RSA, RUA) are read"
        )
    if mxtype[1] not in "SUH":
        raise ConversionError(f"{path}: matrix type {mxtype!r} (S, U or H expected as its 2nd letter)")
    if nrow != ncol:
        raise ConversionError(f"{path}: the matrix is {nrow} x {ncol}, not square")
    formats = _top_level_groups(lines[3])
    if len(formats) < 3:
        raise ConversionError(f"{path}: line 4 does not hold the pointer, index and value formats")
    start = 4 + (1 if rhscrd > 0 else 0)
    blocks = []
    for what, count, fmt, ncards in (
        ("column pointer", ncol + 1, formats[0], ptrcrd),
        ("row index", nnz, formats[1], indcrd),
        ("value", nnz, formats[2], valcrd),
    ):
        blocks.append(_fields(lines[start : start + ncards], fmt, count, what, path, start + 1))
        start += ncards
    pointers = np.array(blocks[0], dtype=np.int64) - 1
    rows = np.array(blocks[1], dtype=np.int64) - 1
    values = np.array(blocks[2], dtype=float)
    if pointers[0] != 0 or pointers[-1] != nnz or np.any(np.diff(pointers) < 0):
        raise ConversionError(f"{path}: the column pointers do not run from 1 to NNZERO+1")
    if rows.min(initial=0) < 0 or rows.max(initial=0) >= nrow:
        raise ConversionError(f"{path}: a row index is outside 1..{nrow}")
    cols = np.repeat(np.arange(ncol), np.diff(pointers))
    symmetric = mxtype[1] in "SH"
    if symmetric:
        rows, cols = np.maximum(rows, cols), np.minimum(rows, cols)
    keys = rows * ncol + cols
    if len(np.unique(keys)) != len(keys):
        raise ConversionError(
            f"{path}: an entry is stored twice"
            + (" (a symmetric matrix with both triangles stored?)" if symmetric else "")
        )
    return nrow, rows, cols, values, symmetric


# --------------------------------------------------------------------------------------------
# Mapping, nodes


def read_mapping(path) -> List[Tuple[int, int, str]]:
    """(equation, node, vbi dof) from HBMAT's Fname.mapping, sorted by equation."""
    path = Path(path)
    rows, unknown = [], {}
    for number, line in enumerate(path.read_text().splitlines(), start=1):
        tokens = line.replace(",", " ").split()
        if len(tokens) < 3:
            continue
        try:
            equation, node = int(tokens[0]), int(tokens[1])
        except ValueError:
            continue  # a header line
        label = tokens[2].upper()
        if label not in DOF_NAMES:
            unknown.setdefault(label, number)
            continue
        rows.append((equation, node, DOF_NAMES[label]))
    if unknown:
        listed = ", ".join(f"{label} (line {line})" for label, line in unknown.items())
        raise ConversionError(
            f"{path}: DOF labels vbi cannot use: {listed}; vbi reads UX UY UZ ROTX ROTY ROTZ "
            "(for a BEAM188/189 with the warping DOF, set KEYOPT(1) = 0)"
        )
    if not rows:
        raise ConversionError(f"{path}: no line `equation node label` found")
    rows.sort()
    equations = [r[0] for r in rows]
    if equations != list(range(1, len(rows) + 1)):
        raise ConversionError(f"{path}: the equation numbers are not 1..{len(rows)}, each once")
    seen: Dict[Tuple[int, str], int] = {}
    for equation, node, dof in rows:
        if (node, dof) in seen:
            raise ConversionError(
                f"{path}: node {node} {dof} is equation {seen[(node, dof)]} and {equation}"
            )
        seen[(node, dof)] = equation
    return rows


def read_nodes(path) -> Dict[int, Tuple[float, ...]]:
    """{node: (x, y[, z])} from a `node x y [z]` file (commas or blanks; headers skipped)."""
    path = Path(path)
    nodes: Dict[int, Tuple[float, ...]] = {}
    for number, line in enumerate(path.read_text().splitlines(), start=1):
        tokens = line.replace(",", " ").split()
        try:
            values = [_number(t) for t in tokens[:4]]
        except ValueError:
            continue  # a header or comment line
        if len(values) < 3:
            continue
        tag = values[0]
        if tag != int(tag) or tag <= 0:
            raise ConversionError(f"{path}:{number}: node number {tokens[0]!r} is not a positive integer")
        if int(tag) in nodes:
            raise ConversionError(f"{path}:{number}: node {int(tag)} is listed twice")
        nodes[int(tag)] = tuple(values[1:])
    if not nodes:
        raise ConversionError(f"{path}: no line `node x y [z]` found")
    return nodes


# --------------------------------------------------------------------------------------------
# Deck lines


def parse_node_list(text: str) -> List[int]:
    """'1,2,5' or '1:41' (inclusive) or '1:41:2', combined with commas."""
    nodes: List[int] = []
    for part in text.replace(" ", "").split(","):
        if not part:
            continue
        pieces = part.split(":")
        try:
            if len(pieces) == 1:
                nodes.append(int(pieces[0]))
            elif len(pieces) in (2, 3):
                first, last = int(pieces[0]), int(pieces[1])
                step = int(pieces[2]) if len(pieces) == 3 else 1
                if step <= 0:
                    raise ValueError
                nodes.extend(range(first, last + 1, step))
            else:
                raise ValueError
        except ValueError:
            raise ConversionError(f"--deck-line {text!r}: {part!r} is not N, FIRST:LAST or FIRST:LAST:STEP")
    return nodes


def axes(vertical_axis: str) -> Tuple[int, int]:
    """Indices of (lateral, vertical) in a node's coordinates (x, y, z)."""
    return (1, 2) if vertical_axis == "z" else (2, 1)


def nodes_on_line(nodes, lateral: float, level: Optional[float], vertical_axis: str,
                  x_range: Tuple[float, float], tolerance: float) -> List[int]:
    """Nodes at one lateral position (and vertical level), with x within the supports."""
    lat, vert = axes(vertical_axis)
    picked = []
    for tag, coords in nodes.items():
        c = tuple(coords) + (0.0,) * (3 - len(coords))
        if abs(c[lat] - lateral) > tolerance:
            continue
        if level is not None and abs(c[vert] - level) > tolerance:
            continue
        if not (x_range[0] - tolerance <= c[0] <= x_range[1] + tolerance):
            continue
        picked.append(tag)
    return picked


def sort_by_x(tags: Sequence[int], nodes, what: str, tolerance: float) -> List[int]:
    missing = [t for t in tags if t not in nodes]
    if missing:
        raise ConversionError(f"{what}: nodes {missing[:10]} are not in the nodes file")
    ordered = sorted(set(tags), key=lambda t: nodes[t][0])
    xs = [nodes[t][0] for t in ordered]
    for a, b, ta, tb in zip(xs, xs[1:], ordered, ordered[1:]):
        if b - a <= tolerance:
            raise ConversionError(f"{what}: nodes {ta} and {tb} are at the same x ({a!r})")
    if len(ordered) < 2:
        raise ConversionError(f"{what}: fewer than 2 nodes")
    return ordered


# --------------------------------------------------------------------------------------------
# Writing


def write_matrix_market(path: Path, n: int, rows, cols, values, symmetric: bool, comment: str):
    """Matrix Market coordinate file; `symmetric` holds the lower triangle (row >= col)."""
    keep = values != 0.0
    rows, cols, values = rows[keep], cols[keep], values[keep]
    order = np.lexsort((rows, cols))
    with open(path, "w") as out:
        out.write(f"%%MatrixMarket matrix coordinate real {'symmetric' if symmetric else 'general'}\n")
        out.write(f"% {comment}\n")
        out.write(f"{n} {n} {len(values)}\n")
        for i, j, v in zip(rows[order], cols[order], values[order]):
            out.write(f"{i + 1} {j + 1} {float(v)!r}\n")


def convert(args) -> Path:
    out = Path(args.out_dir)
    stamp = f"an ANSYS model (HBMAT files {Path(args.stiffness).name}, {Path(args.mass).name}), converted by {SCRIPT}"

    n_k, rk, ck, vk, sym_k = read_harwell_boeing(args.stiffness)
    n_m, rm, cm, vm, sym_m = read_harwell_boeing(args.mass)
    dofs = read_mapping(args.mapping)
    if not (n_k == n_m == len(dofs)):
        raise ConversionError(
            f"K is {n_k} x {n_k}, M is {n_m} x {n_m} and {args.mapping} maps {len(dofs)} "
            "equations: they must agree (all three from the same .full file)"
        )
    nodes = read_nodes(args.nodes)
    lacking = sorted({node for _, node, _ in dofs if node not in nodes})
    if lacking:
        raise ConversionError(f"{args.nodes}: no coordinates for nodes {lacking[:10]} of the mapping")

    scale = LENGTH_M[args.units]
    supports = [float(s) for s in args.supports]
    tolerance = args.tolerance
    if tolerance is None:
        extent = max(max(abs(v) for v in c) for c in nodes.values()) or 1.0
        tolerance = 1e-6 * extent
    x_range = (supports[0] / scale, supports[-1] / scale)

    lines: List[List[int]] = []
    for text in args.deck_line or []:
        lines.append(sort_by_x(parse_node_list(text), nodes, f"--deck-line {text}", tolerance))
    for lateral in args.deck_line_at or []:
        picked = nodes_on_line(nodes, lateral, args.deck_level, args.vertical_axis, x_range, tolerance)
        lines.append(sort_by_x(picked, nodes, f"--deck-line-at {lateral!r}", tolerance))
    if not lines:
        raise ConversionError("give at least one --deck-line or --deck-line-at")

    def per_line(values, name, default=None):
        if not values:
            if default is None:
                raise ConversionError(f"{name} is required (one value, or one per deck line)")
            return [default] * len(lines)
        if len(values) == 1:
            return values * len(lines)
        if len(values) != len(lines):
            raise ConversionError(f"{name}: {len(values)} values for {len(lines)} deck lines")
        return values

    ei = per_line(args.ei, "--ei")
    mbar = per_line(args.mass_per_length, "--mass-per-length", 0.0)

    out.mkdir(parents=True, exist_ok=True)
    write_matrix_market(out / "stiffness.mtx", n_k, rk, ck, vk, sym_k, f"stiffness [{args.units}] of {stamp}")
    write_matrix_market(out / "mass.mtx", n_m, rm, cm, vm, sym_m, f"mass [{args.units}] of {stamp}")
    with open(out / "dofs.csv", "w") as handle:
        handle.write(f"# equations of {stamp} (from {Path(args.mapping).name})\nequation,node,dof\n")
        for equation, node, dof in dofs:
            handle.write(f"{equation},{node},{dof}\n")
    three_d = any(len(c) >= 3 for c in nodes.values())
    with open(out / "nodes.csv", "w") as handle:
        handle.write(f"# nodes of {stamp}\n")
        handle.write("node,x,y,z\n" if three_d else "node,x,y\n")
        for tag in sorted(nodes):
            coords = tuple(nodes[tag]) + ((0.0,) * (3 - len(nodes[tag])) if three_d else ())
            handle.write(",".join([str(tag)] + [repr(float(v)) for v in coords]) + "\n")

    text = [
        f"# {stamp}.",
        "",
        "[bridge]",
        'type = "imported_matrices"',
        'stiffness_mtx = "stiffness.mtx"',
        'mass_mtx = "mass.mtx"',
        'dof_map_csv = "dofs.csv"',
        'nodes_csv = "nodes.csv"',
        f'units = "{args.units}"',
        f'vertical_axis = "{args.vertical_axis}"',
        f"support_positions_m = [{', '.join(repr(s) for s in supports)}]",
    ]
    if args.centreline is not None:
        text.append(f"centreline_m = {float(args.centreline)!r}")
    text.append(f"damping_ratio = {float(args.damping_ratio)!r}")
    for tags, e, m in zip(lines, ei, mbar):
        text += [
            "",
            "[[bridge.deck_line]]",
            f"nodes = [{', '.join(str(t) for t in tags)}]",
            f"flexural_rigidity_n_m2 = {float(e)!r}",
            f"mass_per_length_kg_per_m = {float(m)!r}",
        ]
    path = out / "bridge.toml"
    path.write_text("\n".join(text) + "\n")
    return path


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(
        description="Convert ANSYS HBMAT files (K, M, .mapping) and node coordinates into a "
        "vbi imported_matrices bridge (stiffness.mtx, mass.mtx, dofs.csv, nodes.csv, bridge.toml).",
    )
    parser.add_argument("out_dir", help="directory to write the vbi files to")
    parser.add_argument("--stiffness", required=True, help="HBMAT,...,ASCII,STIFF file (Harwell-Boeing)")
    parser.add_argument("--mass", required=True, help="HBMAT,...,ASCII,MASS file (Harwell-Boeing)")
    parser.add_argument("--mapping", required=True, help="the Fname.mapping file HBMAT wrote with Mapping = YES")
    parser.add_argument("--nodes", required=True, help="node coordinates, one `node x y [z]` a line")
    parser.add_argument("--units", required=True, choices=sorted(LENGTH_M), help="the model's consistent units")
    parser.add_argument("--vertical-axis", default="z", choices=["z", "y"],
                        help="z: x along, y lateral, z up; y: x along, y up, z lateral (default z)")
    parser.add_argument("--supports", required=True, nargs="+", type=float, metavar="X_M",
                        help="x of every support line [m], ascending")
    parser.add_argument("--deck-line", action="append", metavar="NODES",
                        help="a girder's nodes: '1,2,3', '1:41' or '1:41:2' (sorted by x); repeat per girder")
    parser.add_argument("--deck-line-at", action="append", type=float, metavar="LATERAL",
                        help="a girder by rule: every node at this lateral coordinate (file's length "
                        "unit) with x within the supports; repeat per girder")
    parser.add_argument("--deck-level", type=float, metavar="VERTICAL",
                        help="with --deck-line-at: only nodes at this vertical coordinate (file's length unit)")
    parser.add_argument("--tolerance", type=float,
                        help="coordinate tolerance for the rule [file's length unit] (default 1e-6 x model size)")
    parser.add_argument("--ei", action="append", type=float, metavar="N_M2",
                        help="girder EI [N*m^2]: once for all deck lines, or once per line in order")
    parser.add_argument("--mass-per-length", action="append", type=float, metavar="KG_M",
                        help="girder consistent-mass m-bar [kg/m] (0 for lumped mass): once, or per line")
    parser.add_argument("--centreline", type=float, metavar="M", help="lateral coordinate of the centreline [m]")
    parser.add_argument("--damping-ratio", type=float, default=0.05)
    args = parser.parse_args(argv)
    if any(b <= a for a, b in zip(args.supports, args.supports[1:])) or len(args.supports) < 2:
        parser.error("--supports: at least 2 positions, strictly ascending")
    try:
        path = convert(args)
    except (ConversionError, OSError) as error:
        print(f"hbmat_to_vbi: {error}", file=sys.stderr)
        return 2
    print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
