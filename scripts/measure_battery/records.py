"""The battery's records (issue 52, item 1): each case's crossing simulated by `vbi run`, sampled
as a logger would record it, and described by the `[measurement]` file an engineer would write.

For each case, in OUT/cases/<case>/:

- `scenario.toml` and `run/` (`vbi run`'s outputs without its large CSVs): the crossing at speed,
  with a fixed 1 ms step (as examples/measurements/field_4x30/fast_scenario.toml) and an
  inline road of the case's ISO 8608 class whose approach holds the record's lead-in;
- `record.csv`: the sensors at the mid-span of the case's span (the girder nearest the deck's
  centreline on a grillage, the section on a beam), from the converged (static-corrected)
  histories, sampled at the case's rate:

      deflection_mm      1000 u(t_i) + p_u (o + d t_i) + n_i,     n ~ Normal(0, s p_u)
      strain_ue          M(t_i) / (1000 k) + p_e (o + d t_i) + n_i  (k kN·m per microstrain)
      acceleration_m_s2  a(t_i) + n_i,  n ~ Normal(0, s max|a|)   (the station's modal acceleration)

  p the channel's static peak, o, d and s the case's offset, drift per second and noise as
  fractions of it, t_i the record's time. With jitter the sampling instants are
  t_i = i/f_s + Normal(0, j/f_s) (the logger writes them; the values are the histories
  interpolated there by a four-point Lagrange polynomial on the 1 ms steps);
- `record.toml`: what a user must give (the CSV, its time column, the channels with their units
  and the strain gauge's stated kN·m per microstrain, the speed, the loaded span and the bridge
  length, `resample_hz` for a jittering clock, which vbi otherwise refuses) and what the case's
  information level adds (the crawl run, the bridge model with the sensors' positions, the
  truck's axle loads and spacings, the entry time). Every other key is left at its default;
- `crawl.csv`, `crawl.toml` (cases with a crawl run): the same truck at 5 km/h on a smooth road
  (one `vbi run` per bridge and truck, shared by the cases, in OUT/crawls/), recorded at 50 Hz
  by the same logger: the same noise fraction and drift per second, its own offset, no jitter;
  its entry time given (vbi needs it).

The truth of each channel is the exact DAF of the run: summary.json's converged dynamic maximum
over the exact static maximum at the station (`deflection`, `bending_moment`; the extremes
between the steps), checked against the same ratio taken from the histories at their step (1 ms
with jitter, else the record's), as examples/measurements/field_4x30/generate.py does: they agree
but for a kinked moment line's static peak between two steps. The truth of f1 is the bridge
model's first vertical-bending frequency (`vbi modes` of the [bridge] file), checked to be one of
the run's `frequencies_hz` (`first_frequency_in_run`; the presets' runs and the files agree).
"""

from __future__ import annotations

import json
import math
import os
import random
import threading
from dataclasses import dataclass, field
from pathlib import Path
from typing import Dict, List, Sequence

from cases import BRIDGES, CRAWL_SPEED_KMH, Bridge, Case
from common import ROOT, read_json, require, run_vbi, toml_table

TIME_STEP_S = 0.001  # fixed, as field_4x30/fast_scenario.toml: no time-step check, exact sampling
CRAWL_TIME_STEP_S = 0.004  # the crawl is quasi-static (its under-resolved high modes are not excited)
CRAWL_RATE_HZ = 50.0  # as examples/measurements/field_4x30/crawl.csv
CRAWL_LEAD_S = 4.0
CRAWL_APPROACH_M = 8.0
CRAWL_FREE_VIBRATION_S = 3.0
STRAIN_TARGET_UE = 60.0  # the gauge factor is chosen for about this static peak
QUANTITY = {"deflection": "deflection", "strain": "bending_moment"}

# ---------------------------------------------------------------------------------------------
# Bridges and vehicles


@dataclass
class BridgeFacts:
    """What the battery needs of a bridge model: its file, f1, the girders' lateral places."""

    path: Path
    first_vertical_bending_hz: float
    frequencies_hz: list
    kinds: list
    girder_y_m: list  # empty for a beam


def bridge_file(out: Path, bridge: Bridge) -> Path:
    """OUT/bridges/<name>.toml: the example file with the bridge's edits (each must apply)."""
    text = (ROOT / bridge.source_file).read_text()
    for old, new in bridge.edits:
        if old not in text:
            raise SystemExit(f"measure_battery: {bridge.source_file} no longer holds {old!r}")
        text = text.replace(old, new)
    path = out / "bridges" / f"{bridge.name}.toml"
    path.parent.mkdir(parents=True, exist_ok=True)
    edited = " with the edits of scripts/measure_battery/cases.py" if bridge.edits else ""
    path.write_text(f"# {bridge.name}: {bridge.source_file}{edited}\n" + text)
    return path


def bridge_facts(vbi: Path, out: Path, bridge: Bridge, cache: Dict[str, BridgeFacts]) -> BridgeFacts:
    """The bridge file and `vbi modes` of it (once per bridge)."""
    if bridge.name not in cache:
        path = bridge_file(out, bridge)
        done = run_vbi(vbi, ["modes", str(path), "--modes", "12", "--format", "json"], cwd=out)
        require(done, f"the modes of {bridge.name}")
        modes = json.loads(done.stdout)
        if abs(modes["model"]["length_m"] - sum(bridge.span_lengths_m)) > 1e-6:
            raise SystemExit(f"measure_battery: {bridge.name} is {modes['model']['length_m']} m long, "
                             f"not the {sum(bridge.span_lengths_m)} m of cases.py")
        frequencies = [m["frequency_hz"] for m in modes["modes"]]
        kinds = [m["kind"] for m in modes["modes"]]
        first = next(f for f, k in zip(frequencies, kinds) if k == "vertical_bending")
        girders = [g["y_m"] for g in modes["model"].get("girders", [])] if bridge.kind == "grillage" else []
        cache[bridge.name] = BridgeFacts(path, first, frequencies, kinds, girders)
    return cache[bridge.name]


def vehicle_axles(vbi: Path, out: Path, vehicle: str, cache: Dict[str, dict]) -> dict:
    """The preset's static axle loads [kN] and spacings behind the first axle [m], and the
    distance between its wheels (`vbi vehicle show --format json`; vbi takes one track width
    for every axle: the axles' own, weighted by their loads)."""
    if vehicle not in cache:
        done = run_vbi(vbi, ["vehicle", "show", vehicle, "--format", "json"], cwd=out)
        require(done, f"the vehicle {vehicle}")
        wheels = json.loads(done.stdout)["wheels"]
        axles: Dict[float, float] = {}
        sides: Dict[float, list] = {}
        for wheel in wheels:
            x = round(-wheel["longitudinal_offset_m"], 6) + 0.0  # not -0.0
            axles[x] = axles.get(x, 0.0) + wheel["static_load_n"] / 1e3
            sides.setdefault(x, []).append(wheel["lateral_offset_m"])
        track = sum(axles[x] * (max(sides[x]) - min(sides[x])) for x in axles) / sum(axles.values())
        cache[vehicle] = {
            "axle_offsets_m": sorted(axles),
            "axle_loads_kn": [round(axles[x], 2) for x in sorted(axles)],
            "track_width_m": round(track, 3),
            "length_m": max(axles),
        }
    return cache[vehicle]


@dataclass
class Sensor:
    """Where a case's sensors are."""

    station: str  # the station of vbi run's histories
    span: int
    span_length_m: float
    position_m: float  # from the first support, along the girders
    lateral_position_m: float  # from the deck centreline, left positive


def sensor_of(bridge: Bridge, facts: BridgeFacts, span: int) -> Sensor:
    """The mid-span of `span`, on the girder nearest the centreline (a grillage) or the beam."""
    lengths = bridge.span_lengths_m
    position = sum(lengths[: span - 1]) + lengths[span - 1] / 2
    if bridge.kind == "grillage":
        girder = (len(facts.girder_y_m) + 1) // 2
        return Sensor(f"span{span}_mid_g{girder}", span, lengths[span - 1], position, facts.girder_y_m[girder - 1])
    return Sensor(f"span{span}_mid_section", span, lengths[span - 1], position, 0.0)


# ---------------------------------------------------------------------------------------------
# Simulation


def scenario_text(name: str, bridge: Bridge, facts: BridgeFacts, case_dir: Path, vehicle: str, speed_kmh: float,
                  road: str, seed: int, approach_m: float, free_vibration_s: float, time_step_s: float) -> str:
    """A `[scenario]` with an inline `[road]` (its approach holds the record's lead-in)."""
    bridge_name = bridge.preset or os.path.relpath(facts.path, case_dir)
    scenario = {
        "name": name,
        "bridge": bridge_name,
        "vehicle": vehicle,
        "seed": seed,
        "speed_kmh": speed_kmh,
        "modes": bridge.modes,
        "time_step_s": time_step_s,
        "free_vibration_s": free_vibration_s,
    }
    road_table = {"class": road, "approach_length_m": round(approach_m, 1)}
    return ("# SYNTHETIC load-test crossing of scripts/measure_battery (not a measurement)\n"
            + toml_table("scenario", scenario) + "\n" + toml_table("road", road_table))


def history_columns(stations: Sequence[str]) -> List[str]:
    columns = ["time_s", "front_axle_x_m"]
    for station in stations:
        columns += [f"{station}_deflection_m", f"{station}_static_deflection_m", f"{station}_moment_n_m",
                    f"{station}_static_moment_n_m", f"{station}_acceleration_m_s2"]
    return columns


def read_history(path: Path, columns: Sequence[str]) -> Dict[str, list]:
    """The named columns of a histories.csv (streamed: the file holds every station)."""
    with open(path) as handle:
        header = handle.readline().strip().split(",")
        missing = [c for c in columns if c not in header]
        if missing:
            raise SystemExit(f"measure_battery: {path} has no column {missing[0]} (vbi run's names changed?)")
        index = [header.index(c) for c in columns]
        values: List[list] = [[] for _ in columns]
        for line in handle:
            cells = line.split(",")
            for slot, i in enumerate(index):
                values[slot].append(float(cells[i]))
    return dict(zip(columns, values))


def write_history(path: Path, history: Dict[str, list]) -> None:
    names = list(history)
    with open(path, "w") as handle:
        handle.write(",".join(names) + "\n")
        for row in zip(*history.values()):
            handle.write(",".join(repr(v) for v in row) + "\n")


def simulate(vbi: Path, directory: Path, scenario: str, history_every: int, stations: Sequence[str]) -> tuple:
    """`vbi run` of `scenario` in `directory`: its summary and the sensors' histories (kept as
    sensors.csv; the run's large CSVs are removed). Reuses a finished run."""
    directory.mkdir(parents=True, exist_ok=True)
    kept = directory / "sensors.csv"
    summary_path = directory / "run" / "summary.json"
    scenario_path = directory / "scenario.toml"
    if kept.exists() and summary_path.exists() and scenario_path.exists() and scenario_path.read_text() == scenario:
        return read_json(summary_path), read_history(kept, history_columns(stations))
    scenario_path.write_text(scenario)
    done = run_vbi(vbi, ["run", "scenario.toml", "--out", "run", "--history-every", str(history_every)],
                   cwd=directory, log=directory / "run.log")
    require(done, f"the crossing of {directory.name}")
    history = read_history(directory / "run" / "histories.csv", history_columns(stations))
    write_history(kept, history)
    for large in ("histories.csv", "vehicles.csv"):
        (directory / "run" / large).unlink(missing_ok=True)
    return read_json(summary_path), history


def entry_time(history: Dict[str, list]) -> float:
    """When the front axle reaches x = 0 (linear between the steps: constant speed)."""
    t, x = history["time_s"], history["front_axle_x_m"]
    i = next(i for i in range(len(x)) if x[i] >= 0.0)
    if i == 0:
        return t[0]
    return t[i - 1] + (0.0 - x[i - 1]) / (x[i] - x[i - 1]) * (t[i] - t[i - 1])


# ---------------------------------------------------------------------------------------------
# Truth


def station_result(summary: dict, station: str, quantity: str) -> dict:
    return next(s for s in summary["stations"] if s["name"] == station and s["quantity"] == quantity)


def daf_of(dynamic: Sequence[float], static: Sequence[float]) -> float:
    """Converged dynamic maximum over the exact static maximum, both in the direction of the
    static response (generate.py's `daf`)."""
    peak = max(static, key=abs)
    sign = 1.0 if peak > 0 else -1.0
    return max(sign * v for v in dynamic) / (sign * peak)


def truth_of(case: Case, summary: dict, history: Dict[str, list], sensor: Sensor, facts: BridgeFacts) -> dict:
    """The exact answers of a case (see the module's docstring)."""
    truth: Dict[str, dict] = {}
    for channel in case.channels:
        result = station_result(summary, sensor.station, QUANTITY[channel])
        column = {"deflection": "deflection_m", "strain": "moment_n_m"}[channel]
        truth[channel] = {
            "daf": result["daf"],
            "static_max": result["static_max"],
            "dynamic_max": result["dynamic_max"],
            # the same ratio from the histories at their step (the static peak of a kinked
            # moment line falls between the steps: a check, not the truth)
            "daf_from_histories": daf_of(history[f"{sensor.station}_{column}"],
                                         history[f"{sensor.station}_static_{column}"]),
        }
    run_frequencies = summary["frequencies_hz"]
    first = facts.first_vertical_bending_hz
    in_run = any(abs(f - first) <= 1e-6 * first for f in run_frequencies)
    rdm = None
    if "deflection" in truth and "strain" in truth:
        rdm = truth["deflection"]["daf"] / truth["strain"]["daf"]
    return {"channels": truth, "rdm": rdm, "first_frequency_hz": first, "first_frequency_in_run": in_run,
            "run_frequencies_hz": run_frequencies[:6], "run_warnings": summary.get("warnings", [])}


# ---------------------------------------------------------------------------------------------
# Sampling the record


def lagrange_at(values: Sequence[float], position: float) -> float:
    """values interpolated at a fractional index by the four-point Lagrange polynomial."""
    i = min(max(int(math.floor(position)), 1), len(values) - 3)
    s = position - i  # between values[i] and values[i + 1]
    a, b, c, d = values[i - 1], values[i], values[i + 1], values[i + 2]
    return (-s * (s - 1) * (s - 2) / 6 * a + (s + 1) * (s - 1) * (s - 2) / 2 * b
            - (s + 1) * s * (s - 2) / 2 * c + (s + 1) * s * (s - 1) / 6 * d)


def sampling_instants(history: Dict[str, list], start_s: float, rate_hz: float, jitter_fraction: float,
                      rng: random.Random) -> List[float]:
    """The logger's sampling instants in run time, from `start_s` to the end of the run."""
    t = history["time_s"]
    step = 1.0 / rate_hz
    count = int(math.floor((t[-1] - start_s) * rate_hz + 1e-9)) + 1
    if jitter_fraction > 0:
        count -= 1  # keep the last jittered instant inside the run
        return [start_s + i * step + rng.gauss(0.0, jitter_fraction * step) if i else start_s for i in range(count)]
    return [start_s + i * step for i in range(count)]


def values_at(series: Sequence[float], times: Sequence[float], instants: Sequence[float]) -> List[float]:
    """series (on the uniform steps `times`) at the instants: exact on a step, else interpolated."""
    h = (times[-1] - times[0]) / (len(times) - 1)
    out = []
    for instant in instants:
        position = (instant - times[0]) / h
        nearest = round(position)
        if abs(position - nearest) < 1e-6:
            out.append(series[int(nearest)])
        else:
            out.append(lagrange_at(series, position))
    return out


def gauge_factor(peak_moment_n_m: float) -> float:
    """The strain gauge's stated kN·m per microstrain: two significant digits, for a static peak
    near STRAIN_TARGET_UE."""
    raw = abs(peak_moment_n_m) / 1e3 / STRAIN_TARGET_UE
    digits = 1 - int(math.floor(math.log10(raw)))
    return round(raw, digits)


def logger_channels(case: Case, history: Dict[str, list], sensor: Sensor, instants: Sequence[float],
                    record_times: Sequence[float], gauge: float, offset_fraction: float, rng: random.Random) -> dict:
    """The recorded columns: the sensors' signals with the case's offset, drift and noise."""
    t = history["time_s"]
    station = sensor.station
    columns = {"time_s": list(record_times)}
    signals = {
        "deflection": ("deflection_mm", [1e3 * v for v in history[f"{station}_deflection_m"]],
                       max(history[f"{station}_static_deflection_m"], key=abs) * 1e3),
        "strain": ("strain_ue", [v / (1e3 * gauge) for v in history[f"{station}_moment_n_m"]],
                   max(history[f"{station}_static_moment_n_m"], key=abs) / (1e3 * gauge)),
    }
    for channel in case.channels:
        column, series, peak = signals[channel]
        clean = values_at(series, t, instants)
        scale = abs(peak)
        baseline = [scale * (offset_fraction + case.drift_fraction_per_s * time) for time in record_times]
        columns[column] = [v + b + rng.gauss(0.0, case.noise_fraction * scale) for v, b in zip(clean, baseline)]
    if case.accelerometer:
        series = history[f"{station}_acceleration_m_s2"]
        scale = max(abs(v) for v in series)
        columns["acceleration_m_s2"] = [v + rng.gauss(0.0, case.noise_fraction * scale)
                                        for v in values_at(series, t, instants)]
    return columns


def write_csv(path: Path, columns: dict) -> None:
    formats = {"time_s": "{:.6f}", "deflection_mm": "{:.7f}", "strain_ue": "{:.5f}", "acceleration_m_s2": "{:.6e}"}
    names = list(columns)
    with open(path, "w") as handle:
        handle.write("# SYNTHETIC data: a vbi run sampled by scripts/measure_battery; not a measurement\n")
        handle.write(",".join(names) + "\n")
        for row in zip(*columns.values()):
            handle.write(",".join(formats[n].format(v) for n, v in zip(names, row)) + "\n")


# ---------------------------------------------------------------------------------------------
# The [measurement] files


def channel_tables(case: Case, sensor: Sensor, gauge: float, located: bool, accelerometer: bool) -> str:
    """The `[[measurement.channels]]` of the record (and of its crawl run, without the
    accelerometer): names, columns, kinds, units; the gauge's stated factor; the sensors'
    positions when the bridge model is given (where its lines and shapes are read)."""
    place = {"position_m": sensor.position_m, "lateral_position_m": sensor.lateral_position_m or None} if located else {}
    channel = lambda keys: toml_table("measurement.channels", {**keys, **place}, array=True)  # noqa: E731
    tables = []
    if "deflection" in case.channels:
        tables.append(channel({"name": "deflection", "column": "deflection_mm", "kind": "deflection", "unit": "mm",
                               "section": "sensor"}))
    if "strain" in case.channels:
        tables.append(channel({"name": "strain", "column": "strain_ue", "kind": "strain", "unit": "microstrain",
                               "section": "sensor"}) + f"moment = {{ knm_per_microstrain = {gauge!r} }}\n")
    if accelerometer:
        tables.append(channel({"name": "acceleration", "column": "acceleration_m_s2", "kind": "acceleration",
                               "unit": "m/s2"}))
    return "\n".join(tables)


def vehicle_table(case: Case, axles: dict) -> str:
    if not case.axle_loads_given:
        return ""
    keys = {"axle_loads_kn": axles["axle_loads_kn"], "axle_offsets_m": axles["axle_offsets_m"],
            "track_width_m": axles["track_width_m"] or None}
    return toml_table("measurement.vehicle", keys) + "\n"


def record_toml(case: Case, bridge: Bridge, sensor: Sensor, facts: BridgeFacts, case_dir: Path, axles: dict,
                gauge: float, entry_s: float) -> str:
    """The record's `[measurement]` file: what a user must give, and the case's information."""
    keys = {
        "description": f"SYNTHETIC battery case {case.name}: {case.vehicle}, {case.speed_kmh:g} km/h, {bridge.name}",
        "csv": "record.csv",
        "time_column": "time_s",
        "speed_kmh": case.speed_kmh,
        "span_length_m": sensor.span_length_m,
        "bridge_length_m": sum(bridge.span_lengths_m),
        "entry_time_s": round(entry_s, 3) if case.entry_time_given else None,
        "resample_hz": case.sampling_rate_hz if case.jitter_fraction > 0 else None,
        "crawl": "crawl.toml" if case.crawl else None,
        "bridge": os.path.relpath(facts.path, case_dir) if case.model else None,
    }
    return ("# SYNTHETIC load test of scripts/measure_battery (not a measurement of any real bridge)\n"
            + toml_table("measurement", keys) + "\n" + vehicle_table(case, axles)
            + channel_tables(case, sensor, gauge, case.model, case.accelerometer))


def crawl_toml(case: Case, bridge: Bridge, sensor: Sensor, axles: dict, gauge: float, entry_s: float) -> str:
    keys = {
        "description": f"SYNTHETIC crawl run of battery case {case.name}: {case.vehicle} at {CRAWL_SPEED_KMH:g} km/h",
        "csv": "crawl.csv",
        "time_column": "time_s",
        "speed_kmh": CRAWL_SPEED_KMH,
        "span_length_m": sensor.span_length_m,
        "bridge_length_m": sum(bridge.span_lengths_m),
        "entry_time_s": round(entry_s, 3),
    }
    return ("# SYNTHETIC crawl run of scripts/measure_battery (not a measurement of any real bridge)\n"
            + toml_table("measurement", keys) + "\n" + vehicle_table(case, axles)
            + channel_tables(case, sensor, gauge, False, False))


# ---------------------------------------------------------------------------------------------
# One case


@dataclass
class Simulations:
    """What several cases share: bridge facts, vehicles, crawl runs."""

    vbi: Path
    out: Path
    bridges: dict = field(default_factory=dict)
    vehicles: dict = field(default_factory=dict)
    crawls: dict = field(default_factory=dict)
    crawl_locks: dict = field(default_factory=dict)
    lock: threading.Lock = field(default_factory=threading.Lock)


def crawl_run(sims: Simulations, bridge: Bridge, facts: BridgeFacts, vehicle: str) -> tuple:
    """The 5 km/h crossing of a bridge by a truck on a smooth road, simulated once (the cases
    that share it wait for it): its summary and the histories at the mid-spans of spans 1-2."""
    key = f"{bridge.name}-{vehicle}"
    with sims.lock:
        lock = sims.crawl_locks.setdefault(key, threading.Lock())
    with lock:
        if key not in sims.crawls:
            stations = [sensor_of(bridge, facts, span).station for span in (1, 2) if span <= len(bridge.span_lengths_m)]
            speed = CRAWL_SPEED_KMH / 3.6
            crawl_dir = sims.out / "crawls" / key
            scenario = scenario_text(f"crawl-{key}", bridge, facts, crawl_dir, vehicle, CRAWL_SPEED_KMH, "smooth", 1,
                                     max(CRAWL_APPROACH_M, speed * (CRAWL_LEAD_S + 1.0)), CRAWL_FREE_VIBRATION_S,
                                     CRAWL_TIME_STEP_S)
            every = int(round(1.0 / CRAWL_RATE_HZ / CRAWL_TIME_STEP_S))
            sims.crawls[key] = simulate(sims.vbi, crawl_dir, scenario, every, stations)
        return sims.crawls[key]


def crawl_record(sims: Simulations, case: Case, bridge: Bridge, facts: BridgeFacts, sensor: Sensor, case_dir: Path,
                 axles: dict, gauge: float, rng: random.Random) -> dict:
    """crawl.csv and crawl.toml of a case: the shared 5 km/h run of its bridge and truck."""
    summary, history = crawl_run(sims, bridge, facts, case.vehicle)
    entry = entry_time(history)
    start = min(history["time_s"], key=lambda t: abs(t - (entry - CRAWL_LEAD_S)))  # on a step
    instants = sampling_instants(history, start, CRAWL_RATE_HZ, 0.0, rng)
    record_times = [t - start for t in instants]
    offset = rng.choice([-1.0, 1.0]) * rng.uniform(0.02, 0.2) if case.offset_fraction else 0.0
    columns = logger_channels(case, history, sensor, instants, record_times, gauge, offset, rng)
    columns.pop("acceleration_m_s2", None)
    write_csv(case_dir / "crawl.csv", columns)
    (case_dir / "crawl.toml").write_text(crawl_toml(case, bridge, sensor, axles, gauge, entry - start))
    static = {c: station_result(summary, sensor.station, QUANTITY[c])["static_max"] for c in case.channels}
    return {"entry_time_s": entry - start, "samples": len(instants), "offset_fraction": offset, "static_max": static,
            "duration_s": record_times[-1]}


def make_record(sims: Simulations, case: Case, seed: int) -> dict:
    """Simulates a case and writes its record, crawl run and [measurement] files; its truth."""
    bridge = BRIDGES[case.bridge]
    facts = bridge_facts(sims.vbi, sims.out, bridge, sims.bridges)
    axles = vehicle_axles(sims.vbi, sims.out, case.vehicle, sims.vehicles)
    sensor = sensor_of(bridge, facts, case.sensor_span)
    case_dir = sims.out / "cases" / case.name
    case_dir.mkdir(parents=True, exist_ok=True)
    step_ms = int(round(1000.0 / case.sampling_rate_hz))
    every = 1 if case.jitter_fraction > 0 else step_ms
    speed = case.speed_kmh / 3.6
    scenario = scenario_text(case.name, bridge, facts, case_dir, case.vehicle, case.speed_kmh, case.road_class,
                             case.road_seed, max(30.0, speed * (case.lead_s + 2.0)), case.free_vibration_s, TIME_STEP_S)
    summary, history = simulate(sims.vbi, case_dir, scenario, every, [sensor.station])
    rng = random.Random(f"{seed}-{case.name}")
    entry = entry_time(history)
    grid = every * TIME_STEP_S
    start = round((entry - case.lead_s) / grid) * grid
    instants = sampling_instants(history, start, case.sampling_rate_hz, case.jitter_fraction, rng)
    record_times = [t - start for t in instants]
    gauge = gauge_factor(max(history[f"{sensor.station}_static_moment_n_m"], key=abs))
    columns = logger_channels(case, history, sensor, instants, record_times, gauge, case.offset_fraction, rng)
    write_csv(case_dir / "record.csv", columns)
    crawl = crawl_record(sims, case, bridge, facts, sensor, case_dir, axles, gauge, rng) if case.crawl else None
    description = record_toml(case, bridge, sensor, facts, case_dir, axles, gauge, entry - start)
    (case_dir / "record.toml").write_text(description)
    return {
        "directory": str(case_dir.relative_to(sims.out)),
        "station": sensor.station,
        "span_length_m": sensor.span_length_m,
        "position_m": sensor.position_m,
        "lateral_position_m": sensor.lateral_position_m,
        "gauge_knm_per_microstrain": gauge,
        "entry_time_s": entry - start,
        "exit_time_s": entry - start + (sum(bridge.span_lengths_m) + axles["length_m"]) / speed,
        "samples": len(instants),
        "duration_s": record_times[-1],
        "axles": axles,
        "crawl": crawl,
        "truth": truth_of(case, summary, history, sensor, facts),
    }
