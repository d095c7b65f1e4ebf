//! End-to-end tests of influence lines as static references (`static_reference = "model"` and
//! `"crawl"`) and of resampling (`resample_hz`), on the SYNTHETIC load test of the paper's
//! 3 × 30 m bridge (examples/measurements/paper_bridges/3x30, truth.json from the noise-free
//! run), and the refusals of `vbi check` and `vbi measure` alike.

use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::common::{check_and_measure as measure, repository_root, vbi};

fn folder() -> PathBuf {
    repository_root().join("examples/measurements/paper_bridges/3x30")
}

fn truth() -> Value {
    serde_json::from_str(&std::fs::read_to_string(folder().join("truth.json")).unwrap()).unwrap()
}

fn channel<'a>(report: &'a Value, name: &str) -> &'a Value {
    report["channels"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["name"] == name)
        .unwrap_or_else(|| panic!("channel {name}"))
}

fn number(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// The DAF of `method` among a channel's static methods, and whether it counts as valid.
fn method(c: &Value, name: &str) -> (f64, bool) {
    let m = c["static_methods"]
        .as_array()
        .unwrap()
        .iter()
        .find(|m| m["method"] == name)
        .unwrap_or_else(|| panic!("method {name} in {}", c["static_methods"]));
    (number(&m["daf"]), m["valid"].as_bool().unwrap())
}

#[test]
fn model_and_crawl_influence_lines_give_the_simulated_daf_within_the_issue_tolerance() {
    // influence_lines.toml: the deflection's line from the bridge model at the gauge, the
    // strain's calibrated from the crawl run. Requirement (issue 18): within 0.01 of the truth.
    // The crawl-calibrated strain DAF also lies within its stated 95 % uncertainty (its
    // measured error is 0.0003 against ± 0.0051); the model's deflection DAF errs by 0.0049,
    // at its 95 % bound: the upward bias of a noisy maximum (σ = 5 µm on 2.9 mm) and the mean
    // track width of the truck's axles (2.0, 1.85, 1.85 m read as 1.9 m).
    let dir = tempfile::tempdir().unwrap();
    let report = measure(&folder().join("influence_lines.toml"), dir.path());
    let truth = truth();
    let deflection = channel(&report, "deflection");
    let strain = channel(&report, "strain");
    assert_eq!(deflection["static_method"], "influence_line_model");
    assert_eq!(strain["static_method"], "influence_line_crawl");
    let exact_u = number(&truth["daf_deflection"]);
    let exact_m = number(&truth["daf_moment"]);
    assert!((number(&deflection["daf"]) - exact_u).abs() < 0.01);
    assert!((number(&strain["daf"]) - exact_m).abs() < 0.01);
    assert!(
        (number(&strain["daf"]) - exact_m).abs() <= number(&strain["uncertainty"]["expanded_95"])
    );
    // Every method the record allows is compared: the unfitted model's line is shown but does
    // not count among the valid methods; the crawl's line does, and agrees with the crawl run
    // low-passed within 0.003.
    let (_, model_valid) = method(deflection, "influence_line_model");
    assert!(!model_valid);
    for c in [deflection, strain] {
        let (crawl_line, crawl_line_valid) = method(c, "influence_line_crawl");
        let (crawl_run, _) = method(c, "crawl_run");
        assert!(crawl_line_valid);
        assert!(
            (crawl_line - crawl_run).abs() < 0.003,
            "{crawl_line} against {crawl_run}"
        );
    }
    // The RDM's side of 1 is the truth's.
    let rdm = number(&report["rdm"][0]["rdm"]);
    assert!((rdm - 1.0).signum() == (number(&truth["rdm"]) - 1.0).signum());
}

/// fast.toml and its CSV (with the crawl run) copied into `dir`, the CSV's times jittered by
/// up to ± `jitter` of the 5 ms interval (a fixed-seed linear congruential sequence), the
/// TOML's `[measurement]` given the `extra` lines.
fn jittered_copy(dir: &Path, jitter: f64, extra: &str) -> PathBuf {
    for name in ["crawl.toml", "crawl.csv"] {
        std::fs::copy(folder().join(name), dir.join(name)).unwrap();
    }
    let mut state: u64 = 18;
    let mut next = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let csv = std::fs::read_to_string(folder().join("fast.csv")).unwrap();
    let mut out = String::new();
    for line in csv.lines() {
        match line.split_once(',') {
            Some((t, rest)) if t.parse::<f64>().is_ok() => {
                let t: f64 = t.parse().unwrap();
                let shifted = t + jitter * 0.005 * (2.0 * next() - 1.0);
                out.push_str(&format!("{shifted:.6},{rest}\n"));
            }
            _ => out.push_str(&format!("{line}\n")),
        }
    }
    std::fs::write(dir.join("fast.csv"), out).unwrap();
    let toml = std::fs::read_to_string(folder().join("fast.toml")).unwrap();
    let toml = toml.replacen("[measurement]\n", &format!("[measurement]\n{extra}\n"), 1);
    let path = dir.join("fast.toml");
    std::fs::write(&path, toml).unwrap();
    path
}

#[test]
fn a_jittered_logger_clock_resampled_to_its_rate_gives_the_dafs_of_the_uniform_record() {
    // Reference: fast.toml on its uniform CSV. Times jittered by ± 10 % of the interval and
    // resampled to 200 Hz: the DAFs move by the interpolation of the peaks (a 3.7 Hz response
    // at 200 Hz: (2π·3.7/200)³/12 ≈ 1.7e-4 of the amplitude) and the shift of the samples,
    // within 0.002 (a fifth of the issue's 0.01); the first three frequencies within 0.1 %.
    let reference_dir = tempfile::tempdir().unwrap();
    let reference = measure(&folder().join("fast.toml"), reference_dir.path());
    let dir = tempfile::tempdir().unwrap();
    let path = jittered_copy(dir.path(), 0.1, "resample_hz = 200.0");
    let report = measure(&path, &dir.path().join("out"));
    assert_eq!(number(&report["sampling_rate_hz"]), 200.0);
    let from = number(&report["preparation"]["resampled_from_hz"]);
    assert!((from / 200.0 - 1.0).abs() < 1e-3, "{from}");
    for name in ["deflection", "strain"] {
        let (a, b) = (channel(&reference, name), channel(&report, name));
        let change = number(&a["daf"]) - number(&b["daf"]);
        assert!(change.abs() < 0.002, "{name}: {change}");
    }
    for k in 0..3 {
        let f = |r: &Value| number(&r["identified_frequencies"][k]["frequency_hz"]);
        assert!((f(&report) / f(&reference) - 1.0).abs() < 1e-3);
    }
}

#[test]
fn a_jittered_record_without_resample_hz_is_refused_at_its_line_naming_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let path = jittered_copy(dir.path(), 0.1, "");
    let out = vbi().arg("check").arg(&path).assert().code(2);
    let e = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(e.contains("fast.csv:") && e.contains("resample_hz"), "{e}");
}

/// The channel block of fast.toml's deflection channel given `reference`, with `extra`
/// [measurement] lines; `vbi check` and `vbi measure` must refuse it alike (exit 2) with a
/// message holding every needle.
fn assert_refused(extra: &str, reference: &str, needles: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let path = jittered_copy(dir.path(), 0.0, extra);
    let toml = std::fs::read_to_string(&path).unwrap().replacen(
        "section = \"span1_mid\"\n",
        &format!("section = \"span1_mid\"\n{reference}\n"),
        1,
    );
    std::fs::write(&path, toml).unwrap();
    let check = vbi().arg("check").arg(&path).assert().code(2);
    let check = String::from_utf8_lossy(&check.get_output().stderr).to_string();
    let run = vbi()
        .arg("measure")
        .arg(&path)
        .arg("--out")
        .arg(dir.path().join("out"))
        .assert()
        .code(2);
    let run = String::from_utf8_lossy(&run.get_output().stderr).to_string();
    for needle in needles {
        assert!(check.contains(needle), "`{needle}` not in: {check}");
        assert!(run.contains(needle), "`{needle}` not in: {run}");
    }
}

#[test]
fn influence_line_references_that_lack_what_they_need_are_refused_with_what_is_allowed() {
    assert_refused(
        "",
        "static_reference = \"model\"",
        &["channels[0].static_reference", "bridge ="],
    );
    let bridge = repository_root().join("examples/bridges/paper-3x30.toml");
    assert_refused(
        &format!("bridge = {:?}", bridge.display().to_string()),
        "static_reference = \"model\"",
        &["channels[0].static_reference", "position_m"],
    );
    assert_refused(
        "",
        "static_reference = \"measured\"",
        &["\"measured\"", "\"model\", \"crawl\""],
    );
    assert_refused("resample_hz = 0.5", "", &["measurement.resample_hz"]);
    // A gauge's position_in_span must agree with its position_m in the loaded span.
    assert_refused(
        "",
        "position_m = 15.0\nposition_in_span = 0.3",
        &["channels[0].position_in_span", "0.500 of span 1"],
    );
}
