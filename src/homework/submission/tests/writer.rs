//! A tiny zip writer for the tests: just enough of the format to build good and bad archives.

/// One entry to write; the fields past `data` bend the format for the hostile cases.
#[derive(Clone, Default)]
pub struct Spec {
    pub name: Vec<u8>,
    pub data: Vec<u8>,
    pub deflate: bool,
    pub flags: u16,
    /// Sizes and CRC after the data, zeros in the local header (flag bit 3).
    pub descriptor: bool,
    pub method: Option<u16>,
    pub declared_bytes: Option<u32>,
    pub compressed: Option<Vec<u8>>,
    pub crc: Option<u32>,
    pub local_name: Option<Vec<u8>>,
}

pub fn spec(name: &str, data: &[u8]) -> Spec {
    Spec { name: name.as_bytes().to_vec(), data: data.to_vec(), ..Spec::default() }
}

pub fn deflated(name: &str, data: &[u8]) -> Spec {
    Spec { deflate: true, ..spec(name, data) }
}

fn put16(out: &mut Vec<u8>, v: u16) {
    out.extend_from_slice(&v.to_le_bytes());
}

fn put32(out: &mut Vec<u8>, v: u32) {
    out.extend_from_slice(&v.to_le_bytes());
}

fn len32(n: usize) -> u32 {
    u32::try_from(n).unwrap_or(u32::MAX)
}

fn len16(n: usize) -> u16 {
    u16::try_from(n).unwrap_or(u16::MAX)
}

/// A local header; `sizes` is (crc, compressed, uncompressed).
pub fn local_header(name: &[u8], flags: u16, method: u16, sizes: (u32, u32, u32)) -> Vec<u8> {
    let mut out = Vec::new();
    put32(&mut out, 0x0403_4b50);
    put16(&mut out, 20);
    put16(&mut out, flags);
    put16(&mut out, method);
    put32(&mut out, 0); // time and date
    put32(&mut out, sizes.0);
    put32(&mut out, sizes.1);
    put32(&mut out, sizes.2);
    put16(&mut out, len16(name.len()));
    put16(&mut out, 0);
    out.extend_from_slice(name);
    out
}

pub fn central_header(name: &[u8], flags: u16, method: u16, sizes: (u32, u32, u32), offset: u32) -> Vec<u8> {
    let mut out = Vec::new();
    put32(&mut out, 0x0201_4b50);
    put16(&mut out, 20);
    put16(&mut out, 20);
    put16(&mut out, flags);
    put16(&mut out, method);
    put32(&mut out, 0);
    put32(&mut out, sizes.0);
    put32(&mut out, sizes.1);
    put32(&mut out, sizes.2);
    put16(&mut out, len16(name.len()));
    put16(&mut out, 0); // extra
    put16(&mut out, 0); // comment
    put16(&mut out, 0); // disk
    put16(&mut out, 0); // internal attributes
    put32(&mut out, 0); // external attributes
    put32(&mut out, offset);
    out.extend_from_slice(name);
    out
}

pub fn end_record(entries: u16, cd_bytes: u32, cd_offset: u32) -> Vec<u8> {
    let mut out = Vec::new();
    put32(&mut out, 0x0605_4b50);
    put32(&mut out, 0); // disks
    put16(&mut out, entries);
    put16(&mut out, entries);
    put32(&mut out, cd_bytes);
    put32(&mut out, cd_offset);
    put16(&mut out, 0);
    out
}

/// Joins local parts and central headers into an archive.
pub fn assemble(body: Vec<u8>, central: &[Vec<u8>]) -> Vec<u8> {
    let mut out = body;
    let cd_offset = len32(out.len());
    let cd: Vec<u8> = central.concat();
    out.extend_from_slice(&cd);
    out.extend(end_record(len16(central.len()), len32(cd.len()), cd_offset));
    out
}

pub fn build(specs: &[Spec]) -> Vec<u8> {
    let mut body = Vec::new();
    let mut central = Vec::new();
    for s in specs {
        let compressed = match (&s.compressed, s.deflate) {
            (Some(raw), _) => raw.clone(),
            (None, true) => miniz_oxide::deflate::compress_to_vec(&s.data, 6),
            (None, false) => s.data.clone(),
        };
        let method = s.method.unwrap_or(if s.deflate { 8 } else { 0 });
        let crc = s.crc.unwrap_or_else(|| crc32fast::hash(&s.data));
        let sizes = (crc, len32(compressed.len()), s.declared_bytes.unwrap_or(len32(s.data.len())));
        let flags = s.flags | if s.descriptor { 8 } else { 0 };
        let offset = len32(body.len());
        let local_sizes = if s.descriptor { (0, 0, 0) } else { sizes };
        body.extend(local_header(s.local_name.as_ref().unwrap_or(&s.name), flags, method, local_sizes));
        body.extend_from_slice(&compressed);
        if s.descriptor {
            put32(&mut body, 0x0807_4b50);
            put32(&mut body, sizes.0);
            put32(&mut body, sizes.1);
            put32(&mut body, sizes.2);
        }
        central.push(central_header(&s.name, flags, method, sizes, offset));
    }
    assemble(body, &central)
}

/// Raw deflate (one fixed-Huffman block) producing `total_bytes` zeros, written bit by bit so a
/// 100 MB bomb costs ~650 KB and no time to make.
pub fn zeros_stream(total_bytes: usize) -> Vec<u8> {
    let mut bits = Bits::default();
    bits.put(1, 1); // final block
    bits.put(1, 2); // fixed Huffman codes
    let matches = total_bytes.saturating_sub(1) / 258;
    let literals = total_bytes.saturating_sub(1) % 258 + usize::from(total_bytes > 0);
    for _ in 0..literals {
        bits.code(0x30, 8); // literal 0
    }
    for _ in 0..matches {
        bits.code(0xC5, 8); // length 258 (symbol 285)
        bits.code(0, 5); // distance 1
    }
    bits.code(0, 7); // end of block (symbol 256)
    bits.finish()
}

#[derive(Default)]
struct Bits {
    out: Vec<u8>,
    acc: u32,
    count: u32,
}

impl Bits {
    /// Plain fields go least significant bit first.
    fn put(&mut self, value: u32, count: u32) {
        for i in 0..count {
            self.acc |= ((value >> i) & 1) << self.count;
            self.count += 1;
            if self.count == 8 {
                self.out.push(self.acc as u8);
                self.acc = 0;
                self.count = 0;
            }
        }
    }

    /// Huffman codes go most significant bit first.
    fn code(&mut self, code: u32, len: u32) {
        for i in (0..len).rev() {
            self.put((code >> i) & 1, 1);
        }
    }

    fn finish(mut self) -> Vec<u8> {
        if self.count > 0 {
            self.out.push(self.acc as u8);
        }
        self.out
    }
}

#[test]
fn zeros_stream_inflates_to_zeros() {
    for n in [1usize, 2, 258, 259, 1000, 10_000] {
        let out = miniz_oxide::inflate::decompress_to_vec(&zeros_stream(n)).unwrap_or_default();
        assert_eq!(out, vec![0u8; n], "{n}");
    }
}
