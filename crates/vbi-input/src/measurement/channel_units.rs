//! A channel's `unit` (or the CSV's unit line) and its factor to SI.

use vbi::signal::MeasuredQuantity;
use vbi::units;

use crate::logger_csv::LoggerTable;
use crate::measurement::raw::RawChannel;
use crate::source::{InputError, SourceFile};

/// SI factor of a unit for a kind of channel, or the list of allowed units.
fn unit_factor(kind: MeasuredQuantity, unit: &str) -> Result<f64, &'static str> {
    let u = unit.trim();
    match kind {
        MeasuredQuantity::Deflection => match u {
            "m" => Ok(1.0),
            "mm" => Ok(units::MM),
            "cm" => Ok(units::CM),
            _ => Err("m, cm, mm"),
        },
        MeasuredQuantity::Strain => match u {
            "strain" | "-" | "m/m" => Ok(1.0),
            "microstrain" | "µε" | "με" | "ue" | "µm/m" | "μm/m" | "um/m" => Ok(1e-6),
            _ => Err("strain (or - , m/m), microstrain (or µε, ue, µm/m)"),
        },
        MeasuredQuantity::BendingMoment => match u {
            "N·m" | "N.m" | "Nm" => Ok(1.0),
            "kN·m" | "kN.m" | "kNm" => Ok(units::KN),
            "MN·m" | "MN.m" | "MNm" => Ok(1e6),
            _ => Err("N·m, kN·m, MN·m (or N.m, kNm …)"),
        },
        MeasuredQuantity::Acceleration => match u {
            "m/s²" | "m/s2" | "m/s^2" => Ok(1.0),
            "g" => Ok(units::GRAVITY),
            "mg" => Ok(units::GRAVITY * 1e-3),
            "cm/s²" | "cm/s2" | "gal" | "Gal" => Ok(0.01),
            _ => Err("m/s² (or m/s2), g, mg, cm/s² (or Gal)"),
        },
    }
}

/// A channel's unit and its SI factor: its `unit` key, or the CSV's unit line, or both when
/// they agree (the same unit, by its factor).
pub(crate) fn channel_unit(
    file: &SourceFile,
    table: &LoggerTable,
    c: usize,
    raw: &RawChannel,
    index: usize,
) -> Result<(String, f64), InputError> {
    let key = format!("measurement.channels[{c}].unit");
    let factor_at_key = |unit: &str| {
        unit_factor(raw.kind, unit).map_err(|allowed| {
            file.error_at(
                &key,
                format!(
                    "unit `{unit}` is not allowed for a {:?} channel; expected one of {allowed}",
                    raw.kind
                )
                .to_lowercase(),
            )
        })
    };
    match (&raw.unit, table.unit(index)) {
        (Some(unit), None) => Ok((unit.clone(), factor_at_key(unit)?)),
        (None, None) => Err(file.error_at(&key, missing_unit(table, index))),
        (None, Some((line, unit))) => {
            let kind = format!("{:?}", raw.kind).to_lowercase();
            let factor = unit_factor(raw.kind, unit).map_err(|allowed| InputError {
                file: table.file.clone(),
                location: Some((line, index + 1)),
                field: Some(table.header[index].clone()),
                message: format!(
                    "unit `{unit}` (csv_format.unit_line) is not allowed for a {kind} channel; \
                     expected one of {allowed}, or give the channel's unit in \
                     measurement.channels[{c}].unit"
                ),
            })?;
            Ok((unit.to_string(), factor))
        }
        (Some(given), Some((line, unit))) => {
            let factor = factor_at_key(given)?;
            match unit_factor(raw.kind, unit) {
                Ok(f) if f == factor => Ok((given.clone(), factor)),
                _ => Err(file.error_at(
                    &key,
                    format!(
                        "unit `{given}` differs from `{unit}`, the unit of column `{}` in the \
                         unit line of {} (line {line}, csv_format.unit_line); give the same \
                         unit, or remove this unit to take the unit line's",
                        table.header[index], table.file
                    ),
                )),
            }
        }
    }
}

/// Why a channel has no unit: no `unit` key and no unit line, or no unit for its column in the
/// unit line.
fn missing_unit(table: &LoggerTable, index: usize) -> String {
    match &table.units {
        None => "missing field `unit`; give the channel's unit (or csv_format.unit_line, the \
                 line of the CSV that holds the units)"
            .to_string(),
        Some((line, _)) => format!(
            "the unit line of {} (line {line}) has no unit for column `{}`; give the channel's \
             unit",
            table.file, table.header[index]
        ),
    }
}
