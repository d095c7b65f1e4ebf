"""Lifetime analyses from Python: ``vbi lifetime``'s static block maxima as a pandas DataFrame."""

from __future__ import annotations

import os
from typing import Any, Mapping, Union

from . import _vbi

LifetimeSource = Union[str, "os.PathLike[str]", Mapping[str, Any]]

#: The columns of ``block_maxima.csv``, in order.
LIFETIME_COLUMNS = ("block", "station", "quantity", "static", "time_s", "trucks")


def lifetime(source: LifetimeSource) -> Any:
    """Runs a static lifetime analysis (``vbi lifetime``) and returns its block maxima as a
    pandas DataFrame, the rows and columns of ``block_maxima.csv``: one row per block,
    station and quantity, blocks in order from 0; ``block``, ``station``, ``quantity``,
    ``static`` (the block's extreme static value in the effect's sense, SI: N, N·m or m; 0
    when no truck loads it), ``time_s`` (when it occurs) and ``trucks`` (trucks on the deck
    in its event). The values are the command's, f64 for f64.

    ``df.attrs`` holds the numbers of ``lifetime.json``: ``name``, ``bridge``,
    ``traffic_file``, ``traffic_format``, ``input_hash``, ``block_seconds``, the counts
    ``trucks``, ``events``, ``multiple_presence_events`` and ``blocks``, and ``effects`` (per
    station and quantity: ``unit``, ``largest_block_maximum``, ``largest_block`` and
    ``mean_block_maximum``).

    ``source``: a ``[lifetime]`` TOML file (its traffic file and bridge file relative to it)
    or a dict of its document (paths relative to the working directory). The traffic file
    is streamed; the GIL is released while it runs. Raises :class:`vbi.InputError` with
    ``vbi lifetime``'s located message for a bad lifetime file or a bad traffic line.
    """
    import numpy as np
    import pandas as pd

    parts = _vbi.lifetime_parts(source)
    effect = parts["effect"].astype(np.intp)
    stations = np.array([station for station, _ in parts["effects"]], dtype=object)
    quantities = np.array([quantity for _, quantity in parts["effects"]], dtype=object)
    frame = pd.DataFrame(
        {
            "block": parts["block"].astype(np.int64),
            "station": stations[effect],
            "quantity": quantities[effect],
            "static": parts["static"],
            "time_s": parts["time_s"],
            "trucks": parts["trucks"].astype(np.int64),
        },
        columns=list(LIFETIME_COLUMNS),
    )
    frame.attrs.update(parts["summary"])
    return frame
