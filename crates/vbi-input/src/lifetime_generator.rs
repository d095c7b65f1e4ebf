//! `[lifetime.generator]`: a lifetime's traffic simulated by vbi's own generator in the BTLS
//! way ([`vbi::traffic::generator`]; docs/lifetime.md, "Simulated traffic") instead of read from
//! a traffic file.
//!
//! ```toml
//! [lifetime.generator]
//! parameters = "GraveParameters/Auxerre"  # a Grave parameter folder (PyBTLS's, not shipped)
//! lane_flow_file = "LaneFlowData_80.csv"  # BTLS's lane flow file: flows by hour and lane
//! headway = "free_flow"                   # free_flow | heds | constant
//! days = 25                               # days of traffic
//! seed = 0                                # the lanes' random streams
//! ```

use vbi::traffic::generator::{HeadwayModel, TrafficGenerator};

use crate::grave_parameters::{load_grave_folder, load_lane_flow};
use crate::source::{relative, require_in_range, InputError, SourceFile};
use crate::traffic_source::{GeneratorInput, TrafficSource};

/// Every key of `[lifetime.generator]`.
pub const GENERATOR_KEYS: [&str; 7] = [
    "parameters",
    "lane_flow_file",
    "headway",
    "constant_gap_s",
    "days",
    "seed",
    "no_overlap_length_m",
];

/// The headway models' names.
pub const HEADWAY_NAMES: [&str; 3] = ["free_flow", "heds", "constant"];

/// The most days of traffic (a thousand years of 250 working days... and more: 10⁶ days).
pub const MAX_DAYS: f64 = 1.0e6;

/// Reads `[lifetime.generator]` (`value`), its folder and lane flow file relative to `file`;
/// `deck_length` [m] is the default no-overlap length.
pub fn load(
    file: &SourceFile,
    value: &toml::Value,
    deck_length: f64,
) -> Result<GeneratorInput, InputError> {
    let at = |key: &str| format!("lifetime.generator.{key}");
    let toml::Value::Table(raw) = value else {
        return Err(file.error_at(
            "lifetime.generator",
            "expected a [lifetime.generator] table (parameters, lane_flow_file, headway, days, seed)",
        ));
    };
    if let Some(unknown) = raw.keys().find(|k| !GENERATOR_KEYS.contains(&k.as_str())) {
        return Err(file.error_at(
            &at(unknown),
            format!(
                "unknown key `{unknown}` in [lifetime.generator]; expected one of {}",
                GENERATOR_KEYS.join(", ")
            ),
        ));
    }
    let path = |key: &str, what: &str| match raw.get(key) {
        Some(toml::Value::String(name)) => Ok(relative(file, name)),
        _ => Err(file.error_at(&at(key), format!("expected {what}, relative to this file"))),
    };
    let parameters_folder = path(
        "parameters",
        "the Grave parameter folder (PyBTLS's py/pybtls/data/GraveParameters/<site>)",
    )?;
    let lane_flow_file = path("lane_flow_file", "BTLS's lane flow file")?;
    let folder = load_grave_folder(&parameters_folder)
        .map_err(|e| e.at_naming_key(file, "lifetime.generator.parameters"))?;
    let lanes = load_lane_flow(&lane_flow_file)
        .map_err(|e| e.at_naming_key(file, "lifetime.generator.lane_flow_file"))?;
    let number = |key: &str, default: f64| -> Result<f64, InputError> {
        match raw.get(key) {
            None => Ok(default),
            Some(toml::Value::Integer(v)) => Ok(*v as f64),
            Some(toml::Value::Float(v)) => Ok(*v),
            Some(other) => Err(file.error_at(
                &at(key),
                format!("{other} is not allowed; expected a number"),
            )),
        }
    };
    let days = require_in_range(
        file,
        &at("days"),
        number("days", f64::NAN)?,
        1.0,
        MAX_DAYS,
        "days",
    )
    .map_err(|_| {
        file.error_at(
            &at("days"),
            format!("expected the days of traffic, a whole number from 1 to {MAX_DAYS:e}"),
        )
    })?;
    if days.fract() != 0.0 {
        return Err(file.error_at(
            &at("days"),
            format!("{days} is not allowed; expected a whole number of days"),
        ));
    }
    let no_overlap_length = require_in_range(
        file,
        &at("no_overlap_length_m"),
        number("no_overlap_length_m", deck_length)?,
        0.0,
        10_000.0,
        "m",
    )?;
    let seed = match raw.get("seed") {
        None => 0,
        Some(value) => {
            value
                .clone()
                .try_into::<crate::seed::Seed>()
                .map_err(|e| file.error_at(&at("seed"), e.message().to_string()))?
                .0
        }
    };
    let headway = headway(file, raw, folder.heds.clone())?;
    let input = GeneratorInput {
        parameters_folder,
        lane_flow_file,
        parameters: folder.parameters,
        heds: folder.heds,
        lanes,
        headway,
        days: days as u64,
        seed,
        no_overlap_length,
    };
    // Every check of the generator, before any work (and for `vbi check`).
    generator_of(file, &input)?;
    Ok(input)
}

/// The headway model named by `headway` (HeDS needs the folder's table).
fn headway(
    file: &SourceFile,
    raw: &toml::Table,
    heds: Option<vbi::traffic::generator::HedsTable>,
) -> Result<HeadwayModel, InputError> {
    let at = "lifetime.generator.headway";
    let name = match raw.get("headway") {
        None => "free_flow",
        Some(toml::Value::String(name)) => name.as_str(),
        Some(other) => {
            return Err(file.error_at(
                at,
                format!(
                    "{other} is not allowed; expected one of {}",
                    HEADWAY_NAMES.join(", ")
                ),
            ))
        }
    };
    if name != "constant" && raw.contains_key("constant_gap_s") {
        return Err(file.error_at(
            "lifetime.generator.constant_gap_s",
            "`constant_gap_s` is the gap of headway = \"constant\"",
        ));
    }
    match name {
        "free_flow" => Ok(HeadwayModel::FreeFlow),
        "heds" => heds.map(HeadwayModel::Heds).ok_or_else(|| {
            file.error_at(
                at,
                "headway = \"heds\" needs the folder's HeDS.csv (PyBTLS ships it for Auxerre only)",
            )
        }),
        "constant" => match raw.get("constant_gap_s") {
            Some(toml::Value::Float(gap)) if *gap > 0.0 && gap.is_finite() => {
                Ok(HeadwayModel::Constant { gap_s: *gap })
            }
            Some(toml::Value::Integer(gap)) if *gap > 0 => {
                Ok(HeadwayModel::Constant { gap_s: *gap as f64 })
            }
            _ => Err(file.error_at(
                "lifetime.generator.constant_gap_s",
                "headway = \"constant\" needs the gap [s], a positive number",
            )),
        },
        other => Err(file.error_at(
            at,
            format!(
                "`{other}` is not a headway model; expected one of {}",
                HEADWAY_NAMES.join(", ")
            ),
        )),
    }
}

/// The generator of `input`, or its refusal located at `[lifetime.generator]`.
fn generator_of(file: &SourceFile, input: &GeneratorInput) -> Result<TrafficGenerator, InputError> {
    TrafficGenerator::new(
        input.parameters.clone(),
        input.lanes.clone(),
        input.headway.clone(),
        input.seed,
        input.days,
        input.no_overlap_length,
    )
    .map_err(|e| file.error_at("lifetime.generator", e.to_string()))
}

/// The generated traffic of `input` as a stream.
pub fn open(file: &SourceFile, input: &GeneratorInput) -> Result<TrafficSource, InputError> {
    Ok(TrafficSource::Generated {
        generator: Box::new(generator_of(file, input)?),
        count: 0,
    })
}
