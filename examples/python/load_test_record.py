"""A load-test record: DAF, RDM and frequencies of the SYNTHETIC 4 x 30 m field test.

examples/measurements/field_4x30/fast.csv is synthetic (a vbi run of the paper's 4 x 30 m
bridge and the 36 t three-axle truck, with noise and a drifting logger baseline added; see
examples/measurements/README.md): the exact answers are DAF_u 1.0882, DAF_M 1.0132, RDM 1.0741.

    python examples/python/load_test_record.py
"""

from __future__ import annotations

from pathlib import Path

import vbi

RECORD = Path(__file__).resolve().parents[1] / "measurements" / "field_4x30" / "fast.toml"


def analyse(record: Path = RECORD) -> vbi.MeasurementResult:
    """The record processed as `vbi measure` processes it."""
    return vbi.measure(record)


def main() -> None:
    result = analyse()
    summary = result.summary
    for channel in summary["channels"]:
        k1 = channel["cutoff_mode"]
        print(
            f"{channel['name']:<12} DAF {channel['daf']:.4f} "
            f"(static part by {channel['static_method']}; "
            f"{100 * k1['relative_change']:+.2f} % after the K1 filter)"
        )
    for rdm in summary["rdm"]:
        print(f"RDM at {rdm['section']}: {rdm['rdm']:.4f}")
    drift = {c["channel"]: c["drift_per_s"] for c in summary["preparation"]["corrections"]}
    print(f"logger drift removed: {drift}")
    static = result.channels["strain"].static
    print(f"static strain peak {static.max() * 1e6:.2f} µε from the crawl run")


if __name__ == "__main__":
    main()
