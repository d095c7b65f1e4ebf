//! The pipeline from a typed [`Scenario`] to a [`RunResult`]: the one path that `vbi run`,
//! `vbi study`, the benchmarks and the Python bindings call.
//!
//! ```text
//! BridgeSpec --prepare_bridge--> PreparedBridge (FE model -> modes, influence lines; once per bridge)
//!                                      |
//! Scenario (vehicle, road, motion) ----+--run_crossing--> RunResult (history, DAF report)
//! ```
//!
//! [`prepare_bridge`] does the work that depends on the bridge alone (discretisation, shift-invert
//! Lanczos, the exact static influence lines) and [`run_crossing`] the work of one crossing
//! (vehicle assembly, road sample, coupled Newmark integration, DAF analysis). A study prepares
//! each bridge once and runs all of its crossings on it; the prepared bridge is read-only, so
//! crossings run in parallel on one.
//!
//! Every type here is the library's own and serde-serialisable: a scenario written as JSON and
//! read back is the same scenario, which is what a study's `--resume` compares.

mod batches;
mod event;
mod fatigue;
mod histories;
pub mod keys;
pub mod plausibility;
mod scenario;
mod streamed;
pub mod time_step_check;

pub use batches::{
    integration_batches, repeats_run, same_crossing_bit_for_bit, same_run_but_road_seed,
};
pub use event::{input_entry, road_extent, vehicle_runs};
pub use fatigue::{check_fatigue_details, crossing_fatigue, FatigueDetailError};
pub use histories::{
    station_acceleration, station_history_columns, station_peak_acceleration,
    vehicle_history_columns, HistoryColumn, VehicleHistoryTable,
};
pub use keys::{Key, KeyError, KeyValue, SCENARIO_KEYS};
pub use scenario::{BridgeSpec, Scenario, DEFAULT_SPEED, DEFAULT_VEHICLE};
// The traffic types a scenario is made of, where its other parts are.
pub use crate::traffic::{Entry, LanePattern, Motion, TrafficVehicle, DEFAULT_PLATOON_GAP};

use crate::analysis::{
    analyse, analyse_runs, AnalysisError, AnalysisOptions, DafReport, StaticReferenceCache,
    TruncatedRun, TruncatedStationDaf,
};
use crate::fe::statics::{influence_lines, StaticError};
use crate::fe::{discretise, FeError};
use crate::influence::InfluenceLines;
use crate::modal::{solve_modes, ModalBasis, ModalError};
use crate::road::{generate, RoadError};
use crate::solver::{
    default_time_step, simulate, simulate_batch, Crossing, Recording, ResponseHistory, SolverError,
    SolverOptions,
};
use crate::vehicle::VehicleError;

/// The text of an error and its causes in one line, `outer: cause: cause` (`anyhow`'s
/// alternate form): the one formatter of error chains for study tables, nested measurement
/// errors and the Python exceptions.
pub fn error_chain(error: &dyn std::error::Error) -> String {
    let mut text = error.to_string();
    let mut cause = error.source();
    while let Some(inner) = cause {
        text.push_str(": ");
        text.push_str(&inner.to_string());
        cause = inner.source();
    }
    text
}

/// Errors of the pipeline, each naming the stage that failed; the stage's own error is the
/// source.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PipelineError {
    /// The FE discretisation of the bridge failed.
    #[error("discretising the bridge")]
    Discretise(#[source] FeError),
    /// The modal analysis failed (a mechanism, a non-converged eigen solve).
    #[error("modal analysis of the bridge")]
    Modes(#[source] ModalError),
    /// The static influence lines could not be computed.
    #[error("static influence lines of the bridge")]
    Influence(#[source] StaticError),
    /// An imported modal basis does not make a basis, or keeps no mode.
    #[error("the imported modes of the bridge (none kept: `modes` and `mode_kinds` select them)")]
    ImportedModes(#[source] crate::modal::import::ImportError),
    /// The vehicle is not a valid model.
    #[error("assembling the vehicle")]
    Vehicle(#[source] VehicleError),
    /// The road profile could not be generated.
    #[error("generating the road profile")]
    Road(#[source] RoadError),
    /// The coupled integration failed.
    #[error("vehicle crossing")]
    Crossing(#[source] SolverError),
    /// The DAF analysis failed.
    #[error("DAF analysis")]
    Analysis(#[source] AnalysisError),
    /// A truncated re-run failed.
    #[error("re-running the crossing with fewer modes")]
    Rerun(#[source] AnalysisError),
    /// A re-run asks for more modes than the basis holds (or none).
    #[error(
        "cannot re-run with {mode_count} modes: the bridge's basis keeps {available} of the \
         {solved} modes solved for (`modes`), those of the kinds in `mode_kinds`; each of \
         `rerun_modes` must lie from 1 to {available}"
    )]
    RerunModeCount {
        /// Requested number of modes.
        mode_count: usize,
        /// Modes kept in the basis.
        available: usize,
        /// Modes solved for.
        solved: usize,
    },
    /// The scenario's traffic stream cannot be drawn.
    /// A fatigue detail the bridge cannot evaluate (`index` into the scenario's details).
    #[error("fatigue detail {}", index + 1)]
    FatigueDetail {
        index: usize,
        #[source]
        source: FatigueDetailError,
    },
    #[error("drawing the traffic stream")]
    Stream(#[source] crate::traffic::stream::StreamError),
    /// A vehicle of the event cannot move as asked, or does not fit on the deck.
    #[error("vehicle {vehicle} ({label}): {reason}")]
    Traffic {
        /// Vehicle number in the event (from 1: the scenario's own vehicle).
        vehicle: usize,
        /// How the input names it.
        label: String,
        /// What is wrong, and what is allowed.
        reason: String,
    },
    /// The scenario's bridge is not the bridge that was prepared.
    #[error("the scenario's bridge differs from the prepared bridge: prepare the scenario's own")]
    BridgeMismatch,
}

/// A bridge ready for crossings: its FE size, modal basis and exact static influence lines.
#[derive(Debug, Clone)]
pub struct PreparedBridge {
    /// What was prepared.
    pub spec: BridgeSpec,
    /// Degrees of freedom of the FE model.
    pub dof_count: usize,
    /// The modal basis (the kept mode kinds), with its stations.
    pub basis: ModalBasis,
    /// Static influence lines of every station from the full stiffness.
    pub influence: InfluenceLines,
    /// The static references of the crossings run on it, reused by the crossings whose wheels
    /// take the same paths (a study's road samples).
    pub static_references: StaticReferenceCache,
}

/// FE model, modes and influence lines of a bridge: the work that a study does once per bridge.
pub fn prepare_bridge(spec: &BridgeSpec) -> Result<PreparedBridge, PipelineError> {
    if let crate::model::BridgeModel::ImportedModes(imported) = &spec.model {
        let basis = imported_basis(imported, &spec.modal)?;
        // The other program's influence lines if given (exact), else the modes' flexibility.
        let influence =
            crate::modal::imported_influence::imported_influence_lines(&imported.data, &basis)
                .map_err(PipelineError::ImportedModes)?
                .unwrap_or_else(|| crate::modal::flexibility::flexibility_influence_lines(&basis));
        return Ok(PreparedBridge {
            spec: spec.clone(),
            dof_count: 0,
            basis,
            influence,
            static_references: StaticReferenceCache::default(),
        });
    }
    let fe = discretise(&spec.model, &spec.mesh).map_err(PipelineError::Discretise)?;
    let basis = solve_modes(&fe, &spec.modal).map_err(PipelineError::Modes)?;
    let influence = influence_lines(&fe).map_err(PipelineError::Influence)?;
    Ok(PreparedBridge {
        spec: spec.clone(),
        dof_count: fe.dof_count(),
        basis,
        influence,
        static_references: StaticReferenceCache::default(),
    })
}

/// Refuses, before any numeric work, a bridge that [`prepare_bridge`] would refuse for its
/// mesh or for the memory of its modal analysis: the mesh is made ([`discretise`]: too many
/// nodes or elements in a span, a structural mechanism) and the modal analysis planned
/// ([`crate::modal::check_modal_plan`]: the symbolic Cholesky analysis and the memory estimate).
/// Milliseconds for any bridge that a crossing can afford; `vbi check` calls it.
pub fn check_bridge(spec: &BridgeSpec) -> Result<(), PipelineError> {
    if let crate::model::BridgeModel::ImportedModes(imported) = &spec.model {
        let basis = imported_basis(imported, &spec.modal)?;
        crate::modal::imported_influence::imported_influence_lines(&imported.data, &basis)
            .map_err(PipelineError::ImportedModes)?;
        return Ok(());
    }
    let fe = discretise(&spec.model, &spec.mesh).map_err(PipelineError::Discretise)?;
    crate::modal::check_modal_plan(&fe, &spec.modal).map_err(PipelineError::Modes)?;
    if let crate::model::BridgeModel::ImportedMatrices(_) = spec.model {
        // An imported K that is indefinite or singular is an input error, not a mesh one: it is
        // factorised once here (what the modal solve does first), so that it is refused before
        // any crossing.
        crate::fe::statics::StaticSolver::new(&fe).map_err(|error| match error {
            crate::fe::statics::StaticError::Mechanism(modal) => PipelineError::Modes(modal),
            other => PipelineError::Influence(other),
        })?;
    }
    Ok(())
}

/// The stations of a bridge's model, as its prepared bridge will have them, without the modal
/// solve: those of the discretised model, or of an imported basis.
pub fn bridge_stations(
    spec: &BridgeSpec,
) -> Result<Vec<crate::model::station::Station>, PipelineError> {
    if let crate::model::BridgeModel::ImportedModes(imported) = &spec.model {
        return Ok(imported_basis(imported, &spec.modal)?.stations);
    }
    Ok(discretise(&spec.model, &spec.mesh)
        .map_err(PipelineError::Discretise)?
        .stations)
}

/// The basis of a bridge known only by its modes, as [`solve_modes`] keeps modes: the first
/// `mode_count` given, those of the kinds in `keep_kinds`. Errors: data that do not make a
/// basis, or no mode kept.
fn imported_basis(
    imported: &crate::model::ImportedModes,
    options: &crate::modal::ModalOptions,
) -> Result<ModalBasis, PipelineError> {
    let basis = crate::modal::import::build_imported_basis(&imported.data)
        .map_err(PipelineError::ImportedModes)?;
    let keep: Vec<usize> = (0..basis.mode_count().min(options.mode_count))
        .filter(|&k| options.keep_kinds.contains(&basis.modes[k].kind))
        .collect();
    if keep.is_empty() {
        return Err(PipelineError::ImportedModes(
            crate::modal::import::ImportError::NoModes,
        ));
    }
    Ok(basis.select_modes(&keep))
}

/// Why a scenario's bridge could not be prepared, naming the bridge or the scenario; the
/// pipeline's error is the source.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ScenarioBridgeError {
    /// The FE model, modes or influence lines of the bridge failed.
    #[error("the bridge {label}")]
    Prepare {
        /// How the scenario names the bridge.
        label: String,
        /// What failed.
        #[source]
        source: PipelineError,
    },
    /// The scenario's re-run mode counts exceed the modes kept.
    #[error("scenario `{name}`")]
    RerunModeCounts {
        /// The scenario's name.
        name: String,
        /// The refusal.
        #[source]
        source: PipelineError,
    },
}

/// The bridge of a scenario prepared, with the scenario's re-run mode counts checked against
/// the modes kept before any crossing is run: what `vbi run` and each bridge group of a study
/// do first.
pub fn prepare_scenario_bridge(scenario: &Scenario) -> Result<PreparedBridge, ScenarioBridgeError> {
    let bridge =
        prepare_bridge(&scenario.bridge).map_err(|source| ScenarioBridgeError::Prepare {
            label: scenario.bridge_label.clone(),
            source,
        })?;
    check_rerun_mode_counts(&bridge, &scenario.rerun_mode_counts).map_err(|source| {
        ScenarioBridgeError::RerunModeCounts {
            name: scenario.name.clone(),
            source,
        }
    })?;
    Ok(bridge)
}

/// Everything one crossing produces; the bridge's basis and influence lines stay with the
/// [`PreparedBridge`], which a study shares among many crossings.
#[derive(Debug, Clone)]
pub struct RunResult {
    /// The crossing as it was integrated (assembled vehicle, road sample, motion).
    pub crossing: Crossing,
    /// Time histories of the modal coordinates, the vehicle and the contacts.
    pub history: ResponseHistory,
    /// The DAF analysis, with the truncated re-runs that the scenario asked for.
    pub report: DafReport,
    /// The fatigue of the scenario's details ([`crossing_fatigue`]); empty without details,
    /// and where the history was not recorded (a study's crossings).
    pub fatigue: Vec<crate::fatigue::DetailFatigue>,
}

/// The crossing of a scenario: its vehicles assembled and placed ([`vehicle_runs`]:
/// the scenario's vehicle with its front axle at the start of the approach, its platoon, the
/// further vehicles of `traffic`), its road sampled over every tyre's path from t = 0 to the
/// exit ([`road_extent`]). The default track relation, coherent at the vehicle's
/// track ([`TrackCorrelation::VehicleTrack`](crate::road::TrackCorrelation::VehicleTrack)),
/// takes the track spacing of the scenario's own vehicle.
pub fn crossing_of(scenario: &Scenario) -> Result<Crossing, PipelineError> {
    let vehicles = vehicle_runs(scenario)?;
    let (start, end) = road_extent(scenario, &vehicles);
    let track_spacing = vehicles
        .first()
        .map_or(0.0, |run| run.vehicle.track_spacing());
    let mut road_spec = scenario.road.clone();
    road_spec.track_correlation = road_spec.track_correlation.resolved(track_spacing);
    let road = generate(&road_spec, start, end, road_spec.seed).map_err(PipelineError::Road)?;
    Ok(Crossing {
        vehicles,
        road,
        free_vibration_duration: scenario.free_vibration_duration,
    })
}

/// One crossing of the scenario's vehicle on its road over a prepared bridge, and its DAF
/// analysis (with the truncated re-runs of `scenario.rerun_mode_counts`).
pub fn run_crossing(
    bridge: &PreparedBridge,
    scenario: &Scenario,
) -> Result<RunResult, PipelineError> {
    run_crossings(bridge, &[scenario], Recording::Everything)
        .pop()
        .expect("one result per scenario")
}

/// [`run_crossing`] of each scenario, in order, the same results bit for bit; the crossings
/// that differ only in their road (a study's roughness samples of one bridge, vehicle and
/// speed) are integrated together by [`simulate_batch`](crate::solver::simulate_batch), which computes what depends on the
/// tyres' positions once per instant for all of them, and analysed together by
/// [`analyse_runs`]. A scenario that repeats an earlier one of the call ([`repeats_run`]: the
/// same run but for a road seed that its road does not read, and the same crossing bit for
/// bit) is given a copy of that one's result ([`run_distinct_crossings`] gives it a reference
/// instead). Memory: every crossing's history at once, unless `recording` is
/// [`Recording::OutcomeOnly`]: then each crossing is analysed instant by instant as it is
/// integrated, its history holds no table, and the reports are the same bit for bit (what a
/// study uses).
pub fn run_crossings(
    bridge: &PreparedBridge,
    scenarios: &[&Scenario],
    recording: Recording,
) -> Vec<Result<RunResult, PipelineError>> {
    run_distinct_crossings(bridge, scenarios, recording).into_results()
}

/// The results of [`run_crossings`] with each repeated run computed and held once: a
/// scenario that repeats an earlier one reads that one's result.
pub struct DistinctRuns {
    /// The result of each scenario; None for a repeat.
    results: Vec<Option<Result<RunResult, PipelineError>>>,
    /// The scenario whose result each scenario reads: itself, or the earlier one it repeats.
    sources: Vec<usize>,
}

impl DistinctRuns {
    /// Number of scenarios.
    pub fn len(&self) -> usize {
        self.results.len()
    }

    /// Whether there are no scenarios.
    pub fn is_empty(&self) -> bool {
        self.results.is_empty()
    }

    /// The result of scenario `i` (that of the run it repeats, for a repeat).
    ///
    /// # Panics
    /// If `i` is not a scenario of the call.
    pub fn result(&self, i: usize) -> &Result<RunResult, PipelineError> {
        self.results[self.sources[i]]
            .as_ref()
            .expect("every run that is not a repeat has its result")
    }

    /// One result per scenario, a repeat's a copy of its original's.
    pub fn into_results(mut self) -> Vec<Result<RunResult, PipelineError>> {
        for (i, &source) in self.sources.iter().enumerate() {
            if source != i {
                self.results[i] = self.results[source].clone();
            }
        }
        self.results
            .into_iter()
            .map(|result| result.expect("every scenario has its result"))
            .collect()
    }
}

/// [`run_crossings`] without the copies: a repeated run's result is held once, and the
/// repeats read it ([`DistinctRuns::result`]). A study takes its records this way: ten
/// samples of a smooth road are one crossing, not ten copies of its history.
pub fn run_distinct_crossings(
    bridge: &PreparedBridge,
    scenarios: &[&Scenario],
    recording: Recording,
) -> DistinctRuns {
    let mut results: Vec<Option<Result<RunResult, PipelineError>>> =
        scenarios.iter().map(|_| None).collect();
    // The checked crossings, in batches of equal solver options (simulate_batch takes one).
    let mut batches: Vec<(&SolverOptions, Vec<(usize, Crossing)>)> = Vec::new();
    let mut sources: Vec<usize> = (0..scenarios.len()).collect();
    for (i, scenario) in scenarios.iter().enumerate() {
        let crossing = match checked_crossing(bridge, scenario) {
            Ok(crossing) => crossing,
            Err(error) => {
                results[i] = Some(Err(error));
                continue;
            }
        };
        let mut earlier = batches.iter().flat_map(|(_, members)| members);
        let repeated =
            earlier.find(|(j, first)| repeats_run((scenarios[*j], first), (scenario, &crossing)));
        if let Some(&(original, _)) = repeated {
            sources[i] = original;
            continue;
        }
        match batches
            .iter_mut()
            .find(|(options, _)| **options == scenario.solver)
        {
            Some((_, members)) => members.push((i, crossing)),
            None => batches.push((&scenario.solver, vec![(i, crossing)])),
        }
    }
    for (options, members) in batches {
        let batch = (options, members, recording);
        for (i, result) in time_step_check::run_checked_batch(bridge, scenarios, batch) {
            results[i] = Some(result);
        }
    }
    DistinctRuns { results, sources }
}

/// What a crossing of a batch ends with: its history and its report, or the solver's error.
type Analysed = Result<(ResponseHistory, Result<DafReport, AnalysisError>), SolverError>;

/// One batch of [`run_crossings`]: its crossings (each with the index of its scenario)
/// integrated together, analysed together and completed; the results by scenario index. With
/// [`Recording::OutcomeOnly`] the analysis takes each instant as it is computed and no history
/// is held ([`streamed`]); otherwise the recorded histories are analysed. The reports are the
/// same bit for bit.
fn run_batch(
    bridge: &PreparedBridge,
    scenarios: &[&Scenario],
    (options, members, recording): (&SolverOptions, Vec<(usize, Crossing)>, Recording),
) -> Vec<(usize, Result<RunResult, PipelineError>)> {
    let (indices, crossings): (Vec<usize>, Vec<Crossing>) = members.into_iter().unzip();
    let analyses: Vec<&AnalysisOptions> = indices.iter().map(|&i| &scenarios[i].analysis).collect();
    let analysed = match recording {
        Recording::OutcomeOnly => {
            streamed::integrate_and_analyse(bridge, &crossings, (options, &analyses), true)
        }
        _ => analyse_recorded(bridge, &crossings, (options, &analyses), recording),
    };
    let completed = |((i, crossing), analysed): ((usize, Crossing), Analysed)| {
        let result = analysed
            .map_err(PipelineError::Crossing)
            .and_then(|(history, report)| {
                let report = report.map_err(PipelineError::Analysis)?;
                complete_run(bridge, scenarios[i], crossing, history, report)
            });
        (i, result)
    };
    indices
        .into_iter()
        .zip(crossings)
        .zip(analysed)
        .map(completed)
        .collect()
}

/// The crossings integrated together with their histories recorded, and the histories
/// analysed together ([`analyse_runs`]).
fn analyse_recorded(
    bridge: &PreparedBridge,
    crossings: &[Crossing],
    (options, analyses): (&SolverOptions, &[&AnalysisOptions]),
    recording: Recording,
) -> Vec<Analysed> {
    let histories = simulate_batch(&bridge.basis, crossings, options, recording);
    let runs: Vec<(&ResponseHistory, &AnalysisOptions)> = analyses
        .iter()
        .zip(&histories)
        .filter_map(|(&options, history)| Some((history.as_ref().ok()?, options)))
        .collect();
    let reports = analyse_runs(
        &bridge.basis,
        &bridge.influence,
        &runs,
        &bridge.static_references,
    );
    let mut reports = reports.into_iter();
    histories
        .into_iter()
        .map(|history| {
            let history = history?;
            Ok((history, reports.next().expect("a report per history")))
        })
        .collect()
}

/// The scenario's crossing, once the scenario is checked to run on `bridge`.
fn checked_crossing(
    bridge: &PreparedBridge,
    scenario: &Scenario,
) -> Result<Crossing, PipelineError> {
    if scenario.bridge != bridge.spec {
        return Err(PipelineError::BridgeMismatch);
    }
    check_rerun_mode_counts(bridge, &scenario.rerun_mode_counts)?;
    crossing_of(scenario)
}

/// A crossing's report completed: its warnings (a truncated static reference, implausible
/// magnitudes), its design-code factors and the truncated re-runs of
/// `scenario.rerun_mode_counts`.
fn complete_run(
    bridge: &PreparedBridge,
    scenario: &Scenario,
    crossing: Crossing,
    history: ResponseHistory,
    mut report: DafReport,
) -> Result<RunResult, PipelineError> {
    if bridge.basis.stations.is_empty() {
        report
            .warnings
            .push(crate::solver::SolverWarning::NoStations);
    }
    if let crate::model::BridgeModel::ImportedModes(imported) = &scenario.bridge.model {
        if imported.data.influence_lines.is_empty() {
            report
                .warnings
                .push(crate::solver::SolverWarning::TruncatedStaticReference {
                    mode_count: bridge.basis.mode_count(),
                });
        }
    }
    let implausible = plausibility::plausibility_warnings(
        &scenario.bridge.model,
        &bridge.basis,
        &bridge.influence,
        &report,
    );
    report.warnings.extend(implausible);
    report.design_codes = design_codes(bridge, scenario, &crossing, &report);
    if !scenario.rerun_mode_counts.is_empty() {
        report.truncated_runs = rerun_truncated(
            &bridge.basis,
            &bridge.influence,
            &crossing,
            &scenario.solver,
            &scenario.analysis,
            &scenario.rerun_mode_counts,
        )?;
    }
    let recorded = history.modal_displacement.len() >= history.step_count * history.mode_count;
    let fatigue = match recorded {
        true => crossing_fatigue(bridge, &history, &scenario.fatigue_details)?,
        false => Vec::new(),
    };
    Ok(RunResult {
        crossing,
        history,
        report,
        fatigue,
    })
}

/// The design codes' impact factors of every entry of the report ([`crate::codes`]): the
/// bridge's spans, section and vertical-bending frequencies, the axles of the scenario's own
/// vehicle (the first of the crossing) and the road's roughness.
fn design_codes(
    bridge: &PreparedBridge,
    scenario: &Scenario,
    crossing: &Crossing,
    report: &DafReport,
) -> Vec<crate::codes::StationCodeFactors> {
    let axle_count = crossing
        .vehicles
        .first()
        .map_or(0, |run| run.vehicle.axle_count());
    let inputs = crate::codes::CodeInputs::of(
        &scenario.bridge.model,
        &bridge.basis,
        axle_count,
        scenario.road.psd_at_iso_reference(),
    );
    crate::codes::design_code_factors(
        &inputs,
        &bridge.basis,
        report.stations.iter().map(|e| (e.station, e.quantity)),
    )
}

/// Refuses, before any crossing, re-run mode counts that the bridge's basis cannot serve.
pub fn check_rerun_mode_counts(
    bridge: &PreparedBridge,
    mode_counts: &[usize],
) -> Result<(), PipelineError> {
    let available = bridge.basis.mode_count();
    match mode_counts.iter().find(|&&k| k == 0 || k > available) {
        Some(&mode_count) => Err(PipelineError::RerunModeCount {
            mode_count,
            available,
            solved: bridge.spec.modal.mode_count,
        }),
        None => Ok(()),
    }
}

/// Re-runs the crossing with only the first K modes of `basis`, for each K in `mode_counts`,
/// and returns each run's DAFs: the second definition of DAF(K), to compare with the partial
/// sums of one run. Every re-run uses the time step of the full-basis run (the given one, or the
/// default for all N modes), so that the comparison isolates the truncation.
pub fn rerun_truncated(
    basis: &ModalBasis,
    influence: &InfluenceLines,
    crossing: &Crossing,
    solver_options: &SolverOptions,
    analysis_options: &AnalysisOptions,
    mode_counts: &[usize],
) -> Result<Vec<TruncatedRun>, PipelineError> {
    let options = SolverOptions {
        time_step: Some(
            solver_options
                .time_step
                .unwrap_or_else(|| default_time_step(basis, crossing, solver_options)),
        ),
        ..solver_options.clone()
    };
    let rerun = |k: usize| -> Result<TruncatedRun, AnalysisError> {
        if k == 0 || k > basis.mode_count() {
            return Err(AnalysisError::InvalidModeCount {
                mode_count: k,
                available: basis.mode_count(),
            });
        }
        let keep: Vec<usize> = (0..k).collect();
        let truncated = basis.select_modes(&keep);
        let history = simulate(&truncated, crossing, &options)?;
        let report = analyse(&truncated, influence, &history, analysis_options)?;
        Ok(TruncatedRun {
            mode_count: k,
            stations: report
                .stations
                .iter()
                .map(|e| TruncatedStationDaf {
                    name: e.name.clone(),
                    quantity: e.quantity,
                    daf: e.converged.daf,
                    daf_paper: e.paper.daf,
                })
                .collect(),
            rdm: report.rdm,
            rdm_paper: report.rdm_paper,
        })
    };
    mode_counts
        .iter()
        .map(|&k| rerun(k).map_err(PipelineError::Rerun))
        .collect()
}

#[cfg(test)]
mod tests;
