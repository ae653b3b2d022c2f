//! The harness is layered, and so is the oracle crate: no module imports one
//! that imports it back.
//!
//! This test reads every `.rs` file under `crates/harness/src` (and then
//! `crates/oracle/src`), maps each file
//! to its module (`lib.rs` → the crate root, `report/campaign.rs` →
//! `report::campaign`, `sweep/mod.rs` → `sweep`), and collects the module
//! paths each file names: in `use` statements (with their `{…}` groups) and in
//! inline paths (`crate::report::campaign::X`). A path starts at `crate::`,
//! `super::`, `self::`, or — the 2018 edition's relative paths — at the name of
//! one of the file's own child modules (`pub use measure::run` in
//! `sweep/mod.rs`). Each path is resolved to the longest prefix that is a
//! module; that module is a dependency of the file's module.
//!
//! Rules:
//! - A path names the module it goes through: importing an item through a
//!   parent's re-export (`super::X` where the parent has `pub use child::X`)
//!   depends on the parent, so a child names its sibling (`super::sibling::X`)
//!   when it means the sibling.
//! - A parent's `mod child;` declaration is not a dependency; its `pub use
//!   child::X` re-exports and its own uses of `child::…` are. A child using
//!   `super::X` or `crate::parent::X` defined in the parent depends on the
//!   parent. So a parent that re-exports its children keeps its own
//!   definitions in a child of their own, or the two form a cycle.
//! - Test-only code is ignored: items under `#[cfg(test)]` (`mod tests { … }`
//!   blocks, test fixtures) and the files of modules declared under
//!   `#[cfg(test)]` (`sweep/tests.rs`). Comments (doc links included) and
//!   string literals are not paths.
//!
//! Two graphs must be free of cycles: the graph of every module (the top-level
//! modules and the submodules of `report/`, `sweep/`, `generate/`, …, each a
//! node of its own), and the graph of the top-level modules, where a
//! submodule's dependencies are its top-level module's (`report::campaign →
//! sweep` is `report → sweep`). A cycle is printed with the file, line and
//! path behind each of its edges.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// A module path below the crate root (`[]` is the root).
type ModPath = Vec<String>;

fn show(m: &[String]) -> String {
    if m.is_empty() { "crate".to_string() } else { m.join("::") }
}

/// Every `.rs` file under `dir`, sorted.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).expect("a readable source folder") {
            let p = entry.expect("a folder entry").path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|e| e == "rs") {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

/// The module a file under `src` defines.
fn module_of(src: &Path, file: &Path) -> ModPath {
    let rel = file.strip_prefix(src).expect("a file under src");
    let mut parts: Vec<String> = rel.iter().map(|s| s.to_string_lossy().into_owned()).collect();
    let last = parts.pop().expect("a file name");
    let stem = last.strip_suffix(".rs").expect("a .rs file");
    if !(stem == "mod" || (parts.is_empty() && stem == "lib")) {
        parts.push(stem.to_string());
    }
    parts
}

/// The source with comments and the contents of string and character literals
/// replaced by spaces (newlines kept, so lines still count).
fn blank(src: &str) -> String {
    let c: Vec<char> = src.chars().collect();
    let mut out = String::with_capacity(src.len());
    let ident = |ch: char| ch.is_alphanumeric() || ch == '_';
    let keep = |ch: char| if ch == '\n' { '\n' } else { ' ' };
    let mut i = 0;
    while i < c.len() {
        let prev_ident = i > 0 && ident(c[i - 1]);
        if c[i] == '/' && c.get(i + 1) == Some(&'/') {
            while i < c.len() && c[i] != '\n' {
                out.push(' ');
                i += 1;
            }
        } else if c[i] == '/' && c.get(i + 1) == Some(&'*') {
            let mut depth = 0;
            while i < c.len() {
                if c[i] == '/' && c.get(i + 1) == Some(&'*') {
                    depth += 1;
                    out.push_str("  ");
                    i += 2;
                } else if c[i] == '*' && c.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    out.push_str("  ");
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    out.push(keep(c[i]));
                    i += 1;
                }
            }
        } else if c[i] == 'r'
            && !prev_ident_before_prefix(&c, i)
            && matches!(c.get(i + 1), Some('"') | Some('#'))
            && raw_string_start(&c, i + 1).is_some()
        {
            let hashes = raw_string_start(&c, i + 1).expect("checked");
            out.push('r');
            i += 1;
            for _ in 0..hashes {
                out.push('#');
            }
            out.push('"');
            i += hashes + 1;
            let closing: String = std::iter::once('"').chain(std::iter::repeat_n('#', hashes)).collect();
            let closing: Vec<char> = closing.chars().collect();
            while i < c.len() && c[i..].get(..closing.len()) != Some(&closing[..]) {
                out.push(keep(c[i]));
                i += 1;
            }
            out.extend(closing.iter());
            i += closing.len();
        } else if c[i] == '"' {
            out.push('"');
            i += 1;
            while i < c.len() && c[i] != '"' {
                if c[i] == '\\' {
                    out.push(' ');
                    i += 1;
                }
                if i < c.len() {
                    out.push(keep(c[i]));
                    i += 1;
                }
            }
            out.push('"');
            i += 1;
        } else if c[i] == '\'' && !prev_ident {
            // A character literal ('a', '\n', '\u{1F600}') or a lifetime ('a).
            if c.get(i + 1) == Some(&'\\') {
                out.push('\'');
                i += 1;
                while i < c.len() && c[i] != '\'' {
                    out.push(' ');
                    i += 1;
                }
                out.push('\'');
                i += 1;
            } else if c.get(i + 2) == Some(&'\'') {
                out.push_str("' '");
                i += 3;
            } else {
                out.push('\'');
                i += 1;
            }
        } else {
            out.push(c[i]);
            i += 1;
        }
    }
    out
}

/// Whether the `r` at `i` continues an identifier (other than a `b` prefix of
/// a raw byte string).
fn prev_ident_before_prefix(c: &[char], i: usize) -> bool {
    let ident = |ch: char| ch.is_alphanumeric() || ch == '_';
    if i == 0 || !ident(c[i - 1]) {
        return false;
    }
    !(c[i - 1] == 'b' && (i < 2 || !ident(c[i - 2])))
}

/// The number of `#`s of a raw string whose `#…#"` starts at `i`.
fn raw_string_start(c: &[char], i: usize) -> Option<usize> {
    let mut n = 0;
    while c.get(i + n) == Some(&'#') {
        n += 1;
    }
    (c.get(i + n) == Some(&'"')).then_some(n)
}

/// A token of blanked source: an identifier, `::`, or one other character.
#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Ident(String),
    Path,
    Punct(char),
}

fn tokens(code: &str) -> Vec<(Tok, usize)> {
    let c: Vec<char> = code.chars().collect();
    let mut out = Vec::new();
    let mut line = 1;
    let mut i = 0;
    while i < c.len() {
        let ch = c[i];
        if ch == '\n' {
            line += 1;
            i += 1;
        } else if ch.is_whitespace() {
            i += 1;
        } else if ch.is_alphanumeric() || ch == '_' {
            let start = i;
            while i < c.len() && (c[i].is_alphanumeric() || c[i] == '_') {
                i += 1;
            }
            out.push((Tok::Ident(c[start..i].iter().collect()), line));
        } else if ch == ':' && c.get(i + 1) == Some(&':') {
            out.push((Tok::Path, line));
            i += 2;
        } else {
            out.push((Tok::Punct(ch), line));
            i += 1;
        }
    }
    out
}

/// The tokens with every `#[cfg(test)]` item removed (up to its `;` or its
/// closing brace), and the names of modules declared `#[cfg(test)] mod name;`.
fn drop_test_items(toks: Vec<(Tok, usize)>) -> (Vec<(Tok, usize)>, Vec<String>) {
    let is = |t: &Tok, s: &str| matches!(t, Tok::Ident(x) if x == s);
    let mut out = Vec::new();
    let mut test_mods = Vec::new();
    let mut i = 0;
    while i < toks.len() {
        let cfg_test = toks[i].0 == Tok::Punct('#')
            && toks.get(i + 1).is_some_and(|t| t.0 == Tok::Punct('['))
            && toks.get(i + 2).is_some_and(|t| is(&t.0, "cfg"))
            && toks.get(i + 3).is_some_and(|t| t.0 == Tok::Punct('('))
            && toks.get(i + 4).is_some_and(|t| is(&t.0, "test"))
            && toks.get(i + 5).is_some_and(|t| t.0 == Tok::Punct(')'))
            && toks.get(i + 6).is_some_and(|t| t.0 == Tok::Punct(']'));
        if !cfg_test {
            out.push(toks[i].clone());
            i += 1;
            continue;
        }
        i += 7;
        // The item: up to a `;` outside brackets, or through its braces.
        let start = i;
        let mut depth = 0i32;
        while i < toks.len() {
            match toks[i].0 {
                Tok::Punct('(') | Tok::Punct('[') => depth += 1,
                Tok::Punct(')') | Tok::Punct(']') => depth -= 1,
                Tok::Punct(';') if depth == 0 => {
                    i += 1;
                    break;
                }
                Tok::Punct('{') if depth == 0 => {
                    let mut braces = 0;
                    while i < toks.len() {
                        match toks[i].0 {
                            Tok::Punct('{') => braces += 1,
                            Tok::Punct('}') => braces -= 1,
                            _ => {}
                        }
                        i += 1;
                        if braces == 0 {
                            break;
                        }
                    }
                    break;
                }
                _ => {}
            }
            i += 1;
        }
        let item = &toks[start..i];
        if let Some(m) = item.iter().position(|t| is(&t.0, "mod"))
            && let Some((Tok::Ident(name), _)) = item.get(m + 1)
            && item.last().is_some_and(|t| t.0 == Tok::Punct(';'))
        {
            test_mods.push(name.clone());
        }
    }
    (out, test_mods)
}

/// The paths of a use tree starting at `toks[i]` (an identifier): every leaf,
/// as segments; `self` in a group stands for the group's prefix.
fn use_tree(toks: &[(Tok, usize)], mut i: usize, prefix: &[String], out: &mut Vec<Vec<String>>) -> usize {
    let mut path = prefix.to_vec();
    loop {
        match toks.get(i).map(|t| &t.0) {
            Some(Tok::Ident(s)) => {
                if s != "self" || path.is_empty() {
                    path.push(s.clone());
                }
                i += 1;
            }
            Some(Tok::Punct('{')) => {
                i += 1;
                loop {
                    match toks.get(i).map(|t| &t.0) {
                        Some(Tok::Punct('}')) | None => return i + 1,
                        Some(Tok::Punct(',')) => i += 1,
                        _ => i = use_tree(toks, i, &path, out),
                    }
                }
            }
            Some(Tok::Punct('*')) => {
                out.push(path);
                return i + 1;
            }
            _ => {
                out.push(path);
                return i;
            }
        }
        if toks.get(i).map(|t| &t.0) == Some(&Tok::Path) {
            i += 1;
        } else {
            out.push(path);
            return i;
        }
    }
}

/// One module's file, its source's paths, and its test-only children.
struct Source {
    file: PathBuf,
    /// Each path named in the file, with its line.
    paths: Vec<(Vec<String>, usize)>,
    test_mods: Vec<String>,
}

fn read(file: &Path, children: &BTreeSet<String>) -> Source {
    let text = std::fs::read_to_string(file).expect("a readable source file");
    let (toks, test_mods) = drop_test_items(tokens(&blank(&text)));
    let mut paths = Vec::new();
    for i in 0..toks.len() {
        let Tok::Ident(s) = &toks[i].0 else { continue };
        let after_path = i > 0 && toks[i - 1].0 == Tok::Path;
        let starts = matches!(s.as_str(), "crate" | "super" | "self") || children.contains(s);
        if after_path || !starts || toks.get(i + 1).map(|t| &t.0) != Some(&Tok::Path) {
            continue;
        }
        let mut leaves = Vec::new();
        use_tree(&toks, i, &[], &mut leaves);
        paths.extend(leaves.into_iter().map(|p| (p, toks[i].1)));
    }
    Source { file: file.to_path_buf(), paths, test_mods }
}

/// The module a path names from module `from`: the longest prefix of the
/// absolute path that is a module; `None` for a path outside the crate.
fn resolve(from: &ModPath, path: &[String], modules: &BTreeSet<ModPath>) -> Option<ModPath> {
    let mut segs = path.iter().peekable();
    let mut abs: ModPath = match segs.peek().map(|s| s.as_str()) {
        Some("crate") => {
            segs.next();
            Vec::new()
        }
        Some("super") | Some("self") => {
            let mut base = from.clone();
            while let Some(s) = segs.peek() {
                match s.as_str() {
                    "super" => {
                        base.pop()?;
                    }
                    "self" => {}
                    _ => break,
                }
                segs.next();
            }
            base
        }
        // A child module's name, relative to this module.
        _ => from.clone(),
    };
    let mut best = abs.clone();
    for s in segs {
        abs.push(s.clone());
        if modules.contains(&abs) {
            best = abs.clone();
        } else {
            break;
        }
    }
    Some(best)
}

/// The evidence behind an edge: file, line and path.
type Why = (PathBuf, usize, String);

/// A cycle in `edges` (every node of it, the first repeated at the end), if
/// there is one.
fn find_cycle<N: Ord + Clone>(edges: &BTreeMap<N, BTreeMap<N, Why>>) -> Option<Vec<N>> {
    #[derive(Clone, Copy, PartialEq)]
    enum Mark {
        Open,
        Done,
    }
    fn visit<N: Ord + Clone>(
        n: &N,
        edges: &BTreeMap<N, BTreeMap<N, Why>>,
        marks: &mut BTreeMap<N, Mark>,
        stack: &mut Vec<N>,
    ) -> Option<Vec<N>> {
        marks.insert(n.clone(), Mark::Open);
        stack.push(n.clone());
        for m in edges.get(n).into_iter().flat_map(|e| e.keys()) {
            match marks.get(m) {
                Some(Mark::Open) => {
                    let at = stack.iter().position(|s| s == m).expect("an open node is on the stack");
                    let mut cycle = stack[at..].to_vec();
                    cycle.push(m.clone());
                    return Some(cycle);
                }
                Some(Mark::Done) => {}
                None => {
                    if let Some(c) = visit(m, edges, marks, stack) {
                        return Some(c);
                    }
                }
            }
        }
        stack.pop();
        marks.insert(n.clone(), Mark::Done);
        None
    }
    let mut marks = BTreeMap::new();
    for n in edges.keys() {
        if !marks.contains_key(n) {
            let mut stack = Vec::new();
            if let Some(c) = visit(n, edges, &mut marks, &mut stack) {
                return Some(c);
            }
        }
    }
    None
}

/// Every cycle found by removing, one at a time, an edge of each cycle found
/// (so that independent cycles are all reported), as printable lines.
fn cycles(edges: &BTreeMap<ModPath, BTreeMap<ModPath, Why>>, src: &Path) -> Vec<String> {
    let mut edges = edges.clone();
    let mut out = Vec::new();
    while let Some(cycle) = find_cycle(&edges) {
        let mut line = show(&cycle[0]);
        for w in cycle.windows(2) {
            let (file, l, path) = &edges[&w[0]][&w[1]];
            let file = file.strip_prefix(src).unwrap_or(file).display();
            line.push_str(&format!("\n    → {}   ({file}:{l}: {path})", show(&w[1])));
        }
        out.push(line);
        let (a, b) = (&cycle[0], &cycle[1]);
        edges.get_mut(a).expect("a node of the cycle").remove(b);
    }
    out
}

#[test]
fn the_harness_modules_import_each_other_without_a_cycle() {
    no_cycle(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src"), "harness", 40, 100);
}

/// The referee's crate too: its stages in double-word numbers, in dyadic
/// numbers and in rationals import one another one way.
#[test]
fn the_oracle_modules_import_each_other_without_a_cycle() {
    no_cycle(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../oracle/src"), "oracle", 20, 40);
}

/// Checks the crate whose sources are in `src` (`what`, at least `modules`
/// modules and `imports` edges found, so that a reader that finds nothing
/// cannot pass) for cycles in both graphs.
fn no_cycle(src: &Path, what: &str, min_modules: usize, min_edges: usize) {
    let src = src.to_path_buf();
    let files = rust_files(&src);
    let all: BTreeSet<ModPath> = files.iter().map(|f| module_of(&src, f)).collect();
    let children_of = |m: &ModPath| -> BTreeSet<String> {
        all.iter().filter(|c| c.len() == m.len() + 1 && c.starts_with(m)).map(|c| c[m.len()].clone()).collect()
    };
    let mut sources: BTreeMap<ModPath, Source> = BTreeMap::new();
    for f in &files {
        let m = module_of(&src, f);
        let source = read(f, &children_of(&m));
        sources.insert(m, source);
    }
    // Modules declared under `#[cfg(test)]`, and everything below them.
    let test_only: Vec<ModPath> = sources
        .iter()
        .flat_map(|(m, s)| {
            s.test_mods.iter().map(move |t| {
                let mut p = m.clone();
                p.push(t.clone());
                p
            })
        })
        .collect();
    sources.retain(|m, _| !test_only.iter().any(|t| m.starts_with(t)));
    let modules: BTreeSet<ModPath> = sources.keys().cloned().collect();
    assert!(modules.len() > min_modules, "{what}'s modules were found: {}", modules.len());

    let mut fine: BTreeMap<ModPath, BTreeMap<ModPath, Why>> = BTreeMap::new();
    let mut top: BTreeMap<ModPath, BTreeMap<ModPath, Why>> = BTreeMap::new();
    for (m, s) in &sources {
        fine.entry(m.clone()).or_default();
        for (path, line) in &s.paths {
            let Some(to) = resolve(m, path, &modules) else { continue };
            if &to == m || to.is_empty() {
                continue;
            }
            let why = (s.file.clone(), *line, path.join("::"));
            fine.entry(m.clone()).or_default().entry(to.clone()).or_insert_with(|| why.clone());
            let (tm, tt) = (m[..1.min(m.len())].to_vec(), to[..1].to_vec());
            if !tm.is_empty() && tm != tt {
                top.entry(tm).or_default().entry(tt).or_insert(why);
            }
        }
    }
    let edges: usize = fine.values().map(BTreeMap::len).sum();
    assert!(edges > min_edges, "{what}'s imports were found: {edges} edges");

    let mut found = cycles(&top, &src).into_iter().map(|c| format!("top-level modules: {c}")).collect::<Vec<_>>();
    found.extend(cycles(&fine, &src).into_iter().map(|c| format!("modules: {c}")));
    assert!(found.is_empty(), "{what}'s modules import each other in a cycle:\n\n{}\n", found.join("\n\n"));
}

/// The reader itself: paths in `use` groups, inline paths, a child's relative
/// path, comments and strings ignored, test-only items dropped.
#[test]
fn the_reader_finds_the_paths_a_file_names() {
    let dir = std::env::temp_dir().join(format!("crashtest-layering-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    let file = dir.join("mod.rs");
    std::fs::write(
        &file,
        "//! [`crate::doc::link`]\n\
         use crate::a::{b::{self, C}, d};\n\
         pub use child::X;\n\
         fn f() { let _ = crate::e::f::g(\"crate::not::a::path\"); let _ = '\"'; }\n\
         /* crate::commented::out */\n\
         #[cfg(test)]\n\
         mod tests { use crate::only::in_tests; }\n\
         #[cfg(test)]\n\
         mod more;\n",
    )
    .expect("a temporary file");
    let children: BTreeSet<String> = ["child".to_string()].into();
    let s = read(&file, &children);
    std::fs::remove_dir_all(&dir).expect("the temporary folder removed");
    let paths: Vec<String> = s.paths.iter().map(|(p, _)| p.join("::")).collect();
    assert_eq!(paths, ["crate::a::b", "crate::a::b::C", "crate::a::d", "child::X", "crate::e::f::g"]);
    assert_eq!(s.test_mods, ["more"]);

    let m = |s: &str| s.split("::").filter(|x| !x.is_empty()).map(String::from).collect::<ModPath>();
    let modules: BTreeSet<ModPath> = [m("a"), m("a::b"), m("e"), m("p"), m("p::child")].into();
    let seg = |s: &str| s.split("::").map(String::from).collect::<Vec<_>>();
    assert_eq!(resolve(&m("p"), &seg("crate::a::b::C"), &modules), Some(m("a::b")));
    assert_eq!(resolve(&m("p"), &seg("crate::e::f::g"), &modules), Some(m("e")));
    assert_eq!(resolve(&m("p"), &seg("child::X"), &modules), Some(m("p::child")));
    assert_eq!(resolve(&m("p::child"), &seg("super::Y"), &modules), Some(m("p")));

    let mut edges: BTreeMap<ModPath, BTreeMap<ModPath, Why>> = BTreeMap::new();
    let why = (PathBuf::from("x.rs"), 1, String::new());
    edges.entry(m("a")).or_default().insert(m("e"), why.clone());
    edges.entry(m("e")).or_default().insert(m("p"), why.clone());
    assert!(find_cycle(&edges).is_none());
    edges.entry(m("p")).or_default().insert(m("a"), why);
    assert_eq!(find_cycle(&edges), Some(vec![m("a"), m("e"), m("p"), m("a")]));
}
