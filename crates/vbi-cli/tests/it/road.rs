//! End-to-end tests of `vbi road` and its inputs.

use crate::common::{repository_root, vbi};

fn stderr_of(assert: &assert_cmd::assert::Assert) -> String {
    String::from_utf8_lossy(&assert.get_output().stderr).to_string()
}

#[test]
fn road_with_a_class_writes_the_profile_plots_and_psd() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let assert = vbi()
        .args([
            "road", "--class", "medium", "--length", "40", "--seed", "9", "--out",
        ])
        .arg(&out)
        .assert()
        .success();
    let stdout = String::from_utf8_lossy(&assert.get_output().stdout).to_string();
    assert!(stdout.contains("medium"), "{stdout}");
    assert!(stdout.contains("RMS elevation"), "{stdout}");
    for name in [
        "profile.csv",
        "profile.png",
        "profile.svg",
        "psd.png",
        "psd.svg",
        "summary.json",
    ] {
        assert!(out.join(name).is_file(), "{name} missing");
    }
    let csv = std::fs::read_to_string(out.join("profile.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("x_m,left_m,right_m"));
    // Default approach 100 m and exit 30 m around the 40 m bridge, at 0.05 m: 3401 samples.
    assert_eq!(lines.clone().count(), 3401);
    assert!(lines.next().unwrap().starts_with("-100,"));
}

#[test]
fn same_seed_writes_identical_profiles_and_another_sample_differs() {
    let dir = tempfile::tempdir().unwrap();
    let run = |name: &str, sample: &str| {
        let out = dir.path().join(name);
        vbi()
            .args([
                "road", "--class", "B", "--length", "20", "--seed", "3", "--sample", sample,
            ])
            .arg("--out")
            .arg(&out)
            .assert()
            .success();
        std::fs::read(out.join("profile.csv")).unwrap()
    };
    let first = run("a", "0");
    assert_eq!(first, run("b", "0"));
    assert_ne!(first, run("c", "1"));
}

#[test]
fn every_example_road_file_checks_and_generates() {
    let dir = tempfile::tempdir().unwrap();
    let examples = repository_root().join("examples/roads");
    let mut count = 0;
    for entry in std::fs::read_dir(&examples).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            vbi().arg("check").arg(&path).assert().success();
            vbi()
                .arg("road")
                .arg(&path)
                .args(["--length", "30", "--out"])
                .arg(dir.path().join(path.file_stem().unwrap()))
                .assert()
                .success();
            count += 1;
        }
    }
    assert!(count >= 3);
}

#[test]
fn unknown_class_on_the_command_line_exits_2_listing_the_classes() {
    let assert = vbi().args(["road", "--class", "awful"]).assert().code(2);
    let stderr = stderr_of(&assert);
    assert!(stderr.contains("--class"), "{stderr}");
    assert!(stderr.contains("smooth, good, medium, poor, A"), "{stderr}");
}

#[test]
fn reversed_band_in_a_file_exits_2_naming_line_field_and_range() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.toml");
    std::fs::write(
        &path,
        "[road]\nclass = \"good\"\nband_cycles_per_m = [3.0, 0.01]\n",
    )
    .unwrap();
    for command in ["road", "check"] {
        let assert = vbi().arg(command).arg(&path).assert().code(2);
        let stderr = stderr_of(&assert);
        assert!(stderr.contains("bad.toml:3:1"), "{stderr}");
        assert!(stderr.contains("road.band_cycles_per_m"), "{stderr}");
        assert!(stderr.contains("0 < n1 < n2"), "{stderr}");
    }
}

#[test]
fn negative_length_in_a_file_and_on_the_command_line_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("neg.toml");
    std::fs::write(
        &path,
        "[road]\nclass = \"good\"\ntyre_patch_length_m = -0.2\n",
    )
    .unwrap();
    let stderr = stderr_of(&vbi().arg("check").arg(&path).assert().code(2));
    assert!(stderr.contains("road.tyre_patch_length_m"), "{stderr}");
    assert!(stderr.contains("from 0 to 2 m"), "{stderr}");
    let stderr = stderr_of(&vbi().args(["road", "--length", "-5"]).assert().code(2));
    assert!(stderr.contains("--length"), "{stderr}");
}

#[test]
fn measured_profile_is_imported_and_exported() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("measured.csv");
    let mut text = String::from("x_m,left_m,right_m\n");
    for i in 0..400 {
        let x = i as f64 * 0.1;
        text.push_str(&format!(
            "{x},{},{}\n",
            0.002 * (0.5 * x).sin(),
            0.001 * (0.3 * x).cos()
        ));
    }
    std::fs::write(&csv, text).unwrap();
    let out = dir.path().join("out");
    vbi()
        .args(["road", "--measured"])
        .arg(&csv)
        .arg("--out")
        .arg(&out)
        .assert()
        .success();
    let written = std::fs::read_to_string(out.join("profile.csv")).unwrap();
    assert_eq!(written.lines().count(), 401);
    assert!(out.join("psd.svg").is_file());
}

#[test]
fn measured_profile_with_a_bad_cell_exits_2_naming_the_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("bad.csv");
    std::fs::write(&csv, "x_m,left_m,right_m\n0,0,0\n0.1,abc,0\n").unwrap();
    let stderr = stderr_of(
        &vbi()
            .args(["road", "--measured"])
            .arg(&csv)
            .assert()
            .code(2),
    );
    assert!(stderr.contains("bad.csv:3:1"), "{stderr}");
    assert!(stderr.contains("left_m"), "{stderr}");
}

/// Issue 17, defect 4 and defect 7: 2²⁰ harmonics summed directly ran for minutes, and a road
/// file's generation errors were blamed on `--length`, which the user never gave. Now the sum
/// is bounded (2³⁰ terms per track) and the refusal names the file's `harmonic_count` line, in
/// `vbi road` and in `vbi run` of a scenario with that road.
#[test]
fn a_direct_sum_too_long_to_compute_is_refused_at_the_harmonic_count() {
    let dir = tempfile::tempdir().unwrap();
    let text =
        std::fs::read_to_string(repository_root().join("examples/roads/custom-harmonics.toml"))
            .unwrap()
            .replace("harmonic_count = 500", "harmonic_count = 1048576");
    let path = dir.path().join("road.toml");
    std::fs::write(&path, &text).unwrap();
    let line = text
        .lines()
        .position(|l| l.starts_with("harmonic_count"))
        .unwrap()
        + 1;
    let assert = vbi()
        .args(["road", path.to_str().unwrap(), "--out"])
        .arg(dir.path().join("out"))
        .timeout(std::time::Duration::from_secs(60))
        .assert()
        .code(2);
    let stderr = stderr_of(&assert);
    assert!(
        stderr.contains(&format!("road.toml:{line}:1: field `road.harmonic_count`")),
        "{stderr}"
    );
    assert!(stderr.contains("inverse_fft"), "{stderr}");
    assert!(!stderr.contains("--length"), "{stderr}");
    let scenario = std::fs::read_to_string(
        repository_root().join("examples/scenarios/inline-beam-quarter-car.toml"),
    )
    .unwrap();
    let road_table = scenario.find("[road]").unwrap();
    let scenario = format!("{}{}", &scenario[..road_table], text.replace("# ", "## "));
    let path = dir.path().join("scenario.toml");
    std::fs::write(&path, &scenario).unwrap();
    let line = scenario
        .lines()
        .position(|l| l.starts_with("harmonic_count"))
        .unwrap()
        + 1;
    let assert = vbi()
        .args(["run", path.to_str().unwrap(), "--out"])
        .arg(dir.path().join("run"))
        .timeout(std::time::Duration::from_secs(120))
        .assert()
        .code(2);
    let stderr = stderr_of(&assert);
    assert!(
        stderr.contains(&format!(
            "scenario.toml:{line}:1: field `road.harmonic_count`"
        )),
        "{stderr}"
    );
}
