//! End-to-end tests of `vbi measure` and its inputs.

use std::path::Path;

use crate::common::{repository_root, vbi};

/// Writes `m.toml` (with `extra` TOML appended to the [measurement] table's keys) and `m.csv`.
fn write_case(dir: &Path, keys: &str, channels: &str, csv: &str) -> std::path::PathBuf {
    let toml = format!("[measurement]\ncsv = \"m.csv\"\n{keys}\n{channels}");
    std::fs::write(dir.join("m.csv"), csv).unwrap();
    let path = dir.join("m.toml");
    std::fs::write(&path, toml).unwrap();
    path
}

const DEFLECTION: &str =
    "[[measurement.channels]]\nname = \"u\"\nkind = \"deflection\"\nunit = \"mm\"\n";

/// A clean CSV: time at 100 Hz and a deflection bump −sin²(πt/4) mm over 4 s.
fn good_csv(rows: usize) -> String {
    let mut s = String::from("time_s,u\n");
    for i in 0..rows {
        let t = i as f64 / 100.0;
        let u = if t <= 4.0 {
            -(std::f64::consts::PI * t / 4.0).sin().powi(2)
        } else {
            0.0
        };
        s.push_str(&format!("{t:.2},{u:.6}\n"));
    }
    s
}

/// Replaces the CSV line that starts with `prefix` by `new`.
fn replace_line(csv: &str, prefix: &str, new: &str) -> String {
    csv.lines()
        .map(|l| {
            if l.starts_with(prefix) {
                new.to_string()
            } else {
                l.to_string()
            }
        })
        .map(|l| l + "\n")
        .collect()
}

fn stderr_of(path: &Path, command: &str) -> String {
    let mut cmd = vbi();
    cmd.arg(command).arg(path);
    if command == "measure" {
        cmd.arg("--out").arg(path.parent().unwrap().join("out"));
    }
    let out = cmd.assert().code(2);
    String::from_utf8_lossy(&out.get_output().stderr).to_string()
}

#[test]
fn the_synthetic_example_passes_check_and_measure_recovers_daf_and_frequencies() {
    // Reference: examples/measurements/generate_synthetic.py (documented formula): exact
    // noise-free deflection DAF 1.0963; modes 3.62, 4.48, 5.87 Hz; the model frequencies
    // 3.40, 4.21, 5.52 Hz need a stiffness scale of about (3.62/3.40)² ≈ 1.13.
    let example = repository_root().join("examples/measurements/synthetic_4x30.toml");
    vbi().arg("check").arg(&example).assert().success();
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    vbi()
        .arg("measure")
        .arg(&example)
        .arg("--out")
        .arg(&out)
        .assert()
        .success();
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("measure.json")).unwrap()).unwrap();
    let channels = json["channels"].as_array().unwrap();
    assert_eq!(channels.len(), 2);
    let daf = channels[0]["daf"].as_f64().unwrap();
    // Noise peaks (σ = 0.01 mm, ~0.3 % of the static maximum per σ) and the low-pass leave
    // the deflection DAF within 1 % of the exact value.
    assert!((daf - 1.0963).abs() < 0.011, "{daf}");
    assert!(channels[0]["cutoff_mode"]["daf_after"].as_f64().is_some());
    assert!(channels[1]["moment"]["static_max_n_m"].as_f64().unwrap() > 0.0);
    let freqs: Vec<f64> = json["identified_frequencies"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["frequency_hz"].as_f64().unwrap())
        .collect();
    for (got, exact) in freqs.iter().zip([3.62, 4.48, 5.87]) {
        // The issue's requirement: bridge frequencies within 1 %.
        assert!((got / exact - 1.0).abs() < 0.01, "{got} vs {exact}");
    }
    let alpha = json["updating"]["stiffness_scale"].as_f64().unwrap();
    // Closed form √α = Σf f̂/Σf² with f̂ within 1 %: α within 2 % of (3.62/3.40)².
    assert!(
        (alpha / (3.62f64 / 3.40).powi(2) - 1.0).abs() < 0.02,
        "{alpha}"
    );
    assert_eq!(json["rdm"].as_array().unwrap().len(), 1);
    // The loaded span (30 m at 20 m/s: f_q = 5 v/L = 3.33 Hz) reaches f₁/2 = 1.81 Hz: the rule
    // caps the cut-off and the separation is not claimed. The check on the influence-line
    // shapes keeps the smooth deflection (peak −0.45 %, within ±0.5 %) and refuses the kinked
    // mid-span moment (peak −7.8 %), as the exact strain DAF 1.0510 against the low-passed
    // 1.105 shows.
    let separation = &json["static_separation"];
    assert_eq!(separation["rule"], "half_first_frequency");
    assert_eq!(separation["separated"], false);
    assert_eq!(channels[0]["separation_check"]["separated"], true);
    assert_eq!(channels[1]["separation_check"]["separated"], false);
    for stem in [
        "signal_deflection_mid",
        "signal_strain_mid",
        "signal_acceleration_mid",
        "spectrum_acceleration_mid",
    ] {
        for ext in ["png", "svg"] {
            let f = out.join(format!("{stem}.{ext}"));
            assert!(
                f.metadata().map(|m| m.len() > 0).unwrap_or(false),
                "{} missing",
                f.display()
            );
        }
    }
}

/// Issue 52, item 5: what the reader must know reaches the screen, measure.json and the
/// report's key results. The synthetic 4 × 30 m record's DAFs rest on a low-pass that does not
/// separate (its cut-off capped at f₁/2: the strain DAF 1.105 against the exact 1.051): two
/// warnings. Its frequencies come from the free vibration after the exit, the entry being found
/// in the record by default, so no forced content can enter them (before the entry was looked
/// for by default, a third warning said they could not be checked). The field record with its
/// crawl run has none.
#[test]
fn warnings_of_a_low_pass_that_does_not_separate_reach_the_screen_the_json_and_the_key_results() {
    let dir = tempfile::tempdir().unwrap();
    let example = repository_root().join("examples/measurements/synthetic_4x30.toml");
    let out = dir.path().join("synthetic");
    let assert = vbi()
        .arg("measure")
        .arg(&example)
        .arg("--out")
        .arg(&out)
        .assert()
        .success();
    let printed = String::from_utf8_lossy(&assert.get_output().stdout).to_string();
    assert!(printed.contains("warnings (2):"), "{printed}");
    assert!(
        printed.contains("the DAF of strain_mid rests on its low_pass static part"),
        "{printed}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("measure.json")).unwrap()).unwrap();
    let kinds: Vec<&str> = json["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|w| w["kind"].as_str().unwrap())
        .collect();
    assert_eq!(
        kinds,
        ["static_method_not_valid", "static_method_not_valid",]
    );
    assert_eq!(json["warnings"][1]["channel"], "strain_mid");
    assert_eq!(json["identification"], "subspace_free_vibration");
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(
        html.contains("warnings (2)"),
        "the key results name the warnings"
    );
    assert!(
        html.contains("(95 %)"),
        "the key results give the DAF's interval"
    );

    let field = repository_root().join("examples/measurements/field_4x30/fast.toml");
    let out = dir.path().join("field");
    let json = super::common::check_and_measure(&field, &out);
    assert_eq!(json["warnings"].as_array().unwrap().len(), 0);
}

/// Issue 52: a crawl run corrected by an offset alone keeps its logger's drift in the static
/// part (the field example's crawl drifts by 0.4 µε/s over 57 s): a DAF on it is flagged.
#[test]
fn a_crawl_run_without_a_drift_correction_is_flagged() {
    let dir = tempfile::tempdir().unwrap();
    let field = repository_root().join("examples/measurements/field_4x30");
    for name in ["fast.toml", "fast.csv", "crawl.csv"] {
        std::fs::copy(field.join(name), dir.path().join(name)).unwrap();
    }
    let crawl = std::fs::read_to_string(field.join("crawl.toml")).unwrap();
    assert!(crawl.contains("baseline = \"linear\""));
    std::fs::write(
        dir.path().join("crawl.toml"),
        crawl.replace("baseline = \"linear\"", "baseline = \"offset\""),
    )
    .unwrap();
    let json =
        super::common::check_and_measure(&dir.path().join("fast.toml"), &dir.path().join("out"));
    let warnings = json["warnings"].as_array().unwrap();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert_eq!(warnings[0]["kind"], "crawl_baseline_without_drift");
    assert_eq!(warnings[0]["baseline"], "offset");
    assert_eq!(json["preparation"]["crawl"]["baseline"], "offset");
}

#[test]
fn the_two_span_example_with_a_bridge_model_recovers_its_simulation() {
    // Reference: examples/measurements/README.md (simulated DAF 1.0346 by `vbi run`, FE
    // frequencies 6.393 and 9.987 Hz by `vbi modes`).
    let example = repository_root().join("examples/measurements/synthetic_two_span.toml");
    vbi().arg("check").arg(&example).assert().success();
    let dir = tempfile::tempdir().unwrap();
    let report = measure_json(&example, dir.path());
    // The tolerances of the round-trip test below (same scenario, same noise level).
    let daf = report["channels"][0]["daf"].as_f64().unwrap();
    assert!((daf - 1.0346).abs() < 0.01, "{daf}");
    for (p, exact) in report["identified_frequencies"]
        .as_array()
        .unwrap()
        .iter()
        .zip([6.393, 9.987])
    {
        let f = p["frequency_hz"].as_f64().unwrap();
        assert!((f / exact - 1.0).abs() < 0.01, "{f}");
    }
    assert_eq!(report["channels"][0]["cutoff_mode"]["mode"], 3);
    let alpha = report["updating"]["stiffness_scale"].as_f64().unwrap();
    assert!((alpha - 1.0).abs() < 0.02, "{alpha}");
}

#[test]
fn format_json_prints_the_report() {
    let dir = tempfile::tempdir().unwrap();
    let path = write_case(
        dir.path(),
        "time_column = \"time_s\"\n[measurement.filter]\ncutoff_hz = 2.0\n",
        DEFLECTION,
        &good_csv(600),
    );
    let out = vbi()
        .arg("measure")
        .arg(&path)
        .args(["--format", "json", "--out"])
        .arg(dir.path().join("o"))
        .assert()
        .success();
    let json: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).unwrap();
    // A clean bump through a 2 Hz low-pass (its content lies below 1 Hz): DAF 1 within 0.5 %.
    assert!((json["channels"][0]["daf"].as_f64().unwrap() - 1.0).abs() < 0.005);
    assert_eq!(json["static_separation"]["rule"], "given");
}

#[test]
fn an_influence_line_static_reference_gives_daf_one_for_a_quasi_static_record() {
    // The record is exactly P·IL(v t): the static reference reproduces it, DAF = 1.
    let dir = tempfile::tempdir().unwrap();
    let mut csv = String::from("u\n");
    for i in 0..400 {
        let x = 10.0 * i as f64 / 100.0; // 10 m/s, 100 Hz
        let il = if x <= 20.0 {
            -0.01 * (x / 20.0 * std::f64::consts::PI).sin()
        } else {
            0.0
        };
        csv.push_str(&format!("{:.9}\n", 100.0 * il));
    }
    let positions: Vec<String> = (0..=40).map(|k| format!("{}", k as f64 * 0.5)).collect();
    let values: Vec<String> = (0..=40)
        .map(|k| {
            format!(
                "{:.12}",
                -0.01 * (k as f64 * 0.5 / 20.0 * std::f64::consts::PI).sin()
            )
        })
        .collect();
    let channel = format!(
        "{DEFLECTION}static_reference = {{ position_m = [{}], value_per_kn = [{}] }}\n",
        positions.join(","),
        values.join(",")
    );
    let keys = "sampling_rate_hz = 100.0\nspeed_m_s = 10.0\n[measurement.vehicle]\naxle_loads_kn = [100.0]\naxle_offsets_m = [0.0]\nentry_time_s = 0.0\n";
    let path = write_case(dir.path(), keys, &channel, &csv);
    let out = vbi()
        .arg("measure")
        .arg(&path)
        .args(["--format", "json", "--out"])
        .arg(dir.path().join("o"))
        .assert()
        .success();
    let json: serde_json::Value = serde_json::from_slice(&out.get_output().stdout).unwrap();
    assert_eq!(json["channels"][0]["static_method"], "influence_line");
    // Linear interpolation of a sine sampled every 0.5 m: peak error 1 − cos(π/80) ≈ 8e-4.
    assert!((json["channels"][0]["daf"].as_f64().unwrap() - 1.0).abs() < 1e-3);
}

#[test]
fn a_nan_sample_is_refused_with_its_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    let csv = replace_line(&good_csv(100), "0.10,", "0.10,NaN");
    let path = write_case(dir.path(), "time_column = \"time_s\"", DEFLECTION, &csv);
    let e = stderr_of(&path, "check");
    assert!(
        e.contains("m.csv:12:2") && e.contains("field `u`") && e.contains("finite"),
        "{e}"
    );
}

#[test]
fn an_empty_cell_is_refused_as_a_gap() {
    let dir = tempfile::tempdir().unwrap();
    let csv = replace_line(&good_csv(100), "0.10,", "0.10,");
    let path = write_case(dir.path(), "time_column = \"time_s\"", DEFLECTION, &csv);
    let e = stderr_of(&path, "measure");
    assert!(e.contains("m.csv:12:2") && e.contains("gap"), "{e}");
}

#[test]
fn time_going_back_or_jumping_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let back = good_csv(100).replace("\n0.10,", "\n0.08,");
    let path = write_case(dir.path(), "time_column = \"time_s\"", DEFLECTION, &back);
    let e = stderr_of(&path, "check");
    assert!(
        e.contains("does not increase") && e.contains("field `time_s`"),
        "{e}"
    );

    let gap: String = good_csv(100)
        .lines()
        .enumerate()
        .filter(|(i, _)| *i != 30)
        .map(|(_, l)| format!("{l}\n"))
        .collect();
    let path = write_case(dir.path(), "time_column = \"time_s\"", DEFLECTION, &gap);
    let e = stderr_of(&path, "check");
    assert!(e.contains("a gap") && e.contains("m.csv:31:1"), "{e}");
}

#[test]
fn a_sampling_rate_that_contradicts_the_time_column_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let path = write_case(
        dir.path(),
        "time_column = \"time_s\"\nsampling_rate_hz = 200.0",
        DEFLECTION,
        &good_csv(100),
    );
    let e = stderr_of(&path, "check");
    assert!(
        e.contains("m.toml:4:1") && e.contains("sampling_rate_hz") && e.contains("100.0000"),
        "{e}"
    );
}

#[test]
fn a_missing_channel_is_refused_naming_the_columns() {
    let dir = tempfile::tempdir().unwrap();
    let channels = DEFLECTION.replace("name = \"u\"", "name = \"w\"");
    let path = write_case(
        dir.path(),
        "time_column = \"time_s\"",
        &channels,
        &good_csv(100),
    );
    let e = stderr_of(&path, "check");
    assert!(
        e.contains("channel `w` is missing") && e.contains("time_s, u") && e.contains("m.toml:5"),
        "{e}"
    );
}

/// Issue 17, defect 7: a missing column echoed the first line of whatever file the measurement
/// named. A file whose first line is data (40 numbers) or holds control characters is described
/// by its cell count, not quoted; the channel and the file stay named.
#[test]
fn a_missing_column_does_not_echo_a_file_that_is_not_a_csv_with_a_header() {
    let dir = tempfile::tempdir().unwrap();
    let data_row: Vec<String> = (0..40).map(|i| format!("{}.123456", 1000 + i)).collect();
    let mut csv = String::new();
    for _ in 0..40 {
        csv.push_str(&data_row.join(","));
        csv.push('\n');
    }
    let path = write_case(dir.path(), "time_column = \"time_s\"", DEFLECTION, &csv);
    for command in ["check", "measure"] {
        let e = stderr_of(&path, command);
        assert!(e.contains("m.toml:"), "{command}: {e}");
        assert!(e.contains("40 cells"), "{command}: {e}");
        assert!(!e.contains("1000.123456"), "{command}: {e}");
    }
    let mut binary = String::from("time_s,u\u{1}\u{2}\u{7f}garbage\n");
    for i in 0..40 {
        binary.push_str(&format!("{:.2},1.0\n", i as f64 / 100.0));
    }
    let path = write_case(dir.path(), "time_column = \"time_s\"", DEFLECTION, &binary);
    let e = stderr_of(&path, "check");
    assert!(e.contains("channel `u` is missing"), "{e}");
    assert!(!e.contains("garbage"), "{e}");
}

#[test]
fn a_row_with_a_missing_field_and_a_wrong_unit_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let csv = replace_line(&good_csv(100), "0.10,", "0.10");
    let path = write_case(dir.path(), "time_column = \"time_s\"", DEFLECTION, &csv);
    let e = stderr_of(&path, "check");
    assert!(
        e.contains("m.csv:12") && e.contains("1 fields but the header has 2"),
        "{e}"
    );

    let channels = DEFLECTION.replace("unit = \"mm\"", "unit = \"inch\"");
    let path = write_case(
        dir.path(),
        "time_column = \"time_s\"",
        &channels,
        &good_csv(100),
    );
    let e = stderr_of(&path, "check");
    assert!(e.contains("unit `inch`") && e.contains("m, cm, mm"), "{e}");
}

#[test]
fn fitting_a_mass_scale_from_numbers_and_a_missing_bridge_are_refused_with_the_reason() {
    let dir = tempfile::tempdir().unwrap();
    let acc = "[[measurement.channels]]\nname = \"u\"\nkind = \"acceleration\"\nunit = \"g\"\n";
    let keys = "time_column = \"time_s\"\n[measurement.updating]\nmodel_frequencies_hz = [3.0]\nfit_mass = true\n";
    let path = write_case(dir.path(), keys, acc, &good_csv(100));
    let e = stderr_of(&path, "check");
    assert!(
        e.contains("fit_mass") && e.contains("cannot be identified"),
        "{e}"
    );

    let path = write_case(
        dir.path(),
        "time_column = \"time_s\"\nbridge = \"b.toml\"",
        DEFLECTION,
        &good_csv(100),
    );
    let e = stderr_of(&path, "check");
    assert!(
        e.contains("measurement.bridge") && e.contains("cannot read the bridge file"),
        "{e}"
    );

    // A cut-off mode number without a bridge model.
    let channels = format!("{DEFLECTION}k1_mode = 3\n");
    let path = write_case(
        dir.path(),
        "time_column = \"time_s\"",
        &channels,
        &good_csv(100),
    );
    let e = stderr_of(&path, "check");
    assert!(
        e.contains("channels[0].k1_mode") && e.contains("needs a bridge model"),
        "{e}"
    );

    // A mass scale of a bridge without added mass.
    std::fs::copy(
        repository_root().join("examples/bridges/two-span-beam.toml"),
        dir.path().join("b.toml"),
    )
    .unwrap();
    let keys =
        "time_column = \"time_s\"\nbridge = \"b.toml\"\n[measurement.updating]\nfit_mass = true\n";
    let path = write_case(dir.path(), keys, acc, &good_csv(100));
    let e = stderr_of(&path, "check");
    assert!(e.contains("no added (pavement) mass"), "{e}");
}

#[test]
fn without_cutoff_or_crossing_the_static_part_cannot_be_chosen() {
    let dir = tempfile::tempdir().unwrap();
    let path = write_case(
        dir.path(),
        "time_column = \"time_s\"",
        DEFLECTION,
        &good_csv(300),
    );
    let e = stderr_of(&path, "measure");
    assert!(
        e.contains("filter.cutoff_hz") && e.contains("cannot be chosen"),
        "{e}"
    );
}

/// The scenario of the round trip: the two-span beam of examples/bridges/two-span-beam.toml
/// (f₁ = 6.39 Hz, undamped), crossed by the sprung mass at 72 km/h on a smooth road, six
/// modes, Δt = 1 ms (an exact multiple of the 5 ms measurement interval), 8 s of free vibration.
/// Six modes, not fewer: `vbi run` divides by the exact static response, so the modal record
/// must carry the static deflection (with four modes its quasi-static part is 1.2 % short and
/// the simulated DAF drops to 1.022 while the record's own amplification is 1.036).
const ROUND_TRIP_SCENARIO: &str = r#"[scenario]
bridge = "bridge.toml"
vehicle = "sprung-mass"
road = "smooth"
speed_kmh = 72.0
modes = 6
element_length_m = 2.0
time_step_s = 0.001
free_vibration_s = 8.0
"#;

/// Standard deviation of the white Gaussian noise added to the sampled deflection [m]:
/// 0.3 µm, 0.2 % of the 0.139 mm static maximum (a good displacement transducer).
const ROUND_TRIP_NOISE_M: f64 = 0.3e-6;

/// Seeded standard normal numbers (Box–Muller on the crate's ChaCha20 stream).
fn gaussian_noise(seed: u64, count: usize) -> Vec<f64> {
    let mut rng = vbi::road::SampleRng::new(seed, 0);
    (0..count)
        .map(|_| {
            let u1 = 1.0 - rng.next_unit(); // (0, 1]: ln is finite
            let u2 = rng.next_unit();
            (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
        })
        .collect()
}

fn json_of(output: &assert_cmd::assert::Assert) -> serde_json::Value {
    serde_json::from_slice(&output.get_output().stdout).expect("JSON on stdout")
}

/// `vbi measure FILE --out DIR --format json`, which must succeed: its JSON report.
fn measure_json(
    file: impl AsRef<std::ffi::OsStr>,
    out: impl AsRef<std::ffi::OsStr>,
) -> serde_json::Value {
    json_of(
        &vbi()
            .arg("measure")
            .arg(file)
            .arg("--out")
            .arg(out)
            .args(["--format", "json"])
            .assert()
            .success(),
    )
}

#[test]
fn a_simulated_crossing_sampled_at_200_hz_with_noise_gives_back_its_daf_and_frequencies() {
    // Reference: the simulation itself (`vbi run`, summary.json) for the DAF and `vbi modes`
    // for the FE frequencies; the round trip of issue 7.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::copy(
        repository_root().join("examples/bridges/two-span-beam.toml"),
        d.join("bridge.toml"),
    )
    .unwrap();
    std::fs::write(d.join("s.toml"), ROUND_TRIP_SCENARIO).unwrap();
    vbi()
        .arg("run")
        .arg(d.join("s.toml"))
        .arg("--out")
        .arg(d.join("run"))
        .args(["--format", "json"])
        .assert()
        .success();
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("run/summary.json")).unwrap())
            .unwrap();
    let simulated_daf = summary["stations"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["name"] == "span1_mid_section" && s["quantity"] == "deflection")
        .expect("the mid-span deflection station")["daf"]
        .as_f64()
        .unwrap();

    // Sample the mid-span deflection at 200 Hz: every 5th row of the 1 ms history.
    let mut reader = csv::Reader::from_path(d.join("run/histories.csv")).unwrap();
    let header = reader.headers().unwrap().clone();
    let column = header
        .iter()
        .position(|h| h == "span1_mid_section_deflection_m")
        .unwrap();
    let rows: Vec<(f64, f64)> = reader
        .records()
        .map(|r| {
            let r = r.unwrap();
            (r[0].parse().unwrap(), r[column].parse().unwrap())
        })
        .collect();
    let sampling_rate = 200.0;
    let sampled: Vec<f64> = rows.iter().step_by(5).map(|r| r.1).collect();
    assert!((rows[5].0 - 1.0 / sampling_rate).abs() < 1e-9, "Δt = 1 ms");
    let noise = gaussian_noise(7, sampled.len());
    let deflection: Vec<f64> = sampled
        .iter()
        .zip(&noise)
        .map(|(u, n)| u + ROUND_TRIP_NOISE_M * n)
        .collect();
    // A vertical acceleration from the noisy deflection by the central second difference
    // a_i = (u_{i+1} − 2u_i + u_{i−1})·f_s²: it weights the spectrum by (2 sin(πf/f_s)·f_s)⁴
    // without moving its peaks, so the bridge frequencies stand out of the quasi-static part.
    let mut acceleration = vec![0.0; deflection.len()];
    for i in 1..deflection.len() - 1 {
        acceleration[i] = (deflection[i + 1] - 2.0 * deflection[i] + deflection[i - 1])
            * sampling_rate
            * sampling_rate;
    }
    let mut csv_text = String::from("time_s,deflection_mm,acceleration_m_s2\n");
    for (i, (u, a)) in deflection.iter().zip(&acceleration).enumerate() {
        csv_text.push_str(&format!(
            "{:.3},{:.9},{:.9e}\n",
            i as f64 / sampling_rate,
            u * 1e3,
            a
        ));
    }
    std::fs::write(d.join("m.csv"), csv_text).unwrap();
    std::fs::write(
        d.join("m.toml"),
        r#"[measurement]
csv = "m.csv"
time_column = "time_s"
speed_kmh = 72.0
bridge_length_m = 40.0
bridge = "bridge.toml"
# The whole record's spectral peaks (issue 7's round trip); the default, the entry found in
# the record and the free vibration after the exit, is checked at the end.
detect_entry = false
[measurement.filter]
k1_mode_deflection = 3
[measurement.spectrum]
segment_length = 512
fft_length = 8192
modes = 2
min_frequency_hz = 2.0
max_frequency_hz = 20.0
[[measurement.channels]]
name = "deflection_mid"
column = "deflection_mm"
kind = "deflection"
unit = "mm"
[[measurement.channels]]
name = "acceleration_mid"
column = "acceleration_m_s2"
kind = "acceleration"
unit = "m/s2"
[measurement.updating]
"#,
    )
    .unwrap();
    vbi().arg("check").arg(d.join("m.toml")).assert().success();
    let fe = fe_frequencies(&d.join("bridge.toml"), 3);
    let report = measure_json(d.join("m.toml"), d.join("measure"));

    // DAF. Measured 1.0330 against the simulated 1.0346. Tolerance 0.01,
    // the sum of two bounds: (i) the filter: the static part is the zero-phase low-pass at
    // f₁/2 = 3.2 Hz (order 4, |H|² = 1/257 at f₁), which keeps the low-frequency part of the
    // forced response (of order α² = (v/(2f₁L))² ≈ 0.6 % of the static deflection at this
    // speed parameter) and rounds the influence-line peak; the noise-free bias is −0.0017;
    // (ii) the noise: the dynamic maximum of a record with σ = 0.2 % of the static peak is
    // raised by at most about 3σ, 0.65 % of the DAF.
    let channel = &report["channels"][0];
    let measured_daf = channel["daf"].as_f64().unwrap();
    eprintln!(
        "round trip: simulated DAF {simulated_daf}, measured {measured_daf}, identified {}, FE {fe:?}, alpha {}",
        report["identified_frequencies"], report["updating"]["stiffness_scale"]
    );
    assert!(
        (measured_daf - simulated_daf).abs() < 0.01,
        "measured {measured_daf} vs simulated {simulated_daf}"
    );
    assert!(
        simulated_daf > 1.02,
        "the crossing is dynamic: {simulated_daf}"
    );
    // K1 = 3 taken from the model: the frequency of mode 3 of the (updated) model.
    let k1 = &channel["cutoff_mode"];
    assert_eq!(k1["source"], "model_mode");
    assert_eq!(k1["mode"], 3);
    let k1_hz = k1["mode_frequency_hz"].as_f64().unwrap();
    assert!((k1_hz / fe[2] - 1.0).abs() < 0.01, "{k1_hz} vs {}", fe[2]);
    // The filter passes mode K1 at 0.99: f_c = f_K1·99^{1/(2N)}, N = 4.
    let cutoff = k1["cutoff_hz"].as_f64().unwrap();
    assert!((cutoff / (k1_hz * 99f64.powf(1.0 / 8.0)) - 1.0).abs() < 1e-12);

    // Frequencies: the issue's requirement, within 1 % of the FE model (measured −0.21 % and
    // −0.02 %: the peak of a 2.56 s Welch segment refined by parabolic interpolation).
    let identified: Vec<f64> = report["identified_frequencies"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["frequency_hz"].as_f64().unwrap())
        .collect();
    assert_eq!(identified.len(), 2);
    for (got, exact) in identified.iter().zip(&fe) {
        assert!(
            (got / exact - 1.0).abs() < 0.01,
            "{got} Hz vs FE {exact} Hz"
        );
    }
    // Updating the very model that produced the record: α = 1 within 2 % (frequencies ∝ √α,
    // so twice the 1 % frequency tolerance).
    let alpha = report["updating"]["stiffness_scale"].as_f64().unwrap();
    assert!((alpha - 1.0).abs() < 0.02, "{alpha}");
    assert_eq!(
        report["bridge"]["stiffness_parameter"],
        "flexural_rigidity_n_m2"
    );
    // K1 from the run's DAF analysis instead: deck deflection K1 and its frequency.
    let toml = std::fs::read_to_string(d.join("m.toml")).unwrap().replace(
        "k1_mode_deflection = 3",
        "k1_from_run = \"run/summary.json\"",
    );
    std::fs::write(d.join("m.toml"), toml).unwrap();
    let report = measure_json(d.join("m.toml"), d.join("measure"));
    let k1 = &report["channels"][0]["cutoff_mode"];
    assert_eq!(k1["source"], "run_summary");
    let mode = summary["deck_participation"]["deflection_k1"]
        .as_u64()
        .unwrap();
    assert_eq!(k1["mode"].as_u64(), Some(mode));
    assert_eq!(
        k1["mode_frequency_hz"].as_f64(),
        summary["frequencies_hz"][mode as usize - 1].as_f64()
    );

    // The default (issue 52, item 2): the entry is found in the record, 100 m of approach at
    // 20 m/s, so 5.000 s, within 0.05 s (a metre: the template fit on a noisy record), and
    // the frequencies come from the free vibration after the exit only, where no forced
    // content can enter. The second mode's free vibration is under the noise of the
    // differentiated deflection there: the first mode within 1 % of the FE model.
    let toml = std::fs::read_to_string(d.join("m.toml"))
        .unwrap()
        .replace("detect_entry = false\n", "");
    std::fs::write(d.join("m.toml"), toml).unwrap();
    let report = measure_json(d.join("m.toml"), d.join("measure"));
    let entry = report["preparation"]["detected_entry"]["entry_time_s"]
        .as_f64()
        .unwrap();
    assert!((entry - 5.0).abs() < 0.05, "{entry}");
    assert_eq!(report["identification"], "subspace_free_vibration");
    let first = report["identified_frequencies"][0]["frequency_hz"]
        .as_f64()
        .unwrap();
    assert!((first / fe[0] - 1.0).abs() < 0.01, "{first} vs {}", fe[0]);
}

/// Frequencies [Hz] of `vbi modes --format json` on a bridge file.
fn fe_frequencies(bridge: &Path, modes: usize) -> Vec<f64> {
    let json = json_of(
        &vbi()
            .arg("modes")
            .arg(bridge)
            .args(["--modes", &modes.to_string(), "--format", "json"])
            .assert()
            .success(),
    );
    json["modes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m["frequency_hz"].as_f64().unwrap())
        .collect()
}

#[test]
fn updating_a_bridge_model_recovers_a_stiffness_scale_of_1_1_from_its_own_frequencies() {
    // Reference: the model itself. The "measured" acceleration is a sum of decaying sines at
    // the first two frequencies of the two-span beam with EI × 1.1 (from `vbi modes`); updating
    // the unmodified beam must give α = 1.1.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let base =
        std::fs::read_to_string(repository_root().join("examples/bridges/two-span-beam.toml"))
            .unwrap();
    std::fs::write(d.join("bridge.toml"), &base).unwrap();
    let stiffer = base.replace(
        "flexural_rigidity_n_m2 = 4.86535e10",
        "flexural_rigidity_n_m2 = 5.351885e10",
    );
    assert_ne!(stiffer, base);
    std::fs::write(d.join("stiffer.toml"), &stiffer).unwrap();
    let target = fe_frequencies(&d.join("stiffer.toml"), 2);
    let fs = 200.0;
    let mut csv_text = String::from("a\n");
    for i in 0..12000 {
        let t = i as f64 / fs;
        let a: f64 = target
            .iter()
            .map(|f| {
                let w = 2.0 * std::f64::consts::PI * f;
                (-0.005 * w * t).exp() * (w * t).sin()
            })
            .sum();
        csv_text.push_str(&format!("{a:.9e}\n"));
    }
    std::fs::write(d.join("m.csv"), csv_text).unwrap();
    let toml = r#"[measurement]
csv = "m.csv"
sampling_rate_hz = 200.0
bridge = "bridge.toml"
[measurement.spectrum]
segment_length = 4096
fft_length = 16384
modes = 2
min_frequency_hz = 2.0
max_frequency_hz = 20.0
[[measurement.channels]]
name = "a"
kind = "acceleration"
unit = "m/s2"
[measurement.updating]
"#;
    std::fs::write(d.join("m.toml"), toml).unwrap();
    let report = measure_json(d.join("m.toml"), d.join("o"));
    let alpha = report["updating"]["stiffness_scale"].as_f64().unwrap();
    eprintln!(
        "updating: alpha {alpha}, target {target:?}, {}",
        report["updating"]["pairs"]
    );
    // The peaks of 60 s of 0.5 %-damped sines are located to about 1e-4 relative (parabolic
    // interpolation on 0.012 Hz bins); α ∝ f², so 1e-3 leaves a margin of five.
    assert!((alpha / 1.1 - 1.0).abs() < 1e-3, "{alpha}");
    let ei = report["bridge"]["stiffness_updated"].as_f64().unwrap();
    assert!((ei / 5.351885e10 - 1.0).abs() < 1e-3, "{ei}");
    for (p, f) in report["updating"]["pairs"]
        .as_array()
        .unwrap()
        .iter()
        .zip(&target)
    {
        let updated = p["updated_hz"].as_f64().unwrap();
        assert!((updated / f - 1.0).abs() < 5e-4, "{updated} vs {f}");
    }
}

#[test]
fn a_field_record_with_drift_and_a_crawl_run_gives_back_the_simulated_dafs() {
    // Reference: examples/measurements/field_4x30 (generate.py prints the exact answers of the
    // noise-free, drift-free simulated record: DAF_u 1.0882, DAF_M 1.0132, RDM 1.0741; the
    // logger drift it adds is +0.010 mm/s and +0.4 µε/s). The issue's requirements: both DAFs
    // within 0.01, the sign of RDM − 1 right, K1 filtering changing a DAF by less than 0.3 %.
    let example = repository_root().join("examples/measurements/field_4x30/fast.toml");
    vbi().arg("check").arg(&example).assert().success();
    let dir = tempfile::tempdir().unwrap();
    let report = measure_json(&example, dir.path());
    let channels = report["channels"].as_array().unwrap();
    let daf = |i: usize| channels[i]["daf"].as_f64().unwrap();
    assert_eq!(channels[0]["static_method"], "crawl_run");
    assert!((daf(0) - 1.0882).abs() < 0.01, "deflection DAF {}", daf(0));
    assert!((daf(1) - 1.0132).abs() < 0.01, "strain DAF {}", daf(1));
    let rdm = report["rdm"][0]["rdm"].as_f64().unwrap();
    assert!(rdm > 1.0, "RDM {rdm}: the exact 1.0741 is above 1");
    for c in channels {
        let change = c["cutoff_mode"]["relative_change"].as_f64().unwrap();
        assert!(change.abs() < 0.003, "{}: {change}", c["name"]);
    }
    // The linear baseline: the drift found within 2 % of the one added (the means of 1 s
    // windows of noise σ = 5 µm over 200 samples, and of the decayed free vibration).
    let corrections = &report["preparation"]["corrections"];
    let drift = |i: usize| corrections[i]["drift_per_s"].as_f64().unwrap();
    assert!((drift(0) / 0.010 - 1.0).abs() < 0.02, "{}", drift(0));
    assert!((drift(1) / 0.4 - 1.0).abs() < 0.02, "{}", drift(1));
}
