//! Where everything goes on a slide: the 1920x1080 design grid scaled onto the slide's size, and
//! the text a slide carries.

use crate::i18n::Lang;

/// The design grid.
pub const DESIGN: (f32, f32) = (1920.0, 1080.0);
/// Smallest slide accepted (text below this size is no longer readable).
pub const MIN_SIZE: (u32, u32) = (480, 270);

/// A rectangle in slide pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rect {
    pub x: u32,
    pub y: u32,
    pub w: u32,
    pub h: u32,
}

impl Rect {
    pub(super) fn right(&self) -> f32 {
        (self.x + self.w) as f32
    }
    pub(super) fn bottom(&self) -> f32 {
        (self.y + self.h) as f32
    }
}

/// Where everything goes on a slide of a given size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlideLayout {
    pub size: (u32, u32),
    /// Slide pixels per design unit.
    pub scale: f32,
    pub title_bar: Rect,
    /// The camera view; the camera image is rendered at exactly this size.
    pub camera: Rect,
    /// The shadow map panel (square).
    pub shadow_map: Rect,
    /// Captions under the camera view and the shadow map.
    pub camera_caption: Rect,
    pub shadow_map_caption: Rect,
    /// The diagram, drawn at exactly this size.
    pub diagram: Rect,
    /// The probe's numbers.
    pub probe: Rect,
    /// The explanation and the try-this prompts.
    pub text: Rect,
}

impl SlideLayout {
    pub fn new(width: u32, height: u32) -> Self {
        let scale = (width as f32 / DESIGN.0).min(height as f32 / DESIGN.1);
        // Centred across, from the top down (a taller slide keeps its spare room at the bottom).
        let origin = ((width as f32 - DESIGN.0 * scale) * 0.5, 0.0);
        let r = |x: f32, y: f32, w: f32, h: f32| {
            let x0 = (origin.0 + x * scale).round();
            let y0 = (origin.1 + y * scale).round();
            let x1 = (origin.0 + (x + w) * scale).round();
            let y1 = (origin.1 + (y + h) * scale).round();
            Rect { x: x0 as u32, y: y0 as u32, w: ((x1 - x0) as u32).max(1), h: ((y1 - y0) as u32).max(1) }
        };
        let camera = r(28.0, 96.0, 768.0, 432.0);
        // The map is as tall as the camera view, to the pixel.
        let map_x = r(816.0, 96.0, 432.0, 432.0);
        let shadow_map = Rect { h: camera.h, w: camera.h, y: camera.y, ..map_x };
        Self {
            size: (width, height),
            scale,
            title_bar: Rect { x: 0, y: 0, w: width, h: (72.0 * scale).round().max(1.0) as u32 },
            camera,
            shadow_map,
            camera_caption: r(28.0, 534.0, 768.0, 56.0),
            shadow_map_caption: r(816.0, 534.0, 432.0, 56.0),
            diagram: r(28.0, 598.0, 807.0, 454.0),
            probe: r(855.0, 598.0, 393.0, 454.0),
            text: r(1276.0, 96.0, 616.0, 956.0),
        }
    }

    /// Design units to slide pixels.
    pub fn px(&self, design: f32) -> f32 {
        design * self.scale
    }
}

/// The words on a slide, in one language.
pub struct SlideText<'a> {
    pub lang: Lang,
    pub lesson_title: &'a str,
    pub step_number: usize,
    pub step_count: usize,
    pub step_title: &'a str,
    pub body: &'a str,
    pub try_this: Vec<&'a str>,
}
