//! The `[road]` input file (docs/input-format.md, section `[road]`), and measured profiles as
//! CSV (`x_m,left_m,right_m`).
//!
//! ```toml
//! [road]
//! class = "medium"              # smooth, good, medium, poor, A … H; or psd_at_reference_m3
//! waviness = 2.0
//! band_cycles_per_m = [0.01, 3.0]
//! method = "inverse_fft"        # or "harmonic_superposition" (with harmonic_count)
//! tracks = "coherent"           # identical, independent, coherent
//! track_spacing_m = 1.8
//! seed = 1
//! ```

use std::path::Path;

use serde::Deserialize;
use vbi::road::{
    GenerationMethod, RoadProfile, RoadSpec, Roughness, RoughnessClass, TrackCorrelation,
};

use crate::source::{require_in_range, require_positive, InputError, SourceFile};

#[derive(Debug, Deserialize)]
struct RoadDocument {
    road: RawRoad,
}

/// The `[road]` table as written, before validation; every key optional (defaults from
/// `RoadSpec::default`), except the roughness (`class` or `psd_at_reference_m3`).
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRoad {
    class: Option<String>,
    psd_at_reference_m3: Option<f64>,
    waviness: Option<f64>,
    band_cycles_per_m: Option<Vec<f64>>,
    harmonic_count: Option<i64>,
    method: Option<String>,
    sample_spacing_m: Option<f64>,
    tracks: Option<String>,
    track_spacing_m: Option<f64>,
    coherence_decay: Option<f64>,
    approach_length_m: Option<f64>,
    exit_length_m: Option<f64>,
    tyre_patch_length_m: Option<f64>,
    seed: Option<crate::seed::Seed>,
}

/// The names accepted for `road.class`, for messages.
pub fn class_names() -> String {
    RoughnessClass::ALL
        .iter()
        .map(|c| c.name())
        .collect::<Vec<_>>()
        .join(", ")
}

/// A class by name, or an error at `field` listing the allowed names.
pub fn parse_class(name: &str) -> Result<RoughnessClass, String> {
    RoughnessClass::from_name(name).ok_or_else(|| {
        format!(
            "unknown road class `{name}`; expected one of {}",
            class_names()
        )
    })
}

/// Reads and validates the `[road]` table of a file into a `RoadSpec` (SI units).
pub fn load(file: &SourceFile) -> Result<RoadSpec, InputError> {
    let document: RoadDocument = file.parse()?;
    let raw = document.road;
    let defaults = RoadSpec::default();

    let roughness = match (&raw.class, raw.psd_at_reference_m3) {
        (Some(_), Some(_)) => {
            return Err(file.error_at(
                "road.psd_at_reference_m3",
                "give either `class` or `psd_at_reference_m3`, not both",
            ))
        }
        (Some(name), None) => {
            Roughness::Class(parse_class(name).map_err(|m| file.error_at("road.class", m))?)
        }
        (None, Some(g0)) => Roughness::Custom {
            psd_at_reference: require_in_range(
                file,
                "road.psd_at_reference_m3",
                g0,
                0.0,
                f64::INFINITY,
                "m^3 (G_d(n0) at n0 = 0.1 cycles/m; the paper's medium is 64e-6)",
            )?,
        },
        (None, None) => {
            return Err(file.error_at(
                "road.class",
                format!(
                    "is required: a class ({}) or a custom `psd_at_reference_m3`",
                    class_names()
                ),
            ))
        }
    };
    let waviness = match raw.waviness {
        Some(w) => require_in_range(
            file,
            "road.waviness",
            w,
            0.5,
            5.0,
            "(dimensionless; ISO 8608 uses 2)",
        )?,
        None => defaults.waviness,
    };
    let sample_spacing = match raw.sample_spacing_m {
        Some(v) => require_positive(file, "road.sample_spacing_m", v, "m")?,
        None => defaults.sample_spacing,
    };
    let nyquist = 0.5 / sample_spacing;
    let (band_lower, band_upper) = match &raw.band_cycles_per_m {
        None => (defaults.band_lower, defaults.band_upper),
        Some(band) => {
            let allowed = format!(
                "expected [n1, n2] in cycles/m with 0 < n1 < n2 < {nyquist} (the Nyquist \
                 frequency of sample_spacing_m = {sample_spacing} m)"
            );
            if band.len() != 2 {
                return Err(file.error_at(
                    "road.band_cycles_per_m",
                    format!("has {} numbers; {allowed}", band.len()),
                ));
            }
            let (n1, n2) = (band[0], band[1]);
            if !(n1.is_finite() && n2.is_finite() && n1 > 0.0 && n1 < n2 && n2 < nyquist) {
                return Err(file.error_at(
                    "road.band_cycles_per_m",
                    format!("[{n1}, {n2}] is not allowed; {allowed}"),
                ));
            }
            (n1, n2)
        }
    };
    if raw.band_cycles_per_m.is_none() && band_upper >= nyquist {
        return Err(file.error_at(
            "road.sample_spacing_m",
            format!(
                "{sample_spacing} m puts the Nyquist frequency {nyquist} cycles/m below the default \
                 band's upper end {band_upper}; expected at most {} m, or set band_cycles_per_m",
                0.5 / band_upper
            ),
        ));
    }
    let harmonic_count = match raw.harmonic_count {
        Some(n) => require_in_range(
            file,
            "road.harmonic_count",
            n as f64,
            1.0,
            vbi::road::MAX_HARMONIC_COUNT as f64,
            "harmonics",
        )? as usize,
        None => defaults.harmonic_count,
    };
    let method = match raw.method.as_deref() {
        None => defaults.method,
        Some("inverse_fft") => GenerationMethod::InverseFft,
        Some("harmonic_superposition") => GenerationMethod::HarmonicSuperposition,
        Some(other) => {
            return Err(file.error_at(
                "road.method",
                format!(
                    "unknown method `{other}`; expected `inverse_fft` or `harmonic_superposition`"
                ),
            ))
        }
    };
    let track_correlation = match raw.tracks.as_deref() {
        None | Some("identical") => TrackCorrelation::Identical,
        Some("independent") => TrackCorrelation::Independent,
        Some("coherent") => {
            let track_spacing = match raw.track_spacing_m {
                Some(b) => require_positive(file, "road.track_spacing_m", b, "m")?,
                None => {
                    return Err(file.error_at(
                        "road.track_spacing_m",
                        "is required when tracks = \"coherent\": the lateral distance between the \
                         wheel tracks, a positive number of m (for example 1.8)",
                    ))
                }
            };
            let coherence_decay = match raw.coherence_decay {
                Some(r) => require_in_range(
                    file,
                    "road.coherence_decay",
                    r,
                    0.0,
                    f64::INFINITY,
                    "(dimensionless rho of exp(-rho n b))",
                )?,
                None => 1.0,
            };
            TrackCorrelation::Coherent {
                track_spacing,
                coherence_decay,
            }
        }
        Some(other) => {
            return Err(file.error_at(
                "road.tracks",
                format!(
                    "unknown track relation `{other}`; expected `identical`, `independent` or `coherent`"
                ),
            ))
        }
    };
    if !matches!(track_correlation, TrackCorrelation::Coherent { .. }) {
        for key in ["track_spacing_m", "coherence_decay"] {
            let given = if key == "track_spacing_m" {
                raw.track_spacing_m.is_some()
            } else {
                raw.coherence_decay.is_some()
            };
            if given {
                return Err(file.error_at(
                    &format!("road.{key}"),
                    "applies only with tracks = \"coherent\"",
                ));
            }
        }
    }
    let non_negative = |key: &str, value: Option<f64>, default: f64| -> Result<f64, InputError> {
        match value {
            Some(v) => require_in_range(file, &format!("road.{key}"), v, 0.0, f64::INFINITY, "m"),
            None => Ok(default),
        }
    };
    let spec = RoadSpec {
        roughness,
        waviness,
        band_lower,
        band_upper,
        harmonic_count,
        method,
        sample_spacing,
        track_correlation,
        approach_length: non_negative(
            "approach_length_m",
            raw.approach_length_m,
            defaults.approach_length,
        )?,
        exit_length: non_negative("exit_length_m", raw.exit_length_m, defaults.exit_length)?,
        tyre_patch_length: non_negative(
            "tyre_patch_length_m",
            raw.tyre_patch_length_m,
            defaults.tyre_patch_length,
        )?,
        seed: raw.seed.map_or(defaults.seed, |seed| seed.0),
    };
    // Everything was checked field by field above; a library objection left is a bug to report
    // against the whole table rather than a panic.
    spec.validate()
        .map_err(|e| file.error_at("road", e.to_string()))?;
    Ok(spec)
}

/// Validates a `[road]` file.
pub fn validate(file: &SourceFile) -> Result<(), InputError> {
    load(file).map(|_| ())
}

/// Reads a measured profile from CSV with the header `x_m,left_m,right_m` (distance and the two
/// track elevations in metres); positions must increase; non-uniform positions are resampled
/// linearly at the mean spacing (`RoadProfile::from_measured`).
pub fn read_profile_csv(path: &Path) -> Result<RoadProfile, InputError> {
    let name = path.display().to_string();
    let error = |line: Option<usize>, field: Option<&str>, message: String| InputError {
        file: name.clone(),
        location: line.map(|l| (l, 1)),
        field: field.map(str::to_string),
        message,
    };
    let text = std::fs::read_to_string(path)
        .map_err(|e| error(None, None, format!("cannot read the file: {e}")))?;
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .comment(Some(b'#'))
        .from_reader(text.as_bytes());
    let header = reader
        .headers()
        .map_err(|e| error(Some(1), None, format!("cannot read the CSV header: {e}")))?
        .clone();
    let expected = ["x_m", "left_m", "right_m"];
    if header.len() != 3 || header.iter().zip(expected).any(|(h, e)| h != e) {
        return Err(error(
            Some(1),
            None,
            format!(
                "header `{}` is not allowed; expected `x_m,left_m,right_m`",
                header.iter().collect::<Vec<_>>().join(",")
            ),
        ));
    }
    let (mut x, mut left, mut right) = (Vec::new(), Vec::new(), Vec::new());
    for record in reader.records() {
        let record = record.map_err(|e| {
            let line = e.position().map(|p| p.line() as usize);
            error(line, None, format!("malformed CSV row: {e}"))
        })?;
        let line = record.position().map(|p| p.line() as usize);
        let mut values = [0.0; 3];
        for (i, column) in expected.iter().enumerate() {
            let cell = record.get(i).unwrap_or("");
            values[i] = cell
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    error(
                        line,
                        Some(column),
                        format!("`{cell}` is not allowed; expected a finite number of metres"),
                    )
                })?;
        }
        if let Some(&previous) = x.last() {
            if values[0] <= previous {
                return Err(error(
                    line,
                    Some("x_m"),
                    format!(
                        "{} m is not allowed; positions must increase (previous {previous} m)",
                        values[0]
                    ),
                ));
            }
        }
        x.push(values[0]);
        left.push(values[1]);
        right.push(values[2]);
    }
    RoadProfile::from_measured(&x, &left, &right)
        .map_err(|e| error(None, None, format!("not a usable profile: {e}")))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    fn file(text: &str) -> SourceFile {
        SourceFile::from_text(PathBuf::from("road.toml"), text.to_string())
    }

    #[test]
    fn a_minimal_file_takes_the_defaults() {
        let spec = load(&file("[road]\nclass = \"good\"\n")).unwrap();
        assert_eq!(spec.roughness, Roughness::Class(RoughnessClass::Good));
        assert_eq!(spec.band_upper, RoadSpec::default().band_upper);
    }

    #[test]
    fn unknown_class_names_the_field_line_and_allowed_classes() {
        let e = load(&file("[road]\nclass = \"awful\"\n")).unwrap_err();
        assert_eq!(e.field.as_deref(), Some("road.class"));
        assert_eq!(e.location, Some((2, 1)));
        assert!(
            e.message.contains("smooth, good, medium, poor, A"),
            "{}",
            e.message
        );
    }

    #[test]
    fn reversed_band_names_the_field_and_the_allowed_range() {
        let e = load(&file(
            "[road]\nclass = \"C\"\nband_cycles_per_m = [2.0, 0.5]\n",
        ))
        .unwrap_err();
        assert_eq!(e.field.as_deref(), Some("road.band_cycles_per_m"));
        assert_eq!(e.location, Some((3, 1)));
        assert!(e.message.contains("0 < n1 < n2"), "{}", e.message);
    }

    #[test]
    fn negative_lengths_and_unknown_keys_are_rejected() {
        let e = load(&file("[road]\nclass = \"C\"\napproach_length_m = -5\n")).unwrap_err();
        assert_eq!(e.field.as_deref(), Some("road.approach_length_m"));
        assert!(e.message.contains("at least 0"), "{}", e.message);
        let e = load(&file("[road]\nclass = \"C\"\ncolour = 1\n")).unwrap_err();
        assert!(e.message.contains("colour"), "{}", e.message);
        let e = load(&file("[road]\nclass = \"C\"\ntracks = \"coherent\"\n")).unwrap_err();
        assert_eq!(e.field.as_deref(), Some("road.track_spacing_m"));
    }
}
