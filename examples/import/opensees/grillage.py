"""A one-span, three-girder grillage in OpenSeesPy, exported as a vbi `imported_matrices` bridge.

    python examples/import/opensees/grillage.py [DIRECTORY]

DIRECTORY defaults to grillage/ next to this script. Three girders 2.5 m apart (y = -2.5, 0,
2.5 m) over one 20 m span, 1 m girder elements; transverse members (slab strips 2 m wide)
every 2 m between neighbouring girders; all 3D elasticBeamColumn elements with consistent mass
(-cMass). z is up. Bearings: pinned at x = 0 (ux, uy, uz held), rollers at x = 20 m (uy, uz
held: free longitudinally, laterally guided).
"""

from __future__ import annotations

import sys
from pathlib import Path

import openseespy.opensees as ops

sys.path.insert(0, str(Path(__file__).resolve().parent))
from vbi_export import write_vbi_model  # noqa: E402

SPAN_M = 20.0
ELEMENT_M = 1.0
GIRDERS_Y_M = [-2.5, 0.0, 2.5]
TRANSVERSE_EVERY = 2  # a transverse member at every 2nd girder node (2 m)
E = 3.45e10  # Pa
G = E / 2.4  # Poisson's ratio 0.2
# girder: A, J, I about the lateral axis (vertical bending), I about the vertical axis; kg/m
GIRDER = dict(area=1.0, torsion=0.3, i_vertical=0.6, i_lateral=1.2, mass=4000.0)
# transverse member: a 2 m wide, 0.2 m thick slab strip (its own mass: 2 m x 0.2 m x 2500 kg/m³)
SLAB = dict(area=0.4, torsion=2.0 * 0.2**3 / 6.0, i_vertical=2.0 * 0.2**3 / 12.0,
            i_lateral=0.2 * 2.0**3 / 12.0, mass=1000.0)


def node_tag(girder: int, station: int) -> int:
    """Girder g (from 0) at x = station * ELEMENT_M."""
    return 1000 * (girder + 1) + station


def build() -> tuple:
    """Define the grillage in OpenSees; returns (deck lines' node tags, support x positions)."""
    ops.wipe()
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    stations = round(SPAN_M / ELEMENT_M)
    lines = []
    for g, y in enumerate(GIRDERS_Y_M):
        lines.append([node_tag(g, s) for s in range(stations + 1)])
        for s in range(stations + 1):
            ops.node(node_tag(g, s), s * ELEMENT_M, y, 0.0)
        ops.fix(node_tag(g, 0), 1, 1, 1, 0, 0, 0)  # pinned bearing
        ops.fix(node_tag(g, stations), 0, 1, 1, 0, 0, 0)  # roller, guided laterally
    # local z = global z for both directions, so I about local y is vertical bending (Iy)
    ops.geomTransf("Linear", 1, 0.0, 0.0, 1.0)
    element = 0

    def beam(i: int, j: int, p: dict) -> None:
        nonlocal element
        element += 1
        ops.element("elasticBeamColumn", element, i, j, p["area"], E, G, p["torsion"],
                    p["i_vertical"], p["i_lateral"], 1, "-mass", p["mass"], "-cMass")

    for g in range(len(GIRDERS_Y_M)):
        for s in range(stations):
            beam(node_tag(g, s), node_tag(g, s + 1), GIRDER)
    for s in range(0, stations + 1, TRANSVERSE_EVERY):
        for g in range(len(GIRDERS_Y_M) - 1):
            beam(node_tag(g, s), node_tag(g + 1, s), SLAB)
    return lines, [0.0, SPAN_M]


def main() -> None:
    directory = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent / "grillage"
    lines, supports = build()
    path = write_vbi_model(
        directory,
        deck_lines=[{"nodes": nodes, "flexural_rigidity_n_m2": E * GIRDER["i_vertical"],
                     "mass_per_length_kg_per_m": GIRDER["mass"]} for nodes in lines],
        support_positions_m=supports,
        units="N-m",
        vertical_axis="z",
        damping_ratio=0.02,
        name="the 1 x 20 m three-girder grillage of examples/import/opensees/grillage.py",
    )
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
