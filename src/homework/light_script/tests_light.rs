//! Light scripts in the style of real submissions (written fresh for these tests).

use super::*;

pub(super) const FILE: &str = "DirectionalLight.js";

pub(super) fn load(src: &str) -> Result<LightScript, ScriptError> {
    LightScript::load(src, FILE, &EngineLight::framework(), Limits::default())
}

pub(super) fn matrix(src: &str, t: [f64; 3], s: [f64; 3]) -> [f32; 16] {
    let mut light = load(src).unwrap_or_else(|e| panic!("load failed: {e}"));
    light.light_matrix(t, s).unwrap_or_else(|e| panic!("light_matrix failed: {e}")).clip_from_object
}

/// A class in the template's shape, with `model`, `view` and `proj` lines swappable.
pub(super) fn light_class(model: &str, view: &str, proj: &str) -> String {
    format!(
        r#"class DirectionalLight {{

    constructor(lightIntensity, lightColor, lightPos, focalPoint, lightUp, hasShadowMap, gl) {{
        this.mesh = Mesh.cube(setTransform(0, 0, 0, 0.2, 0.2, 0.2, 0));
        this.mat = new EmissiveMaterial(lightIntensity, lightColor);
        this.lightPos = lightPos;
        this.focalPoint = focalPoint;
        this.lightUp = lightUp

        this.hasShadowMap = hasShadowMap;
        this.fbo = new FBO(gl);
        if (!this.fbo) {{
            console.log("光源的帧缓冲没有建好");
            return;
        }}
    }}

    CalcLightMVP(translate, scale) {{
        let lightMVP = mat4.create();
        let modelMatrix = mat4.create();
        let viewMatrix = mat4.create();
        let projectionMatrix = mat4.create();

        // 模型变换
        {model}

        // 视图变换
        {view}

        // 投影变换
        {proj}

        mat4.multiply(lightMVP, projectionMatrix, viewMatrix);
        mat4.multiply(lightMVP, lightMVP, modelMatrix);

        return lightMVP;
    }}
}}
"#
    )
}

const MODEL: &str = "mat4.translate(modelMatrix, modelMatrix, translate);\n        mat4.scale(modelMatrix, modelMatrix, scale);";
const VIEW: &str = "mat4.lookAt(viewMatrix, this.lightPos, this.focalPoint, this.lightUp);";

fn template(proj: &str) -> String {
    light_class(MODEL, VIEW, proj)
}

// ---- an independent reference: textbook formulas, f32 storage between steps ----

type M = [f64; 16];

fn round32(m: M) -> M {
    m.map(|x| f64::from(x as f32))
}

fn mul(a: &M, b: &M) -> M {
    let mut out = [0.0; 16];
    for c in 0..4 {
        for r in 0..4 {
            out[c * 4 + r] = (0..4).map(|k| a[k * 4 + r] * b[c * 4 + k]).sum();
        }
    }
    out
}

fn model_ref(t: [f64; 3], s: [f64; 3]) -> M {
    round32([s[0], 0.0, 0.0, 0.0, 0.0, s[1], 0.0, 0.0, 0.0, 0.0, s[2], 0.0, t[0], t[1], t[2], 1.0])
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    [v[0] / l, v[1] / l, v[2] / l]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn view_ref(eye: [f64; 3], center: [f64; 3], up: [f64; 3]) -> M {
    let z = unit([eye[0] - center[0], eye[1] - center[1], eye[2] - center[2]]);
    let x = unit(cross(up, z));
    let y = unit(cross(z, x));
    let dot = |a: [f64; 3]| a[0] * eye[0] + a[1] * eye[1] + a[2] * eye[2];
    round32([
        x[0],
        y[0],
        z[0],
        0.0,
        x[1],
        y[1],
        z[1],
        0.0,
        x[2],
        y[2],
        z[2],
        0.0,
        -dot(x),
        -dot(y),
        -dot(z),
        1.0,
    ])
}

fn ortho_ref(l: f64, r: f64, b: f64, t: f64, n: f64, f: f64) -> M {
    round32([
        2.0 / (r - l),
        0.0,
        0.0,
        0.0,
        0.0,
        2.0 / (t - b),
        0.0,
        0.0,
        0.0,
        0.0,
        -2.0 / (f - n),
        0.0,
        -(r + l) / (r - l),
        -(t + b) / (t - b),
        -(f + n) / (f - n),
        1.0,
    ])
}

pub(super) fn reference(proj: M, eye: [f64; 3], t: [f64; 3], s: [f64; 3]) -> [f32; 16] {
    let pv = round32(mul(&proj, &view_ref(eye, [0.0; 3], [0.0, 1.0, 0.0])));
    round32(mul(&pv, &model_ref(t, s))).map(|x| x as f32)
}

const EYE: [f64; 3] = [0.0, 80.0, 80.0];
const PLACES: [([f64; 3], [f64; 3]); 3] = [
    ([0.0, 0.0, -30.0], [4.0, 4.0, 4.0]),
    ([0.0, 0.0, 0.0], [20.0, 20.0, 20.0]),
    ([40.0, 0.0, -40.0], [10.0, 10.0, 10.0]),
];

#[test]
fn template_matches_reference_exactly() {
    let src = template("mat4.ortho(projectionMatrix, -100, 100, -100, 100, 0.01, 500);");
    for (t, s) in PLACES {
        let want = reference(ortho_ref(-100.0, 100.0, -100.0, 100.0, 0.01, 500.0), EYE, t, s);
        assert_eq!(matrix(&src, t, s), want, "at {t:?} {s:?}");
    }
}

#[test]
fn records_the_gl_calls_and_return_line() {
    let src = template("mat4.ortho(projectionMatrix, -150, 150, -150, 150, 1, 400);");
    let mut light = load(&src).expect("loads");
    let m = light.light_matrix([1.0, 2.0, 3.0], [4.0, 5.0, 6.0]).expect("runs");
    let names: Vec<&str> = m.calls.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "mat4.create",
            "mat4.create",
            "mat4.create",
            "mat4.create",
            "mat4.translate",
            "mat4.scale",
            "mat4.lookAt",
            "mat4.ortho",
            "mat4.multiply",
            "mat4.multiply"
        ]
    );
    let ortho = &m.calls[7];
    assert_eq!(ortho.args, [-150.0, 150.0, -150.0, 150.0, 1.0, 400.0]);
    let line_of = |needle: &str| src.lines().position(|l| l.contains(needle)).map(|i| i + 1);
    assert_eq!(Some(ortho.line), line_of("mat4.ortho"));
    assert_eq!(m.calls[4].args.len(), 16 + 3, "the matrix and the vector, flattened");
    assert_eq!(&m.calls[4].args[16..], [1.0, 2.0, 3.0]);
    assert_eq!(m.calls[6].args, [0.0, 80.0, 80.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0]);
    assert_eq!(Some(m.return_line), line_of("return lightMVP"));
    assert!(light.notes().is_empty(), "{:?}", light.notes());
}

#[test]
fn variables_and_arithmetic_in_ortho_arguments() {
    let literal = matrix(
        &template("mat4.ortho(projectionMatrix, -125, 125, -125, 125, 1.0, 300.0);"),
        [0.0; 3],
        [1.0; 3],
    );
    let variants = [
        "let right = 125;\n        let left = -right;\n        let top = 125;\n        let bottom = -top;\n        mat4.ortho(projectionMatrix, left, right, bottom, top, 1.0, 300.0);",
        "var r = 125; var l = -r; var t = 125; var b = -t; var n = 1; var f = 300\n        mat4.ortho(projectionMatrix, l, r, b, t, n, f)",
        "const aspect = 1;\n        const size = 250.0;\n        mat4.ortho(projectionMatrix,\n            -aspect * size / 2,\n            aspect * size / 2,\n            -size/2,\n            size/2,\n            1.0, 300.0);",
        "const half = 5 ** 3, depth = [1, 300];\n        mat4.ortho(projectionMatrix, -half, half, -half, half, ...depth);",
    ];
    for v in variants {
        assert_eq!(matrix(&template(v), [0.0; 3], [1.0; 3]), literal, "{v}");
    }
}

#[test]
fn from_translation_and_scaling_then_multiply() {
    let proj = "mat4.ortho(projectionMatrix, -100, 100, -100, 100, 1, 500);";
    let model = "let t = mat4.create()\n        let s = mat4.create()\n        mat4.fromTranslation(t, translate)\n        mat4.fromScaling(s, scale)\n        mat4.multiply(modelMatrix, t, s)";
    for (t, s) in PLACES {
        let want = reference(ortho_ref(-100.0, 100.0, -100.0, 100.0, 1.0, 500.0), EYE, t, s);
        assert_eq!(matrix(&light_class(model, VIEW, proj), t, s), want);
    }
}

#[test]
fn spread_into_vec3_set_and_normalised_eye() {
    let proj = "let range = 100;\n        mat4.ortho(projectionMatrix, -range, range, -range, range, -range, range);";
    let view = "let eye = vec3.create(), center = vec3.create(), up = vec3.create();\n        vec3.set(eye, ...this.lightPos);\n        vec3.set(center, ...this.focalPoint);\n        vec3.set(up, ...this.lightUp);\n        vec3.normalize(eye, eye);\n        vec3.normalize(up, up)\n        mat4.lookAt(viewMatrix, eye, center, up);";
    let plain_view = "mat4.lookAt(viewMatrix, this.lightPos, this.focalPoint, this.lightUp);";
    let (t, s) = PLACES[2];
    let normalised = matrix(&light_class(MODEL, view, proj), t, s);
    let plain = matrix(&light_class(MODEL, plain_view, proj), t, s);
    assert_ne!(normalised, plain, "a unit-length eye moves the light");
    let eye = [0.0, f64::from(std::f32::consts::FRAC_1_SQRT_2), f64::from(std::f32::consts::FRAC_1_SQRT_2)];
    let want = reference(ortho_ref(-100.0, 100.0, -100.0, 100.0, -100.0, 100.0), eye, t, s);
    for (a, b) in normalised.iter().zip(want) {
        assert!((a - b).abs() <= 1e-6 * b.abs().max(1.0), "{normalised:?} vs {want:?}");
    }
}

#[test]
fn translate_rotate_scale_signature() {
    let src = template("mat4.ortho(projectionMatrix, -200, 200, -200, 200, 0.01, 500);").replace(
        "CalcLightMVP(translate, scale) {",
        "CalcLightMVP(translate, rotate, scale) {",
    ).replace(
        "mat4.scale(modelMatrix, modelMatrix, scale);",
        "mat4.rotateX(modelMatrix, modelMatrix, rotate[0])\n        mat4.rotateY(modelMatrix, modelMatrix, rotate[1])\n        mat4.rotateZ(modelMatrix, modelMatrix, rotate[2])\n        mat4.scale(modelMatrix, modelMatrix, scale)",
    );
    let (t, s) = PLACES[2];
    let want = reference(ortho_ref(-200.0, 200.0, -200.0, 200.0, 0.01, 500.0), EYE, t, s);
    assert_eq!(matrix(&src, t, s), want);
    // Names decide, not positions.
    let swapped = template("mat4.ortho(projectionMatrix, -200, 200, -200, 200, 0.01, 500);")
        .replace("CalcLightMVP(translate, scale) {", "CalcLightMVP(objScale, objTranslation) {")
        .replace("modelMatrix, translate)", "modelMatrix, objTranslation)")
        .replace("modelMatrix, scale)", "modelMatrix, objScale)");
    assert_eq!(matrix(&swapped, t, s), want);
}

#[test]
fn rest_parameters_take_the_positions() {
    let src = "class DirectionalLight {\n  CalcLightMVP(...args) {\n    const [t, s] = args;\n    return mat4.scale([], mat4.fromTranslation(mat4.create(), t), s);\n  }\n}\n";
    let m = matrix(src, [1.0, 2.0, 3.0], [4.0, 5.0, 6.0]);
    assert_eq!((m[0], m[5], m[10], m[12], m[13], m[14]), (4.0, 5.0, 6.0, 1.0, 2.0, 3.0));
}

#[test]
fn rotations_rotate() {
    let model = "mat4.rotateZ(modelMatrix, modelMatrix, Math.PI / 2);";
    let src = light_class(model, "", "");
    let m = matrix(&src, [0.0; 3], [1.0; 3]);
    // x goes to y: the first column is (0, 1, 0, 0).
    assert!(m[0].abs() < 1e-7 && (m[1] - 1.0).abs() < 1e-7 && m[4] + 1.0 < 1e-7, "{m:?}");
    let by_axis = light_class("mat4.rotate(modelMatrix, modelMatrix, Math.PI / 2, [0, 0, 2]);", "", "");
    assert_eq!(matrix(&by_axis, [0.0; 3], [1.0; 3]), m);
    let from = light_class("mat4.fromZRotation(modelMatrix, Math.PI / 2);", "", "");
    assert_eq!(matrix(&from, [0.0; 3], [1.0; 3]), m);
}

#[test]
fn mirrored_ortho_near_zero_and_negative_near() {
    let (t, s) = PLACES[1];
    let mirrored = matrix(&template("mat4.ortho(projectionMatrix, 100, -100, 100, -100, 1.0, 400.0);"), t, s);
    assert_eq!(mirrored, reference(ortho_ref(100.0, -100.0, 100.0, -100.0, 1.0, 400.0), EYE, t, s));
    let normal = matrix(&template("mat4.ortho(projectionMatrix, -100, 100, -100, 100, 1.0, 400.0);"), t, s);
    assert_eq!(mirrored[0], -normal[0]);
    for proj in [
        "mat4.ortho(projectionMatrix, -100, 100, -100, 100, 0, 1000);",
        "mat4.ortho(projectionMatrix, -200,200,-200,200,-10,2000);",
    ] {
        let m = matrix(&template(proj), t, s);
        assert!(m.iter().all(|x| x.is_finite()), "{proj}: {m:?}");
    }
    let zero = matrix(&template("mat4.ortho(projectionMatrix, -100, 100, -100, 100, 0, 1000);"), t, s);
    assert_eq!(zero, reference(ortho_ref(-100.0, 100.0, -100.0, 100.0, 0.0, 1000.0), EYE, t, s));
}

#[test]
fn perspective_light() {
    let (t, s) = PLACES[0];
    let m = matrix(&template("mat4.perspective(projectionMatrix, Math.PI / 2, 1, 20, 1000);"), t, s);
    let f = 1.0 / (std::f64::consts::PI / 4.0).tan();
    let proj = round32([
        f,
        0.0,
        0.0,
        0.0,
        0.0,
        f,
        0.0,
        0.0,
        0.0,
        0.0,
        -1020.0 / 980.0,
        -1.0,
        0.0,
        0.0,
        -40000.0 / 980.0,
        0.0,
    ]);
    assert_eq!(m, reference(proj, EYE, t, s));
    let infinite = matrix(&template("mat4.perspective(projectionMatrix, 1.8, 0.5, 20, Infinity);"), t, s);
    let omitted = matrix(&template("mat4.perspective(projectionMatrix, 1.8, 0.5, 20);"), t, s);
    assert_eq!(infinite, omitted);
    assert!(infinite.iter().all(|x| x.is_finite()));
}

#[test]
fn template_trap_translates_by_the_light_position() {
    let src = template("mat4.ortho(projectionMatrix, -100, 100, -100, 100, 0.01, 500);")
        .replace("modelMatrix, modelMatrix, translate)", "modelMatrix, modelMatrix, this.lightPos)");
    let (t, s) = PLACES[2];
    let want = reference(ortho_ref(-100.0, 100.0, -100.0, 100.0, 0.01, 500.0), EYE, EYE, s);
    assert_eq!(matrix(&src, t, s), want);
}

#[test]
fn no_semicolons_export_default_and_comments() {
    let src = "// 方向光\nexport default class DirectionalLight {\n  constructor(i, c, lightPos, focalPoint, lightUp, has, gl) {\n    this.mesh = Mesh.cube(setTransform(0, 0, 0, 0.2, 0.2, 0.2, 0))\n    this.lightPos = lightPos\n    this.focalPoint = focalPoint\n    this.lightUp = lightUp\n    this.fbo = new FBO(gl)\n    console.log(\"灯光已创建\", this)\n  }\n  /* 计算 MVP */\n  CalcLightMVP(translate, scale) {\n    let out = mat4.create()\n    let m = mat4.create()\n    let v = mat4.create()\n    let p = mat4.create()\n    mat4.translate(m, m, translate)\n    mat4.scale(m, m, scale)\n    mat4.lookAt(v, this.lightPos, this.focalPoint, this.lightUp)\n    mat4.ortho(p, -100, 100, -100, 100, 0.01, 500)\n    mat4.multiply(out, p, v)\n    mat4.multiply(out, out, m)\n    return out\n  }\n}\n";
    let (t, s) = PLACES[0];
    assert_eq!(matrix(src, t, s), reference(ortho_ref(-100.0, 100.0, -100.0, 100.0, 0.01, 500.0), EYE, t, s));
}

#[test]
fn framework_constructor_with_stubs_constructs() {
    let src = template("mat4.ortho(projectionMatrix, -100, 100, -100, 100, 0.01, 500);").replace(
        "this.hasShadowMap = hasShadowMap;",
        "this.hasShadowMap = hasShadowMap;\n        console.warn(`强度 ${lightIntensity}`, this.mat, gl.createFramebuffer());\n        this.fbo2 = gl.getExtension('WEBGL_depth_texture').x;",
    );
    let light = load(&src).expect("loads");
    assert!(light.notes().is_empty(), "{:?}", light.notes());
}

#[test]
fn function_style_light_and_imports() {
    let src = "import { mat4 } from './gl-matrix.js';\nfunction DirectionalLight(a, b, lightPos, focalPoint, lightUp) {\n  this.lightPos = lightPos; this.focalPoint = focalPoint; this.lightUp = lightUp;\n}\nDirectionalLight.prototype.CalcLightMVP = function (translate, scale) {\n  const p = mat4.create(), v = mat4.create(), m = mat4.create();\n  mat4.ortho(p, -100, 100, -100, 100, 0.01, 500);\n  mat4.lookAt(v, this.lightPos, this.focalPoint, this.lightUp);\n  mat4.fromTranslation(m, translate);\n  mat4.scale(m, m, scale);\n  return mat4.multiply(p, mat4.multiply(p, p, v), m);\n};\n";
    let mut light = load(src).expect("loads");
    assert_eq!(light.notes().len(), 1, "the import is noted");
    let (t, s) = PLACES[2];
    let m = light.light_matrix(t, s).expect("runs").clip_from_object;
    assert_eq!(m, reference(ortho_ref(-100.0, 100.0, -100.0, 100.0, 0.01, 500.0), EYE, t, s));
}

#[test]
fn extends_a_stub_or_a_user_class() {
    let base = "class Light extends Material {\n  constructor(pos) { super({}, 'x'); this.lightPos = pos; }\n  get range() { return 100; }\n}\n";
    let src = format!(
        "{base}class DirectionalLight extends Light {{\n  near = 0.01;\n  constructor(i, c, lightPos, focalPoint, lightUp) {{ super(lightPos); this.focalPoint = focalPoint; this.lightUp = lightUp; }}\n  CalcLightMVP(translate, scale) {{\n    const r = this.range, p = mat4.create(), v = mat4.create(), m = mat4.create();\n    mat4.ortho(p, -r, r, -r, r, this.near, 500);\n    mat4.lookAt(v, this.lightPos, this.focalPoint, this.lightUp);\n    mat4.translate(m, m, translate); mat4.scale(m, m, scale);\n    return mat4.mul(p, mat4.mul(p, p, v), m);\n  }}\n}}\n"
    );
    let (t, s) = PLACES[1];
    assert_eq!(
        matrix(&src, t, s),
        reference(ortho_ref(-100.0, 100.0, -100.0, 100.0, 0.01, 500.0), EYE, t, s)
    );
}

#[test]
fn failing_constructor_falls_back_to_template_fields() {
    let src = template("mat4.ortho(projectionMatrix, -100, 100, -100, 100, 0.01, 500);").replace(
        "this.fbo = new FBO(gl);",
        "this.fbo = new FBO(gl);\n        this.extra = undefinedThing.size;",
    );
    let mut light = load(&src).expect("loads");
    assert_eq!(light.notes().len(), 1);
    assert!(light.notes()[0].contains("undefinedThing"), "{:?}", light.notes());
    let (t, s) = PLACES[0];
    let m = light.light_matrix(t, s).expect("runs").clip_from_object;
    assert_eq!(m, reference(ortho_ref(-100.0, 100.0, -100.0, 100.0, 0.01, 500.0), EYE, t, s));
}

#[test]
fn engine_values_reach_the_constructor() {
    let mut engine = EngineLight::framework();
    engine.position.value = [10.0, 50.0, 20.0];
    let src = template("mat4.ortho(projectionMatrix, -100, 100, -100, 100, 0.01, 500);");
    let mut light = LightScript::load(&src, FILE, &engine, Limits::default()).expect("loads");
    let m = light.light_matrix([0.0; 3], [1.0; 3]).expect("runs");
    assert_eq!(m.calls[6].args[..3], [10.0, 50.0, 20.0]);
    // Each call is independent: a script that mutates its light does so visibly, but runs again.
    assert!(light.light_matrix([0.0; 3], [1.0; 3]).is_ok());
}

#[test]
fn light_script_is_send() {
    fn is_send<T: Send>() {}
    is_send::<LightScript>();
    is_send::<EngineLight>();
}

/// Evaluates `lines` (statements ending in `out.push(number)`) inside CalcLightMVP and
/// returns the pushed numbers.
fn run_values(lines: &str) -> Vec<f32> {
    let src = format!(
        "class DirectionalLight {{\n  CalcLightMVP(translate, scale) {{\n    const out = [];\n{lines}\n    while (out.length < 16) out.push(0);\n    return out.slice(0, 16);\n  }}\n}}\n"
    );
    let n = lines.matches("out.push").count();
    matrix(&src, [0.0; 3], [1.0; 3])[..n.min(16)].to_vec()
}

#[test]
fn language_features() {
    let got = run_values(
        r#"
    const fs = []; for (let i = 0; i < 3; i++) fs.push(() => i);
    out.push(fs.map(f => f()).reduce((a, b) => a * 10 + b, 0));            // 12 (per-iteration let)
    const { a = 5, b: [x, , y = 7] = [], ...rest } = { b: [1, 2], c: 3, d: 4 };
    out.push(a * 1000 + x * 100 + y * 10 + Object.keys(rest).length);       // 5172
    const o = { v: 2, get twice() { return this.v * 2; }, set twice(n) { this.v = n / 2; } };
    o.twice = 18; out.push(o.twice + o.v);                                  // 27
    out.push(`${1 + 1}-${'x'.repeat(3)}`.length);                           // 5
    out.push((typeof undefinedName === 'undefined') + (null == undefined) + (0 === -0) + ('1' == 1)); // 4
    out.push([1, 2, 3] instanceof Array ? ('length' in [1] ? 1 : 2) : 3);   // 1
    out.push(o?.missing?.deep ?? 42);                                        // 42
    let s = 0; for (const k in { p: 1, q: 2 }) s += k.length; for (const v of [4, 5]) s += v; out.push(s); // 11
    switch (3) { case 1: out.push(-1); case 3: out.push(30); case 4: out.push(40); break; default: out.push(-2); } // 30, 40
    try { null.x; } catch (e) { out.push(e instanceof TypeError ? 1 : 0); } // 1
    out.push(Math.max(...[3, 9, 2]) + 2 ** 10 - (7 % 4) + (-7 >> 1) + (5 & 3) + (Math.min() === Infinity)); // 1028
    out.push(parseInt('0x1f') + parseFloat('2.5e1px') + Number('  8 ') + (+true)); // 31 + 25 + 8 + 1 = 65
    class P { static make() { return new this(); } constructor() { this.k = 2; } } class Q extends P { constructor() { super(); this.k *= 3; } }
    out.push(Q.make().k);                                                   // 6
"#,
    );
    assert_eq!(got[..10], [12.0, 5172.0, 27.0, 5.0, 4.0, 1.0, 42.0, 11.0, 30.0, 40.0]);
    assert_eq!(got[10], 1.0);
    assert_eq!(got[11], 1028.0);
    assert_eq!(got[12..14], [65.0, 6.0]);
}

#[test]
fn numbers_format_like_javascript() {
    use super::ops::num_to_string;
    let cases = [
        (0.1 + 0.2, "0.30000000000000004"),
        (1e21, "1e+21"),
        (1e-7, "1e-7"),
        (123456.0, "123456"),
        (-1.5e-5, "-0.000015"),
        (2.5e25, "2.5e+25"),
        (f64::NAN, "NaN"),
        (-0.0, "0"),
    ];
    for (x, s) in cases {
        assert_eq!(num_to_string(x), s);
    }
    let got = run_values(
        "out.push(String(0.1 + 0.2).length); out.push((1 / 3).toFixed(2).length); out.push([1, [2, 3]].join('-').length); out.push(JSON.stringify({ a: [1, 'x', null] }).length);",
    );
    assert_eq!(got, [19.0, 4.0, 5.0, 18.0]);
}

#[test]
fn gl_matrix_helpers_agree() {
    let got = run_values(
        r#"
    const m = mat4.create(); mat4.perspective(m, 1, 1.5, 0.1, 100);
    const inv = mat4.create(); mat4.invert(inv, m);
    const id = mat4.multiply(mat4.create(), m, inv);
    let err = 0; for (let i = 0; i < 16; i++) err = Math.max(err, Math.abs(id[i] - (i % 5 === 0 ? 1 : 0)));
    out.push(err < 1e-5 ? 1 : 0);
    out.push(mat4.invert(mat4.create(), mat4.fromValues(1,2,3,4, 2,4,6,8, 0,0,1,0, 0,0,0,1)) === null ? 1 : 0);
    out.push(mat4.determinant(mat4.fromScaling(mat4.create(), [2, 3, 4])));
    const p = vec3.transformMat4(vec3.create(), [1, 2, 3], mat4.fromTranslation(mat4.create(), [10, 20, 30]));
    out.push(p[0] + p[1] + p[2]);
    const n = vec3.normalize(vec3.create(), [0, 0, 0]); out.push(n[0] + n[1] + n[2]);
    out.push(vec3.length(vec3.cross([], [1, 0, 0], [0, 1, 0])) * vec3.dot([1, 2, 3], [4, 5, 6]));
    const t = mat4.targetTo(mat4.create(), [0, 0, 5], [0, 0, 0], [0, 1, 0]); out.push(t[14]);
    const eq = mat4.lookAt(mat4.create(), [1, 1, 1], [1, 1, 1], [0, 1, 0]); out.push(eq[0] + eq[5] + eq[10] + eq[15]);
    out.push(glMatrix.toRadian(180) === Math.PI ? 1 : 0);
    const f = new Float32Array([0.1]); out.push(f[0] === 0.1 ? 0 : 1);
    const tr = mat4.transpose(mat4.create(), mat4.fromTranslation(mat4.create(), [1, 2, 3])); out.push(tr[3] + tr[7] * 10 + tr[11] * 100);
"#,
    );
    assert_eq!(got, [1.0, 1.0, 24.0, 66.0, 0.0, 32.0, 5.0, 4.0, 1.0, 1.0, 321.0]);
}
