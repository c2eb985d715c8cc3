//! Reads a student's GAMES202 homework-1 submission (a folder, a `.zip`, a lone `.glsl`, or
//! dropped files) and finds the framework's files in it wherever the student's layout puts them.
//!
//! Untrusted input throughout: folders are walked without following symlinks and within limits,
//! zips are read in memory by our own checked reader, and only the chosen files are read.

mod find;
mod zip;

#[cfg(test)]
mod tests;

use std::fmt;
use std::fs;
use std::io::Read;
use std::path::{Path, PathBuf};

use find::Kind;

/// One file found in a submission: its path inside the submission ('/'-separated, relative, as the student laid it out) and its text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FoundFile {
    pub path: String,
    pub text: String,
}

/// The framework's files a submission has; None where the student's layout has no such file (the caller then uses the framework's own).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SubmissionFiles {
    pub phong_fragment: FoundFile,
    pub phong_vertex: Option<FoundFile>,
    pub shadow_fragment: Option<FoundFile>,
    pub shadow_vertex: Option<FoundFile>,
    /// DirectionalLight.js
    pub light_script: Option<FoundFile>,
    /// engine.js
    pub engine: Option<FoundFile>,
    /// The rest of the page, for running it: every script and shader under engine.js's folder
    /// and the `index.html` above it, in path order (empty without an engine.js).
    pub page: Vec<FoundFile>,
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Submission {
    /// The submission's name: the folder's or the zip's file name without `.zip` (a class report lists students by it).
    pub name: String,
    pub files: SubmissionFiles,
    /// Why a choice was made where there were several candidates, or a file skipped (one line each), for the report.
    pub notes: Vec<String>,
}

/// A submission that cannot be read, on one line naming the file (or the zip entry) and the problem.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SubmissionError {
    pub path: String,
    pub message: String,
}

impl SubmissionError {
    /// Control characters (a newline in a hostile file name) are escaped to keep it one line.
    fn new(path: impl AsRef<str>, message: impl AsRef<str>) -> Self {
        SubmissionError { path: one_line(path.as_ref()), message: one_line(message.as_ref()) }
    }
}

fn one_line(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if c.is_control() {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    out
}

impl fmt::Display for SubmissionError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.path, self.message)
    }
}

impl std::error::Error for SubmissionError {}

/// Bounds on what one submission may cost to read.
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    /// A zip larger than this is refused unread.
    pub archive_bytes: u64,
    /// A zip with more entries than this is refused.
    pub entries: usize,
    /// A zip whose entries declare more than this in all is refused.
    pub total_uncompressed_bytes: u64,
    /// A candidate file larger than this is refused.
    pub file_bytes: u64,
    /// An entry over 1 MiB declaring more than this many times its compressed size marks the zip hostile.
    pub compression_ratio: u64,
    /// Folder levels walked at most.
    pub depth: usize,
    /// Directory entries walked at most in a folder submission.
    pub folder_entries: usize,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            archive_bytes: 64 << 20,
            entries: 10_000,
            total_uncompressed_bytes: 256 << 20,
            file_bytes: 1 << 20,
            compression_ratio: 200,
            depth: 24,
            folder_entries: 20_000,
        }
    }
}

/// What a path is: a `.glsl` file (the phongFragment alone, the rest the framework's), a folder, or a `.zip`.
pub fn read_path(path: &Path, limits: Limits) -> Result<Submission, SubmissionError> {
    let shown = path.display().to_string();
    let meta =
        fs::metadata(path).map_err(|e| SubmissionError::new(&shown, format!("cannot be read: {e}")))?;
    if meta.is_dir() {
        return read_folder(path, &shown, &limits);
    }
    let file_name = name_of(path);
    let lower = file_name.to_lowercase();
    if !meta.is_file() {
        // A FIFO or device would block or never end.
        return Err(SubmissionError::new(&shown, "is not a regular file or a folder"));
    }
    if lower.ends_with(".zip") {
        if meta.len() > limits.archive_bytes {
            let message =
                format!("is {} bytes, over the limit of {} bytes", meta.len(), limits.archive_bytes);
            return Err(SubmissionError::new(&shown, message));
        }
        let bytes = read_capped(path, limits.archive_bytes).map_err(|e| SubmissionError::new(&shown, e))?;
        return read_zip(&shown, strip_suffix(&file_name, ".zip"), &bytes, &limits);
    }
    if !lower.ends_with(".glsl") {
        return Err(SubmissionError::new(&shown, "is not a folder, a .zip or a .glsl file"));
    }
    let bytes = read_capped(path, limits.file_bytes).map_err(|e| SubmissionError::new(&shown, e))?;
    let text = decode_text(bytes).map_err(|e| SubmissionError::new(&shown, e))?;
    let mut notes = Vec::new();
    if Kind::of(&file_name) != Some(Kind::PhongFragment) {
        notes.push(one_line(&format!("read {file_name} as the phongFragment.glsl")));
    }
    Ok(Submission {
        name: strip_suffix(&file_name, ".glsl").to_owned(),
        files: SubmissionFiles {
            phong_fragment: FoundFile { path: file_name, text },
            phong_vertex: None,
            shadow_fragment: None,
            shadow_vertex: None,
            light_script: None,
            engine: None,
            page: Vec::new(),
        },
        notes,
    })
}

/// A zip handed over as bytes (a browser's drop): `name` is the zip's file name.
pub fn read_zip_bytes(name: &str, bytes: &[u8], limits: Limits) -> Result<Submission, SubmissionError> {
    let file_name = name.rsplit(['/', '\\']).next().unwrap_or(name);
    read_zip(name, strip_suffix(file_name, ".zip"), bytes, &limits)
}

/// Files handed over as (relative path, bytes), e.g. a dropped folder in a browser.
pub fn from_files(
    name: &str,
    files: Vec<(String, Vec<u8>)>,
    limits: Limits,
) -> Result<Submission, SubmissionError> {
    if files.len() > limits.entries {
        let message = format!("has {} files, over the limit of {}", files.len(), limits.entries);
        return Err(SubmissionError::new(name, message));
    }
    let total_bytes = files.iter().fold(0u64, |sum, (_, b)| sum.saturating_add(b.len() as u64));
    if total_bytes > limits.total_uncompressed_bytes {
        let message = format!("holds more than {} bytes in all", limits.total_uncompressed_bytes);
        return Err(SubmissionError::new(name, message));
    }
    let mut skipped = find::SkipNotes::default();
    let mut kept: Vec<(String, Vec<u8>)> = Vec::new();
    for (path, bytes) in files {
        let clean = zip::clean_name(&path).map_err(|e| SubmissionError::new(name, e))?;
        if clean.split('/').count() > limits.depth.saturating_add(1) {
            let message = format!("{} is nested deeper than {} folders", zip::shown(&clean), limits.depth);
            return Err(SubmissionError::new(name, message));
        }
        match find::skip_reason(&clean) {
            Some(why) => skipped.file(&clean, why),
            None if !clean.is_empty() => kept.push((clean, bytes)),
            None => {}
        }
    }
    let paths: Vec<String> = kept.iter().map(|(p, _)| p.clone()).collect();
    assemble(name, name, &paths, skipped.into_notes(), |i| {
        let (path, bytes) = kept.get(i).map_or(("", &[][..]), |(p, b)| (p.as_str(), b.as_slice()));
        let at = format!("{name}/{path}");
        if bytes.len() as u64 > limits.file_bytes {
            let message = format!(
                "is {} bytes, over the limit of {} bytes for one file",
                bytes.len(),
                limits.file_bytes
            );
            return Err(SubmissionError::new(at, message));
        }
        decode_text(bytes.to_vec()).map_err(|e| SubmissionError::new(at, e))
    })
}

/// A class: every submission in `dir` (each sub-folder, and each `.zip`), sorted by name; hidden entries (starting with '.') skipped. Returns the paths only (each is read when checked, so one bad submission never stops the others).
pub fn class_members(dir: &Path) -> Result<Vec<PathBuf>, SubmissionError> {
    let shown = dir.display().to_string();
    let failed = |e: std::io::Error| SubmissionError::new(&shown, format!("cannot be read: {e}"));
    let mut members = Vec::new();
    for entry in fs::read_dir(dir).map_err(failed)? {
        let entry = entry.map_err(failed)?;
        let name = entry.file_name().to_string_lossy().into_owned();
        let path = entry.path();
        // The class folder is the TA's own, so a symlinked submission there is followed;
        // `__MACOSX` is left by unzipping a class zip on a Mac, never a student.
        if !name.starts_with('.')
            && find::skipped_folder(&name).is_none()
            && (path.is_dir() || (name.to_lowercase().ends_with(".zip") && path.is_file()))
        {
            members.push(path);
        }
    }
    members.sort_by(|a, b| a.file_name().cmp(&b.file_name()));
    Ok(members)
}

/// The files of a folder submission as the reader walks it (symlinks, `.git`, `node_modules`,
/// `__MACOSX` and macOS metadata skipped; within `limits`): each file's '/'-separated path inside
/// the folder and its path on the disk. What a class run fingerprints to see whether it changed.
pub fn folder_files(root: &Path, limits: Limits) -> Result<Vec<(String, PathBuf)>, SubmissionError> {
    Ok(find::walk(root, &root.display().to_string(), &limits)?.files)
}

fn read_zip(archive: &str, name: &str, bytes: &[u8], limits: &Limits) -> Result<Submission, SubmissionError> {
    let parsed = zip::Archive::parse(bytes, limits).map_err(|e| SubmissionError::new(archive, e))?;
    let mut skipped = find::SkipNotes::default();
    let mut entries = Vec::new();
    for entry in parsed.entries.iter().filter(|e| !e.is_dir && !e.name.is_empty()) {
        match find::skip_reason(&entry.name) {
            Some(why) => skipped.file(&entry.name, why),
            None => entries.push(entry),
        }
    }
    let paths: Vec<String> = entries.iter().map(|e| e.name.clone()).collect();
    assemble(name, archive, &paths, skipped.into_notes(), |i| {
        let entry = entries.get(i).ok_or_else(|| SubmissionError::new(archive, "lost an entry"))?;
        let bytes = parsed.read(entry, limits.file_bytes).map_err(|e| SubmissionError::new(archive, e))?;
        decode_text(bytes)
            .map_err(|e| SubmissionError::new(archive, format!("entry {} {e}", zip::shown(&entry.name))))
    })
}

fn read_folder(root: &Path, shown: &str, limits: &Limits) -> Result<Submission, SubmissionError> {
    let find::Walked { files, notes } = find::walk(root, shown, limits)?;
    let paths: Vec<String> = files.iter().map(|(p, _)| p.clone()).collect();
    assemble(&name_of(root), shown, &paths, notes, |i| {
        let full = files.get(i).map_or_else(PathBuf::new, |(_, full)| full.clone());
        let at = full.display().to_string();
        let bytes = read_capped(&full, limits.file_bytes).map_err(|e| SubmissionError::new(&at, e))?;
        decode_text(bytes).map_err(|e| SubmissionError::new(&at, e))
    })
}

/// Where a submission's scripts are ES modules (a port to a bundler such as Vite): the first
/// `.js` file with a line that starts `import ... from` or `export `, and that line.
fn es_module_at(
    paths: &[String],
    read: &mut impl FnMut(usize) -> Result<String, SubmissionError>,
) -> Option<(String, usize)> {
    let mut scripts: Vec<usize> =
        (0..paths.len()).filter(|&i| paths[i].to_lowercase().ends_with(".js")).collect();
    // engine.js first: the page's entry.
    scripts.sort_by_key(|&i| (!paths[i].ends_with("engine.js"), paths[i].clone()));
    scripts.into_iter().take(8).find_map(|i| {
        let text = read(i).ok()?;
        let line = text.lines().position(|l| {
            let l = l.trim_start();
            (l.starts_with("import ") && l.contains(" from ")) || l.starts_with("export ")
        })?;
        Some((paths[i].clone(), line + 1))
    })
}

/// Picks the files among `paths` and reads the chosen ones with `read`.
fn assemble(
    name: &str,
    at: &str,
    paths: &[String],
    mut notes: Vec<String>,
    mut read: impl FnMut(usize) -> Result<String, SubmissionError>,
) -> Result<Submission, SubmissionError> {
    let nested: Vec<&String> = paths.iter().filter(|p| p.to_lowercase().ends_with(".zip")).collect();
    let Some(picked) = find::pick(paths) else {
        if let Some((file, line)) = es_module_at(paths, &mut read) {
            let message = format!(
                "{file}:{line}: an ES-module port of the framework (`import ... from`, its shaders imported as strings): the check runs the framework's classic scripts only, so it does not judge this submission"
            );
            return Err(SubmissionError::new(at, message));
        }
        let hint = match nested.first() {
            Some(inner) => format!("; it holds {}, which is not opened", zip::shown(inner)),
            None => String::new(),
        };
        let files = if paths.len() == 1 { "file" } else { "files" };
        let message = format!("no phongFragment.glsl in it (looked in {} {files}{hint})", paths.len());
        return Err(SubmissionError::new(at, message));
    };
    let side_by_side = find::level_homeworks(paths);
    if side_by_side.len() >= 2 {
        let shown: Vec<String> = side_by_side.iter().take(3).map(|t| format!("{t}/")).collect();
        let more = if side_by_side.len() > 3 { ", ..." } else { "" };
        let message = format!(
            "holds {} homeworks side by side ({}{more}): give one of them, or check them all with --class",
            side_by_side.len(),
            shown.join(", ")
        );
        return Err(SubmissionError::new(at, message));
    }
    notes.extend(picked.notes);
    notes.extend(
        nested.iter().map(|p| format!("ignored {p} (an archive inside the submission is not opened)")),
    );
    let mut found = |index: Option<usize>| -> Result<Option<FoundFile>, SubmissionError> {
        let Some(index) = index else { return Ok(None) };
        let path = paths.get(index).cloned().unwrap_or_default();
        Ok(Some(FoundFile { path, text: read(index)? }))
    };
    let phong_fragment = found(Some(picked.phong_fragment))?
        .ok_or_else(|| SubmissionError::new(at, "lost its phongFragment.glsl"))?;
    let [phong_vertex, shadow_fragment, shadow_vertex, light_script, engine] = picked.others;
    let (page_indices, left_out) = engine.map_or((Vec::new(), 0), |e| find::page_files(paths, e));
    if left_out > 0 {
        notes.push(format!(
            "the page's first {} scripts and shaders are kept, {left_out} more are not",
            find::MAX_PAGE_FILES
        ));
    }
    let mut page = Vec::new();
    for index in page_indices {
        page.extend(found(Some(index))?);
    }
    let files = SubmissionFiles {
        phong_fragment,
        phong_vertex: found(phong_vertex)?,
        shadow_fragment: found(shadow_fragment)?,
        shadow_vertex: found(shadow_vertex)?,
        light_script: found(light_script)?,
        engine: found(engine)?,
        page,
    };
    // Paths come from the student: a newline in one must not split a note.
    let notes = notes.iter().map(|note| one_line(note)).collect();
    Ok(Submission { name: name.to_owned(), files, notes })
}

/// Reads at most `limit_bytes` of a file; a larger file is refused rather than cut.
fn read_capped(path: &Path, limit_bytes: u64) -> Result<Vec<u8>, String> {
    let file = fs::File::open(path).map_err(|e| format!("cannot be read: {e}"))?;
    let mut bytes = Vec::new();
    file.take(limit_bytes.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(|e| format!("cannot be read: {e}"))?;
    if bytes.len() as u64 > limit_bytes {
        return Err(format!("is over the limit of {limit_bytes} bytes"));
    }
    Ok(bytes)
}

/// UTF-8 text, without a leading byte order mark; the offset in an error counts the mark.
fn decode_text(bytes: Vec<u8>) -> Result<String, String> {
    const BOM: &[u8] = b"\xEF\xBB\xBF";
    let (body, skipped_bytes) = match bytes.strip_prefix(BOM) {
        Some(rest) => (rest.to_vec(), BOM.len()),
        None => (bytes, 0),
    };
    String::from_utf8(body).map_err(|e| {
        let offset = e.utf8_error().valid_up_to().saturating_add(skipped_bytes);
        format!("is not UTF-8 text (invalid byte at offset {offset})")
    })
}

/// The last component of a path, resolving `.` and the like so a folder always has a name.
fn name_of(path: &Path) -> String {
    let named = path.file_name().map(|n| n.to_string_lossy().into_owned());
    named
        .or_else(|| fs::canonicalize(path).ok()?.file_name().map(|n| n.to_string_lossy().into_owned()))
        .unwrap_or_else(|| path.display().to_string())
}

/// `name` without `suffix`, ignoring case (`Alice.ZIP`).
fn strip_suffix<'a>(name: &'a str, suffix: &str) -> &'a str {
    let cut = name.len().checked_sub(suffix.len());
    match cut.and_then(|at| name.get(at..).map(|tail| (at, tail))) {
        Some((at, tail)) if tail.eq_ignore_ascii_case(suffix) => name.get(..at).unwrap_or(name),
        _ => name,
    }
}
