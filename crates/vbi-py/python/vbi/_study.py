"""Studies from Python: the case table of ``vbi study`` as a pandas DataFrame."""

from __future__ import annotations

import os
from typing import Any, Dict, List, Mapping, Optional, Union

from . import _vbi

StudySource = Union[str, "os.PathLike[str]", Mapping[str, Any]]

#: Columns that hold text even where every cell looks like a number.
_TEXT_COLUMNS = {
    "case", "rdm_station", "warnings", "error", "kind", "quantity", "code", "provision", "basis"
}

#: The tables of a study, in the order of ``vbi study``'s files.
_TABLES = ("cases", "daf_by_modes", "participation", "design_codes")


def _typed(name: str, cells: List[str]) -> List[Any]:
    """A column's cells as Python values: None where empty; int, then float, where every
    filled cell reads as one (``float`` of the shortest text is the exact ``f64``); else str."""
    values: List[Any] = [None if cell == "" else cell for cell in cells]
    if name in _TEXT_COLUMNS:
        return values
    for kind in (int, float):
        try:
            return [None if v is None else kind(v) for v in values]
        except ValueError:
            continue
    return values


def _frame(table: Dict[str, Any]) -> Any:
    import pandas as pd

    columns: List[str] = table["columns"]
    rows: List[List[str]] = table["rows"]
    data = {}
    for index, name in enumerate(columns):
        values = _typed(name, [row[index] for row in rows])
        if values and all(v is None or isinstance(v, int) for v in values) and any(
            v is not None for v in values
        ):
            # Counts, mode numbers and seeds are never negative, and a seed needs all 64
            # bits: unsigned, so that every shard of a study gives the same dtype.
            unsigned = all(v is None or v >= 0 for v in values)
            data[name] = pd.array(values, dtype="UInt64" if unsigned else "Int64")
        elif any(isinstance(v, str) for v in values) or name in _TEXT_COLUMNS:
            # Text (with None where empty) is always of dtype object, so that a shard whose
            # column is all empty and one that holds text concatenate to the same dtype.
            data[name] = pd.Series(values, dtype=object)
        else:
            data[name] = values
    return pd.DataFrame(data, columns=columns)


def study_columns(
    source: StudySource, *, shard: Optional[str] = None, threads: Optional[int] = None
) -> Dict[str, Any]:
    """The tables of a study without pandas: ``{"name": str, "cases": table,
    "daf_by_modes": table, "participation": table, "design_codes": table}``, each table ``{"columns": [...],
    "rows": [[...]]}`` with typed cells (None where empty). Arguments as :func:`study`."""
    cells = _vbi.study_cells(source, shard=shard, threads=threads)
    tables: Dict[str, Any] = {"name": cells["name"]}
    for key in _TABLES:
        table = cells[key]
        columns = table["columns"]
        typed = [_typed(name, [row[i] for row in table["rows"]]) for i, name in enumerate(columns)]
        tables[key] = {"columns": columns, "rows": [list(row) for row in zip(*typed)]}
    return tables


def study(
    source: StudySource, *, shard: Optional[str] = None, threads: Optional[int] = None
) -> Any:
    """Runs a parametric study and returns its case table (``cases.csv`` of ``vbi study``) as
    a pandas DataFrame, one row per case in case order: ``case``, the varied fields,
    ``sample``, ``seed``, the metrics (``daf_u``, ``daf_m``, ``rdm``, cut-off modes, static and
    dynamic extremes in m and N·m, ``f1_hz``, ...) and ``error``.

    ``source``: a ``[study]`` TOML file (str or path) or a dict of its document.
    ``shard``: ``"I/N"`` runs the I-th of N equal contiguous parts of the cases (as
    ``vbi study --shard``), to spread a study over processes or a Dask cluster.
    ``threads``: worker threads (default one per core). The GIL is released while it runs.
    Raises :class:`vbi.InputError` for a bad study file, located as ``vbi check`` locates it.
    """
    return _frame(_vbi.study_cells(source, shard=shard, threads=threads)["cases"])


def study_tables(
    source: StudySource, *, shard: Optional[str] = None, threads: Optional[int] = None
) -> Dict[str, Any]:
    """The four tables of a study as DataFrames: ``cases``, ``daf_by_modes`` (DAF_u, DAF_M,
    RDM against the number of modes K, per case), ``participation`` (deck participation
    MPS_k and frequency [Hz] of each mode, per case) and ``design_codes`` (each design code's
    1 + IM beside the computed DAF at the RDM station, per case). Arguments as :func:`study`."""
    cells = _vbi.study_cells(source, shard=shard, threads=threads)
    return {key: _frame(cells[key]) for key in _TABLES}


def study_case_count(source: StudySource) -> int:
    """The number of cases of a study (to choose shards)."""
    return _vbi.study_case_count(source)
