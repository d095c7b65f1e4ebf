//! Several vehicles, directions and variable speed from scenario files: runs end to end, and
//! bad traffic exits 2 with a located message before any modal analysis.

use crate::common::{repository_root, vbi};

fn scenario_with(extra: &str) -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("traffic.toml");
    let text = format!(
        "[scenario]\nbridge = \"paper-1x20\"\nvehicle = \"quarter-car\"\nroad = \"smooth\"\n\
         modes = 6\n{extra}"
    );
    std::fs::write(&path, text).unwrap();
    (dir, path)
}

fn refusal(extra: &str) -> String {
    let (_dir, path) = scenario_with(extra);
    let out = vbi().arg("check").arg(&path).assert().code(2);
    String::from_utf8_lossy(&out.get_output().stderr).to_string()
}

#[test]
fn a_scenario_with_oncoming_traffic_runs_and_writes_the_vehicle_histories() {
    let (dir, path) = scenario_with(
        "[[traffic]]\nvehicle = \"quarter-car\"\ndirection = \"backward\"\n\
         lateral_position_m = -1.8\nentry_time_s = 0.5\nspeed_kmh = 60\n",
    );
    let out = dir.path().join("out");
    vbi()
        .arg("run")
        .arg(&path)
        .arg("--out")
        .arg(&out)
        .assert()
        .success();
    let vehicles = std::fs::read_to_string(out.join("vehicles.csv")).unwrap();
    let header = vehicles.lines().next().unwrap();
    assert!(header.contains("v2_contact1_force_n"), "{header}");
    assert!(
        header.contains("v1_body_bounce_acceleration_m_s2"),
        "{header}"
    );
    let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
    assert!(summary.contains("\"station_accelerations\""));
    assert!(summary.contains("\"vehicle_extremes\""));
}

#[test]
fn the_traffic_examples_pass_vbi_check() {
    for name in [
        "two-trucks-opposite-lanes",
        "braking-truck",
        "traffic-stream",
    ] {
        let path = repository_root().join(format!("examples/scenarios/{name}.toml"));
        vbi().arg("check").arg(&path).assert().success();
    }
}

#[test]
fn two_vehicles_on_the_same_spot_at_the_start_are_refused_at_the_second() {
    // The scenario's vehicle starts at the approach's start, 100 m before the deck at 80 km/h.
    let stderr = refusal("[[traffic]]\nvehicle = \"quarter-car\"\nentry_time_s = 4.5\n");
    assert!(stderr.contains("traffic.toml:6:"), "{stderr}");
    assert!(stderr.contains("overlap"), "{stderr}");
}

#[test]
fn a_gap_without_a_vehicle_ahead_in_its_direction_is_refused() {
    let stderr =
        refusal("[[traffic]]\nvehicle = \"quarter-car\"\ndirection = \"backward\"\ngap_m = 5\n");
    assert!(stderr.contains("traffic[0]"), "{stderr}");
    assert!(stderr.contains("entry_time_s"), "{stderr}");
}

#[test]
fn a_lane_outside_the_deck_is_refused() {
    let stderr = refusal("lateral_position_m = 4.5\n");
    assert!(stderr.contains("outside the deck"), "{stderr}");
}

#[test]
fn a_braking_that_stops_the_vehicle_on_the_deck_is_refused() {
    let stderr = refusal("speed_kmh = 20\nacceleration_ms2 = -4\n");
    assert!(stderr.contains("reaches zero"), "{stderr}");
}

#[test]
fn an_entry_needs_a_time_or_a_gap_and_knots_must_increase() {
    let stderr = refusal("[[traffic]]\nvehicle = \"quarter-car\"\n");
    assert!(stderr.contains("entry_time_s"), "{stderr}");
    let stderr = refusal(
        "speed_profile = [{ travel_m = 10, speed_kmh = 60 }, { travel_m = 5, speed_kmh = 40 }]\n",
    );
    assert!(stderr.contains("speed_profile[1].travel_m"), "{stderr}");
    let stderr = refusal("[[traffic]]\nvehicle = \"quarter-car\"\ngap_m = 5\nspeed = 3\n");
    assert!(stderr.contains("unknown key `speed`"), "{stderr}");
}

#[test]
fn a_traffic_stream_with_bad_numbers_is_refused_at_its_key() {
    let stream = "[traffic_stream]\nvehicle_count = 3\nvehicles = [\"quarter-car\"]\n\
                  mean_headway_s = 2\nfirst_entry_s = 8\n";
    let stderr = refusal(&format!("{stream}weights = [1, 2]\n"));
    assert!(stderr.contains("traffic_stream.weights"), "{stderr}");
    let stderr = refusal(&format!("{stream}minimum_headway_s = 3\n"));
    assert!(
        stderr.contains("minimum_headway_s < mean_headway_s"),
        "{stderr}"
    );
    let stderr = refusal(&format!("{stream}load_scale_sd = 0.5\n"));
    assert!(stderr.contains("traffic_stream.load_scale_sd"), "{stderr}");
    let (_dir, path) = scenario_with(stream);
    vbi().arg("check").arg(&path).assert().success();
}

#[test]
fn stations_anywhere_are_analysed_and_bad_ones_refused_at_their_key() {
    let (dir, path) = scenario_with(
        "[[station]]\nspan = 1\nfraction = 0.25\n\n[[station]]\nname = \"near_joint\"\n\
         position_m = 1.5\n",
    );
    let out = vbi()
        .arg("run")
        .arg(&path)
        .args(["--format", "json"])
        .current_dir(dir.path())
        .assert()
        .success();
    let stdout = String::from_utf8_lossy(&out.get_output().stdout).to_string();
    assert!(stdout.contains("\"x5_section\""), "a quarter of 20 m");
    assert!(stdout.contains("\"near_joint\""));
    let stderr = refusal("[[station]]\nposition_m = 25\n");
    assert!(stderr.contains("station[0].position_m"), "{stderr}");
    let stderr = refusal("[[station]]\nspan = 2\nfraction = 0.5\n");
    assert!(stderr.contains("station[0].span"), "{stderr}");
    let stderr = refusal("[[station]]\nposition_m = 5\ngirder = 9\n");
    assert!(stderr.contains("station[0].girder"), "{stderr}");
    // Two stations of one name would give histories.csv two columns of that name (the
    // robustness corpus's 1000 repeated [[station]] blocks took 5.5 GB before it was refused).
    let stderr = refusal(
        "[[station]]\nname = \"joint\"\nposition_m = 1\n\n[[station]]\nname = \"joint\"\n\
         position_m = 2\n",
    );
    assert!(stderr.contains("station[1].name"), "{stderr}");
    assert!(stderr.contains("already defined by station[0]"), "{stderr}");
    let stderr = refusal("[[station]]\nposition_m = 5\n\n[[station]]\nposition_m = 5\n");
    assert!(
        stderr.contains("station `x5_section` is already defined"),
        "{stderr}"
    );
    // The automatic stations' names are theirs.
    let stderr = refusal("[[station]]\nname = \"span1_mid_section\"\nposition_m = 5\n");
    assert!(stderr.contains("station[0].name"), "{stderr}");
    assert!(stderr.contains("automatic stations' names"), "{stderr}");
}

#[test]
fn a_station_on_a_support_reports_its_reaction_and_one_in_a_span_its_shear() {
    let (dir, path) = scenario_with(
        "[[station]]\nname = \"abutment\"\nposition_m = 0\n\n[[station]]\n\
         name = \"quarter\"\nposition_m = 5\n",
    );
    vbi()
        .arg("run")
        .arg(&path)
        .args(["--out", "out"])
        .current_dir(dir.path())
        .assert()
        .success();
    let out = dir.path().join("out");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let entry = |name: &str, quantity: &str| {
        summary["stations"]
            .as_array()
            .unwrap()
            .iter()
            .find(|e| e["name"] == name && e["quantity"] == quantity)
            .cloned()
    };
    let reaction = entry("abutment", "support_reaction").expect("the abutment's reaction");
    // Upward positive, largest when the vehicle stands on the abutment.
    assert!(reaction["static_max"].as_f64().unwrap() > 0.0, "{reaction}");
    assert!(reaction["daf"].as_f64().is_some(), "{reaction}");
    assert!(reaction["daf_paper"].as_f64().is_some(), "{reaction}");
    assert!(entry("abutment", "shear_force").is_none());
    assert!(entry("quarter", "shear_force").is_some());
    assert!(entry("quarter", "support_reaction").is_none());
    let histories = std::fs::read_to_string(out.join("histories.csv")).unwrap();
    let header = histories.lines().next().unwrap();
    for column in [
        "abutment_reaction_n",
        "abutment_paper_reaction_n",
        "abutment_static_reaction_n",
        "quarter_shear_n",
        "quarter_paper_shear_n",
        "quarter_static_shear_n",
    ] {
        assert!(
            header.split(',').any(|c| c == column),
            "{column} in {header}"
        );
    }
}

#[test]
fn a_faster_follower_catching_up_is_refused_at_its_entry_naming_both_and_the_meeting() {
    // The scenario's quarter car drives at 80 km/h from the start of the approach; the
    // [[traffic]] one follows 10 m behind at 120 km/h: the gap closes at 40/3.6 m/s, at
    // t = 0.9 s, the follower's front axle at −100 − 10 + 0.9 × 120/3.6 = −80 m.
    let extra = "[[traffic]]\nvehicle = \"quarter-car\"\nlabel = \"fast car\"\ngap_m = 10\n\
                 speed_kmh = 120\n";
    let (dir, path) = scenario_with(extra);
    let stderr_of = |command: &str| {
        let out = vbi()
            .arg(command)
            .arg(&path)
            .args(if command == "run" {
                vec!["--out", "out"]
            } else {
                vec![]
            })
            .current_dir(dir.path())
            .assert()
            .code(2);
        String::from_utf8_lossy(&out.get_output().stderr).to_string()
    };
    let stderr = stderr_of("check");
    assert!(stderr.contains("traffic.toml:6:"), "{stderr}");
    for part in [
        "field `traffic[0]`: vehicle 2 (fast car): catches up with vehicle 1 (quarter-car, at \
         `scenario`) ahead of it in the same lane",
        "t = 0.900 s, -80.00 m past the deck entry",
    ] {
        assert!(stderr.contains(part), "{part}: {stderr}");
    }
    // The same refusal from `vbi run`, before any work.
    assert_eq!(stderr_of("run"), stderr);
    assert!(!dir.path().join("out").exists());
}
