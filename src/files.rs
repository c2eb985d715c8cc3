//! Files written whole or not at all: a temporary file in the same folder, then a rename, so a
//! failure or a crash never leaves a half-written file behind. Files read with limits, and the
//! one way the app looks at files: on the desktop the disk; in a page, which has no file system,
//! the copy of the shipped files built into the binary, by their paths relative to the checkout
//! (which `crate::shipped_path` gives there).

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{SystemTime, UNIX_EPOCH};

/// Write `bytes` to `path` atomically; the error says why, without the path (callers name it).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), String> {
    if IN_PAGE {
        return Err("a page has no folders to write to".into());
    }
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    if !dir.is_dir() {
        return Err(format!("folder {} does not exist", dir.display()));
    }
    let name = path.file_name().ok_or("not a file name")?;
    // Unique per process and call: two writers of one path (threads, or processes of another
    // PID namespace sharing the folder) never share a temporary file.
    static CALLS: AtomicU64 = AtomicU64::new(0);
    let call = CALLS.fetch_add(1, Ordering::Relaxed);
    let nanos = SystemTime::now().duration_since(UNIX_EPOCH).map_or(0, |d| d.subsec_nanos());
    let tmp = dir.join(format!(".{}.tmp-{}-{call}-{nanos}", name.to_string_lossy(), std::process::id()));
    let result = std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&tmp)
        .and_then(|mut file| file.write_all(bytes))
        .and_then(|_| std::fs::rename(&tmp, path));
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(e.to_string());
    }
    Ok(())
}

/// Most bytes a scene or lesson file may have. They are a page or two of text; a file near this
/// size is not one, and reading it whole would only fill the memory.
pub const MAX_TEXT_FILE_BYTES: u64 = 16 << 20;

/// Most bytes an OBJ or MTL file may have (scanned models run to hundreds of megabytes).
pub const MAX_MESH_FILE_BYTES: u64 = 2 << 30;

/// Read a file the user named, whole. What is not a regular file is refused before it is opened:
/// a folder, a device such as /dev/zero (which never ends) or a FIFO (whose open blocks until a
/// writer comes). So is a file of more than `max_bytes`. The error says why, without the path
/// (callers name it).
pub fn read_input(path: &Path, max_bytes: u64) -> Result<Vec<u8>, String> {
    use std::io::Read;
    let too_big = || format!("larger than the {} MiB a file may have here", max_bytes >> 20);
    if check_regular_file(path)? > max_bytes {
        return Err(too_big());
    }
    if let Some(bytes) = built_in(path) {
        return Ok(bytes.into_owned());
    }
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|file| file.take(max_bytes.saturating_add(1)).read_to_end(&mut bytes))
        .map_err(|e| e.to_string())?;
    if bytes.len() as u64 > max_bytes {
        return Err(too_big());
    }
    Ok(bytes)
}

/// `path` names a regular file (following symbolic links), of this many bytes; the error says what
/// it is instead.
pub fn check_regular_file(path: &Path) -> Result<u64, String> {
    if let Some(bytes) = handed(path) {
        return Ok(bytes.len() as u64);
    }
    if IN_PAGE {
        return match built_in(path) {
            Some(bytes) => Ok(bytes.len() as u64),
            None if crate::built_in::is_folder(path) => Err("is a folder, not a file".into()),
            None => Err("not among the files built into the page".into()),
        };
    }
    let metadata = std::fs::metadata(path).map_err(|e| e.to_string())?;
    if metadata.is_dir() {
        Err("is a folder, not a file".into())
    } else if !metadata.is_file() {
        Err("is not a regular file (a device or a pipe?)".into())
    } else {
        Ok(metadata.len())
    }
}

/// Files are the copy built into the binary (a page), not the disk.
const IN_PAGE: bool = cfg!(target_arch = "wasm32");

/// The folder files handed over as bytes open under (see [`hand_over`]).
pub const HANDED_OVER: &str = "handed-over";
/// Files handed over kept at once (the oldest go first): a student's shader, or a model with its
/// material and textures.
const HANDED_OVER_KEPT: usize = 16;

/// Files handed to the app as bytes, not paths (what a page is given when a file is dropped on
/// it or picked in its file dialog), by the path they open under. They are read before the disk
/// and the built-in copy, so everything that opens a path opens them, and a model finds the
/// material and textures dropped with it.
static HANDED: std::sync::Mutex<Vec<(PathBuf, std::sync::Arc<[u8]>)>> = std::sync::Mutex::new(Vec::new());

/// Keep `bytes` as the file `name` (its last path component, after `/` or `\\`) and give the path it opens under,
/// `handed-over/NAME`. A file of the same name handed over before is replaced.
pub fn hand_over(name: &str, bytes: &[u8]) -> PathBuf {
    // The last component, whichever system's separator the sender used.
    let name = name.rsplit(['/', '\\']).next().filter(|n| !n.is_empty() && *n != "." && *n != "..");
    let path = Path::new(HANDED_OVER).join(name.unwrap_or("file"));
    if let Ok(mut handed) = HANDED.lock() {
        handed.retain(|(p, _)| *p != path);
        if handed.len() >= HANDED_OVER_KEPT {
            handed.remove(0);
        }
        handed.push((path.clone(), bytes.into()));
    }
    path
}

/// `path` names a file handed over as bytes.
pub fn is_handed_over(path: &Path) -> bool {
    handed(path).is_some()
}

fn handed(path: &Path) -> Option<std::sync::Arc<[u8]>> {
    let handed = HANDED.lock().ok()?;
    handed.iter().find(|(p, _)| p == path).map(|(_, bytes)| bytes.clone())
}

/// The bytes of `path` where they are not on the disk: handed over, or built into a page.
fn built_in(path: &Path) -> Option<std::borrow::Cow<'static, [u8]>> {
    if let Some(bytes) = handed(path) {
        return Some(std::borrow::Cow::Owned(bytes.to_vec()));
    }
    if IN_PAGE { crate::built_in::file(path).map(std::borrow::Cow::Borrowed) } else { None }
}

/// `path` is there (a file or a folder).
pub fn exists(path: &Path) -> bool {
    if IN_PAGE {
        built_in(path).is_some() || crate::built_in::is_folder(path)
    } else {
        is_handed_over(path) || path.exists()
    }
}

/// `path` is a file (following symbolic links).
pub fn is_file(path: &Path) -> bool {
    if IN_PAGE { built_in(path).is_some() } else { is_handed_over(path) || path.is_file() }
}

/// The paths of what is in the folder `dir`, in no particular order.
pub fn folder_entries(dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    if IN_PAGE {
        return match crate::built_in::is_folder(dir) {
            true => Ok(crate::built_in::files_in(dir)),
            false => Err(std::io::Error::new(
                std::io::ErrorKind::NotFound,
                "no such folder among the files built into the page",
            )),
        };
    }
    Ok(std::fs::read_dir(dir)?.filter_map(|e| e.ok().map(|e| e.path())).collect())
}

/// A file opened to be read in pieces (a decoder reading a header first): buffered from the disk,
/// or the built-in bytes in a page.
pub fn open_input(path: &Path) -> std::io::Result<Box<dyn ReadSeek>> {
    match built_in(path) {
        Some(bytes) => Ok(Box::new(std::io::Cursor::new(bytes))),
        None if IN_PAGE => {
            Err(std::io::Error::new(std::io::ErrorKind::NotFound, "not among the files built into the page"))
        }
        None => Ok(Box::new(std::io::BufReader::new(std::fs::File::open(path)?))),
    }
}

/// A file's bytes, whole (what the caller limits itself).
pub fn read(path: &Path) -> std::io::Result<Vec<u8>> {
    match built_in(path) {
        Some(bytes) => Ok(bytes.into_owned()),
        None if IN_PAGE => {
            Err(std::io::Error::new(std::io::ErrorKind::NotFound, "not among the files built into the page"))
        }
        None => std::fs::read(path),
    }
}

/// What [`open_input`] gives.
pub trait ReadSeek: std::io::BufRead + std::io::Seek {}
impl<T: std::io::BufRead + std::io::Seek> ReadSeek for T {}

/// [`read_input`] as UTF-8 text; the error names the first byte that is not.
pub fn read_input_text(path: &Path, max_bytes: u64) -> Result<String, String> {
    String::from_utf8(read_input(path, max_bytes)?)
        .map_err(|e| format!("not UTF-8 text (byte {} is not)", e.utf8_error().valid_up_to()))
}

/// Text from a file, or a file's name, as it goes into a one-line message: line breaks and other
/// control characters are written as escapes (`\n`, `\r`, `\u{1b}`), so the message stays on
/// its line and cannot move a terminal's cursor.
pub struct OneLine<'a>(pub &'a str);

impl std::fmt::Display for OneLine<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        use std::fmt::Write;
        for c in self.0.chars() {
            if c.is_control() || matches!(c, '\u{2028}' | '\u{2029}') {
                write!(f, "{}", c.escape_default())?;
            } else {
                f.write_char(c)?;
            }
        }
        Ok(())
    }
}

/// A path as [`OneLine`] text.
pub fn path_line(path: &Path) -> String {
    OneLine(&path.to_string_lossy()).to_string()
}

/// FNV-1a, 64 bits: a content hash stable across builds and platforms (std's hasher promises
/// neither), for fingerprints and cache folders' names.
pub struct Fnv1a(u64);

impl Fnv1a {
    pub fn new() -> Self {
        Fnv1a(0xcbf2_9ce4_8422_2325)
    }

    pub fn add(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
        }
    }

    pub fn value(&self) -> u64 {
        self.0
    }
}

impl Default for Fnv1a {
    fn default() -> Self {
        Self::new()
    }
}
