"""What the OpenSees and ospgrillage import tests share: importing OpenSeesPy on a machine
without libblas.so.3, a linear static solve, the Hermite deflection line through nodal values,
and `vbi ... --format json`."""

from __future__ import annotations

import ctypes
import importlib
import importlib.util
import json
import os

import numpy as np
import pytest

from conftest import run_command

MOVING_FORCE_N = 5750.0 * 9.81  # the moving-force preset's P (`vbi vehicle show moving-force`)
FREQUENCY_TOLERANCE = 1e-6


def import_or_skip(name: str):
    """The module `name` (openseespy.opensees, or a package that imports it), or skip the test
    module.

    openseespy's Linux wheel fails with a RuntimeError (not an ImportError, so
    pytest.importorskip does not catch it) when the system has no libblas.so.3: its bundled
    liblapack needs one, and the bundled copy beside it is not on the loader's path. Loading that
    bundled copy first is enough (the same as `apt-get install libblas3`).
    """
    try:
        return importlib.import_module(name)
    except ImportError as error:
        pytest.skip(f"{name} is not installed: {error}", allow_module_level=True)
    except RuntimeError:
        pass
    spec = importlib.util.find_spec("openseespylinux")
    blas = spec and os.path.join(os.path.dirname(spec.origin), "lib", "libblas.so.3")
    try:
        ctypes.CDLL(blas, mode=ctypes.RTLD_GLOBAL)
        return importlib.import_module(name)
    except (OSError, TypeError, ImportError, RuntimeError) as error:
        pytest.skip(f"{name} cannot be imported: {error}", allow_module_level=True)


def vbi_json(*args: str):
    done = run_command(*args, "--format", "json")
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def static_solve(ops, loads) -> None:
    """One linear static step of the current OpenSees model under {node: load vector}."""
    ops.wipeAnalysis()
    ops.timeSeries("Linear", 1)
    ops.pattern("Plain", 1, 1)
    for node, load in loads.items():
        ops.load(node, *load)
    ops.constraints("Plain")
    ops.numberer("RCM")
    ops.system("BandGeneral")
    ops.algorithm("Linear")
    ops.integrator("LoadControl", 1.0)
    ops.analysis("Static")
    assert ops.analyze(1) == 0


def lowest_deflection(x, w, slope, samples: int = 4001) -> float:
    """Minimum (largest downward) of the cubic Hermite deflection through nodal w and dw/dx.

    The elements carry no load between nodes, so this cubic is the FE model's own deflection
    there: the same field vbi loads through when a wheel stands between two nodes.
    """
    t = np.linspace(0.0, 1.0, samples)
    h00, h10, h01, h11 = 2 * t**3 - 3 * t**2 + 1, t**3 - 2 * t**2 + t, -2 * t**3 + 3 * t**2, t**3 - t**2
    lowest = min(w)
    for i in range(len(x) - 1):
        h = x[i + 1] - x[i]
        v = h00 * w[i] + h10 * h * slope[i] + h01 * w[i + 1] + h11 * h * slope[i + 1]
        lowest = min(lowest, v.min())
    return lowest


def crawl_scenario(path, bridge, modes: int, speed_kmh: float = 10.0):
    """A scenario file of the moving force at `speed_kmh` on a smooth road over `bridge`."""
    path.write_text(
        "[scenario]\n"
        f'bridge = "{bridge}"\n'
        'vehicle = "moving-force"\n'
        'road = "smooth"\n'
        f"speed_kmh = {speed_kmh}\n"
        f"modes = {modes}\n"
    )
    return path


def stations(result):
    """A run's station entries by (name, quantity)."""
    return {(s["name"], s["quantity"]): s for s in result["stations"]}
