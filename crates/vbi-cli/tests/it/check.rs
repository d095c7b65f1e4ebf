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
