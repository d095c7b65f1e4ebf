//! `vbi check`: exit codes and messages for good and bad files.

use crate::common::vbi;

#[test]
fn check_of_an_unknown_kind_of_file_exits_2_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("mystery.toml");
    std::fs::write(&path, "[mystery]\nx = 1\n").unwrap();
    let out = vbi().arg("check").arg(&path).assert().code(2);
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(stderr.contains("mystery.toml:1:1"), "{stderr}");
    assert!(stderr.contains("[bridge]"), "{stderr}");
}

#[test]
fn check_of_a_toml_syntax_error_names_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("broken.toml");
    std::fs::write(&path, "[bridge]\nspans = [30.0,\n").unwrap();
    let out = vbi().arg("check").arg(&path).assert().code(2);
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(stderr.contains("broken.toml:"), "{stderr}");
}

#[test]
fn check_of_a_missing_file_exits_2() {
    vbi().args(["check", "no/such/file.toml"]).assert().code(2);
}

/// Issue 17, defect 4: `/dev/zero` and a FIFO as input were read until memory ran out. Every
/// command refuses a path that is not a regular file before reading it, naming the path.
#[test]
fn a_device_or_a_fifo_as_input_is_refused_before_it_is_read() {
    for command in [&["check"][..], &["run"], &["modes"], &["study"]] {
        let out = vbi()
            .args(command)
            .arg("/dev/zero")
            .timeout(std::time::Duration::from_secs(60))
            .assert()
            .code(2);
        let stderr = String::from_utf8_lossy(&out.get_output().stderr).to_string();
        assert!(
            stderr.contains("/dev/zero: cannot read the file: it is not a regular file"),
            "{command:?}: {stderr}"
        );
    }
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("input.toml");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if made.is_ok_and(|s| s.success()) {
        let out = vbi()
            .arg("check")
            .arg(&fifo)
            .timeout(std::time::Duration::from_secs(60))
            .assert()
            .code(2);
        let stderr = String::from_utf8_lossy(&out.get_output().stderr).to_string();
        assert!(stderr.contains("not a regular file"), "{stderr}");
    }
}

/// Issue 17, defects 3 and 7: `vbi check` refuses what the run would refuse before any numeric
/// work. The paper's 4 × 40 m grillage at 0.02 m (143 970 DOFs) with 1000 modes needs about
/// 5.5 GiB, over the 4 GiB limit of a modal analysis: `vbi check` and `vbi run` both refuse
/// it at `modes` with the estimate, in well under a second (the symbolic analysis only).
#[test]
fn check_refuses_a_modal_analysis_over_the_memory_limit_at_the_modes() {
    let example =
        crate::common::repository_root().join("examples/scenarios/paper-3x30-medium-80kmh.toml");
    let text = std::fs::read_to_string(example)
        .unwrap()
        .replace("bridge = \"paper-3x30\"", "bridge = \"paper-4x40\"")
        .replace("element_length_m = 1.0", "element_length_m = 0.02")
        .replace("modes = 50", "modes = 1000");
    assert!(text.contains("paper-4x40") && text.contains("modes = 1000"));
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("large.toml");
    std::fs::write(&path, text).unwrap();
    for command in ["check", "run"] {
        let out = vbi()
            .arg(command)
            .arg(&path)
            .timeout(std::time::Duration::from_secs(60))
            .assert()
            .code(2);
        let stderr = String::from_utf8_lossy(&out.get_output().stderr).to_string();
        assert!(
            stderr.contains("large.toml:13:1: field `scenario.modes`"),
            "{command}: {stderr}"
        );
        assert!(
            stderr.contains("143970 degrees of freedom for 1000 modes")
                && stderr.contains("over the limit of 4.0 GiB"),
            "{command}: {stderr}"
        );
    }
}

/// A copy of `examples/` in a temporary directory, for mutating an example in place.
fn examples_copy() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let copied = std::process::Command::new("cp")
        .arg("-r")
        .arg(crate::common::repository_root().join("examples"))
        .arg(dir.path())
        .status()
        .expect("cp runs");
    assert!(copied.success());
    dir
}

/// Replaces `from` by `to` in `file` of the copy (the text must hold `from`).
fn edit(dir: &tempfile::TempDir, file: &str, from: &str, to: &str) -> std::path::PathBuf {
    let path = dir.path().join("examples").join(file);
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains(from), "{file} holds `{from}`");
    std::fs::write(&path, text.replacen(from, to, 1)).unwrap();
    path
}

fn first_error(output: &std::process::Output) -> String {
    String::from_utf8_lossy(&output.stderr)
        .lines()
        .find(|l| l.starts_with("error: "))
        .unwrap_or_default()
        .to_string()
}

/// Runs `vbi check` (it must pass), `vbi check --deep` and `vbi <command> FILE --out DIR/out`
/// (both must refuse with exit 2), and returns the deep check's first error line after checking
/// that the command's is the same (issue 47's PassedThenRefused class).
fn deep_check_refuses_as(command: &str, file: &std::path::Path, dir: &std::path::Path) -> String {
    vbi().arg("check").arg(file).assert().code(0);
    let deep = vbi().args(["check", "--deep"]).arg(file).assert().code(2);
    let refused = vbi()
        .arg(command)
        .arg(file)
        .arg("--out")
        .arg(dir.join("out"))
        .assert()
        .code(2);
    let refusal = first_error(deep.get_output());
    assert_eq!(refusal, first_error(refused.get_output()));
    refusal
}

/// Issue 47: `vbi check` passed an entry time that leaves no quiet window before it (the
/// robustness corpus's `entry_time_s = -0.0` and `1e308`), and `vbi measure` refused it at
/// `baseline_window_s`. `vbi check` now runs the record's preparation and refuses it with the
/// same message; an entry after the record's end is refused at `entry_time_s` before that,
/// and the number is shown as `1e308`, not 309 digits.
#[test]
fn check_refuses_an_entry_time_without_a_baseline_window_as_measure_does() {
    for (entry, key) in [
        ("-0.0", "measurement.baseline_window_s"),
        ("1e308", "measurement.entry_time_s"),
    ] {
        let dir = examples_copy();
        let file = edit(
            &dir,
            "measurements/field_4x30/fast.toml",
            "entry_time_s = 4.0",
            &format!("entry_time_s = {entry}"),
        );
        let check = vbi().arg("check").arg(&file).assert().code(2);
        let measure = vbi()
            .arg("measure")
            .arg(&file)
            .arg("--out")
            .arg(dir.path().join("out"))
            .assert()
            .code(2);
        let refusal = first_error(check.get_output());
        assert!(refusal.contains(&format!("field `{key}`")), "{refusal}");
        assert_eq!(refusal, first_error(measure.get_output()));
        assert!(!refusal.contains("0000000000"), "{refusal}");
    }
}

/// Issue 47: a crawl reference with no first frequency (the record's spectrum finds none below
/// `max_frequency_hz = 2.5`) needs the spectra: `vbi check` passes it, `vbi check --deep` refuses
/// it with `vbi measure`'s message.
#[test]
fn check_deep_refuses_what_measure_refuses_after_the_spectra() {
    let dir = examples_copy();
    let file = edit(
        &dir,
        "measurements/field_4x30/fast.toml",
        "max_frequency_hz = 12.0",
        "max_frequency_hz = 2.5",
    );
    let refusal = deep_check_refuses_as("measure", &file, dir.path());
    assert!(refusal.contains("field `measurement.crawl`"), "{refusal}");
    assert!(!dir.path().join("out").join("measure.json").exists());
}

/// `vbi check --deep` of good files: the scenario's modes and crossing, the bridge's modes, the
/// measurement's processing all pass, and say that they were deep.
#[test]
fn check_deep_passes_the_examples_it_runs() {
    let root = crate::common::repository_root().join("examples");
    for file in [
        "scenarios/two-span-sprung-mass.toml",
        "bridges/two-span-beam.toml",
        "measurements/synthetic_two_span.toml",
        "roads/paper-medium.toml",
    ] {
        let out = vbi()
            .args(["check", "--deep"])
            .arg(root.join(file))
            .assert()
            .code(0);
        let stdout = String::from_utf8_lossy(&out.get_output().stdout).to_string();
        assert!(stdout.contains(", deep)"), "{file}: {stdout}");
    }
}

/// Issue 47: a 0.01 m mesh of the skewed 2 × 20 m grillage with 1000 modes ran for over ten
/// minutes. The modal analysis's work (n · dim² per Lanczos pass) is estimated before any
/// numeric work and refused over `vbi::modal::MODAL_WORK_LIMIT`, by `vbi check` as by `vbi run`,
/// at the scenario's `modes`.
#[test]
fn a_modal_analysis_over_the_work_limit_is_refused_by_check_at_modes() {
    let dir = examples_copy();
    let file = edit(
        &dir,
        "scenarios/skewed-bridge.toml",
        "modes = 30",
        "modes = 1000\nelement_length_m = 0.01",
    );
    let check = vbi().arg("check").arg(&file).assert().code(2);
    let refusal = first_error(check.get_output());
    assert!(refusal.contains("field `scenario.modes`"), "{refusal}");
    assert!(
        refusal.contains("multiply-adds per Lanczos pass"),
        "{refusal}"
    );
    let run = vbi()
        .arg("run")
        .arg(&file)
        .arg("--out")
        .arg(dir.path().join("out"))
        .assert()
        .code(2);
    assert_eq!(refusal, first_error(run.get_output()));
}

/// Issue 47's reproducer: `modes = 20, rerun_modes = [20]` on the paper's 2 × 20 m bridge
/// passes `vbi check` (how many of the 20 modes the basis keeps needs the modes) and `vbi run`
/// refuses it ("the basis keeps 17"). `vbi check --deep` refuses it with the same line.
#[test]
fn check_deep_refuses_a_rerun_mode_count_above_the_modes_kept_as_run_does() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("rerun.toml");
    std::fs::write(
        &file,
        "[scenario]\nbridge = \"paper-2x20\"\nvehicle = \"three-axle-truck-36t\"\n\
         road = \"good\"\nspeed_kmh = 80\nmodes = 20\nrerun_modes = [20]\n",
    )
    .unwrap();
    let refusal = deep_check_refuses_as("run", &file, dir.path());
    assert!(
        refusal.contains("field `scenario.rerun_modes`"),
        "{refusal}"
    );
    assert!(refusal.contains("keeps 17"), "{refusal}");
}
