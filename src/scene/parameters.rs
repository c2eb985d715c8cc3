//! The parameters the inspector shows, one row each: the key scene files, lesson steps and
//! `--set` write, the inspector's label (English, its Chinese in src/i18n), the unit, the values
//! the loader accepts and the control that edits them. The loader checks each value against its
//! row (`settings.rs`, `file/build.rs`) and the inspector draws its controls from the rows
//! (src/ui/inspector.rs), so no range is written twice.

use super::settings::{BiasMode, DepthStorage, Kernel, ShadowSettings, Technique};

/// Farthest a camera, light or object may be placed from the origin, world units. The frusta end
/// at most 1e7 away (`far`), and near 1e6 an f32 coordinate moves in steps of 1/16: beyond it
/// depths and shadow-map texel centres quantise visibly, and a scene of metres drawn there is a
/// few pixels of noise or nothing. The shipped scenes stay within 200.
pub const MAX_COORDINATE: f32 = 1e6;

impl ShadowSettings {
    /// Check every value against its row of the table; the error names the key.
    pub fn validate(&self) -> Result<(), String> {
        SHADOW.iter().try_for_each(|row| row.check_shadow(self))
    }
}

/// What the loader accepts for a key.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Values {
    /// A finite number in `lo..=hi`.
    Real { lo: f32, hi: f32 },
    /// A whole number in `lo..=hi`.
    Whole { lo: i64, hi: i64 },
    /// A far plane: greater than its light's near plane times `beyond_near`, at most `hi`.
    FarPlane { beyond_near: f32, hi: f32 },
    /// Three finite coordinates, each within [`MAX_COORDINATE`] of the origin.
    Point,
    /// `true` or `false`.
    Switch,
    /// One of the names of its type (`Technique::ALL`, ...): the file's parser refuses any other.
    Name,
}

/// The inspector's control for a key.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Control {
    /// A slider over `lo..=hi`, a part of what the loader accepts (the span a drag covers),
    /// logarithmic where `log`.
    Slider {
        lo: f32,
        hi: f32,
        log: bool,
    },
    /// A near plane's slider (logarithmic): from `lo` to `below_far` times the far plane.
    NearSlider {
        lo: f32,
        below_far: f32,
    },
    /// A far plane's slider (logarithmic): from `beyond_near` times the near plane to `hi`.
    FarSlider {
        beyond_near: f32,
        hi: f32,
    },
    /// A number dragged, with the label before it.
    Drag,
    /// Three numbers dragged, x, y and z.
    Point,
    /// A combo box of these square map sizes, texels a side.
    Sizes(&'static [u32]),
    Checkbox,
    /// A combo box of the names of its type.
    Combo,
}

/// A `[shadow]` field, as its control edits it.
pub enum Field<'a> {
    Real(&'a mut f32),
    Int(&'a mut i32),
    Count(&'a mut u32),
    Switch(&'a mut bool),
    Technique(&'a mut Technique),
    BiasMode(&'a mut BiasMode),
    Kernel(&'a mut Kernel),
    DepthStorage(&'a mut DepthStorage),
}

/// One parameter.
#[derive(Clone, Copy, Debug)]
pub struct Parameter {
    /// The key in scene files, lesson steps and `--set`: a bare `[shadow]` key, `camera.KEY`, or
    /// `light.N.KEY` for any light N.
    pub key: &'static str,
    /// The inspector's label, in English; it ends with the unit in brackets (a light's position
    /// and target aside).
    pub label: &'static str,
    /// The unit of the values ("" for a count, a ratio, a switch or a name).
    pub unit: &'static str,
    pub values: Values,
    pub control: Control,
    /// The inspector's heading the control is under ("" after a bare separator).
    pub section: &'static str,
    /// A lesson's "Try this" may name the control, which shows the key on hover (all but the map
    /// size's combo box); false for the fields of view, whose two sliders share a label, and the
    /// noise seed.
    pub named: bool,
    /// The field a `[shadow]` key sets (None for `camera.` and `light.N.` keys).
    pub field: Option<fn(&mut ShadowSettings) -> Field<'_>>,
}

mod table;
pub use table::*;

/// Every parameter, in the inspector's order.
pub fn all() -> impl Iterator<Item = &'static Parameter> {
    SHADOW.iter().chain(LIGHT_AND_CAMERA.iter().copied())
}

/// The parameter a lesson's "Try this" may name by `key` (`light.2.width` finds `light.N.width`).
pub fn named(key: &str) -> Option<&'static Parameter> {
    let parts: Vec<&str> = key.split('.').collect();
    let key = match parts.as_slice() {
        ["light", n, rest] if n.parse::<usize>().is_ok() => format!("light.N.{rest}"),
        _ => key.to_string(),
    };
    all().find(|p| p.named && p.key == key)
}

impl Parameter {
    /// `v`, the value of `key` (this row's key with its light's number), if the loader accepts it.
    pub fn check_real(&self, key: &str, v: f32) -> Result<f32, String> {
        match self.values {
            Values::Real { lo, hi } => in_range(key, v, lo, hi),
            _ => in_range(key, v, f32::NEG_INFINITY, f32::INFINITY),
        }
    }

    /// As [`Parameter::check_real`], for a whole number.
    pub fn check_whole(&self, key: &str, v: i64) -> Result<i64, String> {
        if let Values::Whole { lo, hi } = self.values
            && !(lo..=hi).contains(&v)
        {
            return Err(format!("`{key}` = {v} is out of range {lo}..={hi}"));
        }
        Ok(v)
    }

    /// As [`Parameter::check_real`], for a far plane beyond the near plane `near` of `near_key`.
    pub fn check_far(&self, key: &str, far: f32, near_key: &str, near: f32) -> Result<f32, String> {
        match self.values {
            Values::FarPlane { beyond_near, hi } => far_plane(key, far, near_key, near, beyond_near, hi),
            _ => self.check_real(key, far),
        }
    }

    /// A `[shadow]` row's value in `settings`, if the loader accepts it.
    pub fn check_shadow(&self, settings: &ShadowSettings) -> Result<(), String> {
        let Some(field) = self.field else { return Ok(()) };
        let mut settings = *settings;
        match field(&mut settings) {
            Field::Real(v) => self.check_real(self.key, *v).map(drop),
            Field::Int(v) => self.check_whole(self.key, i64::from(*v)).map(drop),
            Field::Count(v) => self.check_whole(self.key, i64::from(*v)).map(drop),
            _ => Ok(()),
        }
    }
}

/// `v` if it is finite and in `lo..=hi`; the error names `key`.
pub fn in_range(key: &str, v: f32, lo: f32, hi: f32) -> Result<f32, String> {
    if !v.is_finite() {
        return Err(format!("`{key}` must be a finite number, got {v}"));
    }
    if !(lo..=hi).contains(&v) {
        return Err(format!("`{key}` = {v} is out of range {lo}..={hi}"));
    }
    Ok(v)
}

/// A frustum's far plane: beyond its near plane (by `factor`) and at most `hi`.
pub fn far_plane(
    key: &str,
    far: f32,
    near_key: &str,
    near: f32,
    factor: f32,
    hi: f32,
) -> Result<f32, String> {
    if far.is_finite() && far <= near * factor {
        return Err(format!("`{key}` = {far} must be greater than `{near_key}` = {near}"));
    }
    in_range(key, far, near * factor, hi)
}

#[cfg(test)]
mod tests;
