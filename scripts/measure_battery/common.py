"""Running vbi, reading its JSON, and small helpers shared by the battery's stages."""

from __future__ import annotations

import json
import subprocess
from dataclasses import dataclass
from pathlib import Path
from typing import Sequence

ROOT = Path(__file__).resolve().parent.parent.parent


@dataclass
class Completed:
    """A finished vbi command: its exit code and what it printed."""

    arguments: list
    returncode: int
    stdout: str
    stderr: str
    seconds: float


def run_vbi(vbi: Path, arguments: Sequence[str], cwd: Path, log: Path | None = None) -> Completed:
    """Runs `vbi ARGUMENTS` in `cwd`; keeps its printout in `log` when given."""
    import time

    start = time.perf_counter()
    result = subprocess.run([str(vbi), *arguments], cwd=cwd, capture_output=True, text=True)
    done = Completed(list(arguments), result.returncode, result.stdout, result.stderr, time.perf_counter() - start)
    if log is not None:
        log.parent.mkdir(parents=True, exist_ok=True)
        log.write_text(f"$ vbi {' '.join(arguments)}\n# exit code {result.returncode}\n"
                       f"# stdout\n{result.stdout}# stderr\n{result.stderr}")
    return done


def require(done: Completed, what: str) -> None:
    """Stops the battery when a command that must succeed (a simulation) failed."""
    if done.returncode != 0:
        raise SystemExit(f"measure_battery: {what}: `vbi {' '.join(done.arguments)}` failed:\n{done.stderr[-2000:]}")


def read_json(path: Path) -> dict:
    return json.loads(path.read_text())


def toml_value(value) -> str:
    """A Python value as TOML text (numbers, strings, booleans, lists of them)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(float(value)) if isinstance(value, float) else str(value)
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    raise TypeError(f"no TOML text for {value!r}")


def toml_table(name: str, keys: dict, array: bool = False) -> str:
    """`[name]` (or `[[name]]`) with its keys, one per line; None values left out."""
    head = f"[[{name}]]" if array else f"[{name}]"
    lines = [head] + [f"{key} = {toml_value(value)}" for key, value in keys.items() if value is not None]
    return "\n".join(lines) + "\n"
