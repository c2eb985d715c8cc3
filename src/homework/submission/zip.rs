//! A zip reader written from PKWARE's APPNOTE, for untrusted archives held in memory.
//!
//! The whole central directory is checked before anything is trusted (names, sizes, offsets,
//! overlaps); entries are inflated only on request, with a hard cap, and their CRC-32 checked.
//! Nothing is ever written anywhere. Errors are one-line messages meant to follow the archive's
//! name ("archive.zip: entry x/y.glsl is encrypted").

use super::Limits;

const EOCD_SIGNATURE: u32 = 0x0605_4b50;
const CENTRAL_SIGNATURE: u32 = 0x0201_4b50;
const LOCAL_SIGNATURE: u32 = 0x0403_4b50;
const ZIP64_LOCATOR_SIGNATURE: u32 = 0x0706_4b50;
const EOCD_BYTES: usize = 22;
const CENTRAL_HEADER_BYTES: usize = 46;
const LOCAL_HEADER_BYTES: usize = 30;
const ZIP64_LOCATOR_BYTES: usize = 20;
/// The end record plus the longest comment it can carry: where the record must start.
const EOCD_SEARCH_BYTES: usize = EOCD_BYTES + u16::MAX as usize;
/// The ratio check only applies to entries above this size: small files compress well legitimately.
const RATIO_CHECKED_ABOVE_BYTES: u64 = 1 << 20;
/// Longest entry name shown in a message, so a hostile 64 KiB name keeps the message readable.
const SHOWN_NAME_CHARS: usize = 160;

const FLAG_ENCRYPTED: u16 = 1;
const FLAG_STRONG_ENCRYPTION: u16 = 1 << 6;
const FLAG_UTF8_NAME: u16 = 1 << 11;
const FLAG_MASKED_HEADERS: u16 = 1 << 13;
const METHOD_STORED: u16 = 0;
const METHOD_DEFLATE: u16 = 8;

/// One entry, as its central directory header and local header agree on it.
#[derive(Debug)]
pub(super) struct Entry {
    /// '/'-separated, relative, with no empty, `.` or `..` components.
    pub name: String,
    pub is_dir: bool,
    method: u16,
    crc32: u32,
    compressed_bytes: u64,
    uncompressed_bytes: u64,
    /// Where the entry's local header starts; its data follows the header, up to `data_end`.
    local_start: usize,
    data_start: usize,
    data_end: usize,
}

/// An archive whose directory passed every check; entries are read from `bytes` on demand.
pub(super) struct Archive<'a> {
    bytes: &'a [u8],
    pub entries: Vec<Entry>,
}

/// A fixed-size header already known to be in bounds; out-of-range reads give 0 instead of panicking.
struct Fields<'a>(&'a [u8]);

impl Fields<'_> {
    fn u16(&self, at: usize) -> u16 {
        self.0
            .get(at..at.saturating_add(2))
            .and_then(|s| <[u8; 2]>::try_from(s).ok())
            .map_or(0, u16::from_le_bytes)
    }
    fn u32(&self, at: usize) -> u32 {
        self.0
            .get(at..at.saturating_add(4))
            .and_then(|s| <[u8; 4]>::try_from(s).ok())
            .map_or(0, u32::from_le_bytes)
    }
}

/// `len` bytes at `at`, or None when any of it lies outside `bytes`.
fn slice_at(bytes: &[u8], at: usize, len: usize) -> Option<&[u8]> {
    bytes.get(at..at.checked_add(len)?)
}

/// A name fit for a one-line message: control characters escaped, long names shortened.
pub(super) fn shown(name: &str) -> String {
    let mut out = String::new();
    for (i, c) in name.chars().enumerate() {
        if i == SHOWN_NAME_CHARS {
            out.push('…');
            break;
        }
        if c.is_control() {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    out
}

/// Decodes an entry name: UTF-8 when flagged or when it happens to be valid UTF-8 (macOS and
/// many Windows tools write UTF-8 without the flag), else CP437 with only ASCII kept.
fn decode_name(raw: &[u8], flags: u16) -> String {
    if flags & FLAG_UTF8_NAME != 0 {
        return String::from_utf8_lossy(raw).into_owned();
    }
    match std::str::from_utf8(raw) {
        Ok(text) => text.to_owned(),
        Err(_) => raw.iter().map(|&b| if b.is_ascii() { char::from(b) } else { '?' }).collect(),
    }
}

/// Checks a decoded name and returns it '/'-separated without empty or `.` components.
/// Refuses names that could point outside the submission if anyone ever extracted them.
pub(super) fn clean_name(name: &str) -> Result<String, String> {
    if name.contains('\0') {
        return Err(format!("entry {} has a NUL byte in its name", shown(name)));
    }
    let slashed = name.replace('\\', "/");
    let mut chars = slashed.chars();
    let drive = matches!((chars.next(), chars.next()), (Some(d), Some(':')) if d.is_ascii_alphabetic());
    if slashed.starts_with('/') || drive {
        return Err(format!("entry {} has an absolute path", shown(name)));
    }
    let mut parts = Vec::new();
    for part in slashed.split('/') {
        match part {
            ".." => {
                return Err(format!("entry {} would land outside the submission", shown(name)));
            }
            "" | "." => {}
            _ => parts.push(part),
        }
    }
    Ok(parts.join("/"))
}

/// Finds the end of central directory record: the last signature whose comment ends the file.
fn find_eocd(bytes: &[u8]) -> Result<usize, String> {
    let last = bytes
        .len()
        .checked_sub(EOCD_BYTES)
        .ok_or_else(|| format!("is too short to be a zip ({} bytes)", bytes.len()))?;
    let first = bytes.len().saturating_sub(EOCD_SEARCH_BYTES);
    for at in (first..=last).rev() {
        let Some(record) = slice_at(bytes, at, EOCD_BYTES) else {
            continue;
        };
        let fields = Fields(record);
        if fields.u32(0) != EOCD_SIGNATURE {
            continue;
        }
        let comment_bytes = usize::from(fields.u16(20));
        if at.checked_add(EOCD_BYTES).and_then(|end| end.checked_add(comment_bytes)) == Some(bytes.len()) {
            return Ok(at);
        }
    }
    Err("is not a zip, or is cut short (no end of central directory record)".to_owned())
}

impl<'a> Archive<'a> {
    /// Parses and checks the whole directory; any doubt refuses the whole archive.
    pub(super) fn parse(bytes: &'a [u8], limits: &Limits) -> Result<Self, String> {
        let archive_bytes = u64::try_from(bytes.len()).unwrap_or(u64::MAX);
        if archive_bytes > limits.archive_bytes {
            return Err(format!(
                "is {archive_bytes} bytes, over the limit of {} bytes",
                limits.archive_bytes
            ));
        }
        let eocd_at = find_eocd(bytes)?;
        let zip64_locator = eocd_at
            .checked_sub(ZIP64_LOCATOR_BYTES)
            .and_then(|at| slice_at(bytes, at, 4))
            .is_some_and(|s| Fields(s).u32(0) == ZIP64_LOCATOR_SIGNATURE);
        let eocd = Fields(slice_at(bytes, eocd_at, EOCD_BYTES).unwrap_or_default());
        let (disk, cd_disk) = (eocd.u16(4), eocd.u16(6));
        let (disk_entries, total_entries) = (eocd.u16(8), eocd.u16(10));
        let (cd_bytes, cd_offset) = (eocd.u32(12), eocd.u32(16));
        if zip64_locator || total_entries == u16::MAX || cd_bytes == u32::MAX || cd_offset == u32::MAX {
            return Err("uses ZIP64, which is not supported (re-zip it without ZIP64)".to_owned());
        }
        if disk != 0 || cd_disk != 0 || disk_entries != total_entries {
            return Err("spans several disks, which is not supported".to_owned());
        }
        if total_entries == 0 {
            return Err("holds no entries".to_owned());
        }
        if usize::from(total_entries) > limits.entries {
            return Err(format!("has {total_entries} entries, over the limit of {}", limits.entries));
        }
        let cd_start = usize::try_from(cd_offset).map_err(|_| "is too large".to_owned())?;
        let cd_end = usize::try_from(cd_bytes)
            .ok()
            .and_then(|n| cd_start.checked_add(n))
            .filter(|&end| end <= eocd_at)
            .ok_or_else(|| "has its central directory outside the file".to_owned())?;
        let directory = bytes.get(cd_start..cd_end).unwrap_or_default();

        let mut entries = Vec::with_capacity(usize::from(total_entries));
        let mut declared_total_bytes: u64 = 0;
        let mut at = 0usize;
        for index in 0..total_entries {
            let header = slice_at(directory, at, CENTRAL_HEADER_BYTES)
                .filter(|h| Fields(h).u32(0) == CENTRAL_SIGNATURE)
                .ok_or_else(|| {
                    format!("has a damaged central directory (entry {index} of {total_entries})")
                })?;
            let header = Fields(header);
            let name_bytes = usize::from(header.u16(28));
            let extra_bytes = usize::from(header.u16(30));
            let comment_bytes = usize::from(header.u16(32));
            let name_at = at.saturating_add(CENTRAL_HEADER_BYTES);
            let raw_name = slice_at(directory, name_at, name_bytes).ok_or_else(|| {
                format!("has a damaged central directory (entry {index} of {total_entries})")
            })?;
            at = name_at.saturating_add(name_bytes).saturating_add(extra_bytes).saturating_add(comment_bytes);
            let entry = Self::check_entry(bytes, &header, raw_name, cd_start, limits)?;
            declared_total_bytes = declared_total_bytes.saturating_add(entry.uncompressed_bytes);
            if declared_total_bytes > limits.total_uncompressed_bytes {
                return Err(format!(
                    "declares more than {} bytes uncompressed in all (a zip bomb?)",
                    limits.total_uncompressed_bytes
                ));
            }
            entries.push(entry);
        }
        check_overlaps(&entries)?;
        Ok(Archive { bytes, entries })
    }

    /// Checks one central directory header against the limits and against its local header.
    fn check_entry(
        bytes: &[u8],
        header: &Fields<'_>,
        raw_name: &[u8],
        cd_start: usize,
        limits: &Limits,
    ) -> Result<Entry, String> {
        let flags = header.u16(8);
        let method = header.u16(10);
        let crc32 = header.u32(16);
        let (compressed, uncompressed) = (header.u32(20), header.u32(24));
        let disk_start = header.u16(34);
        let local_offset = header.u32(42);
        if raw_name.contains(&0) {
            let lossy = String::from_utf8_lossy(raw_name);
            return Err(format!("entry {} has a NUL byte in its name", shown(&lossy)));
        }
        let decoded = decode_name(raw_name, flags);
        let name = clean_name(&decoded)?;
        let show = shown(&decoded);
        if flags & (FLAG_ENCRYPTED | FLAG_STRONG_ENCRYPTION | FLAG_MASKED_HEADERS) != 0 {
            return Err(format!("entry {show} is encrypted"));
        }
        if compressed == u32::MAX || uncompressed == u32::MAX || local_offset == u32::MAX {
            return Err(format!("entry {show} uses ZIP64 sizes, which are not supported"));
        }
        if disk_start != 0 {
            return Err(format!("entry {show} is on another disk, which is not supported"));
        }
        let (compressed_bytes, uncompressed_bytes) = (u64::from(compressed), u64::from(uncompressed));
        if uncompressed_bytes > RATIO_CHECKED_ABOVE_BYTES
            && uncompressed_bytes > compressed_bytes.saturating_mul(limits.compression_ratio)
        {
            return Err(format!(
                "entry {show} declares {uncompressed_bytes} bytes from {compressed_bytes} compressed \
                 (over {}x): refused as a zip bomb",
                limits.compression_ratio
            ));
        }

        let damaged = || format!("entry {show} has no local header where the central directory puts it");
        let local_at = usize::try_from(local_offset).map_err(|_| damaged())?;
        let local = slice_at(bytes, local_at, LOCAL_HEADER_BYTES)
            .filter(|h| Fields(h).u32(0) == LOCAL_SIGNATURE)
            .map(Fields)
            .ok_or_else(damaged)?;
        if local.u16(6) & FLAG_ENCRYPTED != 0 {
            return Err(format!("entry {show} is encrypted"));
        }
        let local_name_at = local_at.saturating_add(LOCAL_HEADER_BYTES);
        let local_name_bytes = usize::from(local.u16(26));
        let local_name = slice_at(bytes, local_name_at, local_name_bytes).ok_or_else(damaged)?;
        if local_name != raw_name || local.u16(8) != method {
            return Err(format!("entry {show}: its local header disagrees with the central directory"));
        }
        let outside = || format!("entry {show} has its data outside the file");
        let data_start = local_name_at
            .checked_add(local_name_bytes)
            .and_then(|n| n.checked_add(usize::from(local.u16(28))))
            .ok_or_else(outside)?;
        let data_end = usize::try_from(compressed)
            .ok()
            .and_then(|n| data_start.checked_add(n))
            .filter(|&end| end <= cd_start)
            .ok_or_else(outside)?;
        Ok(Entry {
            is_dir: decoded.ends_with('/') || decoded.ends_with('\\'),
            name,
            method,
            crc32,
            compressed_bytes,
            uncompressed_bytes,
            local_start: local_at,
            data_start,
            data_end,
        })
    }

    /// The entry's bytes: inflated with a cap at its declared size (and `file_bytes`),
    /// and checked against its CRC-32. Sizes come from the central directory, which also
    /// covers entries whose local header defers them to a data descriptor (flag bit 3).
    pub(super) fn read(&self, entry: &Entry, file_bytes: u64) -> Result<Vec<u8>, String> {
        let show = shown(&entry.name);
        if entry.uncompressed_bytes > file_bytes {
            return Err(format!(
                "entry {show} is {} bytes, over the limit of {file_bytes} bytes for one file",
                entry.uncompressed_bytes
            ));
        }
        let declared_bytes =
            usize::try_from(entry.uncompressed_bytes).map_err(|_| format!("entry {show} is too large"))?;
        let data = self
            .bytes
            .get(entry.data_start..entry.data_end)
            .ok_or_else(|| format!("entry {show} has its data outside the file"))?;
        let out = match entry.method {
            METHOD_STORED => {
                if entry.compressed_bytes != entry.uncompressed_bytes {
                    return Err(format!("entry {show} is stored but its two sizes differ"));
                }
                data.to_vec()
            }
            METHOD_DEFLATE => {
                inflate_capped(data, declared_bytes).map_err(|why| format!("entry {show} {why}"))?
            }
            other => {
                return Err(format!(
                    "entry {show} uses compression method {other} (only stored and deflate are read)"
                ));
            }
        };
        if crc32fast::hash(&out) != entry.crc32 {
            return Err(format!("entry {show} fails its CRC-32 check (damaged)"));
        }
        Ok(out)
    }
}

/// Refuses entries whose local header-plus-data ranges overlap: the trick that makes a small
/// archive expand many times by pointing many entries at the same compressed data.
fn check_overlaps(entries: &[Entry]) -> Result<(), String> {
    let mut ranges: Vec<&Entry> = entries.iter().collect();
    ranges.sort_by_key(|e| (e.local_start, e.data_end));
    for pair in ranges.windows(2) {
        if let [first, second] = pair
            && second.local_start < first.data_end
        {
            return Err(format!(
                "entries {} and {} overlap (a zip bomb trick)",
                shown(&first.name),
                shown(&second.name)
            ));
        }
    }
    Ok(())
}

/// Inflates raw deflate data into at most `declared + 1` bytes, so a stream longer than
/// declared is caught without ever holding more than the cap.
fn inflate_capped(data: &[u8], declared_bytes: usize) -> Result<Vec<u8>, String> {
    use miniz_oxide::inflate::{TINFLStatus, decompress_to_vec_with_limit};
    if data.is_empty() {
        return Err("has no deflate data".to_owned());
    }
    let cap_bytes = declared_bytes.saturating_add(1);
    match decompress_to_vec_with_limit(data, cap_bytes) {
        Ok(out) if out.len() == declared_bytes => Ok(out),
        Ok(out) if out.len() > declared_bytes => {
            Err(format!("inflates past its declared {declared_bytes} bytes"))
        }
        Ok(out) => Err(format!("inflates to {} bytes, not the declared {declared_bytes}", out.len())),
        Err(e) if e.status == TINFLStatus::HasMoreOutput => {
            Err(format!("inflates past its declared {declared_bytes} bytes"))
        }
        Err(_) => Err("has damaged or cut-short deflate data".to_owned()),
    }
}
