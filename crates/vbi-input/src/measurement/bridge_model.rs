//! The bridge model a measurement names (`bridge`, `bridge_modes`) and the cut-off modes of a
//! `vbi run` summary (`[measurement.filter] k1_from_run`).

use std::path::Path;

use vbi::measure::measurement::MeasuredBridge;

use crate::bridge;
use crate::measurement::raw::RawMeasurement;
use crate::source::{InputError, SourceFile};

/// Modes computed for a bridge named in a measurement file when `bridge_modes` is absent.
pub const DEFAULT_BRIDGE_MODES: usize = 20;

/// `bridge` (a `[bridge]` file with an FE model, relative to `folder`) and `bridge_modes` (1 to
/// 500, default [`DEFAULT_BRIDGE_MODES`], raised to the largest cut-off mode a channel or the
/// filter names); `bridge_modes` without `bridge` is refused.
pub(crate) fn measured_bridge(
    file: &SourceFile,
    m: &RawMeasurement,
    folder: &Path,
) -> Result<Option<MeasuredBridge>, InputError> {
    let at = |key: &str| format!("measurement.{key}");
    let bridge = match &m.bridge {
        None => None,
        Some(name) => {
            let path = folder.join(name);
            let source = SourceFile::read(&path).map_err(|e| {
                file.error_at(
                    &at("bridge"),
                    format!(
                        "cannot read the bridge file {}: {}",
                        path.display(),
                        e.message
                    ),
                )
            })?;
            let model = bridge::load(&source)?;
            if let vbi::model::BridgeModel::ImportedModes(_) = model {
                // Model updating scales an FE model's stiffness and mass and solves it again.
                return Err(file.error_at(
                    &at("bridge"),
                    format!(
                        "{} is an imported modal basis, which model updating cannot re-solve; \
                         expected a bridge with an FE model (a continuous beam, a grillage or \
                         imported matrices)",
                        path.display()
                    ),
                ));
            }
            let requested = m.bridge_modes.unwrap_or(DEFAULT_BRIDGE_MODES);
            if !(1..=500).contains(&requested) {
                return Err(file.error_at(
                    &at("bridge_modes"),
                    format!("{requested} is not allowed; expected 1 to 500 modes"),
                ));
            }
            let largest_k1 = m
                .channels
                .iter()
                .filter_map(|c| c.k1_mode)
                .chain(m.filter.k1_mode_deflection)
                .chain(m.filter.k1_mode_moment)
                .max()
                .unwrap_or(0);
            Some(MeasuredBridge {
                label: path.display().to_string(),
                model,
                mode_count: requested.max(largest_k1),
            })
        }
    };
    if m.bridge.is_none() && m.bridge_modes.is_some() {
        return Err(file.error_at(
            &at("bridge_modes"),
            "bridge_modes needs a bridge model: give bridge = \"file.toml\"",
        ));
    }
    Ok(bridge)
}

/// `[measurement.filter] k1_from_run`: the cut-off modes of a `vbi run` summary.json, relative
/// to `folder`.
pub(crate) fn run_k1(
    file: &SourceFile,
    m: &RawMeasurement,
    folder: &Path,
) -> Result<Option<RunK1>, InputError> {
    Ok(match &m.filter.k1_from_run {
        None => None,
        Some(name) => Some(read_run_k1(file, &folder.join(name))?),
    })
}

/// K1 of deflection and of moment, with their frequencies [Hz], from a run summary.
pub(crate) struct RunK1 {
    /// K1 of deflection and its frequency [Hz].
    pub(crate) deflection: Option<(usize, f64)>,
    /// K1 of moment and its frequency [Hz].
    pub(crate) moment: Option<(usize, f64)>,
}

/// Reads `deck_participation.{deflection,moment}_k1` and `frequencies_hz` of a `vbi run`
/// summary.json.
pub(crate) fn read_run_k1(file: &SourceFile, path: &Path) -> Result<RunK1, InputError> {
    let key = "measurement.filter.k1_from_run";
    let text = crate::source::read_bounded(path, crate::source::MAX_DATA_FILE_BYTES)
        .map_err(|e| e.at_naming_key(file, key))?;
    let json: serde_json::Value = serde_json::from_str(&text)
        .map_err(|e| file.error_at(key, format!("{} is not JSON: {e}", path.display())))?;
    let frequencies: Option<Vec<f64>> = json["frequencies_hz"]
        .as_array()
        .map(|a| a.iter().filter_map(|v| v.as_f64()).collect());
    let Some(frequencies) = frequencies else {
        return Err(file.error_at(
            key,
            format!(
                "{} has no `frequencies_hz`; expected the summary.json of `vbi run`",
                path.display()
            ),
        ));
    };
    let k1 = |name: &str| -> Result<Option<(usize, f64)>, InputError> {
        match json["deck_participation"][name].as_u64() {
            None => Ok(None),
            Some(k) => {
                let k = k as usize;
                match k.checked_sub(1).and_then(|i| frequencies.get(i)) {
                    Some(f) => Ok(Some((k, *f))),
                    None => Err(file.error_at(
                        key,
                        format!(
                            "{} gives {name} = {k} but lists {} frequencies",
                            path.display(),
                            frequencies.len()
                        ),
                    )),
                }
            }
        }
    };
    Ok(RunK1 {
        deflection: k1("deflection_k1")?,
        moment: k1("moment_k1")?,
    })
}
