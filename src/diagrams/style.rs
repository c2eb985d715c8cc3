//! Palette, text sizes, number formatting and small layout types shared by the diagrams.

use tiny_skia::{Color, ColorU8};

/// Colour-blind-safe palette (Okabe-Ito hues) on a light background.
pub mod pal {
    use tiny_skia::ColorU8;
    pub const BG: ColorU8 = ColorU8::from_rgba(250, 250, 246, 255);
    pub const INK: ColorU8 = ColorU8::from_rgba(20, 24, 28, 255);
    pub const MUTED: ColorU8 = ColorU8::from_rgba(84, 92, 100, 255);
    pub const TITLE_BG: ColorU8 = ColorU8::from_rgba(38, 50, 56, 255);
    pub const TITLE_FG: ColorU8 = ColorU8::from_rgba(255, 255, 255, 255);
    pub const LIGHT: ColorU8 = ColorU8::from_rgba(230, 159, 0, 255);
    pub const LIGHT_DARK: ColorU8 = ColorU8::from_rgba(150, 98, 0, 255);
    pub const BLOCKER: ColorU8 = ColorU8::from_rgba(55, 71, 79, 255);
    pub const RECEIVER: ColorU8 = ColorU8::from_rgba(140, 140, 140, 255);
    pub const SHADOW: ColorU8 = ColorU8::from_rgba(70, 70, 70, 255);
    pub const PENUMBRA: ColorU8 = ColorU8::from_rgba(213, 94, 0, 255);
    pub const SEARCH: ColorU8 = ColorU8::from_rgba(0, 114, 178, 255);
    pub const LIT: ColorU8 = ColorU8::from_rgba(0, 158, 115, 255);
    pub const BLOCKED: ColorU8 = ColorU8::from_rgba(190, 30, 120, 255);
    pub const CAMERA: ColorU8 = ColorU8::from_rgba(0, 114, 178, 255);
    pub const GRID: ColorU8 = ColorU8::from_rgba(200, 204, 208, 255);
    /// Distinct hues for lights in the top view.
    pub const LIGHTS: [ColorU8; 4] = [
        ColorU8::from_rgba(230, 159, 0, 255),
        ColorU8::from_rgba(0, 114, 178, 255),
        ColorU8::from_rgba(0, 158, 115, 255),
        ColorU8::from_rgba(204, 121, 167, 255),
    ];
}

/// `c` with opacity `a` (0..1).
pub fn col(c: ColorU8, a: f32) -> Color {
    let mut out = Color::from_rgba8(c.red(), c.green(), c.blue(), c.alpha());
    out.apply_opacity(a.clamp(0.0, 1.0));
    out
}

/// `v` if finite, else `fallback`.
pub fn fin(v: f32, fallback: f32) -> f32 {
    if v.is_finite() { v } else { fallback }
}

/// Formats a value with about two significant digits below 1 and one decimal above
/// ("100.0", "5.0", "0.26", "0.098", "0.0024"); scientific notation when tiny or huge.
pub fn num(v: f32) -> String {
    let a = v.abs();
    if !v.is_finite() {
        "∞".to_string()
    } else if a == 0.0 {
        "0".to_string()
    } else if !(1e-4..1e7).contains(&a) {
        format!("{v:.1e}")
    } else if a >= 1.0 {
        format!("{v:.1}")
    } else if a >= 0.1 {
        format!("{v:.2}")
    } else if a >= 0.01 {
        format!("{v:.3}")
    } else if a >= 0.001 {
        format!("{v:.4}")
    } else {
        format!("{v:.5}")
    }
}

/// NDC depth values: four decimals, or scientific notation when smaller.
pub fn ndc(v: f32) -> String {
    if v != 0.0 && v.abs() < 1e-3 { format!("{v:.1e}") } else { format!("{v:.4}") }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Anchor {
    TopLeft,
    TopCenter,
    TopRight,
    MidLeft,
    MidRight,
    BottomLeft,
    BottomCenter,
    BottomRight,
}

/// Legend entry symbols.
#[derive(Clone, Copy, Debug)]
pub enum Swatch {
    Fill(ColorU8, f32),
    Line(ColorU8),
    Dashed(ColorU8),
    Dot(ColorU8),
    HollowCross(ColorU8),
}

/// How a piece of text looks.
#[derive(Clone, Copy, Debug)]
pub struct Style {
    pub size: f32,
    pub color: ColorU8,
    pub bold: bool,
    /// Translucent background plate behind the text.
    pub plate: bool,
}

impl Style {
    /// Regular ink-coloured text on a plate.
    pub fn label(size: f32) -> Self {
        Self { size, color: pal::INK, bold: false, plate: true }
    }

    /// Bold coloured text on a plate.
    pub fn em(size: f32, color: ColorU8) -> Self {
        Self { size, color, bold: true, plate: true }
    }

    /// Regular coloured text on a plate.
    pub fn tint(size: f32, color: ColorU8) -> Self {
        Self { size, color, bold: false, plate: true }
    }

    pub fn no_plate(self) -> Self {
        Self { plate: false, ..self }
    }
}

pub const TITLE_H: f32 = 46.0;
pub const FS_TITLE: f32 = 25.0;
pub const FS_LABEL: f32 = 19.0;
pub const FS_SMALL: f32 = 17.0;

/// The largest "nice" number (1, 2 or 5 times a power of ten) not above `v`.
pub fn nice_floor(v: f32) -> f32 {
    if !(v.is_finite() && v > 0.0) {
        return 1.0;
    }
    let base = 10f32.powf(v.log10().floor());
    let f = v / base;
    let m = if f >= 5.0 {
        5.0
    } else if f >= 2.0 {
        2.0
    } else {
        1.0
    };
    m * base
}
