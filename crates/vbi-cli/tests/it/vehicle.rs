//! End-to-end tests of `vbi vehicle` and its inputs.

use crate::common::{repository_root, vbi};

/// Runs `vbi` and returns (exit code, stdout, stderr).
fn run(args: &[&str]) -> (i32, String, String) {
    let out = vbi().args(args).output().expect("vbi runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).to_string(),
        String::from_utf8_lossy(&out.stderr).to_string(),
    )
}

/// Writes a `[vehicle]` file into a temporary directory and runs `vbi check` on it.
fn check(name: &str, text: &str) -> (i32, String) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, text).unwrap();
    let (code, _, stderr) = run(&["check", path.to_str().unwrap()]);
    (code, stderr)
}

const TWO_AXLE: &str = r#"[vehicle]
name = "test-truck"

[[vehicle.bodies]]
name = "body"
mass_kg = 15800.0
pitch_inertia_kg_m2 = 6.0e4
roll_inertia_kg_m2 = 1.2e4
position_m = -3.2

[[vehicle.axles]]
position_m = 0.0
mass_kg = 600.0
roll_inertia_kg_m2 = 400.0
suspension_stiffness_n_per_m = 6.0e5
suspension_damping_n_s_per_m = 8.0e3
suspension_spacing_m = 1.0
tyre_stiffness_n_per_m = 1.0e6
track_m = 2.0

[[vehicle.axles]]
position_m = -5.0
mass_kg = 1000.0
roll_inertia_kg_m2 = 700.0
suspension_stiffness_n_per_m = 1.2e6
suspension_damping_n_s_per_m = 1.2e4
suspension_spacing_m = 1.0
tyre_stiffness_n_per_m = 2.0e6
track_m = 1.85
"#;

#[test]
fn list_names_every_preset() {
    let (code, stdout, _) = run(&["vehicle", "list"]);
    assert_eq!(code, 0);
    for name in vbi::vehicle::PRESET_NAMES {
        assert!(stdout.contains(name), "{name} missing from\n{stdout}");
    }
    let (code, stdout, _) = run(&["vehicle", "list", "--format", "json"]);
    assert_eq!(code, 0);
    let rows: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(
        rows.as_array().unwrap().len(),
        vbi::vehicle::PRESET_NAMES.len()
    );
}

#[test]
fn show_json_of_the_paper_truck_has_15_dofs_and_balanced_wheel_loads() {
    // Reference: the paper §4.1, 15 DOF; statics Σ R = g Σ m.
    let (code, stdout, stderr) = run(&[
        "vehicle",
        "show",
        "tractor-semitrailer-5axle",
        "--format",
        "json",
    ]);
    assert_eq!(code, 0, "{stderr}");
    let report: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(report["dof_count"], 15);
    let mass = report["total_mass_kg"].as_f64().unwrap();
    assert!((mass - 43_000.0).abs() < 1e-6, "{mass}");
    let loads: Vec<f64> = report["static_wheel_loads_n"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(loads.len(), 10);
    let sum: f64 = loads.iter().sum();
    // JSON round trip keeps ~17 digits; 1e-9 relative is round-off.
    assert!((sum - mass * 9.81).abs() < 1e-9 * sum, "{sum}");
    let frequencies = report["natural_frequencies_hz"].as_array().unwrap();
    assert_eq!(frequencies.len(), 15);
    assert!(report["modes"][0]["label"].is_string());
}

#[test]
fn show_table_of_a_file_prints_frequencies_and_dominant_motions() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("truck.toml");
    std::fs::write(&path, TWO_AXLE).unwrap();
    let (code, stdout, stderr) = run(&["vehicle", "show", path.to_str().unwrap()]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("test-truck"), "{stdout}");
    assert!(stdout.contains("body bounce"), "{stdout}");
    assert!(stdout.contains("axle 2 hop"), "{stdout}");
    assert!(stdout.contains("DOFs           7"), "{stdout}");
}

#[test]
fn every_example_vehicle_passes_check_and_show() {
    let dir = repository_root().join("examples/vehicles");
    let mut count = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let (code, _, stderr) = run(&["check", path.to_str().unwrap()]);
            assert_eq!(code, 0, "{}: {stderr}", path.display());
            let (code, _, stderr) = run(&["vehicle", "show", path.to_str().unwrap()]);
            assert_eq!(code, 0, "{}: {stderr}", path.display());
            count += 1;
        }
    }
    assert!(count >= 3, "examples found: {count}");
}

#[test]
fn example_of_the_36t_truck_matches_its_preset() {
    let path = repository_root().join("examples/vehicles/three-axle-truck-36t.toml");
    let (_, from_file, _) = run(&[
        "vehicle",
        "show",
        path.to_str().unwrap(),
        "--format",
        "json",
    ]);
    let (_, from_preset, _) = run(&[
        "vehicle",
        "show",
        "three-axle-truck-36t",
        "--format",
        "json",
    ]);
    let a: serde_json::Value = serde_json::from_str(&from_file).unwrap();
    let b: serde_json::Value = serde_json::from_str(&from_preset).unwrap();
    assert_eq!(a["static_wheel_loads_n"], b["static_wheel_loads_n"]);
    assert_eq!(a["natural_frequencies_hz"], b["natural_frequencies_hz"]);
}

#[test]
fn overriding_a_suspension_of_the_determinate_hs20_changes_frequencies_not_static_loads() {
    // Reference: statics. The HS20-44 tractor–semitrailer is statically determinate, so a
    // softer drive-axle suspension changes its frequencies but not its wheel loads.
    let path = repository_root().join("examples/vehicles/hs20-44-soft-suspension.toml");
    let (code, from_file, stderr) = run(&[
        "vehicle",
        "show",
        path.to_str().unwrap(),
        "--format",
        "json",
    ]);
    assert_eq!(code, 0, "{stderr}");
    let (_, from_preset, _) = run(&["vehicle", "show", "hs20-44", "--format", "json"]);
    let a: serde_json::Value = serde_json::from_str(&from_file).unwrap();
    let b: serde_json::Value = serde_json::from_str(&from_preset).unwrap();
    assert_eq!(a["name"], "hs20-44-soft-drive-axle");
    let loads = |v: &serde_json::Value| -> Vec<f64> {
        v["static_wheel_loads_n"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    for (x, y) in loads(&a).iter().zip(loads(&b)) {
        // Same statics, different stiffness in the solve: round-off only.
        assert!((x - y).abs() < 1e-8 * y, "{x} against {y}");
    }
    assert_ne!(a["natural_frequencies_hz"], b["natural_frequencies_hz"]);
}

#[test]
fn preset_overrides_change_only_the_given_keys() {
    let (code, stderr) = check(
        "soft.toml",
        "[vehicle]\npreset = \"hs20-44\"\n[[vehicle.axles]]\nindex = 2\nsuspension_stiffness_n_per_m = 1.0e6\n",
    );
    assert_eq!(code, 0, "{stderr}");
}

#[test]
fn a_negative_axle_mass_names_the_field_and_what_is_allowed() {
    let text = TWO_AXLE.replace("mass_kg = 1000.0", "mass_kg = -1000.0");
    let (code, stderr) = check("negative.toml", &text);
    assert_eq!(code, 2);
    assert!(stderr.contains("negative.toml:23:1"), "{stderr}");
    assert!(stderr.contains("vehicle.axles[1].mass_kg"), "{stderr}");
    assert!(
        stderr.contains("-1000 is not allowed; expected a positive number of kg"),
        "{stderr}"
    );
}

#[test]
fn a_negative_stiffness_names_the_field() {
    let text = TWO_AXLE.replace(
        "tyre_stiffness_n_per_m = 2.0e6",
        "tyre_stiffness_n_per_m = -2.0e6",
    );
    let (code, stderr) = check("stiffness.toml", &text);
    assert_eq!(code, 2);
    assert!(
        stderr.contains("vehicle.axles[1].tyre_stiffness_n_per_m"),
        "{stderr}"
    );
    assert!(stderr.contains("positive number of N/m"), "{stderr}");
}

#[test]
fn a_wheel_track_wider_than_the_body_names_the_allowed_width() {
    let text = TWO_AXLE.replace("track_m = 1.85", "track_m = 3.2");
    let (code, stderr) = check("wide.toml", &text);
    assert_eq!(code, 2);
    assert!(stderr.contains("vehicle.axles[1].track_m"), "{stderr}");
    assert!(
        stderr.contains(
            "3.2 is not allowed; expected more than 0 and at most 2.5 m, the width of body `body`"
        ),
        "{stderr}"
    );
}

#[test]
fn an_unknown_preset_lists_the_presets() {
    let (code, stderr) = check("unknown.toml", "[vehicle]\npreset = \"lorry\"\n");
    assert_eq!(code, 2);
    assert!(stderr.contains("unknown.toml:2:1"), "{stderr}");
    assert!(stderr.contains("vehicle.preset"), "{stderr}");
    assert!(
        stderr.contains("unknown preset `lorry`; expected one of: moving-force"),
        "{stderr}"
    );

    let (code, _, stderr) = run(&["vehicle", "show", "lorry"]);
    assert_eq!(code, 2);
    assert!(stderr.contains("hs20-44"), "{stderr}");
}

#[test]
fn an_override_index_out_of_range_names_the_axle_count() {
    let (code, stderr) = check(
        "index.toml",
        "[vehicle]\npreset = \"hs20-44\"\n[[vehicle.axles]]\nindex = 4\ntrack_m = 1.8\n",
    );
    assert_eq!(code, 2);
    assert!(stderr.contains("vehicle.axles[0].index"), "{stderr}");
    assert!(
        stderr.contains("4 is not allowed; expected a number from 1 to 3 (the axles of the preset"),
        "{stderr}"
    );
}

#[test]
fn a_missing_key_and_an_unknown_key_are_reported() {
    let text = TWO_AXLE.replace("tyre_stiffness_n_per_m = 1.0e6\n", "");
    let (code, stderr) = check("missing.toml", &text);
    assert_eq!(code, 2);
    assert!(
        stderr.contains("vehicle.axles[0].tyre_stiffness_n_per_m"),
        "{stderr}"
    );
    assert!(stderr.contains("is required"), "{stderr}");

    let text = TWO_AXLE.replace("mass_kg = 600.0", "mass = 600.0");
    let (code, stderr) = check("unknown-key.toml", &text);
    assert_eq!(code, 2);
    assert!(stderr.contains("mass"), "{stderr}");
}

#[test]
fn axles_out_of_order_and_an_unstable_vehicle_are_rejected() {
    let text = TWO_AXLE.replace("position_m = -5.0", "position_m = 1.0");
    let (code, stderr) = check("order.toml", &text);
    assert_eq!(code, 2);
    assert!(stderr.contains("vehicle.axles[1].position_m"), "{stderr}");
    assert!(stderr.contains("front to back"), "{stderr}");

    // A body with a pitch DOF on one axle is a mechanism.
    let one_axle = TWO_AXLE
        .split("[[vehicle.axles]]\nposition_m = -5.0")
        .next()
        .unwrap();
    let (code, stderr) = check("unstable.toml", one_axle);
    assert_eq!(code, 2);
    assert!(stderr.contains("not statically stable"), "{stderr}");
}

#[test]
fn a_centre_of_mass_height_out_of_range_or_without_pitch_is_refused_at_its_key() {
    let body = |preset: &str, name: &str, height: &str| {
        format!(
            "[vehicle]\npreset = \"{preset}\"\n[[vehicle.bodies]]\nname = \"{name}\"\n\
             centre_of_mass_height_m = {height}\n"
        )
    };
    for height in ["0.0", "4.5", "-1.0"] {
        let (code, stderr) = check(
            "tall.toml",
            &body("tractor-semitrailer-5axle", "tractor", height),
        );
        assert_eq!(code, 2, "{stderr}");
        assert!(
            stderr.contains("tall.toml:5:1: field `vehicle.bodies[0].centre_of_mass_height_m`"),
            "{stderr}"
        );
        assert!(stderr.contains("at most 4 m"), "{stderr}");
    }
    let (code, stderr) = check("car.toml", &body("quarter-car", "body", "1.0"));
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("centre_of_mass_height_m"), "{stderr}");
    assert!(stderr.contains("pitch_inertia_kg_m2"), "{stderr}");
    let (code, stderr) = check(
        "ok.toml",
        &body("tractor-semitrailer-5axle", "tractor", "1.1"),
    );
    assert_eq!(code, 0, "{stderr}");
}
