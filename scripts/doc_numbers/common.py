"""Running vbi once per command, reading its tables, and formatting numbers as the pages quote
them; the registry of pages (`page`)."""

from __future__ import annotations

import csv
import math
import shutil
import statistics
import subprocess
from pathlib import Path
from typing import Callable, Dict, Iterable, List, Sequence

ROOT = Path(__file__).resolve().parent.parent.parent
# ---------------------------------------------------------------------------------------------
# Running vbi


class Outputs:
    """vbi's outputs, each command run once and kept in a scratch directory."""

    def __init__(self, vbi: Path, work: Path, reuse: bool = False):
        self.vbi = vbi
        self.work = work
        self.reuse = reuse
        # A copy, so that a variant of an input sits beside its original and its relative paths hold.
        shutil.rmtree(work / "examples", ignore_errors=True)
        shutil.copytree(ROOT / "examples", work / "examples")
        self.done: Dict[str, Path] = {}

    def command(self, name: str, *arguments: str) -> Path:
        """Runs ``vbi ARGUMENTS --out NAME`` once; the output directory."""
        out = self.work / name
        if self.reuse and (out / "stdout.txt").exists():
            self.done[name] = out
        if name not in self.done:
            result = subprocess.run(
                [str(self.vbi), *arguments, "--out", name],
                cwd=self.work,
                capture_output=True,
                text=True,
            )
            if result.returncode != 0:
                raise SystemExit(
                    f"doc_numbers: `vbi {' '.join(arguments)}` failed:\n{result.stderr[-2000:]}"
                )
            (out / "stdout.txt").write_text(result.stdout + result.stderr)
            self.done[name] = out
        return self.done[name]

    def variant(self, name: str, source: str, replace: Sequence[tuple]) -> str:
        """A copy of the input file `source` (repository-relative, under examples/) beside it, with
        each (old, new) text replaced; its path relative to the scratch directory."""
        text = (ROOT / source).read_text()
        for old, new in replace:
            if old not in text:
                raise SystemExit(f"doc_numbers: {source} no longer holds {old!r}")
            text = text.replace(old, new)
        variant = (self.work / source).parent / f"{name}.toml"
        variant.write_text(text)
        return str(variant.relative_to(self.work))

    def study(self, name: str, study_file: str, replace: Sequence[tuple] = ()) -> Path:
        """`vbi study` (tables only) of `study_file`, with text replacements."""
        if name not in self.done:
            study_file = self.variant(name, study_file, replace) if replace else study_file
            return self.command(name, "study", study_file, "--no-figures")
        return self.done[name]

    def run(self, name: str, scenario_file: str | None = None, replace: Sequence[tuple] = ()) -> Path:
        """`vbi run` of a scenario file, with text replacements, or of the built-in scenario."""
        if name not in self.done:
            if scenario_file is None:
                return self.command(name, "run")
            scenario_file = self.variant(name, scenario_file, replace) if replace else scenario_file
            return self.command(name, "run", scenario_file)
        return self.done[name]


def read_csv(path: Path) -> List[dict]:
    with open(path, newline="") as handle:
        return list(csv.DictReader(handle))


# ---------------------------------------------------------------------------------------------
# Formatting


def fixed(x: float, digits: int) -> str:
    """x with `digits` decimals, never "-0.000"."""
    text = f"{x:.{digits}f}"
    return text[1:] if text.startswith("-") and float(text) == 0 else text


def f3(x: float) -> str:
    return fixed(x, 3)


def f4(x: float) -> str:
    return fixed(x, 4)


def span(values: Iterable[float], digits: int = 3, dash: str = "–") -> str:
    values = list(values)
    return f"{fixed(min(values), digits)}{dash}{fixed(max(values), digits)}"


def percent(x: float, digits: int = 1) -> str:
    return f"{fixed(100 * x, digits)} %"


def signed_percent(x: float, digits: int = 1) -> str:
    text = fixed(100 * x, digits)
    return ("+" + text if not text.startswith("-") else "−" + text[1:]) + " %"


def mean(values: Iterable[float]) -> float:
    return statistics.fmean(list(values))


def fractile(values: Sequence[float], p: float) -> float:
    """The p-fractile by the nearest rank (a mode count is an integer)."""
    ordered = sorted(values)
    return ordered[max(0, math.ceil(p * len(ordered)) - 1)]


def table(header: Sequence[str], rows: Sequence[Sequence[str]]) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(row) + " |" for row in rows]
    return "\n".join(lines)


# ---------------------------------------------------------------------------------------------
# The pages: each a function of the outputs, returning {name: text}

PAGES: Dict[str, Callable[[Outputs], Dict[str, str]]] = {}
INPUTS: Dict[str, List[str]] = {}


def page(path: str, inputs: Sequence[str] = ()):
    def register(function):
        PAGES[path] = function
        INPUTS[path] = list(inputs)
        return function

    return register





def claim(holds: bool, statement: str) -> None:
    """A statement of a page's prose that the numbers must bear out; the check fails if not."""
    if not holds:
        raise SystemExit(f"doc_numbers: the page says that {statement}; vbi's outputs no longer do")
