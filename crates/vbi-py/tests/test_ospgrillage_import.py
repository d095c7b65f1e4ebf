"""A grillage built with ospgrillage, exported by examples/import/opensees/vbi_export.py, read by vbi.

The example examples/import/ospgrillage/grillage.py (1 x 20 m, five girders, ospgrillage's y-up
frame, lumped mass) is created in OpenSees by ospgrillage, written as an `imported_matrices`
bridge into tmp_path, and compared with OpenSees' own eigen and static analyses. Runs the `vbi`
command (target/debug/vbi or VBI_BIN); needs ospgrillage (which brings openseespy), not the vbi
package. Skipped when ospgrillage cannot be imported.
"""

from __future__ import annotations

import importlib.util
import math
import shutil
import sys

import pytest

from conftest import EXAMPLES, run_command
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


def _load_example():
    """examples/import/ospgrillage/grillage.py as a module of its own name: the OpenSees tests
    import examples/import/opensees/grillage.py as `grillage`, so a plain import would clash."""
    path = EXAMPLES / "import" / "ospgrillage" / "grillage.py"
    spec = importlib.util.spec_from_file_location("ospgrillage_grillage_example", path)
    module = importlib.util.module_from_spec(spec)
    write_bytecode = sys.dont_write_bytecode
    sys.dont_write_bytecode = True  # no __pycache__ in examples/: the tests write only to tmp_path
    try:
        spec.loader.exec_module(module)
    finally:
        sys.dont_write_bytecode = write_bytecode
    return module


og = import_or_skip("ospgrillage")
ops = og.ops
example = _load_example()



def element_between(i: int, j: int) -> int:
    return next(e for e in ops.getEleTags() if sorted(ops.eleNodes(e)) == sorted([i, j]))


@pytest.fixture(scope="module")
def grill(tmp_path_factory):
    """The example exported, OpenSees' first six frequencies, and the centre girder's (girder 3,
    z = 5 m) deflection line under unit downward loads at mid-span (x = 10 m) on girder 1, 2, 3
    and 1/5 on each, and girder 3's mid-span moment under the load on girder 3."""
    directory = tmp_path_factory.mktemp("ospgrillage")
    _, lines, supports = example.build()
    assert supports == [0.0, 20.0] and len(lines) == 5
    assert all(len(line) == 21 for line in lines)
    bridge = example.export(directory / "grillage", lines)
    frequencies = [math.sqrt(v) / (2.0 * math.pi) for v in ops.eigen("-fullGenLapack", 6)]
    centre = lines[2]
    mid = len(centre) // 2
    assert ops.nodeCoord(centre[mid])[0] == 10.0 and ops.nodeCoord(centre[mid])[2] == 5.0
    deflected, moment = {}, None
    for case, loads in {
        "g1": {lines[0][mid]: 1.0},
        "g2": {lines[1][mid]: 1.0},
        "g3": {lines[2][mid]: 1.0},
        "section": {line[mid]: 1.0 / 5.0 for line in lines},
    }.items():
        # y is up in ospgrillage's frame: the load is -Fy, the deflection uy, dw/dx = rz.
        static_solve(ops, {node: (0.0, -p, 0.0, 0.0, 0.0, 0.0) for node, p in loads.items()})
        deflected[case] = dict(
            x=[ops.nodeCoord(n)[0] for n in centre],
            w=[ops.nodeDisp(n)[1] for n in centre],
            slope=[ops.nodeDisp(n)[5] for n in centre],
        )
        if case == "g3":  # Mz at end j of girder 3's element x = 9..10 m ([N, Vy, Vz, T, My, Mz] x 2)
            forces = ops.eleResponse(element_between(centre[mid - 1], centre[mid]), "localForce")
            moment = forces[11]
        ops.remove("loadPattern", 1)
        ops.remove("timeSeries", 1)
        ops.reset()
    return dict(directory=directory, bridge=bridge, frequencies=frequencies,
                lines=deflected, moment=moment)


def test_vbi_check_accepts_the_export_without_a_units_warning(grill, tmp_path):
    done = run_command("check", str(grill["bridge"]))
    assert done.returncode == 0, done.stderr
    assert "warning" not in done.stdout + done.stderr, done.stderr
    # The check is live: the same files declared in kN-m miss L³/(48 ΣEI) by 1000.
    wrong = tmp_path / "wrong"
    shutil.copytree(grill["bridge"].parent, wrong)
    toml = wrong / "bridge.toml"
    toml.write_text(toml.read_text().replace('units = "N-m"', 'units = "kN-m"'))
    done = run_command("check", str(toml))
    assert "warning" in done.stderr and "`units`" in done.stderr, done.stderr


def test_opensees_eigen_frequencies_equal_vbi_modes_of_the_export(grill):
    ours = [m["frequency_hz"] for m in vbi_json("modes", str(grill["bridge"]), "--modes", "6")["modes"]]
    assert len(ours) == 6
    for theirs, mine in zip(grill["frequencies"], ours):
        assert mine == pytest.approx(theirs, rel=FREQUENCY_TOLERANCE)


def test_static_deflections_and_moment_from_opensees_equal_vbi_static_max(grill, tmp_path):
    # The moving force runs along the centreline, which is girder 3 (z = 5 m). By Maxwell-Betti
    # girder g's deflection at mid-span under P on girder 3 at x is P times girder 3's deflection
    # at x under a unit load on girder g at mid-span (the section's mean: 1/5 on each girder).
    # The grillage is symmetric about z = 5 m, so girders 1 and 5 (2 and 4) have the same answer
    # whichever of them vbi numbers 1 (2).
    result = vbi_json("run", str(crawl_scenario(tmp_path / "crawl.toml", grill["bridge"], modes=10)))
    at = stations(result)
    for case, names in (("g1", ("span1_mid_g1", "span1_mid_g5")), ("g2", ("span1_mid_g2", "span1_mid_g4")),
                           ("g3", ("span1_mid_g3",)), ("section", ("span1_mid_section",))):
        line = grill["lines"][case]
        expected = MOVING_FORCE_N * lowest_deflection(line["x"], line["w"], line["slope"])
        for station in names:
            assert at[(station, "deflection")]["static_max"] == pytest.approx(expected, rel=1e-6), station
    # Girder 3's mid-span moment peaks with the load over it. vbi reads it as the end moment of a
    # Hermite element of EI = E Iz, which is OpenSees' own elasticBeamColumn moment.
    expected_moment = MOVING_FORCE_N * abs(grill["moment"])
    assert at[("span1_mid_g3", "bending_moment")]["static_max"] == pytest.approx(expected_moment, rel=1e-6)
