//! End-to-end tests of `vbi run`: exit codes, the JSON summary, the output directory and
//! determinism. They use a small scenario (inline 20 m beam, sprung mass, 4 modes, short road)
//! so that each run takes a fraction of a second.

use crate::common::{repository_root, vbi};

/// Runs `vbi` and returns (exit code, stdout, stderr).
pub(crate) fn run(args: &[&str]) -> (i32, String, String) {
    let out = vbi().args(args).output().expect("vbi runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).to_string(),
        String::from_utf8_lossy(&out.stderr).to_string(),
    )
}

/// A fast scenario: a 20 m simply supported beam (inline), the VBI-2D sprung mass, a 'good'
/// road with 10 m approach and exit, 4 modes.
pub(crate) const SMALL: &str = r#"[scenario]
name = "small-beam"
vehicle = "sprung-mass"
speed_kmh = 100.0
modes = 4
element_length_m = 1.0
free_vibration_s = 0.2

[bridge]
type = "continuous_beam"
span_lengths_m = [20.0]
supports = ["pinned", "roller"]
damping_ratio = 0.02

[bridge.section]
flexural_rigidity_n_m2 = 4.86535e10
mass_per_length_kg_per_m = 18358.0

[road]
class = "good"
approach_length_m = 10.0
exit_length_m = 10.0
seed = 5
"#;

/// Writes `text` as `name` in a new temporary directory.
fn scenario_file(name: &str, text: &str) -> (tempfile::TempDir, String) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, text).unwrap();
    let path = path.to_str().unwrap().to_string();
    (dir, path)
}

#[test]
fn bad_scenario_value_exits_2_naming_file_line_and_field() {
    let text = SMALL.replace("speed_kmh = 100.0", "speed_kmh = -5.0");
    let (_dir, path) = scenario_file("bad.toml", &text);
    let (code, stdout, stderr) = run(&["run", &path]);
    assert_eq!(code, 2, "stderr: {stderr}");
    assert!(
        stdout.is_empty(),
        "nothing on stdout for a bad input: {stdout}"
    );
    // speed_kmh is on line 4 of the file.
    assert!(stderr.contains("bad.toml:4:"), "{stderr}");
    assert!(stderr.contains("scenario.speed_kmh"), "{stderr}");
    assert!(
        stderr.contains("-5"),
        "the offending value is named: {stderr}"
    );
}

#[test]
fn unknown_scenario_key_and_unknown_preset_exit_2() {
    let text = SMALL.replace("modes = 4", "modes = 4\nmode_count = 4");
    let (_dir, path) = scenario_file("unknown.toml", &text);
    let (code, _, stderr) = run(&["run", &path]);
    assert_eq!(code, 2, "stderr: {stderr}");
    assert!(stderr.contains("unknown.toml:"), "{stderr}");
    assert!(stderr.contains("mode_count"), "{stderr}");

    let text = SMALL.replace("vehicle = \"sprung-mass\"", "vehicle = \"lorry\"");
    let (_dir, path) = scenario_file("preset.toml", &text);
    let (code, _, stderr) = run(&["run", &path]);
    assert_eq!(code, 2, "stderr: {stderr}");
    assert!(stderr.contains("preset.toml:3:"), "{stderr}");
    assert!(stderr.contains("scenario.vehicle"), "{stderr}");

    let text = SMALL.replace("modes = 4", "modes = 0");
    let (_dir, path) = scenario_file("modes.toml", &text);
    let (code, _, stderr) = run(&["run", &path]);
    assert_eq!(code, 2, "stderr: {stderr}");
    assert!(stderr.contains("modes.toml:5:"), "{stderr}");
    assert!(stderr.contains("scenario.modes"), "{stderr}");
}

#[test]
fn json_summary_has_every_station_field_and_the_provenance() {
    let (_dir, path) = scenario_file("small.toml", SMALL);
    let (code, stdout, stderr) = run(&["run", &path, "--format", "json"]);
    assert_eq!(code, 0, "stderr: {stderr}");
    let summary: serde_json::Value = serde_json::from_str(&stdout).expect("stdout is JSON");
    let stations = summary["stations"].as_array().expect("stations array");
    // A single-span beam: the mid-span section, deflection, bending moment and shear force.
    assert!(stations.len() >= 2, "{stations:?}");
    for station in stations {
        for key in [
            "name",
            "quantity",
            "static_max",
            "dynamic_max",
            "daf",
            "impact_factor",
            "daf_change",
            "converged",
            "daf_by_modes",
            "convergence_mode",
            "static_corrected",
            "dynamic_max_paper",
            "daf_paper",
            "daf_paper_by_modes",
            "convergence_mode_paper",
            "participation",
            "cutoff_k1",
            "cutoff_k2",
        ] {
            assert!(station.get(key).is_some(), "{key} missing in {station}");
        }
        let quantity = station["quantity"].as_str().unwrap();
        assert!(["deflection", "bending_moment", "shear_force"].contains(&quantity));
        assert_eq!(station["daf_by_modes"].as_array().unwrap().len(), 4);
        assert_eq!(station["participation"].as_array().unwrap().len(), 4);
    }
    let mid = stations
        .iter()
        .find(|s| s["quantity"] == "deflection" && !s["daf"].is_null())
        .expect("a deflection station with a DAF");
    let daf = mid["daf"].as_f64().unwrap();
    // A sprung mass at 100 km/h on a 'good' road: amplification, but not an order of magnitude.
    assert!(daf > 0.9 && daf < 2.0, "DAF {daf}");
    let daf_by_modes = mid["daf_by_modes"].as_array().unwrap();
    // DAF(N) from the sampled partial sums; the headline DAF takes the extreme between the
    // instants (docs/theory.md): at least DAF(N), within 0.1 % of it.
    let sampled = daf_by_modes[3].as_f64().unwrap();
    assert!(
        daf >= sampled && daf - sampled <= 1e-3 * daf,
        "{daf} vs {sampled}"
    );

    let shear = stations
        .iter()
        .find(|s| s["quantity"] == "shear_force")
        .expect("the mid-span's shear force");
    assert!(shear["static_max"].as_f64().unwrap() != 0.0, "{shear}");
    assert!(shear["daf"].as_f64().is_some(), "{shear}");
    assert_eq!(shear["static_corrected"], true, "{shear}");
    assert!(summary["rdm"].as_f64().is_some(), "{}", summary["rdm"]);
    assert_eq!(summary["rdm_by_modes"].as_array().unwrap().len(), 4);
    let provenance = &summary["provenance"];
    assert_eq!(
        provenance["vbi_version"].as_str(),
        Some(env!("CARGO_PKG_VERSION"))
    );
    let hash = provenance["input_hash"].as_str().unwrap();
    assert_eq!(hash.len(), 64, "SHA-256 in hex: {hash}");
    assert_eq!(provenance["seed"].as_u64(), Some(5));
    assert_eq!(provenance["modes"].as_u64(), Some(4));
    let dt = provenance["time_step_s"].as_f64().unwrap();
    assert!(dt > 0.0 && dt <= 1e-3, "default dt capped at 1 ms: {dt}");
}

#[test]
fn out_directory_holds_summary_csvs_and_figures() {
    let (dir, path) = scenario_file("small.toml", SMALL);
    let out = dir.path().join("out");
    let (code, stdout, stderr) = run(&["run", &path, "--out", out.to_str().unwrap()]);
    assert_eq!(code, 0, "stderr: {stderr}");
    assert!(
        stdout.contains("DAF"),
        "the table is still printed: {stdout}"
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert!(summary["stations"].is_array());
    let histories = std::fs::read_to_string(out.join("histories.csv")).unwrap();
    let header = histories.lines().next().unwrap();
    assert!(header.starts_with("time_s,"), "{header}");
    assert!(histories.lines().count() > 100, "one row per time step");
    let daf = std::fs::read_to_string(out.join("daf_by_modes.csv")).unwrap();
    assert!(daf.starts_with("station,quantity,modes,daf"), "{daf}");
    let participation = std::fs::read_to_string(out.join("participation.csv")).unwrap();
    assert!(participation.starts_with("mode,"), "{participation}");
    assert_eq!(
        participation.lines().count(),
        1 + 4,
        "header and one row per mode"
    );
    // modes_kept.csv: one row per number of modes kept; its last row holds the full run's
    // paper CMs (at the RDM station) and deck-wide cut-off modes of summary.json.
    let kept = std::fs::read_to_string(out.join("modes_kept.csv")).unwrap();
    let rows: Vec<Vec<&str>> = kept.lines().map(|l| l.split(',').collect()).collect();
    assert_eq!(
        rows[0],
        [
            "modes_kept",
            "cm_u_paper",
            "cm_m_paper",
            "k1_u",
            "k2_u",
            "k1_m",
            "k2_m"
        ]
    );
    assert_eq!(rows.len(), 1 + 4);
    let last = &rows[4];
    let rdm_station = summary["rdm_station"].as_str().unwrap();
    let entry = |quantity: &str| {
        summary["stations"]
            .as_array()
            .unwrap()
            .iter()
            .find(|e| e["name"] == rdm_station && e["quantity"] == quantity)
            .unwrap()
            .clone()
    };
    let text = |value: &serde_json::Value| value.as_u64().map(|v| v.to_string()).unwrap();
    assert_eq!(
        last[1],
        text(&entry("deflection")["convergence_mode_paper"])
    );
    assert_eq!(
        last[2],
        text(&entry("bending_moment")["convergence_mode_paper"])
    );
    let deck = &summary["deck_participation"];
    for (column, key) in [
        (3, "deflection_k1"),
        (4, "deflection_k2"),
        (5, "moment_k1"),
        (6, "moment_k2"),
    ] {
        assert_eq!(last[column], text(&deck[key]), "{key}: {kept}");
    }
    for stem in [
        "history_deflection",
        "history_moment",
        "daf_by_modes",
        "modal_decomposition",
        "participation_deflection",
        "participation_moment",
    ] {
        for ext in ["png", "svg"] {
            let file = out.join(format!("{stem}.{ext}"));
            let size = std::fs::metadata(&file).map(|m| m.len()).unwrap_or(0);
            assert!(size > 0, "{} missing or empty", file.display());
        }
    }
}

#[test]
fn same_scenario_gives_identical_json_bytes() {
    // Reference: issue 5, determinism (seeded ChaCha road, fixed operation order).
    let (_dir, path) = scenario_file("small.toml", SMALL);
    let (code, first, _) = run(&["run", &path, "--format", "json"]);
    assert_eq!(code, 0);
    let (_, second, _) = run(&["run", &path, "--format", "json"]);
    assert_eq!(first, second);
    // A different seed changes the road and so the numbers, but not the structure.
    let (_dir2, path2) = scenario_file("small.toml", &SMALL.replace("seed = 5", "seed = 6"));
    let (_, third, _) = run(&["run", &path2, "--format", "json"]);
    assert_ne!(first, third);
}

#[test]
fn table_shows_daf_im_cm_k1_k2_and_rdm() {
    let (_dir, path) = scenario_file("small.toml", SMALL);
    let (code, stdout, stderr) = run(&["run", &path]);
    assert_eq!(code, 0, "stderr: {stderr}");
    for column in ["static max", "dynamic max", "DAF", "IM", "CM", "K1", "K2"] {
        assert!(stdout.contains(column), "{column} missing:\n{stdout}");
    }
    assert!(stdout.contains("span1_mid_section"), "{stdout}");
    assert!(stdout.contains("RDM"), "{stdout}");
}

#[test]
fn example_scenarios_pass_check() {
    // CI runs `vbi check` on every example; `vbi run` on each is exercised by hand (the paper
    // grillage takes ~0.5 s per run, too slow for the test suite).
    let dir = repository_root().join("examples/scenarios");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    assert!(files.len() >= 4, "{files:?}");
    let args: Vec<&str> = std::iter::once("check")
        .chain(files.iter().map(|p| p.to_str().unwrap()))
        .collect();
    let (code, stdout, stderr) = run(&args);
    assert_eq!(code, 0, "{stdout}{stderr}");
}

#[test]
fn under_resolving_time_step_warns_naming_the_mode_and_no_progress_off_a_terminal() {
    // 4 modes of a 20 m beam: mode 4 at ≈ 102 Hz needs Δt ≤ T/20 ≈ 0.49 ms; 2 ms under-resolves
    // modes 2 (26 Hz, 19 steps) to 4.
    let text = SMALL.replace("modes = 4", "modes = 4\ntime_step_s = 0.002");
    let (_dir, path) = scenario_file("coarse.toml", &text);
    let (code, _, stderr) = run(&["run", &path]);
    assert_eq!(code, 0, "stderr: {stderr}");
    assert!(
        stderr.contains("warning: time step 0.002 s under-resolves mode"),
        "{stderr}"
    );
    assert!(stderr.contains("scenario.time_step_s"), "{stderr}");
    // stderr is a pipe here: no progress line.
    assert!(!stderr.contains("computing"), "{stderr}");
}

/// `rerun_modes` solves the crossing again with only K modes; with K = N the re-run must give
/// the full run's DAFs (the same solve), and with fewer modes its own, reported in the JSON.
#[test]
fn rerun_modes_reports_truncated_runs_and_the_full_count_reproduces_the_run() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("rerun.toml");
    std::fs::write(
        &path,
        "[scenario]\nvehicle = \"sprung-mass\"\nroad = \"smooth\"\nspeed_kmh = 72\nmodes = 4\n\
         mode_kinds = [\"vertical_bending\"]\nrerun_modes = [1, 4]\n\
         [bridge]\ntype = \"continuous_beam\"\nspan_lengths_m = [20.0]\n\
         [bridge.section]\nflexural_rigidity_n_m2 = 3.5e10\nmass_per_length_kg_per_m = 18000.0\n",
    )
    .unwrap();
    let out = crate::common::vbi()
        .args(["run", "--format", "json"])
        .arg(&path)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let runs = json["truncated_runs"].as_array().expect("truncated_runs");
    assert_eq!(runs.len(), 2);
    assert_eq!(runs[0]["mode_count"], 1);
    // K = N: the same basis, time step and loads, so the same DAF to round-off.
    let full = json["rdm"].as_f64().unwrap();
    let rerun = runs[1]["rdm"].as_f64().unwrap();
    assert!((full - rerun).abs() < 1e-12, "{full} vs {rerun}");
}

/// One parser of bridge presets: a `paper-NxL` name that a study accepts, a scenario accepts
/// too (issue 11: `paper-5x25` passed in a study and failed in a scenario).
#[test]
fn a_bridge_preset_that_a_study_accepts_a_scenario_accepts() {
    let (_dir, path) = scenario_file("preset.toml", "[scenario]\nbridge = \"paper-5x25\"\n");
    let (code, _, stderr) = run(&["check", &path]);
    assert_eq!(code, 0, "stderr: {stderr}");
    let (_dir, path) = scenario_file("bad.toml", "[scenario]\nbridge = \"paper-0x25\"\n");
    let (code, _, stderr) = run(&["check", &path]);
    assert_eq!(code, 2);
    assert!(stderr.contains("paper-NxL"), "stderr: {stderr}");
}

/// `modes` counts the modes solved for; re-runs count among the modes kept (vertical bending
/// and torsion by default, 17 of the 20 lowest of the 2 × 20 m grillage). A re-run beyond the
/// kept modes is refused as soon as the modes are known, before the crossing, naming the key
/// and both counts (issue 11: it once failed only after the whole crossing).
#[test]
fn rerun_modes_beyond_the_kept_modes_fail_before_the_crossing_with_both_counts() {
    let text = "[scenario]\nbridge = \"paper-2x20\"\nvehicle = \"moving-force\"\n\
                element_length_m = 4.0\nmodes = 20\nrerun_modes = [20]\n";
    let (_dir, path) = scenario_file("rerun.toml", text);
    let (code, _, stderr) = run(&["run", &path]);
    assert_eq!(code, 2, "stderr: {stderr}");
    assert!(
        stderr.contains("cannot re-run with 20 modes"),
        "stderr: {stderr}"
    );
    assert!(stderr.contains("rerun_modes"), "stderr: {stderr}");
    assert!(!stderr.contains("vehicle crossing"), "stderr: {stderr}");
}

/// `vbi run` validates its file exactly as `vbi check` does: a misspelt table is refused, not
/// replaced by the default road, and a study file is refused with the command that runs it
/// (issue 17, defect 1).
#[test]
fn a_misspelt_table_or_a_study_file_is_refused_as_vbi_check_refuses_it() {
    let text = SMALL.replace("[road]", "[raod]");
    let (_dir, path) = scenario_file("misspelt.toml", &text);
    for command in ["check", "run"] {
        let (code, _, stderr) = run(&[command, &path]);
        assert_eq!(code, 2, "{command}: {stderr}");
        assert!(stderr.contains("misspelt.toml:"), "{command}: {stderr}");
        assert!(stderr.contains("raod"), "{command}: {stderr}");
    }
    let study = repository_root().join("examples/studies/quick.toml");
    let (code, _, stderr) = run(&["run", study.to_str().unwrap()]);
    assert_eq!(code, 2, "stderr: {stderr}");
    assert!(stderr.contains("vbi study FILE"), "stderr: {stderr}");
}

/// Issue 17, defect 7: a 0.01 m mesh of a 25 m beam with 340 modes was called a mechanism
/// ("ω² = 660.9", its first bending mode). The 20 m beam at 0.01 m has the most elements a span
/// may have (2000) and runs; the 25 m beam at 0.01 m (2500) is refused at `element_length_m`
/// with the limit, by `vbi check` as by `vbi run`.
#[test]
fn a_mesh_finer_than_the_limit_per_span_is_refused_at_the_element_length() {
    let fine = SMALL.replace("element_length_m = 1.0", "element_length_m = 0.01");
    let (dir, path) = scenario_file("fine.toml", &fine);
    let out = dir.path().join("out");
    let (code, _, stderr) = run(&["run", &path, "--out", out.to_str().unwrap()]);
    assert_eq!(code, 0, "{stderr}");
    let finer = fine.replace("span_lengths_m = [20.0]", "span_lengths_m = [25.0]");
    let (_dir, path) = scenario_file("finer.toml", &finer);
    for command in ["check", "run"] {
        let (code, _, stderr) = run(&[command, &path]);
        assert_eq!(code, 2, "{command}: {stderr}");
        assert!(
            stderr.contains("finer.toml:6:1: field `scenario.element_length_m`"),
            "{command}: {stderr}"
        );
        assert!(stderr.contains("2500 elements in a 25 m span"), "{stderr}");
        assert!(stderr.contains("more than the 2000 allowed"), "{stderr}");
    }
}

/// `vbi run | head`: a reader that closes the pipe before the table is printed is not an error.
/// The read end is closed before the run prints anything, so every write of the table meets a
/// closed pipe (EPIPE); the command must exit 0 without a panic.
#[test]
fn run_into_a_closed_pipe_exits_zero_without_a_panic() {
    let binary = assert_cmd::cargo::cargo_bin("vbi");
    let mut child = std::process::Command::new(binary)
        .arg("run")
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("vbi runs");
    drop(child.stdout.take());
    let out = child.wait_with_output().expect("vbi finishes");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "stderr: {stderr}");
    assert_eq!(out.status.code(), Some(0), "stderr: {stderr}");
}

/// `--history-every K` writes every K-th instant (and the last) of histories.csv and
/// vehicles.csv, the rows of the full file at those instants, while summary.json is unchanged;
/// K = 0 is refused with exit code 2.
#[test]
fn history_every_k_thins_the_history_files_and_nothing_else() {
    let (dir, path) = scenario_file("small.toml", SMALL);
    let (full, thin) = (dir.path().join("full"), dir.path().join("thin"));
    for (out, every) in [(&full, "1"), (&thin, "7")] {
        let out = out.to_str().unwrap();
        let (code, _, stderr) = run(&["run", &path, "--out", out, "--history-every", every]);
        assert_eq!(code, 0, "{stderr}");
    }
    for file in ["histories.csv", "vehicles.csv"] {
        let all: Vec<String> = std::fs::read_to_string(full.join(file))
            .unwrap()
            .lines()
            .map(str::to_string)
            .collect();
        let kept: Vec<String> = std::fs::read_to_string(thin.join(file))
            .unwrap()
            .lines()
            .map(str::to_string)
            .collect();
        let steps = all.len() - 1;
        let expected: Vec<&String> = std::iter::once(&all[0])
            .chain(
                (0..steps)
                    .filter(|i| i % 7 == 0 || i + 1 == steps)
                    .map(|i| &all[1 + i]),
            )
            .collect();
        assert_eq!(kept.iter().collect::<Vec<_>>(), expected, "{file}");
    }
    assert_eq!(
        std::fs::read(full.join("summary.json")).unwrap(),
        std::fs::read(thin.join("summary.json")).unwrap()
    );
    let (code, _, stderr) = run(&["run", &path, "--history-every", "0"]);
    assert_eq!(code, 2, "{stderr}");
}

/// design_codes.csv holds every code beside every entry's computed DAF, worked by hand from
/// the clauses for the 20 m simple span and its one-axle vehicle (docs/verification.md §25):
/// JTG D60 μ(π/(2l²)√(EI/m)), JTJ 021-89 0.3 · 25/40, AASHTO Standard 15.24/(20 + 38.1), CSA S6
/// 0.40 for one axle; the table, summary.json and the figure agree.
#[test]
fn design_codes_beside_the_computed_daf_follow_the_clauses() {
    let (dir, path) = scenario_file("small.toml", SMALL);
    let out = dir.path().join("out");
    let (code, stdout, stderr) = run(&["run", &path, "--out", out.to_str().unwrap()]);
    assert_eq!(code, 0, "stderr: {stderr}");
    assert!(stdout.contains("Design codes at span1_mid"), "{stdout}");
    assert!(out.join("design_codes.svg").is_file());
    let table = std::fs::read_to_string(out.join("design_codes.csv")).unwrap();
    let mut reader = csv::Reader::from_reader(table.as_bytes());
    let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    assert_eq!(
        header,
        [
            "station",
            "quantity",
            "code",
            "provision",
            "clause",
            "basis",
            "impact_factor",
            "code_daf",
            "computed_daf",
            "computed_over_code"
        ]
    );
    let rows: Vec<csv::StringRecord> = reader.records().map(Result::unwrap).collect();
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let station = summary["rdm_station"].as_str().unwrap();
    let value = |code: &str, provision: &str| -> f64 {
        rows.iter()
            .find(|r| {
                &r[0] == station && &r[1] == "bending_moment" && &r[2] == code && &r[3] == provision
            })
            .unwrap_or_else(|| panic!("no {code} {provision} at {station}: {table}"))[6]
            .parse()
            .unwrap()
    };
    let f = std::f64::consts::PI / (2.0 * 400.0) * (4.86535e10_f64 / 18358.0).sqrt();
    let jtg = value("JTG D60-2015", "code_frequency");
    assert!(
        (jtg - (0.1767 * f.ln() - 0.0157)).abs() < 1e-12,
        "{jtg} at f = {f}"
    );
    assert!((value("JTJ 021-89", "span") - 0.1875).abs() < 1e-12);
    let standard = value("AASHTO Standard 2002", "loaded_length");
    assert!((standard - 15.24 / 58.1).abs() < 1e-12, "{standard}");
    // CSA S6 reads the CL-W truck's axles within the 20 m span (five: 0.25), not the moving
    // force's one axle (issue 46).
    assert_eq!(value("CSA S6", "cl_w_axles"), 0.25);
    // Every row's computed DAF is the summary's converged DAF of its entry.
    for r in &rows {
        let entry = summary["stations"]
            .as_array()
            .unwrap()
            .iter()
            .find(|e| e["name"] == r[0] && e["quantity"] == r[1])
            .unwrap();
        assert_eq!(r[8].parse::<f64>().ok(), entry["daf"].as_f64());
    }
    let codes = summary["design_codes"].as_array().unwrap();
    assert!(codes
        .iter()
        .all(|c| c["factors"].as_array().unwrap().len() >= 8));
}

#[test]
fn the_help_shows_example_lines_the_manual_and_what_a_run_reports() {
    // Issue 19: `vbi --help` points a newcomer at example lines and the manual; `vbi run --help`
    // and `vbi study --help` say which stations and quantities they report.
    let (code, stdout, _) = run(&["--help"]);
    assert_eq!(code, 0);
    assert!(stdout.contains("Examples:"), "{stdout}");
    assert!(stdout.contains("docs/input-format.md"), "{stdout}");
    for command in ["run", "study"] {
        let (code, stdout, _) = run(&[command, "--help"]);
        assert_eq!(code, 0);
        assert!(
            stdout.contains("Stations: the mid-span"),
            "{command}: {stdout}"
        );
        assert!(stdout.contains("support reaction"), "{command}: {stdout}");
    }
    // Every example line and every page of the manual that the help names exists.
    let (_, stdout, _) = run(&["--help"]);
    for word in stdout
        .split_whitespace()
        .map(|w| w.trim_end_matches([';', ',', ')', '.']))
        .filter(|w| w.starts_with("examples/") || (w.starts_with("docs/") && w.ends_with(".md")))
    {
        assert!(repository_root().join(word).is_file(), "{word}");
    }
}
