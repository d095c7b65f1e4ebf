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
        // The requirement: bridge frequencies within 1 %.
        assert!((got / exact - 1.0).abs() < 0.01, "{got} vs {exact}");
    }
    let alpha = json["updating"]["stiffness_scale"].as_f64().unwrap();
    // Closed form √α = Σf f̂/Σf² with f̂ within 1 %: α within 2 % of (3.62/3.40)².
    assert!(
        (alpha / (3.62f64 / 3.40).powi(2) - 1.0).abs() < 0.02,
        "{alpha}"
    );
    assert_eq!(json["rdm"].as_array().unwrap().len(), 1);
    assert_eq!(json["static_separation"]["rule"], "geometric_mean");
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
fn fitting_a_mass_scale_from_numbers_and_a_bridge_reference_are_refused_with_the_reason() {
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
        e.contains("measurement.bridge") && e.contains("not supported yet"),
        "{e}"
    );
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
