//! The manual's commands, run: every `vbi …` line of a ```sh block in docs/tutorial/*.md and
//! docs/how-to/*.md is executed, pages in file-name order (the tutorial first) and commands in
//! page order, in one scratch directory whose `examples/` is the repository's, so that a command
//! may read what an earlier one of its page wrote under `out/`. Each must exit with 0. A block
//! ```text preceded by the line `<!-- expected output -->` right after a ```sh block lists lines
//! that the last command of that block must print (standard output and error together; each
//! non-empty line without `…` must appear, trimmed, within a printed line). So the manual shows
//! only commands that work and output they really print (issue 19).

use std::path::{Path, PathBuf};

use super::common::{repository_root, vbi};

/// One runnable ```sh block: its commands (arguments split as a shell would, without quoting
/// beyond "…" and '…') and the lines its last command must print.
#[derive(Debug)]
struct Block {
    page: PathBuf,
    line: usize,
    commands: Vec<Vec<String>>,
    expected: Vec<String>,
}

/// The pages whose commands are run, in order: the tutorial, then the how-to guides.
fn pages() -> Vec<PathBuf> {
    let docs = repository_root().join("docs");
    let mut pages = Vec::new();
    for folder in ["tutorial", "how-to"] {
        let Ok(entries) = std::fs::read_dir(docs.join(folder)) else {
            continue;
        };
        let mut found: Vec<PathBuf> = entries
            .filter_map(|entry| entry.ok().map(|e| e.path()))
            .filter(|path| path.extension().is_some_and(|e| e == "md"))
            .collect();
        found.sort();
        pages.extend(found);
    }
    pages
}

/// The runnable blocks of one page.
fn blocks(page: &Path) -> Vec<Block> {
    let text = std::fs::read_to_string(page).expect("a readable page");
    let lines: Vec<&str> = text.lines().collect();
    let mut blocks = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        if lines[i].trim_end() != "```sh" {
            i += 1;
            continue;
        }
        let start = i + 1;
        let end = fence_end(&lines, start);
        let commands = commands_of(&lines[start..end]);
        let (expected, next) = expected_after(&lines, end + 1);
        if !commands.is_empty() {
            blocks.push(Block {
                page: page.to_path_buf(),
                line: start,
                commands,
                expected,
            });
        }
        i = next;
    }
    blocks
}

/// Index of the closing fence of the block opened before `start`.
fn fence_end(lines: &[&str], start: usize) -> usize {
    (start..lines.len())
        .find(|&j| lines[j].trim_start().starts_with("```"))
        .unwrap_or(lines.len())
}

/// The `vbi …` commands of a block's lines, continuation lines (ending in `\`) joined.
fn commands_of(lines: &[&str]) -> Vec<Vec<String>> {
    let mut commands = Vec::new();
    let mut current: Option<String> = None;
    for line in lines {
        let line = line.trim();
        let (body, continues) = match line.strip_suffix('\\') {
            Some(body) => (body.trim_end(), true),
            None => (line, false),
        };
        match current.as_mut() {
            Some(command) => {
                command.push(' ');
                command.push_str(body);
            }
            None if body.starts_with("vbi ") => current = Some(body.to_string()),
            None => continue,
        }
        if !continues {
            commands.extend(current.take().map(|c| split_words(&c)));
        }
    }
    commands.extend(current.map(|c| split_words(&c)));
    commands
}

/// Shell-like words: spaces separate, "…" and '…' group.
fn split_words(command: &str) -> Vec<String> {
    let mut words = Vec::new();
    let mut word = String::new();
    let mut quote: Option<char> = None;
    let mut in_word = false;
    for c in command.chars() {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), c) => word.push(c),
            (None, '"' | '\'') => {
                quote = Some(c);
                in_word = true;
            }
            (None, c) if c.is_whitespace() => {
                if in_word {
                    words.push(std::mem::take(&mut word));
                    in_word = false;
                }
            }
            (None, c) => {
                word.push(c);
                in_word = true;
            }
        }
    }
    if in_word {
        words.push(word);
    }
    words
}

/// The expected lines of a ```text block marked `<!-- expected output -->` at `from` (blank lines
/// before the marker allowed), and the index after it; none, and `from`, without a marker.
fn expected_after(lines: &[&str], from: usize) -> (Vec<String>, usize) {
    let mut j = from;
    while j < lines.len() && lines[j].trim().is_empty() {
        j += 1;
    }
    if j >= lines.len() || lines[j].trim() != "<!-- expected output -->" {
        return (Vec::new(), from);
    }
    j += 1;
    while j < lines.len() && lines[j].trim().is_empty() {
        j += 1;
    }
    if j >= lines.len() || !lines[j].trim_start().starts_with("```") {
        return (Vec::new(), j);
    }
    let end = fence_end(lines, j + 1);
    let expected = lines[j + 1..end]
        .iter()
        .map(|l| l.trim().to_string())
        .filter(|l| !l.is_empty() && !l.contains('…'))
        .collect();
    (expected, end + 1)
}

#[test]
fn the_command_line_splits_like_a_shell_and_joins_continued_lines() {
    let lines = [
        "# a comment",
        "vbi run examples/a.toml \\",
        "    --out \"out/my run\"",
        "cargo build",
        "vbi check 'x y.toml'",
    ];
    assert_eq!(
        commands_of(&lines),
        vec![
            vec!["vbi", "run", "examples/a.toml", "--out", "out/my run"],
            vec!["vbi", "check", "x y.toml"],
        ]
    );
}

#[test]
fn every_command_of_the_tutorial_and_the_how_to_guides_runs_and_prints_what_the_page_shows() {
    let scratch = tempfile::tempdir().expect("a scratch directory");
    link_examples(scratch.path());
    let all: Vec<Block> = pages().iter().flat_map(|page| blocks(page)).collect();
    // The tutorial and the guides show some forty commands: a handful means the pages moved.
    let count: usize = all.iter().map(|b| b.commands.len()).sum();
    assert!(
        count >= 20,
        "only {count} commands found in docs/tutorial and docs/how-to"
    );
    for block in &all {
        for (c, command) in block.commands.iter().enumerate() {
            let where_ = format!(
                "{}:{}: {}",
                block.page.display(),
                block.line,
                command.join(" ")
            );
            let output = vbi()
                .args(&command[1..])
                .current_dir(scratch.path())
                .output()
                .unwrap_or_else(|e| panic!("{where_}: could not run: {e}"));
            let printed = format!(
                "{}{}",
                String::from_utf8_lossy(&output.stdout),
                String::from_utf8_lossy(&output.stderr)
            );
            assert!(output.status.success(), "{where_} failed:\n{printed}");
            if c + 1 == block.commands.len() {
                for line in &block.expected {
                    assert!(
                        printed.lines().any(|p| p.contains(line.as_str())),
                        "{where_}: the page shows `{line}`, which the command did not print:\n{printed}"
                    );
                }
            }
        }
    }
}

/// `examples` in the scratch directory: the repository's (a symbolic link).
fn link_examples(scratch: &Path) {
    let examples = repository_root().join("examples");
    #[cfg(unix)]
    std::os::unix::fs::symlink(&examples, scratch.join("examples")).expect("examples linked");
    #[cfg(not(unix))]
    panic!(
        "the manual's commands are run on Unix only ({})",
        examples.display()
    );
}
