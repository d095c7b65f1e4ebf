"""docs/design-codes.md: the codes beside the default run's DAF at its RDM station (`vbi run`,
the built-in scenario: the paper's 3 × 30 m grillage, five-axle truck, 'medium' road, 80 km/h)."""

from __future__ import annotations

import json
import math
from typing import Dict

from common import Outputs, claim, f3, f4, fixed, page, read_csv, table

# The comparison's rows: (code, provision) of design_codes.csv and the case's name on the page.
ROWS = [
    ("JTG D60-2015", ["code_frequency"], "JTG D60-2015, code's f"),
    ("JTG D60-2015", ["computed_frequency"], "JTG D60-2015, vbi's f"),
    ("JTJ 021-89", ["span"], "JTJ 021-89"),
    ("AASHTO LRFD", ["strength_service", "fatigue"], "AASHTO LRFD (strength and service / fatigue)"),
    ("AASHTO Standard 2002", ["loaded_length"], "AASHTO Standard"),
    ("CSA S6", ["cl_w_axles"], "CSA S6"),
    (
        "AS 5100.2:2017",
        ["moving_traffic", "triaxle_group", "single_axle_or_wheel"],
        "AS 5100.2 (M1600 moving traffic / M1600 tri-axle group / W80 wheel, A160 axle)",
    ),
    ("EN 1991-2:2003", ["fatigue_roughness"], "EN 1991-2 (fatigue)"),
]


@page(
    "docs/design-codes.md",
    inputs=[
        # the clauses' values (the table of clauses), and 13.616/π²
        "1.5", "0.1767", "0.0157", "0.05", "0.45", "13.616", "23.651", "1.3", "1.0", "37.5",
        "33 %", "15 %", "75 %", "0.30", "0.40", "0.25", "0.50", "0.35", "3.6", "1.2", "6.6",
        "1.30", "1.4", "1.38", "0.3", "5100.2", "4.7",
    ],
)
def values(outputs: Outputs) -> Dict[str, str]:
    out = outputs.run("default_run")
    summary = json.loads((out / "summary.json").read_text())
    station = summary["rdm_station"]
    rows = [r for r in read_csv(out / "design_codes.csv") if r["station"] == station]
    moment = [r for r in rows if r["quantity"] == "bending_moment"]

    def entry(code, provision):
        return next(r for r in moment if r["code"] == code and r["provision"] == provision)

    lines = []
    for code, provisions, label in ROWS:
        entries = [entry(code, p) for p in provisions]
        value = " / ".join(f3(float(e["code_daf"])) for e in entries)
        basis = "; ".join(dict.fromkeys(e["basis"] for e in entries))
        lines.append([label, value, basis])
    daf = {
        s["quantity"]: s["daf"]
        for s in summary["stations"]
        if s["name"] == station and s["quantity"] in ("deflection", "bending_moment")
    }
    first = summary["frequencies_hz"][0]
    second = summary["frequencies_hz"][1]
    code_f1 = float(entry("JTG D60-2015", "code_frequency")["basis"].split("f1 = ")[1].split(" Hz")[0])
    jtg_code = float(entry("JTG D60-2015", "code_frequency")["code_daf"])
    jtg_vbi = float(entry("JTG D60-2015", "computed_frequency")["code_daf"])
    claim(f"{first:.3f}" in entry("JTG D60-2015", "computed_frequency")["basis"], "vbi's f is the first frequency")
    # JTG D60 §4.3.2's μ at the second frequency (what vbi read for hogging before issue 46).
    mu_second = 0.1767 * math.log(second) - 0.0157
    return {
        "rdm_station": f"`{station}`",
        "codes_table": table(["code (case)", "1 + IM of the moment", "basis (design_codes.csv)"], lines),
        "daf_u": f4(daf["deflection"]),
        "daf_m": f4(daf["bending_moment"]),
        "code_f1_above_first": f"{fixed(100 * (code_f1 / first - 1), 0)} %",
        "jtg_difference": fixed(jtg_code - jtg_vbi, 2),
        "second_frequency": fixed(second, 2),
        "mu_second": f3(mu_second),
        "first_frequency": fixed(first, 2),
        "mu_first": f3(jtg_vbi - 1),
        # where the JTG formula meets its cap of 0.45 at 14 Hz
        "jtg_cap_step": f4(0.1767 * math.log(14.0) - 0.0157 - 0.45),
    }
