//! Responses at stations, the exact static reference, DAF, RDM, DAF against the number of modes,
//! modal participation (paper Eq. 30), convergence and cut-off modes.
//!
//! Definitions (docs/theory.md writes each one down):
//! - Station response R(t) = Σₖ cₖ qₖ(t), with cₖ the station value of mode k (deflection or
//!   bending moment); the k-th term is the contribution of mode k (the paper's Fig. 10).
//! - Static reference S(t) = Σ_w S_w · IL(x_w(t), y_w): the exact static response to the static
//!   wheel loads at the wheels' positions at every instant, from the influence lines of the full
//!   stiffness (not from truncated modes).
//! - Governing direction σ = sign of the static extreme (the S(t) of largest magnitude). Hence
//!   deflection is read downwards, the moment sagging at mid-span and hogging over supports.
//!   static_max = S at that extreme, dynamic_max = the R(t) of largest σ·R(t), both signed;
//!   DAF = dynamic_max / static_max (Eqs. 15–16), IM = DAF − 1.
//! - DAF(K) uses the partial sum of the first K modal contributions of the same run and the same
//!   static reference; RDM(K) = DAF_u(K) / DAF_M(K) at one station.
//! - MPS_k (Eq. 30) = Σ_j rms_t(y_k^j) / Σ_k Σ_j rms_t(y_k^j), with y_k^j(t) = c_k^j qₖ(t).
//! - Convergence mode CM: the smallest K such that |DAF(K′) − DAF(N)| ≤ tol·DAF(N) for every
//!   K′ ≥ K. Cut-off modes K1, K2: the smallest K whose cumulative participation reaches 95 % and
//!   99 %.

use serde::{Deserialize, Serialize};

use crate::influence::InfluenceLines;
use crate::modal::{ModalBasis, Quantity};
use crate::solver::{
    default_time_step, simulate, ContactLoss, Crossing, ResponseHistory, SolverError,
    SolverOptions, SolverWarning,
};

/// Errors of the analysis stage.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum AnalysisError {
    /// The modal basis, the influence lines and the history disagree on sizes.
    #[error("inconsistent inputs: {what} (expected {expected}, found {found})")]
    Mismatch {
        /// What disagrees.
        what: &'static str,
        /// Expected count.
        expected: usize,
        /// Found count.
        found: usize,
    },
    /// A station index out of range.
    #[error("station {station} does not exist ({count} stations)")]
    StationOutOfRange {
        /// Requested station.
        station: usize,
        /// Number of stations.
        count: usize,
    },
    /// An analysis option out of range.
    #[error("analysis option `{name}` = {value} is invalid: {allowed}")]
    InvalidOption {
        /// Option name.
        name: &'static str,
        /// Offending value.
        value: f64,
        /// What is allowed.
        allowed: &'static str,
    },
    /// A truncated re-run asked for more modes than the basis has, or none.
    #[error("cannot re-run with {mode_count} modes: the basis has {available}")]
    InvalidModeCount {
        /// Requested number of modes.
        mode_count: usize,
        /// Modes in the basis.
        available: usize,
    },
    /// A re-run failed.
    #[error("re-run failed: {0}")]
    Solver(#[from] SolverError),
}

/// Options of [`analyse`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AnalysisOptions {
    /// Relative tolerance of the convergence mode CM [-]. Default 0.01 (1 %).
    pub convergence_tolerance: f64,
    /// Cumulative participation that defines K1 [-]. Default 0.95.
    pub cutoff_k1_level: f64,
    /// Cumulative participation that defines K2 [-]. Default 0.99.
    pub cutoff_k2_level: f64,
    /// Station whose RDM is reported at the top level. Default (None): the station not over a
    /// support with the largest static deflection.
    pub rdm_station: Option<usize>,
}

impl Default for AnalysisOptions {
    fn default() -> Self {
        AnalysisOptions {
            convergence_tolerance: 0.01,
            cutoff_k1_level: 0.95,
            cutoff_k2_level: 0.99,
            rdm_station: None,
        }
    }
}

/// Direction in which a station's response is read.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Direction {
    /// Positive values govern (upward deflection, sagging moment).
    Positive,
    /// Negative values govern (downward deflection, hogging moment).
    Negative,
}

impl Direction {
    fn sign(self) -> f64 {
        match self {
            Direction::Positive => 1.0,
            Direction::Negative => -1.0,
        }
    }
}

/// DAF and modal results of one station and quantity.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StationDaf {
    /// Station name.
    pub name: String,
    /// Station index in the basis.
    pub station: usize,
    /// Deflection or bending moment.
    pub quantity: Quantity,
    /// Governing direction: the sign of the static extreme.
    pub direction: Direction,
    /// Static extreme, signed [m or N·m].
    pub static_max: f64,
    /// Time of the static extreme [s].
    pub static_max_time: f64,
    /// Dynamic extreme in the governing direction, signed [m or N·m].
    pub dynamic_max: f64,
    /// Time of the dynamic extreme [s].
    pub dynamic_max_time: f64,
    /// DAF = dynamic_max / static_max [-]; None when the static response vanishes (for example
    /// the deflection over a support).
    pub daf: Option<f64>,
    /// IM = DAF − 1 [-].
    pub impact_factor: Option<f64>,
    /// DAF(K) for K = 1…N from partial modal sums (empty when DAF is None).
    pub daf_by_modes: Vec<f64>,
    /// Modal participation MPS_k at this station, k = 1…N [-] (sums to 1).
    pub participation: Vec<f64>,
    /// Cumulative participation [-].
    pub cumulative_participation: Vec<f64>,
    /// Convergence mode CM (1-based).
    pub convergence_mode: Option<usize>,
    /// Cut-off mode K1 (1-based).
    pub cutoff_k1: Option<usize>,
    /// Cut-off mode K2 (1-based).
    pub cutoff_k2: Option<usize>,
}

/// RDM of one station.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StationRdm {
    /// Station name.
    pub name: String,
    /// Station index.
    pub station: usize,
    /// RDM = DAF_u / DAF_M [-].
    pub rdm: Option<f64>,
    /// RDM(K), K = 1…N (None where DAF_M(K) = 0 or a DAF is undefined).
    pub rdm_by_modes: Vec<Option<f64>>,
}

/// Participation over the whole deck (Eq. 30).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DeckParticipation {
    /// Deflection MPS_k over all deck nodes [-].
    pub deflection: Vec<f64>,
    /// Cumulative deflection participation [-].
    pub deflection_cumulative: Vec<f64>,
    /// Deflection K1 (1-based).
    pub deflection_k1: Option<usize>,
    /// Deflection K2 (1-based).
    pub deflection_k2: Option<usize>,
    /// Bending-moment MPS_k over all stations (moments exist only at stations) [-].
    pub moment: Vec<f64>,
    /// Cumulative moment participation [-].
    pub moment_cumulative: Vec<f64>,
    /// Moment K1 (1-based).
    pub moment_k1: Option<usize>,
    /// Moment K2 (1-based).
    pub moment_k2: Option<usize>,
}

/// DAFs of one station from a run with only the first K modes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TruncatedStationDaf {
    /// Station name.
    pub name: String,
    /// Quantity.
    pub quantity: Quantity,
    /// DAF of the K-mode run.
    pub daf: Option<f64>,
}

/// A re-run of the crossing with only the first K modes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TruncatedRun {
    /// K.
    pub mode_count: usize,
    /// DAF per station and quantity.
    pub stations: Vec<TruncatedStationDaf>,
    /// RDM at the report's RDM station.
    pub rdm: Option<f64>,
}

/// Everything the analysis of one crossing gives.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DafReport {
    /// Per station and quantity (station order, deflection then moment).
    pub stations: Vec<StationDaf>,
    /// Name of the station of the top-level RDM.
    pub rdm_station: Option<String>,
    /// RDM = DAF_u / DAF_M at `rdm_station`.
    pub rdm: Option<f64>,
    /// RDM(K) at `rdm_station`, K = 1…N.
    pub rdm_by_modes: Vec<Option<f64>>,
    /// RDM of every station.
    pub station_rdm: Vec<StationRdm>,
    /// Deck-wide participation.
    pub deck_participation: DeckParticipation,
    /// Number of modes N.
    pub mode_count: usize,
    /// Time step [s].
    pub time_step: f64,
    /// Tyre contact losses of the run (never hidden).
    pub contact_losses: Vec<ContactLoss>,
    /// Solver warnings of the run.
    pub warnings: Vec<SolverWarning>,
    /// Re-runs with K modes ([`rerun_truncated`]); empty unless requested.
    pub truncated_runs: Vec<TruncatedRun>,
}

impl DafReport {
    /// The entry of a station and quantity.
    pub fn entry(&self, station: usize, quantity: Quantity) -> Option<&StationDaf> {
        self.stations
            .iter()
            .find(|e| e.station == station && e.quantity == quantity)
    }
}

/// Static response of every station at every instant of a run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StaticReference {
    /// Number of stations.
    pub station_count: usize,
    /// Number of instants.
    pub step_count: usize,
    /// Static deflection [m], step-major: `deflection[i * station_count + s]`.
    pub deflection: Vec<f64>,
    /// Static bending moment [N·m], same layout.
    pub bending_moment: Vec<f64>,
}

impl StaticReference {
    /// History of one station and quantity.
    pub fn history(&self, station: usize, quantity: Quantity) -> Vec<f64> {
        let table = match quantity {
            Quantity::Deflection => &self.deflection,
            Quantity::BendingMoment => &self.bending_moment,
        };
        (0..self.step_count)
            .map(|i| table[i * self.station_count + station])
            .collect()
    }
}

fn check_history(basis: &ModalBasis, history: &ResponseHistory) -> Result<(), AnalysisError> {
    if basis.mode_count() != history.mode_count {
        return Err(AnalysisError::Mismatch {
            what: "modes of the basis and of the history",
            expected: basis.mode_count(),
            found: history.mode_count,
        });
    }
    let n = basis.mode_count();
    let s = basis.stations.len();
    for (what, len) in [
        ("station_deflection length", basis.station_deflection.len()),
        ("station_moment length", basis.station_moment.len()),
    ] {
        if len != s * n {
            return Err(AnalysisError::Mismatch {
                what,
                expected: s * n,
                found: len,
            });
        }
    }
    Ok(())
}

/// Total response R(t_i) = Σₖ cₖ qₖ(t_i) of one station (paper Fig. 10, total).
pub fn station_response(
    basis: &ModalBasis,
    history: &ResponseHistory,
    station: usize,
    quantity: Quantity,
) -> Result<Vec<f64>, AnalysisError> {
    check_history(basis, history)?;
    check_station(station, basis.stations.len())?;
    let c = basis.station_values(station, quantity);
    Ok((0..history.step_count)
        .map(|i| dot(c, history.modal_displacements_at(i)))
        .collect())
}

/// Contribution cₖ qₖ(t_i) of every mode to one station, step-major `[i * N + k]` (paper Fig. 10).
pub fn modal_contributions(
    basis: &ModalBasis,
    history: &ResponseHistory,
    station: usize,
    quantity: Quantity,
) -> Result<Vec<f64>, AnalysisError> {
    check_history(basis, history)?;
    check_station(station, basis.stations.len())?;
    let c = basis.station_values(station, quantity);
    let mut out = Vec::with_capacity(history.step_count * c.len());
    for i in 0..history.step_count {
        let q = history.modal_displacements_at(i);
        out.extend(c.iter().zip(q).map(|(a, b)| a * b));
    }
    Ok(out)
}

fn check_station(station: usize, count: usize) -> Result<(), AnalysisError> {
    if station >= count {
        return Err(AnalysisError::StationOutOfRange { station, count });
    }
    Ok(())
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// The exact static reference: at each instant of the run, the static response of every station
/// to the static wheel loads at the wheels' positions, S(t) = Σ_w S_w · IL(x_w(t), y_w), from the
/// influence lines (full stiffness, not truncated modes).
pub fn static_reference(
    influence: &InfluenceLines,
    history: &ResponseHistory,
) -> Result<StaticReference, AnalysisError> {
    let stations = influence.stations.len();
    for (what, len) in [
        ("influence deflection fields", influence.deflection.len()),
        ("influence moment_left fields", influence.moment_left.len()),
        (
            "influence moment_right fields",
            influence.moment_right.len(),
        ),
    ] {
        if len != stations {
            return Err(AnalysisError::Mismatch {
                what,
                expected: stations,
                found: len,
            });
        }
    }
    let steps = history.step_count;
    let mut deflection = vec![0.0; steps * stations];
    let mut bending_moment = vec![0.0; steps * stations];
    for i in 0..steps {
        let x_front = history.front_axle_position[i];
        let row_u = &mut deflection[i * stations..(i + 1) * stations];
        let row_m = &mut bending_moment[i * stations..(i + 1) * stations];
        for contact in &history.contacts {
            let x = x_front + contact.longitudinal_offset;
            let stencil = influence.deck.stencil(x, contact.lateral_position);
            if stencil.is_empty() {
                continue;
            }
            let load = contact.static_load;
            for s in 0..stations {
                row_u[s] += load * stencil.evaluate(&influence.deflection[s]).0;
                let field = if x >= influence.stations[s].position {
                    &influence.moment_left[s]
                } else {
                    &influence.moment_right[s]
                };
                row_m[s] += load * stencil.evaluate(field).0;
            }
        }
    }
    Ok(StaticReference {
        station_count: stations,
        step_count: steps,
        deflection,
        bending_moment,
    })
}

/// Root mean square over time of every modal coordinate, rms(qₖ) [kg^½·m].
fn modal_rms(history: &ResponseHistory) -> Vec<f64> {
    let n = history.mode_count;
    let mut sum = vec![0.0; n];
    for i in 0..history.step_count {
        for (acc, q) in sum.iter_mut().zip(history.modal_displacements_at(i)) {
            *acc += q * q;
        }
    }
    let steps = history.step_count.max(1) as f64;
    sum.iter().map(|s| (s / steps).sqrt()).collect()
}

/// Normalised participation from per-mode weights, and its running sum.
fn normalise(weights: Vec<f64>) -> (Vec<f64>, Vec<f64>) {
    let total: f64 = weights.iter().sum();
    let share: Vec<f64> = if total > 0.0 && total.is_finite() {
        weights.iter().map(|w| w / total).collect()
    } else {
        vec![0.0; weights.len()]
    };
    let mut running = 0.0;
    let cumulative = share
        .iter()
        .map(|p| {
            running += p;
            running
        })
        .collect();
    (share, cumulative)
}

/// Smallest K (1-based) whose cumulative participation reaches `level`.
fn cutoff(cumulative: &[f64], level: f64) -> Option<usize> {
    // 1e-12 absorbs the rounding of the running sum when level = 1.
    cumulative
        .iter()
        .position(|&c| c >= level - 1e-12)
        .map(|k| k + 1)
}

/// Smallest K (1-based) after which every DAF(K′) stays within `tolerance`·DAF(N) of DAF(N).
pub fn convergence_mode(daf_by_modes: &[f64], tolerance: f64) -> Option<usize> {
    let &last = daf_by_modes.last()?;
    let band = tolerance * last.abs();
    let mut cm = daf_by_modes.len();
    for k in (0..daf_by_modes.len()).rev() {
        if (daf_by_modes[k] - last).abs() <= band {
            cm = k + 1;
        } else {
            break;
        }
    }
    Some(cm)
}

/// Full DAF analysis of one run.
pub fn analyse(
    basis: &ModalBasis,
    influence: &InfluenceLines,
    history: &ResponseHistory,
    options: &AnalysisOptions,
) -> Result<DafReport, AnalysisError> {
    check_history(basis, history)?;
    for (name, value) in [
        ("convergence_tolerance", options.convergence_tolerance),
        ("cutoff_k1_level", options.cutoff_k1_level),
        ("cutoff_k2_level", options.cutoff_k2_level),
    ] {
        if value.is_nan() || value <= 0.0 || value > 1.0 {
            return Err(AnalysisError::InvalidOption {
                name,
                value,
                allowed: "a fraction in (0, 1]",
            });
        }
    }
    let station_count = basis.stations.len();
    if influence.stations.len() != station_count {
        return Err(AnalysisError::Mismatch {
            what: "stations of the basis and of the influence lines",
            expected: station_count,
            found: influence.stations.len(),
        });
    }
    if let Some(s) = options.rdm_station {
        check_station(s, station_count)?;
    }
    let n = basis.mode_count();
    let steps = history.step_count;
    let reference = static_reference(influence, history)?;
    let rms = modal_rms(history);

    // Static extremes first: a station whose static extreme is negligible next to the largest of
    // its quantity (1e-9, far below any physical response yet above rounding of a zero) has no DAF.
    let quantities = [Quantity::Deflection, Quantity::BendingMoment];
    let mut extremes = Vec::new();
    let mut largest = [0.0f64; 2];
    for s in 0..station_count {
        for (qi, &quantity) in quantities.iter().enumerate() {
            let hist = reference.history(s, quantity);
            let (idx, value) =
                hist.iter()
                    .copied()
                    .enumerate()
                    .fold((0usize, 0.0f64), |best, (i, v)| {
                        if v.abs() > best.1.abs() {
                            (i, v)
                        } else {
                            best
                        }
                    });
            largest[qi] = largest[qi].max(value.abs());
            extremes.push((idx, value));
        }
    }

    let mut entries = Vec::new();
    let mut partial = vec![0.0; n];
    let mut best = vec![f64::NEG_INFINITY; n];
    for s in 0..station_count {
        for (qi, &quantity) in quantities.iter().enumerate() {
            let (static_idx, static_value) = extremes[s * 2 + qi];
            let direction = if static_value < 0.0 {
                Direction::Negative
            } else {
                Direction::Positive
            };
            let sign = direction.sign();
            let c = basis.station_values(s, quantity);
            best.fill(f64::NEG_INFINITY);
            let mut best_time_step = 0;
            for i in 0..steps {
                let q = history.modal_displacements_at(i);
                let mut running = 0.0;
                for k in 0..n {
                    running += c[k] * q[k];
                    partial[k] = sign * running;
                }
                if partial[n - 1] > best[n - 1] {
                    best_time_step = i;
                }
                for k in 0..n {
                    best[k] = best[k].max(partial[k]);
                }
            }
            let defined = static_value != 0.0 && static_value.abs() > 1e-9 * largest[qi];
            let static_magnitude = static_value.abs();
            let daf_by_modes: Vec<f64> = if defined {
                best.iter().map(|b| b / static_magnitude).collect()
            } else {
                Vec::new()
            };
            let daf = daf_by_modes.last().copied();
            let (participation, cumulative) =
                normalise((0..n).map(|k| c[k].abs() * rms[k]).collect());
            entries.push(StationDaf {
                name: basis.stations[s].name.clone(),
                station: s,
                quantity,
                direction,
                static_max: static_value,
                static_max_time: history.time(static_idx),
                dynamic_max: sign * best[n - 1],
                dynamic_max_time: history.time(best_time_step),
                daf,
                impact_factor: daf.map(|d| d - 1.0),
                convergence_mode: convergence_mode(&daf_by_modes, options.convergence_tolerance),
                daf_by_modes,
                cutoff_k1: cutoff(&cumulative, options.cutoff_k1_level),
                cutoff_k2: cutoff(&cumulative, options.cutoff_k2_level),
                participation,
                cumulative_participation: cumulative,
            });
        }
    }

    // RDM per station.
    let station_rdm: Vec<StationRdm> = (0..station_count)
        .map(|s| {
            let u = &entries[2 * s];
            let m = &entries[2 * s + 1];
            let ratio = |a: f64, b: f64| if b != 0.0 { Some(a / b) } else { None };
            let rdm = match (u.daf, m.daf) {
                (Some(a), Some(b)) => ratio(a, b),
                _ => None,
            };
            let rdm_by_modes = if rdm.is_some() {
                u.daf_by_modes
                    .iter()
                    .zip(&m.daf_by_modes)
                    .map(|(&a, &b)| ratio(a, b))
                    .collect()
            } else {
                Vec::new()
            };
            StationRdm {
                name: basis.stations[s].name.clone(),
                station: s,
                rdm,
                rdm_by_modes,
            }
        })
        .collect();
    let rdm_station = options.rdm_station.or_else(|| {
        (0..station_count)
            .filter(|&s| !basis.stations[s].over_support && entries[2 * s].daf.is_some())
            .max_by(|&a, &b| {
                let (ea, eb) = (extremes[2 * a].1.abs(), extremes[2 * b].1.abs());
                ea.total_cmp(&eb).then(b.cmp(&a))
            })
    });

    // Deck-wide participation (Eq. 30): deflection over all deck nodes, moment over all stations.
    let nodes = basis.deck.node_count();
    let mut node_weight = vec![0.0; n];
    for j in 0..nodes {
        for k in 0..n {
            node_weight[k] += basis.deck_deflection[j * n + k].abs();
        }
    }
    let mut station_weight = vec![0.0; n];
    for s in 0..station_count {
        let c = basis.station_values(s, Quantity::BendingMoment);
        for k in 0..n {
            station_weight[k] += c[k].abs();
        }
    }
    let (deflection, deflection_cumulative) =
        normalise((0..n).map(|k| node_weight[k] * rms[k]).collect());
    let (moment, moment_cumulative) =
        normalise((0..n).map(|k| station_weight[k] * rms[k]).collect());
    let deck_participation = DeckParticipation {
        deflection_k1: cutoff(&deflection_cumulative, options.cutoff_k1_level),
        deflection_k2: cutoff(&deflection_cumulative, options.cutoff_k2_level),
        moment_k1: cutoff(&moment_cumulative, options.cutoff_k1_level),
        moment_k2: cutoff(&moment_cumulative, options.cutoff_k2_level),
        deflection,
        deflection_cumulative,
        moment,
        moment_cumulative,
    };

    let (rdm, rdm_by_modes) = match rdm_station {
        Some(s) => (station_rdm[s].rdm, station_rdm[s].rdm_by_modes.clone()),
        None => (None, Vec::new()),
    };
    Ok(DafReport {
        stations: entries,
        rdm_station: rdm_station.map(|s| basis.stations[s].name.clone()),
        rdm,
        rdm_by_modes,
        station_rdm,
        deck_participation,
        mode_count: n,
        time_step: history.time_step,
        contact_losses: history.contact_losses.clone(),
        warnings: history.warnings.clone(),
        truncated_runs: Vec::new(),
    })
}

/// Re-runs the crossing with only the first K modes, for each K in `mode_counts`, and returns
/// each run's DAFs: the second definition of DAF(K), to compare with the partial sums of one
/// run. Every re-run uses the time step of the full-basis run (the given one, or the default for
/// all N modes), so that the comparison isolates the truncation.
pub fn rerun_truncated(
    basis: &ModalBasis,
    influence: &InfluenceLines,
    crossing: &Crossing,
    solver_options: &SolverOptions,
    analysis_options: &AnalysisOptions,
    mode_counts: &[usize],
) -> Result<Vec<TruncatedRun>, AnalysisError> {
    let n = basis.mode_count();
    let mut options = solver_options.clone();
    options.time_step = Some(
        solver_options
            .time_step
            .unwrap_or_else(|| default_time_step(basis, crossing, solver_options)),
    );
    let mut runs = Vec::with_capacity(mode_counts.len());
    for &k in mode_counts {
        if k == 0 || k > n {
            return Err(AnalysisError::InvalidModeCount {
                mode_count: k,
                available: n,
            });
        }
        let keep: Vec<usize> = (0..k).collect();
        let truncated = basis.select_modes(&keep);
        let history = simulate(&truncated, crossing, &options)?;
        let report = analyse(&truncated, influence, &history, analysis_options)?;
        runs.push(TruncatedRun {
            mode_count: k,
            stations: report
                .stations
                .iter()
                .map(|e| TruncatedStationDaf {
                    name: e.name.clone(),
                    quantity: e.quantity,
                    daf: e.daf,
                })
                .collect(),
            rdm: report.rdm,
        });
    }
    Ok(runs)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn convergence_mode_is_the_first_mode_after_which_the_daf_stays_in_the_band() {
        // DAF(N) = 1.10; band ±0.011. K = 3 enters the band but K = 4 leaves it; from 5 on it stays.
        let daf = [0.5, 1.0, 1.095, 1.2, 1.105, 1.099, 1.1];
        assert_eq!(convergence_mode(&daf, 0.01), Some(5));
        assert_eq!(convergence_mode(&[], 0.01), None);
    }

    #[test]
    fn cutoff_is_the_first_mode_whose_cumulative_share_reaches_the_level() {
        let (share, cumulative) = normalise(vec![90.0, 6.0, 3.0, 1.0]);
        assert!((share.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        assert_eq!(cutoff(&cumulative, 0.95), Some(2));
        assert_eq!(cutoff(&cumulative, 0.99), Some(3));
        assert_eq!(cutoff(&cumulative, 1.0), Some(4));
    }
}
