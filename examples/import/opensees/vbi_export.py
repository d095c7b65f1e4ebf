"""Write the OpenSeesPy model currently in memory as a vbi `imported_matrices` bridge.

    import openseespy.opensees as ops
    from vbi_export import write_vbi_model

    ...                                   # build the model: nodes, fix, elements (no loads yet)
    write_vbi_model("my-bridge", deck_lines=[{"nodes": [1, 2, 3],
                                              "flexural_rigidity_n_m2": 2.0e10,
                                              "mass_per_length_kg_per_m": 1.0e4}],
                    support_positions_m=[0.0, 20.0, 40.0], vertical_axis="y")

writes my-bridge/stiffness.mtx, mass.mtx, dofs.csv, nodes.csv and bridge.toml, the files that
`vbi check`, `vbi modes` and a scenario's `bridge = "my-bridge/bridge.toml"` read
(docs/input-format.md, bridge type `imported_matrices`).

How K and M are obtained: OpenSees assembles them itself. With the Plain constraint handler
(fixed DOFs are removed: their equation number in `ops.nodeDOFs` is -1), the Plain numberer and
a FullGeneral system, one transient step of zero length with the GimmeMCK integrator assembles
A = m*M + c*C + k*K, which `ops.printA('-ret')` returns: (0, 0, 1) gives K, (1, 0, 0) gives M.
The step also tries to solve A x = R; that fails where A is singular (e.g. M with massless
rotations), which is harmless here: A is printed as assembled. Call this before any load
pattern is defined (the zero-length step would otherwise apply the loads); the analysis
objects are wiped afterwards, so define your own analysis after it.

Only numpy is needed. The units of the files are the model's own (`units`, one of vbi's N-m,
kN-m, MN-m, N-mm, kN-mm, kip-in); the deck lines' EI and m-bar and the support positions are
always SI (N·m², kg/m, m).
"""

from __future__ import annotations

from pathlib import Path
from typing import Dict, Iterable, List, Optional, Sequence

import numpy as np
import openseespy.opensees as ops

SCRIPT = "examples/import/opensees/vbi_export.py"

# DOF names of a node, by (ndm, ndf), in OpenSees' order (vbi's names; axes of the model).
DOF_NAMES = {
    (2, 2): ["ux", "uy"],
    (2, 3): ["ux", "uy", "rz"],
    (3, 3): ["ux", "uy", "uz"],
    (3, 6): ["ux", "uy", "uz", "rx", "ry", "rz"],
}


def _assembled(m: float, c: float, k: float) -> tuple:
    """(A, DOF map): A = m*M + c*C + k*K of the current model, as OpenSees assembles it (dense,
    N x N: 8 N^2 bytes, 2.5 GB at 17 800 DOFs, so meant for models of a few thousand DOFs), and
    the DOF map of its equations. The Plain constraint handler keeps only single-point
    constraints (fix); a model with equalDOF or rigid links needs the Transformation handler
    and its own check that K is the model's."""
    ops.wipeAnalysis()
    ops.constraints("Plain")
    ops.numberer("Plain")
    ops.system("FullGeneral")
    ops.algorithm("Linear")
    ops.integrator("GimmeMCK", m, c, k)
    ops.analysis("Transient")
    ops.analyze(1, 0.0)  # may report a singular A: harmless, A is kept as assembled
    n = ops.systemSize()
    a = np.array(ops.printA("-ret"), dtype=float).reshape(n, n)
    dofs = dof_map()  # the equation numbers exist only while the analysis does
    ops.wipeAnalysis()
    return a, dofs


def system_matrices() -> tuple:
    """(K, M, DOF map) over the model's free DOFs (equations); see `dof_map`."""
    k, dofs = _assembled(0.0, 0.0, 1.0)
    m, _ = _assembled(1.0, 0.0, 0.0)
    return k, m, dofs


def dof_map() -> List[tuple]:
    """(equation from 1, node tag, dof name) for every free DOF, sorted by equation.

    Valid only while an analysis is defined (`ops.nodeDOFs` needs its DOF numbering).
    """
    rows = []
    for tag in ops.getNodeTags():
        equations = ops.nodeDOFs(tag)
        key = (len(ops.nodeCoord(tag)), len(equations))
        if key not in DOF_NAMES:
            raise ValueError(f"node {tag}: ndm={key[0]}, ndf={key[1]} has no DOF names here")
        for name, equation in zip(DOF_NAMES[key], equations):
            if equation >= 0:  # -1: fixed, removed by the Plain handler
                rows.append((equation + 1, tag, name))
    return sorted(rows)


def write_matrix_market(path: Path, a: np.ndarray, comment: str) -> None:
    """Sparse Matrix Market coordinate file: `symmetric` (lower triangle) if A is symmetric."""
    scale = max(np.abs(a).max(), np.finfo(float).tiny)
    symmetric = np.abs(a - a.T).max() <= 1e-14 * scale
    rows, cols = np.nonzero(np.tril(a) if symmetric else a)
    order = np.lexsort((rows, cols))  # column by column, as Matrix Market writers usually do
    with open(path, "w") as out:
        out.write(f"%%MatrixMarket matrix coordinate real {'symmetric' if symmetric else 'general'}\n")
        out.write(f"% {comment}\n")
        out.write(f"{a.shape[0]} {a.shape[1]} {len(rows)}\n")
        for i, j in zip(rows[order], cols[order]):
            out.write(f"{i + 1} {j + 1} {float(a[i, j])!r}\n")


def write_vbi_model(
    directory,
    deck_lines: Sequence[Dict],
    support_positions_m: Iterable[float],
    units: str = "N-m",
    vertical_axis: str = "z",
    damping_ratio: float = 0.05,
    centreline_m: Optional[float] = None,
    name: str = "an OpenSeesPy model",
) -> Path:
    """Write the current OpenSeesPy model as a vbi bridge; returns the bridge.toml path.

    deck_lines: one dict per girder (a beam has one), with keys
        nodes                     node tags by ascending x from the first support to the last
        flexural_rigidity_n_m2    EI of the girder [N·m²] (reads bending moments at stations)
        mass_per_length_kg_per_m  the girder's consistent-mass m-bar [kg/m] (0 for lumped mass)
    support_positions_m: x of every support line in the model's frame [m], ascending.
    vertical_axis: "z" (x along, y lateral, z up) or "y" (x along, y up; e.g. a 2D frame).
    """
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    stamp = f"{name}, written by {SCRIPT} (OpenSeesPy {ops.version()})"

    k, m, dofs = system_matrices()
    write_matrix_market(directory / "stiffness.mtx", k, f"stiffness [{units}] of {stamp}")
    write_matrix_market(directory / "mass.mtx", m, f"mass [{units}] of {stamp}")

    with open(directory / "dofs.csv", "w") as out:
        out.write(f"# equations of {stamp}\nequation,node,dof\n")
        for equation, tag, dof in dofs:
            out.write(f"{equation},{tag},{dof}\n")

    tags = ops.getNodeTags()
    ndm = max(len(ops.nodeCoord(tag)) for tag in tags)
    with open(directory / "nodes.csv", "w") as out:
        out.write(f"# nodes of {stamp}\n")
        out.write("node,x,y,z\n" if ndm == 3 else "node,x,y\n")
        for tag in tags:
            out.write(",".join([str(tag)] + [repr(float(x)) for x in ops.nodeCoord(tag)]) + "\n")

    supports = ", ".join(repr(float(x)) for x in support_positions_m)
    lines = [
        f"# {stamp}.",
        "",
        "[bridge]",
        'type = "imported_matrices"',
        'stiffness_mtx = "stiffness.mtx"',
        'mass_mtx = "mass.mtx"',
        'dof_map_csv = "dofs.csv"',
        'nodes_csv = "nodes.csv"',
        f'units = "{units}"',
        f'vertical_axis = "{vertical_axis}"',
        f"support_positions_m = [{supports}]",
    ]
    if centreline_m is not None:
        lines.append(f"centreline_m = {float(centreline_m)!r}")
    lines.append(f"damping_ratio = {float(damping_ratio)!r}")
    for line in deck_lines:
        lines += [
            "",
            "[[bridge.deck_line]]",
            f"nodes = [{', '.join(str(int(t)) for t in line['nodes'])}]",
            f"flexural_rigidity_n_m2 = {float(line['flexural_rigidity_n_m2'])!r}",
            f"mass_per_length_kg_per_m = {float(line.get('mass_per_length_kg_per_m', 0.0))!r}",
        ]
    path = directory / "bridge.toml"
    path.write_text("\n".join(lines) + "\n")
    return path
