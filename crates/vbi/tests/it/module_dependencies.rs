//! The library's top-level modules (those declared in `src/lib.rs`) depend on each other one
//! way: the graph of `crate::<module>` references between them has no cycle.
//!
//! The source files are read as the compiler finds them: from each `mod name;` declaration,
//! starting at `src/lib.rs`. A reference is a path `crate::m…`, a group `crate::{m…, n…}`, or a
//! `super::…` chain that climbs to the crate root. Comments (doc comments included), string and
//! character literals, and items under `#[cfg(test)]` (inline test modules and test files such
//! as `solver/tests.rs`) are not references: only the library's own code counts, so an
//! intra-doc link to a later stage or a test that uses one is allowed.
//!
//! The same holds one level down, between the files of every crate of the workspace (`vbi`,
//! `vbi-input`, `vbi-cli`, `vbi-py`; the rules are given where the files are read, below), and
//! no function of the library is longer than 150 lines.

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
    tokenize_with_lines(source).0
}

/// [`tokenize`], with the line (from 1) on which each token starts.
fn tokenize_with_lines(source: &str) -> (Vec<Token>, Vec<usize>) {
    let c: Vec<char> = source.chars().collect();
    let at = |i: usize| c.get(i).copied().unwrap_or('\0');
    let ident_char = |ch: char| ch == '_' || ch.is_alphanumeric();
    let mut out = Vec::new();
    let mut lines = Vec::new();
    let mut line = 1;
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
        let start = i;
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
        if lines.len() < out.len() {
            lines.push(line);
        }
        line += c[start..i.min(c.len())]
            .iter()
            .filter(|&&x| x == '\n')
            .count();
    }
    (out, lines)
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

/// What an attribute starting at `t[i]` does to the code after it.
enum Attribute {
    /// Not an attribute.
    None,
    /// An attribute that keeps the code; scanning goes on at the index.
    Keeps(usize),
    /// `#[cfg(test)]`: the item it is on ends just before the index.
    DropsItem(usize),
    /// `#![cfg(test)]`: the whole file is test code.
    DropsFile,
}

fn attribute(t: &[Token], i: usize) -> Attribute {
    if t[i] != Token::Punct('#') {
        return Attribute::None;
    }
    let inner = t.get(i + 1) == Some(&Token::Punct('!'));
    let open = if inner { i + 2 } else { i + 1 };
    if t.get(open) != Some(&Token::Punct('[')) {
        return Attribute::None;
    }
    let end = group_end(t, open);
    let content = &t[open + 1..end - 1];
    assert!(
        !is_ident(content.first(), "path"),
        "#[path] is not followed by this test; resolve the file by hand"
    );
    let cfg_test = content
        == [
            Token::Ident("cfg".into()),
            Token::Punct('('),
            Token::Ident("test".into()),
            Token::Punct(')'),
        ];
    match (cfg_test, inner) {
        (true, true) => Attribute::DropsFile,
        (true, false) => {
            // Any further attributes, then the item.
            let mut j = end;
            while t.get(j) == Some(&Token::Punct('#')) {
                j = group_end(t, j + 1);
            }
            Attribute::DropsItem(item_end(t, j))
        }
        (false, _) => Attribute::Keeps(end),
    }
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
        match attribute(&t, i) {
            Attribute::None => {}
            Attribute::Keeps(next) | Attribute::DropsItem(next) => {
                i = next;
                continue;
            }
            Attribute::DropsFile => return FileScan::default(),
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

// ---------------------------------------------------------------------------------------------
// Files: the same rule one level down, in every crate of the workspace.
//
// Every source file reached from a crate's root (`lib.rs` or `main.rs`) through `mod`
// declarations is a node. A file refers to another when its code uses a path that leads there:
// `crate::a::b::…`, `self::…` and `super::…` (resolved from the module they are written in, inline
// modules included), a path that starts with one of its module's child modules (`child::f()`),
// or with a name that a `use` brought in (`use crate::plot; … plot::draw()`); each path of a
// `use` group (`crate::{a::x, b}`) is one path. The file it refers to is that of the deepest
// module the path names: an item inside a module's file refers to that file, a module to its own
// file (`a.rs` or `a/mod.rs`); a call `a::run()` names a function of `a`, even beside a child
// `a::run`. A name that a module re-exports or aliases (`pub use crate::source::SourceFile;`,
// `use vbi_input as inputs;`) is followed to where it lives (the re-export is itself a use of
// that file), a glob `use a::*` refers to `a`'s file, and a path into another crate refers to
// no file. Declaring a child (`mod x;`) is not a reference: a parent that uses its child's items
// refers to it, which is fine as long as the child does not refer back. As above, comments,
// literals and `#[cfg(test)]` items are not code.

/// What a `use` declaration brings into its module: the name (`None` for a glob or `as _`) and
/// the path it names.
#[derive(Debug, Clone, PartialEq)]
struct Import {
    name: Option<String>,
    path: Vec<String>,
}

/// What one file declares, imports and uses, each with the inline module it is written in (`[]`
/// for the file's own module, `["inner"]` inside `mod inner { … }`).
#[derive(Debug, Default, PartialEq)]
struct FileItems {
    /// Modules declared: (inline scope, name, whether its body is in a file of its own).
    modules: Vec<(Vec<String>, String, bool)>,
    imports: Vec<(Vec<String>, Import)>,
    /// Paths in code (`a::b`; `a` for a call `a::f()`), and the path of every import.
    paths: Vec<(Vec<String>, Vec<String>)>,
}

/// Parses the use tree starting at `t[i]` under `prefix`; returns the index just past it.
fn use_tree(t: &[Token], i: usize, prefix: &[String], into: &mut Vec<Import>) -> usize {
    let mut path = prefix.to_vec();
    let mut j = i;
    if t.get(j) == Some(&Token::PathSep) {
        // `use ::name` names another crate.
        path.push("::".into());
        j += 1;
    }
    loop {
        match t.get(j) {
            Some(Token::Ident(segment)) => {
                path.push(segment.clone());
                j += 1;
                if t.get(j) == Some(&Token::PathSep) {
                    j += 1;
                } else {
                    break;
                }
            }
            Some(Token::Punct('{')) => {
                let end = group_end(t, j);
                j += 1;
                while j + 1 < end {
                    let next = use_tree(t, j, &path, into);
                    j = if next == j { j + 1 } else { next };
                    if t.get(j) == Some(&Token::Punct(',')) {
                        j += 1;
                    }
                }
                return end;
            }
            Some(Token::Punct('*')) => {
                into.push(Import { name: None, path });
                return j + 1;
            }
            _ => break,
        }
    }
    if path.last().map(String::as_str) == Some("self") {
        path.pop();
    }
    let mut name = path.last().cloned();
    if is_ident(t.get(j), "as") {
        name = match t.get(j + 1) {
            Some(Token::Ident(alias)) if alias != "_" => Some(alias.clone()),
            _ => None,
        };
        j += 2;
    }
    if !path.is_empty() {
        into.push(Import { name, path });
    }
    j
}

/// Scans the modules, imports and paths of one file's library code.
fn scan_items(source: &str) -> FileItems {
    let t = tokenize(source);
    let mut items = FileItems::default();
    // Inline modules open at this point: (name, index of their closing brace).
    let mut inline: Vec<(String, usize)> = Vec::new();
    let mut i = 0;
    while i < t.len() {
        while inline.last().is_some_and(|&(_, end)| i >= end) {
            inline.pop();
        }
        let scope: Vec<String> = inline.iter().map(|m| m.0.clone()).collect();
        match attribute(&t, i) {
            Attribute::None => {}
            Attribute::Keeps(next) | Attribute::DropsItem(next) => {
                i = next;
                continue;
            }
            Attribute::DropsFile => return FileItems::default(),
        }
        // `pub(in crate::a)` is a visibility, not a use of `a`.
        if is_ident(t.get(i), "pub") && t.get(i + 1) == Some(&Token::Punct('(')) {
            i = group_end(&t, i + 1);
            continue;
        }
        if is_ident(t.get(i), "mod") {
            if let Some(Token::Ident(name)) = t.get(i + 1) {
                match t.get(i + 2) {
                    Some(Token::Punct(';')) => {
                        items.modules.push((scope, name.clone(), true));
                        i += 3;
                        continue;
                    }
                    Some(Token::Punct('{')) => {
                        items.modules.push((scope, name.clone(), false));
                        inline.push((name.clone(), group_end(&t, i + 2)));
                        i += 3;
                        continue;
                    }
                    _ => {}
                }
            }
        }
        if is_ident(t.get(i), "use") {
            let mut imports = Vec::new();
            use_tree(&t, i + 1, &[], &mut imports);
            for import in imports {
                items.paths.push((scope.clone(), import.path.clone()));
                items.imports.push((scope.clone(), import));
            }
            i = item_end(&t, i);
            continue;
        }
        if let Some(Token::Ident(first)) = t.get(i) {
            let after_separator = i > 0 && t[i - 1] == Token::PathSep;
            if !after_separator && t.get(i + 1) == Some(&Token::PathSep) {
                let mut path = vec![first.clone()];
                let mut j = i;
                while t.get(j + 1) == Some(&Token::PathSep) {
                    match t.get(j + 2) {
                        Some(Token::Ident(segment)) => {
                            path.push(segment.clone());
                            j += 2;
                        }
                        _ => break,
                    }
                }
                // A call or a macro names a function of the module before it, even one that
                // shares its name with a child module (`report::run(…)` beside `mod run;`).
                if path.len() >= 2 {
                    if matches!(t.get(j + 1), Some(Token::Punct('(' | '!'))) {
                        path.pop();
                    }
                    items.paths.push((scope, path));
                }
                i = j + 1;
                continue;
            }
        }
        i += 1;
    }
    items
}

/// A module of a crate: the file its code is in, its child modules and its imports.
#[derive(Debug, Default)]
struct Module {
    file: String,
    children: BTreeSet<String>,
    imports: Vec<Import>,
}

/// A crate's modules and the paths its files use.
struct CrateFiles {
    /// By module path from the crate root (`[]` for the root itself).
    modules: BTreeMap<Vec<String>, Module>,
    /// (file, the module it is written in, the path used).
    paths: Vec<(String, Vec<String>, Vec<String>)>,
    /// The names of other crates (`std`, the dependencies of `Cargo.toml`).
    external: BTreeSet<String>,
}

/// How many re-exports a path may be followed through before it is taken as it is.
const MAX_HOPS: usize = 16;

impl CrateFiles {
    /// Reads the crate whose root file is `root` (files named relative to its folder); `external`
    /// are the names of other crates that its paths may start with.
    fn read(root: &Path, external: BTreeSet<String>) -> CrateFiles {
        let src = root.parent().expect("the source folder");
        let name = |file: &Path| {
            file.strip_prefix(src)
                .expect("a file under the source folder")
                .to_string_lossy()
                .replace('\\', "/")
        };
        let mut modules: BTreeMap<Vec<String>, Module> = BTreeMap::new();
        let mut paths = Vec::new();
        modules.insert(
            Vec::new(),
            Module {
                file: name(root),
                ..Module::default()
            },
        );
        let mut pending = vec![(root.to_path_buf(), Vec::<String>::new())];
        while let Some((file, module)) = pending.pop() {
            let source =
                fs::read_to_string(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
            let items = scan_items(&source);
            let file_name = name(&file);
            // The root's children are beside it, whatever its name (`main.rs` too).
            let dir = if module.is_empty() {
                src.to_path_buf()
            } else {
                children_dir(&file)
            };
            for (scope, child, own_file) in items.modules {
                let parent = [module.clone(), scope.clone()].concat();
                let mut path = parent.clone();
                path.push(child.clone());
                let child_file = if own_file {
                    let mut inline = scope.clone();
                    inline.push(child.clone());
                    let child_file = module_file(&dir, &inline);
                    pending.push((child_file.clone(), path.clone()));
                    name(&child_file)
                } else {
                    file_name.clone()
                };
                modules.entry(parent).or_default().children.insert(child);
                modules.entry(path).or_default().file = child_file;
            }
            for (scope, import) in items.imports {
                let at = [module.clone(), scope].concat();
                modules.entry(at).or_default().imports.push(import);
            }
            for (scope, path) in items.paths {
                paths.push((file_name.clone(), [module.clone(), scope].concat(), path));
            }
        }
        CrateFiles {
            modules,
            paths,
            external,
        }
    }

    /// The import that brings `name` into `module`, if any (`use name;` of a macro names itself,
    /// not an import to follow).
    fn import(&self, module: &[String], name: &str) -> Option<&Import> {
        self.modules.get(module)?.imports.iter().find(|import| {
            import.name.as_deref() == Some(name) && import.path != [name.to_string()]
        })
    }

    fn is_external(&self, first: &str) -> bool {
        first == "::" || self.external.contains(first)
    }

    /// `path`, used in `module`, from the crate root (`None`: outside the crate, or a local
    /// name such as a type or a variable).
    fn absolute(&self, module: &[String], path: &[String], hops: usize) -> Option<Vec<String>> {
        let (first, rest) = path.split_first()?;
        match first.as_str() {
            "crate" => Some(rest.to_vec()),
            "self" => Some([module, rest].concat()),
            "super" => {
                let supers = path.iter().take_while(|s| *s == "super").count();
                let kept = module.len().checked_sub(supers)?;
                Some([&module[..kept], &path[supers..]].concat())
            }
            _ if self.is_external(first) => None,
            _ if self.modules.get(module)?.children.contains(first) => {
                Some([module, path].concat())
            }
            _ if hops < MAX_HOPS => {
                let import = self.import(module, first)?;
                let target = self.absolute(module, &import.path, hops + 1)?;
                Some([target.as_slice(), rest].concat())
            }
            _ => None,
        }
    }

    /// The file that holds what the absolute `path` names (`None`: it leads out of the crate).
    fn file_of(&self, path: &[String], hops: usize) -> Option<&str> {
        let mut module: Vec<String> = Vec::new();
        for (k, segment) in path.iter().enumerate() {
            let here = self.modules.get(&module)?;
            if here.children.contains(segment) {
                module.push(segment.clone());
                continue;
            }
            if hops < MAX_HOPS {
                if let Some(import) = self.import(&module, segment) {
                    if let Some(target) = self.absolute(&module, &import.path, hops + 1) {
                        return self
                            .file_of(&[target.as_slice(), &path[k + 1..]].concat(), hops + 1);
                    }
                    if self.is_external(&import.path[0]) {
                        return None;
                    }
                }
            }
            break;
        }
        Some(self.modules.get(&module)?.file.as_str())
    }

    /// File → the other files it refers to; every file is a key.
    /// The file graph: an edge from a file to each other file that holds what its paths name,
    /// except to the files of its own descendant modules. A module's file is the façade of its
    /// children (it declares them, re-exports their items and may use them), and a child may use
    /// its parent's items (`super::T`): that is the shape of a Rust module, not a cycle. A cycle
    /// is then files of different subtrees naming each other, or a child whose parent's façade
    /// it needs going through another subtree that needs the child.
    fn graph(&self) -> Graph {
        let mut graph: Graph = self
            .modules
            .values()
            .map(|m| (m.file.clone(), BTreeSet::new()))
            .collect();
        // Each file's own module: the shortest module path written in it (inline modules share it).
        let mut module_of_file: BTreeMap<&str, &Vec<String>> = BTreeMap::new();
        for (path, module) in &self.modules {
            let shortest = module_of_file.entry(module.file.as_str()).or_insert(path);
            if path.len() < shortest.len() {
                *shortest = path;
            }
        }
        let is_descendant = |file: &str, target: &str| {
            let (Some(own), Some(other)) = (module_of_file.get(file), module_of_file.get(target))
            else {
                return false;
            };
            other.len() > own.len() && other.starts_with(own)
        };
        for (file, module, path) in &self.paths {
            let target = self
                .absolute(module, path, 0)
                .and_then(|absolute| self.file_of(&absolute, 0));
            if let Some(target) = target {
                if target != file && !is_descendant(file, target) {
                    graph
                        .get_mut(file)
                        .expect("a file of the crate")
                        .insert(target.to_string());
                }
            }
        }
        graph
    }
}

/// The names of the crates the crate of `manifest` depends on, and the standard ones.
fn dependency_names(manifest: &Path) -> BTreeSet<String> {
    let text =
        fs::read_to_string(manifest).unwrap_or_else(|e| panic!("{}: {e}", manifest.display()));
    let mut names: BTreeSet<String> = ["std", "core", "alloc"].map(String::from).into();
    let mut in_dependencies = false;
    for line in text.lines().map(str::trim) {
        if line.starts_with('[') {
            in_dependencies = line.trim_end_matches(']').ends_with("dependencies");
        } else if in_dependencies && !line.is_empty() && !line.starts_with('#') {
            let key = line.split(['=', '.', ' ']).next().expect("a key");
            names.insert(key.replace('-', "_"));
        }
    }
    names
}

/// The groups of files that refer to each other (the strongly connected components of more than
/// one file), each in order.
fn tangles(graph: &Graph) -> Vec<BTreeSet<String>> {
    // Files that reach `from`, following the edges backwards.
    let reaching = |from: &str| -> BTreeSet<String> {
        let mut seen = BTreeSet::from([from.to_string()]);
        let mut pending = vec![from.to_string()];
        while let Some(node) = pending.pop() {
            for (other, targets) in graph {
                if targets.contains(&node) && seen.insert(other.clone()) {
                    pending.push(other.clone());
                }
            }
        }
        seen
    };
    let reached = |from: &str| -> BTreeSet<String> {
        let mut seen = BTreeSet::from([from.to_string()]);
        let mut pending = vec![from.to_string()];
        while let Some(node) = pending.pop() {
            for next in graph.get(&node).into_iter().flatten() {
                if seen.insert(next.clone()) {
                    pending.push(next.clone());
                }
            }
        }
        seen
    };
    let mut groups: Vec<BTreeSet<String>> = Vec::new();
    for node in graph.keys() {
        if groups.iter().any(|g| g.contains(node)) {
            continue;
        }
        let group: BTreeSet<String> = reached(node)
            .intersection(&reaching(node))
            .cloned()
            .collect();
        if group.len() > 1 {
            groups.push(group);
        }
    }
    groups
}

/// The file graph of the crate in `crates/<name>` (root `src/<root>`), checked for cycles.
fn assert_files_without_a_cycle(name: &str, root: &str, min_files: usize) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(name);
    let files = CrateFiles::read(
        &dir.join("src").join(root),
        dependency_names(&dir.join("Cargo.toml")),
    );
    let graph = files.graph();
    // Not vacuous: every file was read, and the files do refer to each other.
    assert!(
        graph.len() >= min_files,
        "files of {name}: {:?}",
        graph.keys()
    );
    assert!(graph.values().map(BTreeSet::len).sum::<usize>() >= graph.len() / 2);
    let found = cycles(&graph);
    let shown: Vec<String> = found.iter().map(|c| c.join(" -> ")).collect();
    let groups: Vec<String> = tangles(&graph)
        .iter()
        .map(|g| g.iter().cloned().collect::<Vec<_>>().join(", "))
        .collect();
    assert!(
        found.is_empty(),
        "the files of crates/{name}/src have {} cycles:\n  {}\nfiles that refer to each other \
         (each group a tangle):\n  {}\nfile graph:\n{}",
        found.len(),
        shown.join("\n  "),
        groups.join("\n  "),
        render(&graph)
    );
    println!("file graph of crates/{name}/src:\n{}", render(&graph));
}

/// The library's files depend on each other one way, not only its top-level modules.
#[test]
fn the_library_files_depend_on_each_other_without_a_cycle() {
    assert_files_without_a_cycle("vbi", "lib.rs", 100);
}

/// The input crate's files depend on each other one way.
#[test]
fn the_input_crate_files_depend_on_each_other_without_a_cycle() {
    assert_files_without_a_cycle("vbi-input", "lib.rs", 15);
}

/// The command line's files depend on each other one way.
#[test]
fn the_command_line_files_depend_on_each_other_without_a_cycle() {
    assert_files_without_a_cycle("vbi-cli", "main.rs", 20);
}

/// The Python extension's files depend on each other one way.
#[test]
fn the_python_extension_files_depend_on_each_other_without_a_cycle() {
    assert_files_without_a_cycle("vbi-py", "lib.rs", 8);
}

/// The functions of one file's library code longer than `limit` lines (from the line of `fn` to
/// that of its closing brace): (line of `fn`, name, length).
fn long_functions(source: &str, limit: usize) -> Vec<(usize, String, usize)> {
    let (t, lines) = tokenize_with_lines(source);
    let mut found = Vec::new();
    let mut i = 0;
    while i < t.len() {
        match attribute(&t, i) {
            Attribute::None => {}
            Attribute::Keeps(next) | Attribute::DropsItem(next) => {
                i = next;
                continue;
            }
            Attribute::DropsFile => return Vec::new(),
        }
        if let (true, Some(Token::Ident(name))) = (is_ident(t.get(i), "fn"), t.get(i + 1)) {
            // The body: the first `{` outside the signature's parentheses and brackets; a `;`
            // first is a declaration without one.
            let mut j = i + 2;
            while j < t.len() && !matches!(t[j], Token::Punct('{' | ';')) {
                j = match t[j] {
                    Token::Punct('(' | '[') => group_end(&t, j),
                    _ => j + 1,
                };
            }
            if t.get(j) == Some(&Token::Punct('{')) {
                let end = group_end(&t, j);
                let length = lines[end - 1] - lines[i] + 1;
                if length > limit {
                    found.push((lines[i], name.clone(), length));
                }
            }
        }
        i += 1;
    }
    found
}

/// The longest a function of the library may be.
const MAX_FUNCTION_LINES: usize = 150;

/// No function of the library's code (outside `#[cfg(test)]` items and test files) is longer
/// than 150 lines: a longer one has steps that want names of their own.
#[test]
fn no_library_function_is_longer_than_150_lines() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let files = CrateFiles::read(&src.join("lib.rs"), BTreeSet::new());
    let names: BTreeSet<&str> = files.modules.values().map(|m| m.file.as_str()).collect();
    assert!(names.len() >= 50, "library files: {names:?}");
    let mut offenders = Vec::new();
    for name in names {
        let path = src.join(name);
        let source =
            fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        for (line, function, length) in long_functions(&source, MAX_FUNCTION_LINES) {
            offenders.push(format!(
                "crates/vbi/src/{name}:{line} fn {function}: {length} lines"
            ));
        }
    }
    assert!(
        offenders.is_empty(),
        "{} library functions are longer than {MAX_FUNCTION_LINES} lines:\n  {}",
        offenders.len(),
        offenders.join("\n  ")
    );
}

/// A folder of its own under the system's temporary one, removed when dropped.
struct TemporaryFolder(PathBuf);

impl TemporaryFolder {
    fn new(name: &str) -> TemporaryFolder {
        let path = std::env::temp_dir().join(format!("vbi-{name}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&path);
        fs::create_dir_all(&path).expect("a temporary folder");
        TemporaryFolder(path)
    }

    fn write(&self, file: &str, text: &str) {
        let path = self.0.join(file);
        fs::create_dir_all(path.parent().expect("a folder")).expect("a folder");
        fs::write(path, text).expect("a written file");
    }
}

impl Drop for TemporaryFolder {
    fn drop(&mut self) {
        let _ = fs::remove_dir_all(&self.0);
    }
}

/// A `use` tree brings each of its leaves into scope by name (`self` names the module, `as`
/// renames, `_` and `*` bring no name) with its whole path.
#[test]
fn a_use_tree_brings_each_leaf_into_scope_with_its_path() {
    let items = scan_items(
        "pub(crate) use crate::{a::{self, X}, b::*, c as d, e::F as _};\n\
         use ::outside::Y;\n\
         fn f() { a::g(); Vec::<u8>::new(); let x = y::z::w(); }",
    );
    let import = |name: Option<&str>, path: &[&str]| Import {
        name: name.map(String::from),
        path: path.iter().map(|s| s.to_string()).collect(),
    };
    let imports: Vec<Import> = items.imports.into_iter().map(|(_, i)| i).collect();
    assert_eq!(
        imports,
        vec![
            import(Some("a"), &["crate", "a"]),
            import(Some("X"), &["crate", "a", "X"]),
            import(None, &["crate", "b"]),
            import(Some("d"), &["crate", "c"]),
            import(None, &["crate", "e", "F"]),
            import(Some("Y"), &["::", "outside", "Y"]),
        ]
    );
    let code_paths: Vec<Vec<String>> = items.paths[6..].iter().map(|p| p.1.clone()).collect();
    assert_eq!(code_paths, vec![vec!["a"], vec!["y", "z"]]);
}

/// The file resolver follows each kind of path to the file that holds what it names, and the
/// cycle finder reports a cycle between two files with its files.
#[test]
fn the_file_resolver_finds_a_cycle_between_two_files() {
    let folder = TemporaryFolder::new("file-resolver");
    folder.write(
        "src/lib.rs",
        "mod a;\nmod b;\npub mod c;\npub use crate::c::Gadget;\nuse other as alias;\n\
         fn g() { a::inner() }\n",
    );
    // a.rs and b.rs refer to each other; a.rs only declares its child `inner` (and a function
    // of that name, which lib.rs calls).
    folder.write(
        "src/a.rs",
        "//! Not code: crate::c::deep.\nuse crate::b::Thing;\nmod inner;\n\
         pub fn helper() { let _ = \"crate::c\"; }\npub fn inner() {}\n",
    );
    folder.write(
        "src/a/inner.rs",
        "use super::super::c::deep::Deep;\nfn f() { crate::alias::x(); }\n",
    );
    folder.write(
        "src/b.rs",
        "pub struct Thing;\nfn f() { crate::a::helper() }\n\
         #[cfg(test)]\nmod tests { use crate::c::Gadget; }\n",
    );
    // c/deep.rs uses a name that the crate root re-exports from c/mod.rs.
    folder.write("src/c/mod.rs", "pub mod deep;\npub struct Gadget;\n");
    folder.write(
        "src/c/deep.rs",
        "use crate::Gadget;\npub struct Deep;\nmod local { use super::super::Gadget; }\n",
    );
    let external = BTreeSet::from(["other".to_string()]);
    let graph = CrateFiles::read(&folder.0.join("src/lib.rs"), external).graph();
    // The root's uses of a.rs and c/mod.rs are a façade's uses of its descendants: not edges.
    let expected: Graph = [
        ("lib.rs", vec![]),
        ("a.rs", vec!["b.rs"]),
        ("a/inner.rs", vec!["c/deep.rs"]),
        ("b.rs", vec!["a.rs"]),
        ("c/mod.rs", vec![]),
        ("c/deep.rs", vec!["c/mod.rs"]),
    ]
    .into_iter()
    .map(|(f, deps)| (f.to_string(), deps.into_iter().map(String::from).collect()))
    .collect();
    assert_eq!(graph, expected);
    assert_eq!(cycles(&graph), vec![vec!["a.rs", "b.rs", "a.rs"]]);
    assert_eq!(
        tangles(&graph),
        vec![BTreeSet::from(["a.rs".to_string(), "b.rs".to_string()])]
    );
}

/// A function's length runs from its `fn` line to its closing brace; test code and bodiless
/// declarations are not measured.
#[test]
fn a_function_is_measured_from_its_fn_line_to_its_closing_brace() {
    let source = "trait T {\n    fn declared(&self);\n}\n\
                  fn long(\n    x: [u8; 2],\n) {\n    let _ = '{';\n\n}\n\
                  #[cfg(test)]\nfn long_test() {\n\n\n\n}\n";
    assert_eq!(long_functions(source, 5), vec![(4, "long".to_string(), 6)]);
    assert!(long_functions(source, 6).is_empty());
}
