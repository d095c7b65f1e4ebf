//! The input refusals, tested where they are made: every file of `tests/files/good` loads, and
//! every file of `tests/files/bad` is refused with exactly the message its first line expects
//! (`# expect: file:line:column: field `key`: message`; tests/files/README.md). Each file is
//! read as `vbi check` reads it: [`vbi_input::validate`], which tells the kind of the file by its
//! top-level table and runs that kind's loader, the one that `vbi run`, `vbi study`,
//! `vbi measure` and the Python package run.
//!
//! `VBI_BLESS=1 cargo test -p vbi-input --test input_files` rewrites each bad file's first line
//! with the message the code gives today (review the diff before committing it).

use std::path::{Path, PathBuf};

use vbi_input::SourceFile;

/// The prefix of a bad file's first line, before its expected message.
const EXPECT: &str = "# expect: ";

/// The folder of the fixtures of one kind (`good` or `bad`).
fn fixture_folder(kind: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests")
        .join("files")
        .join(kind)
}

/// Every `.toml` file of `folder`, by name (data files such as CSVs stand in `files/data`).
fn toml_files(folder: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(folder)
        .unwrap_or_else(|e| panic!("cannot list {}: {e}", folder.display()))
        .map(|entry| entry.expect("a directory entry").path())
        .filter(|path| path.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    files
}

/// What `vbi check` says of the file: its kind, or its refusal with the folder's path taken out
/// of it (so that a message reads `name.toml:3:1: ...` wherever the repository stands).
fn check(path: &Path, folder: &Path) -> Result<&'static str, String> {
    SourceFile::read(path)
        .and_then(|file| vbi_input::validate(&file))
        .map_err(|error| {
            error
                .to_string()
                .replace(&format!("{}/", folder.display()), "")
        })
}

#[test]
fn good_files_load_and_bad_files_are_refused_with_their_expected_message() {
    let bless = std::env::var_os("VBI_BLESS").is_some_and(|v| v == "1");
    let mut failures = Vec::new();

    let good = fixture_folder("good");
    let good_files = toml_files(&good);
    for path in &good_files {
        if let Err(message) = check(path, &good) {
            failures.push(format!("good/{}: refused: {message}", name(path)));
        }
    }

    let bad = fixture_folder("bad");
    let bad_files = toml_files(&bad);
    for path in &bad_files {
        let text = std::fs::read_to_string(path).expect("a readable fixture");
        let (first_line, rest) = text.split_once('\n').unwrap_or((&text, ""));
        let Some(expected) = first_line.strip_prefix(EXPECT) else {
            failures.push(format!(
                "bad/{}: the first line must be `{EXPECT}<message>`",
                name(path)
            ));
            continue;
        };
        match check(path, &bad) {
            Ok(kind) => failures.push(format!(
                "bad/{}: loaded as a {kind} file; expected the refusal {expected}",
                name(path)
            )),
            Err(message) if message == expected => {}
            Err(message) if bless => {
                std::fs::write(path, format!("{EXPECT}{message}\n{rest}")).expect("blessed");
            }
            Err(message) => failures.push(format!(
                "bad/{}:\n  expected: {expected}\n  got:      {message}",
                name(path)
            )),
        }
    }

    assert!(
        good_files.len() >= 10 && bad_files.len() >= 40,
        "too few fixtures: {} good, {} bad",
        good_files.len(),
        bad_files.len()
    );
    assert!(failures.is_empty(), "\n{}", failures.join("\n"));
}

/// The file name of a fixture, for messages.
fn name(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}
