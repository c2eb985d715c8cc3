//! Archives built to hurt: each must be refused on one line naming the archive, quickly.

use super::writer::{self, Spec, build, deflated, spec};
use super::*;
use std::time::{Duration, Instant};

const ARCHIVE: &str = "class/alice.zip";

fn refused(bytes: &[u8], expected: &str) {
    refused_with(bytes, Limits::default(), expected);
}

fn refused_with(bytes: &[u8], limits: Limits, expected: &str) {
    let started = Instant::now();
    assert_refused(read_zip_bytes(ARCHIVE, bytes, limits), ARCHIVE, expected);
    assert!(started.elapsed() < Duration::from_secs(2), "took {:?}", started.elapsed());
}

/// A good submission with one more entry.
fn with(extra: Spec) -> Vec<u8> {
    let mut files: Vec<Spec> = framework("homework1/").iter().map(|(p, b)| deflated(p, b)).collect();
    files.push(extra);
    build(&files)
}

#[test]
fn escaping_names() {
    refused(&with(spec("../../evil.glsl", b"x")), "entry ../../evil.glsl would land outside the submission");
    refused(&with(spec("a\\..\\..\\evil", b"x")), "entry a\\..\\..\\evil would land outside the submission");
    refused(&with(spec("homework1/..", b"")), "would land outside");
    refused(&with(spec("/etc/passwd", b"x")), "entry /etc/passwd has an absolute path");
    refused(&with(spec("C:\\Windows\\evil", b"x")), "has an absolute path");
    refused(&with(spec("c:evil", b"x")), "has an absolute path");
    refused(&with(spec("\\\\server\\share\\evil", b"x")), "has an absolute path");
    refused(&with(spec("evil\0.glsl", b"x")), "has a NUL byte in its name");
    refused(&with(spec("evil\n/../x", b"x")), "entry evil\\n/../x would land outside");
}

#[test]
fn zip_bombs() {
    // Small stream, huge declared size: refused from the directory alone.
    let small = miniz_oxide::deflate::compress_to_vec(&vec![0u8; 1 << 20], 9);
    let declared = Spec {
        compressed: Some(small),
        declared_bytes: Some(100_000_000),
        ..deflated("homework1/zeros.bin", &[])
    };
    refused(&with(declared), "entry homework1/zeros.bin declares 100000000 bytes from");

    // A real 100 MB stream (~650 KB, under the ratio) where a phongFragment.glsl should be.
    let zeros = writer::zeros_stream(100_000_000);
    let honest = Spec {
        compressed: Some(zeros.clone()),
        declared_bytes: Some(100_000_000),
        crc: Some(0),
        ..deflated("phongShader/phongFragment.glsl", &[])
    };
    refused(
        &build(&[honest]),
        "entry phongShader/phongFragment.glsl is 100000000 bytes, over the limit of 1048576 bytes for one file",
    );

    // The same stream declared small: inflating stops at the declared size.
    let lying = Spec {
        compressed: Some(zeros),
        declared_bytes: Some(1000),
        crc: Some(crc32fast::hash(&[0u8; 1000])),
        ..deflated("phongShader/phongFragment.glsl", &[])
    };
    refused(&build(&[lying]), "entry phongShader/phongFragment.glsl inflates past its declared 1000 bytes");

    // Declared larger than the stream, or a wrong CRC.
    let short = Spec { declared_bytes: Some(50), ..deflated("phongFragment.glsl", b"void main() {}") };
    refused(&build(&[short]), "inflates to 14 bytes, not the declared 50");
    let bad_crc = Spec { crc: Some(1), ..deflated("phongFragment.glsl", b"void main() {}") };
    refused(&build(&[bad_crc]), "entry phongFragment.glsl fails its CRC-32 check");
    let stored_crc = Spec { crc: Some(1), ..spec("phongFragment.glsl", b"void main() {}") };
    refused(&build(&[stored_crc]), "fails its CRC-32 check");

    // Many entries declaring a lot in all.
    let many: Vec<Spec> = (0..300)
        .map(|i| Spec {
            declared_bytes: Some(1_000_000),
            compressed: Some(vec![3, 0]),
            ..deflated(&format!("f{i}"), &[])
        })
        .collect();
    refused(&build(&many), "declares more than 268435456 bytes uncompressed in all");
}

#[test]
fn overlapping_entries() {
    // Entry "a" stores bytes that are themselves entry "b"'s local header and data.
    let b_data = b"// b\n";
    let b_local =
        [writer::local_header(b"b", 0, 0, (crc32fast::hash(b_data), 5, 5)), b_data.to_vec()].concat();
    let a_local = writer::local_header(
        b"a",
        0,
        0,
        (crc32fast::hash(&b_local), b_local.len() as u32, b_local.len() as u32),
    );
    let b_offset = a_local.len() as u32;
    let central = [
        writer::central_header(
            b"a",
            0,
            0,
            (crc32fast::hash(&b_local), b_local.len() as u32, b_local.len() as u32),
            0,
        ),
        writer::central_header(b"b", 0, 0, (crc32fast::hash(b_data), 5, 5), b_offset),
    ];
    let zip = writer::assemble([a_local, b_local].concat(), &central);
    refused(&zip, "entries a and b overlap");

    // Two directory entries sharing one local header.
    let local = writer::local_header(b"x", 0, 0, (0, 0, 0));
    let twice =
        [writer::central_header(b"x", 0, 0, (0, 0, 0), 0), writer::central_header(b"x", 0, 0, (0, 0, 0), 0)];
    refused(&writer::assemble(local, &twice), "entries x and x overlap");
}

#[test]
fn counts_and_sizes() {
    let many: Vec<Spec> = (0..20).map(|i| spec(&format!("f{i}.txt"), b"x")).collect();
    let limits = Limits { entries: 10, ..Limits::default() };
    refused_with(&build(&many), limits, "has 20 entries, over the limit of 10");
    let limits = Limits { archive_bytes: 100, ..Limits::default() };
    refused_with(&build(&many), limits, "over the limit of 100 bytes");
    refused(&writer::end_record(0, 0, 0), "holds no entries");
    // An end record claiming 60000 entries in a tiny file.
    refused(&writer::end_record(60_000, 0, 0), "has 60000 entries, over the limit of 10000");
    let limits = Limits { entries: 65_535, ..Limits::default() };
    refused_with(&writer::end_record(60_000, 0, 0), limits, "has a damaged central directory");
    let big = spec("phongFragment.glsl", &vec![b' '; 5000]);
    refused_with(
        &build(&[big]),
        Limits { file_bytes: 4096, ..Limits::default() },
        "entry phongFragment.glsl is 5000 bytes, over the limit of 4096 bytes for one file",
    );
}

#[test]
fn damaged_archives() {
    let good = with(spec("readme.txt", b"hello"));
    for cut in 0..good.len() {
        refused(good.get(..cut).unwrap_or_default(), "");
    }
    refused(good.get(..good.len() / 2).unwrap_or_default(), "is not a zip, or is cut short");
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let random: Vec<u8> = (0..100_000).map(|_| super::fuzz::xorshift(&mut state) as u8).collect();
    refused(&random, "is not a zip");
    refused(b"", "is too short to be a zip");

    // Offsets pointing out of the file.
    let local = writer::local_header(b"phongFragment.glsl", 0, 0, (0, 0, 0));
    let central = [writer::central_header(b"phongFragment.glsl", 0, 0, (0, 0, 0), 1_000_000)];
    refused(
        &writer::assemble(local.clone(), &central),
        "entry phongFragment.glsl has no local header where the central directory puts it",
    );
    let central = [writer::central_header(b"phongFragment.glsl", 0, 0, (0, 500, 0), 0)];
    refused(&writer::assemble(local, &central), "entry phongFragment.glsl has its data outside the file");
    let mut bad_eocd = build(&[spec("a", b"x")]);
    let at = bad_eocd.len() - 6;
    bad_eocd.splice(at..at + 4, 0x00FF_0000u32.to_le_bytes());
    refused(&bad_eocd, "has its central directory outside the file");
}

#[test]
fn refused_features() {
    refused(&with(Spec { flags: 1, ..spec("secret.txt", b"x") }), "entry secret.txt is encrypted");
    refused(
        &with(Spec { declared_bytes: Some(u32::MAX), ..spec("big.bin", b"x") }),
        "entry big.bin uses ZIP64 sizes",
    );
    refused(
        &with(Spec { local_name: Some(b"other.txt".to_vec()), ..spec("name.txt", b"x") }),
        "entry name.txt: its local header disagrees with the central directory",
    );
    let lzma = Spec { method: Some(14), ..spec("homework1/phongShader/phongFragment.glsl", b"x") };
    refused(&build(&[lzma]), "entry homework1/phongShader/phongFragment.glsl uses compression method 14");
    let mut zip64 = build(&[spec("a", b"x")]);
    let eocd_at = zip64.len() - 22;
    zip64.splice(eocd_at..eocd_at, [0x50, 0x4b, 0x06, 0x07].into_iter().chain([0u8; 16]));
    refused(&zip64, "uses ZIP64, which is not supported");
}

#[test]
fn notes_stay_on_one_line() {
    let files = [
        spec("a\nb/phongShader/phongFragment.glsl", b"x"),
        spec("homework1/phongShader/phongFragment.glsl", b"y"),
    ];
    let sub = read_zip_bytes(ARCHIVE, &build(&files), Limits::default()).expect("readable");
    assert_eq!(sub.files.phong_fragment.text, "y");
    assert_eq!(
        sub.notes,
        [
            "phongFragment.glsl: chose homework1/phongShader/phongFragment.glsl over a\\nb/phongShader/phongFragment.glsl (does not name homework 1)"
        ]
    );
}
