//! The DAF analyses of runs, taken as their instants stream ([`static_correction`](super::static_correction)):
//! from recorded histories ([`analyse_runs_with`]), or from crossings as the solver computes
//! them ([`RunAnalyses`], which the pipeline feeds instant by instant so that no history is
//! held). Both take each run's sums in the same order: the same reports, bit for bit.

use std::sync::Arc;

use super::continuous_extreme::dynamic_extreme;
use super::partial_sums::{MaximaOfPartialSums, PartialSumMaxima, LANES};
use super::participation::{self, rms_of_square_sums};
use super::static_correction::{feed_histories, forces_recorded, PanelSink, StreamedRun, Streams};
use super::static_reference::{static_force_reference_of, StaticExtremes};
use super::{
    analysed_targets, check_basis, check_history, check_options, check_station,
    convergence_warnings, entry_statics, station_entry, station_rdms, AnalysisError,
    AnalysisOptions, DafReport, Direction, EntryStatic, ModesKeptIndicators, RunData,
    StaticReferenceCache, StationDaf, StationScope,
};
use crate::influence::InfluenceLines;
use crate::modal::{ModalBasis, Quantity};
use crate::solver::{ResponseHistory, WheelPaths};

/// [`analyse_runs`](super::analyse_runs) of recorded histories, the static references taken
/// from `static_references` when given, else computed (a single run has nothing to share them
/// with).
pub(super) fn analyse_runs_with(
    (basis, influence): (&ModalBasis, &InfluenceLines),
    runs: &[(&ResponseHistory, &AnalysisOptions)],
    static_references: Option<&StaticReferenceCache>,
) -> Vec<Result<DafReport, AnalysisError>> {
    let checks: Vec<Result<(), AnalysisError>> = runs
        .iter()
        .map(|&(history, _)| check_history(basis, history))
        .collect();
    let checked: Vec<Option<&ResponseHistory>> = (runs.iter().zip(&checks))
        .map(|(&(history, _), check)| check.is_ok().then_some(history))
        .collect();
    let to_analyse = runs.iter().zip(checks).map(|(&(history, options), check)| {
        check.map(|()| RunToAnalyse {
            paths: history.wheel_paths(),
            options,
            with_forces: forces_recorded(history),
            time_step: history.time_step,
            with_check_modes: true,
        })
    });
    let mut analyses =
        RunAnalyses::new((basis, influence), to_analyse.collect(), static_references);
    feed_histories(&checked, |r, q, p| analyses.record(r, q, p));
    let histories = runs.iter().map(|&(history, _)| Some(history)).collect();
    analyses
        .finish(histories)
        .into_iter()
        .map(|report| report.expect("a report of every run with its history"))
        .collect()
}

/// One run for [`RunAnalyses`]: where its wheels are, its analysis, and whether its instants
/// will come with their contact forces (the static correction needs them).
pub(crate) struct RunToAnalyse<'a> {
    pub paths: WheelPaths<'a>,
    pub options: &'a AnalysisOptions,
    pub with_forces: bool,
    /// Δt [s].
    pub time_step: f64,
    /// Whether its static-corrected sums go on over the basis's check modes (the convergence
    /// indicator; a run whose indicator nobody reads, the time step's check at 2Δt, goes
    /// without).
    pub with_check_modes: bool,
}

/// The DAF analyses of runs on one bridge, taken as their instants come ([`RunAnalyses::record`]:
/// instant i of every run before instant i + 1 of any, as a [`LockstepBatch`](crate::solver::LockstepBatch)
/// computes them), so that no run's history is held: what [`analyse_runs`](super::analyse_runs)
/// gives for the recorded histories of the same runs, bit for bit. Each run's static reference
/// is computed (or taken from the cache) before its first instant, from its wheel paths.
pub(crate) struct RunAnalyses<'a> {
    basis: &'a ModalBasis,
    influence: &'a InfluenceLines,
    /// Each run's wheel paths (None for a run that cannot be analysed).
    paths: Vec<Option<WheelPaths<'a>>>,
    /// Each run prepared with its options, or why it cannot be analysed.
    prepared: Vec<Result<(PreparedRun, &'a AnalysisOptions), AnalysisError>>,
    /// Each prepared run's index among the streamed runs.
    stream_of: Vec<Option<usize>>,
    streams: Streams<'a, MaximaSink>,
}

impl<'a> RunAnalyses<'a> {
    /// The analyses of `runs` (an error: a run that cannot be analysed, whose report is that
    /// error), none of their instants given yet.
    pub(crate) fn new(
        (basis, influence): (&'a ModalBasis, &'a InfluenceLines),
        runs: Vec<Result<RunToAnalyse<'a>, AnalysisError>>,
        static_references: Option<&StaticReferenceCache>,
    ) -> Self {
        let (mut prepared, mut stream_of, mut streamed) = (Vec::new(), Vec::new(), Vec::new());
        let mut all_paths = Vec::new();
        for run in runs {
            all_paths.push(run.as_ref().ok().map(|run| run.paths));
            let run = run.and_then(|run| {
                let paths = run.paths;
                let ready = prepare_run((basis, influence), paths, run.options, static_references);
                Ok((ready?, run))
            });
            let (ready, run) = match run {
                Ok(ready) => ready,
                Err(error) => {
                    prepared.push(Err(error));
                    stream_of.push(None);
                    continue;
                }
            };
            let check_modes = basis
                .check_modes
                .as_deref()
                .filter(|_| run.with_check_modes);
            stream_of.push(Some(streamed.len()));
            streamed.push(StreamedRun {
                paths: run.paths,
                targets: ready.targets.clone(),
                sink: MaximaSink {
                    plain: ready.maxima_of_partial_sums(basis, None),
                    corrected: ready.maxima_of_partial_sums(basis, check_modes),
                    square_sums: vec![0.0; basis.mode_count()],
                },
                with_forces: run.with_forces,
                time_step: run.time_step,
                with_check_modes: run.with_check_modes,
            });
            prepared.push(Ok((ready, run.options)));
        }
        RunAnalyses {
            basis,
            influence,
            paths: all_paths,
            prepared,
            stream_of,
            streams: Streams::new(basis, influence, streamed),
        }
    }

    /// Gives run `r`'s next instant: its modal coordinates qₖ [kg^½·m] and contact forces P_w
    /// [N] (none for a run without them). Nothing for a run that cannot be analysed.
    pub(crate) fn record(&mut self, r: usize, modal_displacement: &[f64], contact_force: &[f64]) {
        if let Some(s) = self.stream_of[r] {
            self.streams.record(s, modal_displacement, contact_force);
        }
    }

    /// Run `r` will give no more instants (its integration failed): the others go on without it.
    pub(crate) fn abandon(&mut self, r: usize) {
        if let Some(s) = self.stream_of[r] {
            self.streams.abandon(s);
        }
    }

    /// The report of each run, given what its integration ended with: its history (whose
    /// tables may be empty; its time step, step count, warnings and contact losses are read), or
    /// None for a run that failed (no report then, unless it could not be analysed at all).
    pub(crate) fn finish(
        self,
        histories: Vec<Option<&ResponseHistory>>,
    ) -> Vec<Option<Result<DafReport, AnalysisError>>> {
        let mut sinks: Vec<Option<(MaximaSink, bool)>> =
            self.streams.finish().into_iter().map(Some).collect();
        let (basis, influence) = (self.basis, self.influence);
        let each = (self.prepared.into_iter().zip(self.stream_of))
            .zip(histories.into_iter().zip(self.paths));
        each.map(|((prepared, stream), (history, paths))| {
            let (prepared, options) = match prepared {
                Ok(prepared) => prepared,
                Err(error) => return Some(Err(error)),
            };
            let history = history?;
            let (sink, corrected) = stream.and_then(|s| sinks[s].take())?;
            let finish = |maxima: Vec<MaximaOfPartialSums>| -> Vec<PartialSumMaxima> {
                maxima.into_iter().map(|m| m.finish()).collect()
            };
            let mut corrected = corrected.then(|| finish(sink.corrected));
            if let (Some(maxima), Some(paths)) = (&mut corrected, paths) {
                refine_dynamic_extremes(influence, paths, &prepared, maxima);
            }
            let maxima = RunMaxima {
                plain: finish(sink.plain),
                corrected,
                rms: rms_of_square_sums(&sink.square_sums, history.step_count),
            };
            Some(Ok(conclude_run(
                basis,
                (history, options),
                prepared,
                maxima,
            )))
        })
        .collect()
    }
}

/// The extreme between the instants of each deflection and moment target's converged series
/// (all N modes, static-corrected), written as its `continuous_full_maximum`
/// ([`dynamic_extreme`]): the static extremes are taken between the instants too
/// ([`StaticExtremes`]), so that a DAF divides like by like.
fn refine_dynamic_extremes(
    influence: &InfluenceLines,
    paths: WheelPaths,
    prepared: &PreparedRun,
    maxima: &mut [PartialSumMaxima],
) {
    for ((&target, statics), maxima) in prepared.targets.iter().zip(&prepared.statics).zip(maxima) {
        let sign = statics.direction().sign();
        let around = maxima.around_full_maximum.map(|v| sign * v);
        let step = maxima.step_of_full_maximum;
        if let Some((value, instant)) =
            dynamic_extreme(influence, paths, target, (step, sign), around)
        {
            // Never below the sampled extreme (σ·R ≥ the sampled σ·R_N).
            let sampled = maxima.maxima.last().copied().unwrap_or(f64::NEG_INFINITY);
            if sign * value > sampled {
                maxima.continuous_full_maximum = Some((sign * value, instant));
            }
        }
    }
}

/// The maxima of the plain and the corrected partial sums of a run's targets, and the sums of
/// squares of its modal coordinates (for their rms), taken as the panels stream.
struct MaximaSink {
    plain: Vec<MaximaOfPartialSums>,
    corrected: Vec<MaximaOfPartialSums>,
    /// Σᵢ qₖ(tᵢ)² of each mode so far, in the order of time.
    square_sums: Vec<f64>,
}

impl PanelSink for MaximaSink {
    fn plain(&mut self, panel: &[f64], instants: (usize, usize)) {
        for maxima in &mut self.plain {
            maxima.add_panel(panel, instants, None);
        }
        for (sum, lanes) in self.square_sums.iter_mut().zip(panel.chunks_exact(LANES)) {
            for q in &lanes[..instants.1] {
                *sum += q * q;
            }
        }
    }

    fn corrected(
        &mut self,
        panel: &[f64],
        quasi_static: &[[f64; LANES]],
        instants: (usize, usize),
    ) {
        for (maxima, base) in self.corrected.iter_mut().zip(quasi_static) {
            maxima.add_panel(panel, instants, Some(base));
        }
    }
}

/// What one run's analysis knows before its series: the RDM station and the analysed (station,
/// quantity) targets with their static extremes.
struct PreparedRun {
    rdm_station: Option<usize>,
    analysed: Vec<usize>,
    targets: Vec<(usize, Quantity)>,
    statics: Vec<EntryStatic>,
}

impl PreparedRun {
    /// The maxima of each target's partial sums, none taken yet, each in its static extreme's
    /// direction, continued over the `check` modes where given.
    fn maxima_of_partial_sums(
        &self,
        basis: &ModalBasis,
        check: Option<&ModalBasis>,
    ) -> Vec<MaximaOfPartialSums> {
        let each = self.targets.iter().zip(&self.statics);
        each.map(|(&(s, quantity), entry_static)| {
            let sign = entry_static.direction().sign();
            let beyond = check.map_or(&[][..], |check| check.station_values(s, quantity));
            MaximaOfPartialSums::with_check_modes(basis.station_values(s, quantity), beyond, sign)
        })
        .collect()
    }
}

/// The maxima of a run's partial sums: plain, and static-corrected if the run has them; and
/// the rms of its modal coordinates.
struct RunMaxima {
    plain: Vec<PartialSumMaxima>,
    corrected: Option<Vec<PartialSumMaxima>>,
    /// rms(qₖ) of each mode [kg^½·m].
    rms: Vec<f64>,
}

/// The checks and the first half of [`analyse_with_cache`](super::analyse_with_cache) for one
/// run whose wheels take `paths` (its history, if recorded, checked by the caller).
fn prepare_run(
    (basis, influence): (&ModalBasis, &InfluenceLines),
    paths: WheelPaths,
    options: &AnalysisOptions,
    static_references: Option<&StaticReferenceCache>,
) -> Result<PreparedRun, AnalysisError> {
    // The basis's tables (a recorded history's sizes are checked by its caller, before).
    check_basis(basis)?;
    check_options(options)?;
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
    let extremes = match static_references {
        Some(cache) => cache.static_extremes(influence, paths)?,
        None => Arc::new(StaticExtremes::of(influence, paths)?),
    };
    let rdm_station = options.rdm_station.or_else(|| extremes.rdm_station(basis));
    let analysed: Vec<usize> = match &options.stations {
        StationScope::All => (0..station_count).collect(),
        StationScope::RdmStation => rdm_station.into_iter().collect(),
        StationScope::RdmStationAnd(names) => {
            let named = names
                .iter()
                .filter_map(|name| basis.stations.iter().position(|s| &s.name == name));
            let mut analysed: Vec<usize> = rdm_station.into_iter().chain(named).collect();
            analysed.sort_unstable();
            analysed.dedup();
            analysed
        }
    };
    // A study (the RDM station only) reads deflection and moment; every other scope the
    // stations' forces too.
    let with_forces = options.stations != StationScope::RdmStation;
    let targets = analysed_targets(basis, influence, &analysed, with_forces);
    let forces = match with_forces {
        true => static_force_reference_of(influence, paths, &analysed)?,
        false => Vec::new(),
    };
    let given: Vec<Option<Direction>> = targets
        .iter()
        .map(|&(s, quantity)| {
            let name = &basis.stations[s].name;
            (options.governing_directions.iter())
                .find(|g| g.quantity == quantity && &g.station == name)
                .map(|g| g.direction)
        })
        .collect();
    let statics = entry_statics(&extremes, &targets, (&analysed, &forces), &given);
    Ok(PreparedRun {
        rdm_station,
        analysed,
        targets,
        statics,
    })
}

/// The second half of [`analyse_with_cache`](super::analyse_with_cache) for one run, given the maxima of its series.
fn conclude_run(
    basis: &ModalBasis,
    (history, options): (&ResponseHistory, &AnalysisOptions),
    prepared: PreparedRun,
    maxima: RunMaxima,
) -> DafReport {
    let PreparedRun {
        rdm_station,
        analysed,
        targets,
        statics,
    } = prepared;
    let n = basis.mode_count();
    let run = RunData {
        basis,
        history,
        options,
        plain: maxima.plain,
        corrected: maxima.corrected,
        rms: maxima.rms,
    };
    let entries: Vec<StationDaf> = targets
        .iter()
        .zip(&statics)
        .enumerate()
        .map(|(t, (&target, &entry_static))| station_entry(&run, t, target, entry_static))
        .collect();
    let station_rdm = station_rdms(basis, &analysed, &entries);
    let deck_participation = participation::deck_participation(basis, &run.rms, options);

    let rdm_entry = rdm_station.and_then(|s| station_rdm.iter().find(|r| r.station == s));
    let rdm = rdm_entry.and_then(|e| e.rdm);
    let rdm_by_modes = rdm_entry
        .map(|e| e.rdm_by_modes.clone())
        .unwrap_or_default();
    let rdm_paper = rdm_entry.and_then(|e| e.rdm_paper);
    let rdm_paper_by_modes = rdm_entry
        .map(|e| e.rdm_paper_by_modes.clone())
        .unwrap_or_default();
    let rdm_entry_of = |quantity: Quantity| {
        rdm_station.and_then(|s| {
            entries
                .iter()
                .find(|e| e.station == s && e.quantity == quantity)
        })
    };
    let modes_kept = ModesKeptIndicators::of(
        rdm_entry_of(Quantity::Deflection),
        rdm_entry_of(Quantity::BendingMoment),
        &deck_participation,
        options,
    );
    let mut warnings = history.warnings.clone();
    warnings.extend(convergence_warnings(
        &entries,
        options.convergence_tolerance,
    ));
    DafReport {
        stations: entries,
        rdm_station: rdm_station.map(|s| basis.stations[s].name.clone()),
        rdm,
        rdm_by_modes,
        rdm_paper,
        rdm_paper_by_modes,
        station_rdm,
        deck_participation,
        modes_kept,
        mode_count: n,
        time_step: history.time_step,
        time_step_check: None,
        contact_losses: history.contact_losses.clone(),
        warnings,
        truncated_runs: Vec::new(),
        design_codes: Vec::new(),
    }
}
