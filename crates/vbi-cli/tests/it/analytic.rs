//! End-to-end tests of `vbi analytic` and its inputs.

use crate::common::vbi;

fn json(args: &[&str]) -> serde_json::Value {
    let out = vbi()
        .arg("analytic")
        .args(args)
        .args(["--format", "json"])
        .assert()
        .success();
    serde_json::from_slice(&out.get_output().stdout).expect("valid JSON on stdout")
}

#[test]
fn json_output_has_the_documented_keys_indexed_by_k_minus_one() {
    let v = json(&["--modes", "6", "--output-times", "200"]);
    for key in [
        "daf_deflection_by_modes",
        "daf_moment_by_modes",
        "rdm_by_modes",
        "frequencies_hz",
    ] {
        let array = v[key].as_array().unwrap_or_else(|| panic!("{key} missing"));
        assert_eq!(array.len(), 6, "{key}");
    }
    // α = v/(2 f₁ l) for the defaults: 80 km/h, l = 20 m, f₁ = π/(2l²)√(EI/m̄).
    let f1 = std::f64::consts::PI / (2.0 * 400.0) * (3.24e10_f64 / 2.0e4).sqrt();
    let alpha = 80.0 / 3.6 / (2.0 * f1 * 20.0);
    assert!((v["alpha"].as_f64().unwrap() - alpha).abs() < 1e-12);
    assert_eq!(v["static_reference"], "envelope");
    assert_eq!(v["window"], "load-on-beam");
}

#[test]
fn rdm_of_one_mode_is_the_papers_312_over_23_pi_squared() {
    // Reference: docs/verification.md §3 and the paper's Eq. 18: RDM(1) = 1.374444 with
    // the load-at-section statics, 1.37096 with the envelope.
    let v = json(&[
        "--modes",
        "1",
        "--static-reference",
        "load-at-section",
        "--alpha",
        "0.2",
    ]);
    let rdm = v["rdm_by_modes"][0].as_f64().unwrap();
    // One mode: exact up to round-off.
    assert!(
        (rdm - 312.0 / (23.0 * std::f64::consts::PI.powi(2))).abs() < 1e-12,
        "{rdm}"
    );
    let v = json(&["--modes", "1"]);
    // Reference value quoted to 6 significant digits.
    assert!((v["rdm_by_modes"][0].as_f64().unwrap() - 1.37096).abs() < 5e-6);
}

#[test]
fn alpha_sets_the_speed_parameter() {
    let v = json(&["--alpha", "0.25", "--modes", "2", "--spans", "3"]);
    assert!((v["alpha"].as_f64().unwrap() - 0.25).abs() < 1e-12);
    assert_eq!(v["frequencies_hz"].as_array().unwrap().len(), 2);
}

#[test]
fn table_output_names_the_static_reference_and_the_window() {
    let out = vbi()
        .args(["analytic", "--modes", "3", "--free-vibration", "0.5"])
        .assert()
        .success();
    let text = String::from_utf8_lossy(&out.get_output().stdout).to_string();
    assert!(text.contains("static reference: envelope"), "{text}");
    assert!(text.contains("0.5 s of free vibration"), "{text}");
    assert!(text.contains("DAF_u"), "{text}");
}

#[test]
fn bad_options_exit_2_naming_the_option() {
    for (args, option) in [
        (vec!["--spans", "0"], "--spans"),
        (vec!["--damping", "1.5"], "--damping"),
        (vec!["--section", "2.5"], "--section"),
        (vec!["--section", "0"], "--section"),
        (vec!["--section", "2.0"], "--section"),
        (vec!["--speed-kmh", "-3"], "--speed-kmh"),
        (vec!["--modes", "0"], "--modes"),
        (vec!["--ei", "nan"], "--ei"),
        (vec!["--free-vibration", "1e6"], "--free-vibration"),
    ] {
        let out = vbi().arg("analytic").args(&args).assert().code(2);
        let stderr = String::from_utf8_lossy(&out.get_output().stderr).to_string();
        assert!(stderr.contains(option), "{args:?}: {stderr}");
        assert!(stderr.contains("<command line>"), "{args:?}: {stderr}");
    }
    // clap's own usage errors also exit 2.
    vbi()
        .args(["analytic", "--speed-kmh", "80", "--alpha", "0.1"])
        .assert()
        .code(2);
    vbi().args(["analytic", "--format", "xml"]).assert().code(2);
}

#[test]
fn out_writes_csv_json_and_the_figure() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("result");
    vbi()
        .args(["analytic", "--modes", "5", "--output-times", "200", "--out"])
        .arg(&out)
        .assert()
        .success();
    for name in [
        "analytic.csv",
        "analytic.json",
        "analytic_daf.png",
        "analytic_daf.svg",
    ] {
        let path = out.join(name);
        let size = std::fs::metadata(&path)
            .unwrap_or_else(|_| panic!("{name} written"))
            .len();
        assert!(size > 0, "{name} is empty");
    }
    let csv = std::fs::read_to_string(out.join("analytic.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some(
            "modes,frequency_hz,daf_deflection,daf_moment,rdm,daf_deflection_static_corrected,\
             daf_moment_static_corrected,rdm_static_corrected"
        )
    );
    assert_eq!(lines.count(), 5);
}

/// `--free-vibration 1000` (issue 17, defect 2) gives the DAFs of a short window, not the 0.057
/// that 1000 instants spread over 1000 s gave: the damped response is gone long before.
#[test]
fn a_long_free_vibration_window_gives_the_short_windows_dafs() {
    let long = json(&["--modes", "6", "--free-vibration", "1000"]);
    let short = json(&["--modes", "6", "--free-vibration", "2"]);
    for key in ["daf_deflection_by_modes", "daf_moment_by_modes"] {
        let (a, b) = (
            long[key][5].as_f64().unwrap(),
            short[key][5].as_f64().unwrap(),
        );
        assert!((a - b).abs() < 1e-7, "{key}: {a} against {b}");
    }
    assert!(long["daf_deflection_by_modes"][5].as_f64().unwrap() > 1.0);
}

/// Issue 46, item 4: `--section` at an interior support (x/l = 1 of two spans) was refused
/// ("the static deflection is zero there"). It now gives the hogging moment's DAF of the paper's
/// §2, says that the deflection's DAF and the RDM are undefined there, and writes them as
/// empty cells (never a NaN).
#[test]
fn an_interior_support_gives_the_hogging_moment_daf_and_no_deflection_daf() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("support");
    let out = vbi()
        .args([
            "analytic",
            "--spans",
            "2",
            "--section",
            "1",
            "--modes",
            "5",
            "--out",
        ])
        .arg(&out_dir)
        .assert()
        .success();
    let text = String::from_utf8_lossy(&out.get_output().stdout).to_string();
    assert!(text.contains("DAF_u and RDM are undefined"), "{text}");
    assert!(text.contains("hogging moment"), "{text}");
    let csv = std::fs::read_to_string(out_dir.join("analytic.csv")).unwrap();
    // The row of five modes (mode 1 of two equal spans is antisymmetric: no curvature at the
    // middle support, so the plain sum of one mode is zero there; the static-corrected one is
    // the static moment).
    let last = csv.lines().nth(5).expect("a row for five modes");
    let cells: Vec<&str> = last.split(',').collect();
    for undefined in [2, 4, 5, 7] {
        assert_eq!(cells[undefined], "", "column {undefined}: {last}");
    }
    let moment: f64 = cells[6].parse().expect("the hogging moment's DAF");
    assert!(moment > 1.0 && moment < 1.5, "{last}");
    assert!(!csv.to_lowercase().contains("nan"), "{csv}");
    let json = std::fs::read_to_string(out_dir.join("analytic.json")).unwrap();
    assert!(json.contains("\"deflection_defined\": false"), "{json}");
}
