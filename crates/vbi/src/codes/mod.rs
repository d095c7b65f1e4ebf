//! Design-code impact factors beside the computed DAF: what seven bridge codes would have a
//! designer assume for the station and quantity that vbi computed.
//!
//! Each code has one file here (`jtg_d60.rs`, `jtj_021.rs`, `aashto_lrfd.rs`,
//! `aashto_standard.rs`, `csa_s6.rs`, `as_5100.rs`, `en_1991_2.rs`) that holds its clauses, as
//! they are written, and its `CodeEntry`: its name and how it chooses the clause and the input
//! for a station and quantity of the bridge at hand. `REGISTRY` lists the entries, one line a
//! code, and everything else reads them from it: [`DesignCode::name`], [`station_factors`] and
//! [`factors_at`], and the entries of a run's DAF report ([`design_code_factors`]). A new code is
//! one new file, one line of `REGISTRY` and its [`DesignCode`] variant. [`clauses`] gathers the
//! clause functions under one path. Where a code leaves a choice to the engineer (which span
//! length, which frequency, which roughness class), the reading vbi takes is stated in the
//! factor's `basis` and in docs/design-codes.md.

pub mod clauses;

mod aashto_lrfd;
mod aashto_standard;
mod as_5100;
mod csa_s6;
mod en_1991_2;
mod jtg_d60;
mod jtj_021;

use serde::{Deserialize, Serialize};

use crate::fe::{Quantity, Station};
use crate::modal::{ModalBasis, ModeKind};
use crate::model::{support_positions_of, BeamSection, BridgeModel, ModelError};

/// One design code as vbi reads it, held in the code's own file: the [`DesignCode`] it is, its
/// name, and the factors it gives for a location and quantity.
struct CodeEntry {
    /// The code.
    code: DesignCode,
    /// The code's name and edition, as tables and figures print it ([`DesignCode::name`]).
    name: &'static str,
    /// The short label of one of its provisions (a factor's `provision`) on a figure's axis
    /// ([`DesignCode::short_label`]).
    short_label: fn(&str) -> &'static str,
    /// The code's impact factors for a location and quantity, in the order of its cases (none
    /// where it lacks an input, several where it has several cases).
    factors: fn(&CodeInputs, CodeLocation, Quantity) -> Vec<CodeImpactFactor>,
}

/// The design codes, one line each, in the order of the declaration of [`DesignCode`]: the order
/// of the factors of [`station_factors`] and of every table and figure of them.
const REGISTRY: &[CodeEntry] = &[
    jtg_d60::ENTRY,
    jtj_021::ENTRY,
    aashto_lrfd::ENTRY,
    aashto_standard::ENTRY,
    csa_s6::ENTRY,
    as_5100::ENTRY,
    en_1991_2::ENTRY,
];

/// A bridge design code with a dynamic allowance for highway traffic.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DesignCode {
    /// China, JTG D60-2015 §4.3.2: μ from the fundamental frequency.
    JtgD60,
    /// China, JTJ 021-89 §2.3.2: 1 + μ from the span.
    Jtj021,
    /// USA, AASHTO LRFD Bridge Design Specifications §3.6.2: IM by component and limit state.
    AashtoLrfd,
    /// USA, AASHTO Standard Specifications for Highway Bridges (17th ed., 2002) §3.8.2.
    AashtoStandard,
    /// Canada, CSA S6 (CHBDC) §3.8.4.5.3: DLA by the number of axles.
    CsaS6,
    /// Australia, AS 5100.2:2017 §7.7.2: DLA by design load.
    As5100,
    /// Europe, EN 1991-2:2003 Annex B: φ_fat by surface roughness (fatigue).
    En1991,
}

impl DesignCode {
    /// The code's name and edition, as tables and figures print it.
    pub fn name(self) -> &'static str {
        self.entry().name
    }

    /// The short label of the code's provision `provision` (a factor's `provision`, such as
    /// `computed_frequency` or `fatigue`) on a figure's axis: "JTG vbi", "LRFD fat" …
    pub fn short_label(self, provision: &str) -> &'static str {
        (self.entry().short_label)(provision)
    }

    /// The code's line of [`REGISTRY`].
    fn entry(self) -> &'static CodeEntry {
        REGISTRY
            .iter()
            .find(|entry| entry.code == self)
            .unwrap_or_else(|| panic!("{self:?} has no line in codes::REGISTRY"))
    }
}

/// One code's impact factor for one station and quantity.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CodeImpactFactor {
    /// The code.
    pub code: DesignCode,
    /// Which case of the code, a short key: `code_frequency`, `computed_frequency`,
    /// `measured_frequency`, `span`,
    /// `strength_service`, `fatigue`, `loaded_length`, `cl_w_axles`, `moving_traffic`,
    /// `triaxle_group`, `single_axle_or_wheel`, `fatigue_roughness`.
    pub provision: String,
    /// The clause, for example `§4.3.2, Eq. (4.3.2)`.
    pub clause: String,
    /// The input the value follows from, with its unit (`f1 = 4.12 Hz, code formula, l = 30 m`).
    pub basis: String,
    /// The impact factor IM = μ = DLA [-]: the code's design DAF is 1 + IM.
    pub impact_factor: f64,
}

impl CodeImpactFactor {
    /// The code's design DAF, 1 + IM [-].
    pub fn daf(&self) -> f64 {
        1.0 + self.impact_factor
    }

    /// Whether the factor is for the fatigue limit state (EN 1991-2 Annex B's φ_fat, AASHTO
    /// LRFD's 15 %): a factor on the fatigue load model's stress ranges, calibrated on damage,
    /// not a peak DAF; reports set it apart from the comparison with the computed peak DAFs
    /// (issue 46). The dynamic fatigue factor that compares with it is a damage ratio (issue 51).
    pub fn is_fatigue_factor(&self) -> bool {
        matches!(self.provision.as_str(), "fatigue" | "fatigue_roughness")
    }
}

/// The code factors of one entry of a DAF report.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StationCodeFactors {
    /// Station name.
    pub station: String,
    /// Station index in the basis.
    pub station_index: usize,
    /// The quantity.
    pub quantity: Quantity,
    /// The factors, in the order of the declaration of [`DesignCode`].
    pub factors: Vec<CodeImpactFactor>,
}

/// What the codes need to know of the bridge and its traffic.
#[derive(Debug, Clone, PartialEq)]
pub struct CodeInputs {
    /// Span lengths [m].
    pub span_lengths: Vec<f64>,
    /// The deck lines' offsets on a skewed grillage [m] ([`BridgeModel::line_offsets`]): a
    /// girder station's place in its span is its position along the girder.
    pub line_offsets: Vec<f64>,
    /// Flexural rigidity EI_c [N·m²] and mass per length m_c [kg/m] (with the non-structural
    /// mass) of the whole cross-section, for the codes' frequency formulas; None where the
    /// model does not give them.
    pub section: Option<BeamSection>,
    /// vbi's vertical-bending frequencies, ascending [Hz] (or the measured ones, see
    /// `measured_frequencies`).
    pub bending_frequencies: Vec<f64>,
    /// The frequencies were identified from a measurement, not computed by vbi's model.
    pub measured_frequencies: bool,
    /// Number of axles of the scenario's vehicle (0 when unknown), for provenance: CSA S6 reads
    /// the CL-W design truck's axles, not these (issue 46).
    pub axle_count: usize,
    /// The road's G_d(n₀) at n₀ = 0.1 cycles/m [m³]; `None` when unknown (a field test):
    /// EN 1991-2's roughness factor is left out.
    pub psd_at_reference: Option<f64>,
}

impl CodeInputs {
    /// The inputs of a bridge model, its modal basis, the vehicle's axle count and the road's
    /// G_d at 0.1 cycles/m [m³] (`RoadSpec::psd_at_iso_reference`).
    pub fn of(
        model: &BridgeModel,
        basis: &ModalBasis,
        axle_count: usize,
        psd_at_iso_reference: f64,
    ) -> CodeInputs {
        CodeInputs {
            span_lengths: model.span_lengths().to_vec(),
            line_offsets: model.line_offsets(),
            section: whole_section(model).ok(),
            bending_frequencies: basis
                .modes
                .iter()
                .filter(|m| m.kind == ModeKind::VerticalBending)
                .map(|m| m.frequency_hz())
                .collect(),
            measured_frequencies: false,
            axle_count,
            psd_at_reference: Some(psd_at_iso_reference),
        }
    }

    fn longest_span(&self) -> f64 {
        self.span_lengths.iter().copied().fold(0.0, f64::max)
    }

    fn continuous(&self) -> bool {
        self.span_lengths.len() > 1
    }
}

/// EI_c and m_c of the whole cross-section: the beam's own (with its added mass); for a
/// grillage the sums over its composite girders of E·I_y and ρ·A plus the pavement mass
/// (the slab strips and diaphragms between the girders are left out: they carry no
/// longitudinal bending); for imported matrices the sum of the deck lines' EI and the mass
/// moving with a vertical translation per length.
pub fn whole_section(model: &BridgeModel) -> Result<BeamSection, ModelError> {
    match model {
        BridgeModel::ContinuousBeam(beam) => Ok(BeamSection {
            flexural_rigidity: beam.section.flexural_rigidity,
            mass_per_length: beam.section.mass_per_length + beam.added_mass_per_length,
        }),
        BridgeModel::Grillage(grillage) => {
            let mut total = BeamSection {
                flexural_rigidity: 0.0,
                mass_per_length: 0.0,
            };
            for i in 0..grillage.girder_count {
                let girder =
                    BeamSection::from_girder(&grillage.girder_section(i)?, &grillage.material);
                total.flexural_rigidity += girder.flexural_rigidity;
                total.mass_per_length += girder.mass_per_length + grillage.added_mass_per_length(i);
            }
            for (_, barrier_mass, _) in grillage.barrier_loads() {
                total.mass_per_length += barrier_mass;
            }
            Ok(total)
        }
        // The deck lines' EI, and the vertically moving mass spread over the length.
        BridgeModel::ImportedMatrices(imported) => Ok(BeamSection {
            flexural_rigidity: imported
                .deck_lines
                .iter()
                .map(|line| line.flexural_rigidity)
                .sum(),
            mass_per_length: imported.vertical_mass() / imported.length(),
        }),
        // Modes alone give no section: the codes that need EI or mass are left out.
        BridgeModel::ImportedModes(_) => Err(ModelError::ImportedMatrices {
            message: "an imported modal basis has no section properties".into(),
        }),
    }
}

/// Where a code factor is read: the place and the position along the girders [m].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CodeLocation {
    place: Place,
    position: f64,
}

impl CodeLocation {
    /// The location of a station of the bridge's modal basis.
    pub fn of_station(inputs: &CodeInputs, station: &Station) -> Self {
        CodeLocation {
            place: place_of(inputs, station),
            position: station.along_girders(&inputs.line_offsets),
        }
    }

    /// A section at `fraction` (0 to 1 exclusive) of span `span_index` (0-based) of
    /// `inputs.span_lengths`: a gauge in a span, as a field test places it.
    pub fn in_span(inputs: &CodeInputs, span_index: usize, fraction: f64) -> Self {
        let supports = support_positions_of(&inputs.span_lengths);
        let span = span_index.min(inputs.span_lengths.len().saturating_sub(1));
        let (start, end) = match (supports.get(span), supports.get(span + 1)) {
            (Some(&start), Some(&end)) => (start, end),
            _ => (0.0, 0.0),
        };
        CodeLocation {
            place: Place::Span { start, end },
            position: start + fraction * (end - start),
        }
    }
}

/// Where a station lies: in a span, or over a support.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Place {
    /// In the span from `start` to `end` [m].
    Span { start: f64, end: f64 },
    /// Over a support, with the lengths of the spans on each side (0 beyond an end) [m].
    Support { left: f64, right: f64 },
}

fn place_of(inputs: &CodeInputs, station: &Station) -> Place {
    let spans = &inputs.span_lengths;
    let position = station.along_girders(&inputs.line_offsets);
    if spans.is_empty() {
        return Place::Span {
            start: 0.0,
            end: 0.0,
        };
    }
    let supports = support_positions_of(spans);
    let tolerance = 1e-6 * supports[supports.len() - 1].max(1.0);
    if station.over_support || station.support {
        if let Some(k) = supports
            .iter()
            .position(|&x| (position - x).abs() <= tolerance)
        {
            return Place::Support {
                left: if k == 0 { 0.0 } else { spans[k - 1] },
                right: spans.get(k).copied().unwrap_or(0.0),
            };
        }
    }
    let span = supports[..spans.len()]
        .iter()
        .rposition(|&x| x <= position)
        .unwrap_or(0);
    Place::Span {
        start: supports[span],
        end: supports[span + 1],
    }
}

/// The span L that the span rules read for a station [m]: its span, or over a support the mean
/// of the spans on each side (the one span at an end support).
fn station_span(place: Place) -> f64 {
    match place {
        Place::Span { start, end } => end - start,
        Place::Support { left, right } if left > 0.0 && right > 0.0 => (left + right) / 2.0,
        Place::Support { left, right } => left.max(right),
    }
}

/// Whether the entry is a negative (hogging) moment: a bending moment over an interior support.
fn hogging(place: Place, quantity: Quantity) -> bool {
    quantity == Quantity::BendingMoment
        && matches!(place, Place::Support { left, right } if left > 0.0 && right > 0.0)
}

/// The impact factors of every code for one station and quantity, in the order of
/// the declaration of [`DesignCode`] (a code with two cases gives two).
pub fn station_factors(
    inputs: &CodeInputs,
    station: &Station,
    quantity: Quantity,
) -> Vec<CodeImpactFactor> {
    factors_at(inputs, CodeLocation::of_station(inputs, station), quantity)
}

/// The impact factors of every code for one location and quantity, in the order of the
/// declaration of [`DesignCode`] (a code with two cases gives two; CSA S6 needs the axle count
/// and EN 1991-2 the road's roughness, each left out without it).
pub fn factors_at(
    inputs: &CodeInputs,
    location: CodeLocation,
    quantity: Quantity,
) -> Vec<CodeImpactFactor> {
    REGISTRY
        .iter()
        .flat_map(|entry| (entry.factors)(inputs, location, quantity))
        .collect()
}

/// One factor of `code`, as the codes' files build them.
fn factor(
    code: DesignCode,
    provision: &str,
    clause: &str,
    basis: String,
    impact_factor: f64,
) -> CodeImpactFactor {
    CodeImpactFactor {
        code,
        provision: provision.to_string(),
        clause: clause.to_string(),
        basis,
        impact_factor,
    }
}

/// The code factors of the entries (station index, quantity) of a DAF report, in their order:
/// what [`crate::crossing::run_crossing`] puts in `DafReport::design_codes`.
pub fn design_code_factors(
    inputs: &CodeInputs,
    basis: &ModalBasis,
    entries: impl IntoIterator<Item = (usize, Quantity)>,
) -> Vec<StationCodeFactors> {
    entries
        .into_iter()
        .filter_map(|(index, quantity)| {
            let station = basis.stations.get(index)?;
            Some(StationCodeFactors {
                station: station.name.clone(),
                station_index: index,
                quantity,
                factors: station_factors(inputs, station, quantity),
            })
        })
        .collect()
}

#[cfg(test)]
mod tests;
