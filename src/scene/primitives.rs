//! The built-in shapes a scene names by word (`mesh = "sphere"`): generated, not loaded.

use super::mesh::{Mesh, MeshPart, Vertex};
use glam::{DVec3, Vec3};
use std::f64::consts::{PI, TAU};

/// Names accepted by [`primitive`].
pub const PRIMITIVES: &[&str] = &["plane", "cube", "sphere", "cylinder", "torus"];

const SEGMENTS: u32 = 48;
const RINGS: u32 = 24;

/// A built-in shape centred on the origin (one part, no material), or `None`
/// for an unknown name.
///
/// `plane`: unit square in XZ facing +Y (single-sided); `cube`: -0.5..0.5 with
/// flat faces; `sphere`: radius 0.5; `cylinder`: radius 0.5, y in -0.5..0.5,
/// with flat caps; `torus`: radii 0.35 and 0.15 around the Y axis.
pub fn primitive(name: &str) -> Option<Mesh> {
    let mut b = Builder::default();
    match name {
        "plane" => b.face(DVec3::ZERO, DVec3::Y, DVec3::NEG_Z),
        "cube" => {
            let [x, y, z] = [DVec3::X, DVec3::Y, DVec3::Z];
            let faces = [(x, y), (-x, y), (z, y), (-z, y), (y, -z), (-y, z)];
            for (n, up) in faces {
                b.face(n * 0.5, n, up);
            }
        }
        "sphere" => b.grid(SEGMENTS, RINGS, |u, v| {
            let (st, ct) = (PI * v).sin_cos();
            let (sp, cp) = (TAU * u).sin_cos();
            let n = DVec3::new(st * sp, ct, st * cp);
            vertex(n * 0.5, n, u, v)
        }),
        "cylinder" => {
            b.grid(SEGMENTS, 1, |u, v| {
                let (sp, cp) = (TAU * u).sin_cos();
                let n = DVec3::new(sp, 0.0, cp);
                vertex(DVec3::new(0.5 * sp, 0.5 - v, 0.5 * cp), n, u, v)
            });
            // Caps: rings of radius 0.5 * v around the centre, planar uvs.
            b.grid(SEGMENTS, 1, |u, v| {
                let (sp, cp) = (TAU * u).sin_cos();
                let p = DVec3::new(0.5 * v * sp, 0.5, 0.5 * v * cp);
                vertex(p, DVec3::Y, 0.5 + p.x, 0.5 + p.z)
            });
            b.grid(SEGMENTS, 1, |u, v| {
                let (sp, cp) = (-TAU * u).sin_cos();
                let p = DVec3::new(0.5 * v * sp, -0.5, 0.5 * v * cp);
                vertex(p, DVec3::NEG_Y, 0.5 + p.x, 0.5 - p.z)
            });
        }
        "torus" => b.grid(SEGMENTS, RINGS, |u, v| {
            let (major, minor) = (0.35, 0.15);
            let (sp, cp) = (TAU * u).sin_cos();
            let (ss, cs) = (TAU * v).sin_cos();
            let n = DVec3::new(cs * sp, -ss, cs * cp);
            let ring = major + minor * cs;
            vertex(DVec3::new(ring * sp, -minor * ss, ring * cp), n, u, v)
        }),
        _ => return None,
    }
    Some(Mesh {
        name: name.to_owned(),
        parts: vec![MeshPart {
            name: name.to_owned(),
            index_start: 0,
            index_count: b.indices.len() as u32,
            material: None,
        }],
        vertices: b.vertices,
        indices: b.indices,
        materials: Vec::new(),
    })
}

fn vertex(p: DVec3, n: DVec3, u: f64, v: f64) -> Vertex {
    Vertex { position: p.as_vec3().into(), normal: n.normalize().as_vec3().into(), uv: [u as f32, v as f32] }
}

#[derive(Default)]
struct Builder {
    vertices: Vec<Vertex>,
    indices: Vec<u32>,
}

impl Builder {
    /// A unit square centred on `centre`, facing `n`, with `up` towards v = 0.
    fn face(&mut self, centre: DVec3, n: DVec3, up: DVec3) {
        let right = up.cross(n);
        self.grid(1, 1, |u, v| vertex(centre + right * (u - 0.5) - up * (v - 0.5), n, u, v));
    }

    /// A `(nu + 1) x (nv + 1)` vertex grid from `f(u, v)`, u and v in 0..=1.
    /// `f` must map increasing u to the right and increasing v downwards as
    /// seen from the front, like texture coordinates on an image; the cells
    /// are then emitted counter-clockwise from the front. Zero-area triangles
    /// (poles, cap centres) are dropped.
    fn grid(&mut self, nu: u32, nv: u32, f: impl Fn(f64, f64) -> Vertex) {
        let base = self.vertices.len() as u32;
        for iv in 0..=nv {
            for iu in 0..=nu {
                let vertex = f(f64::from(iu) / f64::from(nu), f64::from(iv) / f64::from(nv));
                self.vertices.push(vertex);
            }
        }
        for iv in 0..nv {
            for iu in 0..nu {
                let i00 = base + iv * (nu + 1) + iu;
                let (i10, i01, i11) = (i00 + 1, i00 + nu + 1, i00 + nu + 2);
                self.triangle([i00, i01, i11]);
                self.triangle([i00, i11, i10]);
            }
        }
    }

    fn triangle(&mut self, tri: [u32; 3]) {
        let [a, b, c] = tri.map(|i| Vec3::from(self.vertices[i as usize].position));
        if (b - a).cross(c - a).length() > 1e-9 {
            self.indices.extend_from_slice(&tri);
        }
    }
}
