//! Bridge weigh-in-motion (`[measurement.weighing]`, issue 52 item 6) end to end: the SYNTHETIC
//! load test of the paper's 3 × 30 m bridge (examples/measurements/paper_bridges/3x30, whose
//! truck is the three-axle-truck-36t preset), a batch's COST 323 classes, and the refusals of
//! `vbi check` and `vbi measure` alike.

use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::common::{check_and_measure as measure, repository_root, vbi};

/// The truck's static axle loads [kN], front first: the wheels' static loads of the preset
/// that fast_scenario.toml drives (`vbi vehicle show three-axle-truck-36t`), summed per axle.
fn axle_loads_kn() -> Vec<f64> {
    let done = vbi()
        .args([
            "vehicle",
            "show",
            "three-axle-truck-36t",
            "--format",
            "json",
        ])
        .assert()
        .success();
    let json: Value = serde_json::from_slice(&done.get_output().stdout).unwrap();
    let mut axles: Vec<(f64, f64)> = Vec::new();
    for wheel in json["wheels"].as_array().unwrap() {
        let x = -number(&wheel["longitudinal_offset_m"]);
        let load = number(&wheel["static_load_n"]) / 1e3;
        match axles.iter_mut().find(|(at, _)| (at - x).abs() < 1e-9) {
            Some(axle) => axle.1 += load,
            None => axles.push((x, load)),
        }
    }
    axles.sort_by(|a, b| a.0.total_cmp(&b.0));
    axles.into_iter().map(|(_, load)| load).collect()
}

fn folder() -> PathBuf {
    repository_root().join("examples/measurements/paper_bridges/3x30")
}

fn number(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// `weighing.toml` with the vehicle's axle loads given, written next to a copy of its record.
fn with_given_loads(dir: &Path, speed_note: &str) -> PathBuf {
    let text = std::fs::read_to_string(folder().join("weighing.toml"))
        .unwrap()
        .replace(
            "csv = \"fast.csv\"",
            &format!("csv = {:?}", folder().join("fast.csv")),
        )
        .replace(
            "bridge = \"../../../bridges/paper-3x30.toml\"",
            &format!(
                "bridge = {:?}",
                repository_root().join("examples/bridges/paper-3x30.toml")
            ),
        )
        .replace(
            "axle_offsets_m = [0.0, 3.8, 5.15]",
            &format!(
                "axle_loads_kn = {:?}\naxle_offsets_m = [0.0, 3.8, 5.15]",
                axle_loads_kn()
            ),
        );
    assert!(text.contains("axle_loads_kn"));
    let path = dir.join(format!("weighing_{speed_note}.toml"));
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn the_3x30_record_weighs_the_truck_within_2_percent_and_its_axle_groups_within_5_percent() {
    // Reference: the static axle loads the simulated crossing carries (78.12 kN, then the
    // tandem 139.20 + 135.84 kN, 1.35 m apart). Measured: gross +1.7 %, steer −2.5 %, tandem
    // axles 141.5 kN each (shared equally by default). Tolerances: 2 % on the gross weight, the
    // low-frequency amplification of the bridge's response at 80 km/h that the least squares
    // read as weight (the battery's class-A records above 80 km/h: +2.2 % on average,
    // docs/verification.md §29b), not the 1 %, which this record does not meet; 5 % on
    // the axles, the tandem's equal shares against its true 139.20/135.84 split (±1.2 %) and
    // the same amplification.
    let dir = tempfile::tempdir().unwrap();
    let report = measure(&folder().join("weighing.toml"), dir.path());
    let w = &report["weighing"];
    let gross_kn = number(&w["gross_weight_n"]) / 1e3;
    let exact_axles = axle_loads_kn();
    let exact: f64 = exact_axles.iter().sum();
    assert!((gross_kn / exact - 1.0).abs() < 0.02, "{gross_kn} kN");
    let axles: Vec<f64> = w["axle_loads_n"]
        .as_array()
        .unwrap()
        .iter()
        .map(|a| number(a) / 1e3)
        .collect();
    for (weighed, exact) in axles.iter().zip(exact_axles) {
        assert!(
            (weighed / exact - 1.0).abs() < 0.05,
            "{weighed} vs {exact} kN"
        );
    }
    assert_eq!(w["shared_groups"], serde_json::json!([[2, 3]]));
    assert_eq!(w["entry_time_fitted"], false, "entry_time_s is given");
    assert_eq!(w["against_given"], Value::Null);
    assert_eq!(w["axle_loads_n"].as_array().unwrap().len(), 3);
    let kinds: Vec<&str> = report["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|w| w["kind"].as_str().unwrap())
        .collect();
    assert!(kinds.contains(&"static_part_on_weighed_loads"), "{kinds:?}");
    assert!(kinds.contains(&"weighing_on_unfitted_model"), "{kinds:?}");
    for c in w["channels"].as_array().unwrap() {
        assert_eq!(c["line_source"], "influence_line_model_unfitted");
    }
    // The model's deflection is upwards positive, and the record's (deflection_mm, negative
    // under the truck as its static maximum −2.69 mm shows) too: no flip; the strain gauge
    // reads the sagging moment, positive in both.
    let first_static = number(&report["channels"][0]["static_max"]);
    assert!(first_static < 0.0, "{first_static}");
    assert_eq!(w["channels"][0]["line_sign"], 1.0);
    assert_eq!(w["channels"][1]["line_sign"], 1.0);
}

#[test]
fn low_pass_true_filters_the_record_and_the_lines_at_0_7_times_the_models_first_frequency() {
    // `[measurement.weighing] low_pass = true` on the shipped record: the cut-off is 0.7 × the
    // bridge model's first vertical bending frequency (measure.json's bridge.frequencies_hz,
    // the model's first mode being its first bending one on this grillage), printed on screen
    // and in measure.json; the gross weight stays within the unfiltered test's 2 %
    // (the filter only takes the bridge's vibration out).
    let dir = tempfile::tempdir().unwrap();
    let file = with_given_loads(dir.path(), "low_pass");
    let text = std::fs::read_to_string(&file).unwrap().replace(
        "[measurement.weighing]",
        "[measurement.weighing]\nlow_pass = true",
    );
    std::fs::write(&file, text).unwrap();
    let out = dir.path().join("out");
    let report = measure(&file, &out);
    let w = &report["weighing"];
    let first = number(&report["bridge"]["frequencies_hz"][0]);
    let cutoff = number(&w["low_pass_hz"]);
    let fraction = vbi::measure::WEIGHING_CUTOFF_FRACTION;
    assert!(
        (cutoff / (fraction * first) - 1.0).abs() < 1e-12,
        "{cutoff} Hz, f1 {first} Hz"
    );
    let gross = number(&w["gross_weight_n"]) / 1e3;
    let exact: f64 = axle_loads_kn().iter().sum();
    assert!((gross / exact - 1.0).abs() < 0.02, "{gross} kN");
    let printed = vbi()
        .arg("measure")
        .arg(&file)
        .arg("--out")
        .arg(dir.path().join("printed"))
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let printed = String::from_utf8(printed).unwrap();
    assert!(
        printed.contains(&format!("record and lines low-passed at {cutoff:.2} Hz")),
        "{printed}"
    );
    // Without the key, no filter.
    let plain = measure(
        &with_given_loads(dir.path(), "plain"),
        &dir.path().join("plain"),
    );
    assert_eq!(plain["weighing"]["low_pass_hz"], Value::Null);
}

#[test]
fn a_batch_of_weighings_against_given_loads_gets_its_cost_323_classes_from_ten_runs() {
    // Ten runs of the same record (vbi classes a criterion from ten results): their errors are
    // equal, so the standard deviation is zero and the class follows from the mean error alone.
    // Reference: the COST 323 tolerance table (gross weight A(5) = ±5 %): the gross weight's
    // +1.7 % reaches A(5). Two runs are not classed: π₀ falls below zero at three results
    // (r2, environment I), where any errors would reach A(5).
    let dir = tempfile::tempdir().unwrap();
    let runs: Vec<PathBuf> = (0..10)
        .map(|k| with_given_loads(dir.path(), &format!("run{k}")))
        .collect();
    let batch = |count: usize, name: &str| -> (String, Value) {
        let out = dir.path().join(name);
        let done = vbi()
            .arg("measure")
            .args(&runs[..count])
            .arg("--out")
            .arg(&out)
            .assert()
            .success();
        let printed = String::from_utf8_lossy(&done.get_output().stdout).to_string();
        let json = std::fs::read_to_string(out.join("measurements.json")).unwrap();
        (printed, serde_json::from_str(&json).unwrap())
    };
    let (printed, two) = batch(2, "two");
    assert!(
        printed.contains("not classed: fewer than 10 results"),
        "{printed}"
    );
    assert_eq!(two["weighing_accuracy"]["criteria"], serde_json::json!([]));
    assert_eq!(two["weighing_accuracy"]["class"], Value::Null);
    let (printed, ten) = batch(10, "ten");
    assert!(
        printed.contains("weighing accuracy (COST 323, 10 weighings"),
        "{printed}"
    );
    let accuracy = &ten["weighing_accuracy"];
    assert_eq!(accuracy["weighings"], 10);
    assert_eq!(accuracy["test_conditions"], "extended_repeatability");
    let gross = accuracy["criteria"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["criterion"] == "gross_weight")
        .expect("the gross weight's class");
    assert_eq!(gross["class"], "A(5)");
    assert!(number(&gross["mean_percent"]).abs() < 2.0);
    // Each run's weighing compares with the given loads.
    let run = &ten["runs"][0]["measure"]["weighing"]["against_given"];
    assert!(number(&run["gross_weight_error"]).abs() < 0.02);
}

/// Weighing's refusals, each by `vbi check` and `vbi measure` alike (exit code 2, the field
/// named): the given-loads copy of weighing.toml with one edit each.
#[test]
fn weighing_refusals_are_the_same_in_check_and_measure() {
    let dir = tempfile::tempdir().unwrap();
    let base = std::fs::read_to_string(with_given_loads(dir.path(), "base")).unwrap();
    let without = |prefixes: &[&str]| {
        base.lines()
            .filter(|l| !prefixes.iter().any(|p| l.starts_with(p)))
            .collect::<Vec<_>>()
            .join("\n")
    };
    let cases: Vec<(&str, String, &str)> = vec![
        (
            "no line: no bridge model, no static_reference",
            without(&["bridge = ", "static_reference"]),
            "`measurement.weighing`",
        ),
        (
            "axle offsets not increasing",
            base.replace(
                "axle_offsets_m = [0.0, 3.8, 5.15]",
                "axle_offsets_m = [0.0, 3.8, 3.8]",
            ),
            "`measurement.vehicle.axle_offsets_m`",
        ),
        (
            "a named channel that is an accelerometer",
            base.replace(
                "[measurement.weighing]",
                "[measurement.weighing]\nchannels = [\"acc_s1_g1\"]",
            ),
            "`measurement.weighing.channels`",
        ),
        (
            "a named channel without a line",
            without(&["position_m = 15.0", "static_reference"]).replace(
                "[measurement.weighing]",
                "[measurement.weighing]\nchannels = [\"strain\"]",
            ),
            "`measurement.weighing.channels`",
        ),
        (
            "no vehicle",
            {
                // The [measurement.vehicle] table, up to the next table, and the static
                // references that need it.
                let text = without(&["static_reference"]);
                let start = text.find("[measurement.vehicle]").unwrap();
                let end = start + text[start..].find("\n[measurement.weighing]").unwrap();
                format!("{}{}", &text[..start], &text[end..])
            },
            "`measurement.weighing`",
        ),
    ];
    for (k, (case, text, field)) in cases.iter().enumerate() {
        assert_ne!(text, &base, "{case}: the edit changed nothing");
        let path = dir.path().join(format!("case_{k}.toml"));
        std::fs::write(&path, text).unwrap();
        for command in ["check", "measure"] {
            let mut run = vbi();
            run.arg(command).arg(&path);
            if command == "measure" {
                run.arg("--out").arg(dir.path().join(format!("out_{k}")));
            }
            let done = run.assert().code(2);
            let stderr = String::from_utf8_lossy(&done.get_output().stderr).to_string();
            assert!(stderr.contains(field), "{case}, {command}: {stderr}");
        }
    }
}
