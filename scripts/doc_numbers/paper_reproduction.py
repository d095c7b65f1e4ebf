"""docs/paper-reproduction.md: the paper's full study (three readings), the quick study, and one
crossing of the paper's 3 × 30 m bridge with 50 and 100 modes."""

from __future__ import annotations

import json
from collections import defaultdict
from typing import Dict, List

from common import (
    Outputs,
    claim,
    f3,
    f4,
    fixed,
    fractile,
    mean,
    page,
    percent,
    read_csv,
    signed_percent,
    span,
    table,
)

PAPER = "examples/studies/paper.toml"
LITERAL = 'psd_reference = "iso-8608"'
READINGS = {
    "paper": [],
    "paper_dodds_robson": [(LITERAL, 'psd_reference = "dodds-robson"')],
    "paper_identical": [(LITERAL, LITERAL + '\ntracks = "identical"')],
}
CLASSES = ["smooth", "good", "medium", "poor"]
SPEEDS = [40, 80, 120]
LENGTHS = [20, 30, 40]
COUNTS = [2, 3, 4]


class Study:
    """A study's tables, with the selections the page's statistics need."""

    def __init__(self, outputs: Outputs, name: str, study_file: str = PAPER, replace=()):
        out = outputs.study(name, study_file, replace)
        self.cases = read_csv(out / "cases.csv")
        self.cutoff = {row["group"]: row for row in read_csv(out / "cutoff_modes.csv")}
        self.participation = read_csv(out / "participation.csv")
        for row in self.cases:
            for key in ("span_count", "span_length_m", "speed_kmh"):
                if key in row:
                    row[key] = int(float(row[key]))

    def select(self, **fields) -> List[dict]:
        return [row for row in self.cases if all(row[k] == v for k, v in fields.items())]

    def combinations(self) -> Dict[tuple, List[dict]]:
        """The cases of each bridge, road class and speed (its samples)."""
        groups: Dict[tuple, List[dict]] = defaultdict(list)
        for row in self.cases:
            key = (row["span_count"], row["span_length_m"], row["road"], row["speed_kmh"])
            groups[key].append(row)
        return groups

    def mean_of(self, column: str, **fields) -> float:
        return mean(float(row[column]) for row in self.select(**fields))

    def combination_means(self, column: str) -> List[float]:
        return [mean(float(r[column]) for r in rows) for rows in self.combinations().values()]

    def spread_over_classes(self, column: str, span_count: int) -> float:
        """Largest minus smallest mean over the road classes, n × 20 m, 80 km/h (Figs. 11–12)."""
        means = [
            self.mean_of(column, span_count=span_count, span_length_m=20, speed_kmh=80, road=c)
            for c in CLASSES
        ]
        return max(means) - min(means)

    def range_over(self, column: str, span_count: int, axis: str) -> str:
        """The range of the means over road classes (80 km/h) or speeds ('medium'), n × 20 m."""
        if axis == "road":
            means = [
                self.mean_of(column, span_count=span_count, span_length_m=20, speed_kmh=80, road=c)
                for c in CLASSES
            ]
        else:
            means = [
                self.mean_of(column, span_count=span_count, span_length_m=20, road="medium", speed_kmh=s)
                for s in SPEEDS
            ]
        return span(means)

    def contact_losses(self, **fields) -> int:
        return sum(1 for row in self.select(**fields) if int(row["contact_losses"]) > 0)


def below_one(values: List[float]) -> int:
    return sum(1 for v in values if v < 1.0)


def rdm_table(study: Study) -> str:
    plain = study.combination_means("rdm_paper")
    converged = study.combination_means("rdm")
    count = len(plain)

    def note(values, total):
        n = below_one(values)
        return "(none below 1)" if n == 0 else f"({n} of {total} below 1)"

    singles_plain = [float(r["rdm_paper"]) for r in study.cases]
    singles = [float(r["rdm"]) for r in study.cases]
    road = lambda column: ", ".join(study.range_over(column, n, "road") for n in COUNTS)  # noqa: E731
    speed = lambda column: ", ".join(study.range_over(column, n, "speed") for n in COUNTS)  # noqa: E731
    lengths = lambda column: span(  # noqa: E731
        [study.mean_of(column, span_count=n, span_length_m=l, road="medium", speed_kmh=80) for n in COUNTS for l in LENGTHS],
        dash=" – ",
    )
    by_length = lambda column: " / ".join(f3(study.mean_of(column, span_length_m=l)) for l in LENGTHS)  # noqa: E731
    rows = [
        [
            f"RDM, mean over the 10 samples of each of the {count} combinations",
            f"**{span(plain, dash=' – ')}** {note(plain, count)}",
            f"{span(converged, dash=' – ')} {note(converged, count)}",
            "1.00 – 1.12",
        ],
        [
            "RDM, single crossings",
            f"{span(singles_plain, dash=' – ')} {note(singles_plain, len(singles))}",
            f"{span(singles, dash=' – ')} {note(singles, len(singles))}",
            "–",
        ],
        ["RDM over road classes, 2/3/4 × 20 m, 80 km/h (Fig. 13)", road("rdm_paper"), road("rdm"), "1.02–1.06, 1.00–1.06, 1.00–1.05"],
        ["RDM over speeds, 2/3/4 × 20 m, 'medium' (Fig. 16)", speed("rdm_paper"), speed("rdm"), "1.07–1.09, 1.03–1.10, 1.05–1.12"],
        ["RDM over span lengths, 'medium', 80 km/h (Fig. 17)", lengths("rdm_paper"), lengths("rdm"), "1.03 – 1.10"],
        ["RDM mean over all crossings", f3(mean(singles_plain)), f3(mean(singles)), "–"],
        ["RDM mean for 20 / 30 / 40 m spans", by_length("rdm_paper"), by_length("rdm"), "increases with span"],
    ]
    return table(["", "the paper's series (plain sums)", "converged (static-corrected)", "paper"], rows)


def trend_cells(study: Study, suffix: str) -> List[str]:
    """The DAF trends' cells of one series (suffix "_paper" or "")."""
    u, m = f"daf_u{suffix}", f"daf_m{suffix}"

    def pair(selections):
        text_u = " / ".join(f3(study.mean_of(u, **s)) for s in selections)
        text_m = " / ".join(f3(study.mean_of(m, **s)) for s in selections)
        return f"DAF_u {text_u}; DAF_M {text_m}"

    spread_u = " / ".join(f3(study.spread_over_classes(u, n)) for n in COUNTS)
    spread_m = " / ".join(f3(study.spread_over_classes(m, n)) for n in COUNTS)
    return [
        pair([{"road": c} for c in CLASSES]),
        f"DAF_u {spread_u}; DAF_M {spread_m}",
        pair([{"speed_kmh": s} for s in SPEEDS]),
        pair([{"span_length_m": l, "road": "medium", "speed_kmh": 80} for l in LENGTHS]),
        pair([{"span_count": n} for n in COUNTS]),
    ]


def trends_table(study: Study) -> str:
    labels = [
        "road class smooth / good / medium / poor",
        "spread over the four classes, 2/3/4 × 20 m, 80 km/h (Figs. 11–12)",
        "speed 40 / 80 / 120 km/h",
        "span length 20 / 30 / 40 m ('medium', 80 km/h)",
        "span number 2 / 3 / 4",
    ]
    paper = [
        "DAFs increase with roughness",
        "DAF_u 0.32, DAF_M 0.31 (largest)",
        "no monotone trend with speed",
        "DAF_u, DAF_M, RDM increase with span",
        "no clear relation",
    ]
    rows = zip(labels, trend_cells(study, "_paper"), trend_cells(study, ""), paper)
    return table(["", "the paper's series (means over the other factors)", "converged", "paper"], [list(r) for r in rows])


def trend_differences(study: Study) -> Dict[str, str]:
    """How far the converged means lie from the plain ones, over the trend table's means."""
    selections = (
        [{"road": c} for c in CLASSES]
        + [{"speed_kmh": s} for s in SPEEDS]
        + [{"span_length_m": l, "road": "medium", "speed_kmh": 80} for l in LENGTHS]
        + [{"span_count": n} for n in COUNTS]
    )
    du = [abs(study.mean_of("daf_u", **s) - study.mean_of("daf_u_paper", **s)) for s in selections]
    dm = [study.mean_of("daf_m", **s) - study.mean_of("daf_m_paper", **s) for s in selections]
    by_class = {c: study.mean_of("daf_m", road=c) - study.mean_of("daf_m_paper", road=c) for c in CLASSES}
    by_length = {
        l: study.mean_of("daf_m", span_length_m=l, road="medium", speed_kmh=80)
        - study.mean_of("daf_m_paper", span_length_m=l, road="medium", speed_kmh=80)
        for l in LENGTHS
    }
    claim(max(by_class, key=by_class.get) == "smooth", "the converged DAF_M gains most on the smooth road")
    claim(max(by_length, key=by_length.get) == 20, "the converged DAF_M gains most on the 20 m spans")
    claim(min(dm) > 0, "the converged DAF_M exceeds the plain one on every mean")
    return {
        "trend_u_difference": fixed(max(du), 3),
        "trend_m_difference_low": fixed(min(dm), 3),
        "trend_m_difference_high": fixed(max(dm), 3),
    }


def readings_table(readings: Dict[str, Study]) -> str:
    order = ["paper", "paper_dodds_robson", "paper_identical"]

    def cells(function):
        return [function(readings[name]) for name in order]

    spreads = lambda column: lambda s: " / ".join(f3(s.spread_over_classes(column, n)) for n in COUNTS)  # noqa: E731
    rows = [
        ["spread of DAF_u over the four classes, 2/3/4 × 20 m, 80 km/h", *cells(spreads("daf_u_paper")), "up to 0.32"],
        ["spread of DAF_M, same", *cells(spreads("daf_m_paper")), "up to 0.31"],
        [
            "DAF_u smooth / good / medium / poor",
            *cells(lambda s: " / ".join(f3(s.mean_of("daf_u_paper", road=c)) for c in CLASSES)),
            "increase",
        ],
        [
            "DAF_u, 20 / 30 / 40 m ('medium', 80 km/h)",
            *cells(
                lambda s: " / ".join(
                    f3(s.mean_of("daf_u_paper", span_length_m=l, road="medium", speed_kmh=80)) for l in LENGTHS
                )
            ),
            "increase",
        ],
        ["RDM, combination means", *cells(lambda s: span(s.combination_means("rdm_paper"), dash=" – ")), "1.00 – 1.12"],
        [
            "RDM over road classes, 2/3/4 × 20 m (Fig. 13)",
            *cells(lambda s: ", ".join(s.range_over("rdm_paper", n, "road") for n in COUNTS)),
            "1.02–1.06, 1.00–1.06, 1.00–1.05",
        ],
        ["crossings with a contact loss", *cells(lambda s: str(s.contact_losses())), "–"],
    ]
    header = [
        "the paper's series (plain sums), means",
        "literal: n₀ = 0.1, coherent tracks (`paper.toml`)",
        "Dodds & Robson: n₀ = 1/(2π), coherent",
        "literal, identical tracks",
        "paper",
    ]
    return table(header, rows)


def convergence_table(study: Study) -> str:
    def three(column):
        values = [int(row[column]) for row in study.cases]
        return f"{fractile(values, 0.5)}, {fractile(values, 0.9)}, {max(values)}"

    def ratio(quantity):
        # DAF(20)/DAF(10) − 1 of the paper's series, per crossing, from daf_by_modes.csv.
        values = study.ratio_20_10[quantity]
        return f"mean {signed_percent(mean(values))} ({signed_percent(min(values))} … {signed_percent(max(values))})"

    rows = [
        ["CM_u (the paper's series)", three("cm_u_paper"), "max 10"],
        ["CM_M (the paper's series)", three("cm_m_paper"), "max 40"],
        ["DAF(20)/DAF(10) − 1, deflection (the paper's series)", ratio("u"), "+0.0 % … +0.6 %"],
        ["DAF(20)/DAF(10) − 1, moment (the paper's series)", ratio("m"), "+1.1 % … +6.7 %"],
        ["CM_u, converged series", three("cm_u"), "–"],
        ["CM_M, converged series", three("cm_m"), "–"],
    ]
    count = len(study.cases)
    return table(["", f"ours: median, 90th percentile, max over {count} crossings", "paper"], rows)


def ratios_20_10(outputs: Outputs, name: str) -> Dict[str, List[float]]:
    rows = read_csv(outputs.done[name] / "daf_by_modes.csv")
    at: Dict[str, Dict[int, dict]] = defaultdict(dict)
    for row in rows:
        at[row["case"]][int(row["modes"])] = row
    out: Dict[str, List[float]] = {"u": [], "m": []}
    for by_modes in at.values():
        for quantity in ("u", "m"):
            column = f"daf_{quantity}_paper"
            out[quantity].append(float(by_modes[20][column]) / float(by_modes[10][column]) - 1)
    return out


def participation_table(study: Study) -> str:
    """Mean deck participation of the first two and three modes, per span count (Eq. 30)."""
    by_case: Dict[str, List[dict]] = defaultdict(list)
    for row in study.participation:
        by_case[row["case"]].append(row)
    count_of = {row["case"]: row["span_count"] for row in study.cases}
    sums: Dict[tuple, List[float]] = defaultdict(list)
    for case, modes in by_case.items():
        modes.sort(key=lambda r: int(r["mode"]))
        for first in (2, 3):
            for quantity in ("u", "m"):
                share = sum(float(r[f"mps_{quantity}"]) for r in modes[:first])
                sums[(first, quantity, count_of[case])].append(share)
    per_count = len(study.cases) // len(COUNTS)
    rows = []
    for first, word in ((2, "two"), (3, "three")):
        for quantity, label in (("u", "deflection"), ("m", "moment")):
            rows.append([f"first {word} modes, {label}", *(f3(mean(sums[(first, quantity, n)])) for n in COUNTS)])
    return table([f"mean over the {per_count} crossings of each span count", "2 spans", "3 spans", "4 spans"], rows)


def cutoff_table(study: Study, bending: bool) -> str:
    paper = {"k1_u": [3, 3, 4], "k1_m": [7, 8, 9], "k2_u": [6, 7, 8], "k2_m": [15, 20, 25]}
    suffix = "_bending" if bending else ""

    def cell(k, n):
        row = study.cutoff[f"{n} spans"]
        if bending:
            values = [int(r[f"{k}{suffix}"]) for r in study.select(span_count=n)]
            low, high = min(values), max(values)
        else:
            bounds = [int(x) for x in row[f"{k}_range"].split("-")]
            low, high = bounds[0], bounds[-1]
        inside = f"{low}" if low == high else f"{low}–{high}"
        return f"{row[k + suffix]} ({inside})"

    rows = []
    for k in ("k1", "k2"):
        label = f"{k.upper()} ours" + (", bending modes" if bending else "")
        rows.append([label, *(cell(f"{k}_u", n) for n in COUNTS), *(cell(f"{k}_m", n) for n in COUNTS)])
        rows.append([f"{k.upper()} paper", *(str(v) for v in paper[f"{k}_u"]), *(str(v) for v in paper[f"{k}_m"])])
    header = ["", "deflection 2-span", "3-span", "4-span", "moment 2-span", "3-span", "4-span"]
    return table(header, rows)


def modes_kept(outputs: Outputs) -> Dict[str, str]:
    """One crossing of the paper's 3 × 30 m bridge with 50 and with 100 modes."""
    scenario = "examples/scenarios/paper-3x30-medium-80kmh.toml"
    runs = {
        50: outputs.run("paper_3x30_50_modes", scenario),
        100: outputs.run("paper_3x30_100_modes", scenario, [("modes = 50", "modes = 100")]),
    }
    summaries = {n: json.loads((out / "summary.json").read_text()) for n, out in runs.items()}

    def station(summary, quantity):
        name = summary["rdm_station"]
        return next(s for s in summary["stations"] if s["name"] == name and s["quantity"] == quantity)

    kept = {n: len(s["modes_kept"]["k1_u"]) for n, s in summaries.items()}
    cells = defaultdict(list)
    for n in (50, 100):
        s = summaries[n]
        u, m = station(s, "deflection"), station(s, "bending_moment")
        cells["converged"].append(f"{f4(u['daf'])} / {f4(m['daf'])}")
        cells["change"].append(f"{f4(u['daf_change'])} / {f4(m['daf_change'])}")
        cells["paper"].append(f"{f4(u['daf_paper'])} / {f4(m['daf_paper'])}")
        cells["rdm"].append(f"{f4(s['rdm'])} / {f4(s['rdm_paper'])}")
        cells["cm"].append(f"{u['convergence_mode_paper']} / {m['convergence_mode_paper']}")
        deck = s["deck_participation"]
        cells["k"].append(f"{deck['moment_k1']} / {deck['moment_k2']}")
    rows = [
        ["converged DAF_u / DAF_M (headline)", *cells["converged"]],
        ["its convergence indicator `change` (u / M)", *cells["change"]],
        ["the paper's DAF_u / DAF_M (plain sums)", *cells["paper"]],
        ["converged RDM / the paper's RDM", *cells["rdm"]],
        ["the paper's CM_u / CM_M", *cells["cm"]],
        ["deck-wide K1_M / K2_M", *cells["k"]],
    ]
    long = summaries[100]["modes_kept"]
    tenth = range(9, min(70, len(long["cm_m_paper"])), 10)
    m50, m100 = station(summaries[50], "bending_moment"), station(summaries[100], "bending_moment")
    return {
        "modes_kept_50": str(kept[50]),
        "modes_kept_100": str(kept[100]),
        "modes_kept_table": table(["quantity", f"{kept[50]} modes", f"{kept[100]} modes"], rows),
        "modes_kept_cm_m": ", ".join(str(long["cm_m_paper"][i]) for i in tenth),
        "modes_kept_k2_m": ", ".join(str(long["k2_m"][i]) for i in tenth),
        # from n = 40 on, where the deflection's indicators have settled
        "modes_kept_cm_u": span(long["cm_u_paper"][39:], 0),
        "modes_kept_k2_u": span(long["k2_u"][39:], 0),
        "modes_kept_move_converged": f4(abs(m100["daf"] - m50["daf"])),
        "modes_kept_move_paper": f3(abs(m100["daf_paper"] - m50["daf_paper"])),
    }


def quick_study(outputs: Outputs) -> Dict[str, str]:
    study = Study(outputs, "quick", "examples/studies/quick.toml")
    groups: Dict[str, List[dict]] = defaultdict(list)
    for row in study.cases:
        groups[row["bridge"]].append(row)
    column = lambda name: [float(r[name]) for r in study.cases]  # noqa: E731
    kept = [int(r["modes"]) for r in study.cases]
    return {
        "quick_modes_kept": span(kept, 0),
        "quick_rdm_paper": span(column("rdm_paper")),
        "quick_rdm_paper_means": " and ".join(
            f3(mean(float(r["rdm_paper"]) for r in groups[b])) for b in sorted(groups)
        ),
        "quick_daf_u_paper": span(column("daf_u_paper")),
        "quick_daf_m_paper": span(column("daf_m_paper")),
        "quick_rdm": span(column("rdm")),
        "quick_daf_u": span(column("daf_u")),
        "quick_daf_m": span(column("daf_m")),
    }


@page(
    "docs/paper-reproduction.md",
    inputs=[
        # the paper's girder heights, deck width, n₀ and statements; the road reading's factors
        "1.2", "1.8", "2.0", "8.5", "0.1", "1.00", "1.12", "0.32", "0.31", "2.533", "1.59", "0.2",
        "95 %", "99 %", "1 %", "90 %", "69.5 %", "80 %",
    ],
)
def values(outputs: Outputs) -> Dict[str, str]:
    readings = {name: Study(outputs, name, PAPER, replace) for name, replace in READINGS.items()}
    study = readings["paper"]
    study.ratio_20_10 = ratios_20_10(outputs, "paper")
    cases = study.cases
    total = len(cases)
    combinations = study.combinations()
    plain_means = study.combination_means("rdm_paper")
    converged_means = study.combination_means("rdm")
    lengths_f1 = {}
    for l in LENGTHS:
        f1 = {fixed(float(r["f1_hz"]), 2) for r in study.select(span_length_m=l)}
        claim(len(f1) == 1, f"the first frequency of the {l} m spans is the same for 2, 3 and 4 spans")
        lengths_f1[l] = f1.pop()
    smooth = study.select(road="smooth")
    cm_m = [int(r["cm_m"]) for r in cases]
    claim(fractile(cm_m, 0.9) <= 12, "the converged moment settles within a dozen modes in 90 % of the crossings")
    dr = readings["paper_dodds_robson"]
    dr_spreads = [dr.spread_over_classes(c, n) for c in ("daf_u_paper", "daf_m_paper") for n in COUNTS]
    literal_spreads = [study.spread_over_classes(c, n) for c in ("daf_u_paper", "daf_m_paper") for n in COUNTS]
    rdm_ranges = {
        name: (min(s.combination_means("rdm_paper")), max(s.combination_means("rdm_paper")))
        for name, s in readings.items()
    }
    rdm_move = max(abs(a - b) for a, b in zip(rdm_ranges["paper"], rdm_ranges["paper_dodds_robson"]))
    vertical_bending = {}
    for n, l in zip(COUNTS, LENGTHS):
        case = study.select(span_count=n, span_length_m=l)[0]["case"]
        vertical_bending[n] = sum(
            1 for r in study.participation if r["case"] == case and r["kind"] == "vertical_bending"
        )
    # Participation of the modes from the fifth on, deck-wide deflection, mean per span count.
    tail: Dict[int, List[float]] = defaultdict(list)
    count_of = {r["case"]: r["span_count"] for r in cases}
    by_case: Dict[str, float] = defaultdict(float)
    for r in study.participation:
        if int(r["mode"]) >= 5:
            by_case[r["case"]] += float(r["mps_u"])
    for case, share in by_case.items():
        tail[count_of[case]].append(share)
    tail_means = [mean(tail[n]) for n in COUNTS]
    paper_k = {"k1_u": [3, 3, 4], "k1_m": [7, 8, 9], "k2_u": [6, 7, 8]}
    bending_gap = {
        k: max(abs(int(study.cutoff[f"{n} spans"][f"{k}_bending"]) - p) for n, p in zip(COUNTS, paper_k[k]))
        for k in paper_k
    }
    contact = study.contact_losses()
    by_length = {l: study.mean_of("rdm_paper", span_length_m=l) for l in LENGTHS}
    claim(max(by_length, key=by_length.get) == 20, "the paper's RDM is largest for the 20 m spans")
    claim(max(plain_means) > 1.12, "the largest mean RDM of the paper's series lies above the paper's 1.12")
    rdm_plain = mean(float(r["rdm_paper"]) for r in cases)
    rdm_converged = mean(float(r["rdm"]) for r in cases)
    claim(
        0.3 < (rdm_converged - 1) / (rdm_plain - 1) < 0.7,
        "about half of the plain RDM's excess over 1 is the truncation of the modal moment",
    )
    claim(
        0.4 < max(literal_spreads) / 0.32 < 0.65,
        "the spread over the road classes is about half the paper's",
    )
    values = {
        "first_frequencies": ", ".join(lengths_f1[l] for l in LENGTHS),
        "modes_kept_range": span([int(r["modes"]) for r in cases], 0),
        "cases": str(total),
        "failed": str(sum(1 for r in cases if r["error"])),
        "contact_losses": str(contact),
        "contact_losses_poor": str(study.contact_losses(road="poor")),
        "contact_losses_poor_120": str(study.contact_losses(road="poor", speed_kmh=120)),
        "contact_losses_identical": str(readings["paper_identical"].contact_losses()),
        "rdm_table": rdm_table(study),
        "rdm_plain_above_one": str(sum(1 for v in plain_means if v > 1)),
        "combinations": str(len(combinations)),
        "rdm_plain_excess_low": percent(min(plain_means) - 1),
        "rdm_plain_excess_high": percent(max(plain_means) - 1),
        "rdm_plain_single_reversed": str(below_one([float(r["rdm_paper"]) for r in cases])),
        "rdm_converged_mean": f3(mean(float(r["rdm"]) for r in cases)),
        "rdm_converged_above_one": str(sum(1 for v in converged_means if v > 1)),
        "trends_table": trends_table(study),
        **trend_differences(study),
        "readings_table": readings_table(readings),
        "dodds_robson_spreads": span(dr_spreads, 2),
        "literal_spreads": span(literal_spreads, 2),
        "readings_rdm_move": fixed(rdm_move, 2),
        "convergence_table": convergence_table(study),
        "cm_m_paper_max": str(max(int(r["cm_m_paper"]) for r in cases)),
        "smooth_cases": str(len(smooth)),
        "smooth_daf_m_paper_below_one": str(sum(1 for r in smooth if float(r["daf_m_paper"]) < 1)),
        "daf_m_paper_below_one": str(sum(1 for r in cases if float(r["daf_m_paper"]) < 1)),
        "smooth_daf_m_below_one": str(sum(1 for r in smooth if float(r["daf_m"]) < 1)),
        "daf_m_below_one": str(sum(1 for r in cases if float(r["daf_m"]) < 1)),
        "cm_m_median": str(fractile(cm_m, 0.5)),
        "cm_m_p90": str(fractile(cm_m, 0.9)),
        "participation_table": participation_table(study),
        "cases_per_span_count": str(total // len(COUNTS)),
        "cutoff_table": cutoff_table(study, bending=False),
        "tail_participation": f"{span([100 * t for t in tail_means], 0)} %",
        "station_k1_u_median": str(fractile([int(r["station_k1_u"]) for r in cases], 0.5)),
        "station_k1_m_median": str(fractile([int(r["station_k1_m"]) for r in cases], 0.5)),
        "cutoff_bending_table": cutoff_table(study, bending=True),
        "bending_gap_k1_u": str(bending_gap["k1_u"]),
        "bending_gap_k1_m": str(bending_gap["k1_m"]),
        "bending_gap_k2_u": str(bending_gap["k2_u"]),
        "vertical_bending_modes": ", ".join(str(vertical_bending[n]) for n in COUNTS),
        **modes_kept(outputs),
        **quick_study(outputs),
    }
    return values
