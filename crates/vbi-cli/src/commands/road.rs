//! `vbi road [FILE | --class NAME | --measured CSV] [--length L] [--seed S] [--sample I]
//! [--out DIR]`: generate (or import) a road profile, write it as `profile.csv`, plot it, and
//! plot its PSD against the ISO 8608 target on log–log axes.

use crate::console::outln;
use std::path::{Path, PathBuf};

use anyhow::Result;
use vbi::road::{
    generate_sample, welch_psd, RoadProfile, RoadSpec, Roughness, RoughnessClass, Track,
    TrackCorrelation,
};

use crate::input::{InputError, SourceFile};
use crate::inputs::road as road_input;
use crate::output;
use crate::plot::{self, Chart, Series, SeriesStyle};

/// Arguments of `vbi road`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// A `[road]` input file (TOML). Without it, `--class` (default medium) with default options.
    #[arg(conflicts_with_all = ["class", "measured"])]
    pub file: Option<PathBuf>,
    /// Roughness class: smooth, good, medium, poor (the paper's) or ISO 8608 A … H.
    #[arg(long, conflicts_with = "measured")]
    pub class: Option<String>,
    /// A measured profile to import instead of generating one: CSV with header x_m,left_m,right_m.
    #[arg(long, value_name = "CSV")]
    pub measured: Option<PathBuf>,
    /// Bridge length L [m]; the profile spans [-approach, L + exit].
    #[arg(long, default_value_t = 100.0, allow_negative_numbers = true)]
    pub length: f64,
    /// Base seed (overrides the file's `seed`).
    #[arg(long, conflicts_with = "measured")]
    pub seed: Option<u64>,
    /// Index of the sample within the set of the base seed (ChaCha20 stream).
    #[arg(long, default_value_t = 0, conflicts_with = "measured")]
    pub sample: u64,
    /// Output directory.
    #[arg(long, default_value = "vbi-road")]
    pub out: PathBuf,
}

/// Runs the command.
pub fn run(args: &Args) -> Result<()> {
    if !(args.length.is_finite() && args.length > 0.0) {
        return Err(InputError::command_line(
            "--length",
            format!(
                "{} is not allowed; expected a positive bridge length in m",
                args.length
            ),
        )
        .into());
    }
    let (profile, spec) = match &args.measured {
        Some(path) => (road_input::read_profile_csv(path)?, None),
        None => {
            let mut file = None;
            let mut spec = match (&args.file, &args.class) {
                (Some(path), _) => {
                    let source = SourceFile::read(path)?;
                    crate::inputs::expect_kind(&source, "road", "vbi road")?;
                    let spec = road_input::load(&source)?;
                    file = Some(source);
                    spec
                }
                (None, Some(name)) => RoadSpec::of_class(
                    road_input::parse_class(name)
                        .map_err(|m| InputError::command_line("--class", m))?,
                ),
                (None, None) => RoadSpec::of_class(RoughnessClass::Medium),
            };
            if let Some(seed) = args.seed {
                spec.seed = seed;
            }
            let (start, end) = spec.extent_for_bridge(args.length);
            // A file's road is blamed on its key; a class's on the length asked for.
            let profile = generate_sample(&spec, start, end, spec.seed, args.sample).map_err(
                |e| match &file {
                    Some(file) => file.error_at(road_input::generation_key(&e), e.to_string()),
                    None => InputError::command_line("--length", e.to_string()),
                },
            )?;
            (profile, Some(spec))
        }
    };
    output::create_output_dir(&args.out)?;
    write_profile_csv(&args.out.join("profile.csv"), &profile)?;
    plot_profile(&args.out, &profile)?;
    let psd_written = plot_psd(&args.out, &profile, spec.as_ref())?;
    write_summary(&args.out, &profile, spec.as_ref(), args)?;
    print_summary(&profile, spec.as_ref(), args, psd_written);
    Ok(())
}

/// Writes `x_m,left_m,right_m`.
pub fn write_profile_csv(path: &Path, profile: &RoadProfile) -> Result<()> {
    let rows: Vec<Vec<String>> = (0..profile.len())
        .map(|i| {
            vec![
                output::number(profile.position(i)),
                output::number(profile.left[i]),
                output::number(profile.right[i]),
            ]
        })
        .collect();
    output::write_csv(path, &["x_m", "left_m", "right_m"], &rows)
}

fn tracks_differ(profile: &RoadProfile) -> bool {
    profile.left != profile.right
}

fn plot_profile(dir: &Path, profile: &RoadProfile) -> Result<()> {
    let points = |track: Track| -> Vec<(f64, f64)> {
        envelope(profile.samples(track), 800)
            .into_iter()
            .map(|(i, v)| (profile.position(i), v * 1e3))
            .collect()
    };
    // Thin lines: plotters' bitmap backend drops steep segments of 2-pixel polylines.
    let mut series = vec![Series {
        label: "left track".into(),
        points: points(Track::Left),
        style: SeriesStyle::Thin,
    }];
    if tracks_differ(profile) {
        series.push(Series {
            label: "right track".into(),
            points: points(Track::Right),
            style: SeriesStyle::Thin,
        });
    }
    let chart = Chart {
        title: "Road profile (bridge from x = 0)".into(),
        x_label: "x [m]".into(),
        y_label: "elevation [mm]".into(),
        series,
        ..Chart::default()
    };
    plot::write_chart(&chart, &dir.join("profile"))?;
    Ok(())
}

/// At most 2 × `buckets` points for drawing: the minimum and the maximum of each bucket of
/// samples, in order, so that peaks survive the thinning.
fn envelope(samples: &[f64], buckets: usize) -> Vec<(usize, f64)> {
    if samples.len() <= 2 * buckets {
        return samples.iter().copied().enumerate().collect();
    }
    let size = samples.len().div_ceil(buckets);
    let mut out = Vec::with_capacity(2 * buckets);
    for (b, chunk) in samples.chunks(size).enumerate() {
        let base = b * size;
        let (mut lo, mut hi) = (0, 0);
        for (i, v) in chunk.iter().enumerate() {
            if *v < chunk[lo] {
                lo = i;
            }
            if *v > chunk[hi] {
                hi = i;
            }
        }
        let (first, second) = if lo <= hi { (lo, hi) } else { (hi, lo) };
        out.push((base + first, chunk[first]));
        if second != first {
            out.push((base + second, chunk[second]));
        }
    }
    out
}

/// Welch segment: the largest power of two ≤ samples/4, between 16 and 8192 samples
/// (≥ 7 half-overlapping segments for a smoother estimate).
fn segment_length(count: usize) -> Option<usize> {
    if count < 64 {
        return None;
    }
    let mut m = 16;
    while m * 2 <= count / 4 && m * 2 <= 8192 {
        m *= 2;
    }
    Some(m)
}

fn plot_psd(dir: &Path, profile: &RoadProfile, spec: Option<&RoadSpec>) -> Result<bool> {
    let Some(segment) = segment_length(profile.len()) else {
        return Ok(false);
    };
    // A generated profile holds nothing above its band: plot the estimate over the band only
    // (the window's leakage beyond it would squeeze the axis).
    let upper_limit = spec.map_or(f64::INFINITY, |s| s.band_upper);
    let mut series = Vec::new();
    let mut estimate = |track: Track, label: &str, style: SeriesStyle| -> Result<()> {
        let points = welch_psd(
            profile.samples(track),
            profile.spacing,
            segment,
            segment / 2,
        )
        .map_err(|e| anyhow::anyhow!("{e}"))?
        .into_iter()
        .filter(|p| p.psd > 0.0 && p.spatial_frequency <= upper_limit)
        .map(|p| (p.spatial_frequency, p.psd * 1e6))
        .collect();
        series.push(Series {
            label: label.into(),
            points,
            style,
        });
        Ok(())
    };
    estimate(Track::Left, "left track (Welch)", SeriesStyle::Line)?;
    if tracks_differ(profile) {
        estimate(Track::Right, "right track (Welch)", SeriesStyle::Thin)?;
    }
    if series.iter().all(|s| s.points.is_empty()) {
        return Ok(false);
    }
    if let Some(spec) = spec {
        let psd = spec.psd().map_err(|e| anyhow::anyhow!("{e}"))?;
        if psd.psd_at_reference > 0.0 {
            let (n1, n2) = (spec.band_lower, spec.band_upper);
            let target = (0..=100)
                .map(|i| {
                    let n = n1 * (n2 / n1).powf(i as f64 / 100.0);
                    (n, psd.value(n) * 1e6)
                })
                .collect();
            series.push(Series::line(
                format!("ISO 8608 target ({})", spec.roughness.describe()),
                target,
            ));
        }
    }
    let chart = Chart {
        title: "Displacement PSD".into(),
        x_label: "spatial frequency n [cycles/m]".into(),
        y_label: "G_d(n) [cm^3 = 1e-6 m^3]".into(),
        series,
        log_x: true,
        log_y: true,
        ..Chart::default()
    };
    plot::write_chart(&chart, &dir.join("psd"))?;
    Ok(true)
}

fn tracks_name(correlation: TrackCorrelation) -> String {
    match correlation {
        TrackCorrelation::Identical => "identical".into(),
        TrackCorrelation::Independent => "independent".into(),
        TrackCorrelation::Coherent {
            track_spacing,
            coherence_decay,
        } => format!("coherent (b = {track_spacing} m, rho = {coherence_decay})"),
        TrackCorrelation::VehicleTrack { coherence_decay } => format!(
            "coherent at the crossing vehicle's track (rho = {coherence_decay}); identical here, \
             without a vehicle"
        ),
    }
}

fn write_summary(
    dir: &Path,
    profile: &RoadProfile,
    spec: Option<&RoadSpec>,
    args: &Args,
) -> Result<()> {
    let summary = serde_json::json!({
        "vbi_version": env!("CARGO_PKG_VERSION"),
        "source": match &args.measured {
            Some(p) => format!("measured: {}", p.display()),
            None => "generated".to_string(),
        },
        "spec": spec,
        "sample_index": spec.map(|_| args.sample),
        "start_m": profile.start,
        "end_m": profile.end(),
        "spacing_m": profile.spacing,
        "sample_count": profile.len(),
        "rms_left_m": profile.rms(Track::Left),
        "rms_right_m": profile.rms(Track::Right),
    });
    output::write_json(&dir.join("summary.json"), &summary)
}

fn print_summary(profile: &RoadProfile, spec: Option<&RoadSpec>, args: &Args, psd: bool) {
    if let Some(spec) = spec.filter(|s| !s.events.is_empty()) {
        outln!(
            "events: {} superposed (see the [road] file)",
            spec.events.len()
        );
    }
    match spec {
        Some(RoadSpec {
            profile: Some(user),
            ..
        }) => {
            let (first, last) = user.extent();
            outln!(
                "road: user profile of {} points over [{first}, {last}] m",
                user.positions.len()
            );
        }
        Some(spec) => {
            let g0 = spec.psd_at_iso_reference();
            let iso = match (spec.roughness, RoughnessClass::iso_class_of(g0)) {
                (Roughness::Class(RoughnessClass::Smooth), _) | (_, None) => String::new(),
                (_, Some(c)) => format!(", within ISO 8608 class {}", c.name()),
            };
            let reading = match spec.reference() {
                vbi::road::PsdReference::Iso8608 => String::new(),
                other => format!(
                    "; {:.1} x 1e-6 m^3 read at n0 = 1/(2 pi) cycles/m ({})",
                    spec.roughness.psd_at_reference() * 1e6,
                    other.name()
                ),
            };
            outln!(
                "road: {} (G_d(0.1 cycles/m) = {:.1} x 1e-6 m^3, w = {}{iso}{reading})",
                spec.roughness.describe(),
                g0 * 1e6,
                spec.waviness
            );
            outln!(
                "band {} to {} cycles/m, {:?}, tracks {}, seed {} sample {}",
                spec.band_lower,
                spec.band_upper,
                spec.method,
                tracks_name(spec.track_correlation),
                spec.seed,
                args.sample
            );
            if let Ok(target) = spec.psd() {
                outln!(
                    "target RMS over the band: {:.3} mm",
                    target
                        .band_variance(spec.band_lower, spec.band_upper)
                        .sqrt()
                        * 1e3
                );
            }
        }
        None => {
            if let Some(path) = &args.measured {
                outln!("road: measured profile {}", path.display());
            }
        }
    }
    outln!(
        "profile: x from {} to {} m, {} samples at {:.4} m",
        profile.start,
        profile.end(),
        profile.len(),
        profile.spacing
    );
    outln!(
        "RMS elevation: left {:.3} mm, right {:.3} mm",
        profile.rms(Track::Left) * 1e3,
        profile.rms(Track::Right) * 1e3
    );
    let mut files = vec!["profile.csv", "profile.png", "profile.svg", "summary.json"];
    if psd {
        files.extend(["psd.png", "psd.svg"]);
    }
    outln!("wrote {} in {}", files.join(", "), args.out.display());
}
