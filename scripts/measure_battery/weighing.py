"""Bridge weigh-in-motion over the battery (issue 52, item 6): every record with a crawl run or a
bridge model is weighed (`[measurement.weighing]`, the vehicle's axle loads given to compare),
one `vbi measure` per record, then one batch per road class and speed band, whose
`measurements.json` gives the COST 323 classes (`weighing_accuracy`: extended repeatability r2,
environment I, as `vbi measure` assumes for a load test's runs).

Per record: the gross weight's and each axle's relative error, and whether the fit's own
standard deviation (± 1.96 σ) covers it; refusals are counted. The truth is the preset's static
axle loads (`vbi vehicle show`), which the simulated crossing carries.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Dict, List

from common import read_json, run_vbi

# The target reads "at least B(10) on gross weight on class A roads at ≤ 80 km/h".
SPEED_BANDS = ((0.0, 80.0, "le80"), (80.0, 200.0, "above80"))


def weigh_toml(record_toml: str, axles: dict) -> str:
    """The record's [measurement] file with the vehicle's axles (when it had none) and
    `[measurement.weighing]`."""
    text = record_toml
    if "[measurement.vehicle]" not in text:
        vehicle = (f"[measurement.vehicle]\naxle_loads_kn = {axles['axle_loads_kn']}\n"
                   f"axle_offsets_m = {axles['axle_offsets_m']}\n")
        if axles.get("track_width_m"):
            vehicle += f"track_width_m = {axles['track_width_m']}\n"
        at = text.index("[[measurement.channels]]")
        text = text[:at] + vehicle + "\n" + text[at:]
    return text + "\n[measurement.weighing]\n"


def weigh_case(vbi: Path, out: Path, entry: dict) -> dict:
    case, record = entry["case"], entry["record"]
    case_dir = out / record["directory"]
    (case_dir / "weigh.toml").write_text(weigh_toml((case_dir / "record.toml").read_text(), record["axles"]))
    done = run_vbi(vbi, ["measure", "weigh.toml", "--out", "weigh"], cwd=case_dir, log=case_dir / "weigh.log")
    result = {"case": case["name"], "road_class": case["road_class"], "speed_kmh": case["speed_kmh"],
              "noise_fraction": case["noise_fraction"], "information": case["information"],
              "vehicle": case["vehicle"], "returncode": done.returncode}
    if done.returncode != 0:
        result["refusal"] = (done.stderr.strip().splitlines() or [""])[-1][:300]
        return result
    w = read_json(case_dir / "weigh" / "measure.json")["weighing"]
    given = w["against_given"]
    result.update({
        "file": str(case_dir / "weigh.toml"),
        "entry_time_fitted": w["entry_time_fitted"],
        "line_sources": [c["line_source"] for c in w["channels"]],
        "gross_error": given["gross_weight_error"],
        "gross_covered": abs(w["gross_weight_n"] - given["gross_weight_n"]) <= 1.96 * w["gross_weight_fit_std_n"],
        "axle_errors": given["axle_errors"],
        "axles_covered": [abs(a - p) <= 1.96 * s for a, p, s in
                          zip(w["axle_loads_n"], given["axle_loads_n"], w["axle_load_fit_std_n"])],
    })
    return result


def batch_accuracy(vbi: Path, out: Path, name: str, weighed: List[dict]) -> dict:
    """`vbi measure` over the group's weigh.toml files: its `weighing_accuracy`."""
    if len(weighed) < 2:
        return {"group": name, "weighings": len(weighed), "accuracy": None}
    batch_dir = out / "weighing" / name
    done = run_vbi(vbi, ["measure", *[w["file"] for w in weighed], "--out", str(batch_dir), "--format", "json"],
                   cwd=out, log=out / "weighing" / f"{name}.log")
    if done.returncode != 0:
        return {"group": name, "weighings": len(weighed), "accuracy": None, "refusal": done.stderr[-300:]}
    return {"group": name, "weighings": len(weighed),
            "accuracy": read_json(batch_dir / "measurements.json")["weighing_accuracy"]}


def statistics(rows: List[dict]) -> Dict[str, float]:
    gross = [r["gross_error"] for r in rows]
    axles = [e for r in rows for e in r["axle_errors"]]
    rms = lambda xs: (sum(x * x for x in xs) / len(xs)) ** 0.5 if xs else float("nan")  # noqa: E731
    return {
        "n": len(rows),
        "gross_mean": sum(gross) / len(gross) if gross else float("nan"),
        "gross_rms": rms(gross),
        "gross_largest": max((abs(x) for x in gross), default=float("nan")),
        "gross_within_1_percent": sum(abs(x) <= 0.01 for x in gross),
        "gross_covered": sum(r["gross_covered"] for r in rows),
        "axle_rms": rms(axles),
        "axles_within_3_percent": sum(abs(x) <= 0.03 for x in axles),
        "axles": len(axles),
        "axles_covered": sum(c for r in rows for c in r["axles_covered"]),
    }


def run(vbi: Path, out: Path, results: List[dict]) -> dict:
    """Weighs every record with a crawl run or a model; the groups' classes."""
    (out / "weighing").mkdir(exist_ok=True)
    cases = [weigh_case(vbi, out, e) for e in results if e["case"]["information"] != "record_only"]
    weighed = [c for c in cases if c["returncode"] == 0]
    groups = [("all", weighed), ("noise_free", [c for c in weighed if c["noise_fraction"] == 0.0])]
    for road in sorted({c["road_class"] for c in weighed}):
        for low, high, label in SPEED_BANDS:  # noqa: B007
            members = [c for c in weighed if c["road_class"] == road and low < c["speed_kmh"] <= high]
            groups.append((f"class_{road}_{label}_kmh", members))
    table = []
    for name, members in groups:
        entry = batch_accuracy(vbi, out, name, members)
        entry["statistics"] = statistics(members) if members else None
        table.append(entry)
    return {"cases": cases, "refused": [c for c in cases if c["returncode"] != 0], "groups": table}


def markdown(weighing: dict) -> str:
    """The section of battery.md."""
    lines = [
        "## Bridge weigh-in-motion (Moses' least squares; axle loads given to compare)",
        "",
        f"{len(weighing['cases'])} records with a crawl run or a bridge model weighed, "
        f"{len(weighing['refused'])} refused. Errors are weighed / static − 1; \"covered\": within ± 1.96 × the "
        "fit's own standard deviation (which leaves out the vehicle's dynamic axle forces). Classes: COST 323, "
        "extended repeatability r2, environment I (`vbi measure` batch over the group).",
        "",
        "| group | n | gross: mean | RMS | largest | within 1 % | fit σ covers | axles: RMS | within 3 % | fit σ covers "
        "| gross weight | group of axles | single axle | axle of a group | class |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for g in weighing["groups"]:
        s = g["statistics"]
        if not s:
            continue
        classes = {c["criterion"]: c["class"] for c in (g["accuracy"] or {}).get("criteria", [])}
        name = lambda k: classes.get(k, "–")  # noqa: E731
        system = (g["accuracy"] or {}).get("class") or "–"
        lines.append(
            f"| {g['group']} | {s['n']} | {100 * s['gross_mean']:+.2f} % | {100 * s['gross_rms']:.2f} % | "
            f"{100 * s['gross_largest']:.1f} % | {s['gross_within_1_percent']}/{s['n']} | {s['gross_covered']}/{s['n']} | "
            f"{100 * s['axle_rms']:.1f} % | {s['axles_within_3_percent']}/{s['axles']} | {s['axles_covered']}/{s['axles']} | "
            f"{name('gross_weight')} | {name('group_of_axles')} | {name('single_axle')} | {name('axle_of_group')} | {system} |")
    if weighing["refused"]:
        lines += ["", "Refused: " + "; ".join(f"{c['case']}: {c.get('refusal', '')[:140]}" for c in weighing["refused"])]
    return "\n".join(lines) + "\n"


def write(out: Path, weighing: dict) -> str:
    (out / "weighing.json").write_text(json.dumps(weighing, indent=1))
    text = markdown(weighing)
    with open(out / "battery.md", "a") as handle:
        handle.write("\n" + text)
    return text
