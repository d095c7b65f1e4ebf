//! The library's top-level modules (those declared in `src/lib.rs`) depend on each other one
//! way: the graph of `crate::<module>` references between them has no cycle.
//!
//! The source files are read as the compiler finds them: from each `mod name;` declaration,
//! starting at `src/lib.rs`. A reference is a path `crate::m…`, a group `crate::{m…, n…}`, or a
//! `super::…` chain that climbs to the crate root. Comments (doc comments included), string and
//! character literals, and items under `#[cfg(test)]` (inline test modules and test files such
//! as `solver/tests.rs`) are not references: only the library's own code counts, so an
//! intra-doc link to a later stage or a test that uses one is allowed.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// Module → the other top-level modules it refers to.
type Graph = BTreeMap<String, BTreeSet<String>>;

#[derive(Debug, Clone, PartialEq)]
enum Token {
    Ident(String),
    /// `::`
    PathSep,
    Punct(char),
}

/// The tokens of a Rust source that matter for paths; comments and literals are dropped.
fn tokenize(source: &str) -> Vec<Token> {
    let c: Vec<char> = source.chars().collect();
    let at = |i: usize| c.get(i).copied().unwrap_or('\0');
    let ident_char = |ch: char| ch == '_' || ch.is_alphanumeric();
    let mut out = Vec::new();
    let mut i = 0;
    // Skips a (possibly raw) string literal starting at c[i] (at `"` or at the first `#`).
    let skip_string = |mut i: usize, raw: bool| -> usize {
        if raw {
            let mut hashes = 0;
            while at(i) == '#' {
                hashes += 1;
                i += 1;
            }
            i += 1; // the opening quote
            loop {
                if i >= c.len() {
                    return i;
                }
                if c[i] == '"' && (1..=hashes).all(|h| at(i + h) == '#') {
                    return i + 1 + hashes;
                }
                i += 1;
            }
        }
        i += 1;
        while i < c.len() && c[i] != '"' {
            i += if c[i] == '\\' { 2 } else { 1 };
        }
        i + 1
    };
    while i < c.len() {
        let ch = c[i];
        if ch.is_whitespace() {
            i += 1;
        } else if ch == '/' && at(i + 1) == '/' {
            while i < c.len() && c[i] != '\n' {
                i += 1;
            }
        } else if ch == '/' && at(i + 1) == '*' {
            let mut depth = 0;
            while i < c.len() {
                if c[i] == '/' && at(i + 1) == '*' {
                    depth += 1;
                    i += 2;
                } else if c[i] == '*' && at(i + 1) == '/' {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
        } else if ch == '"' {
            i = skip_string(i, false);
        } else if ch == '\'' {
            if at(i + 1) == '\\' {
                // An escaped character literal: '\n', '\'', '\u{..}'.
                i += 3;
                while i < c.len() && c[i] != '\'' {
                    i += 1;
                }
                i += 1;
            } else if at(i + 2) == '\'' {
                i += 3; // 'x'
            } else {
                // A lifetime or a label: the quote and its name.
                i += 1;
                while i < c.len() && ident_char(c[i]) {
                    i += 1;
                }
            }
        } else if ident_char(ch) {
            let start = i;
            while i < c.len() && ident_char(c[i]) {
                i += 1;
            }
            let word: String = c[start..i].iter().collect();
            let prefix = matches!(word.as_str(), "b" | "r" | "br" | "c" | "cr");
            if prefix && at(i) == '"' {
                i = skip_string(i, word.contains('r'));
            } else if prefix && word.contains('r') && at(i) == '#' && matches!(at(i + 1), '"' | '#')
            {
                i = skip_string(i, true);
            } else if word == "b" && at(i) == '\'' {
                // A byte literal b'x' or b'\n'.
                i += if at(i + 1) == '\\' { 1 } else { 0 };
                i += 2;
                while i < c.len() && c[i] != '\'' {
                    i += 1;
                }
                i += 1;
            } else if word == "r" && at(i) == '#' {
                // A raw identifier r#name.
                let start = i + 1;
                i += 1;
                while i < c.len() && ident_char(c[i]) {
                    i += 1;
                }
                out.push(Token::Ident(c[start..i].iter().collect()));
            } else if !ch.is_ascii_digit() {
                out.push(Token::Ident(word));
            }
        } else if ch == ':' && at(i + 1) == ':' {
            out.push(Token::PathSep);
            i += 2;
        } else {
            out.push(Token::Punct(ch));
            i += 1;
        }
    }
    out
}

/// What one file declares and refers to.
#[derive(Debug, Default, PartialEq)]
struct FileScan {
    /// Names of the crate-root items it refers to (`crate::name`, or `super::…` up to the root).
    root_references: BTreeSet<String>,
    /// Out-of-line child modules (`mod name;`) outside `#[cfg(test)]`, with the inline modules
    /// they are declared in: `["inline", "name"]`.
    child_modules: Vec<Vec<String>>,
}

fn is_ident(t: Option<&Token>, word: &str) -> bool {
    matches!(t, Some(Token::Ident(w)) if w == word)
}

/// Index just past the delimiter group opening at `open` (a `(`, `[` or `{`).
fn group_end(t: &[Token], open: usize) -> usize {
    let mut depth = 0i32;
    let mut i = open;
    while i < t.len() {
        match t[i] {
            Token::Punct('(' | '[' | '{') => depth += 1,
            Token::Punct(')' | ']' | '}') => {
                depth -= 1;
                if depth == 0 {
                    return i + 1;
                }
            }
            _ => {}
        }
        i += 1;
    }
    t.len()
}

/// Index just past the item starting at `start`: its `;` or its closing `}` at depth 0.
fn item_end(t: &[Token], start: usize) -> usize {
    let mut i = start;
    while i < t.len() {
        match t[i] {
            Token::Punct(';') => return i + 1,
            Token::Punct('{') => {
                let end = group_end(t, i);
                // `use a::{b, c};` and `struct S {..}` alike: a `;` right after still belongs.
                return if matches!(t.get(end), Some(Token::Punct(';'))) {
                    end + 1
                } else {
                    end
                };
            }
            Token::Punct('(' | '[') => i = group_end(t, i),
            _ => i += 1,
        }
    }
    t.len()
}

/// The first segment of the path (or of each path of a `{..}` group) starting at `i`.
fn first_segments(t: &[Token], i: usize, into: &mut BTreeSet<String>) {
    match t.get(i) {
        Some(Token::Ident(name)) if name != "self" => {
            into.insert(name.clone());
        }
        Some(Token::Punct('{')) => {
            let end = group_end(t, i);
            let mut item_start = true;
            let mut j = i + 1;
            while j + 1 < end {
                match &t[j] {
                    Token::Punct('{' | '(' | '[') => {
                        j = group_end(t, j);
                        item_start = false;
                        continue;
                    }
                    Token::Punct(',') => item_start = true,
                    Token::Ident(name) if item_start => {
                        if name != "self" {
                            into.insert(name.clone());
                        }
                        item_start = false;
                    }
                    _ => item_start = false,
                }
                j += 1;
            }
        }
        _ => {}
    }
}

/// Scans a file whose module lies `depth` levels below the crate root (1 for `src/fe/mod.rs`,
/// 2 for `src/fe/statics.rs`).
fn scan(source: &str, depth: usize) -> FileScan {
    let t = tokenize(source);
    let mut scan = FileScan::default();
    // Inline modules open at this point: (name, index of their closing brace).
    let mut inline: Vec<(String, usize)> = Vec::new();
    let mut i = 0;
    while i < t.len() {
        while inline.last().is_some_and(|&(_, end)| i >= end) {
            inline.pop();
        }
        // Attributes: `#[..]` and `#![..]`; `cfg(test)` drops the item (or the file) it is on.
        if t[i] == Token::Punct('#') {
            let inner = t.get(i + 1) == Some(&Token::Punct('!'));
            let open = if inner { i + 2 } else { i + 1 };
            if t.get(open) == Some(&Token::Punct('[')) {
                let end = group_end(&t, open);
                let attribute = &t[open + 1..end - 1];
                assert!(
                    !is_ident(attribute.first(), "path"),
                    "#[path] is not followed by this test; resolve the file by hand"
                );
                let cfg_test = attribute
                    == [
                        Token::Ident("cfg".into()),
                        Token::Punct('('),
                        Token::Ident("test".into()),
                        Token::Punct(')'),
                    ];
                if cfg_test && inner {
                    return FileScan::default();
                }
                if cfg_test {
                    // Skip any further attributes, then the item.
                    let mut j = end;
                    while t.get(j) == Some(&Token::Punct('#')) {
                        j = group_end(&t, j + 1);
                    }
                    i = item_end(&t, j);
                } else {
                    i = end;
                }
                continue;
            }
        }
        if is_ident(t.get(i), "mod") {
            if let Some(Token::Ident(name)) = t.get(i + 1) {
                match t.get(i + 2) {
                    Some(Token::Punct(';')) => {
                        let mut path: Vec<String> = inline.iter().map(|m| m.0.clone()).collect();
                        path.push(name.clone());
                        scan.child_modules.push(path);
                        i += 3;
                        continue;
                    }
                    Some(Token::Punct('{')) => {
                        inline.push((name.clone(), group_end(&t, i + 2)));
                        i += 3;
                        continue;
                    }
                    _ => {}
                }
            }
        }
        if is_ident(t.get(i), "crate") && t.get(i + 1) == Some(&Token::PathSep) {
            first_segments(&t, i + 2, &mut scan.root_references);
            i += 2;
            continue;
        }
        if is_ident(t.get(i), "super")
            && (i == 0 || t[i - 1] != Token::PathSep)
            && t.get(i + 1) == Some(&Token::PathSep)
        {
            let mut supers = 0;
            let mut j = i;
            while is_ident(t.get(j), "super") && t.get(j + 1) == Some(&Token::PathSep) {
                supers += 1;
                j += 2;
            }
            if supers >= depth + inline.len() {
                first_segments(&t, j, &mut scan.root_references);
            }
            i = j;
            continue;
        }
        i += 1;
    }
    scan
}

/// The file of module `name` declared in a file whose children live in `dir`.
fn module_file(dir: &Path, path: &[String]) -> PathBuf {
    let mut base = dir.to_path_buf();
    for segment in &path[..path.len() - 1] {
        base.push(segment);
    }
    let name = path.last().expect("a module name");
    let flat = base.join(format!("{name}.rs"));
    if flat.exists() {
        flat
    } else {
        base.join(name).join("mod.rs")
    }
}

/// Directory in which the out-of-line children of `file` live.
fn children_dir(file: &Path) -> PathBuf {
    let dir = file.parent().expect("a parent directory");
    match file.file_stem().and_then(|s| s.to_str()) {
        Some("mod" | "lib") => dir.to_path_buf(),
        Some(stem) => dir.join(stem),
        None => dir.to_path_buf(),
    }
}

/// The module graph of the crate whose root is `lib`, and the files read for each module.
fn module_graph(lib: &Path) -> (Graph, BTreeMap<String, Vec<PathBuf>>) {
    let read = |path: &Path| {
        fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
    };
    let root = scan(&read(lib), 0);
    let modules: Vec<String> = root
        .child_modules
        .iter()
        .filter(|p| p.len() == 1)
        .map(|p| p[0].clone())
        .collect();
    let names: BTreeSet<&String> = modules.iter().collect();
    let mut graph = Graph::new();
    let mut files = BTreeMap::new();
    for module in &modules {
        let mut references = BTreeSet::new();
        let mut read_files = Vec::new();
        let mut pending = vec![(
            module_file(&children_dir(lib), std::slice::from_ref(module)),
            1,
        )];
        while let Some((file, depth)) = pending.pop() {
            let s = scan(&read(&file), depth);
            references.extend(s.root_references);
            let dir = children_dir(&file);
            for child in s.child_modules {
                let child_depth = depth + child.len();
                pending.push((module_file(&dir, &child), child_depth));
            }
            read_files.push(file);
        }
        references.retain(|r| r != module && names.contains(r));
        graph.insert(module.clone(), references);
        files.insert(module.clone(), read_files);
    }
    (graph, files)
}

/// Every cycle found by a depth-first search (each as `a -> b -> … -> a`), none if acyclic.
fn cycles(graph: &Graph) -> Vec<Vec<String>> {
    #[derive(Clone, Copy, PartialEq)]
    enum State {
        New,
        OnStack,
        Done,
    }
    fn visit(
        node: &str,
        graph: &Graph,
        state: &mut BTreeMap<String, State>,
        stack: &mut Vec<String>,
        found: &mut Vec<Vec<String>>,
    ) {
        state.insert(node.to_string(), State::OnStack);
        stack.push(node.to_string());
        for next in graph.get(node).into_iter().flatten() {
            match state.get(next.as_str()).copied().unwrap_or(State::New) {
                State::New => visit(next, graph, state, stack, found),
                State::OnStack => {
                    let from = stack.iter().position(|m| m == next).expect("on the stack");
                    let mut cycle = stack[from..].to_vec();
                    cycle.push(next.clone());
                    found.push(cycle);
                }
                State::Done => {}
            }
        }
        stack.pop();
        state.insert(node.to_string(), State::Done);
    }
    let mut state = BTreeMap::new();
    let mut found = Vec::new();
    for node in graph.keys() {
        if state.get(node.as_str()).copied().unwrap_or(State::New) == State::New {
            visit(node, graph, &mut state, &mut Vec::new(), &mut found);
        }
    }
    found
}

fn render(graph: &Graph) -> String {
    graph
        .iter()
        .map(|(m, deps)| {
            let deps: Vec<&str> = deps.iter().map(String::as_str).collect();
            format!("  {m} -> {}\n", deps.join(", "))
        })
        .collect()
}

/// The library's modules form a directed acyclic graph: stations and FE-model checks in `fe`,
/// the modal stage after it, the studies after the analysis, and so on (docs/architecture.md).
#[test]
fn the_library_modules_depend_on_each_other_without_a_cycle() {
    let lib = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/lib.rs");
    let (graph, files) = module_graph(&lib);
    // Not vacuous: every module was read, and the stages do refer to each other.
    assert!(graph.len() >= 10, "modules of lib.rs: {:?}", graph.keys());
    for (module, read) in &files {
        assert!(!read.is_empty(), "no file read for `{module}`");
    }
    assert!(graph.values().map(BTreeSet::len).sum::<usize>() >= 10);
    let found = cycles(&graph);
    let shown: Vec<String> = found.iter().map(|c| c.join(" -> ")).collect();
    assert!(
        found.is_empty(),
        "the module graph has cycles:\n  {}\nmodule graph:\n{}",
        shown.join("\n  "),
        render(&graph)
    );
    println!("module graph:\n{}", render(&graph));
}

/// The scanner counts code only: not comments, doc comments, strings or `#[cfg(test)]` items;
/// it reads grouped imports, `super` chains to the root, and the files of `mod name;`.
#[test]
fn the_dependency_scanner_counts_only_library_code() {
    let source = r####"
        //! Module docs link [`crate::doc_module`].
        /* a block comment about crate::block /* nested crate::nested */ */
        use crate::plain::Thing;
        use crate::{grouped::{A, B}, other, self};
        use super::super::climbed;
        use super::sibling;
        /// Doc comment on crate::documented.
        fn f<'a>(x: &'a str) -> char {
            let _ = "a string with crate::quoted and a quote \" inside";
            let _ = r#"raw crate::raw "quoted" "#;
            let _ = b'{';
            let _ = crate::in_code::call();
            '{'
        }
        mod sub;
        mod inline {
            use super::super::super::deep;
            mod nested_file;
        }
        #[cfg(test)]
        mod tests;
        #[cfg(test)]
        #[allow(unused)]
        mod inline_tests {
            use crate::only_in_tests;
        }
        #[cfg(test)]
        use crate::test_import::{X, Y};
        fn g() { crate::after_tests::h() }
    "####;
    let found = scan(source, 2);
    let expected: BTreeSet<String> = [
        "plain",
        "grouped",
        "other",
        "climbed",
        "in_code",
        "deep",
        "after_tests",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    assert_eq!(found.root_references, expected);
    assert_eq!(
        found.child_modules,
        vec![
            vec!["sub".to_string()],
            vec!["inline".to_string(), "nested_file".to_string()]
        ]
    );
    assert_eq!(scan("#![cfg(test)]\nuse crate::x;", 1), FileScan::default());
}

/// The cycle finder reports a cycle as the path that closes it.
#[test]
fn a_cycle_is_reported_with_its_modules() {
    let graph: Graph = [
        ("a", vec!["b"]),
        ("b", vec!["c"]),
        ("c", vec!["a", "d"]),
        ("d", vec![]),
    ]
    .into_iter()
    .map(|(m, deps)| (m.to_string(), deps.into_iter().map(String::from).collect()))
    .collect();
    assert_eq!(cycles(&graph), vec![vec!["a", "b", "c", "a"]]);
    let mut acyclic = graph.clone();
    acyclic.get_mut("c").expect("c").remove("a");
    assert!(cycles(&acyclic).is_empty());
}
