//! `vbi modes [FILE] [--modes N] [--out DIR] [--format json|table]`: bridge model (each girder's
//! section, the total mass, the mesh and, with `--out`, a plan figure), sparse FE assembly and
//! the lowest modes by shift-invert Lanczos; or, for an imported bridge (`type = "imported"`),
//! the imported modes as read from their CSV files.

use std::io::Write;
use std::path::PathBuf;

use anyhow::{Context, Result};
use serde::Serialize;

use vbi::fe::{discretise, MeshOptions};
use vbi::modal::{solve_modes_with, CheckModes, ModalBasis, ModalError, ModalOptions, ModeKind};
use vbi::model::BridgeModel;

use crate::bridge_summary::{self, BridgeSummary};
use crate::commands::OutputFormat;
use crate::input::{InputError, SourceFile};
use crate::inputs::bridge;
use crate::output::{create_output_dir, number, write_csv};
use crate::plot::{write_charts, Chart, Series};

/// Arguments of `vbi modes`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Bridge file (`[bridge]` TOML). Without it: the paper's 3 × 30 m box-girder bridge.
    pub file: Option<PathBuf>,
    /// Number of modes to compute.
    #[arg(long, default_value_t = 50)]
    pub modes: usize,
    /// Directory for modes.csv, mode_shapes.csv, the mode-shape figure and the plan of the model
    /// (PNG and SVG).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Output on stdout.
    #[arg(long, value_enum, default_value_t = OutputFormat::Table)]
    pub format: OutputFormat,
    /// Also write vbi's FE model of the bridge as matrices into this directory (stiffness.mtx,
    /// mass.mtx, dofs.csv, nodes.csv and a bridge.toml that reads them back as an
    /// `imported_matrices` bridge).
    #[arg(long, value_name = "DIR")]
    pub export_matrices: Option<PathBuf>,
}

/// One mode as printed in JSON.
#[derive(Debug, Serialize)]
struct ModeSummary {
    index: usize,
    frequency_hz: f64,
    period_s: f64,
    kind: ModeKind,
    residual: f64,
    /// The mode's damping ratio [-], shown when the bridge gives each mode its own
    /// (`damping_ratios` or `rayleigh_damping`).
    #[serde(skip_serializing_if = "Option::is_none")]
    damping_ratio: Option<f64>,
}

/// The JSON document of `vbi modes --format json`.
#[derive(Debug, Serialize)]
struct ModesSummary {
    dof_count: usize,
    /// The bridge's sections, mass and mesh (vbi's own models).
    #[serde(skip_serializing_if = "Option::is_none")]
    model: Option<BridgeSummary>,
    modes: Vec<ModeSummary>,
}

/// Runs the command.
pub fn run(args: &Args) -> Result<()> {
    if args.modes == 0 {
        return Err(
            InputError::command_line("--modes", "0 is not allowed; expected at least 1").into(),
        );
    }
    let mut show_damping = false;
    let mut bridge_model = None;
    let (basis, name) = match &args.file {
        Some(path) => {
            let file = SourceFile::read(path)?;
            crate::inputs::expect_kind(&file, "bridge", "vbi modes")?;
            let name = path.display().to_string();
            match bridge::load_imported(&file)? {
                Some(_) if args.export_matrices.is_some() => {
                    return Err(InputError::command_line(
                        "--export-matrices",
                        "an imported modal basis has no matrices to export; expected a \
                         `continuous_beam`, `grillage` or `imported_matrices` bridge",
                    )
                    .into())
                }
                Some(imported) => {
                    // The imported modes are listed as given, the first N of them.
                    let keep: Vec<usize> = (0..imported.mode_count().min(args.modes)).collect();
                    (
                        imported.select_modes(&keep),
                        format!("{name} (imported modes)"),
                    )
                }
                None => {
                    let model = bridge::load(&file)?;
                    show_damping = model.mode_damping().is_some();
                    let basis = solve(&model, args.modes, &name, Some(&file))?;
                    export(args, &model, &name, Some(&file))?;
                    bridge_model = Some(model);
                    (basis, name)
                }
            }
        }
        None => {
            let name = "built-in paper 3×30 m bridge".to_string();
            let model = bridge::built_in_default();
            let basis = solve(&model, args.modes, &name, None)?;
            export(args, &model, &name, None)?;
            bridge_model = Some(model);
            (basis, name)
        }
    };
    let described = match &bridge_model {
        // The model was meshed by `solve` already: this cannot fail where that did not.
        Some(model) => bridge_summary::summarise(model)
            .map_err(|e| anyhow::anyhow!("summarising {name}: {e}"))?,
        None => None,
    };
    let (model_summary, plan) = match described {
        Some((summary, plan)) => (Some(summary), Some(plan)),
        None => (None, None),
    };
    let mut summary = summarise(&basis, basis.dof_count, show_damping);
    summary.model = model_summary;
    let plan = plan.zip(bridge_model.as_ref());
    let mut stdout = std::io::stdout().lock();
    let printed = match args.format {
        OutputFormat::Json => writeln!(stdout, "{}", serde_json::to_string_pretty(&summary)?),
        OutputFormat::Table => print_table(&mut stdout, &name, &summary),
    };
    match printed {
        // A closed pipe (`vbi modes | head`) is not an error: the reader has what it wanted.
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => {}
        other => other.context("writing to standard output")?,
    }
    if let Some(dir) = &args.out {
        write_outputs(dir, &basis, &summary)?;
        if let (Some((plan, model)), Some(model_summary)) = (&plan, &summary.model) {
            let fe = discretise(model, &MeshOptions::default())
                .map_err(|e| anyhow::anyhow!("discretising {name}: {e}"))?;
            let lines: Vec<f64> = fe.deck.lines.iter().map(|l| l.lateral_position).collect();
            bridge_summary::write_plan(dir, model_summary, plan, &fe.stations, &lines, &[])?;
        }
    }
    Ok(())
}

/// Writes the FE model of `model` as matrices, if `--export-matrices` asks for it.
fn export(args: &Args, model: &BridgeModel, name: &str, file: Option<&SourceFile>) -> Result<()> {
    let Some(dir) = &args.export_matrices else {
        return Ok(());
    };
    let exported = match model {
        // An imported model is written back as it was read (in SI and vbi's axes).
        BridgeModel::ImportedMatrices(_) => vbi::fe::export_imported(model),
        _ => vbi::fe::export_matrices(model, &MeshOptions::default()),
    }
    .map_err(|e| -> anyhow::Error {
        match file {
            Some(file) => file
                .error_at("bridge", format!("exporting the matrices: {e}"))
                .into(),
            None => anyhow::anyhow!("exporting the matrices of {name}: {e}"),
        }
    })?;
    crate::export_matrices::write(dir, &exported, name)
}

/// Meshes the model with the default mesh and solves its lowest `mode_count` modes. A failure
/// is located: a model too large for memory at `--modes`, a mechanism at the bridge file's
/// supports, anything else at its `[bridge]`.
pub(crate) fn solve(
    model: &BridgeModel,
    mode_count: usize,
    name: &str,
    file: Option<&SourceFile>,
) -> Result<ModalBasis> {
    let fe = discretise(model, &MeshOptions::default()).map_err(|e| match file {
        Some(file) => file
            .error_at("bridge", format!("discretising the bridge: {e}"))
            .into(),
        None => anyhow::anyhow!("discretising {name}: {e}"),
    })?;
    let options = ModalOptions {
        mode_count,
        ..ModalOptions::default()
    };
    // The modes listed, without the check modes that a crossing's convergence indicator reads.
    solve_modes_with(&fe, &options, CheckModes::Skip).map_err(|e| {
        let message = format!("modal analysis of {name}: {e}");
        match (&e, file) {
            (ModalError::MemoryLimit { .. } | ModalError::WorkLimit { .. }, _) => {
                InputError::command_line("--modes", message)
            }
            (ModalError::Mechanism { .. } | ModalError::Unstable { .. }, Some(file)) => {
                // An imported model's supports are in its matrices.
                let key = if file.has_key("bridge.stiffness_mtx") {
                    "bridge.stiffness_mtx"
                } else {
                    "bridge.supports"
                };
                file.error_at(key, message)
            }
            (_, Some(file)) => file.error_at("bridge", message),
            (_, None) => return anyhow::anyhow!(message),
        }
        .into()
    })
}

/// The summary of the modes; `show_damping`: with each mode's damping ratio.
fn summarise(basis: &ModalBasis, dof_count: usize, show_damping: bool) -> ModesSummary {
    ModesSummary {
        dof_count,
        model: None,
        modes: basis
            .modes
            .iter()
            .enumerate()
            .map(|(i, m)| ModeSummary {
                index: i + 1,
                frequency_hz: m.frequency_hz(),
                period_s: 1.0 / m.frequency_hz(),
                kind: m.kind,
                residual: m.residual,
                damping_ratio: show_damping.then_some(m.damping_ratio),
            })
            .collect(),
    }
}

fn print_table(out: &mut impl Write, name: &str, summary: &ModesSummary) -> std::io::Result<()> {
    if summary.dof_count == 0 {
        // An imported basis: the other program's model size is not known.
        writeln!(out, "{name}: {} modes", summary.modes.len())?;
    } else {
        writeln!(out, "{name}: {} degrees of freedom", summary.dof_count)?;
    }
    if let Some(model) = &summary.model {
        bridge_summary::print(out, model)?;
    }
    let damping_header = match summary.modes.first().and_then(|m| m.damping_ratio) {
        Some(_) => format!(" {:>9}", "damping"),
        None => String::new(),
    };
    writeln!(
        out,
        "{:>5} {:>14} {:>12}  {:<20} {:>10}{damping_header}",
        "mode", "frequency [Hz]", "period [s]", "kind", "residual"
    )?;
    for m in &summary.modes {
        let damping = m
            .damping_ratio
            .map_or(String::new(), |ratio| format!(" {ratio:>9.5}"));
        writeln!(
            out,
            "{:>5} {:>14.4} {:>12.5}  {:<20} {:>10.2e}{damping}",
            m.index,
            m.frequency_hz,
            m.period_s,
            m.kind.name(),
            m.residual
        )?;
    }
    Ok(())
}

fn write_outputs(dir: &std::path::Path, basis: &ModalBasis, summary: &ModesSummary) -> Result<()> {
    create_output_dir(dir)?;
    let rows: Vec<Vec<String>> = summary
        .modes
        .iter()
        .map(|m| {
            vec![
                m.index.to_string(),
                number(m.frequency_hz),
                number(m.period_s),
                m.kind.name().to_string(),
                number(m.residual),
            ]
        })
        .collect();
    write_csv(
        &dir.join("modes.csv"),
        &["mode", "frequency_hz", "period_s", "kind", "residual"],
        &rows,
    )?;

    // Mode shapes at deck nodes: one row per node, one column per mode.
    let n = basis.mode_count();
    let mut header: Vec<String> = vec!["line".into(), "node".into(), "x_m".into(), "y_m".into()];
    header.extend((1..=n).map(|k| format!("mode_{k}")));
    let mut rows = Vec::new();
    for (line_index, line) in basis.deck.lines.iter().enumerate() {
        for (i, &x) in line.node_positions.iter().enumerate() {
            let node = line.first_node + i;
            let mut row = vec![
                line_index.to_string(),
                node.to_string(),
                number(x),
                number(line.lateral_position),
            ];
            row.extend((0..n).map(|k| number(basis.deck_deflection[node * n + k])));
            rows.push(row);
        }
    }
    let header_refs: Vec<&str> = header.iter().map(String::as_str).collect();
    write_csv(&dir.join("mode_shapes.csv"), &header_refs, &rows)?;

    // Figure: the first six shapes, one curve per deck line.
    let charts: Vec<Chart> = (0..n.min(6))
        .map(|k| Chart {
            title: format!(
                "mode {}: {:.3} Hz ({})",
                k + 1,
                basis.modes[k].frequency_hz(),
                basis.modes[k].kind.name()
            ),
            x_label: "x [m]".into(),
            y_label: "vertical shape [-]".into(),
            series: basis
                .deck
                .lines
                .iter()
                .enumerate()
                .map(|(li, line)| {
                    let label = if basis.deck.lines.len() > 1 {
                        format!("girder {}", li + 1)
                    } else {
                        String::new()
                    };
                    Series::line(
                        label,
                        line.node_positions
                            .iter()
                            .enumerate()
                            .map(|(i, &x)| {
                                (x, basis.deck_deflection[(line.first_node + i) * n + k])
                            })
                            .collect(),
                    )
                })
                .collect(),
            ..Chart::default()
        })
        .collect();
    write_charts(&charts, 2, &dir.join("mode_shapes"))?;
    Ok(())
}
