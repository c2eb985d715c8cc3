//! Pictures of the shadow maps themselves: one map as linear depth, a point light's six cube
//! faces unfolded into a cross, a sun's cascades side by side.

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

/// How a light's maps tile its picture: `columns` x `rows` cells of one map each, its view i in
/// `cells[i]`: a point light's six faces unfolded into a cross (`CUBE_CROSS_CELLS`), a sun's
/// cascades side by side (sharpest on the left), or the one map.
#[derive(Clone, Debug, PartialEq)]
pub struct MapsLayout {
    pub columns: u32,
    pub rows: u32,
    pub cells: Vec<(u32, u32)>,
}

impl MapsLayout {
    pub fn of(views: &[ShadowViewGpu]) -> Self {
        if views.len() == 6 && views.iter().all(|v| v.cube == 1) {
            return Self { columns: 4, rows: 3, cells: CUBE_CROSS_CELLS.to_vec() };
        }
        let n = views.len().max(1) as u32;
        Self { columns: n, rows: 1, cells: (0..n).map(|i| (i, 0)).collect() }
    }

    /// More than one map.
    pub fn is_tiled(&self) -> bool {
        self.cells.len() > 1
    }

    /// The picture's height per unit of width.
    pub fn aspect(&self) -> f32 {
        self.rows as f32 / self.columns as f32
    }

    /// Where uv of the light's view `i` (of `views`, the light's own) lies in the picture (0..1
    /// over it): a uv past a cube face's edge is read on the face its direction falls in
    /// (`map_tap`) and drawn there; on any other map it stays in its cell.
    pub fn picture_uv(&self, views: &[ShadowViewGpu], i: usize, uv: [f32; 2]) -> [f32; 2] {
        let Some(view) = views.get(i) else { return uv };
        let (cell, uv) = if view.cube == 1 {
            let (face_view, face_uv) = crate::shadow::map_tap(view, glam::Vec2::from(uv));
            (face_view.face as usize, face_uv.to_array())
        } else {
            (i, uv)
        };
        let Some(&(column, row)) = self.cells.get(cell) else { return uv };
        let (u, v) = (uv[0].clamp(0.0, 1.0), uv[1].clamp(0.0, 1.0));
        [(column as f32 + u) / self.columns as f32, (row as f32 + v) / self.rows as f32]
    }

    /// The view whose cell holds picture uv (u, v), and the uv within its map.
    pub fn cell_at(&self, u: f32, v: f32) -> Option<(usize, [f32; 2])> {
        let (x, y) = (u * self.columns as f32, v * self.rows as f32);
        let cell = (x.floor() as u32, y.floor() as u32);
        let i = self.cells.iter().position(|&c| c == cell)?;
        Some((i, [x - cell.0 as f32, y - cell.1 as f32]))
    }
}

/// A light's maps as one picture with its legend, on one depth scale and tiled by `MapsLayout`:
/// the one map of a spot or plain directional light, a sun's cascades side by side, a point
/// light's six faces unfolded into a cross.
pub fn light_maps_image(maps: &[DepthImage], views: &[ShadowViewGpu]) -> (RgbaImage, Legend) {
    let layout = MapsLayout::of(views);
    if !layout.is_tiled() || maps.len() != views.len() {
        return shadow_map_image(&maps[0], &views[0]);
    }
    let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
    for (map, view) in maps.iter().zip(views) {
        for z in map.depth_ndc.iter().filter(|&&z| z < 1.0) {
            let d = depth_linear_from_ndc(view, *z);
            (lo, hi) = (lo.min(d), hi.max(d));
        }
    }
    if !lo.is_finite() {
        (lo, hi) = (views[0].near, views[0].far);
    }
    let span = (hi - lo).max(1e-6);
    let size = maps[0].size;
    let mut image = RgbaImage::from_pixel(layout.columns * size, layout.rows * size, Rgba([40, 42, 48, 255]));
    for ((map, view), &(column, row)) in maps.iter().zip(views).zip(&layout.cells) {
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
    // Cascades meet edge to edge but do not continue into each other (a cube's faces do): a
    // dark line between them, over each one's first column of texels.
    if views[0].cube == 0 {
        for column in 1..layout.columns {
            for y in 0..image.height() {
                image.put_pixel(column * size, y, Rgba([40, 42, 48, 255]));
            }
        }
    }
    let legend = if views[0].cube == 1 {
        Legend {
            label: "distance to the light, six cube faces unfolded (+Y above; +X, +Z, -X, -Z; -Y below)",
            min: lo,
            max: hi,
            unit: "world units (white: nothing stored)",
        }
    } else {
        Legend {
            label: "light-space depth, the cascades side by side (sharpest on the left)",
            min: lo,
            max: hi,
            unit: "world units from the light (white: nothing stored)",
        }
    };
    (image, legend)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn views_of(scene: &str, overrides: &[(String, String)]) -> Vec<ShadowViewGpu> {
        let path = crate::shipped_path(&format!("assets/scenes/{scene}.toml"));
        let scene = crate::scene::load_scene(&path, overrides).expect("scene");
        crate::shadow::frame_lights(&scene, 1.5, 0.0, 1024).1
    }

    /// A uv on a tile comes back from the picture to the same view and uv: the cascades in a
    /// row, the cube's faces in their cross; the one map is the picture.
    #[test]
    fn tiles_map_uv_to_the_picture_and_back() {
        for (scene, columns, rows) in [("sun_avenue", 4, 1), ("point_lamp", 4, 3), ("games202", 1, 1)] {
            let views = views_of(scene, &[]);
            let views = &views[..views.iter().filter(|v| v.light == 0).count()];
            let layout = MapsLayout::of(views);
            assert_eq!(
                (layout.columns, layout.rows, layout.cells.len()),
                (columns, rows, views.len()),
                "{scene}"
            );
            for i in 0..views.len() {
                let [u, v] = layout.picture_uv(views, i, [0.3, 0.8]);
                let (back, uv) = layout.cell_at(u, v).expect("a tile");
                assert_eq!(back, i, "{scene}");
                assert!((uv[0] - 0.3).abs() < 1e-5 && (uv[1] - 0.8).abs() < 1e-5, "{scene}: {uv:?}");
            }
        }
        // A cube face's uv past its edge is drawn on the neighbour that holds it.
        let lamp = views_of("point_lamp", &[]);
        let layout = MapsLayout::of(&lamp);
        let (face, _) = layout.cell_at(layout.picture_uv(&lamp, 0, [1.2, 0.5])[0], 0.5).expect("a tile");
        assert_ne!(face, 0);
    }
}
