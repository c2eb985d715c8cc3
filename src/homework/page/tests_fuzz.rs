//! Property-style tests of the page: random tokens and random edits of a real light, run as a
//! student's DirectionalLight.js and engine.js, never panic and always come back, as a matrix or
//! as one line naming a file; errors at a script's top level name their line.

use std::time::Duration;

use super::tests::{EXAMPLE_LIGHT, FRAMEWORK_ENGINE, OBJECTS, source};
use super::*;

/// xorshift64*: a tiny deterministic generator (the same cases every run).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

const TOKENS: [&str; 48] = [
    "class",
    "DirectionalLight",
    "CalcLightMVP",
    "constructor",
    "extends",
    "super",
    "this",
    "new",
    "return",
    "function",
    "let",
    "const",
    "if",
    "else",
    "for",
    "while",
    "try",
    "catch",
    "throw",
    "typeof",
    "null",
    "undefined",
    "mat4",
    "vec3",
    "Math",
    "THREE",
    "window",
    "document",
    "(",
    ")",
    "{",
    "}",
    "[",
    "]",
    ";",
    ",",
    ".",
    "=",
    "+",
    "*",
    "/",
    "=>",
    "0",
    "1e308",
    "'x'",
    "`t`",
    "\n",
    "...",
];

/// A run of the page with `light` (and `engine`) that must come back, as a matrix or one line.
fn comes_back(light: &str, engine: Option<&str>) {
    let limits = Limits { time: Duration::from_millis(500), ..Limits::default() };
    let engine = engine.map(|e| source("engine.js", e));
    match PageRun::run(&source("DirectionalLight.js", light), engine.as_ref(), &[], &OBJECTS, limits) {
        Ok(run) => {
            if let Err(e) = run.light_matrix([0.0; 3], [1.0; 3]) {
                assert!(!e.to_string().contains('\n'), "{e}");
            }
        }
        Err(e) => {
            assert!(!e.to_string().contains('\n'), "{e}");
            assert!(!e.file.is_empty(), "{e}");
        }
    }
}

#[test]
fn random_tokens_and_random_edits_always_come_back() {
    let mut rng = Rng(0x5eed_1234_abcd_0001);
    for _ in 0..24 {
        let soup: Vec<&str> = (0..rng.below(60) + 1).map(|_| TOKENS[rng.below(TOKENS.len())]).collect();
        comes_back(&soup.join(" "), None);
    }
    let chars: Vec<char> = EXAMPLE_LIGHT.chars().collect();
    for _ in 0..24 {
        let mut edited = chars.clone();
        for _ in 0..rng.below(4) + 1 {
            let at = rng.below(edited.len());
            match rng.below(3) {
                0 => {
                    let end = (at + rng.below(12) + 1).min(edited.len());
                    edited.drain(at..end);
                }
                1 => {
                    let token: Vec<char> = TOKENS[rng.below(TOKENS.len())].chars().collect();
                    edited.splice(at..at, token);
                }
                _ => {
                    let end = (at + rng.below(20) + 1).min(edited.len());
                    let copy: Vec<char> = edited[at..end].to_vec();
                    edited.splice(at..at, copy);
                }
            }
        }
        let light: String = edited.into_iter().collect();
        comes_back(&light, None);
        // The same edit as the student's engine.js, beside a sound light.
        comes_back(EXAMPLE_LIGHT, Some(&format!("{FRAMEWORK_ENGINE}\n{light}")));
    }
}

#[test]
fn errors_at_a_scripts_top_level_name_their_line() {
    let run = |light: &str| {
        PageRun::run(&source("DirectionalLight.js", light), None, &[], &OBJECTS, Limits::default())
            .err()
            .unwrap_or_else(|| panic!("expected an error for {light:?}"))
    };
    let e = run("let x = 1;\nfoo();\nclass DirectionalLight {}");
    assert_eq!((e.file.as_str(), e.line), ("DirectionalLight.js", 2), "{e}");
    assert!(e.message.contains("foo"), "{e}");
    // QuickJS throws this one from the class's own frame: its line is the class's.
    let e = run("class B {}\nB();\nclass DirectionalLight {}");
    assert_eq!((e.file.as_str(), e.line), ("DirectionalLight.js", 1), "{e}");
    assert!(e.message.contains("'new'"), "{e}");
    let e = run("const a = [];\na.push(...5);\nclass DirectionalLight {}");
    assert_eq!((e.file.as_str(), e.line), ("DirectionalLight.js", 2), "{e}");
}
