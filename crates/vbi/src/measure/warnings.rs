//! What the reader of a measurement must know before using its numbers (issue 52, item 5): each
//! warning is printed under the results, listed in measure.json's `warnings` and in the
//! report's key results, so that no DAF or frequency reaches an assessment without it.

use serde::Serialize;

use super::measurement::Baseline;
use super::{ForcedContentCheck, MeasurementSummary};

/// A damping ratio above which an identified peak is flagged as unlikely to be a bridge mode
/// [-]. Measured bridge damping ratios lie mostly between 0.5 % and 5 %; the validation battery
/// of issue 52 (`scripts/measure_battery`, docs/verification.md §29a) found the crossing's
/// forced content identified as "modes" with 9–13 % damping. An engineering threshold, not a
/// code limit: a flag, never a refusal.
pub const IMPLAUSIBLE_DAMPING_RATIO: f64 = 0.08;

/// One warning of a measurement: what it is and its message (measure.json writes both).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MeasureWarning {
    /// What it is, with its numbers.
    #[serde(flatten)]
    pub kind: MeasureWarningKind,
    /// The sentence printed under the results and in the report.
    pub message: String,
}

impl From<MeasureWarningKind> for MeasureWarning {
    fn from(kind: MeasureWarningKind) -> Self {
        let message = kind.to_string();
        MeasureWarning { kind, message }
    }
}

impl std::fmt::Display for MeasureWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

/// The kinds of warning of a measurement.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum MeasureWarningKind {
    /// The channel's DAF rests on a static method whose own check failed (a low-pass that does
    /// not separate the quasi-static from the dynamic content, or whose separation check
    /// fails): the DAF carries a bias that its stated uncertainty does not include.
    StaticMethodNotValid {
        /// The channel.
        channel: String,
        /// The method behind its DAF.
        method: &'static str,
        /// The methods the record allows whose check holds, with their DAF.
        valid_alternatives: Vec<StaticAlternative>,
    },
    /// A channel's DAF rests on the crawl run, whose baseline could only be an offset (or none):
    /// the crawl record holds no quiet window after its exit, so a drift of the logger over the
    /// crawl (a minute or more at walking pace) enters its static part unseen.
    CrawlBaselineWithoutDrift {
        /// The crawl's baseline correction (`offset` or `none`).
        baseline: Baseline,
        /// The crawl's exit time and how it was found, when known.
        exit: Option<String>,
    },
    /// The identification read the crossing, but the record lacks the vehicle's exit time or a
    /// second of free vibration after it, which tell the bridge's modes from the crossing's
    /// forced content.
    ForcedContentNotChecked {
        /// The first identified frequency, unconfirmed [Hz].
        first_frequency_hz: Option<f64>,
    },
    /// The stated speed differs from the one the record's response shows by more than the
    /// check's tolerance ([`super::SpeedCheck`]).
    ImplausibleSpeed {
        /// The stated speed [km/h].
        stated_kmh: f64,
        /// The speed the record's response fits best [km/h].
        fitted_kmh: f64,
        /// The channel read.
        channel: String,
    },
    /// The weighed axle loads rest on an entry time fitted from the record: their stated
    /// uncertainty is linearised about it and does not cover a misplaced passage (tested: on
    /// a vibrating record the fitted entry moves by up to 0.15 s and the axle loads by tens of
    /// per cent); the gross weight does not depend on it.
    WeighingEntryFitted {
        /// The fitted entry time [s].
        entry_time_s: f64,
    },
    /// The weights rest on the bridge model's influence line, not fitted to the record's
    /// frequencies: the model's stiffness error enters them one to one.
    WeighingOnUnfittedModel {
        /// The channels weighed with the model's line.
        channels: Vec<String>,
    },
    /// Influence-line static parts that rest on the weighed axle loads (none were given): the
    /// static maximum follows the weighed loads, whose split between the axles a record
    /// resolves least well and whose sum carries the bridge's low-frequency amplification at
    /// speed (on the paper's 3 × 30 m bridge at 80 km/h: gross +1.7 %, the DAFs 1.3–1.7 % low).
    StaticPartOnWeighedLoads {
        /// The channels.
        channels: Vec<String>,
    },
    /// Weighed axle loads of zero or less, or axles the record does not tell apart: the
    /// record does not resolve the axles (closely spaced axles on a long span, the vehicle's
    /// and the bridge's dynamics); the gross weight may still hold.
    WeighingAxlesNotResolved {
        /// The axles (1 = the first) weighed at zero or less.
        axles: Vec<usize>,
        /// Whether the normal equations are ill-conditioned ([`super::ILL_CONDITIONED`]).
        ill_conditioned: bool,
    },
    /// An identified mode's damping ratio exceeds [`IMPLAUSIBLE_DAMPING_RATIO`].
    ImplausibleDamping {
        /// Its frequency [Hz].
        frequency_hz: f64,
        /// Its damping ratio [-].
        damping_ratio: f64,
    },
}

/// A static method the record allows, whose check holds, and the DAF it gives.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StaticAlternative {
    /// The method (as [`super::StaticMethodDaf::method`]).
    pub method: &'static str,
    /// Its DAF [-].
    pub daf: f64,
}

impl std::fmt::Display for MeasureWarningKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::StaticMethodNotValid {
                channel,
                method,
                valid_alternatives,
            } => {
                let why = if *method == "low_pass" {
                    "which does not separate the static from the dynamic response here (measure.json: static_separation.reason)"
                } else {
                    "whose own check does not hold (measure.json: the channel's static_methods)"
                };
                write!(
                    f,
                    "the DAF of {channel} rests on its {method} static part, {why}: it carries a bias that its stated uncertainty does not include"
                )?;
                let alternatives: Vec<String> = valid_alternatives
                    .iter()
                    .map(|a| format!("{} {:.4}", a.method, a.daf))
                    .collect();
                if alternatives.is_empty() {
                    write!(f, "; give a crawl run, an influence line or a bridge model")
                } else {
                    write!(
                        f,
                        "; the record allows {} (static_reference)",
                        alternatives.join(", ")
                    )
                }
            }
            Self::CrawlBaselineWithoutDrift { baseline, exit } => {
                let baseline = match baseline {
                    Baseline::None => "none",
                    _ => "an offset",
                };
                let exit = exit
                    .as_ref()
                    .map_or(String::new(), |e| format!(" (its exit: {e})"));
                write!(
                    f,
                    "the crawl run's baseline is {baseline}: its record holds no quiet window after the vehicle's exit{exit}, so a drift of the logger over the crawl enters its static part and the DAFs on it, unseen by their stated uncertainty; record the crawl on past the exit, or give the vehicle's axle offsets for its exit time"
                )
            }
            Self::ForcedContentNotChecked { first_frequency_hz } => {
                let first = first_frequency_hz
                    .map_or(String::new(), |f1| format!(" (f1 = {f1:.3} Hz unconfirmed)"));
                write!(
                    f,
                    "the frequencies were identified from the crossing, and without the vehicle's exit time (entry time, speed, bridge length) and a second of record after it a bridge mode cannot be told from the crossing's forced content{first}"
                )
            }
            Self::ImplausibleSpeed {
                stated_kmh,
                fitted_kmh,
                channel,
            } => {
                let ratio = stated_kmh / fitted_kmh;
                let hint = if (ratio - 1.0 / 3.6).abs() < 0.1 {
                    " (a speed in m/s given as speed_kmh?)"
                } else if (ratio - 3.6).abs() < 0.4 {
                    " (a speed in km/h given as m/s?)"
                } else {
                    ""
                };
                write!(
                    f,
                    "the stated speed {stated_kmh:.1} km/h does not match the record: the static response of {channel} fits a crossing at {fitted_kmh:.1} km/h{hint}; every DAF and window that rests on the speed rests on a wrong one (measure.json: speed_check)"
                )
            }
            Self::WeighingEntryFitted { entry_time_s } => write!(
                f,
                "the weighed axle loads rest on an entry time fitted from the record ({entry_time_s:.3} s): their stated uncertainty does not cover a misplaced passage, and a tandem's axles trade load with it; give entry_time_s from axle detectors for axle loads (the gross weight does not depend on it)"
            ),
            Self::WeighingOnUnfittedModel { channels } => write!(
                f,
                "the weights rest on the bridge model's influence line of {}, not fitted to the record's frequencies: the model's stiffness error enters them one to one; give the model's updating ([measurement.updating]), a crawl run of a truck of known weight, or the influence line",
                channels.join(", ")
            ),
            Self::StaticPartOnWeighedLoads { channels } => write!(
                f,
                "the static parts of {} rest on the weighed axle loads (none were given), whose split between the axles the record resolves poorly and whose sum carries the bridge's dynamics: their DAFs carry a bias that their stated uncertainty does not include; give the axle loads (axle_loads_kn) from a static weighing",
                channels.join(", ")
            ),
            Self::WeighingAxlesNotResolved {
                axles,
                ill_conditioned,
            } => {
                let negative: Vec<String> = axles.iter().map(|a| a.to_string()).collect();
                let why = match (negative.is_empty(), ill_conditioned) {
                    (false, _) => format!("axle(s) {} weigh zero or less", negative.join(", ")),
                    _ => "the least squares cannot tell the axles apart".to_string(),
                };
                write!(
                    f,
                    "the record does not resolve the vehicle's axles: {why}; read its gross weight, and weigh the axles with sensors near a support or axle detectors"
                )
            }
            Self::ImplausibleDamping {
                frequency_hz,
                damping_ratio,
            } => write!(
                f,
                "the mode at {frequency_hz:.3} Hz has {:.1} % damping, above the {:.0} % that a bridge mode rarely exceeds: likely forced content or a spectral artefact",
                100.0 * damping_ratio,
                100.0 * IMPLAUSIBLE_DAMPING_RATIO
            ),
        }
    }
}

/// The warnings of a measurement's summary, in the order: channels, then frequencies.
pub(super) fn warnings_of(summary: &MeasurementSummary) -> Vec<MeasureWarning> {
    let mut warnings: Vec<MeasureWarningKind> = Vec::new();
    for channel in &summary.channels {
        let chosen = channel.static_methods.iter().find(|m| m.chosen);
        if let Some(chosen) = chosen.filter(|m| !m.valid) {
            warnings.push(MeasureWarningKind::StaticMethodNotValid {
                channel: channel.name.clone(),
                method: chosen.method,
                valid_alternatives: channel
                    .static_methods
                    .iter()
                    .filter(|m| m.valid && !m.chosen)
                    .map(|m| StaticAlternative {
                        method: m.method,
                        daf: m.daf,
                    })
                    .collect(),
            });
        }
    }
    let on_crawl = summary
        .channels
        .iter()
        .any(|c| c.static_method == "crawl_run");
    if let Some(crawl) = summary.preparation.crawl.as_deref().filter(|_| on_crawl) {
        if crawl.baseline != Baseline::Linear {
            warnings.push(MeasureWarningKind::CrawlBaselineWithoutDrift {
                baseline: crawl.baseline,
                exit: crawl
                    .crossing
                    .as_ref()
                    .and_then(|w| w.exit_time_s.map(|t| format!("{t:.2} s, {}", w.exit_rule))),
            });
        }
    }
    if summary.forced_content_check == ForcedContentCheck::NotPossible {
        warnings.push(MeasureWarningKind::ForcedContentNotChecked {
            first_frequency_hz: summary
                .identified_frequencies
                .first()
                .map(|p| p.frequency_hz),
        });
    }
    if let Some(check) = summary.speed_check.as_ref().filter(|c| !c.plausible) {
        warnings.push(MeasureWarningKind::ImplausibleSpeed {
            stated_kmh: crate::units::metres_per_second_to_kmh(check.stated_speed_m_s),
            fitted_kmh: crate::units::metres_per_second_to_kmh(check.fitted_speed_m_s),
            channel: check.channel.clone(),
        });
    }
    if summary
        .weighing
        .as_ref()
        .is_some_and(|w| w.against_given.is_none())
    {
        let on_weighed: Vec<String> = summary
            .channels
            .iter()
            .filter(|c| c.static_method.starts_with("influence_line"))
            .map(|c| c.name.clone())
            .collect();
        if !on_weighed.is_empty() {
            warnings.push(MeasureWarningKind::StaticPartOnWeighedLoads {
                channels: on_weighed,
            });
        }
    }
    if let Some(w) = &summary.weighing {
        let negative: Vec<usize> = (0..w.axle_loads_n.len())
            .filter(|&a| w.axle_loads_n[a] <= 0.0)
            .map(|a| a + 1)
            .collect();
        if !negative.is_empty() || !w.well_conditioned {
            warnings.push(MeasureWarningKind::WeighingAxlesNotResolved {
                axles: negative,
                ill_conditioned: !w.well_conditioned,
            });
        }
        if w.entry_time_fitted && w.axle_loads_n.len() > 1 {
            warnings.push(MeasureWarningKind::WeighingEntryFitted {
                entry_time_s: w.entry_time_s,
            });
        }
        let unfitted: Vec<String> = w
            .channels
            .iter()
            .filter(|c| c.line_source == "influence_line_model_unfitted")
            .map(|c| c.channel.clone())
            .collect();
        if !unfitted.is_empty() {
            warnings.push(MeasureWarningKind::WeighingOnUnfittedModel { channels: unfitted });
        }
    }
    for mode in &summary.identified_frequencies {
        if let Some(z) = mode
            .damping_ratio
            .filter(|&z| z > IMPLAUSIBLE_DAMPING_RATIO)
        {
            warnings.push(MeasureWarningKind::ImplausibleDamping {
                frequency_hz: mode.frequency_hz,
                damping_ratio: z,
            });
        }
    }
    warnings.into_iter().map(MeasureWarning::from).collect()
}
