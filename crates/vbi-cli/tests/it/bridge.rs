//! End-to-end tests of `[bridge]` input files, through `vbi check`.

use crate::common::{repository_root, vbi};

#[test]
fn every_example_bridge_passes_check() {
    // examples/bridges/*.toml and the imported basis in examples/bridges/imported/.
    let dir = repository_root().join("examples/bridges");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.push(dir.join("imported/two-span-imported.toml"));
    files.push(dir.join("imported/two-span-imported-with-lines.toml"));
    files.sort();
    assert_eq!(files.len(), 19, "{files:?}");
    let out = vbi().arg("check").args(&files).assert().success();
    let stdout = String::from_utf8_lossy(&out.get_output().stdout).to_string();
    assert_eq!(stdout.matches("ok (bridge)").count(), 19, "{stdout}");
}

fn check_error(text: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.toml");
    std::fs::write(&path, text).unwrap();
    let out = vbi().arg("check").arg(&path).assert().code(2);
    String::from_utf8_lossy(&out.get_output().stderr).to_string()
}

#[test]
fn an_out_of_range_girder_height_names_line_field_and_range() {
    let text = std::fs::read_to_string(repository_root().join("examples/bridges/paper-2x20.toml"))
        .unwrap()
        .replace("height_m = 1.2", "height_m = -1.2");
    let line = text
        .lines()
        .position(|l| l.starts_with("height_m = -1.2"))
        .unwrap()
        + 1;
    let stderr = check_error(&text);
    assert!(stderr.contains(&format!("bad.toml:{line}:")), "{stderr}");
    assert!(stderr.contains("bridge.girder.height_m"), "{stderr}");
    assert!(stderr.contains("expected from 0.001 to 100 m"), "{stderr}");
}

#[test]
fn an_unknown_key_and_an_unknown_support_are_rejected() {
    let stderr = check_error(
        "[bridge]\ntype = \"continuous_beam\"\nspan_lengths_m = [10.0]\ncolour = \"red\"\n",
    );
    assert!(stderr.contains("bad.toml:4:"), "{stderr}");
    assert!(stderr.contains("colour"), "{stderr}");
    let stderr = check_error(
        "[bridge]\ntype = \"continuous_beam\"\nspan_lengths_m = [10.0]\nsupports = [\"pinned\", \"hinged\"]\n\
         [bridge.section]\nflexural_rigidity_n_m2 = 1e9\nmass_per_length_kg_per_m = 1000.0\n",
    );
    assert!(stderr.contains("bridge.supports[1]"), "{stderr}");
    assert!(stderr.contains("\"roller\""), "{stderr}");
}

#[test]
fn a_grillage_without_a_pinned_support_is_reported_as_a_mechanism() {
    let text = std::fs::read_to_string(repository_root().join("examples/bridges/paper-2x20.toml"))
        .unwrap()
        .replace(
            "\"pinned\", \"roller\", \"roller\"",
            "\"roller\", \"roller\", \"roller\"",
        );
    let stderr = check_error(&text);
    assert!(stderr.contains("bridge.supports"), "{stderr}");
    assert!(stderr.contains("longitudinal"), "{stderr}");
}

#[test]
fn girders_wider_than_the_deck_are_reported_at_the_spacing() {
    let text = std::fs::read_to_string(repository_root().join("examples/bridges/paper-3x30.toml"))
        .unwrap()
        .replace("girder_spacing_m = 2.9", "girder_spacing_m = 5.0");
    let stderr = check_error(&text);
    assert!(stderr.contains("bridge.girder_spacing_m"), "{stderr}");
    assert!(stderr.contains("wider than the 8.5 m deck"), "{stderr}");
}

#[test]
fn an_unknown_bridge_type_lists_the_four_allowed() {
    let stderr = check_error("[bridge]\ntype = \"truss\"\nspan_lengths_m = [10.0]\n");
    assert!(stderr.contains("bad.toml:2:"), "{stderr}");
    assert!(stderr.contains("bridge.type"), "{stderr}");
    assert!(
        stderr.contains("`continuous_beam`, `grillage`, `imported_matrices` or `imported`"),
        "{stderr}"
    );
}

#[test]
fn a_skewed_grillage_runs_girder_by_girder_and_refuses_a_section_station() {
    // examples/bridges/skewed-2x20.toml: the default stations read each girder; a [[station]]
    // without a girder (the whole section) is refused at its key, as `vbi check` does.
    let bridge = repository_root().join("examples/bridges/skewed-2x20.toml");
    let out = vbi()
        .arg("modes")
        .arg(&bridge)
        .args(["--modes", "3"])
        .assert()
        .success();
    let text = String::from_utf8_lossy(&out.get_output().stdout).to_string();
    assert!(text.contains("skewed 30.0°"), "{text}");
    let scenario = format!(
        "[scenario]\nbridge = \"{}\"\nvehicle = \"moving-force\"\n\n[[station]]\nspan = 1\n\
         fraction = 0.5\n",
        bridge.display()
    );
    let stderr = check_error(&scenario);
    assert!(stderr.contains("station[0].girder"), "{stderr}");
    assert!(stderr.contains("skewed grillage"), "{stderr}");
    let stderr = check_error(
        &std::fs::read_to_string(&bridge)
            .unwrap()
            .replace("skew_angle_deg = 30.0", "skew_angle_deg = 50.0"),
    );
    assert!(stderr.contains("bridge.skew_angle_deg"), "{stderr}");
    assert!(stderr.contains("-45 to 45"), "{stderr}");
}
