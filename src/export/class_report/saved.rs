//! `class.json`: the class's rows as the class report was written from them (each student's
//! name, folder under OUT, submission and how the check ended), so a class report folder can be
//! opened again (the app's class panel) without running a check: each row's report is read back
//! from its folder.

use super::{ClassRow, PICTURES, Status, StudentReport};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The rows of the class report, beside index.html.
pub const CLASS: &str = "class.json";
/// Largest class.json read back (a row is a few hundred bytes).
const MAX_CLASS_BYTES: u64 = 16 << 20;
/// Largest report.json read back (a report is tens of kilobytes).
pub const MAX_REPORT_BYTES: u64 = 32 << 20;

#[derive(Serialize, Deserialize)]
struct SavedRow {
    name: String,
    folder: String,
    path: String,
    status: Status,
    message: String,
}

#[derive(Serialize, Deserialize)]
struct Saved {
    students: Vec<SavedRow>,
}

pub(super) fn json(rows: &[ClassRow]) -> String {
    let students = rows
        .iter()
        .map(|r| SavedRow {
            name: r.name.clone(),
            folder: r.folder.clone(),
            path: r.path.clone(),
            status: r.status,
            message: r.message.clone(),
        })
        .collect();
    serde_json::to_string_pretty(&Saved { students }).unwrap_or_default()
}

/// A report a check wrote (None: missing, too large or not a report).
pub fn read_report(path: &Path) -> Option<StudentReport> {
    let text = crate::files::read_input_text(path, MAX_REPORT_BYTES).ok()?;
    StudentReport::parse(&text).ok()
}

/// `out` holds a class report written by `homework --class`.
pub fn is_class_report(out: &Path) -> bool {
    crate::files::is_file(&out.join(CLASS))
}

/// The class report in `out` read back: its rows with each one's report and pictures. One line
/// on failure, naming the file.
pub fn read(out: &Path) -> Result<Vec<ClassRow>, String> {
    let path = out.join(CLASS);
    let text = crate::files::read_input_text(&path, MAX_CLASS_BYTES).map_err(|e| e.to_string())?;
    let saved: Saved =
        serde_json::from_str(&text).map_err(|e| format!("{}: not a class report: {e}", path.display()))?;
    let mut rows = Vec::with_capacity(saved.students.len());
    for s in saved.students {
        // A folder is one name under OUT, never a way out of it.
        let plain =
            !s.folder.is_empty() && !s.folder.contains(['/', '\\']) && s.folder != "." && s.folder != "..";
        if !plain {
            return Err(format!("{}: `{}` is not a folder of the report", path.display(), s.folder));
        }
        let folder = out.join(&s.folder);
        let report = match s.status {
            Status::Checked | Status::DidNotCompile => read_report(&folder.join("report.json")),
            _ => None,
        };
        let pictures = match report {
            Some(_) if s.status == Status::Checked => {
                PICTURES.iter().copied().filter(|p| crate::files::is_file(&folder.join(p))).collect()
            }
            _ => Vec::new(),
        };
        rows.push(ClassRow {
            name: s.name,
            folder: s.folder,
            path: s.path,
            status: s.status,
            message: s.message,
            report,
            pictures,
        });
    }
    Ok(rows)
}
