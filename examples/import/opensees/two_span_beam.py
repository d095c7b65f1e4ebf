"""A 2 x 20 m continuous beam in OpenSeesPy, exported as a vbi `imported_matrices` bridge.

    python examples/import/opensees/two_span_beam.py [DIRECTORY]

DIRECTORY defaults to two-span-beam/ next to this script. The beam: EI = 2.0e10 N·m²,
m = 1.0e4 kg/m, pinned at x = 0, 20 and 40 m (one of them also holds the beam longitudinally),
1 m elasticBeamColumn elements with consistent mass (-cMass, the Hermite mass matrix vbi uses).
A plane frame (ndm = 2, ndf = 3: ux, uy, rz), so y is up: vertical_axis = "y".
"""

from __future__ import annotations

import sys
from pathlib import Path

import openseespy.opensees as ops

sys.path.insert(0, str(Path(__file__).resolve().parent))
from vbi_export import write_vbi_model  # noqa: E402

SPANS_M = [20.0, 20.0]
ELEMENT_M = 1.0
E = 3.0e10  # Pa (concrete); I = EI / E
EI = 2.0e10  # N·m²
AREA = 4.0  # m²: axial stiffness only (EA = 1.2e11 N); its axial modes are vbi's "longitudinal"
MASS = 1.0e4  # kg/m


def build() -> tuple:
    """Define the beam in OpenSees; returns (deck node tags, support x positions)."""
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    supports = [0.0]
    for span in SPANS_M:
        supports.append(supports[-1] + span)
    count = round(supports[-1] / ELEMENT_M)
    nodes = list(range(1, count + 2))
    for tag in nodes:
        ops.node(tag, (tag - 1) * ELEMENT_M, 0.0)
    for i, x in enumerate(supports):
        tag = 1 + round(x / ELEMENT_M)
        ops.fix(tag, 1 if i == 0 else 0, 1, 0)  # pinned; the first also fixes ux
    ops.geomTransf("Linear", 1)
    for tag in nodes[:-1]:
        ops.element("elasticBeamColumn", tag, tag, tag + 1, AREA, E, EI / E, 1,
                    "-mass", MASS, "-cMass")
    return nodes, supports


def main() -> None:
    directory = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent / "two-span-beam"
    nodes, supports = build()
    path = write_vbi_model(
        directory,
        deck_lines=[{"nodes": nodes, "flexural_rigidity_n_m2": EI, "mass_per_length_kg_per_m": MASS}],
        support_positions_m=supports,
        units="N-m",
        vertical_axis="y",
        damping_ratio=0.0,
        name="the 2 x 20 m continuous beam of examples/import/opensees/two_span_beam.py",
    )
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
