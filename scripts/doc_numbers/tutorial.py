"""docs/tutorial/*.md: the numbers in the chapters' prose and tables, from the commands each chapter
shows (the same files and options), and the hand calculations of the text, from the input files.

The chapters' ```text blocks after `<!-- expected output -->` are vbi's own printout, checked by
crates/vbi-cli/tests/it/docs_commands.rs; what is marked here is the prose and the tables around
them. The pages quote no measured times (docs/performance.md holds them).

Each chapter is one function, `values(outputs)` of its page, built from a few functions, one per
section of the chapter; the readers of the outputs and the formatting come first."""

from __future__ import annotations

import html
import json
import math
import re
import subprocess
import tomllib
from decimal import ROUND_HALF_UP, Decimal
from pathlib import Path
from typing import Dict, List, Sequence

from common import ROOT, Outputs, claim, f3, f4, fixed, page, read_csv, span, table

BEAM = "examples/your-own/three-span-beam.toml"
BEAM_SCENARIO = "examples/your-own/three-span-beam-scenario.toml"
GRILLAGE = "examples/your-own/five-girder-grillage.toml"
GRILLAGE_SCENARIO = "examples/your-own/five-girder-grillage-scenario.toml"
STUDY = "examples/your-own/one-bridge-study.toml"
PAPER_STUDY = "examples/studies/paper.toml"
SYNTHETIC_RECORD = "examples/measurements/synthetic_4x30.toml"
FIELD_RECORD = "examples/measurements/field_4x30/fast.toml"
FIELD_BRIDGE = "examples/bridges/paper-4x30.toml"  # the preset that fast.csv was simulated on

# The synthetic records' exact answers, given with them (examples/measurements/README.md, printed
# by generate_synthetic.py and field_4x30/generate.py): inputs of the page, not vbi's outputs.
SYNTHETIC_EXACT_DAF = {"deflection": "1.0963", "strain": "1.0510"}
FIELD_EXACT_DAF = {"deflection": "1.0882", "strain": "1.0132"}
FIELD_DRIFT_ADDED = {"deflection": 0.010, "strain": 0.4}  # mm/s and µε/s

IN_PLANE = ("lateral", "longitudinal")  # the mode kinds a crossing drops

# ---------------------------------------------------------------------------------------------
# Reading the inputs and the outputs


def input_file(path: str) -> dict:
    with open(ROOT / path, "rb") as handle:
        return tomllib.load(handle)


def printed(out: Path) -> str:
    return (out / "stdout.txt").read_text()


def printed_number(text: str, pattern: str) -> str:
    """The first group of `pattern` in a printout."""
    match = re.search(pattern, text)
    if not match:
        raise SystemExit(f"doc_numbers: vbi no longer prints {pattern!r}")
    return match.group(1)


def printout(outputs: Outputs, name: str, *arguments: str) -> str:
    """What `vbi ARGUMENTS` prints, for the commands that write no directory (`vbi vehicle show`,
    `vbi study --list`), which `Outputs.command` (it appends --out) does not fit."""
    saved = outputs.work / f"{name}.txt"
    if not (outputs.reuse and saved.exists()):
        done = subprocess.run([str(outputs.vbi), *arguments], cwd=outputs.work, capture_output=True, text=True)
        if done.returncode != 0:
            raise SystemExit(f"doc_numbers: `vbi {' '.join(arguments)}` failed:\n{done.stderr[-2000:]}")
        saved.write_text(done.stdout + done.stderr)
    return saved.read_text()


class ModalAnalysis:
    """`vbi modes FILE --modes N --out …`: modes.csv, mode_shapes.csv and the printout."""

    def __init__(self, out: Path):
        self.printout = printed(out)
        self.modes = read_csv(out / "modes.csv")
        self.shapes = read_csv(out / "mode_shapes.csv")
        self.dofs = int(printed_number(self.printout, r"(\d+) degrees of freedom"))
        self.total_mass_t = printed_number(self.printout, r"total mass ([0-9.]+) t")

    def frequency(self, mode: int) -> float:
        return float(self.modes[mode - 1]["frequency_hz"])

    def kept(self) -> List[dict]:
        """The modes a crossing keeps (not in-plane)."""
        return [m for m in self.modes if m["kind"] not in IN_PLANE]

    def girder_sections(self) -> List[dict]:
        """A grillage's table of girder sections."""
        number = r"\s+(-?[0-9.]+)"
        rows = re.findall(rf"^\s+(\d+){number}\s+\w+{number * 6}$", self.printout, re.M)
        keys = ["girder", "y", "area", "i_y", "i_z", "j", "centroid", "mass"]
        return [dict(zip(keys, row)) for row in rows]


class Crossing:
    """`vbi run SCENARIO --out …`: summary.json, the other tables and the printout."""

    def __init__(self, out: Path):
        self.out = out
        self.printout = printed(out)
        self.summary = json.loads((out / "summary.json").read_text())
        # The DAF table's entries (a deflection or moment over a support has no DAF).
        self.entries = [e for e in self.summary["stations"] if e["daf"] is not None]

    def at(self, station: str, quantity: str) -> dict:
        return next(e for e in self.summary["stations"] if e["name"] == station and e["quantity"] == quantity)

    def daf(self, station: str, quantity: str) -> float:
        return self.at(station, quantity)["daf"]

    def cutoff_modes(self, station: str, quantity: str, joint: str = " and ") -> str:
        entry = self.at(station, quantity)
        return f"{entry['cutoff_k1']}{joint}{entry['cutoff_k2']}"

    def time_step_ms(self) -> str:
        return fixed(1000 * self.summary["provenance"]["time_step_s"], 2)

    def file_size(self, name: str, unit: float) -> str:
        return fixed((self.out / name).stat().st_size / unit, 0)


class Vehicle:
    """`vbi vehicle show NAME`: the wheels (x, y, static load) and the natural modes."""

    def __init__(self, outputs: Outputs, name: str):
        text = printout(outputs, f"vehicle_show_{name}", "vehicle", "show", name)
        self.mass_t = float(printed_number(text, r"total mass\s+([0-9.]+) kg")) / 1000
        self.dofs = int(printed_number(text, r"DOFs\s+(\d+)"))
        number = r"(-?[0-9.]+)"
        wheels = re.findall(rf"^\s+{number}\s+{number}\s+{number}\s+[0-9.]+\s+tyre", text, re.M)
        self.wheels = [(Decimal(x), Decimal(y), float(load)) for x, y, load in wheels]
        modes = re.findall(r"^\s+([0-9.]+)\s+(\D.*?) \(\d+ %\)$", text, re.M)
        self.modes = [(float(f), motion) for f, motion in modes]

    def axle_loads_kn(self) -> Dict[Decimal, float]:
        loads: Dict[Decimal, float] = {}
        for x, _, load in self.wheels:
            loads[x] = loads.get(x, 0.0) + load
        return loads

    def frequencies(self, motion: str) -> List[float]:
        """The natural frequencies whose dominant motion starts with `motion` ("truck", "axle")."""
        return [f for f, what in self.modes if what.startswith(motion)]


# ---------------------------------------------------------------------------------------------
# Formatting


def rounded(x: Decimal, digits: int) -> str:
    """A hand calculation's exact decimal result, rounded half up (away from zero) as a reader would."""
    return str(x.quantize(Decimal(1).scaleb(-digits), rounding=ROUND_HALF_UP))


def signed(text: str) -> str:
    """A negative number with the typographic minus of the pages."""
    return "−" + text[1:] if text.startswith("-") else text


def whole_percent(x: float) -> str:
    return f"{fixed(100 * x, 0)} %"


def percent_one_decimal(x: float) -> str:
    return f"{fixed(100 * x, 1)} %"


def percent_range(values: Sequence[float]) -> str:
    """Increments (DAF − 1) as whole per cents: "18 %" or "15–22 %"."""
    low, high = fixed(100 * min(values), 0), fixed(100 * max(values), 0)
    return f"{low} %" if low == high else f"{low}–{high} %"


def short_exponent(x: float) -> str:
    """1.82e-5 as "1.8e-5"."""
    mantissa, exponent = f"{x:.1e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def listed(items: Sequence[str]) -> str:
    """"60, 90 and 120"."""
    return ", ".join(items[:-1]) + " and " + items[-1] if len(items) > 1 else items[0]


WORDS = ["none", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten"]


def in_words(n: int) -> str:
    return WORDS[n] if 0 <= n < len(WORDS) else str(n)


# ---------------------------------------------------------------------------------------------
# index.md


@page("docs/tutorial/index.md", inputs=["1.89"])  # the Rust toolchain's version
def introduction(outputs: Outputs) -> Dict[str, str]:
    # The index shows its commands' output in checked ```text blocks and quotes none of it in prose.
    return {}


# ---------------------------------------------------------------------------------------------
# 01-your-own-beam.md


def beam_hand_checks(bridge: dict, modal: ModalAnalysis) -> Dict[str, str]:
    """"Check what you can by hand": the total mass, a simple span's first frequency, the modes."""
    section = bridge["section"]
    rigidity = Decimal(str(section["flexural_rigidity_n_m2"]))
    mass = Decimal(str(section["mass_per_length_kg_per_m"]))
    claim(Decimal("34.5e9") * Decimal("1.10") == rigidity, "EI = 34.5 GPa × 1.10 m⁴")
    claim(Decimal("6.4") * 2500 == mass, "the structural mass per length is 6.4 m² × 2500 kg/m³")
    mass_per_length = mass + Decimal(str(bridge["added_mass_kg_per_m"]))
    length = sum(Decimal(str(l)) for l in bridge["span_lengths_m"])
    total_mass = rounded(length * mass_per_length / 1000, 1)
    claim(total_mass == modal.total_mass_t, "vbi modes prints the hand calculation's total mass")
    main_span = max(bridge["span_lengths_m"])
    simple_span = math.pi / (2 * main_span**2) * math.sqrt(float(rigidity / mass_per_length))
    claim(modal.frequency(1) > simple_span, "the continuous beam's first mode lies above the simple span's")

    # mode_shapes.csv at the spans' middles (x = 9, 30, 51 m)
    shape = {float(r["x_m"]): r for r in modal.shapes}
    at = lambda mode, x: float(shape[x][f"mode_{mode}"])  # noqa: E731
    side, middle, other_side = 9.0, 30.0, 51.0
    claim(at(1, middle) * at(1, side) < 0 and at(1, middle) * at(1, other_side) < 0,
          "in mode 1 the main span moves against the side spans")
    claim(all(abs(at(2, x) + at(2, float(length) - x)) < 1e-9 for x in shape), "mode 2 is antisymmetric")
    claim(at(3, middle) * at(3, side) > 0 and at(3, side) * at(3, other_side) > 0,
          "mode 3 moves the three spans the same way")
    return {
        "beam_mass_per_length": f"{int(mass_per_length):,}".replace(",", " "),
        "beam_total_mass": total_mass,
        "beam_simple_span_frequency": fixed(simple_span, 2),
        "beam_first_frequency": fixed(modal.frequency(1), 2),
        "beam_second_frequency": fixed(modal.frequency(2), 2),
        "beam_third_frequency": fixed(modal.frequency(3), 2),
    }


def beam_truck(truck: Vehicle, modal: ModalAnalysis) -> Dict[str, str]:
    """`vbi vehicle show three-axle-truck-36t`, read against the bridge's first frequency."""
    axles = truck.axle_loads_kn()
    rear, last = sorted(axles)[1], sorted(axles)[0]  # x is negative behind the front axle
    body, axle = truck.frequencies("truck"), truck.frequencies("axle")
    claim(max(body) < modal.frequency(1) < min(axle),
          "the bridge's first frequency lies between the truck's body and axle modes")
    return {
        "truck_mass": fixed(truck.mass_t, 0),
        "truck_rear_axle_spacing": rounded(rear - last, 2),
        "truck_rear_axle_loads": f"{fixed(axles[rear], 0)} and {fixed(axles[last], 0)}",
        "truck_body_frequencies": span(body, 1),
        "truck_axle_frequencies": span(axle, 1),
        "beam_first_frequency_rounded": fixed(modal.frequency(1), 1),
    }


def beam_crossing(crossing: Crossing, modal: ModalAnalysis, bridge: dict, scenario: dict) -> Dict[str, str]:
    """The crossing's first line, the DAF table's columns, the modes kept and the time step."""
    summary = crossing.summary
    claim(all(e["converged"] for e in crossing.entries) and not summary["warnings"],
          "every entry has converged (no `!`, no warning)")
    # The time step: the note's largest change is relative, over the deflections and moments.
    note = float(printed_number(crossing.printout, r"largest change ([0-9.e-]+) of a deflection or moment DAF"))
    held = [e for e in crossing.entries if e["quantity"] in ("deflection", "bending_moment")]
    claim(abs(max(abs(e["daf_change_dt"]) / e["daf"] for e in held) - note) < 1e-7,
          "the note gives the largest Δt change")
    claim(max(abs(e["daf_change_dt"]) for e in held) < 5e-5,
          "no deflection or moment DAF moved in the fourth decimal with Δt")
    changes = [e["daf_change"] for e in crossing.entries]
    station = next(s for s in scenario["station"] if s["name"] == "span1_at_0.4")
    station_x = Decimal(str(station["fraction"])) * Decimal(str(bridge["span_lengths_m"][station["span"] - 1]))
    return {
        "beam_time_step": crossing.time_step_ms(),
        "beam_dofs": str(summary["provenance"]["dof_count"]),
        "beam_extra_dofs": in_words(summary["provenance"]["dof_count"] - modal.dofs),
        "beam_station_x": rounded(station_x, 1),
        "beam_last_fifth": printed_number(crossing.printout, r"over the last (\d+) modes kept"),
        "beam_check_modes": printed_number(crossing.printout, r"over the (\d+) check modes"),
        "beam_change_low": f4(min(changes)),
        "beam_change_high": f4(max(changes)),
        "beam_span1_daf_u": f4(crossing.daf("span1_mid_section", "deflection")),
        "beam_span1_daf_u_paper": f4(crossing.at("span1_mid_section", "deflection")["daf_paper"]),
        "beam_span1_shear_paper": f4(crossing.at("span1_mid_section", "shear_force")["daf_paper"]),
        "beam_span1_shear": f4(crossing.daf("span1_mid_section", "shear_force")),
        "beam_highest_frequency": fixed(summary["frequencies_hz"][-1], 0),
        "beam_span1_k_u": crossing.cutoff_modes("span1_mid_section", "deflection"),
        "beam_span1_k_m": crossing.cutoff_modes("span1_mid_section", "bending_moment"),
        "beam_step_change": short_exponent(note),
    }


def beam_with_40_modes(crossing: Crossing, with_40: Crossing) -> Dict[str, str]:
    """The same crossing with `modes = 40`: the converged DAFs hardly move, the plain sums do."""
    moves = {
        (e["name"], e["quantity"]): abs(with_40.daf(e["name"], e["quantity"]) - e["daf"]) for e in crossing.entries
    }
    largest = max(moves, key=moves.get)
    claim(largest[1] == "support_reaction", "with 40 modes a reaction moves most")
    deflections_and_moments = [m for (_, q), m in moves.items() if q in ("deflection", "bending_moment")]
    plain = lambda run, station, quantity: f4(run.at(station, quantity)["daf_paper"])  # noqa: E731
    return {
        "beam_40_time_step": with_40.time_step_ms(),
        "beam_40_largest_move": f4(moves[largest]),
        "beam_40_largest_move_where": f"`{largest[0]}`",
        "beam_40_largest_move_u_m": short_exponent(max(deflections_and_moments)),
        "beam_span1_daf_m": f4(crossing.daf("span1_mid_section", "bending_moment")),
        "beam_40_span1_daf_m": f4(with_40.daf("span1_mid_section", "bending_moment")),
        "beam_40_span2_daf_m": f4(with_40.daf("span2_mid_section", "bending_moment")),
        "beam_40_rdm": f4(with_40.summary["rdm"]),
        "beam_span1_daf_m_paper": plain(crossing, "span1_mid_section", "bending_moment"),
        "beam_40_span1_daf_m_paper": plain(with_40, "span1_mid_section", "bending_moment"),
        "beam_40_span1_shear_paper": plain(with_40, "span1_mid_section", "shear_force"),
        "beam_pier_reaction_paper": plain(crossing, "support2_section", "support_reaction"),
        "beam_40_pier_reaction_paper": plain(with_40, "support2_section", "support_reaction"),
        "beam_span1_k_m_comma": crossing.cutoff_modes("span1_mid_section", "bending_moment", ", "),
        "beam_40_span1_k_m": with_40.cutoff_modes("span1_mid_section", "bending_moment", ", "),
    }


def beam_what_the_numbers_say(crossing: Crossing) -> Dict[str, str]:
    """The increments, the main span's DAF below 1, the RDM, the files and the figures."""
    summary = crossing.summary
    increment = lambda station, quantity: crossing.daf(station, quantity) - 1  # noqa: E731
    piers = ("support2_section", "support3_section")
    moment = crossing.at("span2_mid_section", "bending_moment")
    claim(moment["daf"] < 1, "the main span's moment has a DAF below 1 (its dynamic maximum below the static one)")
    claim(summary["rdm_station"] == "span2_mid_section", "the RDM station is the main span's mid-span")
    one_mode = {
        r["quantity"]: float(r["daf_paper"])
        for r in read_csv(crossing.out / "daf_by_modes.csv")
        if r["station"] == summary["rdm_station"] and r["modes"] == "1"
    }
    deck = summary["deck_participation"]
    return {
        "beam_span1_increment_u": percent_range([increment("span1_mid_section", "deflection")]),
        "beam_span1_increment_m": percent_range([increment("span1_mid_section", "bending_moment")]),
        "beam_pier_increment_m": percent_range([increment(p, "bending_moment") for p in piers]),
        "beam_pier_increment_reaction": percent_range([increment(p, "support_reaction") for p in piers]),
        "beam_span2_daf_m_rounded": fixed(moment["daf"], 2),
        "beam_span2_dynamic_m": fixed(moment["dynamic_max"] / 1000, 0),
        "beam_span2_static_m": fixed(moment["static_max"] / 1000, 0),
        "beam_rdm_daf_u": f4(crossing.daf("span2_mid_section", "deflection")),
        "beam_rdm_daf_m": f4(moment["daf"]),
        "beam_rdm": f4(summary["rdm"]),
        "beam_rdm_excess": whole_percent(summary["rdm"] - 1),
        "beam_summary_size": crossing.file_size("summary.json", 1e3),
        "beam_histories_size": crossing.file_size("histories.csv", 1e6),
        "beam_vehicles_size": crossing.file_size("vehicles.csv", 1e6),
        "beam_one_mode_shear_paper": fixed(one_mode["shear_force"], 2),
        "beam_one_mode_moment_paper": fixed(one_mode["bending_moment"], 2),
        "beam_mode1_deflection_share": whole_percent(deck["deflection"][0]),
        "beam_mode1_moment_share": whole_percent(deck["moment"][0]),
        "beam_deck_k1_m": str(deck["moment_k1"]),
        "beam_deck_k2_m": str(deck["moment_k2"]),
    }


@page(
    "docs/tutorial/01-your-own-beam.md",
    inputs=[
        # the bridge file: damping as a fraction and in per cent; E, I, box depth, area; EI
        "0.02", "2 %", "34.5", "1.10", "1.20", "6.4", "3.795e10",
        # the scenario's station at 0.4 of span 1; thresholds: 1 % of the DAF (the modes),
        # 95 % and 99 % of the response (K1, K2), 0.1 % (the time step)
        "0.4", "1 %", "95 %", "99 %", "0.1 %",
    ],
)
def your_own_beam(outputs: Outputs) -> Dict[str, str]:
    bridge, scenario = input_file(BEAM)["bridge"], input_file(BEAM_SCENARIO)
    modal = ModalAnalysis(outputs.command("beam_modes", "modes", BEAM, "--modes", "10"))
    truck = Vehicle(outputs, scenario["scenario"]["vehicle"])
    crossing = Crossing(outputs.run("beam", BEAM_SCENARIO))
    with_40 = Crossing(outputs.run("beam_40_modes", BEAM_SCENARIO, [("modes = 20", "modes = 40")]))
    return {
        **beam_hand_checks(bridge, modal),
        **beam_truck(truck, modal),
        **beam_crossing(crossing, modal, bridge, scenario),
        **beam_with_40_modes(crossing, with_40),
        **beam_what_the_numbers_say(crossing),
    }


# ---------------------------------------------------------------------------------------------
# 02-a-grillage.md


def grillage_section_checks(bridge: dict, modal: ModalAnalysis) -> Dict[str, str]:
    """The section table against the hand calculation: deck share, area, mass, first frequency."""
    sections = modal.girder_sections()
    count = bridge["girder_count"]
    claim(len(sections) == count and len({tuple(list(s.values())[2:]) for s in sections}) == 1,
          "every girder has the same section")
    girder = sections[0]
    given = {**bridge["girder"], **bridge["deck"], **bridge["material"]}
    d = {key: Decimal(str(value)) for key, value in given.items() if not isinstance(value, str)}
    spacing, width = Decimal(str(bridge["girder_spacing_m"])), Decimal(str(bridge["deck_width_m"]))
    edge_share = spacing / 2 + (width / 2 - (count - 1) * spacing / 2)
    claim(edge_share == spacing, "the edge girders' deck share equals the inner girders' (the girder spacing)")
    web_height = d["height_m"] - d["top_flange_thickness_m"] - d["bottom_flange_thickness_m"]
    area = (
        spacing * d["slab_thickness_m"]
        + d["top_flange_width_m"] * d["top_flange_thickness_m"]
        + d["bottom_flange_width_m"] * d["bottom_flange_thickness_m"]
        + d["web_thickness_m"] * web_height
    )
    claim(rounded(area, 4) == girder["area"], "vbi's girder area is the hand calculation's")
    mass = area * d["density_kg_per_m3"] + d["asphalt_thickness_m"] * spacing * d["asphalt_density_kg_per_m3"]
    claim(rounded(mass, 1) == girder["mass"], "vbi's girder mass per length is the hand calculation's")
    # A simple span of the five girders' EI and the deck's mass per length, as the text writes it.
    length = bridge["span_lengths_m"][0]
    rigidity = count * bridge["material"]["modulus_gpa"] * 1e9 * float(girder["i_y"])
    simple_span = math.pi / (2 * length**2) * math.sqrt(rigidity / (float(modal.total_mass_t) * 1000 / length))
    return {
        "grillage_deck_share": str(spacing),
        "grillage_area": rounded(area, 4),
        "grillage_i_y": girder["i_y"],
        "grillage_j": girder["j"],
        "grillage_centroid": girder["centroid"],
        "grillage_mass_per_length": rounded(mass, 1),
        "grillage_total_mass": modal.total_mass_t,
        "grillage_simple_span_frequency": fixed(simple_span, 2),
    }


def grillage_modes_and_plan(bridge: dict, modal: ModalAnalysis, crossing: Crossing) -> Dict[str, str]:
    """The kinds of the modes, the modes a crossing keeps, mode 1's shape, the plan."""
    bending = next(m for m in modal.modes if m["kind"] == "vertical_bending")
    claim(modal.modes[0]["kind"] == "torsion" and modal.frequency(1) < float(bending["frequency_hz"]),
          "mode 1 is a torsion mode just below the first bending mode")
    in_plane = [m["mode"] for m in modal.modes if m["kind"] in IN_PLANE]
    kept = len(modal.kept())
    claim(f"{kept} modes, dt" in crossing.printout, "the crossing keeps the modes that are not in-plane")
    middle = bridge["span_lengths_m"][0] / 2
    mode_1 = {float(r["y_m"]): float(r["mode_1"]) for r in modal.shapes if float(r["x_m"]) == middle}
    y = [float(g["y"]) for g in modal.girder_sections()]
    claim(mode_1[y[0]] * mode_1[y[4]] < 0 and abs(mode_1[y[2]]) < 1e-6 * abs(mode_1[y[0]]),
          "in mode 1 girders 1 and 5 move against each other and girder 3 stands still")
    return {
        "grillage_bending_frequency": fixed(float(bending["frequency_hz"]), 2),
        "grillage_torsion_frequency": fixed(modal.frequency(1), 2),
        "grillage_in_plane_modes": listed(in_plane),
        "grillage_kept_modes": str(kept),
        "grillage_edge_girder_y": f"{signed(fixed(y[0], 1))} … {fixed(y[-1], 1)}",
        "grillage_deck_edge": fixed(bridge["deck_width_m"] / 2, 1),
    }


def grillage_lane(scenario: dict, truck: Vehicle, modal: ModalAnalysis, bridge: dict) -> Dict[str, str]:
    """The truck in the right-hand lane: its wheel paths against the girders; the added station."""
    lateral = Decimal(str(scenario["scenario"]["lateral_position_m"]))
    claim(lateral == -Decimal("3.5") / 2, "the truck runs in the middle of the right-hand 3.5 m lane")
    half_track = max(abs(y) for _, y, _ in truck.wheels if abs(y) < 1)  # the rear axles' (all but the steer axle)
    right, left = lateral - half_track, lateral + half_track
    girder_y = [float(g["y"]) for g in modal.girder_sections()]
    nearest = min(range(len(girder_y)), key=lambda i: abs(girder_y[i] - float(right))) + 1
    claim(nearest == 2, "the right-hand wheels run near girder 2")
    claim(girder_y[1] < float(left) < girder_y[2], "the left-hand wheels run between girders 2 and 3")
    quarter = next(s for s in scenario["station"] if s["name"] == "g1_quarter")
    quarter_x = Decimal(str(quarter["fraction"])) * Decimal(str(bridge["span_lengths_m"][0]))
    return {
        "grillage_truck_mass": fixed(truck.mass_t, 0),
        "truck_track": rounded(2 * half_track, 1),
        "truck_right_wheels_y": signed(rounded(right, 1)),
        "truck_left_wheels_y": signed(rounded(left, 1)),
        "grillage_quarter_x": rounded(quarter_x, 1),
        "truck_dofs": str(truck.dofs),
        "truck_tyres": str(len(truck.wheels)),
    }


def grillage_girders(crossing: Crossing, modal: ModalAnalysis) -> Dict[str, str]:
    """The results per girder: the static table, the DAFs, the RDM, the warning, the abutment."""
    count = len(modal.girder_sections())
    girders = [f"span1_mid_g{i}" for i in range(1, count + 1)]
    whole = "span1_mid_section"
    dofs = crossing.summary["provenance"]["dof_count"]
    claim(dofs > modal.dofs and (dofs - modal.dofs) % count == 0,
          "every girder line gets a node at the added station")
    moments = [crossing.at(g, "bending_moment")["static_max"] for g in girders]
    section_moment = crossing.at(whole, "bending_moment")["static_max"]
    shares = [m / section_moment for m in moments]
    claim(0.3 < shares[0] < 0.37 and max(shares) == shares[0],
          "the edge girder 1 takes the most, a third of the moment")
    claim(sum(moments) > section_moment, "the girders' moments add up to a little more than the section's")
    static = lambda station, quantity: crossing.at(station, quantity)["static_max"]  # noqa: E731
    deflection = lambda station: signed(fixed(1000 * static(station, "deflection"), 3))  # noqa: E731
    girder_y = [float(g["y"]) for g in modal.girder_sections()]
    rows = [
        [str(i + 1), signed(fixed(y, 1)), deflection(g), fixed(moment / 1000, 1), whole_percent(share)]
        for i, (g, y, moment, share) in enumerate(zip(girders, girder_y, moments, shares))
    ]
    rows.append(["section", "", f"{deflection(whole)} (mean)", f"{fixed(section_moment / 1000, 1)} (sum)", ""])
    header = ["girder", "y [m]", "static deflection [mm]", "static moment [kN·m]", "share of the section's moment"]

    claim(crossing.summary["rdm_station"] == "span1_mid_g1", "the RDM station is girder 1's mid-span")
    flagged = [(e["name"], e["quantity"]) for e in crossing.entries if not e["converged"]]
    claim(set(flagged) == {("span1_mid_g5", "shear_force"), ("span1_mid_g5", "bending_moment"),
                           ("abutment1_section", "deflection"), ("abutment1_section", "support_reaction")},
          "girder 5's shear and moment and the abutment line's deflection and reaction are flagged")
    claim(all(e["converged"] for e in crossing.entries if e["name"].endswith("_g1")),
          "every entry of girder 1, the governing one, converged")
    moment_5 = crossing.at("span1_mid_g5", "bending_moment")
    abutment_line = crossing.at("abutment1_section", "support_reaction")
    shear_5, shear_1 = crossing.at("span1_mid_g5", "shear_force"), crossing.at("span1_mid_g1", "shear_force")
    bearing = crossing.at("abutment1_g1", "support_reaction")
    line = crossing.at("abutment1_section", "support_reaction")
    claim(line["daf"] < bearing["daf"], "the whole support line's DAF is below girder 1's bearing's")
    kilonewtons = lambda x: fixed(x / 1000, 1)  # noqa: E731
    return {
        "grillage_dofs": str(dofs),
        "grillage_extra_dofs": str(dofs - modal.dofs),
        "grillage_girder_table": table(header, rows),
        "grillage_girder1_share_over_equal": fixed(shares[0] * count, 2),
        "grillage_equal_share": whole_percent(1 / count),
        "grillage_daf_u_g1": fixed(crossing.daf("span1_mid_g1", "deflection"), 2),
        "grillage_daf_u_g3": fixed(crossing.daf("span1_mid_g3", "deflection"), 2),
        "grillage_daf_u_g5": fixed(crossing.daf("span1_mid_g5", "deflection"), 2),
        "grillage_rdm_daf_u": f4(crossing.daf("span1_mid_g1", "deflection")),
        "grillage_rdm_daf_m": f4(crossing.daf("span1_mid_g1", "bending_moment")),
        "grillage_rdm": f4(crossing.summary["rdm"]),
        "grillage_flagged_change": f4(shear_5["daf_change"]),
        "grillage_flagged_moment_change": f4(moment_5["daf_change"]),
        "grillage_flagged_moment_daf": fixed(moment_5["daf"], 2),
        "grillage_flagged_abutment_change": f4(abutment_line["daf_change"]),
        "grillage_shear_g5": fixed(shear_5["static_max"] / 1000, 0),
        "grillage_shear_g1": fixed(shear_1["static_max"] / 1000, 0),
        "grillage_abutment_deflection": fixed(-1000 * static("abutment1_section", "deflection"), 3),
        "grillage_bearing_static": kilonewtons(bearing["static_max"]),
        "grillage_bearing_dynamic": kilonewtons(bearing["dynamic_max"]),
        "grillage_bearing_daf": fixed(bearing["daf"], 2),
        "grillage_line_static_dynamic": f"{kilonewtons(line['static_max'])} and {kilonewtons(line['dynamic_max'])}",
        "grillage_line_daf": fixed(line["daf"], 2),
    }


def grillage_participation(crossing: Crossing, modal: ModalAnalysis) -> Dict[str, str]:
    """participation.csv's kept modes, paired with `vbi modes`' kinds (the crossing's model also has
    the added station's nodes: the same modes, to round-off)."""
    participation = read_csv(crossing.out / "participation.csv")
    kinds = modal.kept()
    pairs = zip(participation, kinds)
    claim(all(abs(float(p["frequency_hz"]) / float(k["frequency_hz"]) - 1) < 0.01 for p, k in pairs),
          "the crossing's modes are those of `vbi modes` without the in-plane ones")
    first = lambda kind: next(p for p, k in zip(participation, kinds) if k["kind"] == kind)  # noqa: E731
    deck = crossing.summary["deck_participation"]
    return {
        "grillage_bending_share": whole_percent(float(first("vertical_bending")["mps_deflection"])),
        "grillage_torsion_share": whole_percent(float(first("torsion")["mps_deflection"])),
        "grillage_deck_k1_u": str(deck["deflection_k1"]),
        "grillage_deck_k2_u": str(deck["deflection_k2"]),
        "grillage_deck_k_m": f"{deck['moment_k1']} and {deck['moment_k2']}",
    }


@page(
    "docs/tutorial/02-a-grillage.md",
    inputs=[
        # the bridge file: slab, flanges, web, depth, asphalt; the bearings' stiffness;
        # the scenario's 3.5 m lane; thresholds: 1 % of the DAF, 95 % and 99 % of the response
        "0.20", "0.80", "0.18", "0.65", "0.25", "1.60", "0.08", "2.0e9", "3.5", "1 %", "95 %", "99 %",
    ],
)
def a_grillage(outputs: Outputs) -> Dict[str, str]:
    bridge, scenario = input_file(GRILLAGE)["bridge"], input_file(GRILLAGE_SCENARIO)
    modal = ModalAnalysis(outputs.command("grillage_modes", "modes", GRILLAGE, "--modes", "30"))
    truck = Vehicle(outputs, scenario["scenario"]["vehicle"])
    crossing = Crossing(outputs.run("grillage", GRILLAGE_SCENARIO))
    return {
        **grillage_section_checks(bridge, modal),
        **grillage_modes_and_plan(bridge, modal, crossing),
        **grillage_lane(scenario, truck, modal, bridge),
        **grillage_girders(crossing, modal),
        **grillage_participation(crossing, modal),
    }


# ---------------------------------------------------------------------------------------------
# 03-a-study.md


def key_results(report: Path) -> str:
    """The report's "Key results" as the page shows them: one line per row, the design codes' row
    abridged to its first code and AASHTO LRFD (strength)."""
    text = report.read_text()
    start = text.index('<section id="key-results">')
    body = text[start : text.index("</section>", start)]
    lines = ["Key results"]
    for name, value in re.findall(r"<tr><th>(.*?)</th><td>(.*?)</td></tr>", body):
        name, value = html.unescape(name), html.unescape(re.sub(r"<[^>]+>", "", value))
        if name.startswith("design codes"):
            codes = value.split("; ")
            strength = next(c for c in codes if c.startswith("AASHTO LRFD (strength)"))
            value = f"{codes[0]}; … {strength}; …"
        lines.append(f" {name:<14}{value}" if len(name) < 14 else f" {name}   {value}")
    return "\n".join(["```text", *lines, "```"])


def study_run(cases: List[dict], printed_run: str, listing: str) -> Dict[str, str]:
    """The run, its warnings, and the convergence of the RDM station's DAFs."""
    count = int(printed_number(printed_run, r"(\d+) cases run"))
    claim(f"{count} cases" in listing and count == len(cases), "the listing and the run have the same cases")
    warned = [c for c in cases if c["warnings"]]
    claim(len(warned) > count // 2, "most cases have a solver warning")
    claim(f"warning: {len(warned)} case(s) have solver warnings" in printed_run, "the run says how many")
    changes = [float(printed_number(c["warnings"], r"changes by ([0-9.]+)")) for c in warned]
    about = [re.search(r"DAF of (\w+) at `(\w+)`", c["warnings"]).groups() for c in warned]
    at_abutment = sum(1 for _, station in about if station == "abutment1_g1")
    claim(at_abutment > len(warned) // 2, "most warnings name abutment1_g1")
    claim(any(q == "support_reaction" for q, _ in about), "a warning names a support reaction")
    claim(all("converged DAF" in c["warnings"] and "check mode(s)" in c["warnings"] for c in warned),
          "the warnings are the convergence indicator's")
    kept = {c["modes"] for c in cases}
    claim(len(kept) == 1, "every case keeps the same modes")
    return {
        "study_cases": str(count),
        "study_warned_cases": str(len(warned)),
        "study_warning_largest": f4(max(changes)),
        "study_warning_at_abutment": str(at_abutment),
        "study_largest_change_u": f4(max(float(c["daf_u_change"]) for c in cases)),
        "study_largest_change_m": f4(max(float(c["daf_m_change"]) for c in cases)),
        "study_modes_kept": kept.pop(),
    }


def study_statistics(cases: List[dict], summary: List[dict], speeds: List[int], roads: List[str]) -> Dict[str, str]:
    """summary.csv's converged DAF_M per speed and road, and what an engineer reads from it."""

    def group(speed, road, metric="daf_m"):
        return next(r for r in summary if (r["speed_kmh"], r["road"], r["metric"]) == (str(speed), road, metric))

    rows = []
    for speed in speeds:
        for road in roads:
            g = {key: float(group(speed, road)[key]) for key in ("mean", "std", "max", "p95", "p95_low", "p95_high")}
            rows.append([f"{speed} km/h", road, f3(g["mean"]), f3(g["std"]), f3(g["max"]), f3(g["p95"]),
                         f"{f3(g['p95_low'])} – {f3(g['p95_high'])}"])
            samples = sorted(float(c["daf_m"]) for c in cases if (c["speed_kmh"], c["road"]) == (str(speed), road))
            claim(samples[-2] <= g["p95"] <= samples[-1], "with 4 samples p95 lies between the two largest samples")
    mean = lambda speed, road: float(group(speed, road)["mean"])  # noqa: E731
    smooth, rough = roads[0], roads[-1]
    ratios = [(mean(v, rough) - 1) / (mean(v, smooth) - 1) for v in speeds]
    claim(3 <= min(ratios) and max(ratios) < 5.5,
          "the mean increment on class C is three to five times that on class A")
    over_speeds = [max(mean(v, r) for v in speeds) - min(mean(v, r) for v in speeds) for r in roads]
    claim(max(over_speeds) < min(mean(v, rough) - mean(v, smooth) for v in speeds),
          "speed matters less than the road")
    monotone = lambda m: m == sorted(m) or m == sorted(m, reverse=True)  # noqa: E731
    claim(not all(monotone([mean(v, r) for v in speeds]) for r in roads),
          "the DAF does not change monotonically with speed")
    rdm_means = [float(r["mean"]) for r in summary if r["metric"] == "rdm"]

    def losses(**fields):
        return sum(int(c["contact_losses"]) for c in cases if all(c[k] == v for k, v in fields.items()))

    claim(all(losses(road=r) == 0 for r in roads if r != rough), "no contact losses on classes A and B")
    for column in ("static_u_m", "static_m_nm"):
        values = [float(c[column]) for c in cases]
        claim((max(values) - min(values)) / abs(values[0]) < 1e-12,
              f"the static extreme ({column}) is the same in every case")
    return {
        "study_daf_m_table": table(["speed", "road", "mean", "std", "max", "p95", "p95 interval"], rows),
        "study_increment_ratio": f"{in_words(int(min(ratios)))} to {in_words(round(max(ratios)))}",
        "study_class_c_means": span([mean(v, rough) for v in speeds], 2),
        "study_class_a_means": span([mean(v, smooth) for v in speeds], 2),
        "study_rdm_means": f"{f3(min(rdm_means))} to {f3(max(rdm_means))}",
        "study_contact_loss_speeds": listed([str(v) for v in speeds if losses(road=rough, speed_kmh=str(v)) > 0]),
        "study_contact_losses": str(losses()),
    }


def study_report(out: Path, cases: List[dict], groups: int, rough: str) -> Dict[str, str]:
    """The report's key results, and its 95th percentile of all cases against the codes."""
    report = html.unescape((out / "report.html").read_text())
    p95 = float(printed_number(report, r"<th>converged DAF_M</th><td>[^<]*?cases together \(.*?\) ([0-9.]+)"))
    codes = [float(r["code_daf"]) for r in read_csv(out / "design_codes.csv") if r["quantity"] == "bending_moment"]
    claim(p95 > max(codes), "the 95th percentile of DAF_M over all cases exceeds every code value listed")
    largest = sorted(cases, key=lambda c: float(c["daf_m"]))[-2:]
    claim(all(c["road"] == rough for c in largest),
          "the 95th percentile over all cases is driven by the class C cases")
    claim(groups > 8, "the assessment figures take all cases together (more than 8 groups)")
    return {"study_key_results": key_results(out / "report.html"), "study_p95_daf_m": fixed(p95, 2)}


@page("docs/tutorial/03-a-study.md", inputs=["95 %", "1 %"])  # the 95th percentile and its interval; the default convergence tolerance
def a_study(outputs: Outputs) -> Dict[str, str]:
    definition = input_file(STUDY)["study"]
    speeds, roads = definition["axes"]["speed_kmh"], definition["axes"]["road"]
    listing = printout(outputs, "study_list", "study", STUDY, "--list")
    out = outputs.command("study", "study", STUDY)
    cases, summary = read_csv(out / "cases.csv"), read_csv(out / "summary.csv")
    chapter_2 = Crossing(outputs.run("grillage", GRILLAGE_SCENARIO))
    groups = len(speeds) * len(roads)
    larger = groups * 50  # "the same bridge with 50 samples per combination"
    paper_listing = printout(outputs, "paper_study_list", "study", PAPER_STUDY, "--list")
    return {
        "grillage_daf_u_g1": fixed(chapter_2.daf("span1_mid_g1", "deflection"), 2),
        **study_run(cases, printed(out), listing),
        **study_statistics(cases, summary, speeds, roads),
        **study_report(out, cases, groups, roads[-1]),
        "study_larger_cases": str(larger),
        "study_larger_ratio": fixed(larger / len(cases), 1),
        "paper_study_cases": printed_number(paper_listing, r"(\d+) cases"),
    }


# ---------------------------------------------------------------------------------------------
# 04-a-load-test-record.md


def channel(measure: dict, name: str) -> dict:
    return next(c for c in measure["channels"] if c["name"] == name)


def static_method(measured: dict, method: str) -> dict:
    return next(m for m in measured["static_methods"] if m["method"] == method)


def synthetic_record(measure: dict) -> Dict[str, str]:
    """`vbi measure synthetic_4x30.toml`: the low-pass static part, its bias, the frequencies, the update."""
    separation = measure["static_separation"]
    span_length = input_file(SYNTHETIC_RECORD)["measurement"]["span_length_m"]
    claim(abs(separation["pass_frequency_hz"] - measure["speed_m_s"] / span_length) < 1e-12,
          "the pass frequency is v/L_span")
    claim(abs(separation["quasi_static_limit_hz"] - 5 * separation["pass_frequency_hz"]) < 1e-12,
          "f_q is five times the pass frequency")
    claim(separation["rule"] == "half_first_frequency" and not separation["separated"],
          "vbi caps the cut-off at f₁/2 and says that the static part is distorted")
    deflection, strain = channel(measure, "deflection_mid"), channel(measure, "strain_mid")
    reason = separation["reason"]  # quoted by the page

    def quoted_change(name, response):
        changes = rf"{name}: the low-pass at [0-9.]+ Hz changes the peak of the predicted static {response} response"
        return printed_number(reason, changes + r" by (-?[0-9.]+ %)")

    identified = measure["identified_frequencies"]
    claim(measure["identification"] == "subspace_free_vibration",
          "the modes are identified from the free vibration after the exit")
    crossing = measure["preparation"]["crossing"]
    claim(crossing["entry_time_s"] == measure["preparation"]["detected_entry"]["entry_time_s"],
          "the entry is the one found in the record")
    claim(abs(crossing["entry_time_s"] - 2.0 - 3.73 / measure["speed_m_s"]) < 0.02,
          "the entry found is when the load's centroid, 3.7 m behind the first axle, enters")
    frequencies = [fixed(f["frequency_hz"], 3) for f in identified]
    exact_rdm = Decimal(SYNTHETIC_EXACT_DAF["deflection"]) / Decimal(SYNTHETIC_EXACT_DAF["strain"])
    scale = measure["updating"]["stiffness_scale"]
    return {
        "synthetic_speed": fixed(measure["speed_m_s"], 0),
        "synthetic_pass_frequency": fixed(separation["pass_frequency_hz"], 2),
        "synthetic_quasi_static_limit": fixed(separation["quasi_static_limit_hz"], 2),
        "synthetic_first_frequency": fixed(separation["first_frequency_hz"], 2),
        "synthetic_cutoff": fixed(separation["cutoff_hz"], 2),
        "synthetic_daf_u": f4(deflection["daf"]),
        "synthetic_daf_strain": f4(strain["daf"]),
        "synthetic_strain_bias": whole_percent(strain["daf"] / float(SYNTHETIC_EXACT_DAF["strain"]) - 1),
        "synthetic_quoted_cutoff": printed_number(reason, r"deflection_mid: the low-pass at ([0-9.]+) Hz"),
        "synthetic_quoted_deflection_change": quoted_change("deflection_mid", "deflection"),
        "synthetic_quoted_strain_change": quoted_change("strain_mid", "bending_moment"),
        "synthetic_quoted_bias": printed_number(reason, r"biased by about ([-+][0-9.]+ %)"),
        "synthetic_k1_dafs": " and ".join(f4(c["cutoff_mode"]["daf_after"]) for c in (deflection, strain)),
        "synthetic_rdm": f4(measure["rdm"][0]["rdm"]),
        "synthetic_exact_rdm": rounded(exact_rdm, 4),
        "synthetic_frequencies": listed(frequencies),
        "synthetic_damping": f"{span([100 * f['damping_ratio'] for f in identified], 1)} %",
        "synthetic_entry": fixed(crossing["entry_time_s"], 2),
        "synthetic_free_vibration": fixed(measure["duration_s"] - crossing["exit_time_s"], 1),
        "synthetic_strain_interval": fixed(strain["uncertainty"]["expanded_95"], 2),
        "synthetic_stiffness_scale": f4(scale),
        "synthetic_too_soft": whole_percent(scale - 1),
        "synthetic_strain_dynamic": fixed(strain["dynamic_max"], 0),
        "synthetic_strain_static": fixed(strain["static_max"], 0),
    }


def field_record(measure: dict, bridge: ModalAnalysis) -> Dict[str, str]:
    """`vbi measure field_4x30/fast.toml`: crawl-run statics, the drift removed, the free vibration."""
    deflection, strain = channel(measure, "deflection"), channel(measure, "strain")
    crawl = deflection["static_method"] == strain["static_method"] == "crawl_run"
    claim(measure["static_separation"] is None and crawl,
          "each channel's static part is the crawl run's")
    exact_deflection, exact_strain = float(FIELD_EXACT_DAF["deflection"]), float(FIELD_EXACT_DAF["strain"])
    claim(abs(round(deflection["daf"], 4) - exact_deflection) <= 1.0001e-4, "the deflection's DAF is exact to 1e-4")
    drift = {c["channel"]: c["drift_per_s"] for c in measure["preparation"]["corrections"]}
    claim(all(abs(drift[name] / added - 1) < 0.01 for name, added in FIELD_DRIFT_ADDED.items()),
          "the drift removed is the drift added")
    claim(measure["identification"] == "subspace_free_vibration",
          "the frequencies come from the free vibration's subspace identification")
    identified = measure["identified_frequencies"]
    welch = [p["frequency_hz"] for p in measure["spectra"][0]["peaks"]]
    influence_line = static_method(strain, "influence_line_crawl")["daf"]
    claim(abs(influence_line - exact_strain) < abs(strain["daf"] - exact_strain),
          "the influence line's strain DAF is nearer the exact one")
    claim(not static_method(strain, "low_pass")["valid"], "the low-pass fails its check")
    both = lambda values, digits: " and ".join(fixed(v, digits) for v in values)  # noqa: E731
    return {
        "field_daf_u": f4(deflection["daf"]),
        "field_daf_strain": f4(strain["daf"]),
        "field_rdm": f4(measure["rdm"][0]["rdm"]),
        "field_strain_high": percent_one_decimal(strain["daf"] / exact_strain - 1),
        "field_drift_deflection": fixed(drift["deflection"], 5),
        "field_drift_strain": fixed(drift["strain"], 3),
        "field_frequencies": both([f["frequency_hz"] for f in identified], 3),
        "field_damping": both([100 * f["damping_ratio"] for f in identified], 2),
        "field_model_frequencies": both([bridge.frequency(1), bridge.frequency(2)], 3),
        "field_welch_frequencies": both(welch, 2),
        "field_influence_line_strain": f4(influence_line),
        "field_uncertainty_deflection": f4(deflection["uncertainty"]["combined"]),
        "field_uncertainty_strain": f4(strain["uncertainty"]["combined"]),
    }


@page(
    "docs/tutorial/04-a-load-test-record.md",
    inputs=[
        # the synthetic record: its exact DAFs, the formula's frequencies and damping, the model's
        # frequencies in the TOML, the separation check's limit, K1's 95 %
        "1.0963", "1.0510", "3.62", "4.48", "5.87", "2 %", "3.40", "4.21", "5.52", "0.5 %", "95 %",
        # the synthetic truck's load centroid behind its first axle (60, 150, 150 kN at 0, 3.8,
        # 5.15 m: generate_synthetic.py)
        "3.7",
        # the field record: its exact values, its noise, the drift and the damping generate.py put in
        "1.0882", "1.0132", "1.0741", "0.1", "0.010", "0.4", "5 %",
    ],
)
def a_load_test_record(outputs: Outputs) -> Dict[str, str]:
    def measure_json(name, record):
        return json.loads((outputs.command(name, "measure", record) / "measure.json").read_text())

    bridge = ModalAnalysis(outputs.command("field_bridge_modes", "modes", FIELD_BRIDGE, "--modes", "2"))
    return {
        **synthetic_record(measure_json("measure", SYNTHETIC_RECORD)),
        **field_record(measure_json("field", FIELD_RECORD), bridge),
    }
