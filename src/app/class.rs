//! A class open in the app: a folder of students' homeworks (each a sub-folder or a .zip) is
//! checked by this program's own `homework --class` as a process of its own (a crash or a hang
//! in one student's check never reaches the app), into a class report folder; the report is then
//! read back as the findings ranked by how many students have them and the students, each a click
//! away from their homework. A class report folder written before opens at once.

use super::{AppError, AppState};
use crate::export::class_report::{self, ClassRow, Ranked, Status};
use std::path::{Path, PathBuf};

/// A class open in the app.
pub struct ClassState {
    /// What was opened: the class folder, or a class report folder.
    pub dir: PathBuf,
    /// The class report's folder (written by the check, then read).
    pub out: PathBuf,
    /// Submissions in the class, and checks ended so far (while the check runs).
    pub members: usize,
    pub done: usize,
    /// The class report read back (empty until the check has ended).
    pub rows: Vec<ClassRow>,
    pub ranked: Vec<Ranked>,
    /// Why the class check failed (one line).
    pub error: Option<String>,
    /// The student last opened from the list (an index into `rows`).
    pub opened: Option<usize>,
    /// The side panel shows the class (false: the opened student's homework).
    pub showing: bool,
    run: Option<run::ClassRun>,
}

impl ClassState {
    /// The class check is still running.
    pub fn running(&self) -> bool {
        self.run.is_some()
    }

    /// The class's name as the panel shows it (its folder's).
    pub fn name(&self) -> String {
        self.dir.file_name().map_or_else(|| self.dir.display().to_string(), |n| n.to_string_lossy().into())
    }

    /// How many students ended with `status`.
    pub fn count(&self, status: Status) -> usize {
        self.rows.iter().filter(|r| r.status == status).count()
    }

    fn read_report(&mut self) {
        match class_report::read(&self.out) {
            Ok(rows) => {
                self.ranked = class_report::ranked(&rows);
                self.members = rows.len();
                self.done = rows.len();
                self.rows = rows;
            }
            Err(e) => self.error = Some(e),
        }
    }

    /// Take the check's progress; read the report once it has ended.
    pub fn poll(&mut self) {
        let Some(run) = self.run.as_mut() else { return };
        let (done, ended) = run.poll();
        if let Some(d) = done {
            self.done = d;
        }
        if let Some(ended) = ended {
            self.run = None;
            match ended {
                Ok(()) => self.read_report(),
                Err(e) => self.error = Some(e),
            }
        }
    }
}

/// The program that checks a class: this one on the desktop; none in the page.
#[cfg(not(target_arch = "wasm32"))]
pub(super) fn checker() -> Option<PathBuf> {
    std::env::current_exe().ok()
}

#[cfg(target_arch = "wasm32")]
pub(super) fn checker() -> Option<PathBuf> {
    None
}

/// A folder that is not one homework (asked only where it did not read as one) the app opens as a
/// class: a class report, or two or more submissions side by side.
pub fn is_class(path: &Path) -> bool {
    if !crate::files::exists(path) || crate::files::is_file(path) {
        return false;
    }
    class_report::is_class_report(path)
        || crate::homework::submission::class_members(path).is_ok_and(|m| m.len() >= 2)
}

/// Where the app keeps the class report of the class in `dir`: one folder per class, so opening
/// it again checks only the submissions that changed.
fn report_folder(dir: &Path) -> PathBuf {
    let at = std::fs::canonicalize(dir).unwrap_or_else(|_| dir.to_path_buf());
    let mut hash = crate::files::Fnv1a::new();
    hash.add(at.to_string_lossy().as_bytes());
    let name: String = at
        .file_name()
        .map(|n| n.to_string_lossy().chars().filter(|c| c.is_alphanumeric() || *c == '-').take(40).collect())
        .unwrap_or_default();
    std::env::temp_dir().join("shadowlab-classes").join(format!("{name}-{:016x}", hash.value()))
}

impl AppState {
    /// Open a class: a class report folder is read at once; a folder of submissions is checked by
    /// `homework --class` in the background (the panel shows its progress), then read.
    pub fn open_class(&mut self, dir: &Path) {
        let mut class = ClassState {
            dir: dir.to_path_buf(),
            out: dir.to_path_buf(),
            members: 0,
            done: 0,
            rows: Vec::new(),
            ranked: Vec::new(),
            error: None,
            opened: None,
            showing: true,
            run: None,
        };
        if class_report::is_class_report(dir) {
            class.read_report();
            if let Some(e) = class.error.take() {
                self.error = Some(AppError::new("could not open the class", e));
                return;
            }
        } else {
            let members = match crate::homework::submission::class_members(dir) {
                Ok(m) => m.len(),
                Err(e) => {
                    self.error = Some(AppError::new("could not open the class", e.to_string()));
                    return;
                }
            };
            class.members = members;
            class.out = report_folder(dir);
            let Some(checker) = self.class_checker.clone() else {
                let detail = format!(
                    "{}: a class is checked by the desktop program: shadowlab homework --class DIR --out OUT",
                    dir.display()
                );
                self.error = Some(AppError::new("could not open the class", detail));
                return;
            };
            match run::ClassRun::start(&checker, dir, &class.out, self.lang) {
                Ok(r) => class.run = Some(r),
                Err(e) => {
                    self.error = Some(AppError::new("could not open the class", e));
                    return;
                }
            }
        }
        self.show_lesson_list = false;
        self.status = format!("{} {}", crate::i18n::tr(self.lang, "opened"), dir.display());
        self.settings.remember_file(dir);
        self.class = Some(class);
        self.error = None;
    }

    /// Open the `row`th student of the class: their homework, checked in the app.
    pub fn open_class_student(&mut self, row: usize) {
        let Some(path) = self.class.as_ref().and_then(|c| c.rows.get(row)).map(|r| PathBuf::from(&r.path))
        else {
            return;
        };
        self.open_homework(&path);
        if self.error.is_none()
            && let Some(class) = self.class.as_mut()
        {
            class.opened = Some(row);
            class.showing = false;
        }
    }
}

#[cfg(not(target_arch = "wasm32"))]
mod run {
    //! The class check as a child process, its progress read from its `[n/N]` lines.

    use crate::i18n::Lang;
    use std::io::{BufRead, BufReader};
    use std::path::Path;
    use std::process::{Child, Command, Stdio};
    use std::sync::mpsc::{Receiver, channel};

    pub(super) struct ClassRun {
        child: Child,
        lines: Receiver<String>,
        /// The child's last own line (`shadowlab: ...`): why it failed, if it does.
        said: Option<String>,
    }

    impl ClassRun {
        pub(super) fn start(exe: &Path, dir: &Path, out: &Path, lang: Lang) -> Result<Self, String> {
            if let Some(parent) = out.parent() {
                std::fs::create_dir_all(parent).map_err(|e| format!("{}: {e}", parent.display()))?;
            }
            let jobs = std::thread::available_parallelism().map_or(1, |n| n.get().min(4));
            let mut child = Command::new(exe)
                .args(["homework", "--class"])
                .arg(dir)
                .arg("--out")
                .arg(out)
                .args(["--jobs", &jobs.to_string(), "--lang", lang.code()])
                .stdin(Stdio::null())
                .stdout(Stdio::null())
                .stderr(Stdio::piped())
                .spawn()
                .map_err(|e| format!("cannot start {}: {e}", exe.display()))?;
            let (send, lines) = channel();
            if let Some(err) = child.stderr.take() {
                std::thread::spawn(move || {
                    for line in BufReader::new(err).lines().map_while(Result::ok) {
                        if send.send(line).is_err() {
                            break;
                        }
                    }
                });
            }
            Ok(Self { child, lines, said: None })
        }

        /// Checks ended so far (the last `[n/N]` line's n), and the run's end where it has ended.
        pub(super) fn poll(&mut self) -> (Option<usize>, Option<Result<(), String>>) {
            let mut done = None;
            for line in self.lines.try_iter() {
                if let Some(n) = line.strip_prefix('[').and_then(|l| l.split('/').next()?.parse().ok()) {
                    done = Some(n);
                } else if let Some(own) = line.strip_prefix("shadowlab: ") {
                    self.said = Some(own.to_string());
                }
            }
            let ended = match self.child.try_wait() {
                Ok(Some(status)) if status.success() => Some(Ok(())),
                Ok(Some(status)) => Some(Err(self
                    .said
                    .clone()
                    .unwrap_or_else(|| format!("the class check ended with {status}")))),
                Ok(None) => None,
                Err(e) => Some(Err(format!("lost the class check: {e}"))),
            };
            (done, ended)
        }
    }

    impl Drop for ClassRun {
        /// A class closed (or the app) stops its check.
        fn drop(&mut self) {
            if matches!(self.child.try_wait(), Ok(None)) {
                let _ = self.child.kill();
                let _ = self.child.wait();
            }
        }
    }
}

#[cfg(target_arch = "wasm32")]
mod run {
    //! The page starts no processes: a class is checked by the desktop program.

    use crate::i18n::Lang;
    use std::path::Path;

    pub(super) struct ClassRun;

    impl ClassRun {
        pub(super) fn start(_: &Path, _: &Path, _: &Path, _: Lang) -> Result<Self, String> {
            Err("a class is checked by the desktop program: shadowlab homework --class DIR --out OUT".into())
        }

        pub(super) fn poll(&mut self) -> (Option<usize>, Option<Result<(), String>>) {
            (None, Some(Ok(())))
        }
    }
}
