"""examples/import/ansys/hbmat_to_vbi.py on Harwell-Boeing files made from vbi's own model.

No ANSYS here: `vbi modes two-span-beam.toml --export-matrices` writes vbi's own K and M of the
two-span beam (Matrix Market, SI, z up); this test writes them again the way ANSYS's HBMAT does
(examples/import/ansys/README.md): Harwell-Boeing, real symmetric assembled (RSA, the lower
triangle column by column) with D exponents and touching fixed-width fields, in a shuffled
equation order with the .mapping file that says which node and DOF (UX ... ROTZ) each equation
is, and the node coordinates as export_matrices.mac's *VWRITE writes them. It also writes one
unsymmetric-type (RUA) file with scipy.io.hb_write, an independent writer of the format, and
one model in y-up axes (ROTZ = -ry, a deck line found by rule). hbmat_to_vbi.py converts each
into vbi's files, and vbi must give the original's frequencies to 1e-12 and accept it in
`vbi check`; the converted K and M, reordered by (node, DOF), must be the original's to the bit.

What this does not test: the APDL macro itself and ANSYS's own files (no licence here).
Needs numpy and scipy (skipped without them) and the `vbi` command (target/debug/vbi or VBI_BIN).
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import EXAMPLES, run_command

np = pytest.importorskip("numpy")
scipy_io = pytest.importorskip("scipy.io")
sparse = pytest.importorskip("scipy.sparse")
try:
    import tomllib
except ImportError:  # Python < 3.11
    tomllib = pytest.importorskip("tomli")

CONVERTER = EXAMPLES / "import" / "ansys" / "hbmat_to_vbi.py"
BEAM = EXAMPLES / "bridges" / "two-span-beam.toml"
MODES = 6
TOLERANCE = 1e-12

# vbi DOF -> (ANSYS label, sign of the file's DOF against vbi's) for each vertical axis.
LABELS = {
    "z": {"ux": ("UX", 1.0), "uz": ("UZ", 1.0), "ry": ("ROTY", 1.0)},
    # y up: y_file = z_vbi, z_file = -y_vbi, so theta_z,file = -theta_y,vbi (docs/input-format.md)
    "y": {"ux": ("UX", 1.0), "uz": ("UY", 1.0), "ry": ("ROTZ", -1.0)},
}


def vbi_json(*args: str):
    done = run_command(*args, "--format", "json")
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def frequencies(bridge: Path):
    return [m["frequency_hz"] for m in vbi_json("modes", str(bridge), "--modes", str(MODES))["modes"]]


def read_table(path: Path):
    lines = [l for l in path.read_text().splitlines() if l.strip() and not l.startswith("#")]
    header = lines[0].split(",")
    return [dict(zip(header, l.split(","))) for l in lines[1:]]


@pytest.fixture(scope="module")
def original(tmp_path_factory):
    """vbi's own export of the two-span beam: K, M (dense), DOFs, nodes, bridge.toml."""
    directory = tmp_path_factory.mktemp("vbi-export")
    done = run_command("modes", str(BEAM), "--modes", "2", "--export-matrices", str(directory))
    assert done.returncode == 0, done.stderr
    k = scipy_io.mmread(str(directory / "stiffness.mtx")).toarray()
    m = scipy_io.mmread(str(directory / "mass.mtx")).toarray()
    dofs = [(int(r["node"]), r["dof"]) for r in read_table(directory / "dofs.csv")]
    nodes = {int(r["node"]): (float(r["x"]), float(r["y"]), float(r["z"])) for r in read_table(directory / "nodes.csv")}
    bridge = tomllib.loads((directory / "bridge.toml").read_text())["bridge"]
    assert {dof for _, dof in dofs} <= set(LABELS["z"]), "the beam's DOFs changed: extend LABELS"
    return {
        "dir": directory, "k": k, "m": m, "dofs": dofs, "nodes": nodes, "bridge": bridge,
        "frequencies": frequencies(directory / "bridge.toml"),
    }


def d_format(value: float) -> str:
    """Fortran 1PD23.16: 17 significant digits, D exponent; negative values fill all 23."""
    return f"{value:.16E}".replace("E", "D").rjust(23)


def write_hb_rsa(path: Path, a, title: str, with_rhs: bool) -> None:
    """Real symmetric assembled Harwell-Boeing: lower triangle by column, as HBMAT writes K, M."""
    lower = sparse.csc_matrix(np.tril(a))
    lower.sort_indices()
    n, nnz = a.shape[0], lower.nnz
    pointers, rows, values = lower.indptr + 1, lower.indices + 1, lower.data
    chunks = lambda seq, size: [seq[i : i + size] for i in range(0, len(seq), size)]  # noqa: E731
    ptr_lines = ["".join(f"{p:10d}" for p in c) for c in chunks(list(pointers), 8)]
    ind_lines = ["".join(f"{r:10d}" for r in c) for c in chunks(list(rows), 8)]
    val_lines = ["".join(d_format(v) for v in c) for c in chunks(list(values), 3)]
    rhs_lines = ["".join(d_format(float(i)) for i in c) for c in chunks(list(range(n)), 3)] if with_rhs else []
    total = len(ptr_lines) + len(ind_lines) + len(val_lines) + len(rhs_lines)
    header = [
        f"{title:<72.72s}{'VBITEST':<8s}",
        f"{total:14d}{len(ptr_lines):14d}{len(ind_lines):14d}{len(val_lines):14d}{len(rhs_lines):14d}",
        f"{'RSA':<3s}{'':11s}{n:14d}{n:14d}{nnz:14d}{0:14d}",
        f"{'(8I10)':<16s}{'(8I10)':<16s}{'(1P3D23.16)':<20s}{'(1P3D23.16)' if with_rhs else '':<20s}",
    ]
    if with_rhs:
        header.append(f"{'F':<3s}{'':11s}{1:14d}{0:14d}")
    path.write_text("\n".join(header + ptr_lines + ind_lines + val_lines + rhs_lines) + "\n")


def ansys_files(original, directory: Path, vertical_axis: str, writer: str):
    """K, M, .mapping and nodes as ANSYS would write them for vbi's beam; returns their paths."""
    directory.mkdir(parents=True)
    n = len(original["dofs"])
    # HBMAT's equations are in the solver's order, not by node: shuffle them.
    order = np.random.default_rng(20240611).permutation(n)  # new equation e is old order[e]
    signs = np.array([LABELS[vertical_axis][dof][1] for _, dof in original["dofs"]])
    scale = np.outer(signs, signs)
    k = (original["k"] * scale)[np.ix_(order, order)]
    m = (original["m"] * scale)[np.ix_(order, order)]
    paths = {key: directory / name for key, name in
             [("k", "bridge_k.matrix"), ("m", "bridge_m.matrix"), ("map", "bridge_k.mapping"), ("nodes", "vbi_nodes.txt")]}
    if writer == "rsa":
        write_hb_rsa(paths["k"], k, "Stiffness matrix dumped via hbmat (vbi test)", with_rhs=True)
        write_hb_rsa(paths["m"], m, "Mass matrix dumped via hbmat (vbi test)", with_rhs=False)
    else:
        scipy_io.hb_write(str(paths["k"]), sparse.csc_matrix(k))
        scipy_io.hb_write(str(paths["m"]), sparse.csc_matrix(m))
    with open(paths["map"], "w") as out:
        out.write(" Matrix Eqn   Node   DOF\n")
        for equation, old in enumerate(order, start=1):
            node, dof = original["dofs"][old]
            out.write(f"{equation:10d} {node:10d} {LABELS[vertical_axis][dof][0]:>6s}\n")
    with open(paths["nodes"], "w") as out:  # export_matrices.mac's *VWRITE, (F12.0,3E24.16)
        for tag, (x, y, z) in sorted(original["nodes"].items()):
            coords = (x, y, z) if vertical_axis == "z" else (x, z, -y + 0.0)
            out.write(f"{tag:11d}." + "".join(f"{c:24.16E}" for c in coords) + "\n")
    return paths, order, signs


def convert(original, paths, out: Path, vertical_axis: str, deck_args):
    bridge = original["bridge"]
    line = bridge["deck_line"][0]
    command = [
        sys.executable, str(CONVERTER), str(out),
        "--stiffness", str(paths["k"]), "--mass", str(paths["m"]), "--mapping", str(paths["map"]),
        "--nodes", str(paths["nodes"]), "--units", bridge["units"], "--vertical-axis", vertical_axis,
        "--supports", *[repr(s) for s in bridge["support_positions_m"]],
        "--ei", repr(line["flexural_rigidity_n_m2"]),
        "--mass-per-length", repr(line["mass_per_length_kg_per_m"]),
        "--centreline", repr(bridge["centreline_m"]), "--damping-ratio", repr(bridge["damping_ratio"]),
        *deck_args,
    ]
    done = subprocess.run(command, capture_output=True, text=True, check=False)
    assert done.returncode == 0, done.stderr
    return out / "bridge.toml"


CASES = {
    # name: (vertical axis, writer, deck-line arguments)
    "rsa-z-up-node-list": ("z", "rsa", ["--deck-line", "1:41"]),
    "rsa-y-up-rule": ("y", "rsa", ["--deck-line-at", "0.0"]),
    "scipy-rua-z-up": ("z", "scipy", ["--deck-line", ",".join(str(t) for t in range(41, 0, -1))]),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_converted_model_matches_vbi_export(original, tmp_path, case):
    vertical_axis, writer, deck_args = CASES[case]
    paths, order, signs = ansys_files(original, tmp_path / "ansys", vertical_axis, writer)
    bridge_toml = convert(original, paths, tmp_path / "vbi", vertical_axis, deck_args)

    done = run_command("check", str(bridge_toml))
    assert done.returncode == 0, done.stdout + done.stderr

    got = frequencies(bridge_toml)
    want = original["frequencies"]
    assert len(got) == len(want) == MODES
    for g, w in zip(got, want):
        assert abs(g - w) <= TOLERANCE * w, (case, got, want)

    # The converted files are the ANSYS-side ones: same matrix, reordered and signed back.
    converted = read_table(tmp_path / "vbi" / "dofs.csv")
    file_dof = {"UX": "ux", "UY": "uy", "UZ": "uz", "ROTX": "rx", "ROTY": "ry", "ROTZ": "rz"}
    names = {file_dof[label]: dof for dof, (label, _) in LABELS[vertical_axis].items()}
    back = {(n, d): i for i, (n, d) in enumerate(original["dofs"])}
    index = np.array([back[(int(r["node"]), names[r["dof"]])] for r in converted])
    assert sorted(index) == list(range(len(original["dofs"])))
    for name in ("k", "m"):
        file_matrix = scipy_io.mmread(str(tmp_path / "vbi" / ("stiffness.mtx" if name == "k" else "mass.mtx"))).toarray()
        rebuilt = np.zeros_like(file_matrix)
        rebuilt[np.ix_(index, index)] = file_matrix
        assert np.array_equal(rebuilt * np.outer(signs, signs), original[name]), name

    deck = tomllib.loads(bridge_toml.read_text())["bridge"]["deck_line"]
    assert [line["nodes"] for line in deck] == [original["bridge"]["deck_line"][0]["nodes"]]


def test_unknown_dof_label_is_refused(original, tmp_path):
    paths, _, _ = ansys_files(original, tmp_path / "ansys", "z", "rsa")
    text = paths["map"].read_text().splitlines()
    text[5] = text[5].replace("ROTY", "WARP").replace("UZ", "WARP")
    paths["map"].write_text("\n".join(text) + "\n")
    done = subprocess.run(
        [sys.executable, str(CONVERTER), str(tmp_path / "vbi"), "--stiffness", str(paths["k"]),
         "--mass", str(paths["m"]), "--mapping", str(paths["map"]), "--nodes", str(paths["nodes"]),
         "--units", "N-m", "--supports", "0", "20", "40", "--deck-line", "1:41", "--ei", "1e10"],
        capture_output=True, text=True, check=False,
    )
    assert done.returncode == 2
    assert "WARP (line 6)" in done.stderr and "KEYOPT(1)" in done.stderr
    assert not (tmp_path / "vbi").exists()
