//! Mistakes and hostile input in a student's light, each ending in one line that names their file
//! and line as the browser's console would: syntax errors, runtime errors, nesting deep enough to
//! break a parser, and allocations past the memory bound. Never a hang, a crash or a panic.

use std::time::Duration;

use super::tests::{OBJECTS, line_of, source};
use super::*;

fn with_body(body: &str) -> String {
    format!(
        "class DirectionalLight {{\n  constructor() {{}}\n  CalcLightMVP(translate, scale) {{\n    const m = mat4.create();\n{body}\n    return m;\n  }}\n}}\n"
    )
}

/// The one-line error of running `light` (loading it, or its first matrix).
fn error_of(light: &str) -> ScriptError {
    // No case here runs into the time bound on its own (the memory cases end at the memory
    // bound): a generous one only keeps a mistake from hanging, on however busy a machine.
    let limits = Limits { time: Duration::from_secs(60), ..Limits::default() };
    let e = match PageRun::run(&source("lights/DirectionalLight.js", light), None, &[], &OBJECTS, limits) {
        Err(e) => e,
        Ok(page) => match page.light_matrix([0.0; 3], [1.0; 3]) {
            Err(e) => e,
            Ok(m) => panic!("expected an error for {light:?}, got {m:?}"),
        },
    };
    assert!(!e.to_string().contains('\n'), "{e}");
    e
}

/// `light` fails on the line holding `needle` (0: no line) with a message containing `part`.
fn expect(light: &str, needle: &str, part: &str) {
    let e = error_of(light);
    assert_eq!(e.file, "lights/DirectionalLight.js", "{e}");
    if !needle.is_empty() {
        assert_eq!(e.line, line_of(light, needle), "{e}");
    }
    assert!(e.message.to_lowercase().contains(&part.to_lowercase()), "{light:?}: {e}");
}

#[test]
fn syntax_errors_name_their_line() {
    expect(&with_body("    let x = (1 + ;"), "let x = (1 + ;", "unexpected token");
    expect(&with_body("    mat4.ortho(m, -1, 1 -1, 1, 1, 100\n    let y = 2;"), "let y = 2;", "");
    expect("class DirectionalLight {\n  CalcLightMVP() {\n", "", "");
    expect(&with_body("    const f = (a, a) => { 'use strict'; return a; };"), "const f", "");
}

#[test]
fn runtime_errors_name_their_line() {
    let cases = [
        // QuickJS places the first three on another line; the driver finds theirs.
        ("    let p = this.light.lightPos;", "this.light", "cannot read property"),
        ("    const k = 1;\n    k = 2;", "k = 2", "'k' is read-only"),
        ("    let a = 1;\n    a = this.light\n      .lightPos;", ".lightPos", "cannot read property"),
        ("    mat4.orthographic(m, -1, 1, -1, 1, 1, 10);", "mat4.orthographic", "not a function"),
        ("    undeclaredMatrix[0] = 1;", "undeclaredMatrix", "undeclaredMatrix"),
        ("    throw 'no matrix';", "", "no matrix"),
        ("    [].push(...5);", "push(...5)", "not iterable"),
        ("    mat4.multiply(undefined, m, m);", "", "cannot set property"),
    ];
    for (body, needle, part) in cases {
        expect(&with_body(body), needle, part);
    }
}

#[test]
fn what_a_browser_lacks_is_refused_and_what_it_has_is_there() {
    expect(&with_body("    fetch('http://example.com/light.json');"), "fetch(", "fetch is not available");
    expect(
        &with_body("    importScripts('http://example.com/a.js');"),
        "importScripts",
        "importScripts is not available",
    );
    expect(&with_body("    new WebSocket('ws://example.com');"), "WebSocket", "WebSocket is not available");
    // A browser has Math.random, typeof checks of THREE and the document: no error, a matrix.
    let light = with_body("    m[12] = typeof THREE === 'object' && document.body ? Math.random() * 0 : 7;");
    let run = PageRun::run(&source("DirectionalLight.js", &light), None, &[], &OBJECTS, Limits::default())
        .expect("the page runs");
    assert_eq!(run.light_matrix([0.0; 3], [1.0; 3]).expect("a matrix").clip_from_object[12], 0.0);
}

#[test]
fn nesting_deep_enough_to_break_a_parser_is_one_line() {
    let n = 100_000;
    let sources = [
        format!("let x = {}1{};", "(".repeat(n), ")".repeat(n)),
        format!("let x = {}1{};", "[".repeat(n), "]".repeat(n)),
        format!("let x = {}", "{a:".repeat(n)),
        format!("let x = {}1;", "-".repeat(n)),
        format!("let x = 2{};", " ** 2".repeat(n)),
        format!("{}{}", "{".repeat(n), "}".repeat(n)),
        format!("{}x;", "if (1) ".repeat(n)),
        format!("let x = `{}`;", "${`".repeat(n)),
        format!("let x = {}1;", "a => ".repeat(n)),
    ];
    for text in sources {
        let e = error_of(&format!("{text}\nclass DirectionalLight {{}}\n"));
        assert_eq!(e.file, "lights/DirectionalLight.js", "{}: {e}", &text[..12]);
    }
}

#[test]
fn allocations_past_the_memory_bound_end_the_script_not_the_process() {
    let cases = [
        ("    let a = new Array(1e12);", "invalid array length"),
        ("    let s = 'x'.repeat(1e9);", ""),
        ("    let s = 'x'; while (true) s = s + s;", ""),
        ("    let f = new Float32Array(1 << 28);", "memory bound"),
        ("    const keep = []; for (;;) keep.push([[], [], [], [], [], [], [], []]);", "memory bound"),
    ];
    for (body, part) in cases {
        let e = error_of(&with_body(body));
        assert_eq!(e.file, "lights/DirectionalLight.js", "{body}: {e}");
        assert!(e.message.contains(part), "{body}: {e}");
        assert!(
            part.is_empty() || !e.message.contains("time bound"),
            "{body}: ran into the time bound, not the memory bound: {e}"
        );
    }
}
