//! Warnings on implausible magnitudes of a run: a static deflection over span/100, or a
//! fundamental frequency outside the range of real bridges. Both are the usual signs of an
//! input in the wrong unit (EI in kN·m² instead of N·m² makes the bridge 1000 × softer:
//! deflections × 1000, frequencies ÷ 31.6), which otherwise run without a word.

use crate::analysis::DafReport;
use crate::fe::influence::InfluenceLines;
use crate::fe::{statics::PointLoad, MeshOptions, Station};
use crate::modal::{ModalBasis, ModeKind, Quantity};
use crate::model::{BridgeModel, ImportedMatrices, ImportedModes};
use crate::solver::SolverWarning;

/// Largest plausible static deflection as a fraction of the span (1/100). Serviceability limits
/// of bridge codes are span/800 to span/300 under live load (AASHTO LRFD §2.5.2.6.2: L/800 for
/// vehicular load; EN 1990 A2.4.4.2.3 for railway bridges around L/600 or stricter), so span/100
/// is several times beyond any design and only reached by a wrong input.
pub const DEFLECTION_SPAN_FRACTION: f64 = 0.01;

/// Factor by which the fundamental frequency may lie outside the band of EN 1991-2:2003
/// Figure 6.10 ([`eurocode_frequency_band`]) before it is called implausible. The band was
/// drawn from measured railway bridges; road bridges are lighter and often lie below it (the
/// paper's 4 × 40 m grillage: 2.5 Hz against a lower limit of 2.65 Hz), so a factor of 3 in
/// frequency (9 in stiffness over mass) is allowed; a unit error of 1000 in EI or mass is a
/// factor of 31.6.
pub const FREQUENCY_BAND_FACTOR: f64 = 3.0;

/// The band of the first natural frequency n₀ [Hz] of EN 1991-2:2003 §6.4.4, Figure 6.10, for
/// a span L [m] between 4 and 100 m: upper limit 94.76 L^−0.748; lower limit 80/L for
/// L ≤ 20 m and 23.58 L^−0.592 above. None outside 4–100 m, where the figure gives none.
pub fn eurocode_frequency_band(span_length: f64) -> Option<(f64, f64)> {
    if !(4.0..=100.0).contains(&span_length) {
        return None;
    }
    let upper = 94.76 * span_length.powf(-0.748);
    let lower = if span_length <= 20.0 {
        80.0 / span_length
    } else {
        23.58 * span_length.powf(-0.592)
    };
    Some((lower, upper))
}

/// The length [m] of the span that holds position x [m] (the last span beyond the end).
fn span_at(model: &BridgeModel, x: f64) -> f64 {
    let spans = model.span_lengths();
    let mut start = 0.0;
    for &length in spans {
        if x <= start + length {
            return length;
        }
        start += length;
    }
    spans.last().copied().unwrap_or(0.0)
}

/// The station whose static deflection is the largest fraction of its span, when that fraction
/// exceeds [`DEFLECTION_SPAN_FRACTION`].
fn deflection_warning(
    model: &BridgeModel,
    basis: &ModalBasis,
    report: &DafReport,
) -> Option<SolverWarning> {
    let worst = report
        .stations
        .iter()
        .filter(|e| e.quantity == Quantity::Deflection)
        .map(|e| {
            let offsets = model.line_offsets();
            let position = basis
                .stations
                .get(e.station)
                .map_or(0.0, |s| s.along_girders(&offsets));
            let span = span_at(model, position);
            (e, span, e.static_max.abs() / span)
        })
        .filter(|(_, span, _)| *span > 0.0)
        .max_by(|a, b| a.2.total_cmp(&b.2))?;
    let (entry, span, fraction) = worst;
    (fraction > DEFLECTION_SPAN_FRACTION).then(|| SolverWarning::StaticDeflectionImplausible {
        station: entry.name.clone(),
        deflection: entry.static_max.abs(),
        span_length: span,
        limit: DEFLECTION_SPAN_FRACTION * span,
    })
}

/// The first vertical bending frequency (the first mode if there is none) against the widened
/// Eurocode band of the longest span.
fn frequency_warning(model: &BridgeModel, basis: &ModalBasis) -> Option<SolverWarning> {
    let mode = basis
        .modes
        .iter()
        .find(|m| m.kind == ModeKind::VerticalBending)
        .or(basis.modes.first())?;
    let span = model.span_lengths().iter().copied().fold(0.0, f64::max);
    let (lower, upper) = eurocode_frequency_band(span)?;
    let (low, high) = (lower / FREQUENCY_BAND_FACTOR, upper * FREQUENCY_BAND_FACTOR);
    let frequency = mode.frequency_hz();
    (!(low..=high).contains(&frequency)).then_some(SolverWarning::FrequencyImplausible {
        frequency_hz: frequency,
        span_length: span,
        low_hz: low,
        high_hz: high,
    })
}

/// What can be told of a bridge model before any solve (`vbi check`): for a continuous beam,
/// the first frequency is bracketed by closed forms of its longest span L,
/// f_ss = (π/L)² √(EI/m̄)/2π (pinned ends; m̄ with the added mass) ≤ f₁ ≤ (4.730/π)² f_ss
/// (clamped ends, the most that continuity over the supports can stiffen it), and a warning is
/// given when the whole bracket lies outside the widened Eurocode band. None for a grillage
/// (its frequency needs the modal solve; `vbi run` and studies check it).
pub fn model_warning(model: &BridgeModel) -> Option<SolverWarning> {
    if let BridgeModel::ImportedMatrices(imported) = model {
        return imported_model_warning(imported);
    }
    if let BridgeModel::ImportedModes(imported) = model {
        return imported_shapes_warning(imported);
    }
    let BridgeModel::ContinuousBeam(beam) = model else {
        return None;
    };
    let span = beam.span_lengths.iter().copied().fold(0.0, f64::max);
    let mass = beam.section.mass_per_length + beam.added_mass_per_length;
    if !(span > 0.0 && mass > 0.0) {
        return None;
    }
    let pinned = (std::f64::consts::PI / span).powi(2)
        * (beam.section.flexural_rigidity / mass).sqrt()
        / (2.0 * std::f64::consts::PI);
    let clamped = (4.730 / std::f64::consts::PI).powi(2) * pinned;
    let (lower, upper) = eurocode_frequency_band(span)?;
    let (low, high) = (lower / FREQUENCY_BAND_FACTOR, upper * FREQUENCY_BAND_FACTOR);
    let outside = clamped < low || pinned > high;
    outside.then_some(SolverWarning::FrequencyImplausible {
        frequency_hz: if clamped < low { clamped } else { pinned },
        span_length: span,
        low_hz: low,
        high_hz: high,
    })
}

/// [`imported_warnings`] before any modal solve: one static solve of the matrices under a
/// unit load at the middle of the longest span (`vbi check`). The first warning, if any.
fn imported_model_warning(model: &ImportedMatrices) -> Option<SolverWarning> {
    let fe = crate::fe::discretise_imported(model, &MeshOptions::default()).ok()?;
    let solver = crate::fe::statics::StaticSolver::new(&fe).ok()?;
    let deflection = |s: usize| {
        let load = PointLoad {
            x: fe.stations[s].position,
            y: 0.0,
            force: 1.0,
        };
        solver
            .response(&[load])
            .map_or(f64::NAN, |response| response.deflection[s])
    };
    imported_warnings(model, &fe.stations, deflection)
        .into_iter()
        .next()
}

/// Plausible mass per length of a bridge deck [kg/m]: 500 kg/m (a light footbridge) to 500 t/m
/// (a wide multi-girder or box deck is 20 to 100 t/m). Shapes scaled to a unit maximum instead
/// of unit modal mass imply about 2/L kg/m, shapes in mm 10⁻⁶ of the true mass.
pub const DECK_MASS_PER_LENGTH: (f64, f64) = (500.0, 5.0e5);

/// The size of imported mode shapes against a mass-normalised mode of a real deck: a uniform
/// deck of mass m̄ per length over the length L has a first vertical bending mode of largest
/// deflection
/// √(2/(m̄L)) (a sine, also for equal continuous spans and, line by line, for a grillage's
/// first mode), so the shapes imply m̄ = 2/(L·φ²), which must lie in [`DECK_MASS_PER_LENGTH`].
pub fn imported_shapes_warning(model: &ImportedModes) -> Option<SolverWarning> {
    let basis = crate::modal::import::build_imported_basis(&model.data).ok()?;
    shapes_warning(&basis, model.span_lengths.iter().sum())
}

/// [`imported_shapes_warning`] of a basis already built (a run's), over a deck of `length` [m].
fn shapes_warning(basis: &ModalBasis, length: f64) -> Option<SolverWarning> {
    // The first vertical bending mode (given, or classified from the shapes): a lateral or
    // torsional first mode has another size.
    let count = basis.mode_count();
    let first = basis
        .modes
        .iter()
        .position(|mode| mode.kind == ModeKind::VerticalBending)?;
    let amplitude = basis
        .deck_deflection
        .iter()
        .skip(first)
        .step_by(count)
        .fold(0.0_f64, |m, v| m.max(v.abs()));
    if !(amplitude > 0.0 && length > 0.0) {
        return None;
    }
    let implied = 2.0 / (length * amplitude * amplitude);
    let (low, high) = DECK_MASS_PER_LENGTH;
    (!(low..=high).contains(&implied)).then_some(SolverWarning::ImportedShapesImplausible {
        amplitude,
        implied_mass_per_length: implied,
        length,
        low,
        high,
    })
}

/// The plausibility warnings of a run ([`deflection_warning`], [`frequency_warning`], and for
/// imported matrices [`imported_warnings`] from the influence lines).
pub fn plausibility_warnings(
    model: &BridgeModel,
    basis: &ModalBasis,
    influence: &InfluenceLines,
    report: &DafReport,
) -> Vec<SolverWarning> {
    let mut warnings: Vec<SolverWarning> = deflection_warning(model, basis, report)
        .into_iter()
        .chain(frequency_warning(model, basis))
        .collect();
    if let BridgeModel::ImportedMatrices(imported) = model {
        let deflection = |s: usize| {
            let station = &influence.stations[s];
            influence.unit_load_response(s, Quantity::Deflection, station.position, 0.0)
        };
        warnings.extend(imported_warnings(imported, &influence.stations, deflection));
    }
    if let BridgeModel::ImportedModes(_) = model {
        // The run's own basis (the modes kept): no second build of the imported data per crossing.
        warnings.extend(shapes_warning(basis, model.length()));
    }
    warnings
}

/// Factor by which an imported model's static deflection may differ from the bracket of a beam
/// of the deck lines' EI (pinned to clamped ends), and its vertically moving mass from the deck
/// lines' mass: 3 covers a grillage's transverse distribution, shear flexibility and the mass
/// of slabs and diaphragms beside the girders; a unit error is a factor of 1000.
pub const IMPORTED_MODEL_FACTOR: f64 = 3.0;

/// Checks imported matrices against their deck lines' EI and mass per length: the deflection
/// at the middle of the longest span under a unit load there (`deflection_at(station)`, from the
/// matrices, upward positive) against L³/(192 ΣEI) … L³/(48 ΣEI) (a beam of the section's EI
/// clamped or pinned at its ends), and the vertically moving mass per length against Σ m̄ (when
/// every line gives one), each widened by [`IMPORTED_MODEL_FACTOR`].
pub fn imported_warnings(
    model: &ImportedMatrices,
    stations: &[Station],
    deflection_at: impl Fn(usize) -> f64,
) -> Vec<SolverWarning> {
    let mut warnings = Vec::new();
    let rigidity: f64 = model.deck_lines.iter().map(|l| l.flexural_rigidity).sum();
    let (longest, span) =
        model
            .span_lengths
            .iter()
            .copied()
            .enumerate()
            .fold(
                (0, 0.0),
                |best, (i, l)| if l > best.1 { (i, l) } else { best },
            );
    let name = format!("span{}_mid_section", longest + 1);
    if let Some(s) = stations.iter().position(|station| station.name == name) {
        let measured = -deflection_at(s);
        let pinned = span.powi(3) / (48.0 * rigidity);
        let (low, high) = (0.25 / IMPORTED_MODEL_FACTOR, IMPORTED_MODEL_FACTOR);
        let ratio = measured / pinned;
        if ratio.is_finite() && !(low..=high).contains(&ratio) {
            warnings.push(SolverWarning::ImportedModelImplausible {
                what: format!("static deflection at `{name}` under a unit load there"),
                reference: format!(
                    "L³/(48 ΣEI) = {pinned:.3e} m/N of a pinned {span} m beam of the deck lines' \
                     EI"
                ),
                ratio,
                low,
                high,
            });
        }
    }
    let line_mass: f64 = model.deck_lines.iter().map(|l| l.mass_per_length).sum();
    if model.deck_lines.iter().all(|l| l.mass_per_length > 0.0) {
        let ratio = model.vertical_mass() / model.length() / line_mass;
        let (low, high) = (1.0 / IMPORTED_MODEL_FACTOR, 3.0 * IMPORTED_MODEL_FACTOR);
        if !(low..=high).contains(&ratio) {
            warnings.push(SolverWarning::ImportedModelImplausible {
                what: "mass moving with a vertical translation, per length,".into(),
                reference: format!("the deck lines' Σ m̄ = {line_mass:.4e} kg/m"),
                ratio,
                low,
                high,
            });
        }
    }
    warnings
}
