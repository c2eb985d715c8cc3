//! Pictures of the shadow maps themselves: one map as linear depth, a point light's six cube
//! faces unfolded into a cross.

use super::{Legend, heat_color};
use crate::shadow::{DepthImage, ShadowViewGpu, depth_linear_from_ndc};
use image::{Rgba, RgbaImage};

/// The shadow map as linear depth (near = dark, far = light), stretched over the range of
/// depths actually stored (texels still at the clear value are shown in the no-surface colour).
pub fn shadow_map_image(map: &DepthImage, view: &ShadowViewGpu) -> (RgbaImage, Legend) {
    let linear: Vec<Option<f32>> =
        map.depth_ndc.iter().map(|&z| (z < 1.0).then(|| depth_linear_from_ndc(view, z))).collect();
    let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
    for d in linear.iter().flatten() {
        lo = lo.min(*d);
        hi = hi.max(*d);
    }
    if !lo.is_finite() {
        (lo, hi) = (view.near, view.far);
    }
    let span = (hi - lo).max(1e-6);
    let image = RgbaImage::from_fn(map.size, map.size, |x, y| match linear[(y * map.size + x) as usize] {
        Some(d) => heat_color((d - lo) / span),
        None => Rgba([250, 250, 250, 255]),
    });
    (
        image,
        Legend {
            label: "light-space depth",
            min: lo,
            max: hi,
            unit: "world units from the light (white: nothing stored)",
        },
    )
}

/// Where each cube face lies in the unfolded cross, (column, row) of a 4 x 3 grid: +Y above the
/// +Z face, the four around the horizon in a row (+X, +Z, -X, -Z: each face's right edge meets
/// the next one's left), -Y below. With `scene::CUBE_FACES`' up vectors every shared edge meets
/// its neighbour's.
pub const CUBE_CROSS_CELLS: [(u32, u32); 6] = [(0, 1), (2, 1), (1, 0), (1, 2), (1, 1), (3, 1)];

/// A light's maps as one picture with its legend: the one map of a spot or directional light, a
/// point light's six faces unfolded into a cross (`CUBE_CROSS_CELLS`) on one depth scale.
pub fn light_maps_image(maps: &[DepthImage], views: &[ShadowViewGpu]) -> (RgbaImage, Legend) {
    let cube = views.len() == 6 && views.iter().all(|v| v.cube == 1) && maps.len() == 6;
    if !cube {
        return shadow_map_image(&maps[0], &views[0]);
    }
    let view = &views[0];
    let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
    for z in maps.iter().flat_map(|m| &m.depth_ndc).filter(|&&z| z < 1.0) {
        let d = depth_linear_from_ndc(view, *z);
        (lo, hi) = (lo.min(d), hi.max(d));
    }
    if !lo.is_finite() {
        (lo, hi) = (view.near, view.far);
    }
    let span = (hi - lo).max(1e-6);
    let size = maps[0].size;
    let mut image = RgbaImage::from_pixel(4 * size, 3 * size, Rgba([40, 42, 48, 255]));
    for (map, &(column, row)) in maps.iter().zip(&CUBE_CROSS_CELLS) {
        for y in 0..size.min(map.size) {
            for x in 0..size.min(map.size) {
                let z = map.depth_ndc[(y * map.size + x) as usize];
                let color = if z < 1.0 {
                    heat_color((depth_linear_from_ndc(view, z) - lo) / span)
                } else {
                    Rgba([250, 250, 250, 255])
                };
                image.put_pixel(column * size + x, row * size + y, color);
            }
        }
    }
    let legend = Legend {
        label: "distance to the light, six cube faces unfolded (+Y above; +X, +Z, -X, -Z; -Y below)",
        min: lo,
        max: hi,
        unit: "world units (white: nothing stored)",
    };
    (image, legend)
}

/// Where uv of a point light's face `view` lies in its unfolded cross (0..1 over the picture): a
/// uv past the face's edge is read on the face its direction falls in (`map_tap`), and drawn there.
pub fn cube_cross_uv(view: &ShadowViewGpu, uv: [f32; 2]) -> [f32; 2] {
    let (face_view, face_uv) = crate::shadow::map_tap(view, glam::Vec2::from(uv));
    let (column, row) = CUBE_CROSS_CELLS[face_view.face as usize];
    [(column as f32 + face_uv.x) / 4.0, (row as f32 + face_uv.y) / 3.0]
}
