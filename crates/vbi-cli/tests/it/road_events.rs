//! End-to-end tests of road events and user profiles in scenarios: a scenario with events
//! checks and runs, bad events and a profile that does not cover the crossing exit 2 with a
//! located message before any work, the examples check.

use crate::common::repository_root;
use crate::run::{run, SMALL};

/// The small scenario of the `vbi run` tests (20 m beam, the VBI-2D sprung mass, 4 modes) with
/// a 10 m approach and exit and `road` as the rest of its `[road]` table.
fn scenario(road: &str) -> String {
    let (head, _) = SMALL
        .split_once("[road]")
        .expect("SMALL has a [road] table");
    format!("{head}[road]\napproach_length_m = 10.0\nexit_length_m = 10.0\n{road}")
}

const JOINT: &str = r#"class = "smooth"

[[road.event]]
kind = "step"
position_m = 0.0
height_m = 0.02
length_m = 0.1

[[road.event]]
kind = "bump"
centre_m = 10.0
length_m = 0.5
height_m = -0.01
shape = "half_sine"
"#;

/// Writes the files (name, text) into a new temporary directory; returns it.
fn files(entries: &[(&str, &str)]) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for (name, text) in entries {
        std::fs::write(dir.path().join(name), text).unwrap();
    }
    dir
}

fn path(dir: &tempfile::TempDir, name: &str) -> String {
    dir.path().join(name).to_str().unwrap().to_string()
}

fn daf(stdout: &str) -> f64 {
    let summary: serde_json::Value = serde_json::from_str(stdout).expect("stdout is JSON");
    summary["stations"][0]["daf"].as_f64().expect("a DAF")
}

#[test]
fn a_scenario_with_events_checks_and_runs_and_the_events_move_the_daf() {
    let dir = files(&[
        ("joint.toml", &scenario(JOINT)),
        ("plain.toml", &scenario("class = \"smooth\"\n")),
    ]);
    let (code, _, stderr) = run(&["check", &path(&dir, "joint.toml")]);
    assert_eq!(code, 0, "{stderr}");
    let (code, stdout, stderr) = run(&["run", &path(&dir, "joint.toml"), "--format", "json"]);
    assert_eq!(code, 0, "{stderr}");
    let with_events = daf(&stdout);
    let (code, stdout, stderr) = run(&["run", &path(&dir, "plain.toml"), "--format", "json"]);
    assert_eq!(code, 0, "{stderr}");
    let smooth = daf(&stdout);
    assert!(with_events.is_finite() && smooth.is_finite());
    assert_ne!(
        with_events, smooth,
        "the step and the dip change the response"
    );
}

#[test]
fn an_unknown_event_kind_exits_2_naming_the_line_the_field_and_the_kinds() {
    let text = scenario(&JOINT.replace("kind = \"bump\"", "kind = \"pothole\""));
    let line = text.lines().position(|l| l.contains("pothole")).unwrap() + 1;
    let dir = files(&[("kind.toml", &text)]);
    for command in ["check", "run"] {
        let (code, stdout, stderr) = run(&[command, &path(&dir, "kind.toml")]);
        assert_eq!(code, 2, "{stderr}");
        assert!(stdout.is_empty(), "{stdout}");
        assert!(stderr.contains(&format!("kind.toml:{line}:")), "{stderr}");
        assert!(stderr.contains("road.event[1].kind"), "{stderr}");
        assert!(
            stderr.contains("`step`, `ramp`, `bump`, `sine`"),
            "{stderr}"
        );
    }
}

#[test]
fn a_negative_event_length_exits_2_naming_the_field_and_what_is_allowed() {
    let text = scenario(&JOINT.replace("length_m = 0.5", "length_m = -0.5"));
    let line = text.lines().position(|l| l.contains("-0.5")).unwrap() + 1;
    let dir = files(&[("length.toml", &text)]);
    let (code, _, stderr) = run(&["run", &path(&dir, "length.toml")]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains(&format!("length.toml:{line}:")), "{stderr}");
    assert!(stderr.contains("road.event[1].length_m"), "{stderr}");
    assert!(stderr.contains("at least 4 sample spacings"), "{stderr}");
}

/// A user profile CSV over [first, last] m every 0.5 m: a gentle 1 mm swell.
fn profile_csv(first: f64, last: f64) -> String {
    let mut text = String::from("x_m,left_m,right_m\n");
    let count = ((last - first) / 0.5).round() as usize;
    for i in 0..=count {
        let x = first + 0.5 * i as f64;
        let h = 0.001 * (x / 3.0).sin();
        text.push_str(&format!("{x},{h},{h}\n"));
    }
    text
}

#[test]
fn a_user_profile_that_covers_the_crossing_runs() {
    // The crossing needs [-10, 30] m (10 m approach, 20 m beam, 10 m exit; one axle).
    let road = "profile_csv = \"profile.csv\"\n";
    let dir = files(&[
        ("user.toml", &scenario(road)),
        ("profile.csv", &profile_csv(-10.0, 30.0)),
    ]);
    let (code, stdout, stderr) = run(&["run", &path(&dir, "user.toml"), "--format", "json"]);
    assert_eq!(code, 0, "{stderr}");
    assert!(daf(&stdout).is_finite());
}

#[test]
fn a_user_profile_that_does_not_cover_the_crossing_is_refused_before_any_work() {
    let road = "profile_csv = \"short.csv\"\n";
    let text = scenario(road);
    let line = text.lines().position(|l| l.contains("short.csv")).unwrap() + 1;
    let dir = files(&[
        ("user.toml", &text),
        ("short.csv", &profile_csv(-5.0, 25.0)),
    ]);
    let out = dir.path().join("out");
    let file = path(&dir, "user.toml");
    let out_arg = out.to_str().unwrap();
    for args in [
        vec!["check", file.as_str()],
        vec!["run", file.as_str(), "--out", out_arg],
    ] {
        let (code, stdout, stderr) = run(&args);
        assert_eq!(code, 2, "{stderr}");
        assert!(stdout.is_empty(), "{stdout}");
        assert!(stderr.contains(&format!("user.toml:{line}:")), "{stderr}");
        assert!(stderr.contains("road.profile_csv"), "{stderr}");
        assert!(stderr.contains("covers [-5, 25] m"), "{stderr}");
        assert!(stderr.contains("needs [-10, 30] m"), "{stderr}");
    }
    assert!(
        !out.exists(),
        "nothing was written: the refusal came before any work"
    );
}

#[test]
fn a_bad_row_in_the_profile_csv_names_the_csv_line_and_column() {
    let road = "profile_csv = \"bad.csv\"\n";
    let csv = profile_csv(-10.0, 30.0).replace("\n1,", "\nnot-a-number,");
    let line = csv
        .lines()
        .position(|l| l.starts_with("not-a-number"))
        .unwrap()
        + 1;
    let dir = files(&[("user.toml", &scenario(road)), ("bad.csv", &csv)]);
    let (code, _, stderr) = run(&["check", &path(&dir, "user.toml")]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains(&format!("bad.csv:{line}:1")), "{stderr}");
    assert!(stderr.contains("x_m"), "{stderr}");
}

#[test]
fn the_road_event_examples_check_and_the_user_profile_road_generates() {
    let root = repository_root();
    for example in [
        "examples/scenarios/expansion-joint.toml",
        "examples/roads/user-profile.toml",
    ] {
        let (code, _, stderr) = run(&["check", root.join(example).to_str().unwrap()]);
        assert_eq!(code, 0, "{example}: {stderr}");
    }
    let out = tempfile::tempdir().unwrap();
    let (code, _, stderr) = run(&[
        "road",
        root.join("examples/roads/user-profile.toml")
            .to_str()
            .unwrap(),
        "--length",
        "25",
        "--out",
        out.path().to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert!(out.path().join("profile.csv").exists());
}
