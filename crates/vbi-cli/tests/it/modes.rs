//! End-to-end tests of `vbi modes` and its inputs.

use std::f64::consts::PI;
use std::path::Path;

use crate::common::{repository_root, vbi};

fn example(name: &str) -> std::path::PathBuf {
    repository_root().join("examples/bridges").join(name)
}

/// `vbi modes FILE --format json` with extra arguments, parsed.
fn json(file: &Path, extra: &[&str]) -> serde_json::Value {
    let out = vbi()
        .arg("modes")
        .arg(file)
        .args(["--format", "json"])
        .args(extra)
        .assert()
        .success();
    serde_json::from_slice(&out.get_output().stdout).expect("valid JSON on stdout")
}

fn frequencies(v: &serde_json::Value) -> Vec<f64> {
    v["modes"]
        .as_array()
        .expect("a `modes` array")
        .iter()
        .map(|m| m["frequency_hz"].as_f64().expect("a frequency"))
        .collect()
}

/// Writes `text` as a bridge file in a fresh directory and runs `vbi modes` on it, expecting
/// exit code 2; returns stderr.
fn modes_error(text: &str, extra: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.toml");
    std::fs::write(&path, text).unwrap();
    let out = vbi().arg("modes").arg(&path).args(extra).assert().code(2);
    String::from_utf8_lossy(&out.get_output().stderr).to_string()
}

#[test]
fn the_table_lists_mode_frequency_period_and_kind() {
    let out = vbi()
        .arg("modes")
        .arg(example("ss-beam-25m.toml"))
        .args(["--modes", "4"])
        .assert()
        .success();
    let text = String::from_utf8_lossy(&out.get_output().stdout).to_string();
    let lines: Vec<&str> = text.lines().collect();
    // 26 elements (1 m target, an even number so that mid-span is a node), 27 nodes × (w, θ)
    // less the two support deflections.
    assert!(lines[0].contains("52 degrees of freedom"), "{text}");
    // The model line: m̄L = 18358 kg/m × 25 m = 458.95 t, 27 nodes, 26 elements.
    assert!(lines[1].starts_with("model: 1 span(s), 25.000 m"), "{text}");
    assert!(lines[1].contains("total mass 458.9 t"), "{text}");
    assert!(lines[1].contains("27 nodes, 26 girder elements"), "{text}");
    for heading in ["mode", "frequency [Hz]", "period [s]", "kind", "residual"] {
        assert!(lines[2].contains(heading), "{text}");
    }
    assert_eq!(lines.len(), 3 + 4, "{text}");
    let first: Vec<&str> = lines[3].split_whitespace().collect();
    assert_eq!(first[0], "1");
    let f: f64 = first[1].parse().unwrap();
    let period: f64 = first[2].parse().unwrap();
    // The period is printed to 5 decimals: 1/f to half a unit of the last digit.
    assert!((period - 1.0 / f).abs() < 5e-6, "{f} Hz, {period} s");
    assert_eq!(first[3], "vertical_bending");
}

#[test]
fn json_has_the_dof_count_and_each_modes_index_frequency_kind_and_residual() {
    let v = json(&example("ss-beam-25m.toml"), &["--modes", "5"]);
    assert_eq!(v["dof_count"], 52);
    let modes = v["modes"].as_array().unwrap();
    assert_eq!(modes.len(), 5);
    for (i, m) in modes.iter().enumerate() {
        assert_eq!(m["index"], i + 1);
        assert_eq!(m["kind"], "vertical_bending");
        let residual = m["residual"].as_f64().unwrap();
        // The solver's own acceptance limit (ModalOptions::residual_limit, default 1e-6).
        assert!((0.0..1e-6).contains(&residual), "{residual}");
        let f = m["frequency_hz"].as_f64().unwrap();
        assert!(f > 0.0);
        if i > 0 {
            assert!(f > modes[i - 1]["frequency_hz"].as_f64().unwrap());
        }
    }
}

#[test]
fn simply_supported_frequencies_match_the_closed_form() {
    // Reference: docs/verification.md §1: ωₙ = (nπ/L)² √(EI/m̄), here
    // L = 25 m, EI = 3.5e10 Pa × 1.3901 m⁴, m̄ = 18358 kg/m (examples/bridges/ss-beam-25m.toml).
    let v = json(&example("ss-beam-25m.toml"), &["--modes", "6"]);
    let (length, ei, mass): (f64, f64, f64) = (25.0, 3.5e10 * 1.3901, 18358.0);
    // The default mesh: 26 equal elements (mid-span on a node).
    let h = length / 26.0;
    for (i, f) in frequencies(&v).into_iter().enumerate() {
        let n = (i + 1) as f64;
        let k = n * PI / length;
        let exact = k * k * (ei / mass).sqrt() / (2.0 * PI);
        // Cubic Hermite elements with consistent mass overestimate ω by (kh)⁴/1440 to leading
        // order (crates/vbi/tests/it/verification_fe_analytical.rs): ratio 0.95 to 1.01 leaves
        // room for the O((kh)⁶) term (< 0.2 % here, kh ≤ 0.73) and for the printed
        // frequency's round-off (JSON keeps all digits; 1e-12 relative ≪ 1 % of 1.6e-7).
        let estimate = (k * h).powi(4) / 1440.0;
        let ratio = (f / exact - 1.0) / estimate;
        assert!(
            (0.95..=1.01).contains(&ratio),
            "mode {n}: {f} Hz vs {exact} Hz, error {ratio} × (kh)⁴/1440"
        );
    }
}

#[test]
fn out_writes_the_mode_table_the_shapes_and_the_figure() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("modes");
    vbi()
        .arg("modes")
        .arg(example("two-span-beam.toml"))
        .args(["--modes", "7", "--format", "json", "--out"])
        .arg(&out_dir)
        .assert()
        .success();
    let modes = std::fs::read_to_string(out_dir.join("modes.csv")).unwrap();
    let mut lines = modes.lines();
    assert_eq!(
        lines.next(),
        Some("mode,frequency_hz,period_s,kind,residual")
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 7);
    for (i, row) in rows.iter().enumerate() {
        assert_eq!(row[0], (i + 1).to_string());
        let f: f64 = row[1].parse().unwrap();
        let period: f64 = row[2].parse().unwrap();
        // Both written at full precision: reciprocal to round-off.
        assert!((f * period - 1.0).abs() < 1e-12);
        assert_eq!(row[3], "vertical_bending");
    }
    // Two-span ratio f₂/f₁ = 1.56219 (docs/verification.md §3, 6 digits): half a unit
    // of the last digit plus the FE error of the 1 m mesh ((kh)⁴/1440 ≈ 3e-7 for mode 2).
    let f1: f64 = rows[0][1].parse().unwrap();
    let f2: f64 = rows[1][1].parse().unwrap();
    assert!((f2 / f1 - 1.56219).abs() < 5e-6 + 1e-6, "{}", f2 / f1);

    let shapes = std::fs::read_to_string(out_dir.join("mode_shapes.csv")).unwrap();
    let mut lines = shapes.lines();
    let header = lines.next().unwrap();
    assert_eq!(
        header,
        "line,node,x_m,y_m,mode_1,mode_2,mode_3,mode_4,mode_5,mode_6,mode_7"
    );
    // 2 × 20 m at 1 m elements: 41 deck nodes on one line.
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 41);
    assert_eq!(rows[0][2], 0.0);
    assert_eq!(rows[40][2], 40.0);
    // Supports at 0, 20 and 40 m do not deflect.
    for row in [&rows[0], &rows[20], &rows[40]] {
        assert!(row[4..].iter().all(|&w| w == 0.0), "{row:?}");
    }
    for stem in ["mode_shapes.png", "mode_shapes.svg"] {
        let size = std::fs::metadata(out_dir.join(stem)).unwrap().len();
        assert!(size > 1000, "{stem}: {size} bytes");
    }
}

#[test]
fn zero_modes_is_refused_with_exit_2() {
    let out = vbi()
        .arg("modes")
        .arg(example("ss-beam-25m.toml"))
        .args(["--modes", "0"])
        .assert()
        .code(2);
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(stderr.contains("--modes"), "{stderr}");
    assert!(stderr.contains("at least 1"), "{stderr}");
}

const BEAM_SECTION: &str = "[bridge.section]\nflexural_rigidity_n_m2 = 4.86535e10\n\
                            mass_per_length_kg_per_m = 18358.0\n";

#[test]
fn an_unrestrained_bridge_exits_2_naming_the_free_direction() {
    // Both supports springs without vertical stiffness: the beam floats.
    let stderr = modes_error(
        &format!(
            "[bridge]\ntype = \"continuous_beam\"\nspan_lengths_m = [20.0]\n\
             supports = [{{ kind = \"elastic\" }}, {{ kind = \"elastic\" }}]\n{BEAM_SECTION}"
        ),
        &[],
    );
    assert!(stderr.contains("bad.toml:4:"), "{stderr}");
    assert!(stderr.contains("bridge.supports"), "{stderr}");
    assert!(stderr.contains("vertical translation"), "{stderr}");
    // One pin and a spring without stiffness: the beam turns about the pin.
    let stderr = modes_error(
        &format!(
            "[bridge]\ntype = \"continuous_beam\"\nspan_lengths_m = [20.0]\n\
             supports = [\"pinned\", {{ kind = \"elastic\" }}]\n{BEAM_SECTION}"
        ),
        &[],
    );
    assert!(
        stderr.contains("rotation about the lateral axis"),
        "{stderr}"
    );
    // A grillage on rollers only slides along the bridge.
    let text = std::fs::read_to_string(example("paper-2x20.toml"))
        .unwrap()
        .replace(
            "\"pinned\", \"roller\", \"roller\"",
            "\"roller\", \"roller\", \"roller\"",
        );
    let stderr = modes_error(&text, &["--modes", "3"]);
    assert!(stderr.contains("longitudinal translation"), "{stderr}");
}

// ---------------------------------------------------------------------------------------------
// Imported modal data (`type = "imported"`)
// ---------------------------------------------------------------------------------------------

const IMPORTED_DIR: &str = "examples/bridges/imported";

#[test]
fn the_imported_example_lists_the_two_span_modes_it_was_generated_from() {
    // examples/bridges/imported/ was written from our own modes of two-span-beam.toml
    // (regenerate_the_imported_example below): listing it must give the same frequencies.
    let imported = json(
        &repository_root()
            .join(IMPORTED_DIR)
            .join("two-span-imported.toml"),
        &[],
    );
    let own = json(&example("two-span-beam.toml"), &["--modes", "10"]);
    assert_eq!(
        imported["dof_count"], 0,
        "an imported basis has no DOF count"
    );
    let (fi, fo) = (frequencies(&imported), frequencies(&own));
    assert_eq!(fi.len(), 10);
    for (a, b) in fi.iter().zip(&fo) {
        // Written with Rust's shortest round-trip formatting: equal up to the solver's
        // run-to-run round-off (the CSV and this run solve the same system).
        assert!((a / b - 1.0).abs() < 1e-9, "{a} vs {b}");
    }
    for m in imported["modes"].as_array().unwrap() {
        assert_eq!(m["kind"], "vertical_bending");
        assert_eq!(m["residual"], 0.0);
    }
    // --modes N lists the first N.
    let first = json(
        &repository_root()
            .join(IMPORTED_DIR)
            .join("two-span-imported.toml"),
        &["--modes", "3"],
    );
    assert_eq!(frequencies(&first), fi[..3].to_vec());
}

#[test]
fn the_imported_example_passes_check_and_writes_outputs() {
    let file = repository_root()
        .join(IMPORTED_DIR)
        .join("two-span-imported.toml");
    let out = vbi().arg("check").arg(&file).assert().success();
    let stdout = String::from_utf8_lossy(&out.get_output().stdout).to_string();
    assert!(stdout.contains("ok (bridge)"), "{stdout}");
    let dir = tempfile::tempdir().unwrap();
    let out = vbi()
        .arg("modes")
        .arg(&file)
        .arg("--out")
        .arg(dir.path())
        .assert()
        .success();
    let text = String::from_utf8_lossy(&out.get_output().stdout).to_string();
    assert!(text.contains("(imported modes): 10 modes"), "{text}");
    let shapes = std::fs::read_to_string(dir.path().join("mode_shapes.csv")).unwrap();
    assert_eq!(shapes.lines().count(), 1 + 41);
    assert!(dir.path().join("mode_shapes.svg").is_file());
}

/// An imported bridge file beside its CSV files in a fresh directory.
fn imported_case(bridge_extra: &str, frequencies: &str) -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("f.csv"), frequencies).unwrap();
    std::fs::write(
        dir.path().join("s.csv"),
        "line_y_m,x_m,mode_1,mode_2\n0,0,0,0\n0,5,0.01,0.02\n0,10,0,0\n",
    )
    .unwrap();
    let path = dir.path().join("b.toml");
    std::fs::write(
        &path,
        format!(
            "[bridge]\ntype = \"imported\"\nfrequencies_csv = \"f.csv\"\nshapes_csv = \"s.csv\"\n{bridge_extra}"
        ),
    )
    .unwrap();
    (dir, path)
}

#[test]
fn imported_paths_are_relative_to_the_bridge_file_and_errors_name_the_csv_cell() {
    let (_dir, path) = imported_case("damping_ratio = 0.02\n", "mode,frequency_hz\n1,3\n2,7\n");
    let v = json(&path, &[]);
    assert_eq!(frequencies(&v), vec![3.0, 7.0]);

    // A bad cell: the CSV file, its line and column, and the column name.
    let (_dir, path) = imported_case("", "mode,frequency_hz\n1,3\n2,-7\n");
    let out = vbi().arg("modes").arg(&path).assert().code(2);
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(stderr.contains("f.csv:3:2"), "{stderr}");
    assert!(stderr.contains("frequency_hz"), "{stderr}");

    // A missing file and an unknown key: the bridge file's line and key.
    let (_dir, path) = imported_case(
        "station_moments_csv = \"nope.csv\"\n",
        "mode,frequency_hz\n1,3\n2,7\n",
    );
    let out = vbi().arg("check").arg(&path).assert().code(2);
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(stderr.contains("b.toml:5:"), "{stderr}");
    assert!(stderr.contains("bridge.station_moments_csv"), "{stderr}");
    let (_dir, path) = imported_case("damping_ratio = 1.5\n", "mode,frequency_hz\n1,3\n2,7\n");
    let out = vbi().arg("check").arg(&path).assert().code(2);
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(stderr.contains("bridge.damping_ratio"), "{stderr}");
    assert!(stderr.contains("from 0 to 0.99"), "{stderr}");
    let (_dir, path) = imported_case("spans_m = [10.0]\n", "mode,frequency_hz\n1,3\n2,7\n");
    let out = vbi().arg("check").arg(&path).assert().code(2);
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(stderr.contains("spans_m"), "{stderr}");
    // Spans that do not add up to the deck (10 m): refused at their key.
    let (_dir, path) = imported_case("span_lengths_m = [4.0]\n", "mode,frequency_hz\n1,3\n2,7\n");
    let out = vbi().arg("check").arg(&path).assert().code(2);
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(stderr.contains("bridge.span_lengths_m"), "{stderr}");
    assert!(
        stderr.contains("add up to 4 m but the deck is 10 m"),
        "{stderr}"
    );
}

/// Regenerates examples/bridges/imported/*.csv from our own modes of
/// examples/bridges/two-span-beam.toml (default 1 m mesh, 10 modes):
/// `cargo test -p vbi-cli --test it regenerate_the_imported_example -- --ignored`.
#[test]
#[ignore = "writes the example files; run by hand after a change of the FE model"]
fn regenerate_the_imported_example() {
    use vbi::fe::{discretise, MeshOptions};
    use vbi::modal::{solve_modes, ModalOptions, StationTarget};
    use vbi::model::{BeamSection, ContinuousBeam, SupportKind};

    // The model of examples/bridges/two-span-beam.toml.
    let model = vbi::model::BridgeModel::ContinuousBeam(ContinuousBeam {
        span_lengths: vec![20.0, 20.0],
        supports: vec![SupportKind::Pinned; 3],
        section: BeamSection {
            flexural_rigidity: 4.86535e10,
            mass_per_length: 18358.0,
        },
        added_mass_per_length: 0.0,
        damping_ratio: 0.0,
        mode_damping: None,
        damage: Default::default(),
    });
    let fe = discretise(&model, &MeshOptions::default()).unwrap();
    let options = ModalOptions {
        mode_count: 10,
        ..ModalOptions::default()
    };
    let basis = solve_modes(&fe, &options).unwrap();
    let n = basis.mode_count();
    let dir = repository_root().join(IMPORTED_DIR);
    let banner = "# Generated by vbi from its own FE modes of examples/bridges/two-span-beam.toml \
                  (2 x 20 m, 1 m elements), not from another program:\n# see \
                  crates/vbi-cli/tests/it/modes.rs, regenerate_the_imported_example.\n";
    let modes: String = (1..=n).map(|k| format!(",mode_{k}")).collect();

    let mut text = format!("{banner}mode,frequency_hz,damping_ratio,kind\n");
    for (k, m) in basis.modes.iter().enumerate() {
        text += &format!("{},{},,vertical_bending\n", k + 1, m.frequency_hz());
    }
    std::fs::write(dir.join("frequencies.csv"), text).unwrap();

    let mut text = format!("{banner}line_y_m,x_m{modes}\n");
    for line in &basis.deck.lines {
        for (i, &x) in line.node_positions.iter().enumerate() {
            let node = line.first_node + i;
            text += &format!("{},{x}", line.lateral_position);
            for k in 0..n {
                // `+ 0.0` writes −0 as 0.
                text += &format!(",{}", basis.deck_deflection[node * n + k] + 0.0);
            }
            text += "\n";
        }
    }
    std::fs::write(dir.join("shapes.csv"), text).unwrap();

    let mut text = format!("{banner}station,x_m,target,over_support{modes}\n");
    for (s, station) in basis.stations.iter().enumerate() {
        let target = match station.target {
            StationTarget::Section => "section".to_string(),
            StationTarget::Girder(g) => format!("girder_{}", g + 1),
        };
        text += &format!(
            "{},{},{target},{}",
            station.name, station.position, station.over_support
        );
        for k in 0..n {
            text += &format!(",{}", basis.station_moment[s * n + k]);
        }
        text += "\n";
    }
    std::fs::write(dir.join("station_moments.csv"), text).unwrap();

    // The exact static reference, for two-span-imported-with-lines.toml: each station's
    // deflection and moment under a unit load at each node, the moment read on the side of the
    // station away from the load.
    let exact = vbi::fe::statics::influence_lines(&fe).unwrap();
    let mut text = format!("{banner}station,line_y_m,x_m,deflection_m_per_n,moment_n_m_per_n\n");
    for (s, station) in basis.stations.iter().enumerate() {
        for line in &basis.deck.lines {
            for (i, &x) in line.node_positions.iter().enumerate() {
                let node = line.first_node + i;
                let moment = if x >= station.position {
                    &exact.moment_left[s]
                } else {
                    &exact.moment_right[s]
                };
                text += &format!(
                    "{},{},{x},{},{}\n",
                    station.name,
                    line.lateral_position,
                    exact.deflection[s].deflection[node] + 0.0,
                    moment.deflection[node] + 0.0
                );
            }
        }
    }
    std::fs::write(dir.join("influence_lines.csv"), text).unwrap();
}

/// A bridge with a damping law and damage: `vbi check` accepts it, and `vbi modes` shows each
/// mode's damping ratio (Rayleigh: ζ = α/(2ω) + βω/2, between 2 % and 4 % from 3 to 20 Hz).
#[test]
fn a_damaged_bridge_with_rayleigh_damping_is_checked_and_its_modes_show_their_damping() {
    let path = example("damaged-3x30.toml");
    vbi().arg("check").arg(&path).assert().success();
    let modes = json(&path, &["--modes", "6"]);
    let intact = json(&example("paper-3x30.toml"), &["--modes", "6"]);
    let (damaged_f, intact_f) = (frequencies(&modes), frequencies(&intact));
    assert!(damaged_f[0] < intact_f[0], "{damaged_f:?} vs {intact_f:?}");
    for (mode, f) in modes["modes"].as_array().unwrap().iter().zip(&damaged_f) {
        let ratio = mode["damping_ratio"]
            .as_f64()
            .expect("a damping ratio per mode");
        let (w, w1, w2) = (2.0 * PI * f, 2.0 * PI * 3.0, 2.0 * PI * 20.0);
        let alpha = 2.0 * w1 * w2 * (0.02 * w2 - 0.04 * w1) / (w2 * w2 - w1 * w1);
        let beta = 2.0 * (0.04 * w2 - 0.02 * w1) / (w2 * w2 - w1 * w1);
        let expected = alpha / (2.0 * w) + beta * w / 2.0;
        assert!((ratio - expected).abs() < 1e-12, "{ratio} vs {expected}");
    }
    // Without a damping law the JSON has no damping column (outputs unchanged).
    assert!(intact["modes"][0].get("damping_ratio").is_none());
}

/// The per-mode list applies to the modes as `vbi modes` numbers them; beyond it, the last.
#[test]
fn a_per_mode_damping_list_gives_the_listed_modes_their_ratios_and_the_rest_the_last() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("beam.toml");
    let text = std::fs::read_to_string(example("ss-beam-25m.toml")).unwrap();
    let text = text
        .lines()
        .filter(|line| !line.starts_with("damping_ratio"))
        .collect::<Vec<_>>()
        .join("\n")
        .replace("[bridge]\n", "[bridge]\ndamping_ratios = [0.01, 0.02]\n");
    std::fs::write(&path, text).unwrap();
    let modes = json(&path, &["--modes", "3"]);
    let ratios: Vec<f64> = modes["modes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m["damping_ratio"].as_f64().unwrap())
        .collect();
    assert_eq!(ratios, [0.01, 0.02, 0.02]);
}

/// Bad damage and damping inputs exit 2 before any analysis, with the file, line and field.
#[test]
fn bad_damage_and_damping_inputs_exit_2_with_located_messages() {
    let beam = std::fs::read_to_string(example("ss-beam-25m.toml")).unwrap();
    let loss = |start: f64, end: f64, factor: f64| {
        format!(
            "{beam}\n[[bridge.stiffness_loss]]\nstart_m = {start:?}\nend_m = {end:?}\n\
             modulus_factor = {factor:?}\n"
        )
    };
    let stderr = modes_error(&loss(20.0, 30.0, 0.5), &[]);
    assert!(
        stderr.contains("bad.toml:") && stderr.contains("bridge.stiffness_loss[0].end_m"),
        "a located message: {stderr}"
    );
    assert!(stderr.contains("on the bridge"), "{stderr}");
    let stderr = modes_error(&loss(5.0, 10.0, 0.0), &[]);
    assert!(
        stderr.contains("bridge.stiffness_loss[0].modulus_factor") && stderr.contains("above 0"),
        "{stderr}"
    );
    let stderr = modes_error(&loss(12.0, 8.0, 0.5), &[]);
    assert!(stderr.contains("after the start"), "{stderr}");
    let both = beam.replace("[bridge]\n", "[bridge]\ndamping_ratios = [0.02]\n");
    assert!(
        both.contains("damping_ratio ="),
        "the example gives damping_ratio"
    );
    let stderr = modes_error(&both, &[]);
    assert!(
        stderr.contains("bridge.damping_ratio") && stderr.contains("both give the damping"),
        "{stderr}"
    );
    let mechanism = format!(
        "{beam}\n[[bridge.support_change]]\nsupport = 1\nvertical_stiffness_n_per_m = 0.0\n"
    );
    let stderr = modes_error(&mechanism, &[]);
    assert!(
        stderr.contains("bridge.support_change") && stderr.contains("do not hold the bridge"),
        "{stderr}"
    );
}

#[test]
fn a_grillage_of_your_own_prints_each_girders_section_and_draws_its_plan() {
    // examples/bridges/i-girder-3-span.toml: five I-girders, the outer two with a narrower deck
    // share (2.2 m against 2.4 m) and so a smaller area; the plan figure is written whole.
    let dir = tempfile::tempdir().unwrap();
    let out = vbi()
        .arg("modes")
        .arg(example("i-girder-3-span.toml"))
        .args(["--modes", "3", "--out"])
        .arg(dir.path())
        .assert()
        .success();
    let text = String::from_utf8_lossy(&out.get_output().stdout).to_string();
    let rows: Vec<Vec<&str>> = text
        .lines()
        .filter(|l| l.contains("i_girder"))
        .map(|l| l.split_whitespace().collect())
        .collect();
    assert_eq!(rows.len(), 5, "{text}");
    let area = |row: &Vec<&str>| row[3].parse::<f64>().unwrap();
    assert!(
        area(&rows[0]) < area(&rows[1]) && area(&rows[0]) == area(&rows[4]),
        "{text}"
    );
    assert!(text.contains("total mass"), "{text}");
    for file in ["plan.png", "plan.svg"] {
        assert!(std::fs::metadata(dir.path().join(file)).unwrap().len() > 1000);
    }
    let v = json(&example("i-girder-3-span.toml"), &["--modes", "2"]);
    assert_eq!(v["model"]["girders"].as_array().unwrap().len(), 5);
    assert_eq!(v["model"]["deck_width_m"], 11.6);
}
