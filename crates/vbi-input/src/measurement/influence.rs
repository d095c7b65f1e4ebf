//! A channel's `static_reference` in `[[measurement.channels]]`: an influence line given as a
//! table, the bridge model's (`"model"`) or the crawl run's (`"crawl"`).

use vbi::measure::measurement::StaticReference;
use vbi::signal::{MeasuredQuantity, SampledInfluenceLine};
use vbi::units;

use crate::measurement::raw::{RawChannel, RawInfluenceLine};
use crate::source::{InputError, SourceFile};

/// What a channel's static reference needs from the rest of the file.
pub(crate) struct ReferenceContext {
    /// `[measurement.vehicle]` is given.
    pub(crate) has_vehicle: bool,
    /// `bridge` is given.
    pub(crate) has_bridge: bool,
    /// `crawl` is given.
    pub(crate) has_crawl: bool,
    /// `bridge_length_m` or `bridge` is given.
    pub(crate) has_length: bool,
}

/// A channel's `static_reference`: a table `{ position_m, value_per_kn }` (an influence line in
/// the channel unit per kN), "model" (the bridge model's line at `position_m`) or "crawl" (the
/// line calibrated from the crawl run); each needs `[measurement.vehicle]`.
pub(crate) fn static_reference_of(
    file: &SourceFile,
    key: &dyn Fn(&str) -> String,
    raw: &RawChannel,
    factor: f64,
    context: &ReferenceContext,
) -> Result<Option<StaticReference>, InputError> {
    let Some(value) = &raw.static_reference else {
        return Ok(None);
    };
    let field = key("static_reference");
    let refuse = |message: &str| Err(file.error_at(&field, message));
    if raw.kind == MeasuredQuantity::Acceleration {
        return refuse("an acceleration channel has no static reference");
    }
    if !context.has_vehicle {
        return refuse("a static reference from an influence line needs [measurement.vehicle] (axle loads, offsets, entry time)");
    }
    match value {
        toml::Value::String(name) if name == "model" => {
            if !context.has_bridge {
                return refuse("\"model\" reads the bridge model's influence line: give bridge = \"file.toml\"");
            }
            if raw.position_m.is_none() {
                return refuse("\"model\" reads the bridge model's influence line at the sensor: give position_m (and lateral_position_m on a grillage)");
            }
            if raw.kind == MeasuredQuantity::Strain && raw.moment.is_none() {
                return refuse("\"model\" reads a strain gauge through the model's moment line: give moment = { knm_per_microstrain = ... } or the section");
            }
            Ok(Some(StaticReference::BridgeModel))
        }
        toml::Value::String(name) if name == "crawl" => {
            if !context.has_crawl {
                return refuse("\"crawl\" calibrates the influence line from the crawl run: give crawl = \"file.toml\"");
            }
            if !context.has_length {
                return refuse("\"crawl\" calibrates the influence line over the whole bridge: give bridge_length_m or the bridge model");
            }
            Ok(Some(StaticReference::CrawlRun))
        }
        toml::Value::String(name) => Err(file.error_at(
            &field,
            format!("\"{name}\" is not a static reference; expected \"model\", \"crawl\" or a table {{ position_m = [...], value_per_kn = [...] }}"),
        )),
        table @ toml::Value::Table(_) => {
            let il: RawInfluenceLine = table.clone().try_into().map_err(|e: toml::de::Error| {
                file.error_at(&field, format!("{}; expected {{ position_m = [...], value_per_kn = [...] }}", e.message()))
            })?;
            let values = il
                .value_per_kn
                .iter()
                .map(|v| v * factor / units::KN)
                .collect();
            let line = SampledInfluenceLine::new(il.position_m, values)
                .map_err(|e| file.error_at(&key("static_reference.position_m"), e.to_string()))?;
            Ok(Some(StaticReference::Given(line)))
        }
        other => Err(file.error_at(
            &field,
            format!("a {} is not a static reference; expected \"model\", \"crawl\" or a table {{ position_m = [...], value_per_kn = [...] }}", other.type_str()),
        )),
    }
}
