//! `[[measurement.channels]]`: each channel's column of the record, in SI, with its cut-off mode
//! (K1), its strain-to-moment conversion, its static reference and its sensor's place.

use vbi::measure::measurement::{Channel, K1Source};
use vbi::signal::{MeasuredQuantity, StrainToMoment};
use vbi::units;

use crate::logger_csv::LoggerTable;
use crate::measurement::bridge_model::RunK1;
use crate::measurement::channel_units::channel_unit;
use crate::measurement::influence::{static_reference_of, ReferenceContext};
use crate::measurement::raw::{RawChannel, RawMeasurement};
use crate::measurement::sensors::{position_in_span, sensor_location};
use crate::source::{require_in_range, require_positive, InputError, SourceFile};

/// What every channel is read against.
pub(crate) struct ChannelSettings<'a> {
    /// The record's CSV.
    pub(crate) table: &'a LoggerTable,
    /// f_s of the record as read [Hz] (the Nyquist frequency bounds the cut-off frequencies).
    pub(crate) sampling_rate_hz: f64,
    /// A bridge model is named (a cut-off mode number needs one).
    pub(crate) has_bridge: bool,
    /// The cut-off modes of `k1_from_run`, if given.
    pub(crate) run_k1: Option<&'a RunK1>,
    /// What a static reference needs.
    pub(crate) context: &'a ReferenceContext,
    /// The spans the sensors' positions are read in [m].
    pub(crate) spans: &'a [f64],
}

/// Every channel, in the order listed; a name listed twice is refused.
pub(crate) fn channels(
    file: &SourceFile,
    m: &RawMeasurement,
    settings: &ChannelSettings<'_>,
) -> Result<Vec<Channel>, InputError> {
    let mut channels = Vec::with_capacity(m.channels.len());
    for (c, raw) in m.channels.iter().enumerate() {
        let key = |k: &str| format!("measurement.channels[{c}].{k}");
        if channels.iter().any(|o: &Channel| o.name == raw.name) {
            return Err(file.error_at(
                &key("name"),
                format!("channel `{}` is listed twice", raw.name),
            ));
        }
        channels.push(channel(file, m, c, raw, settings)?);
    }
    Ok(channels)
}

/// Channel `c`: its column (`column`, default its name) of the record in SI, and its keys.
fn channel(
    file: &SourceFile,
    m: &RawMeasurement,
    c: usize,
    raw: &RawChannel,
    settings: &ChannelSettings<'_>,
) -> Result<Channel, InputError> {
    let table = settings.table;
    let csv_name = &table.file;
    let key = |k: &str| format!("measurement.channels[{c}].{k}");
    let column = raw.column.clone().unwrap_or_else(|| raw.name.clone());
    let index = table.column(&column).ok_or_else(|| {
        file.error_at(
            &key(if raw.column.is_some() {
                "column"
            } else {
                "name"
            }),
            format!(
                "channel `{column}` is missing from {csv_name}; {}",
                table.columns_shown()
            ),
        )
    })?;
    let (unit, factor) = channel_unit(file, table, c, raw, index)?;
    let samples: Vec<f64> = table
        .numbers(index)?
        .into_iter()
        .map(|v| v * factor)
        .collect();
    let k1 = k1_source(file, m, &key, raw, settings)?;
    let moment = strain_to_moment(file, &key, raw)?;
    let static_reference = static_reference_of(file, &key, raw, factor, settings.context)?;
    Ok(Channel {
        name: raw.name.clone(),
        column,
        kind: raw.kind,
        unit,
        si_per_unit: factor,
        samples,
        section: raw.section.clone(),
        k1,
        moment,
        static_reference,
        position_in_span: position_in_span(file, &key, raw, settings.spans)?,
        location: sensor_location(file, &key, raw, m.bridge_length_m)?,
    })
}

/// The channel's cut-off mode K1: its own `k1_cutoff_hz` or `k1_mode`, else the filter's
/// (`k1_cutoff_hz`, then `k1_mode_deflection` or `k1_mode_moment` by the channel's kind), else
/// the run summary's; none for an acceleration channel. Frequencies must lie below the Nyquist
/// frequency, mode numbers need a bridge model.
fn k1_source(
    file: &SourceFile,
    m: &RawMeasurement,
    key: &dyn Fn(&str) -> String,
    raw: &RawChannel,
    settings: &ChannelSettings<'_>,
) -> Result<Option<K1Source>, InputError> {
    let at = |key: &str| format!("measurement.{key}");
    let nyquist = settings.sampling_rate_hz / 2.0;
    let k1_range = |path: String, f: f64| {
        require_in_range(
            file,
            &path,
            f,
            f64::MIN_POSITIVE,
            nyquist * 0.999,
            "Hz (below the Nyquist frequency)",
        )
    };
    let is_moment = matches!(
        raw.kind,
        MeasuredQuantity::Strain | MeasuredQuantity::BendingMoment
    );
    let (filter_mode, filter_mode_key) = if is_moment {
        (m.filter.k1_mode_moment, "filter.k1_mode_moment")
    } else {
        (m.filter.k1_mode_deflection, "filter.k1_mode_deflection")
    };
    if raw.k1_cutoff_hz.is_some() && raw.k1_mode.is_some() {
        return Err(file.error_at(
            &key("k1_mode"),
            "give the cut-off mode once: k1_cutoff_hz or k1_mode, not both",
        ));
    }
    let model_mode = |path: String, mode: usize| -> Result<K1Source, InputError> {
        if mode == 0 {
            return Err(file.error_at(
                &path,
                "mode 0 is not allowed; modes are numbered from 1 as `vbi modes` lists them",
            ));
        }
        if !settings.has_bridge {
            return Err(file.error_at(
                &path,
                "a cut-off mode number needs a bridge model: give bridge = \"file.toml\", or the frequency as k1_cutoff_hz",
            ));
        }
        Ok(K1Source::ModelMode(mode))
    };
    Ok(if raw.kind == MeasuredQuantity::Acceleration {
        if raw.k1_cutoff_hz.is_some() || raw.k1_mode.is_some() {
            return Err(file.error_at(
                &key("k1_cutoff_hz"),
                "an acceleration channel has no DAF and no cut-off mode",
            ));
        }
        None
    } else if let Some(f) = raw.k1_cutoff_hz {
        Some(K1Source::Given(k1_range(key("k1_cutoff_hz"), f)?))
    } else if let Some(mode) = raw.k1_mode {
        Some(model_mode(key("k1_mode"), mode)?)
    } else if let Some(f) = m.filter.k1_cutoff_hz {
        Some(K1Source::Given(k1_range(at("filter.k1_cutoff_hz"), f)?))
    } else if let Some(mode) = filter_mode {
        Some(model_mode(at(filter_mode_key), mode)?)
    } else if let Some(run) = settings.run_k1 {
        let found = if is_moment {
            run.moment
        } else {
            run.deflection
        };
        match found {
            Some((mode, f)) => {
                k1_range(at("filter.k1_from_run"), f)?;
                Some(K1Source::RunSummary {
                    mode,
                    frequency_hz: f,
                })
            }
            None => None,
        }
    } else {
        None
    })
}

/// A strain channel's `moment`: a factor (`knm_per_microstrain`) or a section (`modulus_gpa`,
/// `second_moment_m4`, `distance_to_neutral_axis_m`), converted to N·m per unit strain.
fn strain_to_moment(
    file: &SourceFile,
    key: &dyn Fn(&str) -> String,
    raw: &RawChannel,
) -> Result<Option<StrainToMoment>, InputError> {
    Ok(match &raw.moment {
        None => None,
        Some(_) if raw.kind != MeasuredQuantity::Strain => {
            return Err(file.error_at(&key("moment"), "a strain-to-moment conversion applies to strain channels only"))
        }
        Some(mo) => Some(match (mo.knm_per_microstrain, mo.modulus_gpa, mo.second_moment_m4, mo.distance_to_neutral_axis_m) {
            (Some(f), None, None, None) => {
                if !(f.is_finite() && f != 0.0) {
                    return Err(file.error_at(&key("moment.knm_per_microstrain"), format!("{f} is not allowed; expected a finite non-zero number")));
                }
                StrainToMoment::Factor { newton_metres_per_strain: f * units::KN * 1e6 }
            }
            (None, Some(e), Some(i), Some(y)) => {
                let e = require_positive(file, &key("moment.modulus_gpa"), e, "GPa")?;
                let i = require_positive(file, &key("moment.second_moment_m4"), i, "m⁴")?;
                if !(y.is_finite() && y != 0.0) {
                    return Err(file.error_at(&key("moment.distance_to_neutral_axis_m"), format!("{y} is not allowed; expected a finite non-zero distance in m (positive below the neutral axis)")));
                }
                StrainToMoment::Section { elastic_modulus: e * units::GPA, second_moment_of_area: i, distance_to_neutral_axis: y }
            }
            _ => {
                return Err(file.error_at(
                    &key("moment"),
                    "give either knm_per_microstrain, or all of modulus_gpa, second_moment_m4 and distance_to_neutral_axis_m",
                ))
            }
        }),
    })
}
