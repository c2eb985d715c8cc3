//! Which module of src/ names which: the module tree as `mod` declares it (`#[path]` and
//! `#[cfg(test)]` heeded, inline modules too), every path in code resolved to the module it
//! names (through `use` aliases and re-exports, and `use super::*`), and from that the edges
//! between sibling modules of each folder, each with a file and line that makes it. A method
//! call names no module: a type's `impl` spread over files shows only where the type is named.

use std::collections::{BTreeMap, BTreeSet, VecDeque};
use std::path::{Path, PathBuf};

/// A module's path from the crate root (`["render", "pipelines"]`); the root is empty.
pub type ModPath = Vec<String>;

#[derive(Debug, Clone, PartialEq)]
enum Tok {
    Ident(String),
    Str(String),
    Punct(&'static str),
}

/// Rust source as identifiers, string literals and punctuation with their lines; comments,
/// numbers, characters and lifetimes dropped.
fn tokens(text: &str) -> Vec<(Tok, usize)> {
    let chars: Vec<char> = text.chars().collect();
    let (mut out, mut i, mut line) = (Vec::new(), 0, 1);
    let at = |i: usize| chars.get(i).copied().unwrap_or('\0');
    while i < chars.len() {
        let c = chars[i];
        if c == '\n' {
            line += 1;
            i += 1;
        } else if c.is_whitespace() {
            i += 1;
        } else if c == '/' && at(i + 1) == '/' {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && at(i + 1) == '*' {
            let mut depth = 0;
            while i < chars.len() {
                if chars[i] == '/' && at(i + 1) == '*' {
                    depth += 1;
                    i += 2;
                } else if chars[i] == '*' && at(i + 1) == '/' {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    line += usize::from(chars[i] == '\n');
                    i += 1;
                }
            }
        } else if c.is_alphanumeric() || c == '_' {
            let start = i;
            while at(i).is_alphanumeric() || at(i) == '_' {
                i += 1;
            }
            let word: String = chars[start..i].iter().collect();
            let raw = matches!(word.as_str(), "r" | "br" | "cr") && matches!(at(i), '"' | '#');
            if raw || (matches!(word.as_str(), "b" | "c") && at(i) == '"') {
                let hashes = (i..).take_while(|&j| at(j) == '#').count();
                i += hashes + 1;
                let start = i;
                loop {
                    if i >= chars.len() {
                        break;
                    }
                    if !raw && chars[i] == '\\' {
                        i += 2;
                        continue;
                    }
                    if chars[i] == '"' && (0..hashes).all(|h| at(i + 1 + h) == '#') {
                        break;
                    }
                    line += usize::from(chars[i] == '\n');
                    i += 1;
                }
                out.push((Tok::Str(chars[start..i.min(chars.len())].iter().collect()), line));
                i += hashes + 1;
            } else if (c.is_alphabetic() || c == '_') && !(word == "b" && at(i) == '\'') {
                out.push((Tok::Ident(word), line));
            }
        } else if c == '"' {
            let start = i + 1;
            i += 1;
            while i < chars.len() && chars[i] != '"' {
                line += usize::from(chars[i] == '\n');
                i += if chars[i] == '\\' { 2 } else { 1 };
            }
            out.push((Tok::Str(chars[start..i.min(chars.len())].iter().collect()), line));
            i += 1;
        } else if c == '\'' {
            // A character literal ('x', '\n'), else a lifetime or label, whose name is no path.
            if at(i + 1) == '\\' {
                i += 3;
                while i < chars.len() && chars[i] != '\'' {
                    i += 1;
                }
                i += 1;
            } else if at(i + 2) == '\'' {
                i += 3;
            } else {
                i += 1;
                while at(i).is_alphanumeric() || at(i) == '_' {
                    i += 1;
                }
            }
        } else if c == ':' && at(i + 1) == ':' {
            out.push((Tok::Punct("::"), line));
            i += 2;
        } else {
            const PUNCT: [&str; 11] = ["{", "}", "(", ")", "[", "]", ";", ",", "#", "*", "."];
            let p = PUNCT.iter().find(|p| p.starts_with(c)).copied().unwrap_or("other");
            out.push((Tok::Punct(p), line));
            i += 1;
        }
    }
    out
}

fn ident(toks: &[(Tok, usize)], i: usize) -> Option<&str> {
    match toks.get(i) {
        Some((Tok::Ident(s), _)) => Some(s),
        _ => None,
    }
}

fn punct(toks: &[(Tok, usize)], i: usize, p: &str) -> bool {
    matches!(toks.get(i), Some((Tok::Punct(q), _)) if *q == p)
}

/// The attributes just before token `i` (its visibility skipped), each as its tokens.
fn attributes_before(toks: &[(Tok, usize)], mut i: usize) -> Vec<&[(Tok, usize)]> {
    let visibility = ["pub", "crate", "super", "self", "in", "(", ")", "::"];
    while i > 0 && visibility.iter().any(|v| ident(toks, i - 1) == Some(v) || punct(toks, i - 1, v)) {
        i -= 1;
    }
    let mut attrs = Vec::new();
    while i > 0 && punct(toks, i - 1, "]") {
        let end = i - 1;
        let mut depth = 0;
        let mut j = end;
        loop {
            if punct(toks, j, "]") {
                depth += 1;
            } else if punct(toks, j, "[") {
                depth -= 1;
                if depth == 0 {
                    break;
                }
            }
            j -= 1;
        }
        attrs.push(&toks[j + 1..end]);
        i = j.saturating_sub(1);
    }
    attrs
}

fn is_test_cfg(attr: &[(Tok, usize)]) -> bool {
    let words: Vec<&str> = attr
        .iter()
        .filter_map(|(t, _)| if let Tok::Ident(s) = t { Some(s.as_str()) } else { None })
        .collect();
    words.first() == Some(&"cfg") && words.contains(&"test") && !words.contains(&"not")
}

/// A path as written, where it was written: `path` is where it leads from its module before
/// any alias is followed (a path without `crate`, `super` or `self` is taken as relative).
struct Reference {
    module: ModPath,
    path: ModPath,
    file: PathBuf,
    line: usize,
}

#[derive(Default)]
pub struct Graph {
    modules: BTreeSet<ModPath>,
    /// Per module, what its `use` declarations bring in: name -> path.
    imports: BTreeMap<ModPath, BTreeMap<String, ModPath>>,
    /// Per module, the modules it imports everything of (`use super::*`).
    globs: BTreeMap<ModPath, Vec<ModPath>>,
    references: Vec<Reference>,
}

/// Where `segments` leads from `module`: from the root after `crate`, up after `super`, and
/// from `module` itself otherwise.
fn anchored(module: &[String], segments: &[String]) -> ModPath {
    let mut at: ModPath = module.to_vec();
    let mut rest = segments;
    if rest.first().is_some_and(|s| s == "crate") {
        at.clear();
        rest = &rest[1..];
    } else if rest.first().is_some_and(|s| s == "self") {
        rest = &rest[1..];
    }
    while rest.first().is_some_and(|s| s == "super") {
        at.pop();
        rest = &rest[1..];
    }
    at.extend(rest.iter().cloned());
    at
}

impl Graph {
    /// The crate whose root is `lib`, its test modules left out.
    pub fn of_crate(lib: &Path) -> Graph {
        let mut graph = Graph::default();
        graph.modules.insert(Vec::new());
        graph.read_file(lib, Vec::new(), lib.parent().expect("a folder").to_path_buf());
        graph
    }

    /// Reads the module `module` from `file`, whose children's files lie in `children`.
    fn read_file(&mut self, file: &Path, module: ModPath, children: PathBuf) {
        let text = std::fs::read_to_string(file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        let toks = tokens(&text);
        let here = file.parent().expect("a folder").to_path_buf();
        // Inline modules open at this brace depth: (depth, module, is test code).
        let mut stack: Vec<(usize, ModPath, bool)> = vec![(0, module, false)];
        let mut depth = 0;
        let mut i = 0;
        while i < toks.len() {
            let (current, in_test) = {
                let top = stack.last().expect("the file's module");
                (top.1.clone(), top.2)
            };
            let after_colons = i > 0 && (punct(&toks, i - 1, "::") || punct(&toks, i - 1, "."));
            match (&toks[i].0, ident(&toks, i + 1)) {
                (Tok::Punct("{"), _) => depth += 1,
                (Tok::Punct("}"), _) => {
                    depth -= 1;
                    if stack.len() > 1 && stack.last().expect("open").0 == depth {
                        stack.pop();
                    }
                }
                (Tok::Ident(m), Some(name)) if m == "mod" && !after_colons => {
                    let attrs = attributes_before(&toks, i);
                    let test = in_test || attrs.iter().any(|a| is_test_cfg(a));
                    let mut child = current.clone();
                    child.push(name.to_string());
                    self.modules.insert(child.clone());
                    if punct(&toks, i + 2, "{") {
                        stack.push((depth, child, test));
                    } else if !test {
                        let path_attr = attrs.iter().find_map(|a| match (ident(a, 0), a.get(2)) {
                            (Some("path"), Some((Tok::Str(p), _))) => Some(p.clone()),
                            _ => None,
                        });
                        let (own, inner) = match path_attr {
                            Some(p) => (here.join(&p), here.join(p.trim_end_matches(".rs"))),
                            None if children.join(format!("{name}.rs")).is_file() => {
                                (children.join(format!("{name}.rs")), children.join(name))
                            }
                            None => (children.join(name).join("mod.rs"), children.join(name)),
                        };
                        self.read_file(&own, child, inner);
                    }
                    i += 1;
                }
                // A declaration, not the capture list of `impl Trait + use<'a>`.
                (Tok::Ident(u), Some(_)) if u == "use" && !after_colons => {
                    let end = (i..toks.len()).find(|&j| punct(&toks, j, ";")).unwrap_or(toks.len());
                    if !in_test {
                        let mut out = Vec::new();
                        use_tree(&toks[i + 1..end], &mut Vec::new(), &mut out);
                        for (segments, name, line) in out {
                            let path = anchored(&current, &segments);
                            match name {
                                Some(name) => {
                                    let names = self.imports.entry(current.clone()).or_default();
                                    names.insert(name, path.clone());
                                }
                                None => self.globs.entry(current.clone()).or_default().push(path.clone()),
                            }
                            let (module, file) = (current.clone(), file.to_path_buf());
                            self.references.push(Reference { module, path, file, line });
                        }
                    }
                    i = end;
                }
                (Tok::Ident(word), _) if !after_colons && !in_test => {
                    let mut segments = vec![word.clone()];
                    let mut j = i;
                    while punct(&toks, j + 1, "::") && ident(&toks, j + 2).is_some() {
                        segments.push(ident(&toks, j + 2).expect("a name").to_string());
                        j += 2;
                    }
                    let path = anchored(&current, &segments);
                    let (module, file, line) = (current.clone(), file.to_path_buf(), toks[i].1);
                    self.references.push(Reference { module, path, file, line });
                    i = j;
                }
                _ => {}
            }
            i += 1;
        }
    }

    /// Follows `use` aliases, re-exports and `use ...::*` until the path names where its item
    /// is defined.
    fn resolve(&self, mut path: ModPath) -> ModPath {
        for _ in 0..32 {
            let step = (0..path.len()).find_map(|k| {
                let (owner, name, more) = (&path[..k], &path[k], k + 1 < path.len());
                if !self.modules.contains(owner) || self.modules.contains(&path[..=k]) {
                    return None;
                }
                if let Some(target) = self.imports.get(owner).and_then(|m| m.get(name)) {
                    return Some([target.as_slice(), &path[k + 1..]].concat());
                }
                // Through a glob, a module only when a path goes on: a bare name like it is
                // more likely a variable.
                let glob = self.globs.get(owner)?.iter().find(|glob| {
                    self.imports.get(*glob).is_some_and(|m| m.contains_key(name))
                        || (more && self.modules.contains(&[glob.as_slice(), &path[k..=k]].concat()))
                })?;
                Some([glob.as_slice(), &path[k..]].concat())
            });
            match step {
                Some(next) if next != path => path = next,
                _ => break,
            }
        }
        path
    }

    /// Per folder (a module with children), its sibling edges: from -> to -> (file, line).
    pub fn sibling_edges(&self) -> BTreeMap<ModPath, Edges> {
        let mut out: BTreeMap<ModPath, Edges> = BTreeMap::new();
        for r in &self.references {
            let target = self.resolve(r.path.clone());
            let k = r.module.iter().zip(&target).take_while(|(a, b)| a == b).count();
            if k >= r.module.len() || k >= target.len() || !self.modules.contains(&target[..=k]) {
                continue;
            }
            let site = format!("{}:{}", r.file.display(), r.line);
            let edge = out.entry(target[..k].to_vec()).or_default();
            edge.entry(r.module[k].clone()).or_default().entry(target[k].clone()).or_insert(site);
        }
        out
    }
}

/// The leaves of a `use` tree: (path, the name it binds or `None` for a glob, line).
fn use_tree(
    toks: &[(Tok, usize)],
    prefix: &mut Vec<String>,
    out: &mut Vec<(Vec<String>, Option<String>, usize)>,
) {
    let mut i = 0;
    let depth_at = prefix.len();
    while i < toks.len() {
        match &toks[i].0 {
            Tok::Ident(s) if s == "as" => {
                if let (Some(last), Some(alias)) = (out.last_mut(), ident(toks, i + 1)) {
                    last.1 = Some(alias.to_string());
                }
                i += 1;
            }
            Tok::Ident(s) if s == "self" && !prefix.is_empty() => {
                out.push((prefix.clone(), prefix.last().cloned(), toks[i].1));
            }
            Tok::Ident(s) => {
                prefix.push(s.clone());
                if !punct(toks, i + 1, "::") {
                    out.push((prefix.clone(), Some(s.clone()), toks[i].1));
                }
            }
            Tok::Punct("*") => out.push((prefix.clone(), None, toks[i].1)),
            Tok::Punct("{") => {
                let mut depth = 0;
                let end = (i..toks.len())
                    .find(|&j| {
                        depth += i32::from(punct(toks, j, "{")) - i32::from(punct(toks, j, "}"));
                        depth == 0
                    })
                    .unwrap_or(toks.len());
                use_tree(&toks[i + 1..end], prefix, out);
                i = end;
            }
            Tok::Punct(",") => prefix.truncate(depth_at),
            _ => {}
        }
        i += 1;
    }
    prefix.truncate(depth_at);
}

/// Sibling -> siblings it names -> the first place it names each.
pub type Edges = BTreeMap<String, BTreeMap<String, String>>;

/// The circles among one folder's siblings: per module on a circle, the shortest circle
/// through it, each once.
pub fn circles(edges: &Edges) -> Vec<Vec<String>> {
    let mut found: Vec<Vec<String>> = Vec::new();
    for start in edges.keys() {
        // Breadth-first from `start`'s successors back to `start`.
        let mut came_from: BTreeMap<&String, &String> = BTreeMap::new();
        let mut queue: VecDeque<&String> = VecDeque::from([start]);
        'search: while let Some(at) = queue.pop_front() {
            for next in edges.get(at).into_iter().flat_map(|m| m.keys()) {
                if next == start {
                    let mut circle = vec![at.clone()];
                    while circle.last() != Some(start) {
                        circle.push(came_from[circle.last().expect("a step")].clone());
                    }
                    circle.reverse();
                    // Begin at its least name, so that the same circle found twice compares equal.
                    let least = circle.iter().enumerate().min_by_key(|(_, m)| *m).expect("a module").0;
                    circle.rotate_left(least);
                    if !found.contains(&circle) {
                        found.push(circle);
                    }
                    break 'search;
                }
                if next != start && !came_from.contains_key(next) {
                    came_from.insert(next, at);
                    queue.push_back(next);
                }
            }
        }
    }
    found
}
