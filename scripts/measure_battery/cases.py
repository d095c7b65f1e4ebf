"""The battery's cases: a fixed, seeded list of synthetic load tests (issue 52, item 1).

Every case is one crossing simulated by `vbi run` (a bridge, a truck, a speed, a road class, a
road seed), one sensor position on that bridge, and what the logger and the engineer add to it:
the sampling rate, the noise, a baseline offset and drift, timing jitter, the channels recorded,
whether the record stops at the exit or keeps the free vibration, and the *information* the
engineer gives `vbi measure` besides the record (a crawl run, the bridge model, the truck's axle
loads, the entry time).

The list is made by `random.Random(SEED)` only, so its order and content are the same on every
machine: each axis's levels are repeated to the number of drawn cases and shuffled (every level
appears equally often, and the axes are combined at random). Four anchor cases come first: clean
records (no noise, drift, offset or jitter) on which the methods' own errors show alone.
"""

from __future__ import annotations

import random
from dataclasses import asdict, dataclass
from typing import Dict, List, Sequence

SEED = 20260552
DRAWN_CASES = 96  # about 30 % are refused by today's defaults (no entry time, no f1): ≥ 60 measured

# ---------------------------------------------------------------------------------------------
# The bridges: (name, how vbi run names it, the [bridge] file given to vbi measure, edits)


@dataclass(frozen=True)
class Bridge:
    """A bridge of the battery: a preset or an example file, optionally edited (a beam's
    damping, its spans)."""

    name: str
    kind: str  # "grillage" or "beam"
    span_lengths_m: tuple
    source_file: str  # repository-relative [bridge] file (the model given to vbi measure)
    preset: str | None = None  # the scenario names the preset instead of the file
    edits: tuple = ()  # (old text, new text) replacements of the source file
    modes: int = 30  # modes solved for by vbi run


def beam_spans(lengths: Sequence[float]) -> tuple:
    """The edits that turn examples/bridges/two-span-beam.toml into a continuous beam of these
    spans (every support pinned, as the file has it), with 2 % damping."""
    supports = ", ".join(['"pinned"'] * (len(lengths) + 1))
    spans = ", ".join(f"{length:.1f}" for length in lengths)
    return (
        ("span_lengths_m = [20.0, 20.0]", f"span_lengths_m = [{spans}]"),
        ('supports = ["pinned", "pinned", "pinned"]', f"supports = [{supports}]"),
        ("damping_ratio = 0.0", "damping_ratio = 0.02"),
    )


def continuous_beam(name: str, lengths: Sequence[float], modes: int) -> Bridge:
    """A continuous beam of the two-span beam's section over these spans."""
    return Bridge(name, "beam", tuple(lengths), "examples/bridges/two-span-beam.toml", edits=beam_spans(lengths),
                  modes=modes)


BRIDGES: Dict[str, Bridge] = {
    b.name: b
    for b in [
        # The paper's box-girder grillages (vbi run presets; examples/bridges holds each as a file).
        Bridge("paper-2x20", "grillage", (20.0, 20.0), "examples/bridges/paper-2x20.toml", "paper-2x20"),
        Bridge("paper-2x30", "grillage", (30.0, 30.0), "examples/bridges/paper-2x30.toml", "paper-2x30"),
        Bridge("paper-2x40", "grillage", (40.0, 40.0), "examples/bridges/paper-2x40.toml", "paper-2x40"),
        Bridge("paper-3x20", "grillage", (20.0,) * 3, "examples/bridges/paper-3x20.toml", "paper-3x20"),
        Bridge("paper-3x30", "grillage", (30.0,) * 3, "examples/bridges/paper-3x30.toml", "paper-3x30"),
        Bridge("paper-4x30", "grillage", (30.0,) * 4, "examples/bridges/paper-4x30.toml", "paper-4x30"),
        Bridge("paper-4x40", "grillage", (40.0,) * 4, "examples/bridges/paper-4x40.toml", "paper-4x40"),
        # Other grillages of examples/bridges.
        Bridge("i-girder-3-span", "grillage", (25.0, 32.0, 25.0), "examples/bridges/i-girder-3-span.toml"),
        Bridge("given-sections-2x25", "grillage", (25.0, 25.0), "examples/bridges/given-sections-2x25.toml"),
        Bridge("skewed-2x20", "grillage", (20.0, 20.0), "examples/bridges/skewed-2x20.toml"),
        # Beams: the VBI-2D beams of examples/bridges (undamped there; 2 % here, so that the
        # free vibration decays as a real bridge's does), and continuous beams of the two-span
        # beam's section over 2-4 spans of 20-35 m.
        Bridge(
            "beam-1x25",
            "beam",
            (25.0,),
            "examples/bridges/ss-beam-25m.toml",
            edits=(("damping_ratio = 0.0", "damping_ratio = 0.02"),),
            modes=10,
        ),
        continuous_beam("beam-2x20", [20.0, 20.0], modes=10),
        continuous_beam("beam-2x30", [30.0, 30.0], modes=10),
        continuous_beam("beam-3x25", [25.0] * 3, modes=12),
        continuous_beam("beam-4x20", [20.0] * 4, modes=14),
        continuous_beam("beam-3x35", [35.0] * 3, modes=12),
    ]
}

VEHICLES = [  # presets of `vbi vehicle list`; the 36 t truck of the paper's field test twice
    "three-axle-truck-36t",
    "three-axle-truck-36t",
    "tractor-semitrailer-5axle",
    "two-axle-truck-vbi2d",
    "hs20-44",
]

# ---------------------------------------------------------------------------------------------
# The axes and their levels

SPEEDS_KMH = [20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0, 90.0, 100.0]
ROAD_CLASSES = ["A", "B", "C"]  # ISO 8608 names, as vbi accepts them
SAMPLING_RATES_HZ = [100.0, 200.0, 500.0]
NOISE_FRACTIONS = [0.0, 0.002, 0.005, 0.01, 0.02]  # sigma per sample / the static peak
CHANNEL_SETS = [
    ("deflection", "strain"),
    ("deflection", "strain"),
    ("deflection",),
    ("strain",),
]
INFORMATION_LEVELS = ["record_only", "crawl", "model", "crawl_and_model"]
FREE_VIBRATION_S = [0.0, 0.0, 3.0, 6.0]  # 0: the record stops when the last axle leaves
CRAWL_SPEED_KMH = 5.0


@dataclass
class Case:
    """One synthetic load test and what the engineer gives `vbi measure` with it."""

    name: str
    bridge: str
    vehicle: str
    speed_kmh: float
    road_class: str
    road_seed: int
    sampling_rate_hz: float
    noise_fraction: float  # sigma of each channel's white noise / its static peak
    offset_fraction: float  # logger offset / the static peak (signed)
    drift_fraction_per_s: float  # logger drift per second / the static peak (signed)
    jitter_fraction: float  # sigma of the sampling instants / the sampling step
    channels: tuple  # "deflection", "strain"
    accelerometer: bool
    free_vibration_s: float  # run time after the last axle has left
    sensor_span: int  # the sensors are at the mid-span of this span (1-based)
    lead_s: float  # record time before the front axle enters the bridge
    information: str  # one of INFORMATION_LEVELS
    axle_loads_given: bool  # [measurement.vehicle] axle_loads_kn and axle_offsets_m
    entry_time_given: bool  # entry_time_s (an axle detector at the abutment)
    anchor: bool = False  # a clean record (the methods' own errors)

    @property
    def crawl(self) -> bool:
        return self.information in ("crawl", "crawl_and_model")

    @property
    def model(self) -> bool:
        return self.information in ("model", "crawl_and_model")

    def as_dict(self) -> dict:
        out = asdict(self)
        out["channels"] = list(self.channels)
        return out


def balanced(rng: random.Random, levels: Sequence, count: int) -> list:
    """`count` draws of `levels`, each level (nearly) equally often, in a seeded random order."""
    repeated = [levels[i % len(levels)] for i in range(count)]
    rng.shuffle(repeated)
    return repeated


def anchor_cases() -> List[Case]:
    """Clean records: no noise, offset, drift or jitter; one per information level."""
    common = dict(
        road_seed=7,
        noise_fraction=0.0,
        offset_fraction=0.0,
        drift_fraction_per_s=0.0,
        jitter_fraction=0.0,
        accelerometer=True,
        sensor_span=1,
        lead_s=4.0,
        axle_loads_given=True,
        entry_time_given=True,
        anchor=True,
    )
    return [
        # The field test of examples/measurements/field_4x30 without its noise and drift.
        Case("a01", "paper-4x30", "three-axle-truck-36t", 60.0, "A", sampling_rate_hz=200.0,
             channels=("deflection", "strain"), free_vibration_s=8.0, information="crawl", **common),
        Case("a02", "beam-2x20", "two-axle-truck-vbi2d", 72.0, "A", sampling_rate_hz=200.0,
             channels=("deflection", "strain"), free_vibration_s=8.0, information="crawl", **common),
        Case("a03", "paper-3x30", "three-axle-truck-36t", 80.0, "B", sampling_rate_hz=200.0,
             channels=("deflection", "strain"), free_vibration_s=0.0, information="model", **common),
        Case("a04", "i-girder-3-span", "hs20-44", 50.0, "A", sampling_rate_hz=500.0,
             channels=("deflection", "strain"), free_vibration_s=6.0, information="record_only", **common),
    ]


def drawn_cases(count: int = DRAWN_CASES, seed: int = SEED) -> List[Case]:
    """`count` cases whose axes are balanced and combined at random by `random.Random(seed)`."""
    rng = random.Random(seed)
    bridges = balanced(rng, sorted(BRIDGES), count)
    vehicles = balanced(rng, VEHICLES, count)
    speeds = balanced(rng, SPEEDS_KMH, count)
    roads = balanced(rng, ROAD_CLASSES, count)
    rates = balanced(rng, SAMPLING_RATES_HZ, count)
    noises = balanced(rng, NOISE_FRACTIONS, count)
    channel_sets = balanced(rng, CHANNEL_SETS, count)
    information = balanced(rng, INFORMATION_LEVELS, count)
    free_vibration = balanced(rng, FREE_VIBRATION_S, count)
    drifting = balanced(rng, [False, True], count)
    offset = balanced(rng, [False, True, True], count)
    jitter = balanced(rng, [False, False, False, True], count)
    accelerometer = balanced(rng, [True, True, True, True, False], count)
    axle_loads = balanced(rng, [True, False], count)
    entry_time = balanced(rng, [True, True, False], count)
    cases = []
    for i in range(count):
        bridge = BRIDGES[bridges[i]]
        spans = len(bridge.span_lengths_m)
        sign = lambda: rng.choice([-1.0, 1.0])  # noqa: E731
        cases.append(
            Case(
                name=f"c{i + 1:02d}",
                bridge=bridge.name,
                vehicle=vehicles[i],
                speed_kmh=speeds[i],
                road_class=roads[i],
                road_seed=rng.randrange(1, 10_000),
                sampling_rate_hz=rates[i],
                noise_fraction=noises[i],
                offset_fraction=sign() * round(rng.uniform(0.02, 0.20), 3) if offset[i] else 0.0,
                drift_fraction_per_s=sign() * round(rng.uniform(0.0005, 0.003), 5) if drifting[i] else 0.0,
                jitter_fraction=0.03 if jitter[i] else 0.0,
                channels=channel_sets[i],
                accelerometer=accelerometer[i],
                free_vibration_s=free_vibration[i],
                sensor_span=2 if spans > 1 and rng.random() < 0.25 else 1,
                lead_s=round(rng.uniform(1.5, 5.0), 2),
                information=information[i],
                axle_loads_given=axle_loads[i],
                entry_time_given=entry_time[i],
            )
        )
    return cases


def all_cases() -> List[Case]:
    """The battery: the anchors, then the drawn cases."""
    return anchor_cases() + drawn_cases()
