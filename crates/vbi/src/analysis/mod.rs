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

mod check_modes;
mod continuous_extreme;
mod node_major;
mod partial_sums;
mod participation;
mod runs;
mod single_vehicle;
mod static_correction;
mod static_reference;
mod wheel_fields;

pub use participation::{
    convergence_mode, convergence_modes_against_modes_kept, cutoff_mode, cutoff_mode_among,
    cutoffs_against_modes_kept,
};
pub use static_reference::{
    static_force_reference, static_reference, StaticReference, StaticReferenceCache,
};

pub(crate) use runs::{RunAnalyses, RunToAnalyse};

use partial_sums::{PartialSumMaxima, LANES};
use participation::{cutoff, normalise};
use runs::analyse_runs_with;
use static_correction::{stream_history, PanelSink};
use static_reference::StaticExtremes;

use crate::codes::StationCodeFactors;
use crate::influence::InfluenceLines;
use crate::modal::{ModalBasis, Quantity};
use crate::solver::{ContactLoss, ResponseHistory, SolverError, SolverWarning};

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
    /// Which stations get the full analysis (DAF(K), participation, the static-corrected
    /// series). Default [`StationScope::All`].
    #[serde(default)]
    pub stations: StationScope,
    /// Entries whose governing direction is given instead of read from the sign of the static
    /// extreme of largest magnitude (default none). Such an entry's static extreme, dynamic
    /// extreme and DAF are those of its given direction: what a lifetime analysis needs, whose
    /// effects each govern in one sense fixed by the influence line, whichever sense one event
    /// loads most (a midspan shear's ±½). An entry the run does not load in that direction has
    /// a static extreme of 0 and no DAF.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub governing_directions: Vec<GoverningDirection>,
}

/// A station's quantity read in a given direction ([`AnalysisOptions::governing_directions`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GoverningDirection {
    /// The station's name.
    pub station: String,
    /// The quantity.
    pub quantity: Quantity,
    /// The direction that governs.
    pub direction: Direction,
}

/// Which stations [`analyse`] reports.
#[derive(Debug, Clone, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StationScope {
    /// Every station of the basis.
    #[default]
    All,
    /// Only the RDM station (deflection and moment): what a parametric study records, at a
    /// fraction of the cost, since the analysis is O(steps × modes) per station. The static
    /// reference still covers every station, to choose the RDM station.
    RdmStation,
    /// The RDM station and the stations of these names (what a study's `record` asks for), in
    /// station order, each once. A name that the basis has no station of is skipped: the input
    /// refuses unknown names before any work.
    RdmStationAnd(Vec<String>),
}

impl Default for AnalysisOptions {
    fn default() -> Self {
        AnalysisOptions {
            convergence_tolerance: 0.01,
            cutoff_k1_level: 0.95,
            cutoff_k2_level: 0.99,
            rdm_station: None,
            stations: StationScope::All,
            governing_directions: Vec::new(),
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
    /// +1 for [`Direction::Positive`], −1 for [`Direction::Negative`].
    pub fn sign(self) -> f64 {
        match self {
            Direction::Positive => 1.0,
            Direction::Negative => -1.0,
        }
    }
}

/// DAF and modal results of one station and quantity.
///
/// The headline (`dynamic_max`, `daf`, `impact_factor`, `daf_by_modes`) is the converged
/// answer: the static-corrected (mode-acceleration) series, which moves by a few thousandths at
/// most between 42 and 110 modes of the paper's grillage (docs/verification.md), with its
/// convergence indicator `convergence`. The paper's plain partial modal sums (Eqs. 15–16 with
/// the first K modes) stay beside it, named `*_paper`: they reproduce the paper's figures, but
/// for a bending moment or a force they still depend on where the list of modes was cut.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StationDaf {
    /// Station name.
    pub name: String,
    /// Station index in the basis.
    pub station: usize,
    /// Deflection, bending moment, shear force or support reaction.
    pub quantity: Quantity,
    /// Governing direction: the sign of the static extreme.
    pub direction: Direction,
    /// Static extreme, signed [m, N·m or N].
    pub static_max: f64,
    /// Time of the static extreme [s].
    pub static_max_time: f64,
    /// With two or more vehicles: the largest static extreme of one vehicle alone, in the
    /// direction of `static_max`, signed [m, N·m] (the event's `static_max` is the static
    /// envelope of all of them together, the headline's reference); None with one vehicle, and
    /// for shear forces and reactions.
    #[serde(default)]
    pub static_max_single_vehicle: Option<f64>,
    /// converged dynamic_max / static_max_single_vehicle [-]: the DAF against the heaviest
    /// single vehicle's static effect.
    #[serde(default)]
    pub daf_single_vehicle: Option<f64>,
    /// The converged series, the headline: the static-corrected sums (the quasi-static response
    /// to the contact forces through the exact influence lines plus the modes' inertia and
    /// damping part), or the paper's plain sums for want of them (`static_corrected`).
    pub converged: DafSeries,
    /// IM = DAF − 1 of the converged DAF [-].
    pub impact_factor: Option<f64>,
    /// How much the converged DAF still moves over the last modes kept ([`DafConvergence`]);
    /// None with one mode or without a DAF.
    pub convergence: Option<DafConvergence>,
    /// How much the converged DAF moved from the run at twice the step
    /// ([`TimeStepConvergence`]); None where the run was not checked (a given `time_step_s`,
    /// `time_step_check = false`) or without a DAF.
    #[serde(default)]
    pub time_step_convergence: Option<TimeStepConvergence>,
    /// Whether the headline is the static-corrected series (true), or the paper's plain sum for
    /// want of it (false: a mode of the basis has no positive frequency; a warning says so).
    pub static_corrected: bool,
    /// The paper's series: plain partial modal sums (Eqs. 15–16, Figs. 12–20), whose
    /// convergence mode depends on N where the plain sum has not converged
    /// (docs/paper-reproduction.md).
    pub paper: DafSeries,
    /// Modal participation MPS_k at this station, k = 1…N [-] (sums to 1).
    pub participation: Vec<f64>,
    /// Cumulative participation [-].
    pub cumulative_participation: Vec<f64>,
    /// Cut-off mode K1 (1-based).
    pub cutoff_k1: Option<usize>,
    /// Cut-off mode K2 (1-based).
    pub cutoff_k2: Option<usize>,
}

/// One DAF series of a station entry, K = 1…N modes summed: the dynamic extreme of the sum of
/// all N modes, its time, the DAF it gives, DAF(K) and the convergence mode. A station entry
/// holds two ([`StationDaf::converged`], [`StationDaf::paper`]), computed alike from their own
/// partial sums.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DafSeries {
    /// Dynamic extreme in the governing direction of the sum of all N modes, signed [m, N·m or
    /// N].
    pub dynamic_max: f64,
    /// Time of the dynamic extreme [s].
    pub dynamic_max_time: f64,
    /// DAF = dynamic_max / static_max [-]; None when the static response vanishes (for example
    /// the deflection over a support).
    pub daf: Option<f64>,
    /// DAF(K) = max over t of the K-mode sum / |static_max|, K = 1…N [-] (empty when DAF is
    /// None).
    pub daf_by_modes: Vec<f64>,
    /// Convergence mode CM (1-based): the first K from which DAF(K) stays within the
    /// convergence tolerance of DAF(N).
    pub convergence_mode: Option<usize>,
    /// DAF(K) of the sums continued over the check modes, K = N + 1…N + C [-]
    /// ([`ModalBasis::check_modes`](crate::modal::ModalBasis::check_modes): modes above N
    /// integrated against the crossing's contact forces without feeding back). Empty for the
    /// paper's plain series, without check modes, or where DAF is None.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub daf_by_check_modes: Vec<f64>,
}

/// How a run's time step was checked: how many times the default step was halved, and
/// whether every deflection and moment DAF of the run at the final step Δt moved by at most
/// [`TIME_STEP_TOLERANCE`] from the run at 2Δt.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TimeStepCheck {
    /// The default step the run started from [s].
    pub default_step: f64,
    /// How many times it was halved (0: the default step was converged).
    pub halvings: u32,
    /// The largest |DAF(Δt) − DAF(2Δt)| / |DAF(Δt)| over the deflection and moment entries
    /// [-].
    pub largest_relative_change: f64,
    /// Whether it is within [`TIME_STEP_TOLERANCE`].
    pub converged: bool,
}

/// The convergence indicator of a DAF series in the number of modes:
///
///   change = max( max |DAF(K) − DAF(N)| over the last w = ⌈N/2⌉ modes kept, K = N − w … N − 1,
///                 2 · max |DAF(K) − DAF(N)| over the check modes, K = N + 1 … N + C )
///
/// ([`DafSeries::daf_by_check_modes`]), and whether it is within the tolerance
/// `AnalysisOptions::convergence_tolerance` (1 % of DAF(N) by default, the tolerance of the
/// convergence mode CM). A change over modes already kept cannot see a mode above N that is
/// the first to move an entry (shear forces and reactions on a grillage move at vertical
/// bending modes above N, between plateaus of torsion modes); the check modes see it, without
/// their feedback on the contact forces, and the factor 2 covers what they leave out. Measured
/// against runs with four times the modes at a fixed step (docs/theory.md, "What it does not
/// see"; docs/verification.md §30).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DafConvergence {
    /// The larger of max |DAF(K) − DAF(N)| over the window and 2 · max |DAF(K) − DAF(N)| over
    /// the check modes [-].
    pub change: f64,
    /// The number of last modes kept the change is taken over (⌈N/2⌉, at least 1).
    pub window: usize,
    /// The number of check modes it is taken over too (0: none, so that it cannot see a mode
    /// above N).
    #[serde(default)]
    pub check_modes: usize,
    /// change ≤ tolerance · |DAF(N)|.
    pub converged: bool,
}

/// The convergence indicator of a converged DAF in the time step: the DAF of the same crossing
/// run at twice the step, and the change DAF(Δt) − DAF(2Δt). For the scheme's second-order
/// error e(Δt) ≈ C Δt², the change is 3 e(Δt): it overstates the error of DAF(Δt) three times.
/// The default step is halved until every deflection and moment DAF changes by at most
/// [`TIME_STEP_TOLERANCE`] of itself (`crate::crossing::time_step_check`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TimeStepConvergence {
    /// The check's step 2Δt [s].
    pub coarse_step: f64,
    /// The converged DAF at 2Δt [-].
    pub coarse_step_daf: f64,
    /// DAF(Δt) − DAF(2Δt) [-].
    pub change: f64,
    /// |change| ≤ [`TIME_STEP_TOLERANCE`] · |DAF(Δt)|.
    pub converged: bool,
}

/// The relative change of a DAF between the steps Δt and 2Δt that the default step accepts:
/// 0.1 % (issue 46: every deflection and moment DAF within 0.1 % of its Δt-converged value; at
/// the second order the error of DAF(Δt) is a third of the change).
pub const TIME_STEP_TOLERANCE: f64 = 1.0e-3;

impl TimeStepConvergence {
    /// The indicator of a DAF at Δt from the DAF at the check's step 2Δt.
    pub fn of(daf: f64, coarse_step: f64, coarse_step_daf: f64) -> TimeStepConvergence {
        let change = daf - coarse_step_daf;
        TimeStepConvergence {
            coarse_step,
            coarse_step_daf,
            change,
            converged: change.abs() <= TIME_STEP_TOLERANCE * daf.abs(),
        }
    }

    /// |change| / |DAF(Δt)| [-] (the change itself for a vanishing DAF).
    pub fn relative_change(&self) -> f64 {
        let daf = self.coarse_step_daf + self.change;
        if daf == 0.0 {
            self.change.abs()
        } else {
            self.change.abs() / daf.abs()
        }
    }
}

impl DafConvergence {
    /// The indicator of a series DAF(K), K = 1…N, continued over check modes by `beyond`
    /// (K = N + 1…N + C; may be empty); None for fewer than two values of DAF(K), K ≤ N.
    pub fn of(series: &[f64], beyond: &[f64], tolerance: f64) -> Option<DafConvergence> {
        let n = series.len();
        let &last = series.last()?;
        if n < 2 {
            return None;
        }
        let window = n.div_ceil(2).clamp(1, n - 1);
        let largest = |values: &[f64]| {
            (values.iter())
                .map(|d| (d - last).abs())
                .fold(0.0, f64::max)
        };
        let change = largest(&series[n - 1 - window..n - 1]).max(2.0 * largest(beyond));
        Some(DafConvergence {
            change,
            window,
            check_modes: beyond.len(),
            converged: change <= tolerance * last.abs(),
        })
    }
}

/// RDM of one station: the converged one (of the static-corrected DAFs) first, the paper's
/// (of the plain modal sums) beside it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StationRdm {
    /// Station name.
    pub name: String,
    /// Station index.
    pub station: usize,
    /// RDM = DAF_u / DAF_M of the converged DAFs [-].
    pub rdm: Option<f64>,
    /// Converged RDM(K), K = 1…N (None where DAF_M(K) = 0 or a DAF is undefined).
    pub rdm_by_modes: Vec<Option<f64>>,
    /// The paper's RDM, of the plain modal sums of all N modes [-].
    pub rdm_paper: Option<f64>,
    /// The paper's RDM(K), K = 1…N.
    pub rdm_paper_by_modes: Vec<Option<f64>>,
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
    /// Bending-moment MPS_k over the girders' sagging stations (moments exist only at stations;
    /// `participation::moment_participation_stations`) [-].
    pub moment: Vec<f64>,
    /// Cumulative moment participation [-].
    pub moment_cumulative: Vec<f64>,
    /// Moment K1 (1-based).
    pub moment_k1: Option<usize>,
    /// Moment K2 (1-based).
    pub moment_k2: Option<usize>,
    /// The same cut-off modes counted among the vertical bending modes only.
    pub vertical_bending: BendingCutoffs,
}

/// Cut-off modes K1, K2 counted among the vertical bending modes only: the deck participation
/// restricted to those modes and normalised over them; K is a number of bending modes (the
/// count a beam model gives, which has no torsion or lateral modes). Torsion modes of a
/// grillage (girders moving against each other) spread a few per cent of the participation thinly
/// over many modes and push the plain K1, K2 far up (docs/paper-reproduction.md, Table 2).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct BendingCutoffs {
    /// Deflection K1 (number of bending modes).
    pub deflection_k1: Option<usize>,
    /// Deflection K2.
    pub deflection_k2: Option<usize>,
    /// Moment K1.
    pub moment_k1: Option<usize>,
    /// Moment K2.
    pub moment_k2: Option<usize>,
}

/// The paper's mode-count indicators against the number of modes kept, n = 1…N (each vector
/// has N entries; entry n − 1 is the value with the first n modes): the convergence modes of the
/// paper's DAF_u and DAF_M at the RDM station ([`convergence_modes_against_modes_kept`]) and the
/// deck-wide cut-off modes of Eq. 30 ([`cutoffs_against_modes_kept`]). Where they still grow at
/// n = N they measure the truncation, not the bridge (docs/paper-reproduction.md).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct ModesKeptIndicators {
    /// CM of the paper's DAF_u(1…n) at the RDM station.
    pub cm_u_paper: Vec<Option<usize>>,
    /// CM of the paper's DAF_M(1…n) at the RDM station.
    pub cm_m_paper: Vec<Option<usize>>,
    /// Deck-wide deflection K1 of the first n modes.
    pub k1_u: Vec<Option<usize>>,
    /// Deck-wide deflection K2.
    pub k2_u: Vec<Option<usize>>,
    /// Deck-wide moment K1.
    pub k1_m: Vec<Option<usize>>,
    /// Deck-wide moment K2.
    pub k2_m: Vec<Option<usize>>,
}

impl ModesKeptIndicators {
    fn of(
        deflection: Option<&StationDaf>,
        moment: Option<&StationDaf>,
        deck: &DeckParticipation,
        options: &AnalysisOptions,
    ) -> ModesKeptIndicators {
        let cms = |entry: Option<&StationDaf>| {
            entry.map_or_else(Vec::new, |e| {
                convergence_modes_against_modes_kept(
                    &e.paper.daf_by_modes,
                    options.convergence_tolerance,
                )
            })
        };
        let (k1, k2) = (options.cutoff_k1_level, options.cutoff_k2_level);
        ModesKeptIndicators {
            cm_u_paper: cms(deflection),
            cm_m_paper: cms(moment),
            k1_u: cutoffs_against_modes_kept(&deck.deflection, k1),
            k2_u: cutoffs_against_modes_kept(&deck.deflection, k2),
            k1_m: cutoffs_against_modes_kept(&deck.moment, k1),
            k2_m: cutoffs_against_modes_kept(&deck.moment, k2),
        }
    }
}

/// DAFs of one station from a run with only the first K modes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TruncatedStationDaf {
    /// Station name.
    pub name: String,
    /// Quantity.
    pub quantity: Quantity,
    /// The converged (static-corrected) DAF of the K-mode run [-].
    pub daf: Option<f64>,
    /// The paper's DAF (plain modal sum) of the K-mode run [-].
    pub daf_paper: Option<f64>,
}

/// A re-run of the crossing with only the first K modes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TruncatedRun {
    /// K.
    pub mode_count: usize,
    /// DAF per station and quantity.
    pub stations: Vec<TruncatedStationDaf>,
    /// The converged RDM at the report's RDM station [-].
    pub rdm: Option<f64>,
    /// The paper's RDM at the report's RDM station [-].
    pub rdm_paper: Option<f64>,
}

/// Everything the analysis of one crossing gives.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DafReport {
    /// Per analysed station and quantity (station order; deflection, moment, then the station's
    /// force: shear force, or support reaction at a support): every station, or only the RDM
    /// station (deflection and moment) under [`StationScope::RdmStation`].
    pub stations: Vec<StationDaf>,
    /// Name of the station of the top-level RDM.
    pub rdm_station: Option<String>,
    /// The converged RDM = DAF_u / DAF_M at `rdm_station` [-].
    pub rdm: Option<f64>,
    /// The converged RDM(K) at `rdm_station`, K = 1…N.
    pub rdm_by_modes: Vec<Option<f64>>,
    /// The paper's RDM (plain modal sums) at `rdm_station` [-].
    pub rdm_paper: Option<f64>,
    /// The paper's RDM(K) at `rdm_station`, K = 1…N.
    pub rdm_paper_by_modes: Vec<Option<f64>>,
    /// RDM of every analysed station.
    pub station_rdm: Vec<StationRdm>,
    /// Deck-wide participation.
    pub deck_participation: DeckParticipation,
    /// The paper's CM (at `rdm_station`) and deck-wide K1, K2 had only the first n modes been
    /// kept, n = 1…N.
    pub modes_kept: ModesKeptIndicators,
    /// Number of modes N.
    pub mode_count: usize,
    /// Time step [s].
    pub time_step: f64,
    /// The check of the time step, where it was made (`crate::crossing::time_step_check`).
    #[serde(default)]
    pub time_step_check: Option<TimeStepCheck>,
    /// Tyre contact losses of the run (never hidden).
    pub contact_losses: Vec<ContactLoss>,
    /// Solver warnings of the run.
    pub warnings: Vec<SolverWarning>,
    /// Re-runs with K modes ([`crate::crossing::rerun_truncated`]); empty unless requested.
    pub truncated_runs: Vec<TruncatedRun>,
    /// The design codes' impact factors of every entry of `stations`, in its order
    /// ([`crate::codes`]); filled by [`crate::crossing::run_crossing`], empty from [`analyse`].
    #[serde(default)]
    pub design_codes: Vec<StationCodeFactors>,
}

impl DafReport {
    /// The entry of a station and quantity.
    pub fn entry(&self, station: usize, quantity: Quantity) -> Option<&StationDaf> {
        self.stations
            .iter()
            .find(|e| e.station == station && e.quantity == quantity)
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
    // Saturating: a deserialised history may claim any number of instants.
    let recorded = history.step_count.saturating_mul(n);
    if history.modal_displacement.len() != recorded {
        return Err(AnalysisError::Mismatch {
            what: "modal displacements of the history (instants × modes)",
            expected: recorded,
            found: history.modal_displacement.len(),
        });
    }
    check_basis(basis)
}

/// Checks that the basis's station tables hold a value per station and mode.
fn check_basis(basis: &ModalBasis) -> Result<(), AnalysisError> {
    let (s, n) = (basis.stations.len(), basis.mode_count());
    let force_tables = match basis.station_force.is_empty() {
        true => None,
        false => Some(("station_force length", basis.station_force.len())),
    };
    for (what, len) in [
        ("station_deflection length", basis.station_deflection.len()),
        ("station_moment length", basis.station_moment.len()),
    ]
    .into_iter()
    .chain(force_tables)
    {
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

/// One station's histories, one per quantity: (quantity, values in its SI unit).
pub type StationSeries = Vec<(Quantity, Vec<f64>)>;

/// The static-corrected (mode-acceleration) responses of every station with every kept mode,
/// R̃_N(t) = Q(t) + Σ_k cₖ (qₖ(t) − Fₖ(t)/ωₖ²) (see [`static_correction`](self)), per station
/// as (quantity, history) for each quantity that the basis and the influence lines both have
/// (deflection [m], bending moment [N·m], shear force or support reaction [N]): the converged
/// histories, which tend to the exact static response as the speed goes to zero. `None` when a
/// mode has no positive finite frequency or the contact forces were not recorded.
pub fn corrected_station_responses(
    basis: &ModalBasis,
    influence: &InfluenceLines,
    history: &ResponseHistory,
) -> Result<Option<Vec<StationSeries>>, AnalysisError> {
    check_history(basis, history)?;
    let n = basis.mode_count();
    let stations: Vec<usize> = (0..basis.stations.len()).collect();
    let targets = analysed_targets(basis, influence, &stations, true);
    let sink = ResponseSink {
        coefficients: targets
            .iter()
            .map(|&(s, quantity)| basis.station_values(s, quantity))
            .collect(),
        values: vec![vec![0.0; history.step_count]; targets.len()],
        mode_count: n,
    };
    let (sink, corrected) = stream_history((basis, influence), history, (targets.clone(), sink));
    if !corrected {
        return Ok(None);
    }
    let mut out: Vec<StationSeries> = vec![Vec::new(); stations.len()];
    for (&(s, quantity), values) in targets.iter().zip(sink.values) {
        out[s].push((quantity, values));
    }
    Ok(Some(out))
}

/// The static-corrected response of one station's quantity with only the first K modes, for
/// each K of `mode_counts` (returned ascending, each once): R̃_K(t_i) = Q(t_i) + Σ_{k<K} cₖ yₖ(t_i),
/// the partial sums whose K = N is the converged history ([`corrected_station_responses`]), and
/// K = N + 1 … N + C with the basis's check modes after the N (integrated against the contact
/// forces without feeding back, as `daf_by_check_modes`): what a convergence indicator of a
/// quantity read from the whole history (a fatigue damage) compares. `None` when the correction
/// does not exist (as there); a K outside 1 … N + C is left out.
pub fn corrected_station_response_by_modes(
    basis: &ModalBasis,
    influence: &InfluenceLines,
    history: &ResponseHistory,
    (station, quantity): (usize, Quantity),
    mode_counts: &[usize],
) -> Result<Option<Vec<PartialHistory>>, AnalysisError> {
    check_history(basis, history)?;
    check_station(station, basis.stations.len())?;
    let mut coefficients = basis.station_values(station, quantity).to_vec();
    if let Some(check) = usable_check_modes(basis) {
        coefficients.extend_from_slice(check.station_values(station, quantity));
    }
    let mut counts: Vec<usize> = mode_counts
        .iter()
        .copied()
        .filter(|&k| (1..=coefficients.len()).contains(&k))
        .collect();
    counts.sort_unstable();
    counts.dedup();
    let sink = PartialSumSink {
        coefficients: &coefficients,
        counts: counts.clone(),
        values: vec![vec![0.0; history.step_count]; counts.len()],
    };
    let targets = vec![(station, quantity)];
    let (sink, corrected) = stream_history((basis, influence), history, (targets, sink));
    Ok(corrected.then(|| counts.into_iter().zip(sink.values).collect()))
}

/// A history with the first K modes: (K, its values per instant in the quantity's SI unit).
pub type PartialHistory = (usize, Vec<f64>);

/// The check modes a streamed analysis integrates: the basis's, where every one has a positive
/// finite frequency (the stream's own condition).
pub fn usable_check_modes(basis: &ModalBasis) -> Option<&ModalBasis> {
    basis.check_modes.as_deref().filter(|check| {
        (check.modes.iter()).all(|m| m.circular_frequency.is_finite() && m.circular_frequency > 0.0)
    })
}

/// [`corrected_station_response_by_modes`]'s sink: R̃_K of one target for several K.
struct PartialSumSink<'a> {
    coefficients: &'a [f64],
    counts: Vec<usize>,
    values: Vec<Vec<f64>>,
}

impl PanelSink for PartialSumSink<'_> {
    fn plain(&mut self, _panel: &[f64], _instants: (usize, usize)) {}

    fn corrected(
        &mut self,
        panel: &[f64],
        quasi_static: &[[f64; LANES]],
        (start, len): (usize, usize),
    ) {
        for j in 0..len {
            let mut sum = 0.0;
            let mut k = 0;
            for (values, &count) in self.values.iter_mut().zip(&self.counts) {
                while k < count {
                    sum += self.coefficients[k] * panel[k * LANES + j];
                    k += 1;
                }
                values[start + j] = quasi_static[0][j] + sum;
            }
        }
    }
}

/// The corrected responses R̃_N(t_i) = Q(t_i) + Σₖ cₖ yₖ(t_i) of some targets, written as the
/// panels stream (the plain panels are not wanted).
struct ResponseSink<'a> {
    /// cₖ of each target.
    coefficients: Vec<&'a [f64]>,
    /// R̃_N of each target, per instant.
    values: Vec<Vec<f64>>,
    mode_count: usize,
}

impl PanelSink for ResponseSink<'_> {
    fn plain(&mut self, _panel: &[f64], _instants: (usize, usize)) {}

    fn corrected(
        &mut self,
        panel: &[f64],
        quasi_static: &[[f64; LANES]],
        (start, len): (usize, usize),
    ) {
        let n = self.mode_count;
        let each = self.coefficients.iter().zip(&mut self.values);
        for ((c, values), quasi_static) in each.zip(quasi_static) {
            for j in 0..len {
                let modal: f64 = (0..n).map(|k| c[k] * panel[k * LANES + j]).sum();
                values[start + j] = quasi_static[j] + modal;
            }
        }
    }
}

/// The (station, quantity) pairs analysed for `stations`, in station order and then in the
/// order of [`Quantity::ALL`]: deflection and bending moment always; with `with_forces`, the
/// station's force quantity too where both the basis and the influence lines have it.
fn analysed_targets(
    basis: &ModalBasis,
    influence: &InfluenceLines,
    stations: &[usize],
    with_forces: bool,
) -> Vec<(usize, Quantity)> {
    stations
        .iter()
        .flat_map(|&s| {
            basis
                .station_quantities(s)
                .into_iter()
                .filter(move |&q| {
                    PAIRED.contains(&q) || (with_forces && influence.has_quantity(s, q))
                })
                .map(move |q| (s, q))
        })
        .collect()
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

/// RDM = DAF_u / DAF_M and RDM(K) (None where DAF_M is zero; empty when either DAF is None).
fn ratio_of(
    deflection: Option<f64>,
    moment: Option<f64>,
    deflection_by_modes: &[f64],
    moment_by_modes: &[f64],
) -> (Option<f64>, Vec<Option<f64>>) {
    let ratio = |a: f64, b: f64| if b != 0.0 { Some(a / b) } else { None };
    match (deflection, moment) {
        (Some(a), Some(b)) => (
            ratio(a, b),
            deflection_by_modes
                .iter()
                .zip(moment_by_modes)
                .map(|(&a, &b)| ratio(a, b))
                .collect(),
        ),
        _ => (None, Vec::new()),
    }
}

/// Checks that the option fractions lie in (0, 1].
fn check_options(options: &AnalysisOptions) -> Result<(), AnalysisError> {
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
    Ok(())
}

/// The two quantities of every station, whose DAFs give the RDM.
const PAIRED: [Quantity; 2] = [Quantity::Deflection, Quantity::BendingMoment];

/// The step and signed value of a history's extreme (the value of largest magnitude; the first
/// on a tie; step 0 and 0 for an all-zero history).
fn extreme_of(history: &[f64]) -> (usize, f64) {
    history
        .iter()
        .copied()
        .enumerate()
        .fold((0usize, 0.0f64), |best, (i, v)| {
            if v.abs() > best.1.abs() {
                (i, v)
            } else {
                best
            }
        })
}

/// Whether a static extreme `value` has a DAF: one negligible next to the largest of its
/// quantity over the stations, `largest` (1e-9, far below any physical response yet above
/// rounding of a zero), has none.
fn has_daf(value: f64, largest: f64) -> bool {
    value != 0.0 && value.abs() > 1e-9 * largest
}

/// The static extreme of one entry: step, signed value, and whether it has a DAF.
#[derive(Clone, Copy)]
struct EntryStatic {
    value: f64,
    /// The largest static extreme of one vehicle alone (runs of two or more vehicles).
    single_vehicle: Option<f64>,
    /// The fractional instant of `value` (t = instant · Δt).
    instant: f64,
    defined: bool,
    /// The direction given for the entry ([`AnalysisOptions::governing_directions`]), if any.
    given: Option<Direction>,
}

impl EntryStatic {
    /// The direction of the static extreme, that of the dynamic one compared with it: the given
    /// one, else the sign of the extreme.
    fn direction(&self) -> Direction {
        if let Some(given) = self.given {
            return given;
        }
        if self.value < 0.0 {
            Direction::Negative
        } else {
            Direction::Positive
        }
    }
}

/// The static extremes of `targets`: deflection and moment from the extremes of every
/// station; a force quantity from its static history in `forces` (indexed like `stations`),
/// compared with the largest of the same quantity over the analysed stations. A target with a
/// given direction (`given`, indexed like `targets`) takes its extreme in that direction.
fn entry_statics(
    extremes: &StaticExtremes,
    targets: &[(usize, Quantity)],
    (stations, forces): (&[usize], &[Vec<f64>]),
    given: &[Option<Direction>],
) -> Vec<EntryStatic> {
    let force_history = |s: usize| stations.iter().position(|&t| t == s).map(|j| &forces[j]);
    let force_extreme = |s: usize| force_history(s).map_or((0, 0.0), |f| extreme_of(f));
    let largest = |quantity: Quantity| {
        targets
            .iter()
            .filter(|&&(_, q)| q == quantity)
            .map(|&(s, _)| force_extreme(s).1.abs())
            .fold(0.0f64, f64::max)
    };
    targets
        .iter()
        .zip(given)
        .map(|(&(s, quantity), &given)| {
            let paired = PAIRED.iter().position(|&q| q == quantity);
            let force = |(step, value): (usize, f64)| {
                (value, step as f64, has_daf(value, largest(quantity)))
            };
            let (mut value, mut instant, mut defined) = match paired {
                Some(qi) => {
                    let (value, instant) = extremes.continuous_at(s, qi);
                    (value, instant, extremes.defined(s, qi))
                }
                None => force(force_extreme(s)),
            };
            let mut single_vehicle = paired.and_then(|qi| extremes.single_vehicle_at(s, qi));
            let natural = match value < 0.0 {
                true => Direction::Negative,
                false => Direction::Positive,
            };
            if let Some(direction) = given.filter(|&d| d != natural) {
                single_vehicle = None;
                (value, instant, defined) = match paired {
                    Some(qi) => {
                        let (value, instant) = extremes.opposite_at(s, qi);
                        (value, instant, extremes.has_daf_of(value, qi))
                    }
                    None => force(
                        force_history(s)
                            .map_or((0, 0.0), |f| directed_extreme_of(f, direction.sign())),
                    ),
                };
            }
            EntryStatic {
                value,
                single_vehicle,
                instant,
                defined,
                given,
            }
        })
        .collect()
}

/// The step and signed value of a history's extreme in the direction σ = `sign` (the largest
/// σ·v; the first on a tie; step 0 and 0 when no value has that sign).
fn directed_extreme_of(history: &[f64], sign: f64) -> (usize, f64) {
    history
        .iter()
        .copied()
        .enumerate()
        .fold((0usize, 0.0f64), |best, (i, v)| {
            if sign * v > sign * best.1 {
                (i, v)
            } else {
                best
            }
        })
}

/// What every station entry of one run shares.
struct RunData<'a> {
    basis: &'a ModalBasis,
    history: &'a ResponseHistory,
    options: &'a AnalysisOptions,
    /// The maxima of the plain partial sums of each target.
    plain: Vec<PartialSumMaxima>,
    /// The maxima of the static-corrected partial sums of each target, if the run has them.
    corrected: Option<Vec<PartialSumMaxima>>,
    rms: Vec<f64>,
}

/// The DAF entry of the `t`-th analysed (station, quantity), `target`, whose static extreme is
/// `statics`: DAF and DAF(K) of the plain and the static-corrected series, participation, CM,
/// K1, K2.
fn station_entry(
    run: &RunData,
    t: usize,
    target: (usize, Quantity),
    statics: EntryStatic,
) -> StationDaf {
    let (basis, history, options) = (run.basis, run.history, run.options);
    let n = basis.mode_count();
    let (s, quantity) = target;
    let static_value = statics.value;
    let direction = statics.direction();
    let sign = direction.sign();
    let c = basis.station_values(s, quantity);
    let plain = &run.plain[t];
    let corrected = run.corrected.as_ref().map(|maxima| &maxima[t]);
    let defined = statics.defined;
    let static_magnitude = static_value.abs();
    let by_modes = |maxima: &[f64]| -> Vec<f64> {
        if defined {
            maxima.iter().map(|b| b / static_magnitude).collect()
        } else {
            Vec::new()
        }
    };
    let daf_paper_by_modes = by_modes(&plain.maxima);
    let (participation, cumulative) = normalise((0..n).map(|k| c[k].abs() * run.rms[k]).collect());
    let full_maximum =
        |m: &PartialSumMaxima| sign * m.maxima.last().copied().unwrap_or(f64::NEG_INFINITY);
    // The headline: the static-corrected series, or the plain one for want of it.
    let converged = corrected.unwrap_or(plain);
    let daf_by_modes = by_modes(&converged.maxima);
    let tolerance = options.convergence_tolerance;
    // The full sum's extreme between the instants where it was refined (the converged
    // deflections and moments), else the sampled one; DAF(K) stays the sampled series.
    let series = |maxima: &PartialSumMaxima, daf_by_modes: Vec<f64>| {
        let (dynamic_max, dynamic_max_time, daf) = match maxima.continuous_full_maximum {
            Some((value, instant)) => (
                sign * value,
                instant * history.time_step,
                defined.then(|| value / static_magnitude),
            ),
            None => (
                full_maximum(maxima),
                history.time(maxima.step_of_full_maximum),
                daf_by_modes.last().copied(),
            ),
        };
        DafSeries {
            dynamic_max,
            dynamic_max_time,
            daf,
            convergence_mode: convergence_mode(&daf_by_modes, tolerance),
            daf_by_modes,
            daf_by_check_modes: by_modes(&maxima.beyond),
        }
    };
    let converged_series = series(converged, daf_by_modes.clone());
    let daf = converged_series.daf;
    StationDaf {
        name: basis.stations[s].name.clone(),
        station: s,
        quantity,
        direction,
        static_max: static_value,
        static_max_time: statics.instant * history.time_step,
        static_max_single_vehicle: statics.single_vehicle.filter(|_| defined),
        daf_single_vehicle: (statics.single_vehicle)
            .filter(|v| defined && *v != 0.0)
            .map(|v| converged_series.dynamic_max / v),
        impact_factor: daf.map(|d| d - 1.0),
        convergence: DafConvergence::of(
            &daf_by_modes,
            &converged_series.daf_by_check_modes,
            tolerance,
        ),
        time_step_convergence: None,
        static_corrected: corrected.is_some(),
        converged: converged_series,
        paper: series(plain, daf_paper_by_modes),
        cutoff_k1: cutoff(&cumulative, options.cutoff_k1_level),
        cutoff_k2: cutoff(&cumulative, options.cutoff_k2_level),
        participation,
        cumulative_participation: cumulative,
    }
}

/// RDM and RDM(K), plain and static-corrected, of every analysed station (from its deflection
/// and moment entries).
fn station_rdms(basis: &ModalBasis, analysed: &[usize], entries: &[StationDaf]) -> Vec<StationRdm> {
    let entry = |s: usize, quantity: Quantity| {
        entries
            .iter()
            .find(|e| e.station == s && e.quantity == quantity)
            .expect("every analysed station has a deflection and a moment entry")
    };
    analysed
        .iter()
        .map(|&s| {
            let u = entry(s, Quantity::Deflection);
            let m = entry(s, Quantity::BendingMoment);
            let (rdm, rdm_by_modes) = ratio_of(
                u.converged.daf,
                m.converged.daf,
                &u.converged.daf_by_modes,
                &m.converged.daf_by_modes,
            );
            let (rdm_paper, rdm_paper_by_modes) = ratio_of(
                u.paper.daf,
                m.paper.daf,
                &u.paper.daf_by_modes,
                &m.paper.daf_by_modes,
            );
            StationRdm {
                name: basis.stations[s].name.clone(),
                station: s,
                rdm,
                rdm_by_modes,
                rdm_paper,
                rdm_paper_by_modes,
            }
        })
        .collect()
}

/// The warnings on the headline DAFs: that the converged DAF of some entries still moves by
/// more than the tolerance over the last modes kept (the entry that moves most, and how many
/// more do); and that the headline is the paper's plain sum for want of the static-corrected
/// series (a mode of the basis without a positive frequency).
fn convergence_warnings(entries: &[StationDaf], tolerance: f64) -> Vec<SolverWarning> {
    let unsettled: Vec<(&StationDaf, DafConvergence)> = entries
        .iter()
        .filter_map(|e| e.convergence.filter(|c| !c.converged).map(|c| (e, c)))
        .collect();
    let worst = unsettled
        .iter()
        .max_by(|a, b| a.1.change.total_cmp(&b.1.change));
    let not_converged = worst.map(|(entry, convergence)| SolverWarning::DafNotConverged {
        station: entry.name.clone(),
        quantity: entry.quantity.name().to_string(),
        change: convergence.change,
        window: convergence.window,
        check_modes: convergence.check_modes,
        tolerance,
        further_entries: unsettled.len() - 1,
    });
    let plain = entries.iter().filter(|e| !e.static_corrected).count();
    let paper_series =
        (plain > 0).then_some(SolverWarning::HeadlineIsPaperSeries { entries: plain });
    not_converged.into_iter().chain(paper_series).collect()
}

/// Full DAF analysis of one run.
pub fn analyse(
    basis: &ModalBasis,
    influence: &InfluenceLines,
    history: &ResponseHistory,
    options: &AnalysisOptions,
) -> Result<DafReport, AnalysisError> {
    analyse_runs_with((basis, influence), &[(history, options)], None)
        .pop()
        .expect("one report per run")
}

/// [`analyse`], taking the static reference from `static_references` when a run with the same
/// wheel paths on the same influence lines stored it there (the result is the same bit for bit).
pub fn analyse_with_cache(
    basis: &ModalBasis,
    influence: &InfluenceLines,
    history: &ResponseHistory,
    options: &AnalysisOptions,
    static_references: &StaticReferenceCache,
) -> Result<DafReport, AnalysisError> {
    analyse_runs_with(
        (basis, influence),
        &[(history, options)],
        Some(static_references),
    )
    .pop()
    .expect("one report per run")
}

/// [`analyse_with_cache`] of several runs on one bridge, in order, the same reports bit for bit:
/// the runs whose wheels take the same paths (a study's road samples of one crossing) share the
/// evaluation of the mode shapes at the wheels for their static-corrected series
/// ([`static_correction`](self)), computed once per instant for all of them.
pub fn analyse_runs(
    basis: &ModalBasis,
    influence: &InfluenceLines,
    runs: &[(&ResponseHistory, &AnalysisOptions)],
    static_references: &StaticReferenceCache,
) -> Vec<Result<DafReport, AnalysisError>> {
    analyse_runs_with((basis, influence), runs, Some(static_references))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_convergence_indicator_is_the_change_over_the_last_half_or_twice_that_over_the_check_modes(
    ) {
        // N = 10: the window is the last ⌈10/2⌉ = 5 modes before N, K = 5…9.
        let series = [0.5, 0.9, 1.2, 1.0, 1.1, 1.05, 1.3, 1.08, 1.095, 1.1];
        let c = DafConvergence::of(&series, &[], 0.01).unwrap();
        assert_eq!((c.window, c.check_modes), (5, 0));
        // K = 7: |1.3 − 1.1| = 0.2.
        assert!((c.change - 0.2).abs() < 1e-15, "{c:?}");
        assert!(!c.converged);
        // Check modes that move less than half the window's change do not raise it.
        let c = DafConvergence::of(&series, &[1.15, 1.0], 0.01).unwrap();
        assert!(
            (c.change - 0.2).abs() < 1e-15 && c.check_modes == 2,
            "{c:?}"
        );
        // A flat kept series whose check modes move it: the check modes decide.
        let flat = [1.0, 1.05, 1.1, 1.1, 1.1, 1.1];
        let c = DafConvergence::of(&flat, &[1.1, 1.104, 1.103], 0.01).unwrap();
        assert_eq!((c.window, c.check_modes), (3, 3));
        assert!((c.change - 0.008).abs() < 1e-12, "{c:?}");
        // 0.008 ≤ 1 % of 1.1 = 0.011: converged; with 0.5 % (0.0055) not.
        assert!(c.converged);
        assert!(
            !DafConvergence::of(&flat, &[1.1, 1.104, 1.103], 0.005)
                .unwrap()
                .converged
        );
        // N = 3: two modes of window (at most N − 1); N = 1: no indicator.
        let c = DafConvergence::of(&[1.0, 1.2, 1.21], &[], 0.01).unwrap();
        assert_eq!(c.window, 2);
        assert!((c.change - 0.21).abs() < 1e-12 && !c.converged);
        assert_eq!(DafConvergence::of(&[1.1], &[1.2], 0.01), None);
        assert_eq!(DafConvergence::of(&[], &[], 0.01), None);
    }

    fn entry(name: &str, series: &[f64], static_corrected: bool) -> StationDaf {
        StationDaf {
            name: name.into(),
            station: 0,
            quantity: Quantity::BendingMoment,
            direction: Direction::Positive,
            static_max: 1.0,
            static_max_time: 0.0,
            static_max_single_vehicle: None,
            daf_single_vehicle: None,
            converged: DafSeries {
                dynamic_max: 1.0,
                dynamic_max_time: 0.0,
                daf: series.last().copied(),
                daf_by_modes: series.to_vec(),
                convergence_mode: None,
                daf_by_check_modes: Vec::new(),
            },
            impact_factor: None,
            convergence: DafConvergence::of(series, &[], 0.01),
            time_step_convergence: None,
            static_corrected,
            paper: DafSeries {
                dynamic_max: 1.0,
                dynamic_max_time: 0.0,
                daf: None,
                daf_by_modes: Vec::new(),
                convergence_mode: None,
                daf_by_check_modes: Vec::new(),
            },
            participation: Vec::new(),
            cumulative_participation: Vec::new(),
            cutoff_k1: None,
            cutoff_k2: None,
        }
    }

    #[test]
    fn an_unconverged_headline_is_warned_about_naming_the_entry_that_moves_most() {
        let settled = entry("settled", &[1.0, 1.1, 1.1, 1.1, 1.1], true);
        let moving = entry("moving", &[1.0, 1.1, 1.2, 1.3, 1.1], true);
        let worst = entry("worst", &[1.0, 1.1, 1.2, 1.5, 1.1], true);
        assert!(convergence_warnings(std::slice::from_ref(&settled), 0.01).is_empty());
        let warnings = convergence_warnings(&[settled.clone(), moving, worst], 0.01);
        match &warnings[..] {
            [SolverWarning::DafNotConverged {
                station,
                change,
                further_entries,
                ..
            }] => {
                assert_eq!(station, "worst");
                assert!((change - 0.4).abs() < 1e-12);
                assert_eq!(*further_entries, 1);
            }
            other => panic!("{other:?}"),
        }
        // A headline that had to fall back on the paper's plain sum is named too.
        let plain = entry("plain", &[1.0, 1.1, 1.1, 1.1, 1.1], false);
        assert_eq!(
            convergence_warnings(&[settled, plain], 0.01),
            [SolverWarning::HeadlineIsPaperSeries { entries: 1 }]
        );
    }
}
