//! `report.html` of `vbi measure`: one self-contained page (figures inline as SVG, no script)
//! over one run or the runs of a load test, built with the page helpers of `vbi report`
//! ([`crate::commands::report::page`]).
//!
//! Key results (each channel's DAF and each section's RDM per run), then a section "DAF of
//! every run" (a table across the runs and, with two runs or more that give their speed, the
//! DAF against the speed per channel), then a section per run: its description, its numbers
//! (the rows of `measurements.csv`, the RDM, the identified frequencies, the static
//! separation), a figure per DAF channel (the record, its static part and the dynamic part
//! measured − static, with the two maxima of the DAF marked) and its spectra with the picked
//! peaks.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use vbi::units::metres_per_second_to_kmh;

use anyhow::{bail, Context, Result};
use vbi::measure::{ChannelDaf, MeasurementResult};

use super::rows::Row;
use crate::commands::report::page::{self, escape, figure, fixed, number, Page};
use crate::output;
use crate::plot::{self, Chart, Series, SeriesStyle};

/// One run as the report shows it.
pub(super) struct ReportRun<'a> {
    /// Its name (the file's stem, unique in the batch).
    pub(super) stem: &'a str,
    /// The measurement file as given.
    pub(super) input: &'a str,
    /// The folder its figures were written to.
    pub(super) dir: &'a Path,
    /// That folder relative to the report (several runs), or `None` (the report's own folder).
    pub(super) directory_label: Option<&'a str>,
    /// The stems of the figures in `dir`.
    pub(super) figures: &'a [String],
    /// The processing's result.
    pub(super) result: &'a MeasurementResult,
    /// Its rows of the table (one per DAF channel).
    pub(super) rows: &'a [Row],
}

/// Writes the report of `runs` to `path`, whole or not at all.
pub(super) fn write(runs: &[ReportRun], path: &Path) -> Result<()> {
    let folder = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let scratch = Scratch::new(folder)?;
    let html = html(runs, &scratch)?;
    drop(scratch);
    output::write_atomic(path, html.as_bytes())
}

/// A hidden folder where the report's own figures are drawn (by [`plot::write_chart`], whole or
/// not at all) and read back; removed with everything in it when dropped.
struct Scratch(PathBuf);

impl Scratch {
    fn new(folder: &Path) -> Result<Scratch> {
        let path = folder.join(format!(".report-figures-{}.partial", std::process::id()));
        std::fs::create_dir_all(&path)
            .with_context(|| format!("creating directory {}", path.display()))?;
        Ok(Scratch(path))
    }

    /// The `<svg>` element of a chart.
    fn svg(&self, chart: &Chart, name: &str) -> Result<String> {
        let [png, svg] = plot::write_chart(chart, &self.0.join(name))?;
        let text = std::fs::read_to_string(&svg);
        let _ = std::fs::remove_file(png);
        let _ = std::fs::remove_file(&svg);
        inline_svg(
            &text.with_context(|| format!("reading {}", svg.display()))?,
            &svg,
        )
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// The `<svg>` element of an SVG file's text (without the XML declaration); an error for a torn
/// figure.
fn inline_svg(text: &str, path: &Path) -> Result<String> {
    let svg = text.find("<svg").map_or(text, |i| &text[i..]).trim_end();
    if !svg.ends_with("</svg>") {
        bail!(
            "{} is not a whole SVG figure (torn or foreign); run `vbi measure` again",
            path.display()
        );
    }
    Ok(svg.to_string())
}

/// The speed of a run [km/h].
fn speed_kmh(run: &ReportRun) -> Option<f64> {
    run.result.summary.speed_m_s.map(metres_per_second_to_kmh)
}

/// "pass_40kmh (40.0 km/h)".
fn run_label(run: &ReportRun) -> String {
    match speed_kmh(run) {
        Some(v) => format!("{} ({v:.1} km/h)", run.stem),
        None => run.stem.to_string(),
    }
}

/// Names in order of first appearance.
fn ordered<'a>(names: impl Iterator<Item = &'a str>) -> Vec<&'a str> {
    let mut list: Vec<&str> = Vec::new();
    for name in names {
        if !list.contains(&name) {
            list.push(name);
        }
    }
    list
}

/// The DAF channels of all runs, by name, in order of first appearance.
fn channel_names<'a>(runs: &'a [ReportRun]) -> Vec<&'a str> {
    ordered(
        runs.iter()
            .flat_map(|r| r.rows.iter().map(|x| x.channel.as_str())),
    )
}

/// The RDM sections of all runs, in order of first appearance.
fn section_names<'a>(runs: &'a [ReportRun]) -> Vec<&'a str> {
    ordered(
        runs.iter()
            .flat_map(|r| r.result.summary.rdm.iter().map(|x| x.section.as_str())),
    )
}

fn html(runs: &[ReportRun], scratch: &Scratch) -> Result<String> {
    let title = match runs {
        [one] => format!("vbi measure report: {}", one.input),
        _ => format!("vbi measure report: {} runs", runs.len()),
    };
    let mut page = Page::new(&title);
    key_results(&mut page, runs);
    page.section("summary", "DAF of every run", summary(runs, scratch)?);
    for run in runs {
        page.section(
            &format!("run-{}", run.stem),
            &format!("Run {}", run_label(run)),
            run_section(run, scratch)?,
        );
    }
    Ok(page.html())
}

fn key_results(page: &mut Page, runs: &[ReportRun]) {
    let names: Vec<String> = runs.iter().map(run_label).collect();
    page.key_result("runs", format!("{}: {}", runs.len(), names.join(", ")));
    if let [one] = runs {
        if let Some(d) = &one.result.summary.description {
            page.key_result("description", d.clone());
        }
    }
    let per_run = |value: &dyn Fn(&ReportRun) -> Option<String>| -> String {
        let values: Vec<String> = runs
            .iter()
            .filter_map(|run| match runs.len() {
                1 => value(run),
                _ => value(run).map(|v| format!("{}: {v}", run_label(run))),
            })
            .collect();
        if values.is_empty() {
            "–".into()
        } else {
            values.join("; ")
        }
    };
    for name in channel_names(runs) {
        let value = per_run(&|run| {
            run.rows.iter().find(|r| r.channel == name).map(|r| {
                // The stated 95 % interval beside the DAF (issue 52: a bare number reads as
                // exact).
                let interval = run
                    .result
                    .summary
                    .channels
                    .iter()
                    .find(|c| c.name == name)
                    .and_then(|c| c.uncertainty.as_ref())
                    .map_or(String::new(), |u| {
                        format!(" ± {} (95 %)", number(Some(u.expanded_95)))
                    });
                format!(
                    "{}{interval} (at K1: {})",
                    number(Some(r.daf)),
                    number(r.daf_at_k1)
                )
            })
        });
        page.key_result(&format!("DAF of {name}"), value);
    }
    for section in section_names(runs) {
        let value = per_run(&|run| {
            run.result
                .summary
                .rdm
                .iter()
                .find(|x| x.section == section)
                .map(|x| number(Some(x.rdm)))
        });
        page.key_result(&format!("RDM at {section}"), value);
    }
    let value = per_run(&|run| {
        run.result
            .summary
            .identified_frequencies
            .first()
            .map(|p| format!("{} Hz", number(Some(p.frequency_hz))))
    });
    page.key_result("first identified frequency", value);
    let warnings: Vec<String> = runs
        .iter()
        .flat_map(|run| {
            run.result
                .summary
                .warnings
                .iter()
                .map(move |w| match runs.len() {
                    1 => w.to_string(),
                    _ => format!("{}: {w}", run_label(run)),
                })
        })
        .collect();
    let value = match warnings.len() {
        0 => "none".to_string(),
        _ => warnings.join("; "),
    };
    page.key_result(&format!("warnings ({})", warnings.len()), value);
}

/// The table across the runs and the DAF against the speed.
fn summary(runs: &[ReportRun], scratch: &Scratch) -> Result<String> {
    let channels = channel_names(runs);
    let sections = section_names(runs);
    let mut header = vec!["run".to_string(), "speed [km/h]".to_string()];
    for c in &channels {
        header.push(format!("DAF {c}"));
        header.push(format!("DAF at K1 {c}"));
    }
    for s in &sections {
        header.push(format!("RDM {s}"));
    }
    header.push("f₁ [Hz]".into());
    let rows: Vec<Vec<String>> = runs
        .iter()
        .map(|run| {
            let mut row = vec![run.stem.to_string(), fixed(speed_kmh(run), 1)];
            for c in &channels {
                let r = run.rows.iter().find(|r| r.channel == *c);
                row.push(number(r.map(|r| r.daf)));
                row.push(number(r.and_then(|r| r.daf_at_k1)));
            }
            for s in &sections {
                let x = run.result.summary.rdm.iter().find(|x| x.section == *s);
                row.push(number(x.map(|x| x.rdm)));
            }
            row.push(number(
                run.result
                    .summary
                    .identified_frequencies
                    .first()
                    .map(|p| p.frequency_hz),
            ));
            row
        })
        .collect();
    let source = if runs.len() > 1 {
        "measurements.csv"
    } else {
        "measure.json"
    };
    let mut body = format!(
        "<p>One row per run, in the order given. DAF = dynamic maximum / static maximum of the \
         channel; DAF at K1: the same after a low-pass just above the frequency of the cut-off \
         mode K1; RDM = DAF of deflection / DAF of moment of a section. The numbers in full \
         precision are in <code>{source}</code>.</p>{}",
        page::table(&header, &rows)
    );
    let with_speed = runs.iter().filter(|r| speed_kmh(r).is_some()).count();
    if with_speed >= 2 {
        let svg = scratch.svg(&daf_speed_chart(runs, &channels), "daf_against_speed")?;
        let _ = write!(
            body,
            "<div id=\"daf-against-speed\">{}</div>",
            figure(
                &svg,
                "The DAF of each channel against the vehicle speed, one point per run \
                 (runs without a speed are left out)."
            )
        );
    }
    Ok(body)
}

/// The DAF of each channel against the speed [km/h], a line and points per channel, in the
/// channel's colour.
fn daf_speed_chart(runs: &[ReportRun], channels: &[&str]) -> Chart {
    let lines: Vec<(String, Vec<(f64, f64)>)> = channels
        .iter()
        .map(|c| {
            let mut points: Vec<(f64, f64)> = runs
                .iter()
                .filter_map(|run| {
                    let v = speed_kmh(run)?;
                    let r = run.rows.iter().find(|r| r.channel == *c)?;
                    Some((v, r.daf))
                })
                .collect();
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            (format!("DAF {c}"), points)
        })
        .collect();
    // Lines join the points of a channel when its runs have distinct speeds (two passes at one
    // speed would draw a vertical segment): points only otherwise.
    let distinct = lines
        .iter()
        .all(|(_, points)| points.windows(2).all(|w| w[0].0 < w[1].0));
    // The plot colours series by their index modulo its palette of 8: the points of channel i
    // go to index 8 + i, in the colour of its line (the series between are empty).
    const PALETTE_SIZE: usize = 8;
    let points = |label: String, points: Vec<(f64, f64)>| Series {
        label,
        points,
        style: SeriesStyle::Points,
    };
    let series: Vec<Series> = if !distinct {
        lines
            .into_iter()
            .map(|(label, p)| points(label, p))
            .collect()
    } else if lines.len() <= PALETTE_SIZE {
        let mut series: Vec<Series> = lines
            .iter()
            .map(|(label, p)| Series::line(label.clone(), p.clone()))
            .collect();
        series.resize_with(PALETTE_SIZE, || Series::line("", Vec::new()));
        series.extend(lines.into_iter().map(|(_, p)| points(String::new(), p)));
        series
    } else {
        lines
            .into_iter()
            .map(|(label, p)| Series::line(label, p))
            .collect()
    };
    Chart {
        title: "DAF against the vehicle speed".into(),
        x_label: "speed [km/h]".into(),
        y_label: "DAF [-]".into(),
        series,
        ..Chart::default()
    }
}

fn run_section(run: &ReportRun, scratch: &Scratch) -> Result<String> {
    let s = &run.result.summary;
    let mut body = String::new();
    if let Some(d) = &s.description {
        let _ = write!(body, "<p>{}</p>", escape(d));
    }
    let folder = match run.directory_label {
        Some(dir) => format!("<code>{}/</code>", escape(dir)),
        None => "this folder".into(),
    };
    let _ = write!(
        body,
        "<p>Input <code>{}</code>: {} samples at {} Hz ({} s){}. Its <code>measure.json</code> \
         and figures: {folder}.</p>",
        escape(run.input),
        s.samples,
        number(Some(s.sampling_rate_hz)),
        fixed(Some(s.duration_s), 2),
        s.speed_m_s.map_or(String::new(), |v| format!(
            ", vehicle speed {} m/s ({} km/h)",
            fixed(Some(v), 2),
            fixed(Some(metres_per_second_to_kmh(v)), 1)
        )),
    );
    body.push_str(&channel_table(run.rows));
    match &s.static_separation {
        Some(x) => {
            let _ = write!(
                body,
                "<p><b>Static separation</b> (zero-phase Butterworth order {}): {}. \
                 Separated: {}. Why: {}.</p>",
                x.filter_order,
                escape(&x.explanation),
                if x.cutoff.separated { "yes" } else { "no" },
                escape(&x.reason)
            );
        }
        None => {
            let methods: Vec<String> = s
                .channels
                .iter()
                .map(|c| format!("{}: {}", c.name, c.static_method))
                .collect();
            let _ = write!(
                body,
                "<p><b>Static parts</b> without a low-pass on this record (so no separation \
                 verdict): {}.</p>",
                escape(&methods.join("; "))
            );
        }
    }
    if !s.rdm.is_empty() {
        let rows: Vec<Vec<String>> = s
            .rdm
            .iter()
            .map(|x| {
                vec![
                    x.section.clone(),
                    x.deflection_channel.clone(),
                    x.moment_channel.clone(),
                    number(Some(x.daf_deflection)),
                    number(Some(x.daf_moment)),
                    number(Some(x.rdm)),
                ]
            })
            .collect();
        let header: Vec<String> = [
            "section",
            "deflection channel",
            "moment channel",
            "DAF_u",
            "DAF_M",
            "RDM",
        ]
        .map(String::from)
        .to_vec();
        body.push_str(&page::table(&header, &rows));
    }
    body.push_str(&frequencies(run));
    if let Some(u) = &s.updating {
        let _ = write!(
            body,
            "<p><b>Model updating</b>: stiffness scale {}; RMS frequency error {} Hz → {} Hz.</p>",
            number(Some(u.stiffness_scale)),
            number(Some(u.initial_rms_error_hz)),
            number(Some(u.updated_rms_error_hz))
        );
    }
    for (i, c) in s.channels.iter().enumerate() {
        if let Some(chart) = daf_chart(run.result, c) {
            let svg = scratch.svg(&chart, &format!("{}_{i}", run.stem))?;
            body.push_str(&figure(&svg, &daf_caption(c)));
        }
    }
    let spectra = run.figures.iter().filter(|f| f.starts_with("spectrum_"));
    for (stem, spectrum) in spectra.zip(&s.spectra) {
        let path = run.dir.join(format!("{stem}.svg"));
        let text = std::fs::read_to_string(&path)
            .with_context(|| format!("reading {}", path.display()))?;
        let peaks: Vec<String> = spectrum
            .peaks
            .iter()
            .map(|p| fixed(Some(p.frequency_hz), 3))
            .collect();
        let caption = format!(
            "Welch PSD of {} ({} segments, resolution {} Hz) with the picked peaks at {} Hz.",
            spectrum.channel,
            spectrum.segments,
            fixed(Some(spectrum.resolution_hz), 3),
            if peaks.is_empty() {
                "–".into()
            } else {
                peaks.join(", ")
            }
        );
        body.push_str(&figure(&inline_svg(&text, &path)?, &caption));
    }
    if let Some(subspace) = &s.subspace {
        let stem = "stabilisation_diagram";
        let path = run.dir.join(format!("{stem}.svg"));
        if run.figures.iter().any(|f| f == stem) {
            let text = std::fs::read_to_string(&path)
                .with_context(|| format!("reading {}", path.display()))?;
            let modes: Vec<String> = s
                .identified_frequencies
                .iter()
                .map(|p| fixed(Some(p.frequency_hz), 3))
                .collect();
            let caption = format!(
                "Stabilisation diagram of the subspace identification ({}) of {}: poles by model order, the stable ones marked; modes identified at {} Hz.",
                s.identification,
                subspace.channels.join(", "),
                if modes.is_empty() { "–".into() } else { modes.join(", ") }
            );
            body.push_str(&figure(&inline_svg(&text, &path)?, &caption));
        }
    }
    Ok(body)
}

/// The run's rows of the table, with units.
fn channel_table(rows: &[Row]) -> String {
    let header: Vec<String> = [
        "channel",
        "kind",
        "unit",
        "static part",
        "cut-off [Hz]",
        "static max",
        "dynamic max",
        "DAF",
        "K1 [Hz]",
        "DAF at K1",
        "change at K1 [%]",
        "section",
        "separation check",
    ]
    .map(String::from)
    .to_vec();
    let flag = |x: Option<bool>| match x {
        Some(true) => "passed".to_string(),
        Some(false) => "failed".to_string(),
        None => "–".to_string(),
    };
    let cells: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            vec![
                r.channel.clone(),
                r.kind.clone(),
                r.unit.clone(),
                r.static_method.clone(),
                number(r.cutoff_hz),
                number(Some(r.static_max)),
                number(Some(r.dynamic_max)),
                number(Some(r.daf)),
                number(r.k1_hz),
                number(r.daf_at_k1),
                fixed(r.k1_relative_change.map(|x| 100.0 * x), 2),
                r.section.clone().unwrap_or_else(|| "–".into()),
                flag(r.channel_separated),
            ]
        })
        .collect();
    page::table(&header, &cells)
}

/// The identified frequencies with their damping.
fn frequencies(run: &ReportRun) -> String {
    let s = &run.result.summary;
    let Some(channel) = &s.frequency_channel else {
        return String::new();
    };
    if s.identified_frequencies.is_empty() {
        return format!(
            "<p>No frequency identified from <code>{}</code>.</p>",
            escape(channel)
        );
    }
    let rows: Vec<Vec<String>> = s
        .identified_frequencies
        .iter()
        .enumerate()
        .map(|(i, p)| {
            vec![
                (i + 1).to_string(),
                fixed(Some(p.frequency_hz), 3),
                fixed(p.damping_ratio.map(|z| 100.0 * z), 2),
                if p.damping_resolution_limited {
                    "upper bound (resolution-limited)".into()
                } else {
                    String::new()
                },
            ]
        })
        .collect();
    let header: Vec<String> = ["mode", "frequency [Hz]", "damping [%]", "damping note"]
        .map(String::from)
        .to_vec();
    // The subspace identification reads every acceleration channel, not one.
    let source = s
        .subspace
        .as_ref()
        .map_or(channel.clone(), |sub| sub.channels.join(", "));
    format!(
        "<p>Identified frequencies of <code>{}</code> ({}):</p>{}",
        escape(&source),
        escape(s.identification),
        page::table(&header, &rows)
    )
}

/// A DAF channel's record (as analysed, baseline corrected), its static part and its dynamic
/// part (record − static) in the channel's unit, with the static and the dynamic maximum of the
/// DAF as points; `None` when the record has no such channel.
fn daf_chart(result: &MeasurementResult, daf: &ChannelDaf) -> Option<Chart> {
    let m = &result.record;
    let index = m.channels.iter().position(|c| c.name == daf.name)?;
    let signals = result.signals.iter().find(|s| s.channel_index == index)?;
    let c = &m.channels[index];
    let step = (m.time.len() / 3000).max(1);
    let scale = 1.0 / c.si_per_unit;
    let samples = m.time.iter().zip(&c.samples).zip(&signals.static_part);
    let pick = |f: &dyn Fn(f64, f64) -> f64| -> Vec<(f64, f64)> {
        samples
            .clone()
            .step_by(step)
            .map(|((t, x), s)| (*t, f(*x, *s) * scale))
            .collect()
    };
    let point = |label: &str, t: f64, y: f64| Series {
        label: label.into(),
        points: vec![(t, y)],
        style: SeriesStyle::Points,
    };
    Some(Chart {
        title: format!("{}: record, static and dynamic parts", daf.name),
        x_label: "time [s]".into(),
        y_label: format!("{} [{}]", daf.name, daf.unit),
        series: vec![
            Series {
                label: "measured".into(),
                points: pick(&|x, _| x),
                style: SeriesStyle::Thin,
            },
            Series::line(format!("static ({})", daf.static_method), pick(&|_, s| s)),
            Series::line("dynamic part (measured − static)", pick(&|x, s| x - s)),
            point("static maximum", daf.time_of_static_max_s, daf.static_max),
            point(
                "dynamic maximum",
                daf.time_of_dynamic_max_s,
                daf.dynamic_max,
            ),
        ],
        ..Chart::default()
    })
}

fn daf_caption(c: &ChannelDaf) -> String {
    format!(
        "{}: the record (baseline corrected), its static part ({}) and the dynamic part \
         (measured − static) in {}; points: the static maximum {} at {} s and the measured \
         maximum {} at {} s, DAF = {}.",
        c.name,
        c.static_method,
        c.unit,
        number(Some(c.static_max)),
        fixed(Some(c.time_of_static_max_s), 3),
        number(Some(c.dynamic_max)),
        fixed(Some(c.time_of_dynamic_max_s), 3),
        number(Some(c.daf))
    )
}
