"""Your own beam: DAF at mid-span.

A 32 m simply supported concrete beam, given as a dict (the same document a `[bridge]` TOML file
holds), crossed by the paper's five-axle truck on a 'good' road at a few speeds; prints the first
frequencies and the DAF of the mid-span deflection and moment at each speed.

    pip install ./crates/vbi-py      # once, from the repository
    python examples/python/own_beam_daf.py
"""

from __future__ import annotations

import vbi

# SI units, as docs/input-format.md describes the [bridge] table.
BEAM = {
    "bridge": {
        "type": "continuous_beam",
        "span_lengths_m": [32.0],
        "supports": ["pinned", "roller"],
        "damping_ratio": 0.02,
        "section": {
            "modulus_gpa": 34.0,
            "second_moment_of_area_m4": 2.1,
            "mass_per_length_kg_per_m": 21000.0,
        },
    }
}


def mid_span_dafs(speeds_kmh=(40.0, 80.0, 120.0)):
    """{speed [km/h]: (DAF of the deflection, DAF of the moment)} at mid-span."""
    scenario = vbi.Scenario({"scenario": {"road": "good", "modes": 10, "seed": 3}})
    scenario.bridge = vbi.Bridge(BEAM)
    bridge = vbi.prepare(scenario)  # FE model and modes, once for every speed
    print("first frequencies [Hz]:", ", ".join(f"{f:.2f}" for f in bridge.frequencies_hz[:3]))
    station = bridge.station_names[0]
    dafs = {}
    for speed in speeds_kmh:
        result = vbi.run(scenario.copy().set("speed_kmh", speed), bridge)
        dafs[speed] = (
            result.daf(station, "deflection"),
            result.daf(station, "bending_moment"),
        )
    return station, dafs


def main():
    station, dafs = mid_span_dafs()
    print(f"{'speed [km/h]':>12} {'DAF deflection':>15} {'DAF moment':>11}   at {station}")
    for speed, (daf_u, daf_m) in dafs.items():
        print(f"{speed:>12.0f} {daf_u:>15.4f} {daf_m:>11.4f}")


if __name__ == "__main__":
    main()
