"""Measuring each record with `vbi measure` at its defaults and scoring the results against the
truth (issue 52, item 1).

Per DAF channel: the static method chosen (`channels[].static_method`), the DAF and its error
(DAF − exact), the stated 95 % interval's half-width (`channels[].uncertainty.expanded_95`, when
vbi states one), whether it covers the exact value, whether the error exceeds twice the
half-width, and whether vbi warned:

- on screen: a line of the `warnings` block that names the channel ("the DAF of NAME …"), for
  a low-pass channel the `static part:` line when it says "distorted", for a crawl-run channel
  the warning on the crawl run's baseline;
- in the report's key results (the `key-results` box of report.html): the channel's row, or a row
  of its own, with such a word;
- in measure.json (information only: the issue asks for the screen and the key results): its
  `warnings` naming the channel, the chosen method marked not `valid`, or a low-pass whose
  run-wide or channel check says not separated.

Every other static method that measure.json lists for the channel (`static_methods`) is scored
too (its DAF and error), so that each method's bias shows even where the default did not choose
it. f1: the first identified frequency (`identified_frequencies[0]`; without an accelerometer
the f1 of the static separation, when vbi took one from the bridge model) against the model's
first vertical-bending frequency: within 1 %, or flagged on screen or in the key results.
"""

from __future__ import annotations

import html
import re
from pathlib import Path
from typing import Dict, List, Optional

from common import read_json, run_vbi

WARNING_WORDS = re.compile(
    r"\bwarn|distort|not separated|unreliable|caution|not possible|inaccurate|cannot|doubt|suspect|"
    r"failed|refus|outside|implausib|too short|not resolved",
    re.IGNORECASE,
)
FREQUENCY_WORDS = re.compile(r"forced|first (bridge )?frequenc|f₁|\bf1\b|identified|mode \d|spectrum", re.IGNORECASE)
# Ordinary lines of `vbi measure`'s table (what is not one of them is listed as an extra line).
ORDINARY_LINES = re.compile(
    r"^(\d+ samples at|static part:|channel\s+kind|\S+\s+(deflection|strain|bending_moment) \[|RDM at|"
    r"identified (modes|frequencies)|  mode \d+:|DAF of .*: [\d.]+ ± |vehicle speed|wrote |model updating|"
    r"calibration|  \S+: factor|  RMS frequency|  elastic_modulus|  flexural_rigidity)"
)
COVERAGE_TOLERANCE = 0.002  # a second, looser coverage: |error| within the half-width + this


def measure(vbi: Path, case_dir: Path) -> dict:
    """`vbi measure record.toml --out measure` in the case's folder: exit code, printout, and
    measure.json and the report's key results when it succeeded."""
    done = run_vbi(vbi, ["measure", "record.toml", "--out", "measure"], cwd=case_dir, log=case_dir / "measure.log")
    result = {"returncode": done.returncode, "seconds": done.seconds, "stdout": done.stdout, "stderr": done.stderr}
    if done.returncode == 0:
        result["json"] = read_json(case_dir / "measure" / "measure.json")
        result["key_results"] = key_results((case_dir / "measure" / "report.html").read_text())
    return result


def key_results(page: str) -> Dict[str, str]:
    """The rows of report.html's key-results box: header -> text."""
    match = re.search(r'<section id="key-results">(.*?)</section>', page, re.DOTALL)
    if not match:
        return {}
    rows = re.findall(r"<tr><th>(.*?)</th><td>(.*?)</td></tr>", match.group(1), re.DOTALL)
    strip = lambda text: html.unescape(re.sub(r"<[^>]+>", "", text)).strip()  # noqa: E731
    return {strip(head): strip(value) for head, value in rows}


def screen_lines(result: dict) -> List[str]:
    return [line for line in (result["stdout"] + "\n" + result["stderr"]).splitlines() if line.strip()]


def warnings_on_screen(result: dict) -> List[str]:
    """Printed lines that warn: each item of `vbi measure`'s `warnings (N):` block, and any line
    with a word of WARNING_WORDS."""
    lines, in_block = [], False
    for line in screen_lines(result):
        if re.match(r"^warnings \(\d+\):", line):
            in_block = True
            continue
        if in_block and line.startswith("  - "):
            lines.append(line.strip()[2:])
            continue
        in_block = False
        if WARNING_WORDS.search(line):
            lines.append(line.strip())
    return lines


def extra_lines(result: dict) -> List[str]:
    """Printed lines that are none of the ordinary table's (a new message shows here)."""
    return [line for line in screen_lines(result) if not ORDINARY_LINES.match(line)]


def key_result_warning(keys: Dict[str, str], row: str) -> Optional[str]:
    """The key-results text that warns about `row` (its own row, or a row of warnings)."""
    for head, text in keys.items():
        if head == row and WARNING_WORDS.search(text):
            return f"{head}: {text}"
        if WARNING_WORDS.search(head) and (row.split(" of ")[-1] in text or "all" in text.lower()):
            return f"{head}: {text}"
    return None


def json_flags(summary: dict, channel: dict) -> List[str]:
    """What measure.json says against the chosen static method of a channel."""
    flags = [
        f"warnings: {w['kind']}" for w in summary.get("warnings", []) if w.get("channel") == channel["name"]
    ]
    chosen = next((m for m in channel.get("static_methods", []) if m.get("chosen")), None)
    if chosen is not None and not chosen.get("valid", True):
        flags.append(f"static_methods: {chosen['method']} not valid")
    if channel["static_method"] == "low_pass":
        separation = summary.get("static_separation") or {}
        if separation.get("separated") is False:
            flags.append("static_separation.separated = false")
        check = channel.get("separation_check") or {}
        if check.get("separated") is False:
            flags.append("separation_check.separated = false")
    return flags


def score_channel(name: str, truth: dict, result: dict) -> dict:
    """The default DAF of one channel against its exact value."""
    summary = result["json"]
    channel = next(c for c in summary["channels"] if c["name"] == name)
    exact = truth["daf"]
    error = channel["daf"] - exact
    uncertainty = channel.get("uncertainty")
    half_width = uncertainty["expanded_95"] if uncertainty else None
    # A printed warning about this channel (vbi's `warnings` block names it: "the DAF of NAME
    # …"), or the run-wide "static part … distorted" line of a low-pass channel.
    method = channel["static_method"]
    screen = [
        line for line in warnings_on_screen(result)
        if f"DAF of {name} " in line
        or (line.startswith("static part:") and method == "low_pass")
        or ("crawl run's baseline" in line and method == "crawl_run")
    ]
    key = key_result_warning(result["key_results"], f"DAF of {name}")
    if key is None and method == "crawl_run":
        key = next(
            (f"{head}: {text}" for head, text in result["key_results"].items()
             if WARNING_WORDS.search(head) and "crawl run's baseline" in text),
            None,
        )
    beyond = half_width is not None and abs(error) > 2.0 * half_width
    return {
        "channel": name,
        "method": channel["static_method"],
        "daf": channel["daf"],
        "exact": exact,
        "error": error,
        "half_width_95": half_width,
        "covered": None if half_width is None else abs(error) <= half_width,
        "covered_within_tolerance": None if half_width is None else abs(error) <= half_width + COVERAGE_TOLERANCE,
        "beyond_twice_half_width": beyond,
        "warned_on_screen": bool(screen),
        "warned_in_key_results": key is not None,
        "warned_in_json": json_flags(summary, channel),
        "unflagged_beyond": beyond and not (screen and key is not None),
        "bare_unwarned": half_width is None and not (screen and key is not None),
        "daf_at_k1": (channel.get("cutoff_mode") or {}).get("daf_after"),
        "cutoff_hz": channel.get("cutoff_hz"),
        "every_method": [
            {"method": m["method"], "daf": m["daf"], "error": m["daf"] - exact, "valid": m.get("valid"),
             "chosen": m.get("chosen"), "stated_bias": m.get("bias")}
            for m in channel.get("static_methods", [])
        ],
    }


def score_frequency(truth: dict, result: dict) -> dict:
    """f1 identified (or taken from the model) against the model's first vertical bending."""
    summary = result["json"]
    identified = summary.get("identified_frequencies") or []
    exact = truth["first_frequency_hz"]
    if identified:
        value, source = identified[0]["frequency_hz"], summary.get("identification")
        spread = identified[0].get("frequency_std_hz")
    else:
        separation = summary.get("static_separation") or {}
        value, source, spread = separation.get("first_frequency_hz"), "static_separation", None
    screen = [line for line in warnings_on_screen(result) if FREQUENCY_WORDS.search(line)]
    key = key_result_warning(result["key_results"], "first identified frequency") or next(
        (f"{head}: {text}" for head, text in result["key_results"].items()
         if WARNING_WORDS.search(head) and FREQUENCY_WORDS.search(text)),
        None,
    )
    relative = None if value is None else value / exact - 1.0
    within = relative is not None and abs(relative) <= 0.01
    return {
        "exact_hz": exact,
        "value_hz": value,
        "source": source,
        "scatter_hz": spread,
        "relative_error": relative,
        "within_1_percent": within,
        "flagged_on_screen": bool(screen),
        "flagged_in_key_results": key is not None,
        "forced_content_check": summary.get("forced_content_check"),
        "ok": value is None or within or bool(screen) or key is not None,
    }


def score_rdm(truth: dict, result: dict) -> Optional[dict]:
    rdm = next((r for r in result["json"].get("rdm", [])), None)
    if rdm is None or truth.get("rdm") is None:
        return None
    error = rdm["rdm"] - truth["rdm"]
    u = rdm.get("uncertainty")
    return {"rdm": rdm["rdm"], "exact": truth["rdm"], "error": error, "half_width_95": None if u is None else 2 * u,
            "covered": None if u is None else abs(error) <= 2 * u,
            "side_of_one_right": (rdm["rdm"] > 1) == (truth["rdm"] > 1),
            "side_of_one_resolved": rdm.get("side_of_one_resolved")}


def score_case(record: dict, result: dict, channels: List[str]) -> dict:
    """Everything scored of one case (a refusal: the message instead)."""
    truth = record["truth"]
    scored = {"returncode": result["returncode"], "seconds": round(result["seconds"], 3),
              "screen_warnings": warnings_on_screen(result), "extra_lines": extra_lines(result)}
    if result["returncode"] != 0:
        scored["refusal"] = result["stderr"].strip()[-1500:]
        return scored
    summary = result["json"]
    scored["key_results"] = result["key_results"]
    scored["channels"] = [score_channel(name, truth["channels"][name], result) for name in channels]
    scored["first_frequency"] = score_frequency(truth, result)
    scored["rdm"] = score_rdm(truth, result)
    scored["preparation"] = {k: summary["preparation"].get(k) for k in ("baseline", "crossing", "detected_entry")}
    scored["static_separation"] = {k: (summary.get("static_separation") or {}).get(k)
                                   for k in ("rule", "cutoff_hz", "first_frequency_hz", "separated", "reason")}
    scored["identification"] = summary.get("identification")
    return scored
