//! Every failure is one `ScriptError` line with the right line number; limits hold.

use std::time::{Duration, Instant};

use super::tests_light::{FILE, light_class, load};
use super::*;

/// The error of loading `src`, or of its first light matrix.
fn error_of(src: &str, limits: Limits) -> ScriptError {
    let mut light = match LightScript::load(src, FILE, &EngineLight::framework(), limits) {
        Err(e) => return single_line(e),
        Ok(l) => l,
    };
    match light.light_matrix([0.0; 3], [1.0; 3]) {
        Err(e) => single_line(e),
        Ok(m) => panic!("expected an error, got {m:?}"),
    }
}

fn single_line(e: ScriptError) -> ScriptError {
    assert!(!e.message.contains('\n') && !e.to_string().contains('\n'), "{e}");
    assert_eq!(e.file, FILE);
    e
}

fn line_of(src: &str, needle: &str) -> usize {
    src.lines().position(|l| l.contains(needle)).map_or(0, |i| i + 1)
}

/// A light whose CalcLightMVP runs `body` (which returns a matrix or fails).
fn with_body(body: &str) -> String {
    light_class(body, "", "")
}

fn expect(src: &str, needle: &str, message_part: &str) {
    let e = error_of(src, Limits::default());
    assert_eq!(e.line, line_of(src, needle), "{e}");
    assert!(e.message.contains(message_part), "{e}");
}

#[test]
fn display_formats() {
    let e = ScriptError {
        file: "DirectionalLight.js".into(),
        line: 37,
        message: "mat4.ortho needs 7 arguments".into(),
    };
    assert_eq!(e.to_string(), "DirectionalLight.js:37: mat4.ortho needs 7 arguments");
    let e = ScriptError { line: 0, ..e };
    assert_eq!(e.to_string(), "DirectionalLight.js: mat4.ortho needs 7 arguments");
}

#[test]
fn syntax_errors_name_their_line() {
    expect(&with_body("let x = (1 + ;"), "let x = (1 + ;", "syntax error: unexpected `;`");
    // The missing `)` shows at the next token, as a browser reports it.
    expect(
        &with_body("mat4.ortho(projectionMatrix, -1, 1 -1, 1, 1, 100"),
        "mat4.multiply(lightMVP, projectionMatrix",
        "syntax error: expected `)`, found `mat4`",
    );
    expect(
        "class DirectionalLight {\n  CalcLightMVP() {\n    return 'open\n  }\n}\n",
        "return 'open",
        "unterminated string",
    );
    let e = error_of("class DirectionalLight {\n  CalcLightMVP() {\n", Limits::default());
    assert!(e.message.contains("missing `}`"), "{e}");
}

#[test]
fn unsupported_features_are_one_line_errors() {
    expect(&with_body("let ok = /ab+c/.test('abc');"), "/ab+c/", "unsupported: regular expression literals");
    expect(&with_body("const f = async () => 1;"), "async", "unsupported: async");
    expect(&with_body("outer: for (;;) { break outer; }"), "outer:", "unsupported: labels");
    expect(&with_body("delete this.mesh;"), "delete", "unsupported: `delete`");
    expect(
        &with_body("let [a, b] = [1, 2]; [a, b] = [b, a];"),
        "[a, b] = [b, a]",
        "unsupported: destructuring assignment",
    );
}

#[test]
fn uncaught_throw_in_calc_light_mvp() {
    expect(&with_body("throw new Error('x');"), "throw new Error", "uncaught exception: Error: x");
    expect(&with_body("throw 'no matrix';"), "throw 'no", "uncaught exception: no matrix");
    // Caught ones are fine.
    let src = with_body(
        "try { throw new TypeError('t'); } catch (e) { modelMatrix[0] = e.message === 't' ? 2 : 3; } finally { modelMatrix[1] = 7; }",
    );
    let m = load(&src).expect("loads").light_matrix([0.0; 3], [1.0; 3]).expect("runs").clip_from_object;
    assert_eq!((m[0], m[1]), (2.0, 7.0));
}

#[test]
fn runtime_type_errors() {
    expect(
        &with_body("let p = this.light.lightPos;"),
        "this.light.lightPos",
        "TypeError: cannot read `lightPos` of undefined",
    );
    expect(
        &with_body("mat4.orthographic(projectionMatrix, -1, 1, -1, 1, 1, 10);"),
        "mat4.orthographic",
        "TypeError: `mat4.orthographic` is not a function",
    );
    expect(&with_body("const k = 1;\n        k = 2;"), "k = 2", "assignment to the constant `k`");
    expect(
        &with_body("undeclaredMatrix = mat4.create();"),
        "undeclaredMatrix",
        "`undeclaredMatrix` is not defined",
    );
}

#[test]
fn gl_matrix_argument_errors() {
    expect(
        &with_body("mat4.ortho(projectionMatrix, -1, 1, -1, 1, 1);"),
        "mat4.ortho",
        "mat4.ortho needs 7 arguments",
    );
    let e = error_of(
        &with_body("let near;\n        mat4.ortho(projectionMatrix, -1, 1, -1, 1, near, 10);"),
        Limits::default(),
    );
    assert_eq!(e.message, "mat4.ortho: argument 6 (near) is undefined, not a number");
    expect(
        &with_body("mat4.translate(modelMatrix, modelMatrix, [1, 2]);"),
        "mat4.translate",
        "argument 3 (v) has 2 elements, needs 3",
    );
    expect(
        &with_body("mat4.lookAt(viewMatrix, this.lightPosition, [0, 0, 0], [0, 1, 0]);"),
        "mat4.lookAt",
        "argument 2 (eye) is undefined",
    );
    expect(
        &with_body("mat4.multiply(undefined, modelMatrix, modelMatrix);"),
        "mat4.multiply",
        "argument 1 (out) is undefined",
    );
    expect(&with_body("let r = Math.random();"), "Math.random", "Math.random is not available");
}

#[test]
fn bad_return_values() {
    let src = with_body("return; // nothing yet").replace("return lightMVP;", "");
    let e = error_of(&src, Limits::default());
    assert_eq!(e.message, "CalcLightMVP returned undefined, not a 4x4 matrix");
    assert_eq!(e.line, line_of(&src, "return; // nothing yet"));
    let src = light_class("", "", "").replace("return lightMVP;", "return [1, 2, 3];");
    expect(&src, "return [1, 2, 3]", "returned an array of 3 elements");
    let src = light_class("", "", "")
        .replace("return lightMVP;", "let m = Array.from(lightMVP); m[5] = 'x'; return m;");
    expect(&src, "return m", "element 5 is string");
    // Falling off the end names the method's last line.
    let src = "class DirectionalLight {\n  CalcLightMVP(t, s) {\n    mat4.create();\n  }\n}\n";
    let e = error_of(src, Limits::default());
    assert_eq!((e.line, e.message.as_str()), (4, "CalcLightMVP returned undefined, not a 4x4 matrix"));
    // Non-finite entries are kept for the caller.
    let src = light_class("modelMatrix[0] = NaN; modelMatrix[5] = 1 / 0;", "", "");
    let m = load(&src).expect("loads").light_matrix([0.0; 3], [1.0; 3]).expect("runs").clip_from_object;
    assert!(m[0].is_nan() && m[5].is_infinite());
}

#[test]
fn missing_light_or_method() {
    let e = error_of("class Light { CalcLightMVP() { return mat4.create(); } }", Limits::default());
    assert_eq!(e.message, "no class or function named DirectionalLight");
    let e =
        error_of("class DirectionalLight { calcLightMVP() { return mat4.create(); } }", Limits::default());
    assert_eq!(e.message, "DirectionalLight has no CalcLightMVP method");
    expect("let x = 1;\nfoo();\nclass DirectionalLight {}", "foo();", "`foo` is not defined");
}

#[test]
fn browser_globals_are_not_defined() {
    for g in ["THREE", "document", "Date", "fetch", "require", "window", "globalThis", "setTimeout", "eval"] {
        let src = with_body(&format!("let thing = {g};"));
        let e = error_of(&src, Limits::default());
        assert_eq!(
            e.message,
            format!("`{g}` is not defined (a light script here has gl-matrix and Math only)")
        );
        assert_eq!(e.line, line_of(&src, "let thing"));
    }
    // `typeof` may probe.
    let src = with_body("modelMatrix[0] = typeof THREE === 'undefined' ? 9 : 1;");
    assert_eq!(
        load(&src).expect("loads").light_matrix([0.0; 3], [1.0; 3]).expect("runs").clip_from_object[0],
        9.0
    );
}

fn timed(src: &str, limits: Limits) -> (ScriptError, Duration) {
    let t0 = Instant::now();
    let e = error_of(src, limits);
    (e, t0.elapsed())
}

#[test]
fn endless_loops_are_bounded() {
    let src = with_body("while (true) {}");
    let (e, took) = timed(&src, Limits::default());
    assert_eq!(e.message, "did not finish within 5000000 steps (an endless loop?)");
    assert_eq!(e.line, line_of(&src, "while (true)"));
    assert!(took < Duration::from_secs(20), "{took:?}");
    let src = "function spin() { for (;;) { let a = [1, 2, 3].map(x => x * 2); } }\nfor (;;) spin()\nclass DirectionalLight {}\n";
    let (e, _) = timed(src, Limits { steps: 200_000, ..Limits::default() });
    assert!(e.message.starts_with("did not finish within 200000 steps"), "{e}");
    let src = with_body("let i = 0;\n        do { i++; } while (i > 0)");
    let (e, _) = timed(&src, Limits { steps: 100_000, ..Limits::default() });
    assert!(e.message.contains("steps"), "{e}");
    // The top level has its own budget, and so does each matrix.
    let src =
        format!("for (let i = 0; i < 50000; i++) {{}}\n{}", with_body("for (let i = 0; i < 50000; i++) {}"));
    let mut light = LightScript::load(
        &src,
        FILE,
        &EngineLight::framework(),
        Limits { steps: 300_000, ..Limits::default() },
    )
    .expect("loads");
    for _ in 0..3 {
        assert!(light.light_matrix([0.0; 3], [1.0; 3]).is_ok());
    }
}

#[test]
fn deep_recursion_is_bounded() {
    let src = with_body("function down(n) { return down(n + 1) + 1; }\n        down(0);");
    expect(&src, "function down", "calls nested deeper than 200");
    // Recursion through methods, constructors and natives.
    let src = with_body("const o = { f() { return [1].map(() => this.f()); } };\n        o.f();");
    let e = error_of(&src, Limits::default());
    assert!(e.message.contains("nested"), "{e}");
    let src = "class DirectionalLight { constructor() { new DirectionalLight(); } CalcLightMVP() { return mat4.create(); } }";
    let mut light = load(src).expect("the constructor's failure falls back");
    assert!(light.notes()[0].contains("calls nested deeper than 200"), "{:?}", light.notes());
    assert!(light.light_matrix([0.0; 3], [1.0; 3]).is_ok());
}

#[test]
fn deep_nesting_does_not_overflow_the_stack() {
    let n = 100_000;
    let shapes = [
        format!("let x = {}1{};", "(".repeat(n), ")".repeat(n)),
        format!("let x = {}1{};", "[".repeat(n), "]".repeat(n)),
        format!("let x = {}", "{a:".repeat(n)),
        format!("let x = {}1;", "-".repeat(n)),
        format!("let x = {}1;", "- ".repeat(n)),
        format!("let x = 1{};", " + 1".repeat(n)),
        format!("let x = 2{};", " ** 2".repeat(n)),
        format!("let x = a{};", ".b".repeat(n)),
        format!("let x = f{};", "()".repeat(n)),
        format!("let x = {}1;", "a => ".repeat(n)),
        format!("let x = {}1;", "c ? 1 : ".repeat(n)),
        format!("let x = {}1;", "y = ".repeat(n)),
        format!("{}{}", "{".repeat(n), "}".repeat(n)),
        format!("{}x;", "if (1) ".repeat(n)),
        format!("let x = `{}`;", "${`".repeat(n)),
        format!("let x = {}", "function(){ return ".repeat(n / 4)),
    ];
    for s in &shapes {
        let src = with_body(s);
        let t0 = Instant::now();
        let e = error_of(&src, Limits::default());
        // "nested deeper than 200 levels", or in debug builds (bigger frames) the stack backstop.
        assert!(e.message.contains("nested") || e.message.contains("syntax error"), "{}: {e}", &s[..20]);
        assert!(t0.elapsed() < Duration::from_secs(20));
    }
}

#[test]
fn deep_evaluation_within_the_parser_limit_is_safe() {
    // Calls that each sit inside a deep expression: the evaluator's own depth budget holds.
    let expr = format!("{}down(n + 1){}", "(1 + ".repeat(150), ")".repeat(150));
    let src = with_body(&format!("function down(n) {{ return {expr}; }}\n        down(0);"));
    let e = error_of(&src, Limits::default());
    assert!(e.message.contains("nested"), "{e}");
}

#[test]
fn memory_is_bounded() {
    let big = [
        ("let a = new Array(1e12);", "an array longer than 1048576"),
        ("let a = []; a.length = 1e9;", "array length 1000000000 is invalid"),
        ("let a = []; a[5e6] = 1;", "an array longer than 1048576"),
        ("let s = 'x'.repeat(1e9);", "String.repeat would pass"),
        ("let s = 'x'; while (true) s = s + s;", "a string longer than 1048576 bytes"),
        ("let f = new Float32Array(1 << 21);", "an array longer than 1048576"),
        (
            "let a = []; while (true) a.push(0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0);",
            "an array longer than 1048576",
        ),
        ("while (true) { const o = [[], [], [], [], [], [], [], []]; }", "used more than 64 MiB of memory"),
        (
            "const keep = [], s = 'x'.repeat(1 << 19); while (true) keep.push(s + keep.length);",
            "used more than 64 MiB of memory",
        ),
        ("let s = 'ab'.padStart(1e8);", "a string longer"),
    ];
    for (code, part) in big {
        let src = with_body(code);
        let t0 = Instant::now();
        let e = error_of(&src, Limits::default());
        assert!(e.message.contains(part), "{code}: {e}");
        assert_eq!(e.line, line_of(&src, code), "{code}");
        assert!(t0.elapsed() < Duration::from_secs(20), "{code}");
    }
    let e = LightScript::load(
        &"/".repeat(MAX_SOURCE_BYTES + 1),
        FILE,
        &EngineLight::framework(),
        Limits::default(),
    );
    assert!(e.err().is_some_and(|e| e.message.contains("larger than")));
}

#[test]
fn errors_in_the_top_level_fail_the_load() {
    expect("const a = [];\na.push(...5);\nclass DirectionalLight {}", "a.push", "TypeError: spreading");
    expect(
        "class DirectionalLight extends LightBase {}",
        "class DirectionalLight",
        "`LightBase` is not defined",
    );
    expect("class B {}\nB();\nclass DirectionalLight {}", "B();", "cannot be called without `new`");
}
