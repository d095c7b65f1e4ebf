//! The load-test battery's truth and its best static methods (issue 52, item 1):
//! `scripts/measure_battery` on its clean anchor records (no noise, drift or jitter), with the
//! binary under test. Each record is a `vbi run` crossing and its truth that run's converged DAF
//! at the gauge; `vbi measure` must recover it where the record allows an exact static part:
//! the crawl run's deflection (a01, a02) within 10⁻⁴ (the crawl sampled at 50 Hz and low-passed
//! at f₁/2 keeps a smooth deflection line), the crawl-calibrated influence line's strain within
//! 2·10⁻³ (the crawl's low-pass rounds the kink of the moment's line), and the bridge model's
//! influence line (a03) within 10⁻⁴ for the deflection and 2·10⁻³ for the strain. The first
//! identified frequency of the records that keep their free vibration (a01, a02) lies within
//! 0.1 % of the model's. The whole battery (100 records, with today's defaults' bias and
//! coverage) is docs/verification.md §29a; it runs in a minute with a release build.

use serde_json::Value;

use super::common::repository_root;

fn method_error(channel: &Value, method: &str) -> f64 {
    channel["every_method"]
        .as_array()
        .unwrap()
        .iter()
        .find(|m| m["method"] == method)
        .unwrap_or_else(|| panic!("no {method} in {channel}"))["error"]
        .as_f64()
        .unwrap()
}

#[test]
fn the_batterys_clean_records_give_back_their_simulated_daf_by_the_exact_static_parts() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("battery");
    let vbi = assert_cmd::cargo::cargo_bin("vbi");
    let done = std::process::Command::new("python3")
        .arg(repository_root().join("scripts/measure_battery"))
        .args([
            "--vbi",
            vbi.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ])
        .args(["--cases", "a01", "a02", "a03"])
        .output()
        .expect("python3 runs (the test command needs CPython 3, as CI has)");
    assert!(
        done.status.success(),
        "{}{}",
        String::from_utf8_lossy(&done.stdout),
        String::from_utf8_lossy(&done.stderr)
    );
    let battery: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("battery.json")).unwrap()).unwrap();
    let cases = battery["cases"].as_array().unwrap();
    assert_eq!(cases.len(), 3);
    for case in cases {
        let name = case["case"]["name"].as_str().unwrap();
        let score = &case["score"];
        assert_eq!(score["returncode"], 0, "{name}: {score}");
        let channel = |kind: &str| {
            score["channels"]
                .as_array()
                .unwrap()
                .iter()
                .find(|c| c["channel"] == kind)
                .unwrap_or_else(|| panic!("{name}: no {kind} channel"))
                .clone()
        };
        let (deflection, strain) = (channel("deflection"), channel("strain"));
        if name == "a03" {
            let u = method_error(&deflection, "influence_line_model");
            let m = method_error(&strain, "influence_line_model");
            assert!(u.abs() < 1e-4 && m.abs() < 2e-3, "{name}: {u} {m}");
        } else {
            let u = method_error(&deflection, "crawl_run");
            let m = method_error(&strain, "influence_line_crawl");
            assert!(u.abs() < 1e-4 && m.abs() < 2e-3, "{name}: {u} {m}");
            let f1 = score["first_frequency"]["relative_error"].as_f64().unwrap();
            assert!(f1.abs() < 1e-3, "{name}: f1 off by {f1}");
        }
    }
}
