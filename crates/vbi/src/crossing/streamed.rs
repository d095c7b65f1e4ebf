//! A batch's crossings integrated in lockstep and analysed as their instants are computed
//! ([`Recording::OutcomeOnly`]): no history is held, only a panel of instants per crossing and
//! the wheel paths (each contact's position at every instant) of each distinct crossing, a
//! value per contact and instant where a history held one per mode too. The reports are those of
//! the recorded path ([`analyse_runs`](crate::analysis::analyse_runs) of the histories), bit
//! for bit: the solver computes the same instants and the analysis takes the same sums in the
//! same order, only sooner.

use crate::analysis::{AnalysisError, AnalysisOptions, DafReport, RunAnalyses, RunToAnalyse};
use crate::solver::{ContactPath, Crossing, LockstepBatch, Recording, SolverOptions, WheelPaths};

use super::{Analysed, PreparedBridge};

/// The crossings (each analysed with its options in `analyses`) integrated together on
/// `bridge` and analysed instant by instant: each crossing's history without its tables
/// ([`Recording::OutcomeOnly`]) and its report, in order. `with_check_modes`: whether the
/// reports carry the check modes' series (the convergence indicator); the time step's check at
/// 2Δt reads only the converged DAFs.
pub(super) fn integrate_and_analyse(
    bridge: &PreparedBridge,
    crossings: &[Crossing],
    (options, analyses): (&SolverOptions, &[&AnalysisOptions]),
    with_check_modes: bool,
) -> Vec<Analysed> {
    let basis = &bridge.basis;
    let mut batch = LockstepBatch::new(basis, crossings, options, Recording::OutcomeOnly);
    let started: Vec<usize> = (0..batch.len())
        .filter(|&i| batch.integrator(i).is_some())
        .collect();
    let (paths, path_of) = distinct_wheel_paths(&batch, &started);
    let runs = started.iter().zip(&path_of).map(|(&i, &p)| {
        let integrator = batch.integrator(i).expect("a started crossing");
        Ok(RunToAnalyse {
            paths: WheelPaths {
                contacts: &paths[p].0,
                positions: &paths[p].1,
                step_count: integrator.step_count(),
            },
            options: analyses[i],
            with_forces: true,
            time_step: integrator.time_step(),
            with_check_modes,
        })
    });
    let cache = Some(&bridge.static_references);
    let mut analysing = RunAnalyses::new((basis, &bridge.influence), runs.collect(), cache);
    feed_instants(&mut batch, &started, &mut analysing);
    let histories = batch.finish();
    let ended = started.iter().map(|&i| histories[i].as_ref().ok());
    let mut reports: Vec<Option<Result<DafReport, AnalysisError>>> =
        (0..crossings.len()).map(|_| None).collect();
    for (&i, report) in started.iter().zip(analysing.finish(ended.collect())) {
        reports[i] = report;
    }
    (histories.into_iter().zip(reports))
        .map(|(history, report)| {
            let history = history?;
            Ok((
                history,
                report.expect("a report of every finished crossing"),
            ))
        })
        .collect()
}

/// Steps `batch` to its end, giving `analysing` every instant of each of the `started`
/// crossings (analysis run r is crossing started[r]) as it is computed; a crossing whose step
/// failed is abandoned.
fn feed_instants(batch: &mut LockstepBatch, started: &[usize], analysing: &mut RunAnalyses) {
    for instant in 0.. {
        for (r, &i) in started.iter().enumerate() {
            match batch.integrator(i) {
                // A crossing with fewer instants has finished: it was not stepped.
                Some(integrator) if integrator.step_index() == instant => {
                    let q = integrator.modal_displacements();
                    analysing.record(r, q, integrator.contact_forces());
                }
                Some(_) => {}
                // Abandoning again does nothing.
                None => analysing.abandon(r),
            }
        }
        if !batch.step() {
            return;
        }
    }
}

/// A run's contacts and their positions at every instant, step-major [m]
/// ([`WheelPaths`] borrows them).
type OwnedPaths = (Vec<ContactPath>, Vec<f64>);

/// The wheel paths of the started crossings, each computed once for the crossings that share
/// it bit for bit (a batch's road samples): the distinct (contacts, positions) and the index of
/// each started crossing's.
fn distinct_wheel_paths(batch: &LockstepBatch, started: &[usize]) -> (Vec<OwnedPaths>, Vec<usize>) {
    let mut distinct: Vec<OwnedPaths> = Vec::new();
    let mut path_of = Vec::with_capacity(started.len());
    for &i in started {
        let integrator = batch.integrator(i).expect("a started crossing");
        let contacts = integrator.contact_paths();
        let positions = integrator.contact_positions_of_run();
        // The same contacts (their lateral positions and loads bit for bit) and positions.
        let same = |(c, p): &OwnedPaths| {
            let paths = WheelPaths {
                contacts: c,
                positions: p,
                step_count: integrator.step_count(),
            };
            *c == contacts && paths.same_as(&contacts, &positions)
        };
        match distinct.iter().position(same) {
            Some(p) => path_of.push(p),
            None => {
                path_of.push(distinct.len());
                distinct.push((contacts, positions));
            }
        }
    }
    (distinct, path_of)
}
