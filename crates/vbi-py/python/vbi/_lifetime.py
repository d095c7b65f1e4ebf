"""Lifetime analyses from Python: ``vbi lifetime``'s static block maxima as a pandas DataFrame."""

from __future__ import annotations

import os
from typing import Any, Mapping, Union

from . import _vbi

LifetimeSource = Union[str, "os.PathLike[str]", Mapping[str, Any]]

#: The columns of ``block_maxima.csv``, in order (with dynamics, ``total`` and ``daf`` follow).
LIFETIME_COLUMNS = ("block", "station", "quantity", "static", "time_s", "trucks")

#: The columns of ``events.csv`` (a lifetime with dynamics), in order.
EVENT_COLUMNS = (
    "event",
    "trucks",
    "station",
    "quantity",
    "static",
    "crossing_static",
    "total",
    "daf",
    "time_s",
)


def lifetime(source: LifetimeSource, shard: Any = None) -> Any:
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

    With ``dynamics = true`` the frame has the columns ``total`` (the block's largest total,
    dynamic, extreme in the effect's sense, from the events integrated) and ``daf`` (total /
    static; NaN where the static maximum is 0), as ``block_maxima.csv`` has them; each
    effect of ``attrs["effects"]`` has its ``total`` (the total block maxima's fits and the
    assessment DAF) and ``attrs["dynamic_events"]`` the counts; ``attrs["event_totals"]`` is
    ``events.csv`` as a DataFrame (one row per integrated event and effect it loads).

    ``source``: a ``[lifetime]`` TOML file (its traffic file and bridge file relative to it)
    or a dict of its document (paths relative to the working directory). The traffic file
    is streamed; the GIL is released while it runs. Raises :class:`vbi.InputError` with
    ``vbi lifetime``'s located message for a bad lifetime file or a bad traffic line.

    ``shard``: ``"I/N"`` or ``(I, N)`` runs shard I of N of the record (``vbi lifetime
    --shard I/N``): the rows of its blocks, static only (no ``total`` column), its events in
    ``attrs["event_totals"]``, its counts, ``attrs["shard"]`` (``"I/N"``) and
    ``attrs["shard_json"]`` (the text of its ``shard.json``);
    :func:`merge_lifetime` makes the N shards' frames the single run's frame. Each shard is
    independent: run them on a cluster (``examples/python/lifetime_dask.py``).
    """
    import numpy as np
    import pandas as pd

    if isinstance(shard, str):
        index, _, count = shard.partition("/")
        shard = (int(index), int(count)) if index.isdigit() and count.isdigit() else shard
    if shard is not None and not (isinstance(shard, tuple) and len(shard) == 2):
        raise ValueError(f"shard {shard!r}: expected 'I/N' or (I, N), for example '2/8'")
    parts = _vbi.lifetime_parts(source, shard)
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
    if "total" in parts:
        frame["total"] = parts["total"]
        frame["daf"] = parts["daf"]
    frame.attrs.update(parts["summary"])
    if "shard" in parts:
        frame.attrs["shard_json"] = parts["shard"]
    if "events" in parts:
        events = parts["events"]
        rows = events["effect"].astype(np.intp)
        with np.errstate(divide="ignore", invalid="ignore"):
            daf = np.where(events["static"] != 0.0, events["total"] / events["static"], np.nan)
        frame.attrs["event_totals"] = pd.DataFrame(
            {
                "event": events["event"].astype(np.int64),
                "trucks": events["trucks"].astype(np.int64),
                "station": stations[rows],
                "quantity": quantities[rows],
                "static": events["static"],
                "crossing_static": events["crossing_static"],
                "total": events["total"],
                "daf": daf,
                "time_s": events["time_s"],
            },
            columns=list(EVENT_COLUMNS),
        )
    return frame


def merge_lifetime(source: LifetimeSource, shards: Any) -> Any:
    """The single run's frame of :func:`lifetime` from the frames of its N shards (each from
    ``vbi.lifetime(source, shard=(I, N))``, in any order): the shards' rows in block order,
    the ``total`` and ``daf`` columns and every attr of ``lifetime.json`` merged as ``vbi
    lifetime merge`` merges them, and the shards' events concatenated; equal to
    ``vbi.lifetime(source)``'s frame, f64 for f64 (tested). Raises :class:`vbi.InputError`
    when the frames are not the N shards of one run of ``source``."""
    import pandas as pd

    frames = sorted(shards, key=lambda f: int(f.attrs["shard"].split("/")[0]))
    parts = _vbi.lifetime_merge_parts(source, [f.attrs["shard_json"] for f in frames])
    frame = pd.concat(
        [f[list(LIFETIME_COLUMNS)] for f in frames], ignore_index=True
    )
    if "total" in parts:
        frame["total"] = parts["total"]
        frame["daf"] = parts["daf"]
    frame.attrs.update(parts["summary"])
    events = [f.attrs["event_totals"] for f in frames if "event_totals" in f.attrs]
    if "total" in parts:
        # A shard without events adds no row (nor its empty columns' dtypes).
        loaded = [e for e in events if len(e)] or events[:1]
        frame.attrs["event_totals"] = pd.concat(loaded, ignore_index=True)
    return frame


def fit_extreme_value(values: Any, model: str = "gev", threshold: Any = None) -> dict:
    """The maximum-likelihood fit of ``values`` by ``model``: ``"gev"`` (the generalised
    extreme-value law) or ``"gumbel"`` for block maxima, ``"gpd"`` (the generalised Pareto
    law) for the exceedances of ``threshold`` (every value above it); a dict of ``location``
    (the threshold for ``"gpd"``), ``scale``, ``shape`` (Coles's sign, negative for a bounded
    upper tail; scipy's ``genextreme`` has ``c = -shape``, its ``genpareto`` ``c = shape``; 0
    for Gumbel) and ``log_likelihood``. The fits ``vbi lifetime`` makes (docs/lifetime.md,
    "Return levels"). Needs at least 10 finite values, not all equal (:class:`vbi.VbiError`
    otherwise). The values are maxima: for an effect that governs negative (a hogging
    moment, a deflection), pass magnitudes (``-values``)."""
    return _vbi.fit_extreme_value(
        [float(v) for v in values], model, None if threshold is None else float(threshold)
    )


def fit_block_maxima(
    values: Any,
    *,
    block_days: float = 1.0,
    sense: float = 1.0,
    return_periods_years: Any = (1000.0,),
    days_per_year: float = 250.0,
    bootstrap_resamples: int = 400,
    seed: int = 0,
) -> dict:
    """The GEV and Gumbel fits of one effect's block maxima and their return levels with 95 %
    intervals, as ``vbi lifetime`` reports them in ``lifetime.json`` (``effects[i]["fits"]``):
    ``loaded_blocks``, ``unloaded_blocks`` (blocks of maximum 0, which the fit leaves out and
    the levels account for), ``errors`` (laws that could not be fitted) and ``fits``, a list
    (GEV first) of ``model``, ``law`` (``location``, ``scale``, ``shape``),
    ``log_likelihood``, ``return_levels`` (``period_years``, ``value``, ``low`` and ``high``:
    the profile-likelihood interval, ``low`` the end nearer zero, ``high`` None where
    unbounded; ``bootstrap_low`` and ``bootstrap_high``: the percentile bootstrap, None
    without resamples) and ``failed_resamples``.

    ``values``: the block maxima, signed; ``sense`` (+1 or -1) the sign of the effect (the
    fit takes ``sense * value``); ``block_days`` the block length; ``days_per_year`` the days
    of traffic in a year (250: BTLS's); the T-year level has a block non-exceedance
    probability of (1 - 1/T)^(block_days/days_per_year)."""
    return _vbi.fit_block_maxima_parts(
        [float(v) for v in values],
        float(block_days),
        float(sense),
        [float(t) for t in return_periods_years],
        float(days_per_year),
        int(bootstrap_resamples),
        int(seed),
    )


#: The columns of ``return_levels.csv``, in order.
RETURN_LEVEL_COLUMNS = (
    "station",
    "quantity",
    "model",
    "period_years",
    "return_level",
    "low",
    "high",
    "bootstrap_low",
    "bootstrap_high",
    "fitted",
    "location",
    "scale",
    "shape",
)


def lifetime_return_levels(frame: Any) -> Any:
    """The return levels of a :func:`vbi.lifetime` result as a pandas DataFrame with the rows
    and columns of ``vbi lifetime``'s ``return_levels.csv``: per effect, law (``gev``,
    ``gumbel`` for the block maxima, ``gpd`` for the peaks over threshold) and return period,
    the level (signed, SI), its 95 % profile-likelihood interval (``low`` the end nearer zero,
    ``high`` NaN where unbounded), the bootstrap interval (NaN without resamples and for
    ``gpd``), the values fitted, and the law's parameters (a ``gpd`` row's ``location`` is its
    threshold). Read from ``frame.attrs``, so the numbers are the command's."""
    import pandas as pd

    rows = []
    for effect in frame.attrs["effects"]:
        key = (effect["station"], effect["quantity"])
        fits = effect.get("fits")
        if fits:
            for fit in fits["fits"]:
                law = fit["law"]
                for level in fit["return_levels"]:
                    rows.append(
                        (*key, fit["model"], *_level(level), fits["loaded_blocks"],
                         law["location"], law["scale"], law["shape"])
                    )
        peaks = effect.get("peaks_over_threshold")
        if peaks:
            law = peaks["law"]
            for level in peaks["return_levels"]:
                rows.append(
                    (*key, "gpd", *_level(level), peaks["exceedances"],
                     law["threshold"], law["scale"], law["shape"])
                )
    return pd.DataFrame(rows, columns=list(RETURN_LEVEL_COLUMNS))


def _level(level: dict) -> tuple:
    """A level's period, value and interval ends, None as NaN."""
    nan = float("nan")
    value = lambda key: nan if level.get(key) is None else level[key]  # noqa: E731
    return (
        level["period_years"],
        level["value"],
        level["low"],
        value("high"),
        value("bootstrap_low"),
        value("bootstrap_high"),
    )


def lifetime_fatigue(source: LifetimeSource) -> Any:
    """The static fatigue of a lifetime's ``[[fatigue_detail]]`` tables (``vbi lifetime``'s
    ``fatigue.csv``, docs/fatigue.md) as a pandas DataFrame: one row per detail, the columns of
    the library's table of lifetime fatigue outputs (Miner's sum of the record's static stress
    history counted as one history, per year, the fatigue life, Δσ_E,2 of 100 years, cycles,
    largest and equivalent ranges), the command's numbers f64 for f64. ``df.attrs["blocks"]``
    is ``fatigue_blocks.csv``: each block's Miner's sum per detail (a DataFrame, one row per
    block from 0). Only the fatigue pass runs (the block maxima are :func:`lifetime`'s).
    """
    import pandas as pd

    from ._vbi import lifetime_fatigue_parts

    parts = lifetime_fatigue_parts(source)
    frame = pd.DataFrame(parts["rows"], columns=parts["columns"])
    blocks = parts["blocks"]
    length = max((len(v) for v in blocks.values()), default=0)
    frame.attrs["blocks"] = pd.DataFrame(
        {f"{name}_static_damage": list(values) + [0.0] * (length - len(values))
         for name, values in blocks.items()}
    ).rename_axis("block")
    return frame
