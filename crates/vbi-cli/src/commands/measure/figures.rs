//! The figures of one run of `vbi measure`, as PNG and SVG under its folder: `signal_<channel>`
//! (raw, static and K1-filtered signals), `spectrum_<channel>` (Welch PSD with the picked peaks)
//! and the subspace identification's `stabilisation_diagram`.

use std::path::Path;

use anyhow::Result;
use vbi::measure::measurement::Measurement;
use vbi::measure::{ChannelSpectrum, IdentifiedMode, MeasurementResult, SubspaceSummary};
use vbi::signal::Psd;

use crate::plot::{self, Chart, Series, SeriesStyle};

/// The longest file stem made from a name, in characters (ASCII, so also in bytes): a file
/// name holds at most 255 bytes on Linux, macOS and Windows, and a figure's name adds a prefix
/// (`spectrum_`), a suffix against collisions (`_2`) and an extension (`.png`). Longer names
/// are cut, and [`unique_stem`] keeps two cut names apart (issue 47: a 3,000-character channel
/// name failed in the plotting library with "File name too long").
const FILE_STEM_CHARACTERS: usize = 100;

/// A name made of ASCII letters, digits, `-` and `_` (every other character `_`), cut to
/// [`FILE_STEM_CHARACTERS`]: a file stem.
pub(super) fn file_stem(name: &str) -> String {
    name.chars()
        .take(FILE_STEM_CHARACTERS)
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// `stem`, or `stem_2`, `stem_3`, … when an earlier figure has it: two channel names that map to
/// one file stem (`u 1` and `u/1`) must not overwrite each other's figure.
fn unique_stem(stem: String, taken: &[String]) -> String {
    if !taken.contains(&stem) {
        return stem;
    }
    (2..)
        .map(|k| format!("{stem}_{k}"))
        .find(|s| !taken.contains(s))
        .expect("an unused suffix")
}

/// The figures of every channel (raw, static and K1-filtered signals) and of every spectrum
/// (Welch PSD with the picked peaks); returns their stems.
pub(super) fn draw_figures(
    m: &Measurement,
    result: &MeasurementResult,
    out: &Path,
) -> Result<Vec<String>> {
    let mut figures = Vec::new();
    for (index, c) in m.channels.iter().enumerate() {
        let stem = unique_stem(format!("signal_{}", file_stem(&c.name)), &figures);
        plot::write_chart(&signal_chart(m, result, index), &out.join(&stem))?;
        figures.push(stem);
    }
    for (psd, spectrum) in result.densities.iter().zip(&result.summary.spectra) {
        let stem = unique_stem(
            format!("spectrum_{}", file_stem(&spectrum.channel)),
            &figures,
        );
        plot::write_chart(&spectrum_chart(m, psd, spectrum), &out.join(&stem))?;
        figures.push(stem);
    }
    if let Some(subspace) = &result.summary.subspace {
        let stem = "stabilisation_diagram".to_string();
        let chart = stabilisation_chart(subspace, &result.summary.identified_frequencies);
        plot::write_chart(&chart, &out.join(&stem))?;
        figures.push(stem);
    }
    Ok(figures)
}

/// The subspace identification's stabilisation diagram: every pole kept (frequency against
/// model order), the stable ones marked, and the identified modes at the highest order.
fn stabilisation_chart(subspace: &SubspaceSummary, modes: &[IdentifiedMode]) -> Chart {
    let poles = |stable: bool| -> Vec<(f64, f64)> {
        subspace
            .diagram
            .iter()
            .filter(|p| p.stable == stable)
            .map(|p| (p.frequency_hz, p.order as f64))
            .collect()
    };
    let top = subspace.max_order as f64 + 2.0;
    let identified: Vec<(f64, f64)> = modes
        .iter()
        .flat_map(|p| [(p.frequency_hz, 0.0), (p.frequency_hz, top)])
        .collect();
    Chart {
        title: format!(
            "stabilisation diagram ({} acceleration channels)",
            subspace.channels.len()
        ),
        x_label: "frequency [Hz]".into(),
        y_label: "model order [-]".into(),
        series: vec![
            Series {
                label: "poles".into(),
                points: poles(false),
                style: SeriesStyle::Points,
            },
            Series {
                label: "stable poles".into(),
                points: poles(true),
                style: SeriesStyle::Points,
            },
            Series {
                label: "identified modes".into(),
                points: identified,
                style: SeriesStyle::ThinSegments,
            },
        ],
        ..Chart::default()
    }
}

/// A channel's measured signal with its static part and its K1-filtered signal (at most about
/// 4000 points drawn), in the channel's unit.
fn signal_chart(m: &Measurement, result: &MeasurementResult, index: usize) -> Chart {
    let c = &m.channels[index];
    let step = (m.time.len() / 4000).max(1);
    let points = |v: &[f64]| -> Vec<(f64, f64)> {
        m.time
            .iter()
            .zip(v)
            .step_by(step)
            .map(|(t, x)| (*t, x / c.si_per_unit))
            .collect()
    };
    let mut series = vec![Series {
        label: "measured".into(),
        points: points(&c.samples),
        style: SeriesStyle::Thin,
    }];
    if let Some(signals) = result.signals.iter().find(|s| s.channel_index == index) {
        if let Some(filtered) = &signals.filtered_at_cutoff_mode {
            let label = result
                .summary
                .channels
                .iter()
                .find(|r| r.name == c.name)
                .and_then(|r| r.cutoff_mode.as_ref())
                .map_or("low-pass above K1".to_string(), |k| {
                    format!(
                        "low-pass above K1 ({:.2} Hz), f_c = {:.2} Hz",
                        k.mode_frequency_hz, k.cutoff_hz
                    )
                });
            series.push(Series::line(label, points(filtered)));
        }
        series.push(Series::line("static", points(&signals.static_part)));
    }
    Chart {
        title: format!("{} ({:?})", c.name, c.kind).to_lowercase(),
        x_label: "time [s]".into(),
        y_label: format!("{} [{}]", c.name, c.unit),
        series,
        ..Chart::default()
    }
}

/// A Welch PSD in dB with its picked peaks, up to twice the search band (the whole band when
/// unbounded): the modes stay readable next to the noise floor.
fn spectrum_chart(m: &Measurement, psd: &Psd, spectrum: &ChannelSpectrum) -> Chart {
    let f_max = (2.0 * m.spectrum.max_frequency_hz).min(m.sampling_rate_hz / 2.0);
    let db = |p: f64| 10.0 * p.max(1e-300).log10();
    let line: Vec<(f64, f64)> = psd
        .frequency_hz
        .iter()
        .zip(&psd.density)
        .skip(1)
        .filter(|(f, _)| **f <= f_max)
        .map(|(f, p)| (*f, db(*p)))
        .collect();
    let peaks: Vec<(f64, f64)> = spectrum
        .peaks
        .iter()
        .map(|p| (p.frequency_hz, db(p.density)))
        .collect();
    Chart {
        title: format!("Welch PSD of {} with picked peaks", spectrum.channel),
        x_label: "frequency [Hz]".into(),
        y_label: "PSD [dB re 1 (m/s²)²/Hz]".into(),
        series: vec![
            Series::line("PSD", line),
            Series {
                label: "picked peaks".into(),
                points: peaks,
                style: SeriesStyle::Points,
            },
        ],
        ..Chart::default()
    }
}

#[cfg(test)]
mod tests {
    use super::{file_stem, unique_stem};

    #[test]
    fn channel_names_that_map_to_one_file_stem_get_figures_of_their_own() {
        let mut figures = Vec::new();
        for name in ["u 1", "u/1", "u_1"] {
            let stem = unique_stem(format!("signal_{}", file_stem(name)), &figures);
            figures.push(stem);
        }
        assert_eq!(figures, ["signal_u_1", "signal_u_1_2", "signal_u_1_3"]);
    }

    #[test]
    fn channel_names_longer_than_a_file_name_are_cut_and_kept_apart() {
        let long = "x".repeat(3000);
        let mut figures = Vec::new();
        for name in [long.clone(), format!("{long}y")] {
            let stem = unique_stem(format!("spectrum_{}", file_stem(&name)), &figures);
            figures.push(stem);
        }
        assert_eq!(figures[0].len(), "spectrum_".len() + 100);
        assert_eq!(figures[1], format!("{}_2", figures[0]));
        assert!(figures.iter().all(|f| f.len() + ".png".len() <= 255));
    }
}
