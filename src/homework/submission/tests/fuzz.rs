//! Mutated archives: whatever the bytes, reading never panics and always returns quickly.

use super::writer::{build, deflated, spec};
use super::*;
use std::time::{Duration, Instant};

pub fn xorshift(state: &mut u64) -> u64 {
    *state ^= *state << 13;
    *state ^= *state >> 7;
    *state ^= *state << 17;
    *state
}

fn below(state: &mut u64, n: usize) -> usize {
    usize::try_from(xorshift(state) % n.max(1) as u64).unwrap_or(0)
}

/// Values that make sizes and offsets interesting.
const WORDS: [u32; 7] = [0, 1, 0xFFFF, 0xFFFF_FFFF, 0x7FFF_FFFF, 0x0100_0000, 22];

#[test]
fn mutated_archives_never_panic() {
    let mut files: Vec<_> = framework("homework1/").iter().map(|(p, b)| deflated(p, b)).collect();
    files.push(spec("homework1/src/readme.txt", b"stored"));
    files
        .push(deflated("homework1/src/shaders/phongShader/phongFragment.glsl", &b"// padding\n".repeat(200)));
    let good = build(&files);
    let mut state = 0x2545_F491_4F6C_DD1Du64;
    let mut accepted = 0;
    let mut slowest = Duration::ZERO;
    // More rounds on request, for a longer hunt than CI needs.
    let rounds: usize =
        std::env::var("SUBMISSION_FUZZ_ROUNDS").ok().and_then(|r| r.parse().ok()).unwrap_or(2000);
    for round in 0..rounds {
        let mut bytes = good.clone();
        for _ in 0..1 + below(&mut state, 4) {
            // Half the edits land in the last 400 bytes, where the directory is.
            let len = bytes.len();
            let at = if xorshift(&mut state).is_multiple_of(2) {
                len.saturating_sub(400) + below(&mut state, 400.min(len))
            } else {
                below(&mut state, len)
            };
            match below(&mut state, 4) {
                0 => {
                    if let Some(b) = bytes.get_mut(at) {
                        *b ^= 1 << below(&mut state, 8);
                    }
                }
                1 => bytes.insert(at.min(len), xorshift(&mut state) as u8),
                2 => {
                    if at < len {
                        bytes.remove(at);
                    }
                }
                _ => {
                    let word = WORDS[below(&mut state, WORDS.len())].to_le_bytes();
                    for (i, w) in word.iter().enumerate() {
                        if let Some(b) = bytes.get_mut(at + i) {
                            *b = *w;
                        }
                    }
                }
            }
        }
        let started = Instant::now();
        let result = std::panic::catch_unwind(|| read_zip_bytes("fuzz.zip", &bytes, Limits::default()));
        let took = started.elapsed();
        slowest = slowest.max(took);
        match result {
            Err(_) => panic!("round {round} panicked"),
            Ok(Ok(_)) => accepted += 1,
            Ok(Err(err)) => {
                let line = err.to_string();
                assert!(line.starts_with("fuzz.zip: ") && !line.contains('\n'), "round {round}: {line}");
            }
        }
        assert!(took < Duration::from_secs(1), "round {round} took {took:?}");
    }
    // Some edits hit bytes nobody checks (timestamps, unused data), so some still read.
    assert!(accepted > 0 && accepted < rounds, "accepted {accepted}");
    eprintln!("fuzz: {accepted} of {rounds} mutated archives still read; slowest {slowest:?}");
}
