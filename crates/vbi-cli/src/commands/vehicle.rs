//! `vbi vehicle list` and `vbi vehicle show NAME|FILE`: the built-in vehicles, and the DOFs,
//! total mass, static wheel loads and natural frequencies of one vehicle.

use crate::console::outln;
use anyhow::Result;
use serde::Serialize;
use vbi::units::GRAVITY;
use vbi::vehicle::{natural_modes, presets, ContactKind, VehicleModel, VehicleSpec};

use crate::commands::OutputFormat;
use crate::input::InputError;
use crate::inputs::vehicle::resolve;

/// Subcommands of `vbi vehicle`.
#[derive(Debug, clap::Subcommand)]
pub enum Command {
    /// List the presets with their DOFs, total mass and source.
    List {
        /// Output format on standard output.
        #[arg(long, value_enum, default_value = "table")]
        format: OutputFormat,
    },
    /// Show a vehicle: DOFs, total mass, static wheel loads, natural frequencies with the
    /// dominant motion of each (check body bounce at 1.5–3 Hz and axle hop at 8–15 Hz).
    Show {
        /// A preset name (see `vbi vehicle list`) or a `[vehicle]` TOML file.
        vehicle: String,
        /// Output format on standard output.
        #[arg(long, value_enum, default_value = "table")]
        format: OutputFormat,
    },
}

/// Runs the command.
pub fn run(command: &Command) -> Result<()> {
    match command {
        Command::List { format } => list(*format),
        Command::Show { vehicle, format } => show(vehicle, *format),
    }
}

#[derive(Debug, Serialize)]
struct Wheel {
    longitudinal_offset_m: f64,
    lateral_offset_m: f64,
    static_load_n: f64,
    kind: &'static str,
    tyre_stiffness_n_per_m: Option<f64>,
    tyre_damping_n_s_per_m: Option<f64>,
}

#[derive(Debug, Serialize)]
struct Mode {
    frequency_hz: f64,
    motion: &'static str,
    part: String,
    label: String,
    energy_share: f64,
}

#[derive(Debug, Serialize)]
struct Report {
    name: String,
    source: String,
    dof_count: usize,
    dof_names: Vec<String>,
    total_mass_kg: f64,
    total_weight_n: f64,
    static_wheel_loads_n: Vec<f64>,
    wheels: Vec<Wheel>,
    natural_frequencies_hz: Vec<f64>,
    modes: Vec<Mode>,
}

fn report(spec: &VehicleSpec, model: &VehicleModel) -> Result<Report, InputError> {
    let modes = natural_modes(model)
        .map_err(|e| InputError::command_line("vehicle", format!("{}: {e}", spec.name)))?;
    let wheels: Vec<Wheel> = model
        .contacts
        .iter()
        .map(|c| {
            let (kind, stiffness, damping) = match &c.kind {
                ContactKind::Force => ("force", None, None),
                ContactKind::Tyre {
                    stiffness, damping, ..
                } => ("tyre", Some(*stiffness), Some(*damping)),
            };
            Wheel {
                longitudinal_offset_m: c.longitudinal_offset,
                lateral_offset_m: c.lateral_offset,
                static_load_n: c.static_load,
                kind,
                tyre_stiffness_n_per_m: stiffness,
                tyre_damping_n_s_per_m: damping,
            }
        })
        .collect();
    Ok(Report {
        name: spec.name.clone(),
        source: spec.source.clone(),
        dof_count: model.dof_count(),
        dof_names: model.dof_names.clone(),
        total_mass_kg: spec.total_mass(),
        total_weight_n: model.total_static_load(),
        static_wheel_loads_n: model.contacts.iter().map(|c| c.static_load).collect(),
        wheels,
        natural_frequencies_hz: modes.iter().map(|m| m.frequency_hz).collect(),
        modes: modes
            .iter()
            .map(|m| Mode {
                frequency_hz: m.frequency_hz,
                motion: m.motion.label(),
                part: m.part.clone(),
                label: m.label(),
                energy_share: m.energy_share,
            })
            .collect(),
    })
}

fn assemble_preset(spec: &VehicleSpec) -> Result<VehicleModel> {
    vbi::vehicle::assemble(spec)
        .map_err(|e| anyhow::anyhow!("built-in vehicle `{}` does not assemble: {e}", spec.name))
}

fn list(format: OutputFormat) -> Result<()> {
    let mut rows = Vec::new();
    for spec in presets() {
        let model = assemble_preset(&spec)?;
        rows.push(serde_json::json!({
            "name": spec.name,
            "dof_count": model.dof_count(),
            "axle_count": axle_count(&model),
            "total_mass_kg": spec.total_mass(),
            "source": spec.source,
        }));
    }
    match format {
        OutputFormat::Json => outln!("{}", serde_json::to_string_pretty(&rows)?),
        OutputFormat::Table => {
            outln!(
                "{:<28} {:>4} {:>6} {:>12}  source",
                "name",
                "DOF",
                "axles",
                "mass [kg]"
            );
            for row in &rows {
                let source = row["source"].as_str().unwrap_or_default();
                let short: String = source.chars().take(60).collect();
                let ellipsis = if source.chars().count() > 60 {
                    "…"
                } else {
                    ""
                };
                outln!(
                    "{:<28} {:>4} {:>6} {:>12.0}  {short}{ellipsis}",
                    row["name"].as_str().unwrap_or_default(),
                    row["dof_count"].as_u64().unwrap_or_default(),
                    row["axle_count"].as_u64().unwrap_or_default(),
                    row["total_mass_kg"].as_f64().unwrap_or(f64::NAN),
                );
            }
            outln!("\n`vbi vehicle show NAME` gives the details of one.");
        }
    }
    Ok(())
}

/// Number of distinct axle positions.
fn axle_count(model: &VehicleModel) -> usize {
    let mut positions: Vec<f64> = model
        .contacts
        .iter()
        .map(|c| c.longitudinal_offset)
        .collect();
    positions.dedup();
    positions.len()
}

fn show(vehicle: &str, format: OutputFormat) -> Result<()> {
    let spec = resolve(vehicle)?;
    let model = vbi::vehicle::assemble(&spec)
        .map_err(|e| InputError::command_line("vehicle", format!("`{vehicle}`: {e}")))?;
    let report = report(&spec, &model)?;
    match format {
        OutputFormat::Json => outln!("{}", serde_json::to_string_pretty(&report)?),
        OutputFormat::Table => print_table(&report),
    }
    Ok(())
}

fn print_table(report: &Report) {
    outln!("vehicle        {}", report.name);
    outln!("source         {}", report.source);
    outln!("DOFs           {}", report.dof_count);
    if !report.dof_names.is_empty() {
        outln!("               {}", report.dof_names.join(", "));
    }
    outln!(
        "total mass     {:.1} kg (weight {:.2} kN)",
        report.total_mass_kg,
        report.total_mass_kg * GRAVITY / 1e3
    );
    outln!(
        "\nstatic wheel loads (sum {:.2} kN)\n  {:>9} {:>9} {:>11} {:>9}  contact",
        report.total_weight_n / 1e3,
        "x [m]",
        "y [m]",
        "load [kN]",
        "load [t]"
    );
    for w in &report.wheels {
        let contact = match w.tyre_stiffness_n_per_m {
            Some(k) => format!("tyre {:.3e} N/m", k),
            None => "constant force".into(),
        };
        outln!(
            "  {:>9.3} {:>9.3} {:>11.2} {:>9.3}  {contact}",
            w.longitudinal_offset_m,
            w.lateral_offset_m,
            w.static_load_n / 1e3,
            w.static_load_n / GRAVITY / 1e3
        );
    }
    if report.modes.is_empty() {
        outln!("\nno natural frequencies (moving forces have no DOFs)");
        return;
    }
    outln!(
        "\nnatural frequencies (rigid road)\n  {:>9}  dominant motion (energy share)",
        "f [Hz]"
    );
    for m in &report.modes {
        outln!(
            "  {:>9.3}  {} ({:.0} %)",
            m.frequency_hz,
            m.label,
            100.0 * m.energy_share
        );
    }
}
