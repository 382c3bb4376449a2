//! `module_cycles`: the import graph between the modules of one crate, read from its source
//! (`use crate::…`, `use super::…`, `self::…` and such paths in code, with the `mod` tree), and
//! the cycles in it. `tests/workspace.rs` runs it over every crate of the workspace, so a cycle
//! fails `cargo test --workspace` with its modules named.
//!
//! Invariant: it knows nothing of the workspace's crates; it reads Rust text, it does not
//! compile it (no macros expanded, `#[path]` ignored).
//!
//! A node is a module *file* (`src/a/b.rs` or `src/a/b/mod.rs` is `a::b`; inline modules such
//! as `mod tests { … }` belong to their file). An edge a → b says a file names a path in b. An
//! edge from a module to its own descendants is left out: a parent declares its children, so
//! counting those would make every `use super::…` of a child a cycle; a cycle needs two
//! modules of which neither contains the other to name each other (possibly through others).

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// The module graph of one crate: nodes are module paths (`""` is the crate root), edges go
/// from the file that names a path to the file that defines it.
#[derive(Debug, Default, Clone, PartialEq)]
pub struct Graph {
    pub edges: BTreeMap<String, BTreeSet<String>>,
}

/// The module path of a file relative to `src/`: `lib.rs`/`main.rs` → `""`, `a/mod.rs` and
/// `a.rs` → `a`, `a/b.rs` → `a::b`. `None` for files that are no module of the library or
/// binary root (e.g. `src/bin/x.rs` is a crate of its own).
pub fn module_of(relative: &Path) -> Option<String> {
    let parts: Vec<String> = relative
        .iter()
        .map(|p| p.to_string_lossy().into_owned())
        .collect();
    let (last, dirs) = parts.split_last()?;
    if dirs.first().is_some_and(|d| d == "bin") {
        return None;
    }
    let stem = last.strip_suffix(".rs")?;
    let mut path: Vec<&str> = dirs.iter().map(String::as_str).collect();
    if !(stem == "mod" || (dirs.is_empty() && (stem == "lib" || stem == "main"))) {
        path.push(stem);
    }
    Some(path.join("::"))
}

/// Rust source with comments removed and string and character literals emptied, so that
/// braces and paths inside them are not read as code.
fn code_only(text: &str) -> String {
    let b: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        let next = b.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < b.len() && b[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            while i < b.len() {
                if b[i] == '/' && b.get(i + 1) == Some(&'*') {
                    depth += 1;
                    i += 2;
                } else if b[i] == '*' && b.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
            out.push(' ');
        } else if c == 'r'
            && matches!(next, Some('#') | Some('"'))
            && !ident_char(b.get(i.wrapping_sub(1)))
        {
            // Raw string r#"…"#: skip to the quote and the same number of hashes.
            let mut j = i + 1;
            let mut hashes = 0;
            while b.get(j) == Some(&'#') {
                hashes += 1;
                j += 1;
            }
            if b.get(j) != Some(&'"') {
                out.push(c);
                i += 1;
                continue;
            }
            j += 1;
            loop {
                if j >= b.len() {
                    break;
                }
                if b[j] == '"' && (0..hashes).all(|k| b.get(j + 1 + k) == Some(&'#')) {
                    j += 1 + hashes;
                    break;
                }
                j += 1;
            }
            out.push_str("\"\"");
            i = j;
        } else if c == '"' {
            i += 1;
            while i < b.len() && b[i] != '"' {
                if b[i] == '\\' {
                    i += 1;
                }
                i += 1;
            }
            i += 1;
            out.push_str("\"\"");
        } else if c == '\'' {
            // A character literal ('x', '\n', '\u{..}') or a lifetime ('a): only the first is
            // skipped.
            let close = if next == Some('\\') {
                (i + 2..b.len().min(i + 12)).find(|&k| b[k] == '\'')
            } else if b.get(i + 2) == Some(&'\'') {
                Some(i + 2)
            } else {
                None
            };
            match close {
                Some(k) => {
                    out.push_str("' '");
                    i = k + 1;
                }
                None => {
                    out.push(c);
                    i += 1;
                }
            }
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

fn ident_char(c: Option<&char>) -> bool {
    c.is_some_and(|c| c.is_alphanumeric() || *c == '_')
}

/// The paths a `use` tree names, braces expanded: `a::{b, c::{d, e}}` → `a::b`, `a::c::d`,
/// `a::c::e` (`self` in braces names the prefix; `as` renames are dropped).
fn expand_use(tree: &str) -> Vec<String> {
    let tree: String = tree.split_whitespace().collect::<Vec<_>>().join(" ");
    let mut out = Vec::new();
    expand_into("", &tree, &mut out);
    out
}

fn expand_into(prefix: &str, tree: &str, out: &mut Vec<String>) {
    let tree = tree.trim();
    if tree.is_empty() {
        return;
    }
    if let Some(open) = tree.find('{') {
        let head = tree[..open].trim().trim_end_matches("::");
        let inner = &tree[open + 1..tree.rfind('}').unwrap_or(tree.len())];
        let base = join(prefix, head);
        for part in split_top_level(inner) {
            if part.trim() == "self" {
                out.push(base.clone());
            } else {
                expand_into(&base, part, out);
            }
        }
    } else {
        let path = tree.split(" as ").next().unwrap_or(tree).trim();
        out.push(join(prefix, path));
    }
}

fn join(a: &str, b: &str) -> String {
    match (a.is_empty(), b.is_empty()) {
        (true, _) => b.to_string(),
        (_, true) => a.to_string(),
        _ => format!("{a}::{b}"),
    }
}

fn split_top_level(s: &str) -> Vec<&str> {
    let mut parts = Vec::new();
    let (mut depth, mut start) = (0, 0);
    for (k, c) in s.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                parts.push(&s[start..k]);
                start = k + 1;
            }
            _ => {}
        }
    }
    parts.push(&s[start..]);
    parts
}

/// Where each path is named in a file: the inline module it is in (relative to the file's
/// module) and the path as written (starting with `crate`, `super` or `self`).
struct Mention {
    inline: Vec<String>,
    path: String,
}

/// The inline modules a file declares (relative paths) and the crate-relative paths it names.
fn scan(code: &str) -> (Vec<Vec<String>>, Vec<Mention>) {
    let chars: Vec<char> = code.chars().collect();
    let mut inline_decls = Vec::new();
    let mut mentions = Vec::new();
    // Open braces: Some(name) for an inline module's.
    let mut stack: Vec<Option<String>> = Vec::new();
    let current =
        |stack: &Vec<Option<String>>| -> Vec<String> { stack.iter().flatten().cloned().collect() };
    let word_at = |i: usize| -> Option<(String, usize)> {
        if ident_char(i.checked_sub(1).and_then(|k| chars.get(k))) {
            return None;
        }
        let end = (i..chars.len())
            .find(|&k| !ident_char(chars.get(k)))
            .unwrap_or(chars.len());
        (end > i).then(|| (chars[i..end].iter().collect(), end))
    };
    let skip_ws = |mut k: usize| {
        while chars.get(k).is_some_and(|c| c.is_whitespace()) {
            k += 1;
        }
        k
    };
    let mut i = 0;
    while i < chars.len() {
        match chars[i] {
            '{' => {
                stack.push(None);
                i += 1;
                continue;
            }
            '}' => {
                stack.pop();
                i += 1;
                continue;
            }
            _ => {}
        }
        let Some((word, end)) = word_at(i) else {
            i += 1;
            continue;
        };
        match word.as_str() {
            "mod" => {
                let k = skip_ws(end);
                if let Some((name, after)) = word_at(k) {
                    let k = skip_ws(after);
                    if chars.get(k) == Some(&'{') {
                        let mut path = current(&stack);
                        path.push(name.clone());
                        inline_decls.push(path);
                        stack.push(Some(name));
                        i = k + 1;
                        continue;
                    }
                }
                i = end;
            }
            "use" => {
                let stop = (end..chars.len())
                    .find(|&k| chars[k] == ';')
                    .unwrap_or(chars.len());
                let tree: String = chars[end..stop].iter().collect();
                for path in expand_use(&tree) {
                    let first = path.split("::").next().unwrap_or("");
                    if matches!(first, "crate" | "super" | "self") {
                        mentions.push(Mention {
                            inline: current(&stack),
                            path,
                        });
                    }
                }
                i = stop;
            }
            "crate" | "super" | "self"
                if chars.get(end) == Some(&':') && chars.get(end + 1) == Some(&':') =>
            {
                // A path in code: crate::a::b, super::super::x (visibility `pub(in crate::x)`
                // is not followed by `::` after `in`, so it is read as a path too: harmless, it
                // names an ancestor).
                let mut k = end;
                while chars.get(k) == Some(&':') && chars.get(k + 1) == Some(&':') {
                    match word_at(k + 2) {
                        Some((_, e)) => k = e,
                        None => break,
                    }
                }
                let path: String = chars[i..k].iter().collect();
                mentions.push(Mention {
                    inline: current(&stack),
                    path,
                });
                i = k;
            }
            _ => i = end,
        }
    }
    (inline_decls, mentions)
}

impl Graph {
    /// The graph of the files `(module path, source text)` of one crate.
    pub fn from_files(files: &[(String, String)]) -> Graph {
        // Every module (file or inline) → the file module that holds it.
        let mut holder: BTreeMap<Vec<String>, String> = BTreeMap::new();
        let split = |m: &str| -> Vec<String> {
            if m.is_empty() {
                Vec::new()
            } else {
                m.split("::").map(String::from).collect()
            }
        };
        let scanned: Vec<(Vec<String>, Vec<Mention>)> = files
            .iter()
            .map(|(module, text)| {
                let base = split(module);
                holder.insert(base.clone(), module.clone());
                let (inline, mentions) = scan(&code_only(text));
                for rel in inline {
                    let mut full = base.clone();
                    full.extend(rel);
                    holder.entry(full).or_insert_with(|| module.clone());
                }
                (base, mentions)
            })
            .collect();
        let mut graph = Graph::default();
        for ((module, _), (base, mentions)) in files.iter().zip(&scanned) {
            let from = graph.edges.entry(module.clone()).or_default();
            for m in mentions {
                let mut here = base.clone();
                here.extend(m.inline.iter().cloned());
                let mut segs = m.path.split("::").peekable();
                let mut target: Vec<String> = match segs.peek().copied() {
                    Some("crate") => {
                        segs.next();
                        Vec::new()
                    }
                    _ => here.clone(),
                };
                for s in segs {
                    match s {
                        "self" => {}
                        "super" => {
                            target.pop();
                        }
                        "*" => {}
                        name => target.push(name.to_string()),
                    }
                }
                // The longest module prefix of the path: the file that defines it.
                let to = (0..=target.len())
                    .rev()
                    .find_map(|n| holder.get(&target[..n]))
                    .cloned()
                    .unwrap_or_default();
                let inside = |a: &str, b: &str| a.is_empty() || b.starts_with(&format!("{a}::"));
                if to != *module && !inside(module, &to) {
                    from.insert(to);
                }
            }
        }
        graph
    }

    /// The graph of the crate whose sources are under `src` (every `*.rs` but `src/bin/`).
    pub fn of_crate(src: &Path) -> std::io::Result<Graph> {
        Ok(Graph::from_files(&module_files(src)?))
    }

    /// Every cycle, one per strongly connected set of modules: a closed path through it,
    /// starting at its first module in name order (`a → b → a` is `["a", "b"]`).
    pub fn cycles(&self) -> Vec<Vec<String>> {
        let mut cycles = Vec::new();
        for component in self.components() {
            if component.len() < 2 {
                continue;
            }
            let start = component.iter().min().expect("not empty").clone();
            cycles.push(self.path_back(&start, &component));
        }
        cycles.sort();
        cycles
    }

    /// Strongly connected components (Kosaraju: the reversed graph in the order of finishing).
    fn components(&self) -> Vec<BTreeSet<String>> {
        let nodes: BTreeSet<&String> = self
            .edges
            .iter()
            .flat_map(|(a, bs)| std::iter::once(a).chain(bs))
            .collect();
        let mut order = Vec::new();
        let mut seen = BTreeSet::new();
        for &n in &nodes {
            self.finish(n, &mut seen, &mut order);
        }
        let mut reverse: BTreeMap<&String, Vec<&String>> = BTreeMap::new();
        for (a, bs) in &self.edges {
            for b in bs {
                reverse.entry(b).or_default().push(a);
            }
        }
        let mut assigned = BTreeSet::new();
        let mut components = Vec::new();
        for n in order.into_iter().rev() {
            if assigned.contains(n) {
                continue;
            }
            let mut component = BTreeSet::new();
            let mut todo = vec![n];
            assigned.insert(n);
            while let Some(m) = todo.pop() {
                component.insert(m.clone());
                for &p in reverse.get(m).into_iter().flatten() {
                    if assigned.insert(p) {
                        todo.push(p);
                    }
                }
            }
            components.push(component);
        }
        components
    }

    fn finish<'a>(
        &'a self,
        n: &'a String,
        seen: &mut BTreeSet<&'a String>,
        order: &mut Vec<&'a String>,
    ) {
        if !seen.insert(n) {
            return;
        }
        // Iterative depth-first search: (node, its successors not yet visited).
        let mut stack: Vec<(&String, Vec<&String>)> = vec![(n, self.successors(n))];
        while let Some((node, next)) = stack.last_mut() {
            match next.pop() {
                Some(m) if seen.insert(m) => {
                    let succ = self.successors(m);
                    stack.push((m, succ));
                }
                Some(_) => {}
                None => {
                    order.push(node);
                    stack.pop();
                }
            }
        }
    }

    fn successors(&self, n: &String) -> Vec<&String> {
        let mut v: Vec<&String> = self.edges.get(n).into_iter().flatten().collect();
        v.reverse();
        v
    }

    /// The shortest path from `start` back to itself inside `component` (breadth first).
    fn path_back(&self, start: &String, component: &BTreeSet<String>) -> Vec<String> {
        let mut parent: BTreeMap<&String, &String> = BTreeMap::new();
        let mut queue = std::collections::VecDeque::from([start]);
        while let Some(n) = queue.pop_front() {
            for m in self.edges.get(n).into_iter().flatten() {
                if !component.contains(m) {
                    continue;
                }
                if m == start {
                    let mut path = vec![n.clone()];
                    let mut k = n;
                    while k != start {
                        k = parent[k];
                        path.push(k.clone());
                    }
                    path.reverse();
                    return path;
                }
                if m != start && !parent.contains_key(m) {
                    parent.insert(m, n);
                    queue.push_back(m);
                }
            }
        }
        component.iter().cloned().collect()
    }
}

/// Every module file of the crate whose sources are in `src`: (module path, text), in module
/// order ([`module_of`]).
pub fn module_files(src: &Path) -> std::io::Result<Vec<(String, String)>> {
    let mut files = Vec::new();
    collect(src, src, &mut files)?;
    files.sort();
    Ok(files)
}

fn collect(root: &Path, dir: &Path, out: &mut Vec<(String, String)>) -> std::io::Result<()> {
    for entry in std::fs::read_dir(dir)? {
        let path = entry?.path();
        if path.is_dir() {
            collect(root, &path, out)?;
        } else if path.extension().is_some_and(|e| e == "rs") {
            let relative = path.strip_prefix(root).expect("under the root");
            if let Some(module) = module_of(relative) {
                out.push((module, std::fs::read_to_string(&path)?));
            }
        }
    }
    Ok(())
}

impl Graph {
    /// The graph of the crate's top-level folders: each module stands for the top-level
    /// module it lies in (`core::phone::draw` → `core`); edges inside one folder and edges from
    /// or to the crate root (which declares every folder and, in a binary, calls into them) are
    /// left out. A cycle here is a back arrow between folders: `a` names something in `b` and
    /// `b` (or a folder it names) something in `a`.
    pub fn folders(&self) -> Graph {
        let top = |m: &str| m.split("::").next().unwrap_or("").to_string();
        let mut out = Graph::default();
        for (from, tos) in &self.edges {
            let a = top(from);
            for to in tos {
                let b = top(to);
                if !a.is_empty() && !b.is_empty() && a != b {
                    out.edges.entry(a.clone()).or_default().insert(b);
                }
            }
        }
        out
    }

    /// The top-level folders with an edge to `folder` in [`Graph::folders`]: who imports it.
    pub fn importers_of(&self, folder: &str) -> Vec<String> {
        self.folders()
            .edges
            .iter()
            .filter(|(_, tos)| tos.contains(folder))
            .map(|(from, _)| from.clone())
            .collect()
    }
}

/// A cycle as people read it: `a → b → a` (the crate root is `crate`).
pub fn describe(cycle: &[String]) -> String {
    let name = |m: &String| {
        if m.is_empty() {
            "crate".to_string()
        } else {
            m.clone()
        }
    };
    let mut parts: Vec<String> = cycle.iter().map(name).collect();
    if let Some(first) = cycle.first() {
        parts.push(name(first));
    }
    parts.join(" → ")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn files(list: &[(&str, &str)]) -> Vec<(String, String)> {
        list.iter()
            .map(|(m, t)| (m.to_string(), t.to_string()))
            .collect()
    }

    #[test]
    fn two_modules_that_import_each_other_are_a_cycle() {
        let g = Graph::from_files(&files(&[
            ("", "mod a;\nmod b;\n"),
            ("a", "use crate::b::THING;\npub const OTHER: u32 = 1;\n"),
            ("b", "use super::a::OTHER;\npub const THING: u32 = OTHER;\n"),
        ]));
        assert_eq!(g.cycles(), vec![vec!["a".to_string(), "b".to_string()]]);
        assert_eq!(describe(&g.cycles()[0]), "a → b → a");
    }

    #[test]
    fn a_one_way_import_is_no_cycle() {
        let g = Graph::from_files(&files(&[
            ("", "mod a;\nmod b;\n"),
            ("a", "use crate::b::THING;\n"),
            (
                "b",
                "pub const THING: u32 = 1;\n#[cfg(test)]\nmod tests {\n    use super::*;\n}\n",
            ),
        ]));
        assert_eq!(g.cycles(), Vec::<Vec<String>>::new());
        assert_eq!(g.edges["a"], BTreeSet::from(["b".to_string()]));
    }

    #[test]
    fn a_longer_cycle_through_paths_in_code_and_braces_is_found() {
        // a → b (a path in code), b → c (a use tree in braces), c → a (super::super).
        let g = Graph::from_files(&files(&[
            ("", "mod a;\nmod b;\nmod x;\n"),
            ("a", "fn f() -> u32 { crate::b::ONE }\n"),
            (
                "b",
                "use crate::{x::{c::TWO, self}};\npub const ONE: u32 = TWO;\n",
            ),
            ("x", "pub mod c;\n"),
            (
                "x::c",
                "pub const TWO: u32 = 2;\nfn g() { let _ = super::super::a::f(); }\n",
            ),
        ]));
        assert_eq!(g.cycles().len(), 1, "{:?}", g.edges);
        assert_eq!(describe(&g.cycles()[0]), "a → b → x::c → a");
    }

    #[test]
    fn parents_using_their_children_and_children_their_parent_are_no_cycle() {
        let g = Graph::from_files(&files(&[
            ("", "mod p;\n"),
            ("p", "mod child;\nuse child::helper;\npub struct Shared;\n"),
            ("p::child", "use super::Shared;\npub fn helper() {}\n"),
        ]));
        assert!(g.cycles().is_empty(), "{:?}", g.edges);
        assert_eq!(g.edges["p::child"], BTreeSet::from(["p".to_string()]));
    }

    #[test]
    fn comments_strings_and_inline_modules_are_read_as_rust_reads_them() {
        let g = Graph::from_files(&files(&[
            ("", "mod a;\nmod b;\n"),
            (
                "a",
                "// use crate::b::X;\n/* crate::b::Y */\nconst S: &str = \"crate::b::Z {\";\n\
                 const C: char = '{';\nmod inner {\n    use super::super::b::W;\n}\n",
            ),
            (
                "b",
                "pub mod deep { pub struct W; }\nfn f<'a>(x: &'a str) -> &'a str { x }\n",
            ),
        ]));
        // Only the inline module's `super::super::b` is an import; b's inline module `deep`
        // belongs to b.
        assert_eq!(g.edges["a"], BTreeSet::from(["b".to_string()]));
        assert!(g.cycles().is_empty());
    }

    #[test]
    fn folders_fold_modules_into_their_top_folder_and_find_back_arrows() {
        // core::phone → overlay::touch and overlay → core::scene: no module cycle, but a back
        // arrow between the folders core and overlay; cli is imported by desktop.
        let g = Graph::from_files(&files(&[
            (
                "",
                "mod core;\nmod overlay;\nmod cli;\nmod desktop;\nfn main() { cli::run(); }\n",
            ),
            ("core", "pub mod phone;\npub mod scene;\n"),
            ("core::phone", "use crate::overlay::touch::Touch;\n"),
            ("core::scene", "pub struct Scene;\n"),
            (
                "overlay",
                "pub mod touch;\nuse crate::core::scene::Scene;\n",
            ),
            ("overlay::touch", "pub struct Touch;\n"),
            ("cli", "pub fn run() { crate::desktop::go(); }\n"),
            ("desktop", "pub fn go() {}\nuse crate::cli::run;\n"),
        ]));
        assert!(
            g.cycles().iter().all(|c| !c.contains(&"core".to_string())),
            "{:?}",
            g.cycles()
        );
        let folders = g.folders();
        let cycles: Vec<String> = folders.cycles().iter().map(|c| describe(c)).collect();
        assert!(
            cycles.contains(&"core → overlay → core".to_string()),
            "{cycles:?}"
        );
        assert_eq!(g.importers_of("cli"), vec!["desktop".to_string()]);
        assert!(
            !folders.edges.contains_key(""),
            "the root's own calls are left out"
        );
    }

    #[test]
    fn module_paths_follow_the_file_layout() {
        let m = |p: &str| module_of(Path::new(p));
        assert_eq!(m("lib.rs").as_deref(), Some(""));
        assert_eq!(m("main.rs").as_deref(), Some(""));
        assert_eq!(m("a.rs").as_deref(), Some("a"));
        assert_eq!(m("a/mod.rs").as_deref(), Some("a"));
        assert_eq!(m("a/b.rs").as_deref(), Some("a::b"));
        assert_eq!(m("bin/tool.rs"), None);
    }
}
