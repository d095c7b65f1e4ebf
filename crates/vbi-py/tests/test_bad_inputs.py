"""The Python API fed bad input (issue 47): a seeded corpus of mutated example documents given as
dicts, and bad scalars, NaN, wrong types and huge arrays given to every entry point. Each call
either succeeds or raises a Python exception with a message (`vbi.InputError` for a value of a
document, with the field named), never a panic (`pyo3`'s `PanicException`, a `BaseException`)
or a crash of the interpreter.

The dicts are the example files' documents, so that a refusal can be compared with the `vbi`
command's refusal of the same document written as a file: for the mutants that TOML can
write (every value but NaN, ±inf and `None`), `vbi check` of the file gives the same message
as the Python exception, field included.
"""

from __future__ import annotations

import copy
import math
import os
import random
from pathlib import Path
from typing import Any, Callable, Dict, List, Tuple

import numpy as np
import pytest

import vbi
from conftest import EXAMPLES, run_command

try:  # Python 3.11+
    import tomllib
except ImportError:  # pragma: no cover - older Pythons
    import tomli as tomllib  # type: ignore[no-redef]

SEED = 0x5EED_0047_0000_0001

#: Example documents and the constructor that reads each kind.
DOCUMENTS: List[Tuple[str, Callable[[Any], Any]]] = [
    ("scenarios/paper-3x30-medium-80kmh.toml", vbi.Scenario),
    ("scenarios/two-trucks-opposite-lanes.toml", vbi.Scenario),
    ("scenarios/braking-pitch.toml", vbi.Scenario),
    ("scenarios/expansion-joint.toml", vbi.Scenario),
    ("scenarios/traffic-stream.toml", vbi.Scenario),
    ("bridges/paper-2x20.toml", vbi.Bridge),
    ("bridges/two-span-beam.toml", vbi.Bridge),
    ("bridges/i-girder-3-span.toml", vbi.Bridge),
    ("bridges/skewed-2x20.toml", vbi.Bridge),
    ("vehicles/three-axle-truck-36t.toml", vbi.Vehicle),
    ("vehicles/tractor-semitrailer-cg-heights.toml", vbi.Vehicle),
    ("vehicles/moving-forces-tandem.toml", vbi.Vehicle),
    ("roads/iso-class-c-3d.toml", vbi.Road),
    ("roads/paper-medium.toml", vbi.Road),
    ("roads/custom-harmonics.toml", vbi.Road),
]

#: What replaces a value: bad numbers, wrong types, huge and nested values.
REPLACEMENTS: List[Any] = [
    float("nan"),
    float("inf"),
    float("-inf"),
    -1,
    0,
    -0.0,
    1e308,
    -1e308,
    5e-324,
    2**64,
    2**200,
    -(2**63) - 1,
    "",
    "no-such-name",
    "\x00",
    True,
    [],
    [float("nan")],
    {},
    {"nested": {"deeper": [1, 2, 3]}},
    None,
    list(range(100_000)),
    [[[[[[[[[[1.0]]]]]]]]]],
]

#: Exceptions a bad input may raise: vbi's own, or Python's for a value of the wrong type
#: at the binding (a `None`, an integer beyond 64 bits).
ALLOWED = (vbi.VbiError, TypeError, ValueError, OverflowError)


def document(relative: str) -> Dict[str, Any]:
    with open(EXAMPLES / relative, "rb") as handle:
        return tomllib.load(handle)


def leaves(value: Any, path: Tuple[Any, ...] = ()) -> List[Tuple[Any, ...]]:
    """The paths of every value of a document (dict keys and list indices)."""
    if isinstance(value, dict):
        out = [path] if path else []
        for key, item in value.items():
            out += leaves(item, path + (key,))
        return out
    if isinstance(value, list):
        out = [path]
        for index, item in enumerate(value):
            out += leaves(item, path + (index,))
        return out
    return [path]


def replaced(doc: Dict[str, Any], path: Tuple[Any, ...], value: Any) -> Dict[str, Any]:
    mutant = copy.deepcopy(doc)
    target = mutant
    for key in path[:-1]:
        target = target[key]
    target[path[-1]] = value
    return mutant


def mutants(count: int) -> List[Tuple[str, Callable[[Any], Any], Tuple[Any, ...], Any]]:
    rng = random.Random(SEED)
    out = []
    for index in range(count):
        relative, constructor = DOCUMENTS[index % len(DOCUMENTS)]
        paths = leaves(document(relative))
        path = rng.choice(paths)
        value = REPLACEMENTS[rng.randrange(len(REPLACEMENTS))]
        out.append((relative, constructor, path, value))
    return out


def writable_in_toml(value: Any) -> bool:
    if value is None:
        return False
    if isinstance(value, float):
        return math.isfinite(value)
    if isinstance(value, int) and not isinstance(value, bool):
        return -(2**63) <= value < 2**63
    if isinstance(value, str):
        return "\x00" not in value
    if isinstance(value, list):
        return len(value) < 1000 and all(writable_in_toml(v) for v in value)
    if isinstance(value, dict):
        return all(writable_in_toml(v) for v in value.values())
    return True


def toml_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, int):
        return str(value)
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, list):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f'"{k}" = {toml_value(v)}' for k, v in value.items()) + "}"
    raise TypeError(value)


def toml_document(doc: Dict[str, Any]) -> str:
    """A document as TOML: every top-level table inline (`name = {…}`) is not how the examples
    are written, so each table is a header and its keys inline values."""
    lines = []
    for table, body in doc.items():
        if isinstance(body, dict):
            lines.append(f'["{table}"]')
            for key, value in body.items():
                lines.append(f'"{key}" = {toml_value(value)}')
        else:
            lines.insert(0, f'"{table}" = {toml_value(body)}')
    return "\n".join(lines) + "\n"


CORPUS = mutants(300)


@pytest.fixture(scope="module")
def examples_copy(tmp_path_factory):
    """A copy of `examples/`, where the mutants are written beside the example they come from
    (so that its relative references resolve as the example's do)."""
    import shutil

    copy_root = tmp_path_factory.mktemp("examples") / "examples"
    shutil.copytree(EXAMPLES, copy_root)
    return copy_root


@pytest.mark.parametrize(
    "relative,constructor,path,value",
    CORPUS,
    ids=[f"{i:03}-{m[0]}-{'.'.join(map(str, m[2]))}" for i, m in enumerate(CORPUS)],
)
def test_a_mutated_document_is_accepted_or_refused_with_a_message(
    relative, constructor, path, value, monkeypatch, examples_copy
):
    # The example's own references (bridge = "../bridges/…") are relative to its folder.
    folder = (examples_copy / relative).parent
    monkeypatch.chdir(folder)
    mutant = replaced(document(relative), path, value)
    try:
        constructor(mutant)
    except ALLOWED as error:
        assert str(error), "an exception without a message"
        if isinstance(error, vbi.InputError) and writable_in_toml(value):
            # `vbi check` refuses the same document, written as a file, with the same words.
            file = folder / "mutant.toml"
            file.write_text(toml_document(mutant))
            completed = run_command("check", str(file))
            assert completed.returncode == 2, completed.stdout
            assert error.message in completed.stderr, (str(error), completed.stderr)


BAD_NUMBERS = [float("nan"), float("inf"), -1.0, 0.0, 1e308, -1e308]


@pytest.mark.parametrize("n", [0, -1, 2**64])
def test_modes_of_a_bad_count_raise(n):
    with pytest.raises(ALLOWED):
        vbi.modes(vbi.Bridge("paper-2x20"), n)


@pytest.mark.parametrize(
    "start,end",
    [(x, 10.0) for x in [float("nan"), float("inf"), float("-inf"), 1e308, -1e308]]
    + [(0.0, 1e308), (0.0, float("nan")), (10.0, 0.0)],
)
def test_a_road_profile_over_a_bad_range_raises(start, end):
    road = vbi.Road({"road": {"class": "C"}})
    with pytest.raises(ALLOWED):
        road.profile(start, end)


@pytest.mark.parametrize("key", ["speed_kmh", "modes", "time_step_s", "lateral_position_m"])
@pytest.mark.parametrize("value", BAD_NUMBERS + ["text", [1.0, 2.0], True])
def test_scenario_set_of_a_bad_value_raises_an_input_error_or_is_accepted(key, value):
    scenario = vbi.Scenario()
    try:
        scenario.set(key, value)
    except ALLOWED as error:
        assert str(error)


@pytest.mark.parametrize(
    "source",
    [
        42,
        3.5,
        b"bytes",
        [1, 2, 3],
        {"scenario": None},
        {1: 2},
        {"scenario": {"speed_kmh": np.float64("nan")}},
        {"scenario": {"speed_kmh": np.array([1.0, 2.0])}},
        "/nonexistent/file.toml",
        "/dev/zero",
        os.devnull,
    ],
)
def test_a_source_of_the_wrong_kind_raises(source):
    with pytest.raises(ALLOWED):
        vbi.Scenario(source)


def test_a_measurement_with_nan_and_huge_values_raises_with_the_field(tmp_path):
    doc = document("measurements/synthetic_two_span.toml")
    folder = EXAMPLES / "measurements"
    doc["measurement"]["csv"] = str(folder / doc["measurement"]["csv"])
    doc["measurement"]["bridge"] = str((folder / doc["measurement"]["bridge"]).resolve())
    for key, value in [
        ("speed_kmh", float("nan")),
        ("bridge_length_m", 1e20),
        ("entry_time_s", 1e308),
        ("speed_kmh", "fast"),
    ]:
        bad = replaced(doc, ("measurement", key), value)
        with pytest.raises(ALLOWED) as raised:
            vbi.measure(bad)
        assert str(raised.value)


def test_the_corpus_covers_every_document_and_replacement():
    assert {m[0] for m in CORPUS} == {d[0] for d in DOCUMENTS}
    assert len(CORPUS) >= 300
