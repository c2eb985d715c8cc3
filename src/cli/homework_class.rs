//! `shadowlab homework --class DIR --out OUT`: every submission in DIR (each sub-folder and each
//! .zip, as `submission::class_members` lists them) checked by this same program as a process of
//! its own, `homework MEMBER --out OUT/NAME --json`, at most `--jobs` at once. A child that
//! crashes, hangs (stopped after `--timeout`) or is refused ends as its own row: one submission
//! never stops the others. Then the class report (`export::class_report`) is written to OUT.
//!
//! A check that is done is remembered (`done`): a rerun checks only what changed, unless
//! `--force`. Bad input (DIR not a folder, OUT a file, no submissions) is one line, exit 2, and
//! nothing written.

mod done;
mod progress;

use super::CliError;
use super::homework::HomeworkArgs;
use crate::export::class_report::{self, ClassRow, PICTURES, Status, StudentReport};
use crate::files::OneLine;
use done::{Done, Fingerprint};
use progress::Progress;
use std::collections::VecDeque;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, ExitStatus, Stdio};
use std::sync::mpsc::{Receiver, channel};
use std::time::{Duration, Instant};

/// How often a running check is asked whether it has ended.
const POLL: Duration = Duration::from_millis(50);
/// Most of a child's output kept (its report on stdout is tens of kilobytes); the rest is read
/// and dropped, so a child never blocks on a full pipe.
const MAX_STDOUT_BYTES: u64 = done::MAX_REPORT_BYTES;
const MAX_STDERR_BYTES: u64 = 1 << 20;
/// A message is one line of at most this many characters.
const MAX_MESSAGE_CHARS: usize = 400;

/// One submission of the class.
struct Member {
    path: PathBuf,
    /// Its name (the folder's, or the zip's without `.zip`), one line.
    name: String,
    /// The folder under OUT its check writes to.
    folder: String,
}

/// The names OUT's own files have: no member's folder may take one.
const RESERVED: [&str; 3] = [class_report::INDEX_EN, class_report::INDEX_ZH, class_report::GRADES];

/// Each member's name and folder under OUT: the folder's name, or the zip's without `.zip`; a
/// name taken already (`alice/` beside `alice.zip`, in any case) or one of OUT's own files keeps
/// its whole file name, then a number.
fn members(paths: Vec<PathBuf>) -> Vec<Member> {
    let mut taken: Vec<String> = RESERVED.iter().map(|r| r.to_lowercase()).collect();
    let mut out = Vec::with_capacity(paths.len());
    for path in paths {
        let file_name = path.file_name().map_or_else(String::new, |n| n.to_string_lossy().into_owned());
        let stem = match file_name.len().checked_sub(4).and_then(|at| file_name.get(at..).map(|s| (at, s))) {
            Some((at, tail)) if path.is_file() && tail.eq_ignore_ascii_case(".zip") => &file_name[..at],
            _ => file_name.as_str(),
        };
        let mut folder = if stem.is_empty() { file_name.clone() } else { stem.to_string() };
        if taken.contains(&folder.to_lowercase()) {
            folder = file_name.clone();
        }
        let base = folder.clone();
        let mut n = 2;
        while taken.contains(&folder.to_lowercase()) {
            folder = format!("{base}-{n}");
            n += 1;
        }
        taken.push(folder.to_lowercase());
        out.push(Member { path, name: OneLine(&folder).to_string(), folder });
    }
    out
}

/// Everything checked before the first file is written.
fn prepare(dir: &Path, out: &Path) -> Result<Vec<Member>, CliError> {
    if !dir.is_dir() {
        let why = if dir.exists() { "is not a folder" } else { "does not exist" };
        return Err(CliError::input(format!("--class {}: {why}", dir.display())));
    }
    if out.exists() && !out.is_dir() {
        return Err(CliError::input(format!("{}: is a file, not a folder", out.display())));
    }
    let parent = out.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    if !parent.is_dir() {
        return Err(CliError::input(format!(
            "{}: folder {} does not exist",
            out.display(),
            parent.display()
        )));
    }
    let canonical = |p: &Path| std::fs::canonicalize(p).ok();
    let out_at = canonical(out);
    if out_at.is_some() && out_at == canonical(dir) {
        return Err(CliError::input(format!("--out {}: is the class folder itself", out.display())));
    }
    let mut paths =
        crate::homework::submission::class_members(dir).map_err(|e| CliError::input(e.to_string()))?;
    // OUT inside DIR is the report, not a student.
    paths.retain(|p| out_at.is_none() || canonical(p) != out_at);
    if let Some(inside) =
        paths.iter().find(|p| out_at.as_ref().is_some_and(|o| canonical(p).is_some_and(|m| o.starts_with(m))))
    {
        return Err(CliError::input(format!(
            "--out {}: is inside the submission {}",
            out.display(),
            inside.display()
        )));
    }
    if paths.is_empty() {
        return Err(CliError::input(format!(
            "--class {}: no submissions in it (each student is a sub-folder or a .zip)",
            dir.display()
        )));
    }
    Ok(members(paths))
}

/// A check running as a child process.
struct Running {
    index: usize,
    child: Child,
    started: Instant,
    stdout: Receiver<Vec<u8>>,
    stderr: Receiver<Vec<u8>>,
}

/// Read at most `max` bytes of a pipe, then drain the rest, on a thread of its own.
fn collect(mut pipe: impl Read + Send + 'static, max: u64) -> Receiver<Vec<u8>> {
    let (send, receive) = channel();
    std::thread::spawn(move || {
        let mut bytes = Vec::new();
        let _ = (&mut pipe).take(max).read_to_end(&mut bytes);
        let _ = std::io::copy(&mut pipe, &mut std::io::sink());
        let _ = send.send(bytes);
    });
    receive
}

/// How a child ended.
enum Ended {
    Exited(ExitStatus),
    TimedOut,
    Lost(String),
}

struct Settings {
    exe: PathBuf,
    out: PathBuf,
    dir_prefix: String,
    size: (u32, u32),
    lang: crate::i18n::Lang,
    timeout: Duration,
}

fn spawn(settings: &Settings, index: usize, member: &Member) -> std::io::Result<Running> {
    let (w, h) = settings.size;
    let mut child = Command::new(&settings.exe)
        .arg("homework")
        .arg("--out")
        .arg(settings.out.join(&member.folder))
        .args(["--json", "--lang", settings.lang.code(), "--size", &format!("{w}x{h}"), "--"])
        .arg(&member.path)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()?;
    let (Some(out), Some(err)) = (child.stdout.take(), child.stderr.take()) else {
        let _ = child.kill();
        let _ = child.wait();
        return Err(std::io::Error::other("no pipes to the check"));
    };
    Ok(Running {
        index,
        child,
        started: Instant::now(),
        stdout: collect(out, MAX_STDOUT_BYTES),
        stderr: collect(err, MAX_STDERR_BYTES),
    })
}

/// The line of a child's stderr that says what happened: its own error (`shadowlab: ...`), a
/// panic's message, or its last line; on one line, without the class folder's path.
fn message_of(stderr: &str, settings: &Settings, warnings_only: bool) -> String {
    let lines: Vec<&str> = stderr.lines().map(str::trim).filter(|l| !l.is_empty()).collect();
    let own = lines.iter().rev().find(|l| l.starts_with("shadowlab: ")).map(|l| &l["shadowlab: ".len()..]);
    let line = if warnings_only {
        own.filter(|l| l.starts_with("warning: ")).unwrap_or("")
    } else {
        let panic =
            lines.iter().position(|l| l.contains("panicked at")).and_then(|at| lines.get(at + 1).copied());
        own.or(panic).or(lines.last().copied()).unwrap_or("")
    };
    let line = line.strip_prefix(settings.dir_prefix.as_str()).unwrap_or(line);
    let mut text = OneLine(line).to_string();
    if text.chars().count() > MAX_MESSAGE_CHARS {
        text = text.chars().take(MAX_MESSAGE_CHARS).chain("…".chars()).collect();
    }
    text
}

/// What a child's ending makes of its row, and whether it is done (a rerun need not repeat it).
fn judge(
    member: &Member,
    ended: Ended,
    stdout: &[u8],
    stderr: &[u8],
    settings: &Settings,
) -> (ClassRow, bool) {
    let stderr = String::from_utf8_lossy(stderr);
    let report = std::str::from_utf8(stdout).map_err(|e| e.to_string()).and_then(StudentReport::parse);
    let error = message_of(&stderr, settings, false);
    let (status, message, report, done) = match ended {
        Ended::TimedOut => {
            let secs = settings.timeout.as_secs_f64();
            (Status::TimedOut, format!("stopped after {secs} s (--timeout)"), None, false)
        }
        Ended::Lost(why) => (Status::Failed, why, None, false),
        Ended::Exited(exit) => match (exit.code(), report) {
            (Some(0), Ok(report)) if report.compiled => {
                (Status::Checked, message_of(&stderr, settings, true), Some(report), true)
            }
            (Some(0), Ok(_)) => (Status::Failed, "its report says it did not compile".into(), None, false),
            (Some(0), Err(e)) => (Status::Failed, format!("its report cannot be read: {e}"), None, false),
            (Some(2), Ok(report)) if !report.compiled => (Status::DidNotCompile, error, Some(report), true),
            // Refused for what the submission is (the message names it) is done; refused for
            // the machine (no GPU adapter) is not.
            (Some(2), _) => {
                let names_it = stderr.contains(&format!("shadowlab: {}", member.path.display()));
                (Status::Refused, error, None, names_it)
            }
            (Some(code), _) if error.is_empty() => (Status::Failed, format!("exit code {code}"), None, false),
            (Some(_), _) => (Status::Failed, error, None, false),
            (None, _) => {
                let signal = signal_of(exit);
                let message = if error.is_empty() { signal } else { format!("{signal}: {error}") };
                (Status::Failed, message, None, false)
            }
        },
    };
    let folder = settings.out.join(&member.folder);
    let pictures = if status == Status::Checked {
        PICTURES.iter().copied().filter(|p| folder.join(p).is_file()).collect()
    } else {
        Vec::new()
    };
    let row = ClassRow {
        name: member.name.clone(),
        folder: member.folder.clone(),
        path: member.path.display().to_string(),
        status,
        message,
        report,
        pictures,
    };
    (row, done)
}

#[cfg(unix)]
fn signal_of(exit: ExitStatus) -> String {
    use std::os::unix::process::ExitStatusExt;
    exit.signal().map_or_else(|| "ended without an exit code".into(), |s| format!("crashed (signal {s})"))
}

#[cfg(not(unix))]
fn signal_of(_: ExitStatus) -> String {
    "ended without an exit code".into()
}

/// Run the checks of `todo` (indices into `members`), at most `jobs` at once, each row into
/// `rows` as it ends.
fn run_checks(
    members: &[Member],
    todo: Vec<usize>,
    jobs: usize,
    settings: &Settings,
    rows: &mut [Option<ClassRow>],
) {
    let total = todo.len();
    let progress = Progress::new(total);
    let mut queue: VecDeque<usize> = todo.into();
    let mut running: Vec<Running> = Vec::new();
    let mut finished = 0usize;
    let mut finish = |index: usize, ended: Ended, out: Vec<u8>, err: Vec<u8>, took: Duration| {
        let member = &members[index];
        let (row, is_done) = judge(member, ended, &out, &err, settings);
        if is_done && let Some(fingerprint) = fingerprint(member, settings) {
            let done = Done { fingerprint, status: row.status, message: row.message.clone() };
            if let Err(e) = done::record(&settings.out.join(&member.folder), &done) {
                eprintln!("shadowlab: warning: {}: cannot remember the check: {e}", member.name);
            }
        }
        finished += 1;
        progress.done(finished, total, &row, took);
        rows[index] = Some(row);
    };
    while !queue.is_empty() || !running.is_empty() {
        while running.len() < jobs
            && let Some(index) = queue.pop_front()
        {
            done::forget(&settings.out.join(&members[index].folder));
            match spawn(settings, index, &members[index]) {
                Ok(child) => running.push(child),
                Err(e) => finish(
                    index,
                    Ended::Lost(format!("cannot start the check: {e}")),
                    vec![],
                    vec![],
                    Duration::ZERO,
                ),
            }
        }
        progress.running(&running.iter().map(|r| members[r.index].name.as_str()).collect::<Vec<_>>());
        let mut k = 0;
        while k < running.len() {
            let r = &mut running[k];
            let ended = match r.child.try_wait() {
                Ok(Some(exit)) => Some(Ended::Exited(exit)),
                Ok(None) if r.started.elapsed() >= settings.timeout => Some(Ended::TimedOut),
                Ok(None) => None,
                Err(e) => Some(Ended::Lost(format!("lost the check: {e}"))),
            };
            let Some(ended) = ended else {
                k += 1;
                continue;
            };
            let mut r = running.swap_remove(k);
            if !matches!(ended, Ended::Exited(_)) {
                let _ = r.child.kill();
                let _ = r.child.wait();
            }
            // The pipes close when the child has ended (it starts no processes of its own).
            let wait = Duration::from_secs(5);
            let out = r.stdout.recv_timeout(wait).unwrap_or_default();
            let err = r.stderr.recv_timeout(wait).unwrap_or_default();
            finish(r.index, ended, out, err, r.started.elapsed());
        }
        if !running.is_empty() {
            std::thread::sleep(POLL);
        }
    }
    progress.finish();
}

fn fingerprint(member: &Member, settings: &Settings) -> Option<Fingerprint> {
    done::fingerprint(&member.path, settings.size, settings.lang.code())
}

/// The row of a member whose check is done and unchanged, if it is.
fn already_checked(member: &Member, settings: &Settings) -> Option<ClassRow> {
    let folder = settings.out.join(&member.folder);
    let (done, report) = done::already(&folder, &fingerprint(member, settings)?)?;
    let pictures = if done.status == Status::Checked {
        PICTURES.iter().copied().filter(|p| folder.join(p).is_file()).collect()
    } else {
        Vec::new()
    };
    Some(ClassRow {
        name: member.name.clone(),
        folder: member.folder.clone(),
        path: member.path.display().to_string(),
        status: done.status,
        message: done.message,
        report,
        pictures,
    })
}

pub fn run(dir: &Path, args: &HomeworkArgs) -> Result<(), CliError> {
    let members = prepare(dir, &args.out)?;
    let exe = std::env::current_exe()
        .map_err(|e| CliError::input(format!("cannot find this program to run the checks: {e}")))?;
    std::fs::create_dir_all(&args.out)
        .map_err(|e| CliError::input(format!("{}: {e}", args.out.display())))?;
    let settings = Settings {
        exe,
        out: args.out.clone(),
        dir_prefix: format!("{}/", dir.display().to_string().trim_end_matches('/')),
        size: args.size,
        lang: args.lang,
        timeout: args.timeout,
    };
    let started = Instant::now();
    let mut rows: Vec<Option<ClassRow>> = members.iter().map(|_| None).collect();
    let mut todo = Vec::new();
    for (index, member) in members.iter().enumerate() {
        match already_checked(member, &settings).filter(|_| !args.force) {
            Some(row) => rows[index] = Some(row),
            None => todo.push(index),
        }
    }
    let skipped = members.len() - todo.len();
    if skipped > 0 {
        eprintln!("skipped {skipped} already checked (--force checks them again)");
    }
    let ran = todo.len();
    run_checks(&members, todo, args.jobs.max(1) as usize, &settings, &mut rows);
    let rows: Vec<ClassRow> = rows.into_iter().flatten().collect();
    class_report::write(&args.out, &rows, args.lang)
        .map_err(|e| CliError { code: 1, message: e.to_string() })?;
    let secs = started.elapsed().as_secs_f64();
    summary(&rows, skipped, ran, secs, &args.out);
    Ok(())
}

fn summary(rows: &[ClassRow], skipped: usize, ran: usize, secs: f64, out: &Path) {
    let counts: Vec<String> = Status::ALL
        .iter()
        .map(|s| (s, rows.iter().filter(|r| r.status == *s).count()))
        .filter(|(_, n)| *n > 0)
        .map(|(s, n)| format!("{n} {}", s.label()))
        .collect();
    println!("{} submissions: {}", rows.len(), counts.join(", "));
    if skipped > 0 {
        println!("skipped {skipped} already checked");
    }
    if ran > 0 {
        let per_minute = 60.0 * ran as f64 / secs.max(1e-3);
        println!("{ran} submissions in {secs:.1} s ({per_minute:.1} per minute)");
    }
    println!(
        "wrote {}, {} and {}",
        out.join(class_report::INDEX_EN).display(),
        out.join(class_report::INDEX_ZH).display(),
        out.join(class_report::GRADES).display()
    );
}
