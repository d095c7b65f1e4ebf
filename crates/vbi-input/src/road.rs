//! The `[road]` input file (docs/input-format.md, section `[road]`), and measured profiles as
//! CSV (`x_m,left_m,right_m`).
//!
//! ```toml
//! [road]
//! class = "medium"              # smooth, good, medium, poor, A … H, dr-very-good … dr-very-poor;
//!                               # or psd_at_reference_m3
//! psd_reference = "iso-8608"    # where G_d(n0) is read: iso-8608 (0.1 cycles/m) or
//!                               # dodds-robson (1/2pi cycles/m); default: the class's own
//! waviness = 2.0
//! band_cycles_per_m = [0.01, 3.0]
//! method = "inverse_fft"        # or "harmonic_superposition" (with harmonic_count)
//! tracks = "coherent"           # identical, independent, coherent (default: coherent at the
//! track_spacing_m = 1.8         # vehicle's own track spacing, rho = 1)
//! seed = 1
//!
//! [[road.event]]                # deterministic events on top (deck coordinates, m)
//! kind = "step"                 # step, ramp, bump, sine
//! position_m = 0.0
//! height_m = 0.02
//! length_m = 0.1
//! ```
//!
//! `profile_csv = "file.csv"` (relative to the TOML file) replaces the random roughness by a
//! user or measured profile (`x_m,left_m,right_m`); events still superpose on it.

use std::path::Path;

use serde::Deserialize;
use vbi::road::{
    BumpShape, EventShape, EventTracks, GenerationMethod, PsdReference, RoadError, RoadEvent,
    RoadProfile, RoadSpec, Roughness, RoughnessClass, TrackCorrelation, UserProfile,
};

use crate::source::{require_in_range, require_positive, shown, InputError, SourceFile};

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
    psd_reference: Option<String>,
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
    event: Option<Vec<toml::Table>>,
    profile_csv: Option<String>,
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
    load_with_sources(file).map(|(spec, _)| spec)
}

/// [`load`], with the (name, text) of every other file read (the `profile_csv`), for an
/// input hash.
pub fn load_with_sources(
    file: &SourceFile,
) -> Result<(RoadSpec, Vec<(String, String)>), InputError> {
    let document: RoadDocument = file.parse()?;
    let raw = document.road;
    let defaults = RoadSpec::default();

    let roughness = if raw.profile_csv.is_some() {
        refuse_random_keys(file, &raw)?;
        // Unused: the user profile replaces the random roughness.
        Roughness::Class(RoughnessClass::Smooth)
    } else {
        random_roughness(file, &raw)?
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
    let (band_lower, band_upper) = band(file, &raw, sample_spacing)?;
    let (harmonic_count, method) = generation(file, &raw)?;
    let track_correlation = track_correlation(file, &raw)?;
    let non_negative = |key: &str, value: Option<f64>, default: f64| -> Result<f64, InputError> {
        match value {
            // At most 10 km: the profile of a crossing runs over the approach, the bridge and
            // the exit, at most MAX_SAMPLE_COUNT samples (issue 47: 1e308 passed `vbi check`).
            Some(v) => require_in_range(file, &format!("road.{key}"), v, 0.0, 10_000.0, "m"),
            None => Ok(default),
        }
    };
    let psd_reference = match raw.psd_reference.as_deref() {
        None => None,
        Some(name) => Some(PsdReference::from_name(name).ok_or_else(|| {
            file.error_at(
                "road.psd_reference",
                format!(
                    "unknown reference `{name}`; expected `iso-8608` (G_d(n0) at n0 = 0.1 \
                     cycles/m) or `dodds-robson` (at n0 = 1/(2 pi) cycles/m)"
                ),
            )
        })?),
    };
    let mut spec = RoadSpec {
        roughness,
        psd_reference,
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
        tyre_patch_length: match raw.tyre_patch_length_m {
            Some(v) => require_in_range(
                file,
                "road.tyre_patch_length_m",
                v,
                0.0,
                vbi::road::MAX_TYRE_PATCH_LENGTH,
                "m (a truck tyre's contact patch is 0.15-0.3 m long)",
            )?,
            None => defaults.tyre_patch_length,
        },
        seed: raw.seed.map_or(defaults.seed, |seed| seed.0),
        events: read_events(file, raw.event.as_deref().unwrap_or(&[]), sample_spacing)?,
        profile: None,
    };
    let mut sources = Vec::new();
    if let Some(name) = &raw.profile_csv {
        let (profile, text) = read_user_profile(file, name)?;
        spec.profile = Some(profile);
        sources.push((name.clone(), text));
    }
    // Everything was checked field by field above; a library objection left is a bug to report
    // against the whole table rather than a panic.
    spec.validate()
        .map_err(|e| file.error_at("road", e.to_string()))?;
    Ok((spec, sources))
}

/// `band_cycles_per_m` [cycles/m]: two numbers 0 < n1 < n2 below the Nyquist frequency of
/// `sample_spacing` [m]; the default band, whose upper end must lie below it too (unless a user
/// profile replaces the random roughness).
fn band(file: &SourceFile, raw: &RawRoad, sample_spacing: f64) -> Result<(f64, f64), InputError> {
    let defaults = RoadSpec::default();
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
                    format!("[{}, {}] is not allowed; {allowed}", shown(n1), shown(n2)),
                ));
            }
            // The lowest wavenumber's wavelength in samples: the inverse FFT's length must hold
            // it (issue 47: n1 = 1e-308 passed here and failed in `vbi road`). Half the limit,
            // as the generator's spacing may be finer than sample_spacing_m (the largest that
            // divides the profile into whole intervals).
            let lowest = 2.0 / (vbi::road::MAX_SAMPLE_COUNT as f64 * sample_spacing);
            if n1 < lowest {
                return Err(file.error_at(
                    "road.band_cycles_per_m",
                    format!(
                        "n1 = {} cycles/m is a wavelength of {} m, more than {} samples of \
                         sample_spacing_m = {sample_spacing} m; expected a wavelength 1/n1 of at \
                         most {} m",
                        shown(n1),
                        shown(1.0 / n1),
                        vbi::road::MAX_SAMPLE_COUNT / 2,
                        shown(1.0 / lowest)
                    ),
                ));
            }
            (n1, n2)
        }
    };
    if raw.band_cycles_per_m.is_none() && band_upper >= nyquist && raw.profile_csv.is_none() {
        return Err(file.error_at(
            "road.sample_spacing_m",
            format!(
                "{sample_spacing} m puts the Nyquist frequency {nyquist} cycles/m below the default \
                 band's upper end {band_upper}; expected at most {} m, or set band_cycles_per_m",
                0.5 / band_upper
            ),
        ));
    }
    Ok((band_lower, band_upper))
}

/// `harmonic_count` (1 to [`vbi::road::MAX_HARMONIC_COUNT`]) and `method` (`inverse_fft` or
/// `harmonic_superposition`).
fn generation(file: &SourceFile, raw: &RawRoad) -> Result<(usize, GenerationMethod), InputError> {
    let defaults = RoadSpec::default();
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
    Ok((harmonic_count, method))
}

/// `tracks` (`identical`, `independent` or `coherent`, the default) with, for coherent tracks
/// only, `track_spacing_m` [m] (default: the vehicle's) and `coherence_decay` (ρ ≥ 0).
fn track_correlation(file: &SourceFile, raw: &RawRoad) -> Result<TrackCorrelation, InputError> {
    let track_correlation = match raw.tracks.as_deref() {
        Some("identical") => TrackCorrelation::Identical,
        Some("independent") => TrackCorrelation::Independent,
        None | Some("coherent") => {
            let coherence_decay = match raw.coherence_decay {
                Some(r) => require_in_range(
                    file,
                    "road.coherence_decay",
                    r,
                    0.0,
                    f64::INFINITY,
                    "(dimensionless rho of exp(-rho n b))",
                )?,
                None => vbi::road::DEFAULT_COHERENCE_DECAY,
            };
            match raw.track_spacing_m {
                Some(b) => TrackCorrelation::Coherent {
                    track_spacing: require_positive(file, "road.track_spacing_m", b, "m")?,
                    coherence_decay,
                },
                // The spacing of the crossing vehicle's wheel tracks, filled in by the pipeline.
                None => TrackCorrelation::VehicleTrack { coherence_decay },
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
    if matches!(
        track_correlation,
        TrackCorrelation::Identical | TrackCorrelation::Independent
    ) {
        for key in ["track_spacing_m", "coherence_decay"] {
            let given = if key == "track_spacing_m" {
                raw.track_spacing_m.is_some()
            } else {
                raw.coherence_decay.is_some()
            };
            if given {
                return Err(file.error_at(
                    &format!("road.{key}"),
                    "applies only to coherent tracks (tracks = \"coherent\", or no `tracks`)",
                ));
            }
        }
    }
    Ok(track_correlation)
}

/// An event kind's number keys, each with its default (None: required).
type EventKeys = &'static [(&'static str, Option<f64>)];

/// The number keys of each event kind (besides `kind`, `track` and a bump's `shape`).
const EVENT_KEYS: [(&str, EventKeys); 4] = [
    (
        "step",
        &[("position_m", None), ("height_m", None), ("length_m", None)],
    ),
    (
        "ramp",
        &[("start_m", None), ("end_m", None), ("height_m", None)],
    ),
    (
        "bump",
        &[("centre_m", None), ("length_m", None), ("height_m", None)],
    ),
    (
        "sine",
        &[
            ("start_m", None),
            ("end_m", None),
            ("wavelength_m", None),
            ("amplitude_m", None),
            ("phase_rad", Some(0.0)),
        ],
    ),
];

/// The `[[road.event]]` tables as events, each checked against the sample spacing [m].
fn read_events(
    file: &SourceFile,
    tables: &[toml::Table],
    sample_spacing: f64,
) -> Result<Vec<RoadEvent>, InputError> {
    tables
        .iter()
        .enumerate()
        .map(|(index, table)| read_event(file, &format!("road.event[{index}]"), table))
        .map(|event| {
            event.and_then(|(at, event)| {
                event
                    .shape
                    .validate(0, sample_spacing)
                    .map_err(|e| event_error(file, &at, &event.shape, e))?;
                Ok(event)
            })
        })
        .collect()
}

/// A text key of an event table: its value among `allowed`, or `default` when absent.
fn event_choice<'a>(
    file: &SourceFile,
    at: &str,
    table: &'a toml::Table,
    key: &str,
    allowed: &[&'a str],
    default: Option<&'a str>,
) -> Result<&'a str, InputError> {
    let expected = allowed
        .iter()
        .map(|a| format!("`{a}`"))
        .collect::<Vec<_>>()
        .join(", ");
    match table.get(key) {
        None => default.ok_or_else(|| {
            file.error_at(
                &format!("{at}.{key}"),
                format!("is required; expected one of {expected}"),
            )
        }),
        Some(toml::Value::String(text)) if allowed.contains(&text.as_str()) => Ok(text),
        Some(other) => Err(file.error_at(
            &format!("{at}.{key}"),
            format!("{other} is not allowed; expected one of {expected}"),
        )),
    }
}

/// One `[[road.event]]` table at `at` (`road.event[i]`), and where it stands.
fn read_event(
    file: &SourceFile,
    at: &str,
    table: &toml::Table,
) -> Result<(String, RoadEvent), InputError> {
    let kinds: Vec<&str> = EVENT_KEYS.iter().map(|(kind, _)| *kind).collect();
    let kind = event_choice(file, at, table, "kind", &kinds, None)?;
    let keys = EVENT_KEYS
        .iter()
        .find(|(name, _)| *name == kind)
        .map_or(&[][..], |(_, keys)| *keys);
    let shape_key = kind == "bump";
    let known = |key: &str| {
        ["kind", "track"].contains(&key)
            || (shape_key && key == "shape")
            || keys.iter().any(|(name, _)| *name == key)
    };
    if let Some(unknown) = table.keys().find(|key| !known(key)) {
        let mut allowed: Vec<&str> = vec!["kind", "track"];
        allowed.extend(keys.iter().map(|(name, _)| *name));
        if shape_key {
            allowed.push("shape");
        }
        return Err(file.error_at(
            &format!("{at}.{unknown}"),
            format!(
                "unknown key `{unknown}` for kind = \"{kind}\"; expected {}",
                allowed.join(", ")
            ),
        ));
    }
    let tracks = match event_choice(
        file,
        at,
        table,
        "track",
        &["both", "left", "right"],
        Some("both"),
    )? {
        "left" => EventTracks::Left,
        "right" => EventTracks::Right,
        _ => EventTracks::Both,
    };
    let mut values = Vec::with_capacity(keys.len());
    for &(key, default) in keys {
        values.push(event_number(
            file,
            &format!("{at}.{key}"),
            table.get(key),
            default,
            kind,
        )?);
    }
    let shape = match (kind, values.as_slice()) {
        ("step", &[position, height, length]) => EventShape::Step {
            position,
            height,
            length,
        },
        ("ramp", &[start, end, height]) => EventShape::Ramp { start, end, height },
        ("bump", &[centre, length, height]) => EventShape::Bump {
            centre,
            length,
            height,
            shape: match event_choice(
                file,
                at,
                table,
                "shape",
                &["cosine", "half_sine"],
                Some("cosine"),
            )? {
                "half_sine" => BumpShape::HalfSine,
                _ => BumpShape::Cosine,
            },
        },
        (_, &[start, end, wavelength, amplitude, phase]) => EventShape::Sine {
            start,
            end,
            wavelength,
            amplitude,
            phase,
        },
        _ => unreachable!("EVENT_KEYS gives each kind its keys"),
    };
    Ok((at.to_string(), RoadEvent { tracks, shape }))
}

/// A number of an event: finite (an integer is taken as it is), or `default` when absent.
fn event_number(
    file: &SourceFile,
    at: &str,
    value: Option<&toml::Value>,
    default: Option<f64>,
    kind: &str,
) -> Result<f64, InputError> {
    let unit = if at.ends_with("_rad") { "rad" } else { "m" };
    match value {
        Some(toml::Value::Float(x)) if x.is_finite() => Ok(*x),
        Some(toml::Value::Integer(i)) => Ok(*i as f64),
        Some(other) => Err(file.error_at(
            at,
            format!("{other} is not allowed; expected a finite number of {unit}"),
        )),
        None => default.ok_or_else(|| {
            file.error_at(
                at,
                format!("is required for kind = \"{kind}\": a number of {unit}"),
            )
        }),
    }
}

/// The library's objection to an event, located at the key it concerns.
fn event_error(file: &SourceFile, at: &str, shape: &EventShape, error: RoadError) -> InputError {
    let RoadError::InvalidEvent {
        quantity,
        value,
        allowed,
        ..
    } = &error
    else {
        return file.error_at(at, error.to_string());
    };
    let key = match (shape, *quantity) {
        (EventShape::Ramp { .. }, _) | (EventShape::Sine { .. }, "end") => "end_m",
        (_, "wavelength") => "wavelength_m",
        _ => "length_m",
    };
    let shown = match shape {
        EventShape::Ramp { end, .. } => {
            format!("{} m ({quantity} = {} m)", shown(*end), shown(*value))
        }
        _ => format!("{} m", shown(*value)),
    };
    file.error_at(
        &format!("{at}.{key}"),
        format!("{shown} is not allowed; expected {allowed}"),
    )
}

/// The user profile named by `profile_csv` (relative to `file`), and the CSV's text.
fn read_user_profile(file: &SourceFile, name: &str) -> Result<(UserProfile, String), InputError> {
    let path = crate::source::relative(file, name);
    let text = crate::source::read_bounded(&path, crate::source::MAX_DATA_FILE_BYTES)
        .map_err(|e| e.at_naming_key(file, "road.profile_csv"))?;
    let (positions, left, right) = profile_columns(&path.display().to_string(), &text)?;
    Ok((
        UserProfile {
            positions,
            left,
            right,
        },
        text,
    ))
}

/// The random roughness: a `class` or a custom `psd_at_reference_m3`, one of the two.
fn random_roughness(file: &SourceFile, raw: &RawRoad) -> Result<Roughness, InputError> {
    Ok(match (&raw.class, raw.psd_at_reference_m3) {
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
                "m^3 (G_d(n0), at n0 = 0.1 cycles/m unless psd_reference says otherwise; the \
                 paper's medium is 64e-6)",
            )?,
        },
        (None, None) => {
            return Err(file.error_at(
                "road.class",
                format!(
                    "is required: a class ({}), a custom `psd_at_reference_m3` or a user \
                     profile `profile_csv`",
                    class_names()
                ),
            ))
        }
    })
}

/// Refuses, beside `profile_csv`, the keys of the random roughness that it replaces.
fn refuse_random_keys(file: &SourceFile, raw: &RawRoad) -> Result<(), InputError> {
    let given = [
        ("class", raw.class.is_some()),
        ("psd_at_reference_m3", raw.psd_at_reference_m3.is_some()),
        ("psd_reference", raw.psd_reference.is_some()),
        ("waviness", raw.waviness.is_some()),
        ("band_cycles_per_m", raw.band_cycles_per_m.is_some()),
        ("harmonic_count", raw.harmonic_count.is_some()),
        ("method", raw.method.is_some()),
        ("tracks", raw.tracks.is_some()),
        ("track_spacing_m", raw.track_spacing_m.is_some()),
        ("coherence_decay", raw.coherence_decay.is_some()),
        ("seed", raw.seed.is_some()),
    ];
    match given.iter().find(|(_, given)| *given) {
        Some((key, _)) => Err(file.error_at(
            &format!("road.{key}"),
            "applies only to the random roughness, which `profile_csv` replaces; remove one of \
             the two",
        )),
        None => Ok(()),
    }
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
    let text = crate::source::read_bounded(path, crate::source::MAX_DATA_FILE_BYTES)?;
    let (x, left, right) = profile_columns(&name, &text)?;
    RoadProfile::from_measured(&x, &left, &right).map_err(|e| InputError {
        file: name,
        location: None,
        field: None,
        message: format!("not a usable profile: {e}"),
    })
}

/// The largest elevation a road profile may give [m]: ±10 m holds any roughness, ramp or joint
/// step, and a measured profile's grade over a bridge's length; a larger value is a unit error
/// or a corrupt cell, whose square would overflow the profile's statistics.
const LARGEST_PROFILE_ELEVATION: f64 = 10.0;

/// The columns (x, left, right) [m] of a profile CSV's text (header `x_m,left_m,right_m`,
/// finite numbers, x increasing strictly, at least 2 rows); errors name the file `name`, the
/// line and the column.
#[allow(clippy::type_complexity)]
fn profile_columns(name: &str, text: &str) -> Result<(Vec<f64>, Vec<f64>, Vec<f64>), InputError> {
    let error = |line: Option<usize>, field: Option<&str>, message: String| InputError {
        file: name.to_string(),
        location: line.map(|l| (l, 1)),
        field: field.map(str::to_string),
        message,
    };
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
        for (i, column) in expected.iter().enumerate().skip(1) {
            if values[i].abs() > LARGEST_PROFILE_ELEVATION {
                return Err(error(
                    line,
                    Some(column),
                    format!(
                        "{} m is not allowed; expected an elevation within ±{LARGEST_PROFILE_ELEVATION} m \
                         (millimetres given as metres?)",
                        crate::source::shown(values[i])
                    ),
                ));
            }
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
    if x.len() < 2 {
        return Err(error(
            None,
            None,
            format!(
                "not a usable profile: {}",
                RoadError::TooFewSamples { count: x.len() }
            ),
        ));
    }
    Ok((x, left, right))
}

/// The `[road]` key that governs a failure to generate the road: the harmonic count for a direct
/// superposition too long to sum, the sample spacing for too many samples, else the table.
pub fn generation_key(error: &vbi::road::RoadError) -> &'static str {
    use vbi::road::RoadError;
    match error {
        RoadError::TooManyDirectTerms { .. } | RoadError::InvalidHarmonicCount { .. } => {
            "road.harmonic_count"
        }
        RoadError::TooManySamples { .. } => "road.sample_spacing_m",
        _ => "road",
    }
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
        assert!(
            e.message.contains("expected from 0 to 10000 m"),
            "{}",
            e.message
        );
        let e = load(&file(
            "[road]\nclass = \"C\"\ntyre_patch_length_m = 1e308\n",
        ))
        .unwrap_err();
        assert_eq!(e.field.as_deref(), Some("road.tyre_patch_length_m"));
        assert_eq!(e.location, Some((3, 1)));
        let e = load(&file("[road]\nclass = \"C\"\ncolour = 1\n")).unwrap_err();
        assert!(e.message.contains("colour"), "{}", e.message);
        let e = load(&file(
            "[road]\nclass = \"C\"\ntracks = \"identical\"\ntrack_spacing_m = 1.8\n",
        ))
        .unwrap_err();
        assert_eq!(e.field.as_deref(), Some("road.track_spacing_m"));
        let e = load(&file("[road]\nclass = \"C\"\npsd_reference = \"1/2pi\"\n")).unwrap_err();
        assert_eq!(e.field.as_deref(), Some("road.psd_reference"));
        assert!(e.message.contains("dodds-robson"), "{}", e.message);
    }

    /// Coherent tracks are the default, at the vehicle's track spacing (the pipeline fills it
    /// in); `tracks = "coherent"` without a spacing is the same; `identical` is still honoured;
    /// a Dodds & Robson class is read at n0 = 1/(2 pi), 2.533 times rougher at 0.1 cycles/m.
    #[test]
    fn tracks_default_to_the_vehicle_track_and_classes_carry_their_reference() {
        let spec = load(&file("[road]\nclass = \"medium\"\n")).unwrap();
        let vehicle = TrackCorrelation::VehicleTrack {
            coherence_decay: 1.0,
        };
        assert_eq!(spec.track_correlation, vehicle);
        let coherent = load(&file("[road]\nclass = \"medium\"\ntracks = \"coherent\"\n")).unwrap();
        assert_eq!(coherent.track_correlation, vehicle);
        let identical = load(&file(
            "[road]\nclass = \"medium\"\ntracks = \"identical\"\n",
        ))
        .unwrap();
        assert_eq!(identical.track_correlation, TrackCorrelation::Identical);
        assert_eq!(spec.psd_at_iso_reference(), 64e-6);
        let dodds = load(&file(
            "[road]\nclass = \"medium\"\npsd_reference = \"dodds-robson\"\n",
        ))
        .unwrap();
        let factor = (1.0 / (2.0 * std::f64::consts::PI * 0.1)).powi(2);
        assert!((dodds.psd_at_iso_reference() / (64e-6 * factor) - 1.0).abs() < 1e-14);
        assert!((factor - 2.533).abs() < 1e-3);
        let average = load(&file("[road]\nclass = \"dr-average\"\n")).unwrap();
        assert_eq!(average.psd_at_iso_reference(), dodds.psd_at_iso_reference());
    }

    #[test]
    fn events_are_read_in_si_with_their_defaults() {
        let spec = load(&file(
            "[road]\nclass = \"smooth\"\n\
             [[road.event]]\nkind = \"step\"\nposition_m = 0\nheight_m = 0.02\nlength_m = 0.1\n\
             [[road.event]]\nkind = \"bump\"\ncentre_m = 12.5\nlength_m = 0.5\nheight_m = -0.03\n\
             track = \"left\"\n\
             [[road.event]]\nkind = \"sine\"\nstart_m = 0\nend_m = 30\nwavelength_m = 5\n\
             amplitude_m = 0.005\n",
        ))
        .unwrap();
        assert_eq!(spec.events.len(), 3);
        assert_eq!(
            spec.events[1],
            RoadEvent {
                tracks: EventTracks::Left,
                shape: EventShape::Bump {
                    centre: 12.5,
                    length: 0.5,
                    height: -0.03,
                    shape: BumpShape::Cosine,
                },
            }
        );
        assert!(matches!(
            spec.events[2].shape,
            EventShape::Sine { phase, .. } if phase == 0.0
        ));
        assert_eq!(spec.events[0].tracks, EventTracks::Both);
    }

    #[test]
    fn bad_events_name_the_key_its_line_and_what_is_allowed() {
        let cases = [
            ("kind = \"pothole\"\n", "road.event[0].kind", 4, "`step`, `ramp`, `bump`, `sine`"),
            (
                "kind = \"bump\"\ncentre_m = 1\nlength_m = -0.5\nheight_m = 0.01\n",
                "road.event[0].length_m",
                6,
                "at least 4 sample spacings",
            ),
            (
                "kind = \"step\"\nposition_m = 0\nheight_m = 0.02\n",
                "road.event[0].length_m",
                3, // a missing key: the line of its [[road.event]] table
                "is required for kind = \"step\"",
            ),
            (
                "kind = \"step\"\nposition_m = 0\nheight_m = 0.02\nlength_m = 0.1\ncentre_m = 1\n",
                "road.event[0].centre_m",
                8,
                "expected kind, track, position_m, height_m, length_m",
            ),
            (
                "kind = \"ramp\"\nstart_m = 0\nend_m = -10\nheight_m = -0.02\n",
                "road.event[0].end_m",
                6,
                "at least 2 sample spacings",
            ),
            (
                "kind = \"sine\"\nstart_m = 0\nend_m = 10\nwavelength_m = 0.1\namplitude_m = 0.01\n",
                "road.event[0].wavelength_m",
                7,
                "finer sample spacing",
            ),
            (
                "kind = \"step\"\nposition_m = 0\nheight_m = nan\nlength_m = 0.1\ntrack = \"both\"\n",
                "road.event[0].height_m",
                6,
                "finite number of m",
            ),
        ];
        for (event, field, line, allowed) in cases {
            let text = format!("[road]\nclass = \"C\"\n[[road.event]]\n{event}");
            let e = load(&file(&text)).unwrap_err();
            assert_eq!(e.field.as_deref(), Some(field), "{text}: {e}");
            assert_eq!(e.location.map(|l| l.0), Some(line), "{text}: {e}");
            assert!(e.message.contains(allowed), "{text}: {e}");
        }
    }

    #[test]
    fn profile_csv_replaces_the_roughness_keys_and_must_be_readable() {
        let e = load(&file(
            "[road]\nclass = \"C\"\nprofile_csv = \"absent.csv\"\n",
        ))
        .unwrap_err();
        assert_eq!(e.field.as_deref(), Some("road.class"));
        assert!(e.message.contains("profile_csv"), "{e}");
        let e = load(&file("[road]\nprofile_csv = \"absent.csv\"\n")).unwrap_err();
        assert_eq!(e.field.as_deref(), Some("road.profile_csv"));
        assert_eq!(e.location, Some((2, 1)));
        assert!(e.message.contains("cannot read"), "{e}");
    }
}
