"""Shared fixtures: the repository, the `vbi` command to compare with, and its outputs."""

from __future__ import annotations

import csv
import json
import os
import subprocess
from pathlib import Path
from typing import Dict, List

import pytest

REPOSITORY = Path(__file__).resolve().parents[3]
EXAMPLES = REPOSITORY / "examples"


def vbi_command() -> Path:
    """The `vbi` binary built from the same sources (VBI_BIN, or target/debug/vbi)."""
    path = Path(os.environ.get("VBI_BIN", REPOSITORY / "target" / "debug" / "vbi"))
    if not path.exists():
        pytest.skip(f"the vbi command is not built at {path} (cargo build --workspace)")
    return path


def run_command(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [str(vbi_command()), *args], capture_output=True, text=True, check=False
    )


def read_csv(path: Path) -> List[Dict[str, str]]:
    with open(path, newline="") as handle:
        return list(csv.DictReader(handle))


def read_json(path: Path):
    with open(path) as handle:
        return json.load(handle)
