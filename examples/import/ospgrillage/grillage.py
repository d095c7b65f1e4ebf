"""A one-span grillage built with ospgrillage, exported as a vbi `imported_matrices` bridge.

    python examples/import/ospgrillage/grillage.py [DIRECTORY]

DIRECTORY defaults to grillage/ next to this script. ospgrillage (a grillage generator on top of
OpenSeesPy) creates the model in OpenSees; ../opensees/vbi_export.py then writes OpenSees' own K
and M. The deck: 20 m span, 10 m wide, five main girders 2 m apart (z = 1, 3, 5, 7, 9 m) and an
edge beam 1 m outside each outer girder (z = 0 and 10 m), transverse slab members every 1 m
(1 m strips), all ospgrillage `elasticBeamColumn` members. Supports are ospgrillage's defaults:
pinned (ux, uy, uz held) at x = 0 and rollers (uy, uz held) at x = 20 m under the five girders;
the edge beams are not supported.

ospgrillage's frame: x along the bridge, y UP, z across (0 to the width). So the export has
`vertical_axis = "y"`, and a girder's vertical bending is about its local z axis: EI = E * Iz.
Units are N and m throughout.

Two ospgrillage conventions matter here (ospgrillage 0.6.0, members.py):
- a beam member's mass per length is A * rho * 1000, and it is LUMPED (`-mass` without
  `-cMass`: m L / 2 on each end node's translations, none on rotations). For kg/m in an N-m
  model, rho is therefore given in t/m³ (2.4 for concrete); and the deck lines get
  `mass_per_length_kg_per_m = 0`, vbi's value for a lumped-mass model.
- the element's A, E, G, J, Iy, Iz are written with 4 significant digits ("{:.3e}"), so E and
  the girders' Iz are chosen with at most 4, to make the deck lines' EI the model's exact EI.
"""

from __future__ import annotations

import contextlib
import os
import sys
import tempfile
from pathlib import Path

import ospgrillage as og

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "opensees"))
from vbi_export import write_vbi_model  # noqa: E402

SPAN_M = 20.0
WIDTH_M = 10.0
LONGITUDINAL_LINES = 7  # 2 edge beams + 5 main girders
EDGE_BEAM_M = 1.0  # edge beam to the outer girder
TRANSVERSE_LINES = 21  # grid lines across, 1 m apart (the girder elements are 1 m long)
E = 3.45e10  # Pa
G = 1.44e10  # Pa (given, not E / 2(1 + v) = 1.4375e10, which ospgrillage would round)
RHO = 2.4  # t/m³: ospgrillage's element mass per length is A * rho * 1000 [kg/m]
# Section properties [m², m⁴]. Iz: bending about local z, which is vertical bending for these
# members (ospgrillage's vecxz leaves local y vertical); Iy: lateral bending; J: torsion.
GIRDER = dict(A=0.8, Iz=0.3, Iy=0.2, J=0.05)
EDGE_BEAM = dict(A=0.3, Iz=0.01, Iy=0.02, J=0.005)
SLAB = dict(A=0.2, Iz=6.667e-4, Iy=1.667e-2, J=1.333e-3)  # a 1 m wide, 0.2 m thick strip
GIRDER_MEMBERS = ("exterior_main_beam_1", "interior_main_beam", "exterior_main_beam_2")
FLEXURAL_RIGIDITY = E * GIRDER["Iz"]  # N·m², each girder
GIRDER_MASS = GIRDER["A"] * RHO * 1000.0  # kg/m, lumped


@contextlib.contextmanager
def _scratch_directory():
    """ospgrillage's Material writes mat_lib.json into the working directory when it finds none
    there (and reads one it finds): create materials in an empty scratch directory."""
    here = os.getcwd()
    with tempfile.TemporaryDirectory() as scratch:
        os.chdir(scratch)
        try:
            yield
        finally:
            os.chdir(here)


def _four_digits(value: float) -> float:
    """`value` as ospgrillage writes it into the element command ("{:.3e}")."""
    return float(f"{value:.3e}")


def build():
    """Create the grillage in OpenSees with ospgrillage.

    Returns (the ospgrillage model, the deck lines' node tags by ascending x, one list per main
    girder from z = 1 m to z = 9 m, the support x positions).
    """
    for value in (E, GIRDER["Iz"]):
        assert _four_digits(value) == value, f"{value} has more than 4 significant digits"
    model = og.create_grillage(
        bridge_name="vbi_ospgrillage_example",
        long_dim=SPAN_M,
        width=WIDTH_M,
        skew=0,
        num_long_grid=LONGITUDINAL_LINES,
        num_trans_grid=TRANSVERSE_LINES,
        edge_beam_dist=EDGE_BEAM_M,
        mesh_type="Ortho",
    )
    with _scratch_directory():
        concrete = og.create_material(E=E, G=G, v=0.2, rho=RHO)

    def member(props):
        return og.create_member(section=og.create_section(**props), material=concrete)

    girder, edge, slab = member(GIRDER), member(EDGE_BEAM), member(SLAB)
    for name in GIRDER_MEMBERS:
        model.set_member(girder, member=name)
    model.set_member(edge, member="edge_beam")
    for name in ("transverse_slab", "start_edge", "end_edge"):
        model.set_member(slab, member=name)
    model.create_osp_model(pyfile=False)
    return model, deck_lines(model), [0.0, SPAN_M]


def deck_lines(model) -> list:
    """Node tags of each main girder by ascending x, from ospgrillage's own member groups (the
    mesh's longitudinal grid lines, "z groups"), ordered by the lines' z."""
    ops = og.ops
    groups = sorted({g for name in GIRDER_MEMBERS for g in model.common_grillage_element_z_group[name]})
    lines = []
    for group in groups:
        nodes = {n for element in model.Mesh_obj.z_group_to_ele[group] for n in element[1:3]}
        lines.append(sorted(nodes, key=lambda n: ops.nodeCoord(n)[0]))
    return sorted(lines, key=lambda line: ops.nodeCoord(line[0])[2])


def export(directory, model_lines=None, damping_ratio: float = 0.02) -> Path:
    """Build the grillage (unless `model_lines` = build()'s lines) and write it to `directory`."""
    lines = model_lines if model_lines is not None else build()[1]
    return write_vbi_model(
        directory,
        deck_lines=[{"nodes": nodes, "flexural_rigidity_n_m2": FLEXURAL_RIGIDITY,
                     "mass_per_length_kg_per_m": 0.0}  # lumped mass (see above)
                    for nodes in lines],
        support_positions_m=[0.0, SPAN_M],
        units="N-m",
        vertical_axis="y",
        damping_ratio=damping_ratio,
        name=f"the 1 x 20 m five-girder grillage of examples/import/ospgrillage/grillage.py "
             f"(ospgrillage {og.__version__})",
    )


def main() -> None:
    directory = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent / "grillage"
    print(f"wrote {export(directory)}")


if __name__ == "__main__":
    main()
