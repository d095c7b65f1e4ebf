//! End-to-end tests of `vbi measure` with several runs: examples/measurements/batch (three
//! SYNTHETIC passes of one truck over the 4 × 30 m bridge at 40, 60 and 80 km/h).

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::common::{repository_root, vbi};

const SPEEDS: [u32; 3] = [40, 60, 80];

/// The example runs, in speed order.
fn example_runs() -> Vec<PathBuf> {
    let dir = repository_root().join("examples/measurements/batch");
    SPEEDS
        .iter()
        .map(|v| dir.join(format!("pass_{v}kmh.toml")))
        .collect()
}

fn read_json(path: &Path) -> Value {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    serde_json::from_str(&text).unwrap()
}

/// `vbi measure FILES --out OUT`, which must succeed; its standard output.
fn measure(files: &[PathBuf], out: &Path) -> String {
    let output = vbi()
        .arg("measure")
        .args(files)
        .arg("--out")
        .arg(out)
        .assert()
        .success();
    String::from_utf8_lossy(&output.get_output().stdout).to_string()
}

/// `vbi measure FILES --out OUT`, which must fail with exit code 2; its standard error.
fn measure_fails(files: &[PathBuf], out: &Path) -> String {
    let output = vbi()
        .arg("measure")
        .args(files)
        .arg("--out")
        .arg(out)
        .assert()
        .code(2);
    String::from_utf8_lossy(&output.get_output().stderr).to_string()
}

fn file_names(dir: &Path) -> BTreeSet<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .collect()
}

#[test]
fn three_runs_give_a_row_per_run_and_channel_with_the_dafs_of_each_run_alone() {
    let scratch = tempfile::tempdir().unwrap();
    let runs = example_runs();
    let out = scratch.path().join("batch");
    let printed = measure(&runs, &out);
    let mut reader = csv::Reader::from_path(out.join("measurements.csv")).unwrap();
    let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    for column in [
        "run",
        "speed_m_s",
        "channel",
        "cutoff_hz",
        "daf",
        "daf_at_k1",
        "rdm",
    ] {
        assert!(header.iter().any(|h| h == column), "{column}: {header:?}");
    }
    let column = |name: &str| header.iter().position(|h| h == name).unwrap();
    let records: Vec<csv::StringRecord> = reader.records().map(|r| r.unwrap()).collect();
    let table = read_json(&out.join("measurements.json"));
    let mut row = 0;
    for (i, (path, speed)) in runs.iter().zip(SPEEDS).enumerate() {
        let stem = format!("pass_{speed}kmh");
        // Each run alone: its measure.json is the batch's, and its DAFs are the table's.
        let alone = scratch.path().join(format!("alone_{speed}"));
        measure(std::slice::from_ref(path), &alone);
        let own = read_json(&alone.join("measure.json"));
        assert_eq!(read_json(&out.join(&stem).join("measure.json")), own);
        let channels = own["channels"].as_array().unwrap();
        assert_eq!(channels.len(), 2, "deflection and strain");
        for channel in channels {
            let record = &records[row];
            assert_eq!(&record[column("run")], stem.as_str());
            assert_eq!(
                &record[column("channel")],
                channel["name"].as_str().unwrap()
            );
            let daf: f64 = record[column("daf")].parse().unwrap();
            assert_eq!(daf, channel["daf"].as_f64().unwrap(), "{stem}");
            let at_k1: f64 = record[column("daf_at_k1")].parse().unwrap();
            assert_eq!(at_k1, channel["cutoff_mode"]["daf_after"].as_f64().unwrap());
            let v: f64 = record[column("speed_m_s")].parse().unwrap();
            assert!((v * 3.6 - f64::from(speed)).abs() < 1e-9, "{v}");
            let rdm: f64 = record[column("rdm")].parse().unwrap();
            assert_eq!(rdm, own["rdm"][0]["rdm"].as_f64().unwrap());
            assert_eq!(table["table"][row]["daf"], channel["daf"]);
            row += 1;
        }
        let listed = &table["runs"][i];
        assert_eq!(listed["run"], stem.as_str());
        assert_eq!(listed["measure"], own);
        assert!(printed.contains(&stem), "{printed}");
    }
    assert_eq!(records.len(), row);
    assert_eq!(row, 3 * 2);
    for file in ["measurements.csv", "measurements.json", "report.html"] {
        let line = format!("wrote {}", out.join(file).display());
        assert!(printed.contains(&line), "{line} not in\n{printed}");
    }
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    for speed in SPEEDS {
        let section = format!("<section id=\"run-pass_{speed}kmh\">");
        assert_eq!(html.matches(&section).count(), 1, "{section}");
    }
    // Per run a figure per DAF channel and the spectrum, and the DAF against the speed.
    assert!(html.matches("<svg").count() > 3 * 3);
    assert!(html.contains("id=\"daf-against-speed\""));
    assert!(!html.contains("<img") && !html.contains("<script"));
    // The report's own figures were drawn in a scratch folder, which is gone.
    assert!(
        file_names(&out).iter().all(|n| !n.contains("partial")),
        "{:?}",
        file_names(&out)
    );
}

#[test]
fn one_file_writes_its_measure_json_and_figures_as_before_plus_the_report() {
    let scratch = tempfile::tempdir().unwrap();
    let run = &example_runs()[1];
    let out = scratch.path().join("one");
    let printed = measure(std::slice::from_ref(run), &out);
    let json = read_json(&out.join("measure.json"));
    // The files of one run: measure.json, each figure in PNG and SVG, and report.html.
    let mut expected: BTreeSet<String> = ["measure.json", "report.html"].map(String::from).into();
    for stem in json["figures"].as_array().unwrap() {
        for ext in ["png", "svg"] {
            expected.insert(format!("{}.{ext}", stem.as_str().unwrap()));
        }
    }
    assert_eq!(file_names(&out), expected);
    assert_eq!(
        json["figures"],
        serde_json::json!([
            "signal_deflection",
            "signal_strain",
            "signal_acceleration",
            "spectrum_acceleration",
            "stabilisation_diagram"
        ])
    );
    // The same run in a batch writes the same measure.json.
    let batch = scratch.path().join("batch");
    measure(&[run.clone(), example_runs()[0].clone()], &batch);
    assert_eq!(read_json(&batch.join("pass_60kmh/measure.json")), json);
    // The table as before, then the report.
    let lines: Vec<&str> = printed.lines().collect();
    assert!(lines[0].starts_with("3502 samples at 200 Hz"), "{printed}");
    assert!(lines
        .iter()
        .any(|l| l.starts_with("channel ") && l.contains("DAF at K1")));
    let n = lines.len();
    assert_eq!(
        lines[n - 2..],
        [
            format!("wrote {}", out.join("measure.json").display()),
            format!("wrote {}", out.join("report.html").display())
        ]
    );
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert_eq!(html.matches("<section id=\"run-").count(), 1);
    assert!(html.contains("<svg"));
    assert!(
        !html.contains("daf-against-speed"),
        "one run, no speed figure"
    );
}

#[test]
fn a_bad_file_stops_the_batch_with_its_located_error_before_anything_is_written() {
    let scratch = tempfile::tempdir().unwrap();
    let bad = scratch.path().join("bad.toml");
    std::fs::write(
        &bad,
        "[measurement]\ncsv = \"m.csv\"\ntime_column = \"time_s\"\ncolour = \"red\"\n",
    )
    .unwrap();
    let runs = example_runs();
    let out = scratch.path().join("out");
    let e = measure_fails(&[runs[0].clone(), bad, runs[2].clone()], &out);
    assert!(e.contains("bad.toml:4:1") && e.contains("colour"), "{e}");
    assert!(!out.exists(), "nothing written: {:?}", file_names(&out));
}

#[test]
fn a_run_that_fails_in_processing_names_its_file_and_nothing_is_written() {
    // A record without a cut-off, a speed or a crossing time: it passes `vbi check`, but its
    // static part cannot be chosen.
    let scratch = tempfile::tempdir().unwrap();
    let mut csv = String::from("time_s,u\n");
    for i in 0..300 {
        let t = f64::from(i) / 100.0;
        csv.push_str(&format!(
            "{t:.2},{:.6}\n",
            -(t / 3.0 * std::f64::consts::PI).sin()
        ));
    }
    std::fs::write(scratch.path().join("m.csv"), csv).unwrap();
    let path = scratch.path().join("no_cutoff.toml");
    std::fs::write(
        &path,
        "[measurement]\ncsv = \"m.csv\"\ntime_column = \"time_s\"\n\n[[measurement.channels]]\n\
         name = \"u\"\nkind = \"deflection\"\nunit = \"mm\"\n",
    )
    .unwrap();
    vbi().arg("check").arg(&path).assert().success();
    let runs = example_runs();
    let out = scratch.path().join("out");
    let e = measure_fails(&[runs[0].clone(), path], &out);
    assert!(
        e.contains("no_cutoff.toml") && e.contains("cutoff_hz"),
        "{e}"
    );
    assert!(!out.exists(), "nothing written: {:?}", file_names(&out));
}

#[test]
fn runs_with_the_same_stem_get_their_own_folders_and_json_prints_measurements_json() {
    let scratch = tempfile::tempdir().unwrap();
    let run = example_runs()[2].clone();
    let out = scratch.path().join("out");
    let output = vbi()
        .arg("measure")
        .args([&run, &run])
        .arg("--out")
        .arg(&out)
        .args(["--format", "json"])
        .assert()
        .success();
    let printed: Value = serde_json::from_slice(&output.get_output().stdout).unwrap();
    assert_eq!(printed, read_json(&out.join("measurements.json")));
    let names: Vec<&str> = printed["runs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["run"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["pass_80kmh", "pass_80kmh_2"]);
    for name in names {
        assert!(out.join(name).join("measure.json").is_file(), "{name}");
    }
    assert_eq!(printed["table"].as_array().unwrap().len(), 4);
    // Two runs at one speed: the DAF-against-speed figure has two points per channel.
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(html.contains("id=\"daf-against-speed\""));
}
