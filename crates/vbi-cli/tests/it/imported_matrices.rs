//! End-to-end tests of bridges imported as matrices (`type = "imported_matrices"`): vbi's own
//! models written by `vbi modes --export-matrices` and read back give the same modes and
//! crossings (the round trip of issue 15), and broken imports are refused where they are broken.

use std::path::{Path, PathBuf};

use crate::common::{repository_root, vbi};

/// Exports `bridge` (a file under examples/bridges) into `dir`/`name` and returns the
/// directory of the export.
fn export(dir: &Path, bridge: &str, name: &str) -> PathBuf {
    let out = dir.join(name);
    vbi()
        .arg("modes")
        .arg(repository_root().join("examples/bridges").join(bridge))
        .args(["--modes", "2", "--export-matrices"])
        .arg(&out)
        .assert()
        .success();
    out
}

fn modes_json(file: &Path, modes: usize) -> serde_json::Value {
    let out = vbi()
        .arg("modes")
        .arg(file)
        .args(["--format", "json", "--modes", &modes.to_string()])
        .assert()
        .success();
    serde_json::from_slice(&out.get_output().stdout).unwrap()
}

/// `vbi run --format json` of a scenario on `bridge` (a path or a preset name).
fn run_json(dir: &Path, bridge: &str) -> serde_json::Value {
    let scenario = dir.join(format!("scenario-{}.toml", bridge.replace(['/', '.'], "-")));
    std::fs::write(
        &scenario,
        format!(
            "[scenario]\nbridge = \"{bridge}\"\nvehicle = \"three-axle-truck-36t\"\nroad = \
             \"good\"\nspeed_kmh = 80\nmodes = 20\n"
        ),
    )
    .unwrap();
    let out = vbi()
        .arg("run")
        .arg(&scenario)
        .args(["--format", "json"])
        .assert()
        .success();
    serde_json::from_slice(&out.get_output().stdout).unwrap()
}

#[test]
fn the_paper_grillage_exported_and_read_back_has_the_same_modes_to_round_off() {
    let dir = tempfile::tempdir().unwrap();
    let exported = export(dir.path(), "paper-2x20.toml", "export");
    for name in [
        "stiffness.mtx",
        "mass.mtx",
        "dofs.csv",
        "nodes.csv",
        "bridge.toml",
    ] {
        assert!(exported.join(name).is_file(), "{name} written");
    }
    let own = modes_json(
        &repository_root().join("examples/bridges/paper-2x20.toml"),
        12,
    );
    let imported = modes_json(&exported.join("bridge.toml"), 12);
    assert_eq!(own["dof_count"], imported["dof_count"]);
    assert_same_modes(&own, &imported, 12);
}

/// The same frequencies (to 1e-12: the same matrices in the same DOF order, so the same
/// Lanczos to round-off) and kinds of `count` modes.
fn assert_same_modes(own: &serde_json::Value, imported: &serde_json::Value, count: usize) {
    let (a, b) = (
        own["modes"].as_array().unwrap(),
        imported["modes"].as_array().unwrap(),
    );
    assert_eq!((a.len(), b.len()), (count, count));
    for (a, b) in a.iter().zip(b) {
        let (fa, fb) = (
            a["frequency_hz"].as_f64().unwrap(),
            b["frequency_hz"].as_f64().unwrap(),
        );
        assert!((fa - fb).abs() <= 1e-12 * fa, "{fa} Hz against {fb} Hz");
        assert_eq!(a["kind"], b["kind"]);
    }
}

#[test]
fn a_crossing_of_the_exported_grillage_gives_the_daf_of_the_native_one() {
    let dir = tempfile::tempdir().unwrap();
    export(dir.path(), "paper-2x20.toml", "export");
    let native = run_json(dir.path(), "paper-2x20");
    let imported = run_json(dir.path(), "export/bridge.toml");
    // (name, quantity, static max, dynamic max, DAF); the DAF is absent (null) where the
    // static response is zero (a deflection over a support).
    type Entry = (String, String, f64, f64, Option<f64>);
    let entries = |v: &serde_json::Value| -> Vec<Entry> {
        v["stations"]
            .as_array()
            .unwrap()
            .iter()
            .map(|s| {
                (
                    s["name"].as_str().unwrap().to_string(),
                    s["quantity"].as_str().unwrap().to_string(),
                    s["static_max"].as_f64().unwrap(),
                    s["dynamic_max"].as_f64().unwrap(),
                    s["daf"].as_f64(),
                )
            })
            .collect()
    };
    let native = entries(&native);
    let imported = entries(&imported);
    // The import reads deflection and moment (no shear or reaction: its matrices hold no
    // restrained DOF and no element); every one of its entries is in the native run.
    assert!(!imported.is_empty());
    assert!(imported
        .iter()
        .all(|e| e.1 == "deflection" || e.1 == "bending_moment"));
    for entry in &imported {
        let twin = native
            .iter()
            .find(|n| n.0 == entry.0 && n.1 == entry.1)
            .unwrap_or_else(|| panic!("{} {} in the native run", entry.0, entry.1));
        assert_eq!(
            twin.4.is_some(),
            entry.4.is_some(),
            "{} {}",
            entry.0,
            entry.1
        );
        let daf = (twin.4.unwrap_or(0.0), entry.4.unwrap_or(0.0));
        for (a, b) in [(twin.2, entry.2), (twin.3, entry.3), daf] {
            assert!(
                (a - b).abs() <= 1e-9 * a.abs(),
                "{} {}: {a} against {b}",
                entry.0,
                entry.1
            );
        }
    }
}

#[test]
fn a_two_span_beam_exported_as_a_frame_rotation_reads_back_the_same_modes() {
    // The beam's slope DOF dw/dx is written as θ_y = −dw/dx: a sign error would leave the
    // frequencies but break the deck's slopes, so the crossing is compared too.
    let dir = tempfile::tempdir().unwrap();
    export(dir.path(), "two-span-beam.toml", "beam");
    let own = modes_json(
        &repository_root().join("examples/bridges/two-span-beam.toml"),
        6,
    );
    let imported = modes_json(&dir.path().join("beam/bridge.toml"), 6);
    assert_same_modes(&own, &imported, 6);
    let native_path = repository_root().join("examples/bridges/two-span-beam.toml");
    let native = run_json(dir.path(), native_path.to_str().unwrap());
    let imported = run_json(dir.path(), "beam/bridge.toml");
    let daf = |v: &serde_json::Value, name: &str, quantity: &str| -> f64 {
        v["stations"]
            .as_array()
            .unwrap()
            .iter()
            .find(|s| s["name"] == name && s["quantity"] == quantity)
            .unwrap_or_else(|| panic!("{name} {quantity}"))["daf"]
            .as_f64()
            .unwrap()
    };
    for (name, quantity) in [
        ("span1_mid_section", "deflection"),
        ("span1_mid_section", "bending_moment"),
        ("support2_section", "bending_moment"),
    ] {
        let (a, b) = (daf(&native, name, quantity), daf(&imported, name, quantity));
        assert!(
            (a - b).abs() <= 1e-9 * a,
            "{name} {quantity}: {a} against {b}"
        );
    }
}

/// Writes a copy of the exported beam into a fresh directory, with `edit` applied to the file
/// `file`, and returns `vbi check`'s stderr (expecting exit code 2).
fn broken(file: &str, edit: impl Fn(&str) -> String) -> String {
    let dir = tempfile::tempdir().unwrap();
    let exported = export(dir.path(), "two-span-beam.toml", "beam");
    let path = exported.join(file);
    let text = std::fs::read_to_string(&path).unwrap();
    std::fs::write(&path, edit(&text)).unwrap();
    let out = vbi()
        .arg("check")
        .arg(exported.join("bridge.toml"))
        .assert()
        .code(2);
    String::from_utf8_lossy(&out.get_output().stderr).to_string()
}

#[test]
fn an_asymmetric_stiffness_is_refused_naming_the_entries() {
    // The symmetric file holds the lower triangle: written as `general`, one off-diagonal
    // entry has no mirror.
    let error = broken("stiffness.mtx", |text| {
        text.replacen("real symmetric", "real general", 1)
    });
    assert!(error.contains("stiffness.mtx` is not symmetric"), "{error}");
    assert!(error.contains("entries (2, 1) and (1, 2)"), "{error}");
    assert!(error.contains("field `bridge.stiffness_mtx`"), "{error}");
}

#[test]
fn a_dof_map_that_does_not_match_the_matrices_is_refused() {
    let error = broken("dofs.csv", |text| {
        let mut lines: Vec<&str> = text.lines().collect();
        lines.pop();
        lines.join("\n") + "\n"
    });
    // The matrices are larger than the map: refused at their size line, naming the map.
    assert!(error.contains("stiffness.mtx:3:1"), "{error}");
    assert!(
        error.contains("1 to 78 rows (one per DOF of the DOF map)"),
        "{error}"
    );
}

#[test]
fn a_deck_node_missing_from_the_nodes_file_is_refused_at_its_key() {
    let error = broken("bridge.toml", |text| {
        text.replacen("nodes = [1, ", "nodes = [9999, ", 1)
    });
    assert!(error.contains("bridge.deck_line[0].nodes[0]"), "{error}");
    assert!(
        error.contains("node 9999 is not in the nodes file"),
        "{error}"
    );
}

#[test]
fn an_unknown_unit_system_is_refused_with_the_allowed_ones() {
    let error = broken("bridge.toml", |text| {
        text.replace("units = \"N-m\"", "units = \"lb-ft\"")
    });
    assert!(error.contains("bridge.units"), "{error}");
    assert!(error.contains("`kN-m`"), "{error}");
}

#[test]
fn a_malformed_matrix_entry_is_refused_at_its_line() {
    let error = broken("mass.mtx", |text| {
        let mut lines: Vec<String> = text.lines().map(String::from).collect();
        lines[4] = "1 1 abc".into();
        lines.join("\n") + "\n"
    });
    assert!(error.contains("mass.mtx:5:"), "{error}");
    assert!(error.contains("is not an entry"), "{error}");
}

#[test]
fn span_and_mesh_axes_of_a_study_on_imported_matrices_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    export(dir.path(), "two-span-beam.toml", "beam");
    let study = dir.path().join("study.toml");
    std::fs::write(
        &study,
        "[study]\nname = \"s\"\nsamples = 1\n[study.axes]\nspan_length_m = [20.0, 25.0]\n\
         [scenario]\nbridge = \"beam/bridge.toml\"\nvehicle = \"moving-force\"\nmodes = 4\n",
    )
    .unwrap();
    let out = vbi().arg("check").arg(&study).assert().code(2);
    let error = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(error.contains("span_length_m"), "{error}");
    assert!(error.contains("an imported model's spans"), "{error}");
}

#[test]
fn an_indefinite_stiffness_is_refused_by_check_at_its_key() {
    // Symmetric, positive diagonal, but one coupling 10³ times the geometric mean of its two
    // diagonal entries: K has a negative eigenvalue, found by the factorisation `vbi check`
    // makes of an imported K (the modal solve's first step).
    let error = broken("stiffness.mtx", |text| {
        let mut diagonal = std::collections::HashMap::new();
        for line in text.lines().filter(|l| !l.starts_with('%')) {
            let f: Vec<&str> = line.split_whitespace().collect();
            if f.len() == 3 && f[0] == f[1] {
                diagonal.insert(f[0].to_string(), f[2].parse::<f64>().unwrap());
            }
        }
        let mut done = false;
        let lines: Vec<String> = text
            .lines()
            .map(|line| {
                let f: Vec<&str> = line.split_whitespace().collect();
                if !done && !line.starts_with('%') && f.len() == 3 && f[0] != f[1] {
                    done = true;
                    let coupling = 1e3 * (diagonal[f[0]] * diagonal[f[1]]).sqrt();
                    format!("{} {} {coupling:e}", f[0], f[1])
                } else {
                    line.to_string()
                }
            })
            .collect();
        lines.join("\n") + "\n"
    });
    assert!(error.contains("field `bridge.stiffness_mtx`"), "{error}");
    assert!(error.contains("not positive definite"), "{error}");
}

#[test]
fn a_study_runs_on_imported_matrices_as_on_any_bridge() {
    let dir = tempfile::tempdir().unwrap();
    export(dir.path(), "two-span-beam.toml", "beam");
    let study = dir.path().join("study.toml");
    std::fs::write(
        &study,
        "[study]\nname = \"imported\"\nseed = 5\nsamples = 2\n[study.axes]\n\
         bridge = [\"beam/bridge.toml\"]\nspeed_kmh = [60, 90]\n[scenario]\n\
         vehicle = \"three-axle-truck-36t\"\nroad = \"good\"\nmodes = 8\n",
    )
    .unwrap();
    vbi().arg("check").arg(&study).assert().success();
    let out = dir.path().join("out");
    vbi()
        .arg("study")
        .arg(&study)
        .arg("--out")
        .arg(&out)
        .assert()
        .success();
    let table = std::fs::read_to_string(out.join("cases.csv")).unwrap();
    let mut rows = csv::Reader::from_reader(table.as_bytes());
    let header = rows.headers().unwrap().clone();
    let column = |name: &str| header.iter().position(|h| h == name).unwrap();
    let (daf_u, daf_m) = (column("daf_u"), column("daf_m"));
    let records: Vec<csv::StringRecord> = rows.records().map(Result::unwrap).collect();
    assert_eq!(records.len(), 4);
    for record in &records {
        for c in [daf_u, daf_m] {
            let daf: f64 = record[c].parse().unwrap();
            // A good road: DAFs within a few tenths of 1 (a unit or sign error moves them by
            // factors).
            assert!((0.8..1.5).contains(&daf), "{record:?}");
        }
    }
}

#[test]
fn a_deck_node_without_a_vertical_dof_is_refused_with_the_axis_hint() {
    // vbi's own export is z up; read as y up, its deck nodes have no vertical translation (their
    // uz becomes lateral): without the check every deflection would read as restrained, zero.
    let error = broken("bridge.toml", |text| {
        text.replace("vertical_axis = \"z\"", "vertical_axis = \"y\"")
    });
    assert!(error.contains("bridge.deck_line[0].nodes[1]"), "{error}");
    assert!(error.contains("has no vertical translation"), "{error}");
    assert!(error.contains("the vertical DOF is `uy`"), "{error}");
}

#[test]
fn a_wheel_outside_an_imported_deck_is_refused() {
    // The paper 2 x 20 m grillage's lines lie at y = -2.9, 0, 2.9 m: wheels may run to half a
    // line spacing beyond the outer ones, 4.35 m.
    let dir = tempfile::tempdir().unwrap();
    export(dir.path(), "paper-2x20.toml", "export");
    let scenario = dir.path().join("wide.toml");
    std::fs::write(
        &scenario,
        "[scenario]\nbridge = \"export/bridge.toml\"\nvehicle = \"three-axle-truck-36t\"\n\
         lateral_position_m = 4.0\n",
    )
    .unwrap();
    let out = vbi().arg("run").arg(&scenario).assert().code(2);
    let error = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(
        error.contains("outside the deck (y from -4.350 to 4.350 m)"),
        "{error}"
    );
}
