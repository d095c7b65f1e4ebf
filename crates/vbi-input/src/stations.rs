//! Stations where the engineer wants them: `[[station]]` tables beside `[scenario]`
//! (docs/input-format.md, "Stations").
//!
//! ```toml
//! [[station]]
//! name = "joint_side"     # optional; default x<position>_g<girder> or x<position>_section
//! span = 2                # span number from 1 ...
//! fraction = 0.25         # ... and the fraction of its length; or position_m = 37.5
//! girder = 3              # girder number from 1 (the rightmost); or "section" (default)
//! ```
//!
//! Each station is a node of the mesh and records deflection and bending moment, like the
//! automatic mid-span and support stations, which stay.

use vbi::crossing::Scenario;
use vbi::fe::StationRequest;
use vbi::modal::StationTarget;
use vbi::model::BridgeModel;

use crate::source::{require_in_range, InputError, SourceFile};

/// Every key of a `[[station]]` table.
const STATION_KEYS: [&str; 5] = ["name", "position_m", "span", "fraction", "girder"];

/// Reads `[[station]]` (if any) into the scenario's mesh options.
pub fn load(
    file: &SourceFile,
    table: &toml::Table,
    scenario: &mut Scenario,
) -> Result<(), InputError> {
    let Some(value) = table.get("station") else {
        return Ok(());
    };
    let toml::Value::Array(entries) = value else {
        return Err(file.error_at("station", "expected [[station]] tables, one per station"));
    };
    if matches!(scenario.bridge.model, BridgeModel::ImportedModes(_)) && !entries.is_empty() {
        return Err(file.error_at(
            "station[0]",
            "an imported modal basis has only the stations of its station_moments_csv (their \
             modal moments come from the other program); expected no [[station]], or the \
             model's matrices (type = \"imported_matrices\") to place stations anywhere",
        ));
    }
    for (i, entry) in entries.iter().enumerate() {
        let at = format!("station[{i}]");
        let toml::Value::Table(entry) = entry else {
            return Err(file.error_at(&at, "expected a [[station]] table"));
        };
        let request = station(file, &at, entry, &scenario.bridge.model)?;
        let name = request.name_or_default();
        if is_automatic_name(&name) {
            return Err(file.error_at(
                &format!("{at}.name"),
                format!(
                    "`{name}` is the form of the automatic stations' names (spanN_mid_… and \
                     supportN_…, histories.csv's columns); expected another name"
                ),
            ));
        }
        if let Some(first) = scenario
            .bridge
            .mesh
            .stations
            .iter()
            .position(|other| other.name_or_default() == name)
        {
            let key = if entry.contains_key("name") {
                format!("{at}.name")
            } else {
                at.clone()
            };
            return Err(file.error_at(
                &key,
                format!(
                    "station `{name}` is already defined by station[{first}]; expected a name of \
                     its own (each names its columns in histories.csv)"
                ),
            ));
        }
        scenario.bridge.mesh.stations.push(request);
    }
    Ok(())
}

/// Whether `name` has the form of an automatic station's name: `span<N>_mid_<target>` or
/// `support<N>_<target>`, target `g<N>` or `section`.
fn is_automatic_name(name: &str) -> bool {
    /// The text after a leading whole number, if there is one.
    fn number_then(rest: &str) -> Option<&str> {
        let after = rest.trim_start_matches(|c: char| c.is_ascii_digit());
        (after.len() < rest.len()).then_some(after)
    }
    let target = |rest: &str| {
        rest == "section"
            || rest
                .strip_prefix('g')
                .and_then(number_then)
                .is_some_and(|after| after.is_empty())
    };
    if let Some(rest) = name.strip_prefix("span").and_then(number_then) {
        return rest.strip_prefix("_mid_").is_some_and(&target);
    }
    name.strip_prefix("support")
        .and_then(number_then)
        .and_then(|rest| rest.strip_prefix('_'))
        .is_some_and(target)
}

fn station(
    file: &SourceFile,
    at: &str,
    entry: &toml::Table,
    model: &BridgeModel,
) -> Result<StationRequest, InputError> {
    if let Some(unknown) = entry.keys().find(|k| !STATION_KEYS.contains(&k.as_str())) {
        return Err(file.error_at(
            &format!("{at}.{unknown}"),
            format!(
                "unknown key `{unknown}` in [[station]]; expected one of {}",
                STATION_KEYS.join(", ")
            ),
        ));
    }
    let number = |key: &str| -> Result<Option<f64>, InputError> {
        match entry.get(key) {
            None => Ok(None),
            Some(toml::Value::Integer(i)) => Ok(Some(*i as f64)),
            Some(toml::Value::Float(x)) => Ok(Some(*x)),
            Some(other) => {
                Err(file.error_at(&format!("{at}.{key}"), format!("{other} is not a number")))
            }
        }
    };
    let length = model.length();
    let position =
        match (number("position_m")?, number("span")?, number("fraction")?) {
            (Some(x), None, None) => {
                require_in_range(file, &format!("{at}.position_m"), x, 0.0, length, "m")?
            }
            (None, Some(span), Some(fraction)) => {
                let spans = model.span_lengths();
                let path = format!("{at}.span");
                if span.fract() != 0.0 || span < 1.0 || span > spans.len() as f64 {
                    return Err(file.error_at(
                        &path,
                        format!("expected a span number from 1 to {}", spans.len()),
                    ));
                }
                let fraction =
                    require_in_range(file, &format!("{at}.fraction"), fraction, 0.0, 1.0, "")?;
                let k = span as usize - 1;
                let start: f64 = spans[..k].iter().sum();
                start + fraction * spans[k]
            }
            _ => return Err(file.error_at(
                at,
                "give a station's place as `position_m` (from the first support), or as `span` \
                 (from 1) and `fraction` (0 to 1) of its length",
            )),
        };
    let target = match entry.get("girder") {
        None => StationTarget::Section,
        Some(toml::Value::String(s)) if s == "section" => StationTarget::Section,
        Some(toml::Value::Integer(g)) => {
            let girders = match model {
                BridgeModel::Grillage(g) => g.girder_count,
                BridgeModel::ContinuousBeam(_) => 1,
                BridgeModel::ImportedMatrices(m) => m.deck_lines.len(),
                BridgeModel::ImportedModes(m) => m.data.lines.len(),
            };
            if *g < 1 || *g as usize > girders {
                return Err(file.error_at(
                    &format!("{at}.girder"),
                    format!(
                        "girder {g} is not allowed; expected a girder number from 1 (the \
                         rightmost) to {girders}, or \"section\""
                    ),
                ));
            }
            StationTarget::Girder(*g as usize - 1)
        }
        Some(other) => {
            return Err(file.error_at(
                &format!("{at}.girder"),
                format!("{other} is not allowed; expected a girder number from 1, or \"section\""),
            ))
        }
    };
    if let (BridgeModel::Grillage(g), StationTarget::Section) = (model, target) {
        if g.is_skewed() {
            return Err(file.error_at(
                &format!("{at}.girder"),
                format!(
                    "a skewed grillage has no section through every girder at one place (its \
                     girders' supports are offset); expected a girder number from 1 to {}",
                    g.girder_count
                ),
            ));
        }
    }
    let name = match entry.get("name") {
        None => None,
        Some(toml::Value::String(name)) if !name.trim().is_empty() => Some(name.clone()),
        Some(_) => return Err(file.error_at(&format!("{at}.name"), "expected a non-empty text")),
    };
    Ok(StationRequest {
        name,
        position,
        target,
    })
}
