//! `vbi run [SCENARIO] [--out DIR] [--format json|table]`: one vehicle crossing, coupled in
//! modal coordinates, and its DAF analysis.

use crate::console::outln;
use std::path::{Path, PathBuf};
use std::time::Instant;
use vbi::units::metres_per_second_to_kmh;

use anyhow::{Context, Result};

use vbi::analysis::modal_contributions;
use vbi::crossing::{
    run_crossing, station_history_columns, station_peak_acceleration, HistoryColumn, PipelineError,
    PreparedBridge, RunResult, Scenario, ScenarioBridgeError, VehicleHistoryTable,
};
use vbi::modal::Quantity;
use vbi::outputs::{
    ColumnExtremes, FatigueEntry, Provenance, StationAcceleration, StationEntry, FATIGUE_OUTPUTS,
};

use crate::commands::OutputFormat;
use crate::input::SourceFile;
use crate::inputs::{self, scenario};
use crate::output::{number, write_csv, write_json, write_numbers_csv_streamed};
use crate::plot::{write_chart, Chart, Series, SeriesStyle};

/// Arguments of `vbi run`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Scenario file (`[scenario]` TOML). Without it: the paper's 3 × 30 m bridge, five-axle
    /// truck, 'medium' road, 80 km/h.
    pub scenario: Option<PathBuf>,
    /// Directory for summary.json, histories.csv, vehicles.csv, daf_by_modes.csv, modes_kept.csv,
    /// participation.csv, design_codes.csv and figures.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Output on stdout.
    #[arg(long, value_enum, default_value_t = OutputFormat::Table)]
    pub format: OutputFormat,
    /// Write every K-th time step (and the last) to histories.csv and vehicles.csv, for long
    /// runs at a fine step; the analysis, summary.json and the figures use every step.
    #[arg(long, value_name = "K", default_value_t = 1,
          value_parser = clap::value_parser!(u64).range(1..))]
    pub history_every: u64,
}

/// The JSON summary of a run: the library's one summary type, its station entries written from
/// the analysis through the table of outputs.
type RunSummary<'a> = vbi::outputs::RunSummary<StationEntry<'a>, FatigueEntry<'a>>;

/// One crossing as `vbi run` reports it: the prepared bridge, the crossing's result and where
/// the numbers came from.
pub struct RunReport<'a> {
    /// The bridge (modal basis, influence lines).
    pub bridge: &'a PreparedBridge,
    /// The crossing and its DAF analysis.
    pub result: &'a RunResult,
    /// Provenance.
    pub provenance: Provenance,
    /// Whether tyres may leave the road (for the wording of contact losses).
    pub tyre_separation: bool,
    /// The relative tolerance of the DAFs' convergence [-] (for the table's note).
    pub convergence_tolerance: f64,
}

fn provenance(
    scenario: &Scenario,
    input_hash: &str,
    bridge: &PreparedBridge,
    result: &RunResult,
) -> Provenance {
    Provenance {
        vbi_version: env!("CARGO_PKG_VERSION").to_string(),
        input_hash: input_hash.to_string(),
        seed: scenario.road.seed,
        time_step_s: result.history.time_step,
        modes: bridge.basis.mode_count(),
        dof_count: bridge.dof_count,
        scenario: scenario.name.clone(),
        bridge: scenario.bridge_label.clone(),
        vehicle: result.crossing.vehicle_names(),
        speed_kmh: metres_per_second_to_kmh(result.history.speed),
    }
}

/// Runs the command.
pub fn run(args: &Args) -> Result<()> {
    let (loaded, file) = match &args.scenario {
        Some(path) => {
            let file = SourceFile::read(path)?;
            inputs::expect_kind(&file, "scenario", "vbi run")?;
            (scenario::load(&file)?, Some(file))
        }
        None => (scenario::built_in_default(), None),
    };
    let scenario = &loaded.scenario;
    // A failure of a file's scenario is located at the key that governs it.
    let located = |error: &PipelineError| -> anyhow::Error {
        match &file {
            Some(file) => scenario::locate_failure(file, scenario, error).into(),
            None => anyhow::anyhow!("{}", vbi::crossing::error_chain(error)),
        }
    };
    let started = Instant::now();
    let bridge = with_progress(&format!("vbi run: {} (modes)", scenario.name), || {
        vbi::crossing::prepare_scenario_bridge(scenario)
    })
    .map_err(|error| match &error {
        ScenarioBridgeError::Prepare { source, .. }
        | ScenarioBridgeError::RerunModeCounts { source, .. } => located(source),
    })?;
    if let Some(file) = &file {
        // A detail whose station the bridge lacks is refused before the crossing.
        inputs::fatigue_details::check(file, scenario, &bridge.basis.stations)?;
    }
    let result = with_progress(&format!("vbi run: {}", scenario.name), || {
        run_crossing(&bridge, scenario)
    })
    .map_err(|error| located(&error))?;
    let elapsed = started.elapsed().as_secs_f64();
    let report = RunReport {
        bridge: &bridge,
        result: &result,
        provenance: provenance(scenario, &loaded.input_hash, &bridge, &result),
        tyre_separation: scenario.solver.tyre_separation,
        convergence_tolerance: scenario.analysis.convergence_tolerance,
    };
    for warning in warning_lines(&report) {
        eprintln!("warning: {warning}");
    }
    let vehicle_columns = VehicleHistoryTable::of(&result.history);
    let summary = summarise(&report, &vehicle_columns);
    match args.format {
        OutputFormat::Json => outln!("{}", serde_json::to_string_pretty(&summary)?),
        OutputFormat::Table => print_table(&report, elapsed),
    }
    if let Some(dir) = &args.out {
        write_outputs(
            dir,
            &report,
            &summary,
            &vehicle_columns,
            args.history_every as usize,
        )?;
    }
    Ok(())
}

/// The JSON summary of a run; `vehicle_columns` are those of vehicles.csv (their extremes).
fn summarise<'a>(run: &'a RunReport<'_>, vehicle_columns: &VehicleHistoryTable) -> RunSummary<'a> {
    let report = &run.result.report;
    RunSummary {
        stations: report.stations.iter().map(StationEntry).collect(),
        rdm_station: report.rdm_station.clone(),
        rdm: report.rdm,
        rdm_by_modes: report.rdm_by_modes.clone(),
        rdm_paper: report.rdm_paper,
        rdm_paper_by_modes: report.rdm_paper_by_modes.clone(),
        frequencies_hz: run
            .bridge
            .basis
            .modes
            .iter()
            .map(|m| m.frequency_hz())
            .collect(),
        deck_participation: report.deck_participation.clone(),
        modes_kept: report.modes_kept.clone(),
        contact_losses: report.contact_losses.clone(),
        warnings: warning_lines(run),
        truncated_runs: report.truncated_runs.clone(),
        design_codes: report.design_codes.clone(),
        fatigue: run.result.fatigue.iter().map(FatigueEntry).collect(),
        station_accelerations: run
            .bridge
            .basis
            .stations
            .iter()
            .enumerate()
            .map(|(s, station)| StationAcceleration {
                station: station.name.clone(),
                max_abs_m_s2: station_peak_acceleration(run.bridge, &run.result.history, s),
            })
            .collect(),
        vehicle_extremes: (1..vehicle_columns.column_count())
            .map(|c| ColumnExtremes {
                min: vehicle_columns.column(c).fold(f64::INFINITY, f64::min),
                max: vehicle_columns.column(c).fold(f64::NEG_INFINITY, f64::max),
                column: vehicle_columns.name(c).to_owned(),
            })
            .collect(),
        provenance: run.provenance.clone(),
    }
}

/// Runs `work`; if it takes longer than a second and stderr is a terminal, shows a one-line
/// progress indication (label and elapsed time) on stderr, erased when the work is done.
fn with_progress<T>(label: &str, work: impl FnOnce() -> T) -> T {
    use std::io::{IsTerminal, Write};
    use std::sync::mpsc;
    use std::time::Duration;
    if !std::io::stderr().is_terminal() {
        return work();
    }
    let (done, finished) = mpsc::channel::<()>();
    std::thread::scope(|scope| {
        let label = label.to_string();
        let indicator = scope.spawn(move || {
            let started = Instant::now();
            let mut shown = false;
            let wait = Duration::from_secs(1);
            // Wait a second; then refresh the line four times a second until the work ends.
            let mut timeout = wait;
            while let Err(mpsc::RecvTimeoutError::Timeout) = finished.recv_timeout(timeout) {
                shown = true;
                let mut stderr = std::io::stderr().lock();
                let _ = write!(
                    stderr,
                    "\r{label}: computing… {:.1} s",
                    started.elapsed().as_secs_f64()
                );
                let _ = stderr.flush();
                timeout = Duration::from_millis(250);
            }
            if shown {
                let mut stderr = std::io::stderr().lock();
                let _ = write!(stderr, "\r\x1b[2K");
                let _ = stderr.flush();
            }
        });
        let result = work();
        let _ = done.send(());
        let _ = indicator.join();
        result
    })
}

/// With two or more vehicles: which static reference the DAFs divide by, and the DAFs at the
/// RDM station against the heaviest single vehicle alone.
fn single_vehicle_line(run: &RunReport) -> Option<String> {
    let report = &run.result.report;
    let vehicles = run.result.crossing.vehicles.len();
    if vehicles < 2 {
        return None;
    }
    let station = report.rdm_station.as_ref();
    let daf = |quantity: Quantity| {
        let entry = report
            .stations
            .iter()
            .find(|e| Some(&e.name) == station && e.quantity == quantity);
        optional(entry.and_then(|e| e.daf_single_vehicle), 4)
    };
    Some(format!(
        "Static reference: the event's static envelope ({vehicles} vehicles together). Against \
         the heaviest single vehicle's own static effect (summary.json daf_single_vehicle) at \
         {}: DAF_u {}, DAF_M {}",
        station.map_or("–", |s| s.as_str()),
        daf(Quantity::Deflection),
        daf(Quantity::BendingMoment)
    ))
}

/// What the change column reads beyond the modes kept: the check modes, if the run had them.
fn check_modes_note(report: &vbi::analysis::DafReport) -> String {
    let check_modes = (report.stations.iter())
        .filter_map(|s| s.convergence.map(|c| c.check_modes))
        .max()
        .unwrap_or(0);
    match check_modes {
        0 => " (no check modes above them: it cannot see a mode above N)".to_string(),
        c => format!(
            ", or twice its change over the {c} check modes above them (integrated against the \
             contact forces, not fed back) where larger"
        ),
    }
}

/// What the table's Δt column rests on: the check of the default step, or why there is none.
fn time_step_note(report: &vbi::analysis::DafReport) -> String {
    match report.time_step_check {
        Some(check) if check.halvings == 0 => format!(
            "the default step, checked at twice it: largest change {:.2e} of a deflection or \
             moment DAF, within {:.0e}; shear forces and reactions, whose extremes sit on the \
             jump of their influence lines, are shown but not held to it",
            check.largest_relative_change,
            vbi::analysis::TIME_STEP_TOLERANCE
        ),
        Some(check) => format!(
            "the default step {} s halved {} time(s){}",
            vbi::units::shown(check.default_step),
            check.halvings,
            if check.converged {
                " until the deflection and moment DAFs held within 0.1 %"
            } else {
                ", still moving: see the warning"
            }
        ),
        None => "not checked: a given time_step_s, or time_step_check = false".to_string(),
    }
}

/// The solver's warnings and the contact losses, one clear sentence each.
fn warning_lines(run: &RunReport) -> Vec<String> {
    use vbi::solver::SolverWarning;
    let report = &run.result.report;
    let mut lines: Vec<String> = report
        .warnings
        .iter()
        .map(|w| match w {
            SolverWarning::ModeUnderResolved {
                mode,
                frequency_hz,
                period,
                time_step,
                steps_per_period,
                further_modes,
            } => {
                let affected = if *further_modes == 0 {
                    format!("mode {mode}")
                } else {
                    format!("modes {mode} to {}", mode + further_modes)
                };
                format!(
                    "time step {time_step} s under-resolves mode {mode} ({frequency_hz:.3} Hz): \
                     {:.1} steps per period of {period:.6} s, fewer than {steps_per_period}; the \
                     response of {affected} is inaccurate (set scenario.time_step_s ≤ {:.3e} s or \
                     keep fewer modes)",
                    period / time_step,
                    period / steps_per_period
                )
            }
            other => other.to_string(),
        })
        .collect();
    for loss in &report.contact_losses {
        lines.push(contact_loss_line(loss, run.tyre_separation));
    }
    lines
}

/// A contact loss in words: with tyre separation the tyre left the road and carried no force;
/// without it the model kept the tyre bonded through a tensile force.
fn contact_loss_line(loss: &vbi::solver::ContactLoss, tyre_separation: bool) -> String {
    let (tyre, start, end, force) = (
        loss.contact + 1,
        loss.start_time,
        loss.end_time,
        loss.minimum_force,
    );
    if tyre_separation {
        format!(
            "contact loss: tyre {tyre} left the road from t = {start:.3} s to {end:.3} s (its \
             would-be contact force was tensile, down to {force:.0} N); it carried no force in \
             that interval (scenario.tyre_separation = true)"
        )
    } else {
        format!(
            "contact loss: tyre {tyre} would lift off the road from t = {start:.3} s to {end:.3} \
             s (tensile contact force, down to {force:.0} N); the model keeps the tyre bonded, so \
             the responses in that interval are those of a bonded tyre \
             (scenario.tyre_separation = false)"
        )
    }
}

fn optional(value: Option<f64>, decimals: usize) -> String {
    value.map_or_else(|| "-".to_string(), |v| format!("{v:.decimals$}"))
}

/// One line per vehicle when the crossing has several or a variable speed: its direction, lane,
/// start and speeds.
fn traffic_lines(crossing: &vbi::solver::Crossing) -> Vec<String> {
    use vbi::solver::{SpeedProfile, TravelDirection};
    let simple = matches!(crossing.vehicles.as_slice(),
        [one] if matches!(one.speed, SpeedProfile::Constant(_))
            && one.direction == TravelDirection::Forward);
    if simple {
        return Vec::new();
    }
    crossing
        .vehicles
        .iter()
        .enumerate()
        .map(|(i, run)| {
            let speeds = match &run.speed {
                SpeedProfile::Constant(v) => format!("{:.1} km/h", metres_per_second_to_kmh(*v)),
                SpeedProfile::Knots(knots) => knots
                    .iter()
                    .map(|k| format!("{:.1} km/h at s = {:.1} m", metres_per_second_to_kmh(k.speed), k.travel))
                    .collect::<Vec<_>>()
                    .join(" → "),
            };
            let direction = match run.direction {
                TravelDirection::Forward => "forward",
                TravelDirection::Backward => "backward",
            };
            format!(
                "  vehicle {}: {}, {direction}, y = {:.2} m, front axle at s = {:.2} m at t = 0, {speeds}",
                i + 1,
                run.vehicle.name,
                run.lateral_position,
                run.start_position
            )
        })
        .collect()
}

fn optional_index(value: Option<usize>) -> String {
    value.map_or_else(|| "-".to_string(), |v| v.to_string())
}

fn print_table(run: &RunReport, elapsed: f64) {
    let p = &run.provenance;
    let report = &run.result.report;
    outln!(
        "{}: {} at {:.1} km/h on {}, {} modes, dt = {} s, seed {} ({} DOF; {:.2} s)",
        p.scenario,
        p.vehicle,
        p.speed_kmh,
        p.bridge,
        p.modes,
        vbi::units::shown(p.time_step_s),
        p.seed,
        p.dof_count,
        elapsed
    );
    for line in traffic_lines(&run.result.crossing) {
        outln!("{line}");
    }
    outln!(
        "{:<22} {:<16} {:>13} {:>13} {:>7} {:>7} {:>7} {:>8} | {:>9} {:>4} {:>4} {:>4}",
        "station",
        "quantity",
        "static max",
        "dynamic max",
        "DAF",
        "IM",
        "change",
        "Δt chg",
        "paper DAF",
        "CM",
        "K1",
        "K2"
    );
    for s in report.stations.iter().filter(|s| s.converged.daf.is_some()) {
        // Table units: millimetres and kilonewton-metres.
        let (unit_scale, unit) = match s.quantity {
            Quantity::Deflection => (1e3, "mm"),
            Quantity::BendingMoment => (1e-3, "kNm"),
            Quantity::ShearForce | Quantity::SupportReaction => (1e-3, "kN"),
        };
        // A change beyond the tolerance is marked with '!' (and a warning names it).
        let change = match s.convergence {
            Some(c) => format!("{:.4}{}", c.change, if c.converged { " " } else { "!" }),
            None => "-".to_string(),
        };
        // The change from twice the step: '!' above the tolerance (a warning names it).
        let step_change = match s.time_step_convergence {
            Some(c) => format!("{:+.4}{}", c.change, if c.converged { " " } else { "!" }),
            None => "-".to_string(),
        };
        // The plain modal sums of shear forces and reactions are not DAFs (issue 46): they
        // converge slowly and not to the response; summary.json keeps them, named.
        let (paper_daf, paper_cm) = if s.quantity.plain_sum_is_a_daf() {
            (
                optional(s.paper.daf, 4),
                optional_index(s.paper.convergence_mode),
            )
        } else {
            ("–".to_string(), "–".to_string())
        };
        outln!(
            "{:<22} {:<16} {:>9.3} {:<3} {:>9.3} {:<3} {:>7} {:>7} {:>7} {:>8} | {:>9} {:>4} {:>4} {:>4}",
            s.name,
            s.quantity.name(),
            s.static_max * unit_scale,
            unit,
            s.converged.dynamic_max * unit_scale,
            unit,
            optional(s.converged.daf, 4),
            optional(s.impact_factor, 4),
            change,
            step_change,
            paper_daf,
            paper_cm,
            optional_index(s.cutoff_k1),
            optional_index(s.cutoff_k2),
        );
    }
    outln!(
        "DAF: converged (static-corrected, mode-acceleration) with all {} modes, static and \
         dynamic extremes taken between the time steps; change: its largest change over the \
         last {} modes kept{} ('!' above {} of the DAF); Δt chg: DAF(Δt) − DAF(2Δt) ({}). \
         Right of '|': the \
         paper's plain modal sum and its CM, K1, K2, which depend on the number of modes kept \
         (docs/theory.md, docs/paper-reproduction.md); for shear forces and support reactions \
         the plain sum is no DAF (it converges slowly and not to the response) and is left out \
         (–)",
        report.mode_count,
        (report.stations.iter())
            .filter_map(|s| s.convergence.map(|c| c.window))
            .max()
            .unwrap_or(0),
        check_modes_note(report),
        format!("{} %", 100.0 * run.convergence_tolerance),
        time_step_note(report),
    );
    if let Some(line) = single_vehicle_line(run) {
        outln!("{line}");
    }
    if let Some(station) = &report.rdm_station {
        outln!(
            "RDM (DAF_u / DAF_M) at {station}: {} (paper's plain modal sums: {})",
            optional(report.rdm, 4),
            optional(report.rdm_paper, 4)
        );
        for run in &report.truncated_runs {
            let daf = |quantity: Quantity| {
                run.stations
                    .iter()
                    .find(|e| e.name == *station && e.quantity == quantity)
                    .and_then(|e| e.daf)
            };
            outln!(
                "re-run with {} modes: DAF_u {}, DAF_M {}, RDM {}",
                run.mode_count,
                optional(daf(Quantity::Deflection), 4),
                optional(daf(Quantity::BendingMoment), 4),
                optional(run.rdm, 4)
            );
        }
    }
    for line in crate::design_codes::table_lines(report) {
        outln!("{line}");
    }
    for line in fatigue_lines(run) {
        outln!("{line}");
    }
}

/// A Miner's sum in the terminal: 0, or three significant digits in scientific notation.
fn damage_cell(damage: f64) -> String {
    match damage {
        0.0 => "0".into(),
        d => format!("{d:.3e}"),
    }
}

/// The fatigue table of the terminal (none without details): per detail its curve, the largest
/// stress ranges, the cycles, Miner's sums and the fatigue DAF, with the codes' fatigue factors
/// at its station beside.
fn fatigue_lines(run: &RunReport) -> Vec<String> {
    let fatigue = &run.result.fatigue;
    if fatigue.is_empty() {
        return Vec::new();
    }
    let mpa = |pa: f64| pa / vbi::units::MPA;
    let mut lines = vec![format!(
        "{:<24} {:<22} {:>9} {:>9} {:>13} {:>10} {:>10} {:>8} {:>8} {:>7}  {}",
        "fatigue detail",
        "station",
        "Δσmax dyn",
        "static",
        "cycles dyn/st",
        "D dynamic",
        "D static",
        "fat. DAF",
        "no c-off",
        "change",
        "codes' fatigue factors"
    )];
    for f in fatigue {
        let beside: Vec<String> = (run.result.report.design_codes.iter())
            .filter(|c| c.station == f.detail.station && c.quantity == f.detail.quantity)
            .flat_map(|c| c.factors.iter().filter(|factor| factor.is_fatigue_factor()))
            .map(|factor| {
                let label = factor.code.short_label(&factor.provision);
                format!("{label} {:.2}", factor.daf())
            })
            .collect();
        lines.push(format!(
            "{:<24} {:<22} {:>5.1} MPa {:>5.1} MPa {:>6.1}/{:<6.1} {:>10} {:>10} {:>8} {:>8} {:>7}  {}",
            f.detail.name,
            f.detail.station,
            mpa(f.dynamic.sum.max_range),
            mpa(f.static_history.sum.max_range),
            f.dynamic.sum.cycles,
            f.static_history.sum.cycles,
            damage_cell(f.dynamic.sum.damage),
            damage_cell(f.static_history.sum.damage),
            optional(f.amplification.fatigue_daf, 4),
            optional(f.amplification.fatigue_daf_straight_line, 4),
            // The change of the headline: on the curve where defined, else without cut-off.
            optional(
                f.convergence.and_then(|c| c.fatigue_daf_change.or(c.straight_line_change)),
                4
            ),
            if beside.is_empty() {
                "–".to_string()
            } else {
                beside.join(", ")
            },
        ));
    }
    lines.push(
        "fatigue: rainflow (ASTM E1049-85 §5.4.4) of each detail's stress from the converged and \
         the static histories, Miner's sum D on its S–N curve; fat. DAF = (D dynamic / D static)^(1/m) \
         (empty where the static ranges are below the cut-off); no c-off: the same on a straight \
         line without cut-off; change: the DAF's largest change over the last ⌈N/2⌉ modes kept \
         (docs/fatigue.md)"
            .to_string(),
    );
    lines
}

/// Columns as a CSV table, `header[c]` over `value(c, i)`: the rows of every `every`-th instant
/// of `steps`, and the last.
fn write_columns(
    path: &Path,
    header: &[&str],
    (steps, every): (usize, usize),
    value: impl Fn(usize, usize) -> f64,
) -> Result<()> {
    let value = &value;
    let columns = header.len();
    let rows = recorded_instants(steps, every).map(|i| (0..columns).map(move |c| value(c, i)));
    write_numbers_csv_streamed(path, header, rows)
}

/// The instants 0, k, 2k, … of `steps`, and the last one.
fn recorded_instants(steps: usize, every: usize) -> impl Iterator<Item = usize> {
    let every = every.max(1);
    (0..steps).filter(move |&i| i % every == 0 || i + 1 == steps)
}

fn write_outputs(
    dir: &Path,
    run: &RunReport,
    summary: &RunSummary<'_>,
    vehicle_columns: &VehicleHistoryTable,
    every: usize,
) -> Result<()> {
    let _lock = crate::output::lock_output_dir(dir)?;
    write_json(&dir.join("summary.json"), summary)?;
    crate::design_codes::write_table(dir, &run.result.report)?;
    let basis = &run.bridge.basis;
    let history = &run.result.history;

    // histories.csv: time, front axle, then the converged (static-corrected), the paper's modal
    // sum and the static response of every station (the library's columns, as Python shows them).
    let columns = station_history_columns(run.bridge, history).context("station histories")?;
    let instants = (history.step_count, every);
    let header: Vec<&str> = columns.iter().map(|c| c.name.as_str()).collect();
    write_columns(&dir.join("histories.csv"), &header, instants, |c, i| {
        columns[c].values[i]
    })?;
    // vehicles.csv: every vehicle DOF's displacement and acceleration, every contact's position
    // and force.
    let header: Vec<&str> = (0..vehicle_columns.column_count())
        .map(|c| vehicle_columns.name(c))
        .collect();
    write_columns(&dir.join("vehicles.csv"), &header, instants, |c, i| {
        vehicle_columns.value(c, i)
    })?;

    // fatigue.csv: one row per fatigue detail, the columns of the table of fatigue outputs.
    if !run.result.fatigue.is_empty() {
        let header: Vec<&str> = FATIGUE_OUTPUTS.iter().map(|row| row.name).collect();
        let rows: Vec<Vec<String>> = (run.result.fatigue.iter())
            .map(|f| {
                FATIGUE_OUTPUTS
                    .iter()
                    .map(|row| (row.value)(f).cell())
                    .collect()
            })
            .collect();
        write_csv(&dir.join("fatigue.csv"), &header, &rows)?;
    }

    // daf_by_modes.csv: one row per station, quantity and K: the converged DAF(K) and the
    // paper's.
    let mut rows = Vec::new();
    for s in &run.result.report.stations {
        for (k, daf) in s.converged.daf_by_modes.iter().enumerate() {
            rows.push(vec![
                s.name.clone(),
                s.quantity.name().to_string(),
                (k + 1).to_string(),
                number(*daf),
                s.paper
                    .daf_by_modes
                    .get(k)
                    .map(|d| number(*d))
                    .unwrap_or_default(),
            ]);
        }
    }
    write_csv(
        &dir.join("daf_by_modes.csv"),
        &["station", "quantity", "modes", "daf", "daf_paper"],
        &rows,
    )?;

    // modes_kept.csv: the paper's CM (at the RDM station) and deck-wide K1, K2 had only the
    // first n modes been kept.
    let kept = &run.result.report.modes_kept;
    let cell = |values: &[Option<usize>], k: usize| {
        values
            .get(k)
            .copied()
            .flatten()
            .map(|v| v.to_string())
            .unwrap_or_default()
    };
    let rows: Vec<Vec<String>> = (0..basis.mode_count())
        .map(|k| {
            let mut row = vec![(k + 1).to_string()];
            for values in [
                &kept.cm_u_paper,
                &kept.cm_m_paper,
                &kept.k1_u,
                &kept.k2_u,
                &kept.k1_m,
                &kept.k2_m,
            ] {
                row.push(cell(values, k));
            }
            row
        })
        .collect();
    write_csv(
        &dir.join("modes_kept.csv"),
        &[
            "modes_kept",
            "cm_u_paper",
            "cm_m_paper",
            "k1_u",
            "k2_u",
            "k1_m",
            "k2_m",
        ],
        &rows,
    )?;

    // participation.csv: deck-wide and per-station participation of every mode.
    let deck = &run.result.report.deck_participation;
    let rows: Vec<Vec<String>> = (0..basis.mode_count())
        .map(|k| {
            vec![
                (k + 1).to_string(),
                number(basis.modes[k].frequency_hz()),
                number(deck.deflection[k]),
                number(deck.moment[k]),
            ]
        })
        .collect();
    write_csv(
        &dir.join("participation.csv"),
        &["mode", "frequency_hz", "mps_deflection", "mps_moment"],
        &rows,
    )?;

    write_figures(dir, run, &columns)?;
    crate::design_codes::write_figure(dir, &run.result.report)?;
    Ok(())
}

fn write_figures(dir: &Path, run: &RunReport, columns: &[HistoryColumn]) -> Result<()> {
    crate::bridge_summary::write_run_plan(dir, run.bridge, &run.result.crossing)?;
    let report = &run.result.report;
    let history = &run.result.history;
    let basis = &run.bridge.basis;
    let Some(rdm_name) = report.rdm_station.as_deref() else {
        return Ok(());
    };
    let Some(s) = basis.stations.iter().position(|st| st.name == rdm_name) else {
        return Ok(());
    };
    // The RDM station's histories, from the columns that histories.csv holds.
    let column = |name: &str| {
        columns
            .iter()
            .find(|c| c.name == name)
            .map(|c| &c.values[..])
    };
    let Some(times) = column("time_s") else {
        return Ok(());
    };
    let series = |values: &[f64], scale: f64| -> Vec<(f64, f64)> {
        times
            .iter()
            .zip(values)
            .map(|(t, v)| (*t, v * scale))
            .collect()
    };
    for (unit, scale, label, stem) in [
        ("deflection_m", 1e3, "deflection [mm]", "history_deflection"),
        (
            "moment_n_m",
            1e-3,
            "bending moment [kN·m]",
            "history_moment",
        ),
    ] {
        let (Some(dynamic), Some(paper), Some(statics)) = (
            column(&format!("{rdm_name}_{unit}")),
            column(&format!("{rdm_name}_paper_{unit}")),
            column(&format!("{rdm_name}_static_{unit}")),
        ) else {
            continue;
        };
        write_chart(
            &Chart {
                title: format!(
                    "{rdm_name}: dynamic and static {}",
                    label.split(' ').next().unwrap_or("")
                ),
                x_label: "time [s]".into(),
                y_label: label.into(),
                series: vec![
                    Series::line("dynamic (converged)", series(dynamic, scale)),
                    Series {
                        label: "dynamic, paper's modal sum".into(),
                        points: series(paper, scale),
                        style: SeriesStyle::Thin,
                    },
                    Series::line("static", series(statics, scale)),
                ],
                ..Chart::default()
            },
            &dir.join(stem),
        )?;
    }
    // DAF and RDM against the number of modes: the converged series and the paper's.
    let against_modes = |values: &[f64]| -> Vec<(f64, f64)> {
        values
            .iter()
            .enumerate()
            .map(|(k, d)| ((k + 1) as f64, *d))
            .collect()
    };
    let ratio_against_modes = |values: &[Option<f64>]| -> Vec<(f64, f64)> {
        values
            .iter()
            .enumerate()
            .filter_map(|(k, r)| r.map(|r| ((k + 1) as f64, r)))
            .collect()
    };
    let mut daf_series = Vec::new();
    for entry in report.stations.iter().filter(|e| e.name == rdm_name) {
        let quantity = entry.quantity.name();
        daf_series.push(Series::line(
            format!("DAF {quantity}"),
            against_modes(&entry.converged.daf_by_modes),
        ));
        daf_series.push(Series {
            label: format!("paper's DAF {quantity}"),
            points: against_modes(&entry.paper.daf_by_modes),
            style: SeriesStyle::Thin,
        });
    }
    daf_series.push(Series::line(
        "RDM",
        ratio_against_modes(&report.rdm_by_modes),
    ));
    daf_series.push(Series {
        label: "paper's RDM".into(),
        points: ratio_against_modes(&report.rdm_paper_by_modes),
        style: SeriesStyle::Thin,
    });
    write_chart(
        &Chart {
            title: format!("{rdm_name}: DAF and RDM against the number of modes"),
            x_label: "number of modes K".into(),
            y_label: "DAF, RDM [-]".into(),
            series: daf_series,
            ..Chart::default()
        },
        &dir.join("daf_by_modes"),
    )?;
    // Modal decomposition of the deflection (paper Fig. 10): the first six modes.
    let n = basis.mode_count();
    let contributions = modal_contributions(basis, history, s, Quantity::Deflection)
        .context("modal contributions")?;
    // The modes sum to the paper's plain modal sum.
    let total = column(&format!("{rdm_name}_paper_deflection_m")).unwrap_or_default();
    let mut decomposition = vec![Series::line("total", series(total, 1e3))];
    for k in 0..n.min(6) {
        let values: Vec<f64> = (0..history.step_count)
            .map(|i| contributions[i * n + k])
            .collect();
        decomposition.push(Series {
            label: format!("mode {}", k + 1),
            points: series(&values, 1e3),
            style: SeriesStyle::Thin,
        });
    }
    write_chart(
        &Chart {
            title: format!("{rdm_name}: modal decomposition of the deflection"),
            x_label: "time [s]".into(),
            y_label: "deflection [mm]".into(),
            series: decomposition,
            ..Chart::default()
        },
        &dir.join("modal_decomposition"),
    )?;
    // Participation bars.
    let deck = &report.deck_participation;
    let n = basis.mode_count().min(20);
    for (values, stem, what) in [
        (&deck.deflection, "participation_deflection", "deflection"),
        (&deck.moment, "participation_moment", "bending moment"),
    ] {
        write_chart(
            &Chart {
                title: format!("modal participation MPS_k, {what} (Eq. 30)"),
                x_label: "mode".into(),
                y_label: "participation [-]".into(),
                series: vec![Series {
                    label: String::new(),
                    points: (0..n).map(|k| ((k + 1) as f64, values[k])).collect(),
                    style: SeriesStyle::Bars,
                }],
                ..Chart::default()
            },
            &dir.join(stem),
        )?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// With tyre separation (the default) a contact loss is a tyre in flight, not a bonded tyre
    /// (issue 11: the message once said "keeps the tyre bonded" for both models).
    #[test]
    fn a_contact_loss_is_worded_for_the_tyre_model_that_was_run() {
        let loss = vbi::solver::ContactLoss {
            contact: 0,
            start_time: 1.0,
            end_time: 1.25,
            minimum_force: -1500.0,
        };
        let flying = contact_loss_line(&loss, true);
        assert!(flying.contains("left the road"), "{flying}");
        assert!(flying.contains("carried no force"), "{flying}");
        assert!(!flying.contains("bonded"), "{flying}");
        let bonded = contact_loss_line(&loss, false);
        assert!(bonded.contains("keeps the tyre bonded"), "{bonded}");
    }
}
