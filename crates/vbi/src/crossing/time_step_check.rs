//! The check of the default time step (issue 46, item 1). Every crossing run at the default
//! step Δt is run again at 2Δt, and each converged DAF gets the change DAF(Δt) − DAF(2Δt) as its
//! indicator ([`TimeStepConvergence`]) beside the modal one. For the scheme's second-order error
//! e(Δt) ≈ C Δt², the change is 3 e(Δt): the indicator overstates the error of the headline three
//! times. While some deflection or bending-moment DAF changes by more than
//! [`TIME_STEP_TOLERANCE`] of itself, the crossing runs at Δt/2 and is compared with the run at Δt
//! (no further run), up to [`MAX_HALVINGS`] times; a run still moving then says so
//! ([`SolverWarning::TimeStepNotConverged`]).
//!
//! Shear forces and support reactions get their indicator too, but do not halve the step:
//! their extremes occur as a wheel passes the station, where the influence line jumps, and the
//! sampled jump converges at first order in Δt whatever the scheme (docs/theory.md).
//!
//! Every crossing is checked on its own, so its result does not depend on the others of its
//! call, nor on a study's batches, threads or shards. The checks at 2Δt of a batch's crossings
//! are integrated together as the batch itself is ([`streamed::integrate_and_analyse`]: they
//! share what depends on the tyres' positions), at half the steps: the check costs about half
//! of the run.

use super::{run_batch, Analysed, PipelineError, PreparedBridge, RunResult, Scenario};
use crate::analysis::{DafReport, TimeStepCheck, TimeStepConvergence, TIME_STEP_TOLERANCE};
use crate::crossing::streamed;
use crate::modal::Quantity;
use crate::solver::{Crossing, Recording, SolverOptions, SolverWarning};

/// The most times the default step is halved: Δt/8 (at most 1 + ½ + 2 + 4 + 8 = 15.5 times
/// the work of one run, for a crossing that needs them all).
pub const MAX_HALVINGS: u32 = 3;

/// A batch's members: each crossing with the index of its scenario.
type Members = Vec<(usize, Crossing)>;

/// [`run_batch`] with the check of the default time step (see the module documentation): the
/// results by scenario index, each at the step its check settled on.
pub(super) fn run_checked_batch(
    bridge: &PreparedBridge,
    scenarios: &[&Scenario],
    (options, members, recording): (&SolverOptions, Members, Recording),
) -> Vec<(usize, Result<RunResult, PipelineError>)> {
    if options.time_step.is_some() || !options.time_step_check {
        return run_batch(bridge, scenarios, (options, members, recording));
    }
    let scenario_of: Vec<usize> = members.iter().map(|(i, _)| *i).collect();
    let mut results: Vec<Result<RunResult, PipelineError>> =
        run_batch(bridge, scenarios, (options, members.clone(), recording))
            .into_iter()
            .map(|(_, result)| result)
            .collect();
    // The first comparison: each run at Δt with its check at 2Δt.
    let coarse = coarse_check(bridge, scenarios, options, (&scenario_of, &results));
    let mut pending: Vec<usize> = Vec::new();
    for (position, check) in coarse {
        if let Ok(run) = &mut results[position] {
            let comparison = check.and_then(|report| compare(&run.report, &report));
            if record(&mut run.report, comparison, 0) {
                pending.push(position);
            }
        }
    }
    for halvings in 1..=MAX_HALVINGS {
        if pending.is_empty() {
            break;
        }
        let mut finer = options.clone();
        finer.default_step_refinement = halvings as i32;
        let rerun: Members = pending.iter().map(|&m| members[m].clone()).collect();
        let finer_results = run_batch(bridge, scenarios, (&finer, rerun, recording));
        let mut still = Vec::new();
        for (&position, (_, finer_result)) in pending.iter().zip(finer_results) {
            let Ok(previous) = &results[position] else {
                continue;
            };
            match finer_result {
                Ok(mut run) => {
                    // The run at the finer step, compared with the one at twice it.
                    let comparison = compare(&run.report, &previous.report);
                    if record(&mut run.report, comparison, halvings) {
                        still.push(position);
                    }
                    results[position] = Ok(run);
                }
                Err(error) => {
                    // The finer run failed (a limit on its size, say): the crossing keeps its
                    // step and its comparison (not converged), and says why it stopped there.
                    if let Ok(run) = &mut results[position] {
                        run.report.warnings.push(SolverWarning::TimeStepUnchecked {
                            time_step: run.report.time_step,
                            reason: error.to_string(),
                        });
                    }
                }
            }
        }
        pending = still;
    }
    scenario_of.into_iter().zip(results).collect()
}

/// The reports of every successful run of the batch at twice its step (OutcomeOnly, integrated
/// together), by position; Err with the reason where the check could not run.
fn coarse_check(
    bridge: &PreparedBridge,
    scenarios: &[&Scenario],
    options: &SolverOptions,
    (scenario_of, results): (&[usize], &[Result<RunResult, PipelineError>]),
) -> Vec<(usize, Result<DafReport, String>)> {
    let positions: Vec<usize> = (0..results.len()).filter(|&p| results[p].is_ok()).collect();
    let crossings: Vec<Crossing> = (positions.iter())
        .filter_map(|&p| results[p].as_ref().ok())
        .map(|run| run.crossing.clone())
        .collect();
    let analyses: Vec<_> = (positions.iter())
        .map(|&p| &scenarios[scenario_of[p]].analysis)
        .collect();
    let mut coarse = options.clone();
    coarse.default_step_refinement = -1;
    let checks = streamed::integrate_and_analyse(bridge, &crossings, (&coarse, &analyses), false);
    positions
        .into_iter()
        .zip(checks)
        .map(|(p, check): (usize, Analysed)| {
            let report = match check {
                Ok((_, Ok(report))) => Ok(report),
                Ok((_, Err(error))) => Err(error.to_string()),
                Err(error) => Err(error.to_string()),
            };
            (p, report)
        })
        .collect()
}

/// The indicators of a run at Δt against the same crossing at 2Δt (`coarse`), entry by entry.
type Comparison = Result<(f64, Vec<Option<TimeStepConvergence>>), String>;

/// [`Comparison`] of `report` (at Δt) with `coarse` (at 2Δt).
fn compare(report: &DafReport, coarse: &DafReport) -> Comparison {
    if report.stations.len() != coarse.stations.len() {
        return Err("the check's stations differ from the run's".into());
    }
    let indicators = (report.stations.iter().zip(&coarse.stations))
        .map(|(entry, other)| {
            let (daf, coarse_daf) = (entry.converged.daf?, other.converged.daf?);
            Some(TimeStepConvergence::of(daf, coarse.time_step, coarse_daf))
        })
        .collect();
    Ok((coarse.time_step, indicators))
}

/// Writes a comparison into the run's report (its entries' indicators, its [`TimeStepCheck`]
/// and, when it is not converged at the last halving, the warning); true when the step must be
/// halved again.
fn record(report: &mut DafReport, comparison: Comparison, halvings: u32) -> bool {
    let (_, indicators) = match comparison {
        Ok(comparison) => comparison,
        Err(reason) => {
            unchecked(report, reason);
            return false;
        }
    };
    let mut worst: Option<(usize, f64)> = None;
    for (e, (entry, indicator)) in report.stations.iter_mut().zip(indicators).enumerate() {
        entry.time_step_convergence = indicator;
        let Some(indicator) = indicator else { continue };
        let decides = matches!(
            entry.quantity,
            Quantity::Deflection | Quantity::BendingMoment
        );
        let relative = indicator.relative_change();
        if decides && worst.is_none_or(|(_, w)| relative > w) {
            worst = Some((e, relative));
        }
    }
    let largest_relative_change = worst.map_or(0.0, |(_, w)| w);
    let converged = largest_relative_change <= TIME_STEP_TOLERANCE;
    report.time_step_check = Some(TimeStepCheck {
        default_step: report.time_step * 2f64.powi(halvings as i32),
        halvings,
        largest_relative_change,
        converged,
    });
    if converged {
        // The check shows that the modes the step leaves quasi-static do not move the DAFs.
        (report.warnings).retain(|w| !matches!(w, SolverWarning::ModesQuasiStatic { .. }));
        return false;
    }
    if halvings < MAX_HALVINGS {
        return true;
    }
    if let Some((e, relative)) = worst {
        let entry = &report.stations[e];
        report.warnings.push(SolverWarning::TimeStepNotConverged {
            station: entry.name.clone(),
            quantity: entry.quantity.name().to_string(),
            relative_change: relative,
            time_step: report.time_step,
            halvings,
            tolerance: TIME_STEP_TOLERANCE,
        });
    }
    false
}

/// A check that could not run: the run stays as it is, with a warning saying so.
fn unchecked(report: &mut DafReport, reason: String) {
    report.time_step_check = None;
    report.warnings.push(SolverWarning::TimeStepUnchecked {
        time_step: report.time_step,
        reason,
    });
}
