//! Picks the framework's files among a submission's paths, wherever the student put them.
//!
//! Paths are '/'-separated and relative. The phongFragment.glsl is picked first; the other
//! files are then taken from the same homework root where the student has them there.
//! Folders are listed here too, without following symlinks and within the limits.

use std::cmp::Reverse;
use std::fs;
use std::path::{Path, PathBuf};

use super::{Limits, SubmissionError};

/// The framework files a submission may hold, in the order `Picked::files` uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kind {
    PhongFragment,
    PhongVertex,
    ShadowFragment,
    ShadowVertex,
    Light,
    Engine,
}

impl Kind {
    pub(super) const ALL: [Kind; 6] = [
        Kind::PhongFragment,
        Kind::PhongVertex,
        Kind::ShadowFragment,
        Kind::ShadowVertex,
        Kind::Light,
        Kind::Engine,
    ];

    pub(super) fn file_name(self) -> &'static str {
        match self {
            Kind::PhongFragment => "phongFragment.glsl",
            Kind::PhongVertex => "phongVertex.glsl",
            Kind::ShadowFragment => "shadowFragment.glsl",
            Kind::ShadowVertex => "shadowVertex.glsl",
            Kind::Light => "DirectionalLight.js",
            Kind::Engine => "engine.js",
        }
    }

    /// The folder the framework keeps this file in.
    fn parent(self) -> &'static str {
        match self {
            Kind::PhongFragment | Kind::PhongVertex => "phongShader",
            Kind::ShadowFragment | Kind::ShadowVertex => "shadowShader",
            Kind::Light => "lights",
            Kind::Engine => "src",
        }
    }

    /// Which framework file a file name is, ignoring case (students' tools and OSes vary).
    pub(super) fn of(file_name: &str) -> Option<Kind> {
        Kind::ALL.into_iter().find(|k| k.file_name().eq_ignore_ascii_case(file_name))
    }

    /// Which framework file `path` is among the submission's `paths`: by its name, or a shader
    /// the student renamed (`phongShader/phong.frag`, loaded by that name from their loadOBJ.js):
    /// the only `.frag` (`.vert`) in the framework's folder for it, where no file of the
    /// framework's name is in the submission.
    fn of_path(path: &str, paths: &[String]) -> Option<Kind> {
        let (dir, name) = path.rsplit_once('/').unwrap_or(("", path));
        if let Some(kind) = Kind::of(name) {
            return Some(kind);
        }
        let lower = name.to_lowercase();
        let extension = [".frag", ".vert"].into_iter().find(|e| lower.ends_with(e))?;
        let folder = dir.rsplit('/').next().unwrap_or(dir);
        let kind = match (extension, folder.to_lowercase().as_str()) {
            (".frag", "phongshader") => Kind::PhongFragment,
            (".vert", "phongshader") => Kind::PhongVertex,
            (".frag", "shadowshader") => Kind::ShadowFragment,
            (".vert", "shadowshader") => Kind::ShadowVertex,
            _ => return None,
        };
        let named = paths.iter().any(|p| p.rsplit('/').next().and_then(Kind::of) == Some(kind));
        let siblings = paths
            .iter()
            .filter(|p| {
                p.rsplit_once('/').is_some_and(|(d, n)| d == dir && n.to_lowercase().ends_with(extension))
            })
            .count();
        (!named && siblings == 1).then_some(kind)
    }
}

/// Why a path is never looked at, if it is one of those: tool folders and macOS metadata.
pub(super) fn skip_reason(path: &str) -> Option<&'static str> {
    let mut parts = path.split('/').peekable();
    while let Some(part) = parts.next() {
        let is_last = parts.peek().is_none();
        if !is_last && let Some(why) = skipped_folder(part) {
            return Some(why);
        }
        if is_last && part.starts_with("._") {
            return Some("macOS metadata");
        }
    }
    None
}

/// Why a folder is never walked, if it is one of those.
pub(super) fn skipped_folder(name: &str) -> Option<&'static str> {
    if name.eq_ignore_ascii_case(".git") {
        Some("version control")
    } else if name.eq_ignore_ascii_case("node_modules") {
        Some("installed packages")
    } else if name.eq_ignore_ascii_case("__MACOSX") {
        Some("macOS metadata")
    } else {
        None
    }
}

/// Words that name a homework when followed by its number ("homework1", "HW_2", "作业1", "A1").
const HOMEWORK_WORDS: [&str; 6] = ["homework", "assignment", "作业", "lab", "hw", "a"];

/// Whether a folder name names homework 1 (Some(true)), another homework (Some(false)), or none.
fn homework_tag(folder: &str) -> Option<bool> {
    let chars: Vec<char> = folder.to_lowercase().chars().collect();
    let words: Vec<Vec<char>> = HOMEWORK_WORDS.iter().map(|w| w.chars().collect()).collect();
    let mut tag = None;
    for start in 0..chars.len() {
        // "data1" must not read as "a1": the word has to start the name or follow a non-letter.
        let follows_letter =
            start.checked_sub(1).and_then(|i| chars.get(i)).is_some_and(|c| c.is_ascii_alphabetic());
        if follows_letter {
            continue;
        }
        let rest = chars.get(start..).unwrap_or_default();
        for word in words.iter().filter(|w| rest.starts_with(w)) {
            let after = rest.get(word.len()..).unwrap_or_default();
            let after = after.iter().skip_while(|c| matches!(c, ' ' | '_' | '-' | '.'));
            let digits: String = after.take_while(|c| c.is_ascii_digit()).collect();
            if !digits.is_empty() {
                tag = Some(digits.trim_start_matches('0') == "1");
            }
        }
    }
    tag
}

/// Words for a folder of spare copies, matched as whole words with any trailing digits dropped.
const SPARE_WORDS: [&str; 12] = [
    "backup",
    "bak",
    "old",
    "odd",
    "copy",
    "test",
    "tests",
    "tmp",
    "temp",
    "deprecated",
    "unused",
    "archive",
];

/// Whether a folder looks like it holds spare copies ("backup", "src_old", "shaders - Copy").
fn is_spare(folder: &str) -> bool {
    let lower = folder.to_lowercase();
    lower.contains("副本")
        || lower.contains("备份")
        || lower
            .split(|c: char| !c.is_alphanumeric())
            .map(|word| word.trim_end_matches(|c: char| c.is_ascii_digit()))
            .any(|word| SPARE_WORDS.contains(&word))
}

/// A candidate's standing; lower sorts first and wins.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct Rank {
    /// How many of the chosen phongFragment's homework-root folders it shares (others only).
    near: Reverse<usize>,
    /// 0: names homework 1; 1: names no homework; 2: names another homework. Before the folder
    /// layout: a flat `hw1/` beats a framework-shaped `hw2/`.
    homework: u8,
    off_parent: bool,
    spare: bool,
    depth: usize,
    path: String,
}

fn folders(path: &str) -> Vec<&str> {
    let mut parts: Vec<&str> = path.split('/').collect();
    parts.pop();
    parts
}

fn rank(kind: Kind, path: &str, root: &[&str]) -> Rank {
    let dirs = folders(path);
    let near = dirs.iter().zip(root).take_while(|(a, b)| a == b).count();
    let homework = match dirs.iter().rev().find_map(|d| homework_tag(d)) {
        Some(true) => 0,
        None => 1,
        Some(false) => 2,
    };
    Rank {
        near: Reverse(near),
        off_parent: !dirs.last().is_some_and(|d| d.eq_ignore_ascii_case(kind.parent())),
        homework,
        spare: dirs.iter().any(|d| is_spare(d)),
        depth: dirs.len(),
        path: path.to_owned(),
    }
}

/// Why `lost` ranks below the chosen candidate, said of `lost`.
fn reason(kind: Kind, won: &Rank, lost: &Rank) -> String {
    if won.path == lost.path {
        "a second entry of the same name".to_owned()
    } else if won.near != lost.near {
        "farther from the chosen phongFragment.glsl".to_owned()
    } else if won.homework != lost.homework {
        if lost.homework == 2 { "names another homework" } else { "does not name homework 1" }.to_owned()
    } else if won.off_parent != lost.off_parent {
        format!("not in {}/", kind.parent())
    } else if won.spare != lost.spare {
        "in a backup-like folder".to_owned()
    } else if won.depth != lost.depth {
        "deeper".to_owned()
    } else {
        "sorts later".to_owned()
    }
}

/// At most this many passed-over candidates are named in a note.
const NAMED_IN_NOTE: usize = 5;

/// The best candidate of `kind` among `paths`, with a note when there were several.
fn choose(kind: Kind, paths: &[String], root: &[&str]) -> (Option<usize>, Option<String>) {
    let mut ranked: Vec<(Rank, usize)> = paths
        .iter()
        .enumerate()
        .filter(|(_, p)| Kind::of_path(p, paths) == Some(kind))
        .map(|(i, p)| (rank(kind, p, root), i))
        .collect();
    ranked.sort();
    let mut ranked = ranked.into_iter();
    let Some((best, index)) = ranked.next() else {
        return (None, None);
    };
    let passed: Vec<Rank> = ranked.map(|(r, _)| r).collect();
    if passed.is_empty() {
        return (Some(index), None);
    }
    let mut note = format!("{}: chose {} over ", kind.file_name(), best.path);
    let named: Vec<String> = passed
        .iter()
        .take(NAMED_IN_NOTE)
        .map(|lost| format!("{} ({})", lost.path, reason(kind, &best, lost)))
        .collect();
    note.push_str(&named.join(", "));
    if let Some(more) = passed.len().checked_sub(NAMED_IN_NOTE).filter(|&n| n > 0) {
        note.push_str(&format!(" and {more} more"));
    }
    (Some(index), Some(note))
}

/// The top folders of the phongFragment.glsl files that rank level with the best one, told apart
/// only by their order: two or more is a class of homeworks side by side (`alice/`, `bob/`), not
/// one homework with spare copies (a backup, another homework's folder, a deeper copy rank lower).
pub(super) fn level_homeworks(paths: &[String]) -> Vec<String> {
    let mut ranked: Vec<Rank> = paths
        .iter()
        .filter(|p| Kind::of_path(p, paths) == Some(Kind::PhongFragment))
        .map(|p| rank(Kind::PhongFragment, p, &[]))
        .collect();
    ranked.sort();
    let Some(best) = ranked.first() else { return Vec::new() };
    let level = |r: &Rank| {
        (r.near, r.homework, r.off_parent, r.spare, r.depth)
            == (best.near, best.homework, best.off_parent, best.spare, best.depth)
    };
    let mut tops: Vec<String> = Vec::new();
    for r in ranked.iter().filter(|r| level(r)) {
        let top = r.path.split('/').next().unwrap_or_default().to_owned();
        if r.path.contains('/') && !tops.contains(&top) {
            tops.push(top);
        }
    }
    tops
}

/// The picked files, as indices into the paths given to `pick`, in `Kind::ALL` order.
#[derive(Debug)]
pub(super) struct Picked {
    pub phong_fragment: usize,
    pub others: [Option<usize>; 5],
    pub notes: Vec<String>,
}

/// Picks a phongFragment.glsl (None when there is none) and the other files beside it.
pub(super) fn pick(paths: &[String]) -> Option<Picked> {
    let mut notes = Vec::new();
    let (phong, note) = choose(Kind::PhongFragment, paths, &[]);
    let phong = phong?;
    notes.extend(note);
    let phong_path = paths.get(phong).map_or("", String::as_str);
    let root = homework_root(phong_path);
    let mut others = [None; 5];
    for (slot, kind) in others.iter_mut().zip(Kind::ALL.into_iter().skip(1)) {
        let (index, note) = choose(kind, paths, &root);
        *slot = index;
        notes.extend(note);
    }
    for (kind, index) in
        std::iter::once((Kind::PhongFragment, Some(phong))).chain(Kind::ALL.into_iter().skip(1).zip(others))
    {
        let path = index.and_then(|i| paths.get(i)).map_or("", String::as_str);
        let name = path.rsplit('/').next().unwrap_or(path);
        if !path.is_empty() && Kind::of(name).is_none() {
            notes.push(format!(
                "read {path} as the {}: the only shader of its kind in its {}/, and no file of the framework's name",
                kind.file_name(),
                kind.parent()
            ));
        }
    }
    Some(Picked { phong_fragment: phong, others, notes })
}

/// Most files of a page kept for running it.
pub(super) const MAX_PAGE_FILES: usize = 400;

/// The rest of the student's page beside the chosen engine.js: every script and shader under its
/// folder, and the `index.html` in the folder above (where the framework keeps it). Indices into
/// `paths`, in path order; the second value counts the files left out over `MAX_PAGE_FILES`.
pub(super) fn page_files(paths: &[String], engine: usize) -> (Vec<usize>, usize) {
    let Some(engine_path) = paths.get(engine) else { return (Vec::new(), 0) };
    let src = engine_path.rsplit_once('/').map_or("", |(dir, _)| dir);
    let root = src.rsplit_once('/').map_or("", |(dir, _)| dir);
    let under =
        |dir: &str, path: &str| dir.is_empty() || path.strip_prefix(dir).is_some_and(|r| r.starts_with('/'));
    let index_html = if root.is_empty() { "index.html".to_string() } else { format!("{root}/index.html") };
    let mut picked: Vec<usize> = (0..paths.len())
        .filter(|&i| {
            let path = &paths[i];
            let lower = path.to_lowercase();
            let script = [".js", ".glsl", ".vert", ".frag"].iter().any(|e| lower.ends_with(e));
            (script && under(src, path) && skip_reason(path).is_none())
                || path.eq_ignore_ascii_case(&index_html)
        })
        .collect();
    picked.sort_by(|a, b| paths[*a].cmp(&paths[*b]));
    let left_out = picked.len().saturating_sub(MAX_PAGE_FILES);
    picked.truncate(MAX_PAGE_FILES);
    (picked, left_out)
}

/// The folders above the framework's `src/shaders/phongShader/` part of the chosen path, as far
/// as the student kept that part: the homework's root, where the other files should be.
fn homework_root(phong_path: &str) -> Vec<&str> {
    let mut root = folders(phong_path);
    for expected in ["phongShader", "shaders", "src"] {
        if root.last().is_some_and(|d| d.eq_ignore_ascii_case(expected)) {
            root.pop();
        }
    }
    root
}

/// A folder's files as (relative path, full path), and notes on what was skipped.
pub(super) struct Walked {
    pub files: Vec<(String, PathBuf)>,
    pub notes: Vec<String>,
}

/// Lists a folder's files: symlinks and tool folders skipped,
/// depth and entry count bounded.
pub(super) fn walk(root: &Path, shown: &str, limits: &Limits) -> Result<Walked, SubmissionError> {
    let mut files = Vec::new();
    let mut skipped = SkipNotes::default();
    let mut stack = vec![(root.to_path_buf(), String::new(), 0usize)];
    let mut walked_entries = 0usize;
    while let Some((dir, rel, depth)) = stack.pop() {
        let at = dir.display().to_string();
        let failed = |e: std::io::Error| SubmissionError::new(&at, format!("cannot be read: {e}"));
        let mut children = Vec::new();
        for entry in fs::read_dir(&dir).map_err(failed)? {
            walked_entries = walked_entries.saturating_add(1);
            if walked_entries > limits.folder_entries {
                let message =
                    format!("has more than {} files and folders; not walked further", limits.folder_entries);
                return Err(SubmissionError::new(shown, message));
            }
            children.push(entry.map_err(failed)?);
        }
        children.sort_by_key(|e| e.file_name());
        for child in children {
            let name = child.file_name().to_string_lossy().into_owned();
            let child_rel = if rel.is_empty() { name.clone() } else { format!("{rel}/{name}") };
            let file_type = child.file_type().map_err(failed)?;
            if file_type.is_symlink() {
                // A link may point anywhere (outside, or back up into a loop): never followed.
                skipped.push(format!("skipped {child_rel} (a symlink)"));
            } else if file_type.is_dir() {
                if let Some(why) = skipped_folder(&name) {
                    skipped.push(format!("skipped {child_rel}/ ({why})"));
                } else if depth >= limits.depth {
                    let message = format!("{child_rel} is nested deeper than {} folders", limits.depth);
                    return Err(SubmissionError::new(shown, message));
                } else {
                    stack.push((child.path(), child_rel, depth.saturating_add(1)));
                }
            } else if file_type.is_file() {
                match skip_reason(&name) {
                    Some(why) => skipped.file(&child_rel, why),
                    None => files.push((child_rel, child.path())),
                }
            }
        }
    }
    Ok(Walked { files, notes: skipped.into_notes() })
}

/// Notes about skipped things, bounded so a folder of thousands of links stays a short report.
#[derive(Default)]
pub(super) struct SkipNotes {
    lines: Vec<String>,
    more: usize,
}

const SKIP_NOTES_MAX: usize = 20;

impl SkipNotes {
    pub(super) fn push(&mut self, line: String) {
        if self.lines.len() < SKIP_NOTES_MAX {
            self.lines.push(line);
        } else {
            self.more = self.more.saturating_add(1);
        }
    }

    /// Skipped files are worth a note only when they look like one of the framework's files.
    pub(super) fn file(&mut self, path: &str, why: &str) {
        let base = path.rsplit('/').next().unwrap_or(path);
        if Kind::of(base.strip_prefix("._").unwrap_or(base)).is_some() {
            self.push(format!("skipped {} ({why})", super::zip::shown(path)));
        }
    }

    pub(super) fn into_notes(mut self) -> Vec<String> {
        if self.more > 0 {
            self.lines.push(format!("and {} more skipped", self.more));
        }
        self.lines
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn homework_names() {
        for one in ["homework1", "HW1", "hw_1", "Homework 01", "作业1", "assignment1", "A1", "games202-hw1"]
        {
            assert_eq!(homework_tag(one), Some(true), "{one}");
        }
        for other in ["homework2", "hw3", "hw10", "HW12", "A2", "作业3"] {
            assert_eq!(homework_tag(other), Some(false), "{other}");
        }
        for none in ["src", "data1", "GAMES202", "shaders", "phongShader", "hw", ""] {
            assert_eq!(homework_tag(none), None, "{none}");
        }
    }

    #[test]
    fn spare_folders() {
        for spare in ["backup", "old", "src_old", "shaders - Copy", "tmp2", "Deprecated", "副本"] {
            assert!(is_spare(spare), "{spare}");
        }
        for kept in ["src", "bold", "shaders", "homework1", "lights"] {
            assert!(!is_spare(kept), "{kept}");
        }
    }

    #[test]
    fn skips_tool_folders() {
        assert!(skip_reason("__MACOSX/hw1/._phongFragment.glsl").is_some());
        assert!(skip_reason("hw1/._phongFragment.glsl").is_some());
        assert!(skip_reason("a/node_modules/x/engine.js").is_some());
        assert!(skip_reason(".git/x").is_some());
        assert!(skip_reason("hw1/src/engine.js").is_none());
    }

    #[test]
    fn renamed_shaders_stand_in_where_the_framework_names_are_missing() {
        let paths: Vec<String> = [
            "hw1/src/shaders/phongShader/phong.frag",
            "hw1/src/shaders/phongShader/phong.vert",
            "hw1/src/shaders/shadowShader/shadow.frag",
            "hw1/src/shaders/shadowShader/shadow.vert",
            "hw1/src/shaders/lightShader/lightCube.frag",
            "hw1/src/lights/DirectionalLight.js",
        ]
        .map(String::from)
        .to_vec();
        let picked = pick(&paths).expect("a phong fragment shader");
        assert_eq!(paths[picked.phong_fragment], "hw1/src/shaders/phongShader/phong.frag");
        let named: Vec<Option<&str>> = picked.others.iter().map(|i| i.map(|i| paths[i].as_str())).collect();
        assert_eq!(
            named,
            vec![
                Some("hw1/src/shaders/phongShader/phong.vert"),
                Some("hw1/src/shaders/shadowShader/shadow.frag"),
                Some("hw1/src/shaders/shadowShader/shadow.vert"),
                Some("hw1/src/lights/DirectionalLight.js"),
                None,
            ]
        );
        assert!(
            picked
                .notes
                .iter()
                .any(|n| n
                    .starts_with("read hw1/src/shaders/phongShader/phong.frag as the phongFragment.glsl"))
        );
        // A file of the framework's name wins; two .frag files in one folder name none.
        let mut named_too = paths.clone();
        named_too.push("hw1/src/shaders/phongShader/phongFragment.glsl".into());
        let picked = pick(&named_too).expect("a phong fragment shader");
        assert_eq!(named_too[picked.phong_fragment], "hw1/src/shaders/phongShader/phongFragment.glsl");
        let two = ["a/phongShader/one.frag", "a/phongShader/two.frag"].map(String::from).to_vec();
        assert!(pick(&two).is_none());
    }
}
