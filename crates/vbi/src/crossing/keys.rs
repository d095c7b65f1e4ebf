//! One definition per input key of a scenario, as ripgrep defines its flags: name with unit,
//! what is allowed, the default, one line of meaning, and whether a study may vary it. Scenario
//! files, study axes, `vbi check` and the key table of docs/input-format.md all read this table;
//! [`Scenario::set`] is the one place where a key's value enters the typed scenario.
//!
//! Keys whose value names a part (`bridge`, `vehicle`, `road`: a preset, a class or a file) are
//! listed here too, but resolving a file is input and output, which the library does not do:
//! the caller resolves them and sets the typed part itself.

use std::fmt;

use super::{LanePattern, Scenario};
use crate::modal::ModeKind;
use crate::model::BridgeModel;
use crate::solver::TravelDirection;
use crate::units::KMH;

/// What a key accepts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Allowed {
    /// A finite number from `low` to `high` inclusive, in the key's unit.
    Number {
        /// Smallest value.
        low: f64,
        /// Largest value.
        high: f64,
    },
    /// A whole number from `low` to `high` inclusive.
    Whole {
        /// Smallest value.
        low: u64,
        /// Largest value.
        high: u64,
    },
    /// `true` or `false`.
    Bool,
    /// Any text.
    Text,
    /// A preset, class or file name, as described; the caller resolves it.
    Name(&'static str),
    /// A non-empty list of mode kind names.
    ModeKinds,
    /// A list of whole numbers from 1 to the scenario's `modes`.
    ModeCounts,
    /// One of the listed words.
    Choice(&'static [&'static str]),
    /// A road seed, 0 to 2⁶⁴ − 1: an integer up to 2⁶³ − 1 (the largest a TOML integer holds),
    /// or any of them as a decimal string ([`seed_from_value`]).
    Seed,
}

/// The largest seed written as a string in messages, 2⁶⁴ − 1.
const LARGEST_SEED: u64 = u64::MAX;

/// A road seed from a key's value: a whole number from 0 to 2⁶³ − 1, or a decimal string of a
/// whole number from 0 to 2⁶⁴ − 1. Study seeds are 64-bit hashes (half of them above 2⁶³ − 1,
/// which no TOML integer holds), so a study case is replayed with `seed = "<its seed>"`.
/// The one parser of seeds: scenario keys, `[road]` and `[study]` files use it.
pub fn seed_from_value(value: &KeyValue) -> Option<u64> {
    match value {
        KeyValue::Integer(i) => u64::try_from(*i).ok(),
        KeyValue::Text(text) => seed_from_text(text),
        _ => None,
    }
}

/// A seed from its decimal digits (surrounding blanks allowed), 0 to 2⁶⁴ − 1.
pub fn seed_from_text(text: &str) -> Option<u64> {
    let digits = text.trim();
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    digits.parse().ok()
}

/// What a seed may be, for messages.
pub const SEED_ALLOWED: &str = "a whole number from 0 to 9223372036854775807 (2⁶³ − 1, the \
                                largest TOML integer), or a decimal string of one from 0 to \
                                18446744073709551615 (2⁶⁴ − 1), e.g. seed = \"18446744073709551615\"";

impl fmt::Display for Allowed {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Allowed::Number { low, high } => write!(f, "{low} to {high}"),
            Allowed::Whole { low, high } => write!(f, "a whole number from {low} to {high}"),
            Allowed::Bool => write!(f, "`true`, `false`"),
            Allowed::Text => write!(f, "any text"),
            Allowed::Name(what) => write!(f, "{what}"),
            Allowed::ModeKinds => {
                let names: Vec<String> = ModeKind::ALL
                    .iter()
                    .map(|kind| format!("`{}`", kind.name()))
                    .collect();
                write!(f, "non-empty list of {}", names.join(", "))
            }
            Allowed::ModeCounts => write!(f, "each 1 … `modes`"),
            Allowed::Choice(words) => {
                let words: Vec<String> = words.iter().map(|w| format!("`{w}`")).collect();
                write!(f, "{}", words.join(", "))
            }
            Allowed::Seed => write!(
                f,
                "0 to 2⁶³ − 1, or a decimal string up to \"{LARGEST_SEED}\""
            ),
        }
    }
}

/// Where a key may stand.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Place {
    /// In `[scenario]` only.
    Scenario,
    /// In `[scenario]`, and a study may vary it (an axis or a case row).
    ScenarioAndStudy,
    /// Only as a study axis or case row: it changes the base scenario's bridge.
    Study,
}

/// One input key.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Key {
    /// The key as written, with its unit in the name where it has one (`speed_kmh`).
    pub name: &'static str,
    /// Unit of the value, `–` for none.
    pub unit: &'static str,
    /// What is allowed.
    pub allowed: Allowed,
    /// The default, in words.
    pub default: &'static str,
    /// What it means, one line.
    pub meaning: &'static str,
    /// Where it may stand.
    pub place: Place,
}

/// A value given for a key, as read from a file or a Python dict.
#[derive(Debug, Clone, PartialEq)]
pub enum KeyValue {
    /// A whole number as written (seeds need all 64 bits, which an f64 does not hold).
    Integer(i64),
    /// A number.
    Number(f64),
    /// A text.
    Text(String),
    /// A boolean.
    Bool(bool),
    /// A list.
    List(Vec<KeyValue>),
}

impl fmt::Display for KeyValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            KeyValue::Integer(i) => write!(f, "{i}"),
            KeyValue::Number(x) => write!(f, "{}", crate::units::shown(*x)),
            KeyValue::Text(s) => write!(f, "{s}"),
            KeyValue::Bool(b) => write!(f, "{b}"),
            KeyValue::List(items) => {
                let items: Vec<String> = items.iter().map(|i| i.to_string()).collect();
                write!(f, "[{}]", items.join(", "))
            }
        }
    }
}

/// A value that a key does not allow. `index` is the list position at fault, if any.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{message}")]
pub struct KeyError {
    /// The key.
    pub key: &'static str,
    /// The position in a list value, when one element is at fault.
    pub index: Option<usize>,
    /// What is wrong and what is allowed.
    pub message: String,
}

/// Every key of a scenario, in the order they are applied (a key's range may depend on an
/// earlier one: `rerun_modes` on `modes`).
pub const SCENARIO_KEYS: &[Key] = &[
    Key {
        name: "name",
        unit: "–",
        allowed: Allowed::Text,
        default: "the file stem",
        meaning: "name in reports and provenance",
        place: Place::Scenario,
    },
    Key {
        name: "bridge",
        unit: "–",
        allowed: Allowed::Name(
            "`paper-NxL` with N from 1 to 20 and L from 1 to 500 (the paper's box-girder \
             grillage; the paper's nine are N in 2, 3, 4 and L in 20, 30, 40); or a `[bridge]` \
             file",
        ),
        default: "`\"paper-3x30\"`",
        meaning: "the bridge",
        place: Place::ScenarioAndStudy,
    },
    Key {
        name: "span_count",
        unit: "–",
        allowed: Allowed::Whole { low: 1, high: 20 },
        default: "the base bridge's",
        meaning: "number of equal spans of the base bridge (a `paper-NxL` bridge keeps the \
                  paper's girder for its span length)",
        place: Place::Study,
    },
    Key {
        name: "span_length_m",
        unit: "m",
        allowed: Allowed::Number {
            low: 1.0,
            high: 500.0,
        },
        default: "the base bridge's first span",
        meaning: "length of each of the equal spans of the base bridge",
        place: Place::Study,
    },
    Key {
        name: "damping_ratio",
        unit: "–",
        allowed: Allowed::Number {
            low: 0.0,
            high: 0.99,
        },
        default: "the base bridge's",
        meaning: "modal damping ratio ζ of every mode of the bridge",
        place: Place::Study,
    },
    Key {
        name: "vehicle",
        unit: "–",
        allowed: Allowed::Name("a preset of `vbi vehicle list`, or a `[vehicle]` file"),
        default: "`\"tractor-semitrailer-5axle\"`",
        meaning: "the vehicle",
        place: Place::ScenarioAndStudy,
    },
    Key {
        name: "road",
        unit: "–",
        allowed: Allowed::Name(
            "`smooth`, `good`, `medium`, `poor`, ISO 8608 `A` … `H` or Dodds & Robson \
             `dr-very-good` … `dr-very-poor`; or a `[road]` file",
        ),
        default: "`\"medium\"`",
        meaning: "the road surface (a class name takes every other `[road]` default: 100 m \
                  approach, 30 m exit)",
        place: Place::ScenarioAndStudy,
    },
    Key {
        name: "seed",
        unit: "–",
        allowed: Allowed::Seed,
        default: "the road's `seed` (1)",
        meaning: "seed of the road profile (replaces the road's own)",
        place: Place::Scenario,
    },
    Key {
        name: "speed_kmh",
        unit: "km/h",
        allowed: Allowed::Number {
            low: 0.1,
            high: 500.0,
        },
        default: "80",
        meaning: "vehicle speed v (at the deck entry when `acceleration_ms2` is not 0)",
        place: Place::ScenarioAndStudy,
    },
    Key {
        name: "lateral_position_m",
        unit: "m",
        allowed: Allowed::Number {
            low: -50.0,
            high: 50.0,
        },
        default: "0",
        meaning: "vehicle centreline from the deck centreline, left (+y) positive; ignored on a \
                  beam",
        place: Place::ScenarioAndStudy,
    },
    Key {
        name: "direction",
        unit: "–",
        allowed: Allowed::Choice(&["forward", "backward"]),
        default: "`forward`",
        meaning: "direction of travel: `forward` from the first support to the last, `backward` \
                  the other way (the vehicle's left is then the deck's right)",
        place: Place::ScenarioAndStudy,
    },
    Key {
        name: "acceleration_ms2",
        unit: "m/s²",
        allowed: Allowed::Number {
            low: -10.0,
            high: 10.0,
        },
        default: "0",
        meaning: "constant acceleration (negative: braking) from the start of the approach until \
                  the last axle leaves the deck; `speed_kmh` is then the speed at the deck entry",
        place: Place::ScenarioAndStudy,
    },
    Key {
        name: "platoon_size",
        unit: "–",
        allowed: Allowed::Whole { low: 1, high: 50 },
        default: "1",
        meaning: "the vehicle repeated this many times in its lane, each `platoon_gap_m` behind \
                  the one before",
        place: Place::ScenarioAndStudy,
    },
    Key {
        name: "platoon_gap_m",
        unit: "m",
        allowed: Allowed::Number {
            low: 0.0,
            high: 10000.0,
        },
        default: "10",
        meaning: "clear gap between consecutive vehicles of the platoon (last tyre to next front \
                  axle)",
        place: Place::ScenarioAndStudy,
    },
    Key {
        name: "lane_pattern",
        unit: "–",
        allowed: Allowed::Choice(&LanePattern::NAMES),
        default: "`single`",
        meaning:
            "the vehicle's arrangement over two lanes, lane 1 at `lateral_position_m` = y and \
                  lane 2 its mirror at −y: `single` the vehicle alone; `side_by_side` a copy \
                  abreast in lane 2, same direction and speed law; `meeting` a copy in lane 2 \
                  travelling the other way, both reaching their deck entries together. Refused \
                  with `platoon_size` > 1, `[[traffic]]`, `[traffic_stream]`, or lanes that \
                  overlap (|y| at most the half-width over the wheels)",
        place: Place::ScenarioAndStudy,
    },
    Key {
        name: "element_length_m",
        unit: "m",
        allowed: Allowed::Number {
            low: 0.01,
            high: 10.0,
        },
        default: "1.0",
        meaning: "longitudinal element length of the FE mesh; at most 2000 elements in a span \
                  (a finer mesh loses more to round-off than it gains)",
        place: Place::ScenarioAndStudy,
    },
    Key {
        name: "modes",
        unit: "–",
        allowed: Allowed::Whole { low: 1, high: 1000 },
        default: "50",
        meaning: "number of modes solved for (the lowest frequencies); the basis keeps those of \
                  the kinds in `mode_kinds`",
        place: Place::ScenarioAndStudy,
    },
    Key {
        name: "mode_kinds",
        unit: "–",
        allowed: Allowed::ModeKinds,
        default: "`[\"vertical_bending\", \"differential_bending\", \"torsion\"]`",
        meaning: "mode kinds kept (a beam has only vertical bending)",
        place: Place::Scenario,
    },
    Key {
        name: "time_step_s",
        unit: "s",
        allowed: Allowed::Number {
            low: 1e-6,
            high: 0.1,
        },
        default: "min(1 ms, T_b/20, T_v/20, road sample spacing / v)",
        meaning: "Newmark time step Δt; T_b the period of the highest kept mode that does not \
                  respond quasi-statically (docs/theory.md; a note names the modes left), T_v \
                  the vehicle's shortest; a larger Δt gives a warning naming the first \
                  under-resolved bridge or vehicle mode",
        place: Place::ScenarioAndStudy,
    },
    Key {
        name: "time_step_check",
        unit: "–",
        allowed: Allowed::Bool,
        default: "`true`",
        meaning: "with the default Δt: every crossing run again at 2Δt, and Δt halved (up to 3 \
                  times) until every deflection and moment DAF differs by at most 0.1 % from \
                  the run at twice the step (docs/theory.md, \"The check of the time step\"); \
                  the change is the output `daf_change_dt`. `false`: one run at the default \
                  Δt, unchecked",
        place: Place::Scenario,
    },
    Key {
        name: "newmark_beta",
        unit: "–",
        allowed: Allowed::Number {
            low: 0.0,
            high: 0.5,
        },
        default: "0.25",
        meaning: "Newmark β (0.25: average acceleration)",
        place: Place::Scenario,
    },
    Key {
        name: "newmark_gamma",
        unit: "–",
        allowed: Allowed::Number {
            low: 0.5,
            high: 1.0,
        },
        default: "0.5",
        meaning: "Newmark γ; 2β < γ is only conditionally stable (an error if unstable for a kept \
                  mode)",
        place: Place::Scenario,
    },
    Key {
        name: "free_vibration_s",
        unit: "s",
        allowed: Allowed::Number {
            low: 0.0,
            high: 600.0,
        },
        default: "two periods of mode 1",
        meaning: "run time after the last tyre leaves the deck",
        place: Place::Scenario,
    },
    Key {
        name: "convergence_tolerance",
        unit: "–",
        allowed: Allowed::Number {
            low: 1e-9,
            high: 1.0,
        },
        default: "0.01",
        meaning: "relative tolerance of the convergence mode CM",
        place: Place::Scenario,
    },
    Key {
        name: "rerun_modes",
        unit: "–",
        allowed: Allowed::ModeCounts,
        default: "`[]`",
        meaning: "mode counts K for which the crossing is solved again with only the first K \
                  kept modes (the second definition of DAF(K)); reported as `truncated_runs` in \
                  the JSON and one line each in the table",
        place: Place::Scenario,
    },
    Key {
        name: "tyre_separation",
        unit: "–",
        allowed: Allowed::Bool,
        default: "`true`",
        meaning: "whether a tyre may leave the road: a tyre whose force would turn tensile lifts \
                  off and carries no force until it lands (active set per time step); `false` \
                  keeps every tyre bonded to the road (the linear model, tensile forces \
                  allowed). Either way each loss of contact is reported",
        place: Place::Scenario,
    },
    // Damage scenarios (issue 12, part 6): the factor on E of a stiffness loss as a study axis.
    Key {
        name: "damage_factor",
        unit: "–",
        allowed: Allowed::Number {
            low: 0.01,
            high: 1.0,
        },
        default: "the base bridge's",
        meaning: "factor on E of the base bridge's first `[[bridge.stiffness_loss]]` region (1 = \
                  intact); the base bridge must have one",
        place: Place::Study,
    },
    // Damage extent and a softened support as study axes (issue 12).
    Key {
        name: "damage_start_m",
        unit: "m",
        allowed: Allowed::Number {
            low: 0.0,
            high: 10000.0,
        },
        default: "the base bridge's",
        meaning: "start x of the base bridge's first `[[bridge.stiffness_loss]]` region, from the \
                  first support (its girder and factor kept); the base bridge must have one; \
                  0 to the bridge length, and below the region's end",
        place: Place::Study,
    },
    Key {
        name: "damage_end_m",
        unit: "m",
        allowed: Allowed::Number {
            low: 0.0,
            high: 10000.0,
        },
        default: "the base bridge's",
        meaning: "end x of the base bridge's first `[[bridge.stiffness_loss]]` region; the base \
                  bridge must have one; above the region's start, at most the bridge length",
        place: Place::Study,
    },
    Key {
        name: "support_stiffness_n_per_m",
        unit: "N/m",
        allowed: Allowed::Number {
            low: 0.0,
            high: 1e12,
        },
        default: "the base bridge's",
        meaning: "vertical spring stiffness per bearing of the base bridge's first \
                  `[[bridge.support_change]]` (0 removes the support); the base bridge must \
                  have one, and the bridge must stay held",
        place: Place::Study,
    },
];

/// The keys that change the bridge analysis (FE model, modes, influence lines): cases that
/// differ in one of them need a modal analysis of their own. A test checks this list against
/// what each key changes in a scenario.
pub const BRIDGE_KEYS: [&str; 10] = [
    "bridge",
    "span_count",
    "span_length_m",
    "damping_ratio",
    "modes",
    "element_length_m",
    "damage_factor",
    "damage_start_m",
    "damage_end_m",
    "support_stiffness_n_per_m",
];

/// Refuses a first `[[bridge.stiffness_loss]]` region whose start is not below its end, after
/// `damage_start_m` and `damage_end_m` have been set (each is checked against the bridge's
/// length when set; their order only when both are known). The error names `damage_end_m`.
pub fn check_damage_region(bridge: &BridgeModel) -> Result<(), KeyError> {
    match bridge.damage().stiffness_losses.first() {
        Some(loss) if loss.start >= loss.end => Err(KeyError {
            key: "damage_end_m",
            index: None,
            message: format!(
                "the stiffness-loss region would run from {} m to {} m; expected \
                 `damage_start_m` < `damage_end_m`",
                crate::units::shown(loss.start),
                crate::units::shown(loss.end)
            ),
        }),
        _ => Ok(()),
    }
}

/// The key of that name, if there is one.
pub fn key(name: &str) -> Option<&'static Key> {
    SCENARIO_KEYS.iter().find(|k| k.name == name)
}

/// The names of the keys that may stand in `place` (a scenario file, or a study's axes), for
/// messages.
pub fn names_for(scenario_file: bool) -> Vec<&'static str> {
    SCENARIO_KEYS
        .iter()
        .filter(|k| match k.place {
            Place::Scenario => scenario_file,
            Place::ScenarioAndStudy => true,
            Place::Study => !scenario_file,
        })
        .map(|k| k.name)
        .collect()
}

impl Key {
    /// What is allowed, as a message's "expected …" part, with the unit.
    pub fn expected(&self) -> String {
        match self.allowed {
            Allowed::Number { low, high } if self.unit != "–" => {
                format!("a number from {low} to {high} {}", self.unit)
            }
            Allowed::Number { low, high } => format!("a number from {low} to {high}"),
            other => other.to_string(),
        }
    }

    fn refuse(&self, value: &KeyValue) -> KeyError {
        KeyError {
            key: self.name,
            index: None,
            message: format!("`{value}` is not allowed; expected {}", self.expected()),
        }
    }

    /// The value as a number in range.
    pub fn number(&self, value: &KeyValue) -> Result<f64, KeyError> {
        let x = match value {
            KeyValue::Integer(i) => *i as f64,
            KeyValue::Number(x) => *x,
            _ => return Err(self.refuse(value)),
        };
        match self.allowed {
            Allowed::Number { low, high } if x.is_finite() && x >= low && x <= high => Ok(x),
            _ => Err(self.refuse(value)),
        }
    }

    /// The value as a whole number in range: an integer, or a number with no fraction that an
    /// f64 holds exactly (below 2⁵³).
    pub fn whole(&self, value: &KeyValue) -> Result<u64, KeyError> {
        let Allowed::Whole { low, high } = self.allowed else {
            return Err(self.refuse(value));
        };
        let whole = match value {
            KeyValue::Integer(i) => u64::try_from(*i).ok(),
            KeyValue::Number(x)
                if x.fract() == 0.0 && *x >= 0.0 && *x < 9.007_199_254_740_992e15 =>
            {
                Some(*x as u64)
            }
            _ => None,
        };
        match whole {
            Some(w) if w >= low && w <= high => Ok(w),
            _ => Err(self.refuse(value)),
        }
    }
}

/// The row of the key table for one key (docs/input-format.md).
fn markdown_row(key: &Key) -> String {
    let study = match key.place {
        Place::Scenario => "–",
        Place::ScenarioAndStudy => "yes",
        Place::Study => "only",
    };
    format!(
        "| `{}` | {} | {} | {} | {} | {} |",
        key.name, key.unit, key.default, key.allowed, study, key.meaning
    )
}

/// The key table of docs/input-format.md, generated from [`SCENARIO_KEYS`]; a test keeps the
/// document equal to it.
pub fn markdown_table() -> String {
    let mut lines = vec![
        "| key | unit | default | allowed | study axis | meaning |".to_string(),
        "|---|---|---|---|---|---|".to_string(),
    ];
    lines.extend(SCENARIO_KEYS.iter().map(markdown_row));
    lines.join("\n")
}

impl Scenario {
    /// Sets one key from its value: the one place where a key enters the typed scenario, in SI
    /// units (`speed_kmh` is converted here, once). Names (`bridge`, `vehicle`, `road`) are the
    /// caller's to resolve: they are refused here.
    pub fn set(&mut self, name: &str, value: &KeyValue) -> Result<(), KeyError> {
        let Some(key) = key(name) else {
            return Err(KeyError {
                key: "",
                index: None,
                message: format!("unknown key `{name}`"),
            });
        };
        match key.name {
            "name" => match value {
                KeyValue::Text(text) => self.name = text.clone(),
                _ => return Err(key.refuse(value)),
            },
            "span_count" | "span_length_m" | "element_length_m"
                if !self.bridge.model.is_resizable() =>
            {
                return Err(KeyError {
                    key: key.name,
                    index: None,
                    message: "an imported model's spans and mesh are its matrices'; expected \
                              a bridge of vbi's own (a continuous beam or a grillage) to set \
                              them"
                        .into(),
                })
            }
            "span_count" => self.resize_spans(Some(key.whole(value)? as usize), None),
            "span_length_m" => self.resize_spans(None, Some(key.number(value)?)),
            "damping_ratio" => set_uniform_damping(&mut self.bridge.model, key.number(value)?),
            "damage_factor" => set_damage_factor(&mut self.bridge.model, key, value)?,
            "damage_start_m" | "damage_end_m" => {
                set_damage_extent(&mut self.bridge.model, key, value)?
            }
            "support_stiffness_n_per_m" => {
                set_support_stiffness(&mut self.bridge.model, key, value)?
            }
            "lane_pattern" => {
                self.lane_pattern = match value {
                    KeyValue::Text(text) => LanePattern::from_name(text),
                    _ => None,
                }
                .ok_or_else(|| key.refuse(value))?
            }
            "seed" => self.road.seed = seed_from_value(value).ok_or_else(|| key.refuse(value))?,
            "speed_kmh" => self.motion.speed = key.number(value)? * KMH,
            "lateral_position_m" => self.motion.lateral_position = key.number(value)?,
            "direction" => self.motion.direction = direction(key, value)?,
            "acceleration_ms2" => self.motion.acceleration = key.number(value)?,
            "platoon_size" => self.platoon_size = key.whole(value)? as usize,
            "platoon_gap_m" => self.platoon_gap = key.number(value)?,
            "element_length_m" => self.bridge.mesh.element_length = key.number(value)?,
            "modes" => self.bridge.modal.mode_count = key.whole(value)? as usize,
            "mode_kinds" => self.bridge.modal.keep_kinds = mode_kinds(key, value)?,
            "time_step_s" => self.solver.time_step = Some(key.number(value)?),
            "newmark_beta" => self.solver.newmark_beta = key.number(value)?,
            "newmark_gamma" => self.solver.newmark_gamma = key.number(value)?,
            "free_vibration_s" => self.free_vibration_duration = Some(key.number(value)?),
            "convergence_tolerance" => self.analysis.convergence_tolerance = key.number(value)?,
            "rerun_modes" => {
                self.rerun_mode_counts = mode_counts(key, value, self.bridge.modal.mode_count)?
            }
            "tyre_separation" => match value {
                KeyValue::Bool(b) => self.solver.tyre_separation = *b,
                _ => return Err(key.refuse(value)),
            },
            "time_step_check" => match value {
                KeyValue::Bool(b) => self.solver.time_step_check = *b,
                _ => return Err(key.refuse(value)),
            },
            _ => {
                return Err(KeyError {
                    key: key.name,
                    index: None,
                    message: format!("`{}` names a part: resolve it, then set it", key.name),
                })
            }
        }
        Ok(())
    }
}

/// A direction of travel from its word.
pub fn direction(key: &Key, value: &KeyValue) -> Result<TravelDirection, KeyError> {
    match value {
        KeyValue::Text(text) if text == "forward" => Ok(TravelDirection::Forward),
        KeyValue::Text(text) if text == "backward" => Ok(TravelDirection::Backward),
        _ => Err(key.refuse(value)),
    }
}

/// A list value's elements, or the refusal of a non-list.
fn elements<'v>(key: &Key, value: &'v KeyValue) -> Result<&'v [KeyValue], KeyError> {
    match value {
        KeyValue::List(items) => Ok(items),
        other => Err(key.refuse(other)),
    }
}

fn mode_kinds(key: &Key, value: &KeyValue) -> Result<Vec<ModeKind>, KeyError> {
    let items = elements(key, value)?;
    if items.is_empty() {
        return Err(KeyError {
            key: key.name,
            index: None,
            message: format!(
                "an empty list keeps no mode; expected at least one of {}",
                ModeKind::names_in_words()
            ),
        });
    }
    items
        .iter()
        .enumerate()
        .map(|(i, item)| {
            let kind = match item {
                KeyValue::Text(name) => ModeKind::from_name(name),
                _ => None,
            };
            kind.ok_or_else(|| KeyError {
                key: key.name,
                index: Some(i),
                message: format!(
                    "unknown mode kind `{item}`; expected {}",
                    ModeKind::names_in_words()
                ),
            })
        })
        .collect()
}

fn mode_counts(key: &Key, value: &KeyValue, modes: usize) -> Result<Vec<usize>, KeyError> {
    elements(key, value)?
        .iter()
        .enumerate()
        .map(|(i, item)| match item {
            KeyValue::Integer(k) if *k >= 1 && *k <= modes as i64 => Ok(*k as usize),
            _ => Err(KeyError {
                key: key.name,
                index: Some(i),
                message: format!(
                    "{item} is not allowed; expected a mode count from 1 to {modes} (`modes`)"
                ),
            }),
        })
        .collect()
}

impl Scenario {
    /// Sets the span count or the span length of the bridge, keeping the other. A paper-style
    /// bridge (`paper-NxL`) keeps the paper's girder for its span length (its §4.1); any other
    /// keeps its section and its end supports, interior supports like its first interior one.
    fn resize_spans(&mut self, count: Option<usize>, length: Option<f64>) {
        let model = &mut self.bridge.model;
        let spans = model.span_lengths();
        let (n, l) = (count.unwrap_or(spans.len()), length.unwrap_or(spans[0]));
        if self.bridge_label.starts_with("paper-") && self.bridge_label.ends_with("(preset)") {
            let damping = model.damping_ratio();
            *model = crate::model::paper_bridge(n, l);
            set_damping(model, damping);
            self.bridge_label = format!("paper-{n}x{l} (preset)");
        } else {
            model.resize_spans(n, l);
            self.bridge_label = format!("{} with {n} × {l} m spans", self.bridge_label);
        }
    }
}

fn set_damping(bridge: &mut BridgeModel, damping: f64) {
    match bridge {
        BridgeModel::ContinuousBeam(b) => b.damping_ratio = damping,
        BridgeModel::Grillage(g) => g.damping_ratio = damping,
        BridgeModel::ImportedMatrices(m) => m.damping_ratio = damping,
        BridgeModel::ImportedModes(m) => {
            std::sync::Arc::make_mut(&mut m.data).default_damping_ratio = damping
        }
    }
}

/// The `damping_ratio` key: one ratio for every mode, in place of a per-mode law if the bridge
/// has one.
fn set_uniform_damping(bridge: &mut BridgeModel, damping: f64) {
    set_damping(bridge, damping);
    match bridge {
        BridgeModel::ContinuousBeam(b) => b.mode_damping = None,
        BridgeModel::Grillage(g) => g.mode_damping = None,
        BridgeModel::ImportedMatrices(m) => m.mode_damping = None,
        // The key gives every mode the one ratio: the modes' own ratios give way.
        BridgeModel::ImportedModes(m) => {
            let data = std::sync::Arc::make_mut(&mut m.data);
            data.damping_ratios.iter_mut().for_each(|r| *r = None);
        }
    }
}

/// The `damage_factor` key: the factor on E of the bridge's first stiffness loss.
fn set_damage_factor(
    bridge: &mut BridgeModel,
    key: &Key,
    value: &KeyValue,
) -> Result<(), KeyError> {
    let factor = key.number(value)?;
    match bridge.damage_mut().stiffness_losses.first_mut() {
        Some(loss) => {
            loss.elastic_modulus_factor = factor;
            Ok(())
        }
        None => Err(KeyError {
            key: key.name,
            index: None,
            message: "the bridge has no stiffness loss to vary; expected a bridge file with a \
                      [[bridge.stiffness_loss]] region"
                .into(),
        }),
    }
}

/// The `damage_start_m` and `damage_end_m` keys: one end of the bridge's first stiffness loss,
/// on the bridge (0 to its length).
fn set_damage_extent(
    bridge: &mut BridgeModel,
    key: &Key,
    value: &KeyValue,
) -> Result<(), KeyError> {
    let x = key.number(value)?;
    let length = bridge.length();
    if x > length {
        return Err(KeyError {
            key: key.name,
            index: None,
            message: format!(
                "{x} m is outside the bridge; expected 0 to its length, {length} m (from the \
                 first support)"
            ),
        });
    }
    let Some(loss) = bridge.damage_mut().stiffness_losses.first_mut() else {
        return Err(KeyError {
            key: key.name,
            index: None,
            message: "the bridge has no stiffness loss to vary; expected a bridge file with a \
                      [[bridge.stiffness_loss]] region"
                .into(),
        });
    };
    if key.name == "damage_start_m" {
        loss.start = x;
    } else {
        loss.end = x;
    }
    Ok(())
}

/// The `support_stiffness_n_per_m` key: the vertical stiffness of the bridge's first changed
/// support.
fn set_support_stiffness(
    bridge: &mut BridgeModel,
    key: &Key,
    value: &KeyValue,
) -> Result<(), KeyError> {
    let stiffness = key.number(value)?;
    match bridge.damage_mut().support_changes.first_mut() {
        Some(change) => {
            change.vertical_stiffness = stiffness;
            Ok(())
        }
        None => Err(KeyError {
            key: key.name,
            index: None,
            message: "the bridge has no changed support to vary; expected a bridge file with a \
                      [[bridge.support_change]] table"
                .into(),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The built-in scenario with a stiffness loss (factor 0.5 over 10 m of every girder), so
    /// that every key has something to change.
    fn base() -> Scenario {
        let mut scenario = Scenario::default();
        scenario
            .bridge
            .model
            .damage_mut()
            .stiffness_losses
            .push(crate::model::StiffnessLoss {
                start: 10.0,
                end: 20.0,
                girder: None,
                elastic_modulus_factor: 0.5,
            });
        scenario
            .bridge
            .model
            .damage_mut()
            .support_changes
            .push(crate::model::SupportChange {
                support: 1,
                vertical_stiffness: 1e9,
            });
        scenario.motion.lateral_position = -1.875;
        scenario
    }

    /// A value in range for a key, away from its default where it can be.
    fn sample(key: &Key) -> Option<KeyValue> {
        // Keys whose range depends on the bridge (90 m long; its region is 10 to 20 m).
        match key.name {
            "damage_start_m" => return Some(KeyValue::Number(12.0)),
            "damage_end_m" => return Some(KeyValue::Number(18.0)),
            _ => {}
        }
        Some(match key.allowed {
            Allowed::Number { high, .. } => KeyValue::Number(high),
            Allowed::Whole { low, high } => KeyValue::Integer((low + 4).min(high) as i64),
            Allowed::Bool => KeyValue::Bool(false),
            Allowed::Text => KeyValue::Text("a name".into()),
            Allowed::ModeKinds => KeyValue::List(vec![KeyValue::Text("lateral".into())]),
            Allowed::ModeCounts => KeyValue::List(vec![KeyValue::Integer(3)]),
            Allowed::Seed => KeyValue::Text(LARGEST_SEED.to_string()),
            Allowed::Choice(words) => KeyValue::Text(words[words.len() - 1].into()),
            Allowed::Name(_) => return None,
        })
    }

    #[test]
    fn every_key_but_the_parts_is_set_by_scenario_set_and_changes_the_scenario() {
        for key in SCENARIO_KEYS {
            let Some(value) = sample(key) else {
                continue;
            };
            let mut scenario = base();
            scenario
                .set(key.name, &value)
                .unwrap_or_else(|e| panic!("{}: {e}", key.name));
            assert_ne!(scenario, base(), "{} changed nothing", key.name);
        }
    }

    #[test]
    fn values_out_of_range_or_of_the_wrong_type_are_refused_naming_the_key() {
        for key in SCENARIO_KEYS {
            let bad = match key.allowed {
                Allowed::Number { high, .. } => KeyValue::Number(2.0 * high.abs() + 1.0),
                Allowed::Whole { .. } => KeyValue::Number(0.5),
                Allowed::Name(_) => continue,
                _ => KeyValue::Number(f64::NAN),
            };
            let error = Scenario::default().set(key.name, &bad).unwrap_err();
            assert_eq!(error.key, key.name);
            assert!(error.message.contains("not allowed"), "{}", error.message);
        }
    }

    /// [`BRIDGE_KEYS`] is what changes the bridge: setting any other key leaves the scenario's
    /// bridge spec unchanged, and setting one of these changes it.
    #[test]
    fn the_bridge_keys_are_the_keys_that_change_the_bridge_spec() {
        for key in SCENARIO_KEYS {
            let Some(value) = sample(key) else {
                assert!(key.name == "bridge" || !BRIDGE_KEYS.contains(&key.name));
                continue;
            };
            let mut scenario = base();
            scenario.set(key.name, &value).expect("in range");
            let changed = scenario.bridge != base().bridge;
            // mode_kinds changes the bridge spec but a study may not vary it.
            if key.place != Place::Scenario {
                assert_eq!(changed, BRIDGE_KEYS.contains(&key.name), "{}", key.name);
            }
        }
    }

    #[test]
    fn a_damage_factor_needs_a_stiffness_loss_to_vary() {
        let error = Scenario::default()
            .set("damage_factor", &KeyValue::Number(0.5))
            .unwrap_err();
        assert_eq!(error.key, "damage_factor");
        assert!(
            error.message.contains("no stiffness loss"),
            "{}",
            error.message
        );
        let mut scenario = base();
        scenario
            .set("damage_factor", &KeyValue::Number(0.7))
            .unwrap();
        assert_eq!(
            scenario.bridge.model.damage().stiffness_losses[0].elastic_modulus_factor,
            0.7
        );
    }

    #[test]
    fn the_damage_extent_keys_stay_on_the_bridge_and_keep_the_start_below_the_end() {
        let mut scenario = base();
        scenario
            .set("damage_end_m", &KeyValue::Number(30.0))
            .unwrap();
        scenario
            .set("damage_start_m", &KeyValue::Number(25.0))
            .unwrap();
        let loss = scenario.bridge.model.damage().stiffness_losses[0];
        assert_eq!(
            (loss.start, loss.end, loss.elastic_modulus_factor),
            (25.0, 30.0, 0.5)
        );
        assert_eq!(check_damage_region(&scenario.bridge.model), Ok(()));
        // 90 m long: 95 m is off the bridge.
        let error = scenario
            .set("damage_end_m", &KeyValue::Number(95.0))
            .unwrap_err();
        assert!(
            error.message.contains("outside the bridge"),
            "{}",
            error.message
        );
        scenario
            .set("damage_start_m", &KeyValue::Number(30.0))
            .unwrap();
        let error = check_damage_region(&scenario.bridge.model).unwrap_err();
        assert_eq!(error.key, "damage_end_m");
        assert!(error.message.contains("`damage_start_m` < `damage_end_m`"));
        let error = Scenario::default()
            .set("damage_start_m", &KeyValue::Number(5.0))
            .unwrap_err();
        assert!(
            error.message.contains("no stiffness loss"),
            "{}",
            error.message
        );
    }

    #[test]
    fn support_stiffness_sets_the_first_changed_support_and_needs_one() {
        let mut scenario = base();
        scenario
            .set("support_stiffness_n_per_m", &KeyValue::Number(2e8))
            .unwrap();
        let change = scenario.bridge.model.damage().support_changes[0];
        assert_eq!((change.support, change.vertical_stiffness), (1, 2e8));
        let error = Scenario::default()
            .set("support_stiffness_n_per_m", &KeyValue::Number(2e8))
            .unwrap_err();
        assert!(
            error.message.contains("no changed support"),
            "{}",
            error.message
        );
        assert!(base()
            .set("support_stiffness_n_per_m", &KeyValue::Number(-1.0))
            .is_err());
    }

    #[test]
    fn speed_is_converted_from_km_h_once() {
        let mut scenario = Scenario::default();
        scenario.set("speed_kmh", &KeyValue::Integer(72)).unwrap();
        assert_eq!(scenario.motion.speed, 72.0 * KMH);
    }

    #[test]
    fn a_seed_takes_every_integer_that_a_file_can_hold() {
        let mut scenario = Scenario::default();
        scenario.set("seed", &KeyValue::Integer(i64::MAX)).unwrap();
        assert_eq!(scenario.road.seed, i64::MAX as u64);
        assert!(scenario.set("seed", &KeyValue::Integer(-1)).is_err());
        // Above 2⁶³ − 1 as a decimal string (study seeds are 64-bit hashes, issue 14).
        scenario
            .set("seed", &KeyValue::Text("18446744073709551615".into()))
            .unwrap();
        assert_eq!(scenario.road.seed, u64::MAX);
        for bad in ["18446744073709551616", "-1", "+5", "1e3", ""] {
            let error = scenario
                .set("seed", &KeyValue::Text(bad.into()))
                .unwrap_err();
            assert!(
                error.message.contains("not allowed"),
                "{bad}: {}",
                error.message
            );
        }
    }

    /// docs/input-format.md holds the key table generated from [`SCENARIO_KEYS`], so that the
    /// reference cannot drift from the code.
    #[test]
    fn the_input_format_document_holds_the_generated_key_table() {
        let document = include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../docs/input-format.md"
        ));
        let begin = "<!-- scenario keys: generated from vbi::crossing::keys -->\n";
        let end = "\n<!-- end of scenario keys -->";
        let start = document.find(begin).expect("begin marker") + begin.len();
        let stop = document[start..].find(end).expect("end marker") + start;
        assert_eq!(
            &document[start..stop],
            markdown_table(),
            "regenerate the table: cargo test -p vbi --lib print_key_table -- --ignored --nocapture"
        );
    }

    /// Prints the key table for docs/input-format.md.
    #[test]
    #[ignore]
    fn print_key_table() {
        println!("{}", markdown_table());
    }
}
