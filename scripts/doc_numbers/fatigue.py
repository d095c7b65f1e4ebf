"""docs/fatigue.md: the worked example on the 30 m steel-composite deck (`vbi run` of
examples/fatigue/composite-girder-30m.toml, and its variants on ISO 8608 classes A to C at three
speeds and three road seeds), and the lifetime example (`vbi lifetime` of
examples/fatigue/auxerre-3-days-composite-30m.toml)."""

from __future__ import annotations

import json
from typing import Dict

from common import Outputs, claim, f3, fixed, mean, page, read_csv, span, table

CROSSING = "examples/fatigue/composite-girder-30m.toml"
LIFETIME = "examples/fatigue/auxerre-3-days-composite-30m.toml"
CLASSES = ["A", "B", "C"]
SPEEDS = [60, 80, 100]
SEEDS = [1, 2, 3]
MPA = 1.0e6


def fatigue_entry(summary: dict, detail: str) -> dict:
    return next(f for f in summary["fatigue"] if f["detail"] == detail)


def code_factor(out, code: str, provision: str) -> float:
    rows = read_csv(out / "design_codes.csv")
    row = next(
        r
        for r in rows
        if r["station"] == "span1_mid_section"
        and r["quantity"] == "bending_moment"
        and r["code"] == code
        and r["provision"] == provision
    )
    return float(row["code_daf"])


@page(
    "docs/fatigue.md",
    inputs=[
        # EN 1993-1-9's printed constants, the codes' factors, the section and the units
        "0.737", "0.549", "0.457", "1.2", "1.4", "6.894757", "3.2", "0.25", "2.5", "6.5",
        "1.2824", "0.053894", "3.9", "365.25", "15 %",
        # clause, table and figure numbers
        "7.1", "7.2", "3.1", "2.1", "4.4",
    ],
)
def values(outputs: Outputs) -> Dict[str, str]:
    base = outputs.run("fatigue_crossing", CROSSING)
    summary = json.loads((base / "summary.json").read_text())
    flange = fatigue_entry(summary, "bottom_flange_mid_span")
    web = fatigue_entry(summary, "web_shear_quarter_span")
    claim(flange["fatigue_daf"] is None, "one truck's static range is below category 71's cut-off")
    rows = []
    straight = {}
    for road in CLASSES:
        dafs, peaks = [], []
        for speed in SPEEDS:
            for seed in SEEDS:
                out = outputs.run(
                    f"fatigue_{road}_{speed}_{seed}",
                    CROSSING,
                    [
                        ('road = "good"', f'road = "{road}"'),
                        ("speed_kmh = 80.0", f"speed_kmh = {speed}.0\nseed = {seed}"),
                    ],
                )
                run = json.loads((out / "summary.json").read_text())
                dafs.append(fatigue_entry(run, "bottom_flange_mid_span")["fatigue_daf_straight_line"])
                peaks.append(
                    next(
                        s["daf"]
                        for s in run["stations"]
                        if s["name"] == "span1_mid_section" and s["quantity"] == "bending_moment"
                    )
                )
        phi = code_factor(out, "EN 1991-2:2003", "fatigue_roughness")
        lrfd = code_factor(out, "AASHTO LRFD", "fatigue")
        straight[road] = (mean(dafs), phi)
        claim((mean(dafs) <= lrfd) == (road == "A"), "AASHTO's fatigue IM covers class A's mean only")
        claim(mean(dafs) > mean(peaks), "the fatigue DAF exceeds the peak DAF on every class")
        rows.append(
            [road, f3(mean(dafs)), span(dafs), f3(mean(peaks)), span(peaks), fixed(phi, 2), fixed(lrfd, 2)]
        )
    claim(straight["C"][0] > straight["A"][0], "the fatigue DAF grows with the roughness")
    claim(straight["A"][0] <= straight["A"][1], "φ_fat covers class A's mean fatigue DAF")
    claim(
        straight["B"][0] > straight["B"][1] and straight["C"][0] > straight["C"][1],
        "the mean fatigue DAF of classes B and C exceeds φ_fat",
    )
    life = outputs.command("fatigue_lifetime", "lifetime", LIFETIME)
    lifetime = {r["detail"]: r for r in read_csv(life / "fatigue.csv")}
    stdout = (life / "stdout.txt").read_text()
    line = next(l for l in stdout.splitlines() if l.startswith("fatigue (static"))
    events = line.split("; ")[1].split(" events")[0]
    b71 = lifetime["bottom_flange_mid_span"]
    b56 = lifetime["attachment_mid_span"]
    aashto = lifetime["attachment_mid_span_aashto"]

    superscript = str.maketrans("0123456789", "⁰¹²³⁴⁵⁶⁷⁸⁹")

    def scientific(row):
        mantissa, exponent = f"{float(row['static_damage_per_year']):.2e}".split("e")
        return f"{mantissa} × 10⁻{str(-int(exponent)).translate(superscript)}"

    return {
        "static_range": fixed(flange["static_max_range"] / MPA, 1),
        "cut_off_71": fixed(flange["cut_off"] / MPA, 1),
        "straight_daf": f3(flange["fatigue_daf_straight_line"]),
        "lrfd_fatigue": fixed(code_factor(base, "AASHTO LRFD", "fatigue"), 2),
        "en_phi_fat": fixed(code_factor(base, "EN 1991-2:2003", "fatigue_roughness"), 2),
        "web_dynamic_cycles": fixed(web["dynamic_cycles"], 1),
        "web_static_cycles": fixed(web["static_cycles"], 1),
        "classes_table": table(
            [
                "ISO 8608 class",
                "fatigue DAF, no cut-off (mean)",
                "range",
                "peak DAF of the moment (mean)",
                "range",
                "EN 1991-2 φ_fat",
                "AASHTO LRFD 1 + IM (fatigue)",
            ],
            rows,
        ),
        "lifetime_events": events,
        "lifetime_cycles": b71["static_cycles"],
        "lifetime_largest_range": fixed(float(b71["static_max_range"]) / MPA, 1),
        "lifetime_cut_off_71": fixed(float(b71["cut_off"]) / MPA, 1),
        "lifetime_damaging_71": b71["static_damaging_cycles"],
        "lifetime_damage_71": scientific(b71),
        "lifetime_cut_off_56": fixed(float(b56["cut_off"]) / MPA, 1),
        "lifetime_damaging_56": b56["static_damaging_cycles"],
        "lifetime_damage_56": scientific(b56),
        "lifetime_damage_aashto": scientific(aashto),
        "lifetime_life_aashto": fixed(float(aashto["static_fatigue_life_years"]), 0),
    }
