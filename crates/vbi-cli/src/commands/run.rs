//! `vbi run [SCENARIO] [--out DIR] [--format json|table]`: one vehicle crossing, coupled in
//! modal coordinates, and its DAF analysis.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result};
use serde::Serialize;

use vbi::analysis::{
    analyse, rerun_truncated, static_reference, AnalysisOptions, DafReport, StaticReference,
    StationScope,
};
use vbi::fe::{discretise, statics::influence_lines, MeshOptions};
use vbi::influence::InfluenceLines;
use vbi::modal::{solve_modes, ModalBasis, ModalOptions, Quantity};
use vbi::road::generate;
use vbi::solver::{simulate, Crossing, ResponseHistory, SolverOptions};
use vbi::vehicle::assemble;

use crate::commands::OutputFormat;
use crate::input::SourceFile;
use crate::inputs::scenario::{self, Scenario};
use crate::output::{create_output_dir, number, write_csv, write_json};
use crate::plot::{write_chart, Chart, Series, SeriesStyle};

/// Arguments of `vbi run`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Scenario file (`[scenario]` TOML). Without it: the paper's 3 × 30 m bridge, five-axle
    /// truck, 'medium' road, 80 km/h.
    pub scenario: Option<PathBuf>,
    /// Directory for summary.json, histories.csv, daf_by_modes.csv, participation.csv and figures.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Output on stdout.
    #[arg(long, value_enum, default_value_t = OutputFormat::Table)]
    pub format: OutputFormat,
}

/// Where the numbers came from.
#[derive(Debug, Clone, Serialize)]
pub struct Provenance {
    /// vbi version.
    pub vbi_version: String,
    /// SHA-256 of the scenario and every file it names.
    pub input_hash: String,
    /// Road seed.
    pub seed: u64,
    /// Time step [s].
    pub time_step_s: f64,
    /// Number of modes in the basis.
    pub modes: usize,
    /// Degrees of freedom of the FE model.
    pub dof_count: usize,
    /// Scenario name.
    pub scenario: String,
    /// Bridge as named in the scenario.
    pub bridge: String,
    /// Vehicle name.
    pub vehicle: String,
    /// Speed [km/h].
    pub speed_kmh: f64,
}

/// One station entry of the JSON summary.
#[derive(Debug, Serialize)]
struct StationSummary<'a> {
    name: &'a str,
    quantity: &'static str,
    static_max: f64,
    dynamic_max: f64,
    daf: Option<f64>,
    impact_factor: Option<f64>,
    daf_by_modes: &'a [f64],
    participation: &'a [f64],
    convergence_mode: Option<usize>,
    cutoff_k1: Option<usize>,
    cutoff_k2: Option<usize>,
    corrected_dynamic_max: Option<f64>,
    corrected_daf: Option<f64>,
    corrected_daf_by_modes: &'a [f64],
    corrected_convergence_mode: Option<usize>,
}

/// The JSON summary of a run.
#[derive(Debug, Serialize)]
struct RunSummary<'a> {
    stations: Vec<StationSummary<'a>>,
    rdm_station: Option<&'a str>,
    rdm: Option<f64>,
    rdm_by_modes: &'a [Option<f64>],
    corrected_rdm: Option<f64>,
    corrected_rdm_by_modes: &'a [Option<f64>],
    frequencies_hz: Vec<f64>,
    deck_participation: &'a vbi::analysis::DeckParticipation,
    contact_losses: &'a [vbi::solver::ContactLoss],
    warnings: Vec<String>,
    truncated_runs: &'a [vbi::analysis::TruncatedRun],
    provenance: &'a Provenance,
}

/// Everything one crossing produces. It borrows the bridge's modal basis: a study runs many
/// crossings on one basis and must not copy it for each.
pub struct RunResult<'a> {
    /// The modal basis used.
    pub basis: &'a ModalBasis,
    /// The time histories.
    pub history: ResponseHistory,
    /// The bridge's exact static influence lines.
    pub influence: &'a InfluenceLines,
    /// The DAF analysis.
    pub report: DafReport,
    /// Provenance.
    pub provenance: Provenance,
}

fn quantity_name(quantity: Quantity) -> &'static str {
    match quantity {
        Quantity::Deflection => "deflection",
        Quantity::BendingMoment => "bending_moment",
    }
}

/// The bridge half of a scenario, computed once and shared by every crossing of that bridge:
/// FE model, modal basis and exact static influence lines.
pub struct BridgeAnalysis {
    /// Degrees of freedom of the FE model.
    pub dof_count: usize,
    /// Modal basis (the kept kinds).
    pub basis: ModalBasis,
    /// Static influence lines from the full stiffness.
    pub influence: InfluenceLines,
}

/// FE model, modes and influence lines of a scenario's bridge.
pub fn prepare_bridge(scenario: &Scenario) -> Result<BridgeAnalysis> {
    let mesh = MeshOptions {
        element_length: scenario.element_length,
        ..MeshOptions::default()
    };
    let fe = discretise(&scenario.bridge, &mesh)
        .with_context(|| format!("discretising the bridge {}", scenario.bridge_label))?;
    let modal_options = ModalOptions {
        mode_count: scenario.mode_count,
        keep_kinds: scenario.mode_kinds.clone(),
        ..ModalOptions::default()
    };
    let basis = solve_modes(&fe, &modal_options).context("modal analysis of the bridge")?;
    let influence = influence_lines(&fe).context("static influence lines of the bridge")?;
    Ok(BridgeAnalysis {
        dof_count: fe.dof_count(),
        basis,
        influence,
    })
}

/// One crossing of the scenario's vehicle on its road over a prepared bridge, and its DAF
/// analysis.
/// `stations` says which stations get the full analysis: a study records only the RDM station.
pub fn run_crossing<'a>(
    bridge: &'a BridgeAnalysis,
    scenario: &Scenario,
    stations: StationScope,
) -> Result<RunResult<'a>> {
    let vehicle = assemble(&scenario.vehicle).context("assembling the vehicle")?;
    let (start, end) = scenario.road.extent_for_bridge(scenario.bridge.length());
    let road = generate(&scenario.road, start, end, scenario.road.seed)
        .context("generating the road profile")?;
    let crossing = Crossing {
        vehicle,
        road,
        speed: scenario.speed,
        lateral_position: scenario.lateral_position,
        start_position: start,
        free_vibration_duration: scenario.free_vibration,
    };
    let solver_options = SolverOptions {
        time_step: scenario.time_step,
        newmark_beta: scenario.newmark_beta,
        newmark_gamma: scenario.newmark_gamma,
        tyre_separation: scenario.tyre_separation,
        ..SolverOptions::default()
    };
    let basis = &bridge.basis;
    let history = simulate(basis, &crossing, &solver_options).context("vehicle crossing")?;
    let analysis_options = AnalysisOptions {
        convergence_tolerance: scenario.convergence_tolerance,
        stations,
        ..AnalysisOptions::default()
    };
    let mut report =
        analyse(basis, &bridge.influence, &history, &analysis_options).context("DAF analysis")?;
    if !scenario.rerun_mode_counts.is_empty() {
        report.truncated_runs = rerun_truncated(
            basis,
            &bridge.influence,
            &crossing,
            &solver_options,
            &analysis_options,
            &scenario.rerun_mode_counts,
        )
        .context("re-running the crossing with fewer modes")?;
    }
    let provenance = Provenance {
        vbi_version: env!("CARGO_PKG_VERSION").to_string(),
        input_hash: scenario.input_hash.clone(),
        seed: scenario.road.seed,
        time_step_s: history.time_step,
        modes: basis.mode_count(),
        dof_count: bridge.dof_count,
        scenario: scenario.name.clone(),
        bridge: scenario.bridge_label.clone(),
        vehicle: crossing.vehicle.name.clone(),
        speed_kmh: scenario.speed * 3.6,
    };
    Ok(RunResult {
        basis,
        history,
        influence: &bridge.influence,
        report,
        provenance,
    })
}

/// Runs the command.
pub fn run(args: &Args) -> Result<()> {
    let scenario = match &args.scenario {
        Some(path) => scenario::load(&SourceFile::read(path)?)?,
        None => scenario::built_in_default(),
    };
    let started = Instant::now();
    let bridge = with_progress(&format!("vbi run: {} (modes)", scenario.name), || {
        prepare_bridge(&scenario)
    })?;
    let result = with_progress(&format!("vbi run: {}", scenario.name), || {
        run_crossing(&bridge, &scenario, StationScope::All)
    })?;
    let elapsed = started.elapsed().as_secs_f64();
    for warning in warning_lines(&result) {
        eprintln!("warning: {warning}");
    }
    let summary = summarise(&result);
    match args.format {
        OutputFormat::Json => println!("{}", serde_json::to_string_pretty(&summary)?),
        OutputFormat::Table => print_table(&result, elapsed),
    }
    if let Some(dir) = &args.out {
        write_outputs(dir, &result, &summary)?;
    }
    Ok(())
}

fn summarise<'a>(result: &'a RunResult<'_>) -> RunSummary<'a> {
    let report = &result.report;
    RunSummary {
        stations: report
            .stations
            .iter()
            .map(|s| StationSummary {
                name: &s.name,
                quantity: quantity_name(s.quantity),
                static_max: s.static_max,
                dynamic_max: s.dynamic_max,
                daf: s.daf,
                impact_factor: s.impact_factor,
                daf_by_modes: &s.daf_by_modes,
                participation: &s.participation,
                convergence_mode: s.convergence_mode,
                cutoff_k1: s.cutoff_k1,
                cutoff_k2: s.cutoff_k2,
                corrected_dynamic_max: s.corrected_dynamic_max,
                corrected_daf: s.corrected_daf,
                corrected_daf_by_modes: &s.corrected_daf_by_modes,
                corrected_convergence_mode: s.corrected_convergence_mode,
            })
            .collect(),
        rdm_station: report.rdm_station.as_deref(),
        rdm: report.rdm,
        rdm_by_modes: &report.rdm_by_modes,
        corrected_rdm: report.corrected_rdm,
        corrected_rdm_by_modes: &report.corrected_rdm_by_modes,
        frequencies_hz: result
            .basis
            .modes
            .iter()
            .map(|m| m.frequency_hz())
            .collect(),
        deck_participation: &report.deck_participation,
        contact_losses: &report.contact_losses,
        warnings: warning_lines(result),
        truncated_runs: &report.truncated_runs,
        provenance: &result.provenance,
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

/// The solver's warnings and the contact losses, one clear sentence each.
fn warning_lines(result: &RunResult) -> Vec<String> {
    use vbi::solver::SolverWarning;
    let report = &result.report;
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
        lines.push(format!(
            "contact loss: tyre {} would lift off the road from t = {:.3} s to {:.3} s (tensile \
             contact force, down to {:.0} N); the model keeps the tyre bonded, so the responses \
             in that interval are those of a bonded tyre",
            loss.contact + 1,
            loss.start_time,
            loss.end_time,
            loss.minimum_force,
        ));
    }
    lines
}

fn optional(value: Option<f64>, decimals: usize) -> String {
    value.map_or_else(|| "-".to_string(), |v| format!("{v:.decimals$}"))
}

fn optional_index(value: Option<usize>) -> String {
    value.map_or_else(|| "-".to_string(), |v| v.to_string())
}

fn print_table(result: &RunResult, elapsed: f64) {
    let p = &result.provenance;
    println!(
        "{}: {} at {:.1} km/h on {}, {} modes, dt = {} s, seed {} ({} DOF; {:.2} s)",
        p.scenario,
        p.vehicle,
        p.speed_kmh,
        p.bridge,
        p.modes,
        p.time_step_s,
        p.seed,
        p.dof_count,
        elapsed
    );
    println!(
        "{:<22} {:<14} {:>13} {:>13} {:>7} {:>7} {:>4} {:>4} {:>4} {:>7}",
        "station", "quantity", "static max", "dynamic max", "DAF", "IM", "CM", "K1", "K2", "DAF*"
    );
    for s in result.report.stations.iter().filter(|s| s.daf.is_some()) {
        // Table units: millimetres and kilonewton-metres.
        let (unit_scale, unit) = match s.quantity {
            Quantity::Deflection => (1e3, "mm"),
            Quantity::BendingMoment => (1e-3, "kNm"),
        };
        println!(
            "{:<22} {:<14} {:>10.3} {:<2} {:>10.3} {:<2} {:>7} {:>7} {:>4} {:>4} {:>4} {:>7}",
            s.name,
            quantity_name(s.quantity),
            s.static_max * unit_scale,
            unit,
            s.dynamic_max * unit_scale,
            unit,
            optional(s.daf, 4),
            optional(s.impact_factor, 4),
            optional_index(s.convergence_mode),
            optional_index(s.cutoff_k1),
            optional_index(s.cutoff_k2),
            optional(s.corrected_daf, 4),
        );
    }
    println!("DAF*: static-corrected (mode-acceleration) series, see docs/theory.md");
    if let Some(station) = &result.report.rdm_station {
        println!(
            "RDM (DAF_u / DAF_M) at {station}: {} (static-corrected {})",
            optional(result.report.rdm, 4),
            optional(result.report.corrected_rdm, 4)
        );
        for run in &result.report.truncated_runs {
            let daf = |quantity: Quantity| {
                run.stations
                    .iter()
                    .find(|e| e.name == *station && e.quantity == quantity)
                    .and_then(|e| e.daf)
            };
            println!(
                "re-run with {} modes: DAF_u {}, DAF_M {}, RDM {}",
                run.mode_count,
                optional(daf(Quantity::Deflection), 4),
                optional(daf(Quantity::BendingMoment), 4),
                optional(run.rdm, 4)
            );
        }
    }
}

fn write_outputs(dir: &Path, result: &RunResult, summary: &RunSummary<'_>) -> Result<()> {
    create_output_dir(dir)?;
    write_json(&dir.join("summary.json"), summary)?;
    let basis = &result.basis;
    let history = &result.history;
    let reference = &static_reference(result.influence, history).context("static reference")?;
    let stations = basis.stations.len();

    // histories.csv: time, front axle, then dynamic and static responses of every station.
    let mut header = vec!["time_s".to_string(), "front_axle_x_m".to_string()];
    for s in &basis.stations {
        header.push(format!("{}_deflection_m", s.name));
        header.push(format!("{}_static_deflection_m", s.name));
        header.push(format!("{}_moment_n_m", s.name));
        header.push(format!("{}_static_moment_n_m", s.name));
    }
    let dynamic: Vec<[Vec<f64>; 2]> = (0..stations)
        .map(|s| {
            [Quantity::Deflection, Quantity::BendingMoment].map(|q| {
                let c = basis.station_values(s, q);
                (0..history.step_count)
                    .map(|i| {
                        c.iter()
                            .zip(history.modal_displacements_at(i))
                            .map(|(a, b)| a * b)
                            .sum()
                    })
                    .collect()
            })
        })
        .collect();
    let rows: Vec<Vec<String>> = (0..history.step_count)
        .map(|i| {
            let mut row = vec![
                number(i as f64 * history.time_step),
                number(history.front_axle_position[i]),
            ];
            for s in 0..stations {
                row.push(number(dynamic[s][0][i]));
                row.push(number(reference.deflection[i * stations + s]));
                row.push(number(dynamic[s][1][i]));
                row.push(number(reference.bending_moment[i * stations + s]));
            }
            row
        })
        .collect();
    let header_refs: Vec<&str> = header.iter().map(String::as_str).collect();
    write_csv(&dir.join("histories.csv"), &header_refs, &rows)?;

    // daf_by_modes.csv: one row per station, quantity and K.
    let mut rows = Vec::new();
    for s in &result.report.stations {
        for (k, daf) in s.daf_by_modes.iter().enumerate() {
            rows.push(vec![
                s.name.clone(),
                quantity_name(s.quantity).to_string(),
                (k + 1).to_string(),
                number(*daf),
                s.corrected_daf_by_modes
                    .get(k)
                    .map(|d| number(*d))
                    .unwrap_or_default(),
            ]);
        }
    }
    write_csv(
        &dir.join("daf_by_modes.csv"),
        &["station", "quantity", "modes", "daf", "daf_corrected"],
        &rows,
    )?;

    // participation.csv: deck-wide and per-station participation of every mode.
    let deck = &result.report.deck_participation;
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

    write_figures(dir, result, reference, &dynamic)?;
    Ok(())
}

fn write_figures(
    dir: &Path,
    result: &RunResult,
    reference: &StaticReference,
    dynamic: &[[Vec<f64>; 2]],
) -> Result<()> {
    let report = &result.report;
    let history = &result.history;
    let basis = &result.basis;
    let stations = basis.stations.len();
    let Some(rdm_name) = report.rdm_station.as_deref() else {
        return Ok(());
    };
    let Some(s) = basis.stations.iter().position(|st| st.name == rdm_name) else {
        return Ok(());
    };
    let times: Vec<f64> = (0..history.step_count)
        .map(|i| i as f64 * history.time_step)
        .collect();
    let series = |values: &[f64], scale: f64| -> Vec<(f64, f64)> {
        times
            .iter()
            .zip(values)
            .map(|(t, v)| (*t, v * scale))
            .collect()
    };
    let static_of = |table: &[f64]| -> Vec<f64> {
        (0..history.step_count)
            .map(|i| table[i * stations + s])
            .collect()
    };
    for (values, table, scale, label, stem) in [
        (
            &dynamic[s][0],
            &reference.deflection,
            1e3,
            "deflection [mm]",
            "history_deflection",
        ),
        (
            &dynamic[s][1],
            &reference.bending_moment,
            1e-3,
            "bending moment [kN·m]",
            "history_moment",
        ),
    ] {
        write_chart(
            &Chart {
                title: format!(
                    "{rdm_name}: dynamic and static {}",
                    label.split(' ').next().unwrap_or("")
                ),
                x_label: "time [s]".into(),
                y_label: label.into(),
                series: vec![
                    Series::line("dynamic", series(values, scale)),
                    Series::line("static", series(&static_of(table), scale)),
                ],
                ..Chart::default()
            },
            &dir.join(stem),
        )?;
    }
    // DAF and RDM against the number of modes.
    let mut daf_series = Vec::new();
    for entry in report.stations.iter().filter(|e| e.name == rdm_name) {
        daf_series.push(Series::line(
            format!("DAF {}", quantity_name(entry.quantity)),
            entry
                .daf_by_modes
                .iter()
                .enumerate()
                .map(|(k, d)| ((k + 1) as f64, *d))
                .collect(),
        ));
    }
    daf_series.push(Series::line(
        "RDM",
        report
            .rdm_by_modes
            .iter()
            .enumerate()
            .filter_map(|(k, r)| r.map(|r| ((k + 1) as f64, r)))
            .collect(),
    ));
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
    let c = basis.station_values(s, Quantity::Deflection);
    let mut decomposition = vec![Series::line("total", series(&dynamic[s][0], 1e3))];
    for k in 0..basis.mode_count().min(6) {
        let values: Vec<f64> = (0..history.step_count)
            .map(|i| c[k] * history.modal_displacements_at(i)[k])
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
