//! Property-style tests: random bytes, random tokens and random edits of a real-shaped
//! light never panic, and always come back within the limits.

use std::time::{Duration, Instant};

use super::tests_light::light_class;
use super::*;

/// xorshift64*: a tiny deterministic generator (no dependency, same cases every run).
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

    fn pick<'a>(&mut self, items: &[&'a str]) -> &'a str {
        items[self.below(items.len())]
    }
}

const TOKENS: [&str; 96] = [
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
    "var",
    "if",
    "else",
    "for",
    "of",
    "in",
    "while",
    "do",
    "break",
    "continue",
    "try",
    "catch",
    "finally",
    "throw",
    "switch",
    "case",
    "default",
    "typeof",
    "instanceof",
    "void",
    "null",
    "undefined",
    "true",
    "false",
    "export",
    "import",
    "static",
    "get",
    "set",
    "async",
    "await",
    "mat4",
    "vec3",
    "Math",
    "console",
    "Mesh",
    "FBO",
    "gl",
    "x",
    "y",
    "lightPos",
    "translate",
    "scale",
    "0",
    "1",
    "-1",
    "1e9",
    "0x10",
    ".5",
    "'s'",
    "\"中文\"",
    "`t${",
    "}`",
    "`x`",
    "(",
    ")",
    "[",
    "]",
    "{",
    "}",
    ";",
    ",",
    ".",
    "?.",
    "...",
    "=>",
    "=",
    "+=",
    "==",
    "===",
    "!",
    "?",
    ":",
    "+",
    "-",
    "*",
    "**",
    "/",
    "%",
    "&&",
    "||",
    "??",
    "\n",
    "// c\n",
];

/// Runs everything a caller might on `src`, and checks the results' shape and timing.
fn run_all(src: &str, limits: Limits) {
    run_all_n(src, limits, 2);
}

fn run_all_n(src: &str, limits: Limits, matrices: usize) {
    let t0 = Instant::now();
    let engine = engine_light(src, "engine.js", limits);
    assert!(engine.notes.iter().all(|n| !n.contains('\n')), "{:?}", engine.notes);
    match LightScript::load(src, "fuzz.js", &engine, limits) {
        Ok(mut light) => {
            for _ in 0..matrices {
                if let Err(e) = light.light_matrix([1.0, 2.0, 3.0], [4.0, 5.0, 6.0]) {
                    assert!(!e.message.contains('\n'), "{e}");
                }
            }
        }
        Err(e) => assert!(!e.message.contains('\n'), "{e}"),
    }
    // Three runs of `limits.steps` each take well under this even in a debug build.
    assert!(t0.elapsed() < Duration::from_secs(10), "took {:?} on {src:?}", t0.elapsed());
}

fn small() -> Limits {
    Limits { steps: 30_000, ..Limits::default() }
}

#[test]
fn byte_soup_never_panics() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    for _ in 0..1500 {
        let len = rng.below(400);
        // Mostly JavaScript's punctuation and a few letters, some raw bytes.
        let alphabet = b" \n(){}[];,.=+-*/'\"`$\\0123456789abcxyz";
        let bytes: Vec<u8> = (0..len)
            .map(|_| if rng.below(8) == 0 { rng.next() as u8 } else { alphabet[rng.below(alphabet.len())] })
            .collect();
        run_all(&String::from_utf8_lossy(&bytes), small());
    }
}

#[test]
fn token_soup_never_panics() {
    let mut rng = Rng(0xD1B5_4A32_D192_ED03);
    for _ in 0..1500 {
        let n = rng.below(120);
        let src: Vec<&str> = (0..n).map(|_| rng.pick(&TOKENS)).collect();
        run_all(&src.join(" "), small());
    }
}

#[test]
fn edited_lights_never_panic() {
    let base = light_class(
        "mat4.translate(modelMatrix, modelMatrix, translate);\n        mat4.scale(modelMatrix, modelMatrix, scale);",
        "mat4.lookAt(viewMatrix, this.lightPos, this.focalPoint, this.lightUp);",
        "let r = 100; for (let i = 0; i < 3; i++) { r += [1, 2][i % 2] ?? 0; }\n        mat4.ortho(projectionMatrix, -r, r, -r, r, 0.01, 500);",
    );
    let words: Vec<&str> = base.split_inclusive(|c: char| !c.is_alphanumeric()).collect();
    let mut rng = Rng(0x243F_6A88_85A3_08D3);
    for _ in 0..1200 {
        let mut w = words.clone();
        for _ in 0..=rng.below(4) {
            let at = rng.below(w.len());
            match rng.below(4) {
                0 => {
                    let end = (at + rng.below(6)).min(w.len());
                    w.drain(at..end);
                }
                1 => w.insert(at, rng.pick(&TOKENS)),
                2 => {
                    let end = (at + rng.below(10)).min(w.len());
                    let copy: Vec<&str> = w[at..end].to_vec();
                    let to = rng.below(w.len());
                    w.splice(to..to, copy);
                }
                _ => {
                    let other = rng.below(w.len());
                    w.swap(at, other);
                }
            }
        }
        run_all(&w.concat(), small());
    }
}

#[test]
fn hostile_programs_stay_bounded_with_default_limits() {
    let bodies = [
        "while (true) {}",
        "for (;;) { try { throw 1; } catch (e) { continue; } finally { } }",
        "const f = () => f(); f();",
        "let a = [1]; while (true) a = a.concat(a);",
        "let s = 'ab'; for (;;) s += s;",
        "let o = {}; for (let i = 0; ; i++) o['k' + i] = i;",
        "let a = []; a.push(a); String(a); JSON.stringify([[[[[[]]]]]]); a.join();",
        "const arr = Array.from({ length: 1e6 }, (_, i) => i); arr.sort((x, y) => y - x);",
        "class A { constructor() { return new A(); } } new A();",
        "let g = { get x() { return this.x; } }; g.x;",
    ];
    let big_block = format!("let x = 0; for (;;) {{ if (x === 0) continue; {} }}", "x;".repeat(50_000));
    let chains = "let C = class {}; for (;;) C = class extends C { m() { return super.m ? 1 : 0; } };";
    let protos = "function F() {} for (let i = 0; i < 1e5; i++) { F.prototype = new F(); } let k = 0; for (;;) k += new F().missing === undefined;";
    for body in bodies.iter().copied().chain([big_block.as_str(), chains, protos]) {
        let src = light_class(body, "", "");
        let t0 = Instant::now();
        run_all_n(&src, Limits::default(), 1);
        assert!(t0.elapsed() < Duration::from_secs(30), "{body}: {:?}", t0.elapsed());
    }
}

/// The deepest inputs, on the stack a browser gives wasm32 (1 MiB; 2 MiB for debug builds,
/// whose frames are several times larger): each is an error, never an overflow.
#[test]
fn deep_programs_fit_a_small_stack() {
    let stack_bytes = if cfg!(debug_assertions) { 2 << 20 } else { 1 << 20 };
    let run = || {
        let n = 100_000;
        let deep = [
            format!("let x = {}1{};", "(".repeat(n), ")".repeat(n)),
            format!("let x = {}1{};", "[".repeat(n), "]".repeat(n)),
            format!("{}{}", "{".repeat(n), "}".repeat(n)),
            format!("{}x;", "if (1) ".repeat(n)),
            format!("let x = {}1;", "a => ".repeat(n)),
            "function down(n) { if (true) { for (;;) { { { if (1) { return down(n + 1); } } } } } }\n down(0);".to_string(),
            format!("function down(n) {{ return {}down(n + 1){}; }}\n down(0);", "(1 + ".repeat(90), ")".repeat(90)),
            format!("function down(n) {{ return {}down(n + 1){}; }}\n down(0);", "[".repeat(90), "]".repeat(90)),
            "const o = { f() { return [1].map(() => this.f()); } };\n o.f();".to_string(),
            "class A { constructor() { new A(); } } new A();".to_string(),
            "const g = { get x() { return this.x; } }; g.x;".to_string(),
            "function f() { return JSON.stringify({ toString() { return f(); } }) + String({ toString() { return f(); } }); } f();".to_string(),
            "function r() { return [1, 2].sort(() => r()); } r();".to_string(),
        ];
        for body in &deep {
            let src = light_class(body, "", "");
            let outcome = LightScript::load(&src, "f.js", &EngineLight::framework(), Limits::default())
                .and_then(|mut l| l.light_matrix([0.0; 3], [1.0; 3]));
            let e = outcome.err().unwrap_or_else(|| panic!("{body:.30}: expected an error"));
            assert!(e.message.contains("nested"), "{body:.30}: {e}");
        }
    };
    let thread = std::thread::Builder::new().stack_size(stack_bytes).spawn(run).expect("a thread");
    assert!(thread.join().is_ok());
}
