//! End-to-end tests of `vbi study` and `vbi report`: small studies of a moving force on a
//! two-span continuous beam (docs/verification.md §3 geometry), a few modes, so that each
//! runs in well under a second.

use std::path::{Path, PathBuf};

use crate::common::vbi;

/// Checks on the text of an output stream.
trait Has {
    fn stderr_has(self, text: &str) -> Self;
    fn stdout_has(self, text: &str) -> Self;
}

impl Has for assert_cmd::assert::Assert {
    fn stderr_has(self, text: &str) -> Self {
        let s = String::from_utf8_lossy(&self.get_output().stderr).to_string();
        assert!(s.contains(text), "stderr {s:?} lacks {text:?}");
        self
    }
    fn stdout_has(self, text: &str) -> Self {
        let s = String::from_utf8_lossy(&self.get_output().stdout).to_string();
        assert!(s.contains(text), "stdout {s:?} lacks {text:?}");
        self
    }
}

/// A two-span beam (2 × 20 m, docs/verification.md §3, with the VBI-2D section of §9), 8 modes,
/// a moving force.
const BASE: &str = r#"
[scenario]
vehicle = "moving-force"
road = "medium"
modes = 8

[bridge]
type = "continuous_beam"
span_lengths_m = [20.0, 20.0]
supports = ["pinned", "pinned", "pinned"]
damping_ratio = 0.02

[bridge.section]
flexural_rigidity_n_m2 = 4.86535e10
mass_per_length_kg_per_m = 18358.0
"#;

/// Runs a study file into `out` (no figures) and checks that it succeeded.
fn run_study(file: &Path, out: &Path) {
    vbi()
        .args(["study", file.to_str().unwrap(), "--no-figures", "--out"])
        .arg(out)
        .assert()
        .success();
}

/// `vbi study FILE --no-figures --resume --out OUT`, for the caller's assertions.
fn resume_study(file: &Path, out: &Path) -> assert_cmd::assert::Assert {
    vbi()
        .args([
            "study",
            file.to_str().unwrap(),
            "--no-figures",
            "--resume",
            "--out",
        ])
        .arg(out)
        .assert()
}

fn study_file(dir: &Path, name: &str, study: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, format!("{study}\n{BASE}")).unwrap();
    path
}

const SMALL: &str = r#"
[study]
seed = 11
samples = 2

[study.axes]
speed_kmh = [60, 90, 120]
road = ["good", "poor"]
"#;

fn read(path: &Path) -> String {
    std::fs::read(path)
        .map(|bytes| String::from_utf8_lossy(&bytes).into_owned())
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The result files that must be identical whatever the way the study ran.
const RESULTS: [&str; 11] = [
    "design_codes.csv",
    "cases.csv",
    "cases.parquet",
    "daf_by_modes.parquet",
    "daf_by_modes.csv",
    "participation.csv",
    "summary.csv",
    "cutoff_modes.csv",
    "convergence.csv",
    "daf_vs_static.csv",
    "cases_long.csv",
];

fn assert_same_results(a: &Path, b: &Path) {
    for f in RESULTS {
        assert_eq!(read(&a.join(f)), read(&b.join(f)), "{f} differs");
    }
}

#[test]
fn a_small_study_writes_every_table_with_one_row_per_case() {
    let dir = tempfile::tempdir().unwrap();
    let file = study_file(dir.path(), "s.toml", SMALL);
    let out = dir.path().join("out");
    vbi()
        .args([
            "study",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ])
        .assert()
        .success();
    let cases = read(&out.join("cases.csv"));
    let lines: Vec<&str> = cases.lines().collect();
    // 3 speeds × 2 roads × 2 samples.
    assert_eq!(lines.len(), 1 + 12);
    assert!(lines[0].starts_with("case,speed_kmh,road,sample,seed,rdm_station,daf_u,daf_m,rdm,"));
    assert!(lines[1].contains(",60,good,0,"), "{}", lines[1]);
    assert!(lines[2].contains(",60,good,1,"), "{}", lines[2]);
    // Every DAF is a finite number above 0.5 (a moving force on a damped beam).
    let header: Vec<&str> = lines[0].split(',').collect();
    let col = header.iter().position(|h| *h == "daf_u").unwrap();
    for line in &lines[1..] {
        let daf: f64 = line.split(',').nth(col).unwrap().parse().unwrap();
        assert!(daf > 0.5 && daf < 3.0, "{line}");
    }
    // 8 modes per case.
    assert_eq!(
        read(&out.join("daf_by_modes.csv")).lines().count(),
        1 + 12 * 8
    );
    assert_eq!(
        read(&out.join("participation.csv")).lines().count(),
        1 + 12 * 8
    );
    // Every case also has the paper's DAFs (plain modal sums).
    let col = header.iter().position(|h| *h == "daf_m_paper").unwrap();
    for line in &lines[1..] {
        let daf: f64 = line.split(',').nth(col).unwrap().parse().unwrap();
        assert!(daf > 0.5 && daf < 3.0, "{line}");
    }
    // summary: 6 groups × 12 metrics (the converged DAF_u, DAF_M, RDM, the paper's, its CMs and K1/K2).
    let summary = read(&out.join("summary.csv"));
    assert!(summary.starts_with(
        "speed_kmh,road,metric,count,mean,std,min,max,p95,standard_error,p95_low,p95_high,\
         normal_p95\n"
    ));
    assert_eq!(summary.lines().count(), 1 + 6 * 12);
    // The characteristic value (p95) lies in its bootstrap interval, which lies in the range of
    // the group's values; the standard error is std/√n.
    for line in summary.lines().skip(1) {
        let cells: Vec<&str> = line.split(',').collect();
        let value = |i: usize| cells[i].parse::<f64>().unwrap();
        let (count, std, min, max, p95) = (value(3), value(5), value(6), value(7), value(8));
        let (error, low, high) = (value(9), value(10), value(11));
        assert!(
            min <= low && low <= p95 && p95 <= high && high <= max,
            "{line}"
        );
        assert!(
            (error - std / count.sqrt()).abs() <= 1e-15 * std.max(1e-300),
            "{line}"
        );
    }
    // cases.parquet: the same rows, typed; the seeds keep all 64 bits.
    {
        use parquet::file::reader::{FileReader, SerializedFileReader};
        use parquet::record::RowAccessor;
        let file = std::fs::File::open(out.join("cases.parquet")).unwrap();
        let reader = SerializedFileReader::new(file).unwrap();
        let rows: Vec<_> = reader
            .get_row_iter(None)
            .unwrap()
            .map(|r| r.unwrap())
            .collect();
        assert_eq!(rows.len(), 12);
        let seed = header.iter().position(|h| *h == "seed").unwrap();
        for (row, line) in rows.iter().zip(&lines[1..]) {
            let cells: Vec<&str> = line.split(',').collect();
            assert_eq!(row.get_string(0).unwrap(), cells[0]);
            assert_eq!(row.get_ulong(seed).unwrap().to_string(), cells[seed]);
            let daf: f64 = cells[col].parse().unwrap();
            assert_eq!(row.get_double(col).unwrap().to_bits(), daf.to_bits());
        }
    }
    // Monte Carlo convergence: one row per group, headline metric and number of samples.
    let convergence = read(&out.join("convergence.csv"));
    assert!(convergence.starts_with("speed_kmh,road,metric,samples,mean,standard_error\n"));
    assert_eq!(convergence.lines().count(), 1 + 6 * 3 * 2);
    // The long table: one row per case and defined numeric metric.
    let long = read(&out.join("cases_long.csv"));
    assert!(
        long.starts_with("case,speed_kmh,road,sample,seed,metric,value\n"),
        "{long}"
    );
    let daf_m = header.iter().position(|h| *h == "daf_m").unwrap();
    let first: Vec<&str> = lines[1].split(',').collect();
    let row = format!(",daf_m,{}", first[daf_m]);
    assert!(
        long.lines()
            .any(|l| l.starts_with(first[0]) && l.ends_with(&row)),
        "{row} of case {} in {long}",
        first[0]
    );
    assert!(read(&out.join("daf_vs_static.csv")).starts_with("bridge,metric,static_unit,count,"));
    assert!(summary.contains("60,good,daf_u,2,"));
    assert!(summary.contains("60,good,daf_m_paper,2,"));
    // A beam has only vertical bending modes: the cut-off modes counted among them are the
    // plain ones.
    let cutoff = read(&out.join("cutoff_modes.csv"));
    let rows: Vec<Vec<&str>> = cutoff.lines().map(|l| l.split(',').collect()).collect();
    let column = |name: &str| rows[0].iter().position(|h| *h == name).unwrap();
    for name in ["k1_u", "k2_u", "k1_m", "k2_m"] {
        let (plain, bending) = (column(name), column(&format!("{name}_bending")));
        for row in &rows[1..] {
            assert!(!row[plain].is_empty(), "{cutoff}");
            assert_eq!(row[plain], row[bending], "{name}: {cutoff}");
        }
    }
    assert!(read(&out.join("participation.csv")).contains(",vertical_bending\n"));
    for fig in [
        "daf_u_paper_by_modes_per_speed_kmh",
        "rdm_paper_by_modes_per_road",
        "daf_m_by_modes_per_road",
        "participation_moment",
        "assessment_daf_m",
        "daf_vs_static",
    ] {
        assert!(
            out.join("figures").join(format!("{fig}.png")).exists(),
            "{fig}"
        );
        assert!(
            out.join("figures").join(format!("{fig}.svg")).exists(),
            "{fig}"
        );
    }

    // The report is one self-contained HTML file.
    vbi()
        .args(["report", out.to_str().unwrap()])
        .assert()
        .success();
    let html = read(&out.join("report.html"));
    assert!(html.contains("<svg") && html.contains("Table 2") && html.contains("K1"));
    assert!(!html.contains("src=\"figures/"), "no external figure files");
}

#[test]
fn results_are_bit_identical_for_one_and_two_threads() {
    let dir = tempfile::tempdir().unwrap();
    let file = study_file(dir.path(), "s.toml", SMALL);
    let one = dir.path().join("one");
    let two = dir.path().join("two");
    for (out, threads) in [(&one, "1"), (&two, "2")] {
        vbi()
            .args([
                "study",
                file.to_str().unwrap(),
                "--no-figures",
                "--threads",
                threads,
            ])
            .args(["--out", out.to_str().unwrap()])
            .assert()
            .success();
    }
    assert_same_results(&one, &two);
}

#[test]
fn three_shards_in_separate_processes_merge_to_the_single_process_result() {
    let dir = tempfile::tempdir().unwrap();
    let file = study_file(dir.path(), "s.toml", SMALL);
    let single = dir.path().join("single");
    run_study(&file, &single);
    // Three processes at once, each its own shard directory.
    let children: Vec<_> = (1..=3)
        .map(|i| {
            std::process::Command::new(assert_cmd::cargo::cargo_bin("vbi"))
                .args([
                    "study",
                    file.to_str().unwrap(),
                    "--shard",
                    &format!("{i}/3"),
                ])
                .arg("--out")
                .arg(dir.path().join(format!("shard-{i}")))
                .stdout(std::process::Stdio::null())
                .spawn()
                .unwrap()
        })
        .collect();
    for mut child in children {
        assert!(child.wait().unwrap().success());
    }
    // Each shard ran 4 of the 12 cases.
    for i in 1..=3 {
        let rows = read(&dir.path().join(format!("shard-{i}/cases.csv")))
            .lines()
            .count();
        assert_eq!(rows, 1 + 4);
    }
    let merged = dir.path().join("merged");
    vbi()
        .args(["study", "merge", "--no-figures", "--out"])
        .arg(&merged)
        .args((1..=3).map(|i| dir.path().join(format!("shard-{i}"))))
        .assert()
        .success();
    assert_same_results(&single, &merged);
    assert_eq!(
        read(&single.join("journal.jsonl")).lines().count(),
        read(&merged.join("journal.jsonl")).lines().count()
    );
    // A merge with a shard missing is refused.
    vbi()
        .args(["study", "merge", "--out"])
        .arg(dir.path().join("partial"))
        .arg(dir.path().join("shard-1"))
        .arg(dir.path().join("shard-3"))
        .assert()
        .failure()
        .stderr_has("4 of 12 cases are missing");
}

#[test]
fn resume_after_a_crash_runs_only_the_missing_cases_and_equals_an_uninterrupted_run() {
    let dir = tempfile::tempdir().unwrap();
    let file = study_file(dir.path(), "s.toml", SMALL);
    let full = dir.path().join("full");
    vbi()
        .args(["study", file.to_str().unwrap(), "--no-figures", "--out"])
        .arg(&full)
        .assert()
        .success();
    // Simulate a kill: five complete lines and half of the sixth; no final tables.
    let crashed = dir.path().join("crashed");
    std::fs::create_dir(&crashed).unwrap();
    std::fs::copy(full.join("study.json"), crashed.join("study.json")).unwrap();
    let journal = read(&full.join("journal.jsonl"));
    let lines: Vec<&str> = journal.lines().collect();
    let mut cut = lines[..5].join("\n");
    cut.push('\n');
    cut.push_str(&lines[5][..lines[5].len() / 2]);
    std::fs::write(crashed.join("journal.jsonl"), cut).unwrap();
    // Without --resume the directory is refused.
    vbi()
        .args(["study", file.to_str().unwrap(), "--out"])
        .arg(&crashed)
        .assert()
        .code(2)
        .stderr_has("--resume");
    resume_study(&file, &crashed)
        .success()
        .stdout_has("7 cases run, 5 already done");
    assert_same_results(&full, &crashed);
    assert_eq!(read(&crashed.join("journal.jsonl")).lines().count(), 12);
    // Resuming a finished study runs nothing and changes nothing.
    resume_study(&file, &crashed)
        .success()
        .stdout_has("0 cases run, 12 already done");
    assert_same_results(&full, &crashed);
}

/// Issue 17, defect 8: a number edited by hand in journal.jsonl flowed into the tables. Now the
/// edited line fails its checksum: `vbi report` refuses the directory naming the line, and
/// `--resume` drops the line with a warning and runs its case again, giving the tables of an
/// untouched run.
#[test]
fn an_edited_journal_line_fails_its_checksum_and_its_case_runs_again() {
    let dir = tempfile::tempdir().unwrap();
    let file = study_file(dir.path(), "s.toml", SMALL);
    let full = dir.path().join("full");
    run_study(&file, &full);
    let edited = dir.path().join("edited");
    std::fs::create_dir(&edited).unwrap();
    std::fs::copy(full.join("study.json"), edited.join("study.json")).unwrap();
    let journal = read(&full.join("journal.jsonl"));
    let mut lines: Vec<String> = journal.lines().map(str::to_string).collect();
    let start = lines[3].find("\"daf_u\":\"").unwrap() + "\"daf_u\":\"".len();
    let digit = lines[3][start..]
        .find(|c: char| c.is_ascii_digit())
        .unwrap()
        + start;
    let changed = if &lines[3][digit..=digit] == "9" {
        "8"
    } else {
        "9"
    };
    lines[3].replace_range(digit..=digit, changed);
    std::fs::write(edited.join("journal.jsonl"), lines.join("\n") + "\n").unwrap();
    vbi()
        .args(["report"])
        .arg(&edited)
        .assert()
        .code(2)
        .stderr_has("journal.jsonl:4: this journal line fails its checksum");
    resume_study(&file, &edited)
        .success()
        .stderr_has("journal.jsonl:4: this journal line fails its checksum")
        .stdout_has("1 cases run, 11 already done");
    assert_same_results(&full, &edited);
}

#[test]
fn resuming_a_changed_study_is_refused_with_what_changed() {
    let dir = tempfile::tempdir().unwrap();
    let file = study_file(dir.path(), "s.toml", SMALL);
    let out = dir.path().join("out");
    run_study(&file, &out);
    study_file(
        dir.path(),
        "s.toml",
        &SMALL.replace("[60, 90, 120]", "[60, 90]"),
    );
    vbi()
        .args(["study", file.to_str().unwrap(), "--resume", "--out"])
        .arg(&out)
        .assert()
        .code(2)
        .stderr_has("study.axes.speed_kmh: [60, 90, 120] → [60, 90]");
    // A different shard of the same study is refused too.
    vbi()
        .args([
            "study",
            file.to_str().unwrap(),
            "--resume",
            "--shard",
            "1/2",
            "--out",
        ])
        .arg(&out)
        .assert()
        .code(2);
}

/// Every field of the base scenario takes part in the change detection of `--resume`, the
/// physics switches among them: the manifest holds the library's serialised scenario (issue 11:
/// `tyre_separation` and `rerun_modes` were once missed and results of two physics mixed).
#[test]
fn resuming_with_a_changed_tyre_model_or_rerun_modes_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let file = study_file(dir.path(), "s.toml", SMALL);
    let out = dir.path().join("out");
    run_study(&file, &out);
    for (change, named) in [
        (
            "modes = 8\ntyre_separation = false",
            "scenario.solver.tyre_separation: true → false",
        ),
        ("modes = 8\nrerun_modes = [2]", "scenario.rerun_mode_counts"),
    ] {
        let path = dir.path().join("s.toml");
        std::fs::write(
            &path,
            format!("{SMALL}\n{}", BASE.replace("modes = 8", change)),
        )
        .unwrap();
        resume_study(&path, &out).code(2).stderr_has(named);
    }
}

/// A case's solver warnings are never dropped: a time step too coarse for the modes is named
/// in the `warnings` column of cases.csv, and the run says on stderr how many cases have any.
#[test]
fn solver_warnings_reach_the_cases_table_and_stderr() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("s.toml");
    let text = format!("{SMALL}\n{BASE}").replace("modes = 8", "modes = 8\ntime_step_s = 0.02");
    std::fs::write(&path, text).unwrap();
    let out = dir.path().join("out");
    vbi()
        .args(["study", path.to_str().unwrap(), "--no-figures", "--out"])
        .arg(&out)
        .assert()
        .success()
        .stderr_has("12 case(s) have solver warnings");
    let cases = read(&out.join("cases.csv"));
    let header: Vec<&str> = cases.lines().next().unwrap().split(',').collect();
    assert!(header.contains(&"warnings"), "{header:?}");
    assert!(cases.contains("under-resolves mode"), "{cases}");
}

/// Results written by a vbi with other columns (an older results format) are never mixed with
/// new ones: resuming or merging them is refused.
#[test]
fn results_of_another_format_are_refused_for_resume_and_merge() {
    let dir = tempfile::tempdir().unwrap();
    let file = study_file(dir.path(), "s.toml", SMALL);
    let out = dir.path().join("out");
    run_study(&file, &out);
    let manifest = out.join("study.json");
    let text = read(&manifest);
    assert!(text.contains("\"format\": 6"), "{text}");
    std::fs::write(&manifest, text.replace("\"format\": 6", "\"format\": 5")).unwrap();
    vbi()
        .args(["study", file.to_str().unwrap(), "--resume", "--out"])
        .arg(&out)
        .assert()
        .code(2)
        .stderr_has("results of format 5");
    vbi()
        .args(["study", "merge", "--out"])
        .arg(dir.path().join("merged"))
        .arg(&out)
        .assert()
        .code(2)
        .stderr_has("results of format 5");
}

#[test]
fn adding_an_axis_value_leaves_the_other_cases_unchanged() {
    let dir = tempfile::tempdir().unwrap();
    let a = study_file(
        dir.path(),
        "a.toml",
        "[study]\nseed = 3\nsamples = 2\n[study.axes]\nspeed_kmh = [70]\n",
    );
    let b = study_file(
        dir.path(),
        "b.toml",
        "[study]\nseed = 3\nsamples = 3\n[study.axes]\nspeed_kmh = [50, 70]\n",
    );
    for (file, out) in [(&a, "out-a"), (&b, "out-b")] {
        vbi()
            .args(["study", file.to_str().unwrap(), "--no-figures", "--out"])
            .arg(dir.path().join(out))
            .assert()
            .success();
    }
    let small = read(&dir.path().join("out-a/cases.csv"));
    let large = read(&dir.path().join("out-b/cases.csv"));
    for row in small.lines().skip(1) {
        assert!(
            large.lines().any(|r| r == row),
            "{row} is not in the larger study"
        );
    }
}

#[test]
fn bad_studies_and_shards_are_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    for (name, study, message) in [
        (
            "unknown.toml",
            "[study]\n[study.axes]\nwind_speed = [1, 2]\n",
            "unknown field `wind_speed`",
        ),
        (
            "empty.toml",
            "[study]\n[study.axes]\nspeed_kmh = []\n",
            "empty axis",
        ),
        (
            "range.toml",
            "[study]\n[study.axes]\nspeed_kmh = [80, -5]\n",
            "study.axes.speed_kmh[1]",
        ),
        (
            "vehicle.toml",
            "[study]\n[study.axes]\nvehicle = [\"bicycle\"]\n",
            "study.axes.vehicle[0]",
        ),
    ] {
        let file = study_file(dir.path(), name, study);
        let out = dir.path().join(format!("out-{name}"));
        vbi()
            .args(["study", file.to_str().unwrap(), "--out"])
            .arg(&out)
            .assert()
            .code(2)
            .stderr_has(message);
        assert!(!out.exists(), "{name}: no output before validation");
        // `vbi check` agrees.
        vbi()
            .args(["check", file.to_str().unwrap()])
            .assert()
            .code(2);
    }
    let file = study_file(dir.path(), "ok.toml", SMALL);
    for shard in ["0/3", "4/3", "1/0", "x"] {
        let out = dir.path().join("out-shard");
        vbi()
            .args(["study", file.to_str().unwrap(), "--shard", shard, "--out"])
            .arg(&out)
            .assert()
            .code(2)
            .stderr_has("--shard");
        assert!(!out.exists());
    }
    vbi()
        .args(["check", file.to_str().unwrap()])
        .assert()
        .success();
}

#[test]
fn the_example_studies_are_valid() {
    let root = crate::common::repository_root();
    for name in ["paper.toml", "quick.toml", "lanes-and-damage.toml"] {
        vbi()
            .arg("check")
            .arg(root.join("examples/studies").join(name))
            .assert()
            .success();
    }
    // The paper's study has 9 × 4 × 3 × 10 cases.
    vbi()
        .args(["study", "--list"])
        .arg(root.join("examples/studies/paper.toml"))
        .assert()
        .success()
        .stdout_has("paper: 1080 cases");
}

/// The README's main command: `vbi study` with no file runs the built-in quick study (the
/// repository's examples/studies/quick.toml) and ends with its HTML report.
#[test]
fn study_without_a_file_runs_the_built_in_quick_study_and_writes_its_report() {
    let dir = tempfile::tempdir().unwrap();
    crate::common::vbi()
        .current_dir(dir.path())
        .args(["study", "--threads", "2"])
        .assert()
        .success();
    let out = dir.path().join("quick-results");
    let cases = std::fs::read_to_string(out.join("cases.csv")).unwrap();
    // Two bridges × one road × one speed × three samples.
    assert_eq!(cases.lines().count(), 1 + 6, "{cases}");
    let report = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(
        report.contains("Table 2"),
        "the report holds the cut-off mode table"
    );
}

/// The rows of a CSV file after its header, as cells.
fn csv_rows(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = read(path);
    let mut lines = text
        .lines()
        .map(|l| l.split(',').map(str::to_string).collect());
    (lines.next().expect("a header"), lines.collect())
}

const RECORDING: &str = r#"
[study]
seed = 5
samples = 2
record = [
  { station = "span2_mid_section", quantities = ["deflection", "bending_moment"] },
  "support2_section",
]
[study.axes]
speed_kmh = [60, 100]
"#;

/// A study with `record` writes one row of station_records.csv per case, station and quantity
/// (a bare name: every quantity the station has), and each row is what `vbi run` gives at that station when
/// the case is replayed from its row of cases.csv (its seed and speed), bit for bit; sharded and
/// merged, the table is the same bytes (the journal lines carry the records).
#[test]
fn recorded_stations_give_their_rows_and_match_vbi_run_of_the_replayed_case() {
    let dir = tempfile::tempdir().unwrap();
    let file = study_file(dir.path(), "record.toml", RECORDING);
    let out = dir.path().join("out");
    run_study(&file, &out);
    let (header, rows) = csv_rows(&out.join("station_records.csv"));
    assert_eq!(
        header,
        [
            "case",
            "station",
            "quantity",
            "unit",
            "static_max",
            "dynamic_max",
            "daf",
            "daf_change",
            "daf_change_dt",
            "cm",
            "dynamic_max_paper",
            "daf_paper",
            "cm_paper"
        ]
    );
    // A bare name records every quantity the station has: at a support, the support reaction
    // beside deflection and moment (no shear force).
    use vbi::modal::Quantity;
    let quantities = [
        Quantity::Deflection,
        Quantity::BendingMoment,
        Quantity::SupportReaction,
    ];
    let (_, cases) = csv_rows(&out.join("cases.csv"));
    assert_eq!(cases.len(), 4);
    assert_eq!(rows.len(), cases.len() * (2 + quantities.len()));
    let expected: Vec<(String, String)> = [
        ("span2_mid_section", "deflection"),
        ("span2_mid_section", "bending_moment"),
    ]
    .into_iter()
    .map(|(s, q)| (s.to_string(), q.to_string()))
    .chain(
        quantities
            .iter()
            .map(|q| ("support2_section".to_string(), q.name().to_string())),
    )
    .collect();
    for (c, case) in cases.iter().enumerate() {
        let block = &rows[c * expected.len()..(c + 1) * expected.len()];
        let got: Vec<(String, String)> =
            block.iter().map(|r| (r[1].clone(), r[2].clone())).collect();
        assert_eq!(got, expected);
        assert!(block.iter().all(|r| r[0] == case[0]));
        assert_eq!(block[0][3], "m");
        assert_eq!(block[1][3], "N·m");
    }
    // Replay the last case (speed 100, sample 1) with `vbi run`.
    let case = &cases[3];
    let (speed, seed) = (&case[1], &case[3]);
    assert_eq!(speed, "100");
    let scenario = dir.path().join("replay.toml");
    let base = BASE.replace("[scenario]\n", "");
    std::fs::write(
        &scenario,
        format!("[scenario]\nseed = \"{seed}\"\nspeed_kmh = {speed}\n{base}"),
    )
    .unwrap();
    let output = vbi()
        .args(["run", scenario.to_str().unwrap(), "--format", "json"])
        .output()
        .unwrap();
    assert!(output.status.success(), "{output:?}");
    let run: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    let entries = run["stations"].as_array().unwrap();
    for row in &rows[3 * expected.len()..] {
        let entry = entries
            .iter()
            .find(|e| e["name"] == row[1].as_str() && e["quantity"] == row[2].as_str());
        let Some(entry) = entry else {
            // A quantity that `vbi run` does not analyse is empty in the study too.
            assert!(row[6].is_empty(), "{row:?}");
            continue;
        };
        for (cell, key) in [
            (&row[4], "static_max"),
            (&row[5], "dynamic_max"),
            (&row[6], "daf"),
            (&row[7], "daf_change"),
            (&row[8], "daf_change_dt"),
            (&row[10], "dynamic_max_paper"),
            (&row[11], "daf_paper"),
        ] {
            // An empty cell (an undefined DAF: no static deflection over a support) is null.
            let study = (!cell.is_empty()).then(|| cell.parse::<f64>().unwrap().to_bits());
            let run = entry[key].as_f64().map(f64::to_bits);
            assert_eq!(study, run, "{row:?} {key}");
        }
        let cm = entry["convergence_mode"].as_u64().map(|k| k.to_string());
        assert_eq!(row[9], cm.unwrap_or_default(), "{row:?}");
        let cm_paper = entry["convergence_mode_paper"]
            .as_u64()
            .map(|k| k.to_string());
        assert_eq!(row[12], cm_paper.unwrap_or_default(), "{row:?}");
    }
    // The RDM station's columns of cases.csv are unchanged by the record.
    let plain = study_file(
        dir.path(),
        "plain.toml",
        &RECORDING.replace("record = [", "not_recorded = [").replace(
            "not_recorded = [\n  { station = \"span2_mid_section\", quantities = [\"deflection\", \"bending_moment\"] },\n  \"support2_section\",\n]\n",
            "",
        ),
    );
    let plain_out = dir.path().join("plain");
    run_study(&plain, &plain_out);
    assert_eq!(
        read(&plain_out.join("cases.csv")),
        read(&out.join("cases.csv"))
    );
    assert!(!plain_out.join("station_records.csv").exists());
    // Two shards merged: the same table.
    let mut shards = Vec::new();
    for shard in ["1/2", "2/2"] {
        let shard_out = dir.path().join(format!("shard{}", &shard[..1]));
        vbi()
            .args([
                "study",
                file.to_str().unwrap(),
                "--no-figures",
                "--shard",
                shard,
                "--out",
            ])
            .arg(&shard_out)
            .assert()
            .success();
        shards.push(shard_out);
    }
    let merged = dir.path().join("merged");
    vbi()
        .args(["study", "merge", "--no-figures", "--out"])
        .arg(&merged)
        .args(&shards)
        .assert()
        .success();
    assert_eq!(
        read(&merged.join("station_records.csv")),
        read(&out.join("station_records.csv"))
    );
}

/// An unknown station or quantity in `record`, and bad values of the new axes, are refused
/// before any work with the file, line and column, the field and what is allowed (exit 2),
/// identically by `vbi check` and `vbi study`.
#[test]
fn unknown_recorded_stations_and_quantities_and_bad_new_axes_are_refused_located() {
    let dir = tempfile::tempdir().unwrap();
    let damaged =
        "\n[[bridge.stiffness_loss]]\nstart_m = 8.0\nend_m = 12.0\nmodulus_factor = 0.5\n\
                   [[bridge.support_change]]\nsupport = 2\nvertical_stiffness_n_per_m = 1e9\n";
    for (name, study, extra, message) in [
        (
            "station.toml",
            "[study]\nrecord = [\"span1_mid_section\", { station = \"span3_mid_section\" }]\n",
            "",
            "record.toml:2:34: field `study.record[1].station`: unknown station \
             `span3_mid_section` on the study's bridge; expected one of span1_mid_section, \
             span2_mid_section, support2_section",
        ),
        (
            "quantity.toml",
            "[study]\nrecord = [{ station = \"support2_section\", quantities = [\"deflection\", \"torque\"] }]\n",
            "",
            "field `study.record[0].quantities[1]`: unknown quantity `torque`; expected one of \
             `deflection`, `bending_moment`, `shear_force`, `support_reaction`",
        ),
        (
            "force.toml",
            "[study]\nrecord = [{ station = \"support2_section\", quantities = [\"shear_force\"] }]\n",
            "",
            "field `study.record[0].quantities[0]`: station `support2_section` has no \
             shear_force; it records deflection, bending_moment, support_reaction",
        ),
        (
            "span.toml",
            "[study]\nrecord = [\"span2_mid_section\"]\n[study.axes]\nspan_count = [2, 1]\n",
            "",
            "unknown station `span2_mid_section` on the bridge of the cases with span_count=1",
        ),
        (
            "outside.toml",
            "[study]\n[study.axes]\ndamage_end_m = [12, 45]\n",
            damaged,
            "field `study.axes.damage_end_m[1]`: 45 m is outside the bridge; expected 0 to its \
             length, 40 m",
        ),
        (
            "order.toml",
            "[study]\n[study.axes]\ndamage_start_m = [8, 12]\n",
            damaged,
            "field `study.axes.damage_start_m[1]`: the stiffness-loss region would run from 12 m \
             to 12 m; expected `damage_start_m` < `damage_end_m`",
        ),
        (
            "no-region.toml",
            "[study]\n[study.axes]\ndamage_start_m = [8]\n",
            "",
            "field `study.axes.damage_start_m[0]`: the bridge has no stiffness loss to vary",
        ),
        (
            "no-support.toml",
            "[study]\n[study.axes]\nsupport_stiffness_n_per_m = [1e8]\n",
            "",
            "field `study.axes.support_stiffness_n_per_m[0]`: the bridge has no changed support",
        ),
        (
            "negative.toml",
            "[study]\n[study.axes]\nsupport_stiffness_n_per_m = [1e8, -1]\n",
            damaged,
            "field `study.axes.support_stiffness_n_per_m[1]`: `-1` is not allowed; expected a \
             number from 0 to 1000000000000 N/m",
        ),
        (
            "pattern.toml",
            "[study]\n[study.axes]\nlane_pattern = [\"single\", \"in_a_row\"]\n",
            "",
            "field `study.axes.lane_pattern[1]`: `in_a_row` is not allowed; expected `single`, \
             `side_by_side`, `meeting`",
        ),
        (
            "lanes.toml",
            "[study]\n[study.axes]\nlane_pattern = [\"single\", \"meeting\"]\n",
            "",
            "field `study.axes.lane_pattern[1]`: vehicle 1 (moving-force): lane_pattern \
             `meeting` puts a copy in the mirrored lane at y = 0.000 m: with lateral_position_m \
             = 0 m the two lanes overlap",
        ),
        (
            "platoon.toml",
            "[study]\n[study.axes]\nlane_pattern = [\"side_by_side\"]\nplatoon_size = [2]\n",
            "",
            "field `study.axes.lane_pattern[0]`: vehicle 1 (moving-force): lane_pattern \
             `side_by_side` places one vehicle in each of two lanes; it is not allowed with \
             platoon_size = 2",
        ),
    ] {
        let path = dir.path().join(name);
        std::fs::write(&path, format!("{study}\n{BASE}{extra}")).unwrap();
        let message = message.replace("record.toml", name);
        let out = dir.path().join(format!("out-{name}"));
        let study_error = vbi()
            .args(["study", path.to_str().unwrap(), "--out"])
            .arg(&out)
            .assert()
            .code(2)
            .stderr_has(&message)
            .get_output()
            .stderr
            .clone();
        assert!(!out.exists(), "{name}: no output before validation");
        let check_error = vbi()
            .args(["check", path.to_str().unwrap()])
            .assert()
            .code(2)
            .get_output()
            .stderr
            .clone();
        assert_eq!(study_error, check_error, "{name}: check and study agree");
    }
}

/// The axes change what they should: a longer damage region and a softer support lower the
/// first frequency; `side_by_side` loads the beam with two equal forces together (on a beam
/// both run on its axis): twice the static deflection; `meeting` with two forces that enter
/// from both ends at once, which meet over the middle support of the 2 × 20 m beam: another
/// static extreme, below the abreast one.
#[test]
fn the_new_axes_change_the_frequency_and_the_load_as_documented() {
    let dir = tempfile::tempdir().unwrap();
    let damaged =
        "\n[[bridge.stiffness_loss]]\nstart_m = 8.0\nend_m = 12.0\nmodulus_factor = 0.5\n\
                   [[bridge.support_change]]\nsupport = 2\nvertical_stiffness_n_per_m = 1e9\n";
    let study = "[study]\nseed = 3\n[study.axes]\ndamage_end_m = [12, 20]\n\
                 support_stiffness_n_per_m = [1e9, 1e8]\nlane_pattern = [\"single\", \
                 \"side_by_side\", \"meeting\"]\n";
    let path = dir.path().join("axes.toml");
    std::fs::write(
        &path,
        format!(
            "{study}\n{}{damaged}",
            BASE.replace("[scenario]\n", "[scenario]\nlateral_position_m = -1.875\n")
        ),
    )
    .unwrap();
    let out = dir.path().join("out");
    run_study(&path, &out);
    let (header, rows) = csv_rows(&out.join("cases.csv"));
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    let cell = |end: &str, k: &str, pattern: &str, column: &str| -> f64 {
        rows.iter()
            .find(|r| r[1] == end && r[2] == k && r[3] == pattern)
            .map(|r| r[col(column)].parse().unwrap())
            .unwrap()
    };
    let f1 = |end, k| cell(end, k, "single", "f1_hz");
    assert!(f1("20", "1000000000") < f1("12", "1000000000"));
    assert!(f1("12", "100000000") < f1("12", "1000000000"));
    let single = cell("12", "1000000000", "single", "static_u_m");
    let abreast = cell("12", "1000000000", "side_by_side", "static_u_m");
    let meeting = cell("12", "1000000000", "meeting", "static_u_m");
    // Two equal forces abreast: twice the static deflection, to round-off.
    assert!((abreast / single - 2.0).abs() < 1e-9, "{abreast} {single}");
    assert!(
        meeting != single && meeting.abs() < abreast.abs(),
        "{meeting}"
    );
}

/// When standard error is not a terminal (a Slurm log; here a pipe), the study prints plain
/// progress lines at the interval asked (0: one per case) with the cases done, the rate and the
/// time left; a negative interval is refused with exit code 2.
#[test]
fn progress_goes_to_a_log_as_lines_at_the_interval_asked() {
    let dir = tempfile::tempdir().unwrap();
    let file = study_file(dir.path(), "s.toml", SMALL);
    let out = dir.path().join("out");
    let output = vbi()
        .args(["study", file.to_str().unwrap(), "--no-figures"])
        .args(["--progress-interval", "0", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(output.status.success(), "{output:?}");
    let stderr = String::from_utf8(output.stderr).unwrap();
    let lines: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("progress: "))
        .collect();
    assert_eq!(lines.len(), 12, "{stderr}");
    assert!(
        lines[0].starts_with("progress: 1/12 cases (8.3 %), "),
        "{}",
        lines[0]
    );
    assert!(
        lines[11].starts_with("progress: 12/12 cases (100.0 %), "),
        "{}",
        lines[11]
    );
    assert!(lines
        .iter()
        .all(|l| l.contains(" cases/s, elapsed ") && l.contains(", ETA ")));
    // The default interval (30 s) is longer than this study: only the last case's line.
    let quiet = vbi()
        .args(["study", file.to_str().unwrap(), "--no-figures", "--out"])
        .arg(dir.path().join("quiet"))
        .output()
        .unwrap();
    let stderr = String::from_utf8(quiet.stderr).unwrap();
    assert_eq!(stderr.matches("progress: ").count(), 1, "{stderr}");
    vbi()
        .args(["study", file.to_str().unwrap(), "--progress-interval=-1"])
        .assert()
        .code(2)
        .stderr_has("--progress-interval -1 is not allowed");
}

/// Two processes on one `--out` (issue 17, defect 6): while another process holds the
/// directory's lock, `vbi study` and `vbi run` refuse it with exit 2, naming `--out` and the
/// holder's pid, and write nothing there; once it is released they run.
#[test]
fn a_locked_output_directory_is_refused_naming_its_holder() {
    let dir = tempfile::tempdir().unwrap();
    let file = study_file(dir.path(), "s.toml", SMALL);
    let out = dir.path().join("out");
    std::fs::create_dir_all(&out).unwrap();
    let lock = std::fs::OpenOptions::new()
        .read(true)
        .write(true)
        .create(true)
        .truncate(false)
        .open(out.join(".vbi.lock"))
        .unwrap();
    lock.lock().unwrap();
    std::fs::write(out.join(".vbi.lock"), "4242").unwrap();
    let output = vbi()
        .args(["study", file.to_str().unwrap(), "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("--out") && stderr.contains("another vbi process (pid 4242)"),
        "{stderr}"
    );
    assert!(!out.join("study.json").exists(), "nothing written");
    drop(lock);
    run_study(&file, &out);
    assert!(out.join("cases.csv").exists());
}
