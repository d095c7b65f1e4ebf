"""OpenSeesPy models exported by examples/import/opensees/vbi_export.py, read back by vbi.

The examples' beam (2 x 20 m, plane frame, y up) and grillage (3 girders x 20 m, z up) are
built in OpenSeesPy, written as `imported_matrices` bridges into tmp_path, and compared with
OpenSees' own eigen and static analyses and (the beam) with vbi's native continuous beam.
Runs the `vbi` command (target/debug/vbi or VBI_BIN); needs openseespy, not the vbi package.
"""

from __future__ import annotations

import math
import sys

import pytest

from conftest import EXAMPLES
from opensees_support import (
    FREQUENCY_TOLERANCE,
    MOVING_FORCE_N,
    crawl_scenario,
    import_or_skip,
    lowest_deflection,
    static_solve,
    stations,
    vbi_json,
)


ops = import_or_skip("openseespy.opensees")
sys.path.insert(0, str(EXAMPLES / "import" / "opensees"))
sys.dont_write_bytecode = True  # no __pycache__ in examples/: the tests write only to tmp_path
import grillage  # noqa: E402
import two_span_beam  # noqa: E402

sys.dont_write_bytecode = False



def vbi_frequencies(bridge, count: int):
    return [mode["frequency_hz"] for mode in vbi_json("modes", str(bridge), "--modes", str(count))["modes"]]


def opensees_frequencies(count: int):
    return [math.sqrt(value) / (2.0 * math.pi) for value in ops.eigen("-fullGenLapack", count)]


@pytest.fixture(scope="module")
def beam(tmp_path_factory):
    """The example beam exported, with OpenSees' frequencies and its static answer to a unit
    downward load at mid-span of span 1 (node 11, x = 10 m)."""
    directory = tmp_path_factory.mktemp("opensees_beam")
    nodes, supports = two_span_beam.build()
    bridge = two_span_beam.write_vbi_model(
        directory / "beam",
        deck_lines=[{"nodes": nodes, "flexural_rigidity_n_m2": two_span_beam.EI,
                     "mass_per_length_kg_per_m": two_span_beam.MASS}],
        support_positions_m=supports, vertical_axis="y", damping_ratio=0.0,
    )
    frequencies = opensees_frequencies(6)
    static_solve(ops, {11: (0.0, -1.0, 0.0)})
    x = [ops.nodeCoord(n)[0] for n in nodes]
    w = [ops.nodeDisp(n)[1] for n in nodes]
    slope = [ops.nodeDisp(n)[2] for n in nodes]  # rz: dw/dx in the x-y plane
    moment = ops.eleResponse(10, "localForce")[5]  # element 10 (x = 9..10 m), end j: M at x = 10 m
    return dict(directory=directory, bridge=bridge, frequencies=frequencies,
                x=x, w=w, slope=slope, moment=moment)


@pytest.fixture(scope="module")
def grill(tmp_path_factory):
    """The example grillage exported, with OpenSees' frequencies and girder 2's deflection line
    under unit downward loads at mid-span (x = 10 m): on girder 1, girder 2, and 1/3 on each."""
    directory = tmp_path_factory.mktemp("opensees_grillage")
    lines, supports = grillage.build()
    bridge = grillage.write_vbi_model(
        directory / "grillage",
        deck_lines=[{"nodes": nodes, "flexural_rigidity_n_m2": grillage.E * grillage.GIRDER["i_vertical"],
                     "mass_per_length_kg_per_m": grillage.GIRDER["mass"]} for nodes in lines],
        support_positions_m=supports, vertical_axis="z", damping_ratio=0.02,
    )
    frequencies = opensees_frequencies(6)
    middle = lines[1]
    mid = len(middle) // 2
    lines_deflected = {}
    for case, loads in {
        "g1": {lines[0][mid]: 1.0},
        "g2": {lines[1][mid]: 1.0},
        "section": {line[mid]: 1.0 / 3.0 for line in lines},
    }.items():
        static_solve(ops, {node: (0.0, 0.0, -p, 0.0, 0.0, 0.0) for node, p in loads.items()})
        lines_deflected[case] = dict(
            x=[ops.nodeCoord(n)[0] for n in middle],
            w=[ops.nodeDisp(n)[2] for n in middle],
            slope=[-ops.nodeDisp(n)[4] for n in middle],  # dw/dx = -ry (right-handed about y)
        )
        ops.remove("loadPattern", 1)
        ops.remove("timeSeries", 1)
        ops.reset()
    return dict(directory=directory, bridge=bridge, frequencies=frequencies, lines=lines_deflected)


def test_beam_opensees_eigen_frequencies_equal_vbi_modes_of_the_export(beam):
    ours = vbi_frequencies(beam["bridge"], 6)
    # Both lists hold the axial (vbi: longitudinal) mode at 21.65 Hz as their third.
    for theirs, mine in zip(beam["frequencies"], ours):
        assert mine == pytest.approx(theirs, rel=FREQUENCY_TOLERANCE)


def test_beam_static_deflection_and_moment_from_opensees_equal_vbi_static_max(beam, tmp_path):
    result = vbi_json("run", str(crawl_scenario(tmp_path / "crawl.toml", beam["bridge"], modes=10)))
    at = stations(result)
    # Maxwell-Betti: the deflection at x = 10 m under P at x is P times the deflection at x under
    # a unit load at 10 m, so vbi's static extreme over the crossing (the load sampled every
    # v*dt = 2.8 mm) is P times the extreme of OpenSees' deflection line, taken from the nodal
    # values through the Hermite cubics (0.25 mm steps): both samplings put the peak within
    # ~1e-8 relative (measured: 7e-9), so 1e-6 leaves room. The nodal values alone (1 m apart)
    # would miss the peak, which lies between two nodes, by 2.5e-3.
    expected = MOVING_FORCE_N * lowest_deflection(beam["x"], beam["w"], beam["slope"])
    assert at[("span1_mid_section", "deflection")]["static_max"] == pytest.approx(expected, rel=1e-6)
    # The mid-span moment's influence line peaks with the load at the section itself.
    expected_moment = MOVING_FORCE_N * abs(beam["moment"])
    assert at[("span1_mid_section", "bending_moment")]["static_max"] == pytest.approx(expected_moment, rel=1e-9)


def test_beam_crossing_on_the_export_equals_the_native_continuous_beam(beam, tmp_path):
    imported = vbi_json("run", str(crawl_scenario(tmp_path / "imported.toml", beam["bridge"], modes=10)))
    # `modes` counts the modes solved for; the export also has axial modes, which the default
    # mode_kinds drop, so the native beam is given the number of vertical modes kept here.
    kept = len(imported["frequencies_hz"])
    native_bridge = tmp_path / "native.toml"
    native_bridge.write_text(
        '[bridge]\ntype = "continuous_beam"\nspan_lengths_m = [20.0, 20.0]\n'
        'supports = ["pinned", "pinned", "pinned"]\ndamping_ratio = 0.0\n'
        f"[bridge.section]\nflexural_rigidity_n_m2 = {two_span_beam.EI!r}\n"
        f"mass_per_length_kg_per_m = {two_span_beam.MASS!r}\n"
    )
    native = vbi_json("run", str(crawl_scenario(tmp_path / "native_run.toml", native_bridge, modes=kept)))
    assert imported["frequencies_hz"] == pytest.approx(native["frequencies_hz"], rel=1e-9)
    ours, theirs = stations(imported), stations(native)
    for name in ("span1_mid_section", "span2_mid_section", "support2_section"):
        for quantity in ("deflection", "bending_moment"):
            for key in ("static_max", "dynamic_max", "daf"):
                a, b = ours[(name, quantity)][key], theirs[(name, quantity)][key]
                if b is None or b == 0.0:  # the deflection over a support
                    assert a == b, (name, quantity, key)
                else:
                    assert a == pytest.approx(b, rel=1e-6), (name, quantity, key)


def test_grillage_opensees_eigen_frequencies_equal_vbi_modes_of_the_export(grill):
    ours = vbi_frequencies(grill["bridge"], 6)
    for theirs, mine in zip(grill["frequencies"], ours):
        assert mine == pytest.approx(theirs, rel=FREQUENCY_TOLERANCE)


def test_grillage_static_deflections_from_opensees_equal_vbi_static_max(grill, tmp_path):
    # The moving force runs along the centreline, which is girder 2. By Maxwell-Betti girder g's
    # deflection at mid-span under P on girder 2 at x is P times girder 2's deflection at x under
    # a unit load on girder g at mid-span (the section's mean: 1/3 on each girder); tolerance as
    # for the beam. Girders 1 and 3 are symmetric, so which one vbi numbers 1 does not matter.
    result = vbi_json("run", str(crawl_scenario(tmp_path / "crawl.toml", grill["bridge"], modes=10)))
    at = stations(result)
    for case, station in (("g1", "span1_mid_g1"), ("g2", "span1_mid_g2"), ("section", "span1_mid_section")):
        line = grill["lines"][case]
        expected = MOVING_FORCE_N * lowest_deflection(line["x"], line["w"], line["slope"])
        assert at[(station, "deflection")]["static_max"] == pytest.approx(expected, rel=1e-6), station
