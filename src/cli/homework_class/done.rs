//! What a class run remembers of a check it has done: `OUT/NAME/checked.json`, the submission's
//! fingerprint with how its check ended. A rerun skips a member whose fingerprint is the same and
//! whose report still reads.
//!
//! The fingerprint of a folder is its files as the submission reader walks them (the same skips,
//! the same bounds): each one's path inside the folder, size and modification time; of a zip, its
//! size and modification time. The shadowlab version, the picture size and the language are part
//! of it: a new shadowlab, or another --size or --lang, checks everything again.

use crate::export::class_report::{Status, StudentReport};
use crate::homework::submission;
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::time::UNIX_EPOCH;

/// The file a done check leaves in its folder.
pub const CHECKED: &str = "checked.json";
/// Largest checked.json and report.json read back (a report is tens of kilobytes).
const MAX_CHECKED_BYTES: u64 = 1 << 20;

#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Fingerprint {
    pub shadowlab: String,
    /// The pictures' size, `WxH`, and the reports' language.
    pub size: String,
    pub lang: String,
    /// `folder` or `zip`.
    pub kind: String,
    /// Files fingerprinted, and their bytes in all.
    pub files: usize,
    pub bytes: u64,
    /// FNV-1a (64 bits) over each file's path, size and modification time (ns), in path order.
    pub digest: String,
}

/// What checked.json holds.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Done {
    pub fingerprint: Fingerprint,
    pub status: Status,
    pub message: String,
}

/// Size and modification time (ns since 1970; 0 where the system has none) of a file.
fn stamp(path: &Path) -> Option<(u64, u128)> {
    let meta = std::fs::symlink_metadata(path).ok()?;
    let modified = meta.modified().ok().and_then(|t| t.duration_since(UNIX_EPOCH).ok());
    Some((meta.len(), modified.map_or(0, |d| d.as_nanos())))
}

/// The fingerprint of the submission at `path` (a folder or a .zip) for a check at `size` in
/// `lang`; None where it cannot be taken (a folder past the reader's bounds): then it is always
/// checked.
pub fn fingerprint(path: &Path, size: (u32, u32), lang: &str) -> Option<Fingerprint> {
    let mut files: Vec<(String, u64, u128)> = if path.is_dir() {
        let walked = submission::folder_files(path, submission::Limits::default()).ok()?;
        let mut files = Vec::with_capacity(walked.len());
        for (rel, full) in walked {
            let (len, modified) = stamp(&full)?;
            files.push((rel, len, modified));
        }
        files
    } else {
        let (len, modified) = stamp(path)?;
        vec![(String::new(), len, modified)]
    };
    files.sort();
    let mut digest = crate::files::Fnv1a::new();
    for (rel, len, modified) in &files {
        digest.add(rel.as_bytes());
        digest.add(&[0]);
        digest.add(&len.to_le_bytes());
        digest.add(&modified.to_le_bytes());
    }
    Some(Fingerprint {
        shadowlab: env!("CARGO_PKG_VERSION").to_string(),
        size: format!("{}x{}", size.0, size.1),
        lang: lang.to_string(),
        kind: if path.is_dir() { "folder" } else { "zip" }.to_string(),
        files: files.len(),
        bytes: files.iter().map(|f| f.1).fold(0, u64::saturating_add),
        digest: format!("{:016x}", digest.value()),
    })
}

fn read_bounded(path: &Path, max_bytes: u64) -> Option<String> {
    crate::files::read_input_text(path, max_bytes).ok()
}

pub use crate::export::class_report::{MAX_REPORT_BYTES, read_report};

/// How the check of the submission with `fingerprint` ended, if `folder` holds a done check of
/// it whose report (where it has one) still reads.
pub fn already(folder: &Path, fingerprint: &Fingerprint) -> Option<(Done, Option<StudentReport>)> {
    let done: Done = serde_json::from_str(&read_bounded(&folder.join(CHECKED), MAX_CHECKED_BYTES)?).ok()?;
    if done.fingerprint != *fingerprint {
        return None;
    }
    match done.status {
        Status::Checked | Status::DidNotCompile => {
            let report = read_report(&folder.join("report.json"))?;
            (report.compiled == (done.status == Status::Checked)).then_some((done, Some(report)))
        }
        Status::Refused => Some((done, None)),
        Status::Failed | Status::TimedOut => None,
    }
}

/// Record a done check in `folder` (made if missing).
pub fn record(folder: &Path, done: &Done) -> Result<(), String> {
    std::fs::create_dir_all(folder).map_err(|e| format!("{}: {e}", folder.display()))?;
    let text = serde_json::to_string_pretty(done).map_err(|e| e.to_string())?;
    crate::files::write_atomic(&folder.join(CHECKED), text.as_bytes())
}

/// Forget a done check (before it runs again: a check stopped half-way is not done).
pub fn forget(folder: &Path) {
    let _ = std::fs::remove_file(folder.join(CHECKED));
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fs::{File, FileTimes};
    use std::time::{Duration, SystemTime};

    fn set_modified(path: &Path, at: SystemTime) {
        let file = File::options().write(true).open(path).expect("open");
        file.set_times(FileTimes::new().set_modified(at)).expect("set the time");
    }

    #[test]
    fn a_folder_fingerprint_changes_with_its_files_only() {
        let dir = tempfile::tempdir().expect("a folder");
        let student = dir.path().join("alice");
        std::fs::create_dir_all(student.join("homework1/src")).expect("folders");
        std::fs::create_dir_all(student.join(".git")).expect("folders");
        let shader = student.join("homework1/src/phongFragment.glsl");
        std::fs::write(&shader, "void main() {}").expect("write");
        let t0 = SystemTime::UNIX_EPOCH + Duration::from_secs(1_700_000_000);
        set_modified(&shader, t0);
        let first = fingerprint(&student, (240, 135), "en").expect("a fingerprint");
        assert_eq!((first.kind.as_str(), first.files, first.bytes), ("folder", 1, 14));
        assert_eq!(first.shadowlab, env!("CARGO_PKG_VERSION"));
        // What the reader skips does not count.
        std::fs::write(student.join(".git/index"), "x").expect("write");
        assert_eq!(fingerprint(&student, (240, 135), "en"), Some(first.clone()));
        // Another size or language is another check.
        assert_ne!(fingerprint(&student, (960, 540), "en"), Some(first.clone()));
        assert_ne!(fingerprint(&student, (240, 135), "zh"), Some(first.clone()));
        // A touched file, a changed one, a new one: each changes it.
        set_modified(&shader, t0 + Duration::from_secs(1));
        let touched = fingerprint(&student, (240, 135), "en").expect("a fingerprint");
        assert_ne!(touched.digest, first.digest);
        std::fs::write(student.join("homework1/notes.txt"), "").expect("write");
        assert_ne!(fingerprint(&student, (240, 135), "en"), Some(touched));
    }

    #[test]
    fn a_zip_fingerprint_is_its_size_and_time() {
        let dir = tempfile::tempdir().expect("a folder");
        let zip = dir.path().join("bob.zip");
        std::fs::write(&zip, b"PK\x05\x06").expect("write");
        let first = fingerprint(&zip, (240, 135), "en").expect("a fingerprint");
        assert_eq!((first.kind.as_str(), first.files, first.bytes), ("zip", 1, 4));
        set_modified(&zip, SystemTime::UNIX_EPOCH + Duration::from_secs(5));
        assert_ne!(fingerprint(&zip, (240, 135), "en"), Some(first));
    }

    #[test]
    fn a_done_check_is_found_again_while_its_fingerprint_and_report_hold() {
        let dir = tempfile::tempdir().expect("a folder");
        let print = |digest: &str| Fingerprint {
            shadowlab: "1".into(),
            size: "1x1".into(),
            lang: "en".into(),
            kind: "zip".into(),
            files: 1,
            bytes: 1,
            digest: digest.into(),
        };
        let folder = dir.path().join("out");
        let refused = Done { fingerprint: print("a"), status: Status::Refused, message: "bad".into() };
        record(&folder, &refused).expect("record");
        assert_eq!(already(&folder, &print("a")).map(|d| d.0), Some(refused));
        assert!(already(&folder, &print("b")).is_none());
        let checked = Done { fingerprint: print("a"), status: Status::Checked, message: String::new() };
        record(&folder, &checked).expect("record");
        assert!(already(&folder, &print("a")).is_none(), "no report.json");
        std::fs::write(folder.join("report.json"), r#"{"compiled": true}"#).expect("write");
        assert!(already(&folder, &print("a")).is_some());
        std::fs::write(folder.join("report.json"), r#"{"compiled": tr"#).expect("write");
        assert!(already(&folder, &print("a")).is_none(), "a report that does not parse");
        forget(&folder);
        assert!(!folder.join(CHECKED).exists());
    }
}
