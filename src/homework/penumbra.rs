//! The width of a penumbra at one pixel, measured on a picture of visibility: the run of soft
//! pixels (0.05 < v < 0.95) through the pixel across the shadow's edge (along the ground
//! truth's gradient there), from one end's surface point to the other's, in world units.
//! The ground truth's width against the student's, at the same place, says whether their
//! penumbra has the right size (not merely whether it exists).

use glam::Vec2;

/// A visibility is soft strictly between these.
const SOFT: (f32, f32) = (0.05, 0.95);
/// Farthest a run is followed from the pixel, pixels.
const MAX_WALK_PX: i32 = 400;
/// The gradient is taken over this many pixels either side.
const GRADIENT_SPAN_PX: i32 = 2;

/// A picture's visibility and surface points, rows top first.
pub struct Field<'a> {
    pub width: u32,
    pub height: u32,
    /// World position of the surface under each pixel (None: no surface).
    pub positions: &'a [Option<glam::Vec3>],
}

impl Field<'_> {
    fn index(&self, p: (i32, i32)) -> Option<usize> {
        let inside = (0..self.width as i32).contains(&p.0) && (0..self.height as i32).contains(&p.1);
        inside.then(|| (p.1 as u32 * self.width + p.0 as u32) as usize)
    }

    /// The direction across the edge at `at`: the gradient of `truth` there (None where flat).
    pub fn across(&self, truth: &dyn Fn(usize) -> Option<f32>, at: (u32, u32)) -> Option<Vec2> {
        let value = |dx: i32, dy: i32| truth(self.index((at.0 as i32 + dx, at.1 as i32 + dy))?);
        let s = GRADIENT_SPAN_PX;
        let gx = value(s, 0)? - value(-s, 0)?;
        let gy = value(0, s)? - value(0, -s)?;
        let g = Vec2::new(gx, gy);
        (g.length() > 1e-4).then(|| g.normalize())
    }

    /// The penumbra width through `at` along `dir` on the visibility `v`, world units: the soft
    /// run nearest `at` on that line (0 where the line has none within `reach_px`).
    pub fn width_along(
        &self,
        v: &dyn Fn(usize) -> Option<f32>,
        at: (u32, u32),
        dir: Vec2,
        reach_px: i32,
    ) -> f32 {
        let point = |t: i32| {
            let p = Vec2::new(at.0 as f32, at.1 as f32) + dir * t as f32;
            (p.x.round() as i32, p.y.round() as i32)
        };
        let soft = |t: i32| self.index(point(t)).and_then(v).is_some_and(|x| x > SOFT.0 && x < SOFT.1);
        // The soft pixel on the line nearest `at`.
        let Some(start) = (0..=reach_px).flat_map(|d| [d, -d]).find(|&t| soft(t)) else { return 0.0 };
        let mut ends = (start, start);
        while ends.1 - start < MAX_WALK_PX && soft(ends.1 + 1) {
            ends.1 += 1;
        }
        while start - ends.0 < MAX_WALK_PX && soft(ends.0 - 1) {
            ends.0 -= 1;
        }
        // From the last soft pixel's outer neighbour to the other's: the whole transition.
        let position = |t: i32| self.index(point(t)).and_then(|i| self.positions.get(i).copied().flatten());
        match (position(ends.0 - 1).or(position(ends.0)), position(ends.1 + 1).or(position(ends.1))) {
            (Some(a), Some(b)) => a.distance(b),
            _ => 0.0,
        }
    }
}

/// The pixel a penumbra is measured at where none was chosen: the ground truth's soft pixel
/// nearest the picture's centre.
pub fn default_pixel(field: &Field<'_>, truth: &dyn Fn(usize) -> Option<f32>) -> Option<(u32, u32)> {
    let (w, h) = (field.width, field.height);
    let centre = |&(x, y): &(u32, u32)| {
        let (dx, dy) = (i64::from(x) - i64::from(w / 2), i64::from(y) - i64::from(h / 2));
        dx * dx + dy * dy
    };
    (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .filter(|&(x, y)| truth((y * w + x) as usize).is_some_and(|v| v > SOFT.0 && v < SOFT.1))
        .min_by_key(centre)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A floor in the z = 0 plane seen from above, a unit a pixel; a penumbra from x = 40 to 60.
    #[test]
    fn a_linear_edge_measures_its_width_in_world_units() {
        let (w, h) = (100u32, 20u32);
        let positions: Vec<Option<glam::Vec3>> =
            (0..w * h).map(|i| Some(glam::Vec3::new((i % w) as f32, (i / w) as f32, 0.0))).collect();
        let field = Field { width: w, height: h, positions: &positions };
        let ramp = |i: usize| Some((((i as u32 % w) as f32 - 40.0) / 20.0).clamp(0.0, 1.0));
        let dir = field.across(&ramp, (50, 10)).expect("an edge");
        assert!((dir - Vec2::X).length() < 1e-5, "{dir}");
        let width = field.width_along(&ramp, (50, 10), dir, 10);
        // Soft from x = 42 (0.1) to x = 58 (0.9); its outer neighbours are 41 and 59: 18 units.
        assert!((width - 18.0).abs() < 1e-4, "{width}");
        // A hard edge has no soft pixel: width 0.
        let hard = |i: usize| Some(if (i as u32 % w) < 50 { 0.0 } else { 1.0 });
        assert_eq!(field.width_along(&hard, (50, 10), dir, 10), 0.0);
        assert_eq!(default_pixel(&field, &ramp), Some((50, 10)));
    }
}
