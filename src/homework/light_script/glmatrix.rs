//! gl-matrix's maths, written from its documented behaviour [GlMatrix-Mat4]: column-major 4x4
//! matrices (m[12..15] hold the translation), computed in f64 in the same operation order as the
//! library so the browser's doubles are reproduced; the caller rounds on store.

pub(super) type M4 = [f64; 16];
pub(super) type V3 = [f64; 3];

/// gl-matrix's `glMatrix.EPSILON`.
pub(super) const EPSILON: f64 = 0.000001;

/// `Math.hypot` as V8 computes it: scaled by the largest magnitude, Kahan-summed.
pub(super) fn js_hypot(xs: &[f64]) -> f64 {
    let mut max = 0.0f64;
    let mut nan = false;
    for x in xs {
        let a = x.abs();
        if a.is_nan() {
            nan = true;
        } else if a > max {
            max = a;
        }
    }
    if max == f64::INFINITY {
        return f64::INFINITY;
    }
    if nan {
        return f64::NAN;
    }
    if max == 0.0 {
        return 0.0;
    }
    let (mut sum, mut compensation) = (0.0f64, 0.0f64);
    for x in xs {
        let n = x.abs() / max;
        let summand = n * n - compensation;
        let preliminary = sum + summand;
        compensation = (preliminary - sum) - summand;
        sum = preliminary;
    }
    sum.sqrt() * max
}

pub(super) fn identity() -> M4 {
    let mut m = [0.0; 16];
    m[0] = 1.0;
    m[5] = 1.0;
    m[10] = 1.0;
    m[15] = 1.0;
    m
}

/// a * b (b applied first).
pub(super) fn multiply(a: &M4, b: &M4) -> M4 {
    let mut out = [0.0; 16];
    for col in 0..4 {
        let (b0, b1, b2, b3) = (b[4 * col], b[4 * col + 1], b[4 * col + 2], b[4 * col + 3]);
        for row in 0..4 {
            out[4 * col + row] = b0 * a[row] + b1 * a[4 + row] + b2 * a[8 + row] + b3 * a[12 + row];
        }
    }
    out
}

pub(super) fn translate(a: &M4, v: V3) -> M4 {
    let [x, y, z] = v;
    let mut out = *a;
    for row in 0..4 {
        out[12 + row] = a[row] * x + a[4 + row] * y + a[8 + row] * z + a[12 + row];
    }
    out
}

pub(super) fn scale(a: &M4, v: V3) -> M4 {
    let mut out = *a;
    for (col, s) in v.iter().enumerate() {
        for row in 0..4 {
            out[4 * col + row] = a[4 * col + row] * s;
        }
    }
    out
}

/// The 3x3 rotation about a unit axis, rows as gl-matrix names them (b00..b22).
fn axis_rotation(rad: f64, axis: V3) -> Option<[[f64; 3]; 3]> {
    let len = js_hypot(&axis);
    if len < EPSILON {
        return None;
    }
    let inv = 1.0 / len;
    let (x, y, z) = (axis[0] * inv, axis[1] * inv, axis[2] * inv);
    let (s, c) = (rad.sin(), rad.cos());
    let t = 1.0 - c;
    Some([
        [x * x * t + c, y * x * t + z * s, z * x * t - y * s],
        [x * y * t - z * s, y * y * t + c, z * y * t + x * s],
        [x * z * t + y * s, y * z * t - x * s, z * z * t + c],
    ])
}

/// None for an axis of (near) zero length, where gl-matrix returns null.
pub(super) fn rotate(a: &M4, rad: f64, axis: V3) -> Option<M4> {
    let b = axis_rotation(rad, axis)?;
    let mut out = *a;
    for (col, brow) in b.iter().enumerate() {
        for row in 0..4 {
            out[4 * col + row] = a[row] * brow[0] + a[4 + row] * brow[1] + a[8 + row] * brow[2];
        }
    }
    Some(out)
}

pub(super) fn from_rotation(rad: f64, axis: V3) -> Option<M4> {
    let b = axis_rotation(rad, axis)?;
    let mut out = identity();
    for (col, brow) in b.iter().enumerate() {
        out[4 * col..4 * col + 3].copy_from_slice(brow);
    }
    Some(out)
}

/// Rotation about x (columns 1, 2) or z (columns 0, 1), as gl-matrix writes it:
/// first' = first * c + second * s, second' = second * c - first * s.
fn rotate_plane(a: &M4, rad: f64, first: usize, second: usize) -> M4 {
    let (s, c) = (rad.sin(), rad.cos());
    let mut out = *a;
    for row in 0..4 {
        let (p, q) = (a[4 * first + row], a[4 * second + row]);
        out[4 * first + row] = p * c + q * s;
        out[4 * second + row] = q * c - p * s;
    }
    out
}

pub(super) fn rotate_x(a: &M4, rad: f64) -> M4 {
    rotate_plane(a, rad, 1, 2)
}

pub(super) fn rotate_y(a: &M4, rad: f64) -> M4 {
    // y mixes columns 0 and 2 with the opposite sign.
    let (s, c) = (rad.sin(), rad.cos());
    let mut out = *a;
    for row in 0..4 {
        let (p, q) = (a[row], a[8 + row]);
        out[row] = p * c - q * s;
        out[8 + row] = p * s + q * c;
    }
    out
}

pub(super) fn rotate_z(a: &M4, rad: f64) -> M4 {
    rotate_plane(a, rad, 0, 1)
}

pub(super) fn from_translation(v: V3) -> M4 {
    let mut out = identity();
    out[12..15].copy_from_slice(&v);
    out
}

pub(super) fn from_scaling(v: V3) -> M4 {
    let mut out = identity();
    out[0] = v[0];
    out[5] = v[1];
    out[10] = v[2];
    out
}

/// `fromXRotation` (axis 0), `fromYRotation` (1), `fromZRotation` (2).
pub(super) fn from_axis_rotation(axis: usize, rad: f64) -> M4 {
    let (s, c) = (rad.sin(), rad.cos());
    let mut out = identity();
    let (i, j) = match axis {
        0 => (1, 2),
        1 => (2, 0),
        _ => (0, 1),
    };
    out[5 * i] = c;
    out[4 * i + j] = s;
    out[4 * j + i] = -s;
    out[5 * j] = c;
    out
}

pub(super) fn look_at(eye: V3, center: V3, up: V3) -> M4 {
    if (0..3).all(|i| (eye[i] - center[i]).abs() < EPSILON) {
        return identity();
    }
    let mut z = [eye[0] - center[0], eye[1] - center[1], eye[2] - center[2]];
    let len = 1.0 / js_hypot(&z);
    z = [z[0] * len, z[1] * len, z[2] * len];
    let x = unit_or_zero(cross(up, z));
    let y = unit_or_zero(cross(z, x));
    let mut out = [0.0; 16];
    for i in 0..3 {
        out[4 * i] = x[i];
        out[4 * i + 1] = y[i];
        out[4 * i + 2] = z[i];
    }
    out[12] = -(x[0] * eye[0] + x[1] * eye[1] + x[2] * eye[2]);
    out[13] = -(y[0] * eye[0] + y[1] * eye[1] + y[2] * eye[2]);
    out[14] = -(z[0] * eye[0] + z[1] * eye[1] + z[2] * eye[2]);
    out[15] = 1.0;
    out
}

fn unit_or_zero(v: V3) -> V3 {
    let len = js_hypot(&v);
    if len == 0.0 || len.is_nan() {
        return [0.0; 3];
    }
    let inv = 1.0 / len;
    [v[0] * inv, v[1] * inv, v[2] * inv]
}

pub(super) fn target_to(eye: V3, target: V3, up: V3) -> M4 {
    let z = normalize([eye[0] - target[0], eye[1] - target[1], eye[2] - target[2]]);
    let x = normalize(cross(up, z));
    let y = cross(z, x);
    let mut out = [0.0; 16];
    out[0..3].copy_from_slice(&x);
    out[4..7].copy_from_slice(&y);
    out[8..11].copy_from_slice(&z);
    out[12..15].copy_from_slice(&eye);
    out[15] = 1.0;
    out
}

/// GL clip conventions: z in -1..1 between near and far.
pub(super) fn ortho(left: f64, right: f64, bottom: f64, top: f64, near: f64, far: f64) -> M4 {
    let lr = 1.0 / (left - right);
    let bt = 1.0 / (bottom - top);
    let nf = 1.0 / (near - far);
    let mut out = [0.0; 16];
    out[0] = -2.0 * lr;
    out[5] = -2.0 * bt;
    out[10] = 2.0 * nf;
    out[12] = (left + right) * lr;
    out[13] = (top + bottom) * bt;
    out[14] = (far + near) * nf;
    out[15] = 1.0;
    out
}

/// `far` None (null, undefined) or Infinity gives gl-matrix's infinite far plane.
pub(super) fn perspective(fovy: f64, aspect: f64, near: f64, far: Option<f64>) -> M4 {
    let f = 1.0 / (fovy / 2.0).tan();
    let mut out = [0.0; 16];
    out[0] = f / aspect;
    out[5] = f;
    out[11] = -1.0;
    match far {
        Some(far) if far != f64::INFINITY => {
            let nf = 1.0 / (near - far);
            out[10] = (far + near) * nf;
            out[14] = 2.0 * far * near * nf;
        }
        _ => {
            out[10] = -1.0;
            out[14] = -2.0 * near;
        }
    }
    out
}

pub(super) fn frustum(left: f64, right: f64, bottom: f64, top: f64, near: f64, far: f64) -> M4 {
    let rl = 1.0 / (right - left);
    let tb = 1.0 / (top - bottom);
    let nf = 1.0 / (near - far);
    let mut out = [0.0; 16];
    out[0] = near * 2.0 * rl;
    out[5] = near * 2.0 * tb;
    out[8] = (right + left) * rl;
    out[9] = (top + bottom) * tb;
    out[10] = (far + near) * nf;
    out[11] = -1.0;
    out[14] = far * near * 2.0 * nf;
    out
}

/// 2x2 minors of the top two and bottom two rows-of-columns (Laplace expansion).
fn minors(a: &M4) -> [f64; 12] {
    [
        a[0] * a[5] - a[1] * a[4],
        a[0] * a[6] - a[2] * a[4],
        a[0] * a[7] - a[3] * a[4],
        a[1] * a[6] - a[2] * a[5],
        a[1] * a[7] - a[3] * a[5],
        a[2] * a[7] - a[3] * a[6],
        a[8] * a[13] - a[9] * a[12],
        a[8] * a[14] - a[10] * a[12],
        a[8] * a[15] - a[11] * a[12],
        a[9] * a[14] - a[10] * a[13],
        a[9] * a[15] - a[11] * a[13],
        a[10] * a[15] - a[11] * a[14],
    ]
}

pub(super) fn determinant(a: &M4) -> f64 {
    let b = minors(a);
    b[0] * b[11] - b[1] * b[10] + b[2] * b[9] + b[3] * b[8] - b[4] * b[7] + b[5] * b[6]
}

/// None for a singular matrix (gl-matrix returns null).
pub(super) fn invert(a: &M4) -> Option<M4> {
    let b = minors(a);
    let det = determinant(a);
    if det == 0.0 || det.is_nan() {
        return None;
    }
    let d = 1.0 / det;
    Some([
        (a[5] * b[11] - a[6] * b[10] + a[7] * b[9]) * d,
        (a[2] * b[10] - a[1] * b[11] - a[3] * b[9]) * d,
        (a[13] * b[5] - a[14] * b[4] + a[15] * b[3]) * d,
        (a[10] * b[4] - a[9] * b[5] - a[11] * b[3]) * d,
        (a[6] * b[8] - a[4] * b[11] - a[7] * b[7]) * d,
        (a[0] * b[11] - a[2] * b[8] + a[3] * b[7]) * d,
        (a[14] * b[2] - a[12] * b[5] - a[15] * b[1]) * d,
        (a[8] * b[5] - a[10] * b[2] + a[11] * b[1]) * d,
        (a[4] * b[10] - a[5] * b[8] + a[7] * b[6]) * d,
        (a[1] * b[8] - a[0] * b[10] - a[3] * b[6]) * d,
        (a[12] * b[4] - a[13] * b[2] + a[15] * b[0]) * d,
        (a[9] * b[2] - a[8] * b[4] - a[11] * b[0]) * d,
        (a[5] * b[7] - a[4] * b[9] - a[6] * b[6]) * d,
        (a[0] * b[9] - a[1] * b[7] + a[2] * b[6]) * d,
        (a[13] * b[1] - a[12] * b[3] - a[14] * b[0]) * d,
        (a[8] * b[3] - a[9] * b[1] + a[10] * b[0]) * d,
    ])
}

pub(super) fn transpose(a: &M4) -> M4 {
    let mut out = [0.0; 16];
    for i in 0..4 {
        for j in 0..4 {
            out[4 * i + j] = a[4 * j + i];
        }
    }
    out
}

pub(super) fn cross(a: V3, b: V3) -> V3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// gl-matrix's vec3.normalize: a zero vector stays zero.
pub(super) fn normalize(a: V3) -> V3 {
    let mut len = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
    if len > 0.0 {
        len = 1.0 / len.sqrt();
    }
    [a[0] * len, a[1] * len, a[2] * len]
}

/// vec3.transformMat4: with the w divide (w = 0 counts as 1, as `w || 1.0` does).
pub(super) fn transform_point(m: &M4, a: V3) -> V3 {
    let [x, y, z] = a;
    let w = m[3] * x + m[7] * y + m[11] * z + m[15];
    let w = if w == 0.0 || w.is_nan() { 1.0 } else { w };
    [
        (m[0] * x + m[4] * y + m[8] * z + m[12]) / w,
        (m[1] * x + m[5] * y + m[9] * z + m[13]) / w,
        (m[2] * x + m[6] * y + m[10] * z + m[14]) / w,
    ]
}

pub(super) fn transform_vec4(m: &M4, a: [f64; 4]) -> [f64; 4] {
    let [x, y, z, w] = a;
    let mut out = [0.0; 4];
    for (row, o) in out.iter_mut().enumerate() {
        *o = m[row] * x + m[4 + row] * y + m[8 + row] * z + m[12 + row] * w;
    }
    out
}
