//! The rows: what the loader accepts and how the inspector edits each key, in the inspector's
//! order.

use super::{Control, Field, Parameter, Values};
use crate::scene::{MAX_CASCADES, MAX_TAPS};

/// What most rows share: a named `[shadow]` key with no field yet.
const ROW: Parameter = Parameter {
    key: "",
    label: "",
    unit: "",
    values: Values::Name,
    control: Control::Combo,
    section: "",
    named: true,
    field: None,
};

/// The `[shadow]` keys, in the inspector's order.
pub static SHADOW: [Parameter; 23] = [
    Parameter {
        key: "technique",
        label: "technique",
        section: "Technique",
        field: Some(|s| Field::Technique(&mut s.technique)),
        ..ROW
    },
    Parameter {
        key: "bias_mode",
        label: "bias mode",
        section: "Bias",
        field: Some(|s| Field::BiasMode(&mut s.bias_mode)),
        ..ROW
    },
    Parameter {
        key: "bias",
        label: "bias (NDC depth)",
        unit: "NDC depth",
        values: Values::Real { lo: 0.0, hi: 1.0 },
        control: Control::Slider { lo: 0.0, hi: 0.05, log: true },
        section: "Bias",
        field: Some(|s| Field::Real(&mut s.bias)),
        ..ROW
    },
    Parameter {
        key: "slope_bias",
        label: "slope bias (NDC)",
        unit: "NDC",
        values: Values::Real { lo: 0.0, hi: 1.0 },
        control: Control::Slider { lo: 0.0, hi: 0.2, log: true },
        section: "Bias",
        field: Some(|s| Field::Real(&mut s.slope_bias)),
        ..ROW
    },
    Parameter {
        key: "adaptive_c",
        label: "adaptive c (× half texel)",
        unit: "× half texel",
        values: Values::Real { lo: 0.0, hi: 100.0 },
        control: Control::Slider { lo: 0.0, hi: 8.0, log: false },
        section: "Bias",
        field: Some(|s| Field::Real(&mut s.adaptive_c)),
        ..ROW
    },
    Parameter {
        key: "normal_offset_texels",
        label: "normal offset (texels)",
        unit: "texels",
        values: Values::Real { lo: 0.0, hi: 64.0 },
        control: Control::Slider { lo: 0.0, hi: 4.0, log: false },
        section: "Bias",
        field: Some(|s| Field::Real(&mut s.normal_offset_texels)),
        ..ROW
    },
    Parameter {
        key: "depth_bias_constant",
        label: "hardware bias (depth units)",
        unit: "depth units",
        values: Values::Whole { lo: -100_000, hi: 100_000 },
        control: Control::Slider { lo: 0.0, hi: 20000.0, log: false },
        section: "Bias",
        field: Some(|s| Field::Int(&mut s.depth_bias_constant)),
        ..ROW
    },
    Parameter {
        key: "depth_bias_slope",
        label: "hardware slope bias",
        values: Values::Real { lo: -16.0, hi: 16.0 },
        control: Control::Slider { lo: -4.0, hi: 8.0, log: false },
        section: "Bias",
        field: Some(|s| Field::Real(&mut s.depth_bias_slope)),
        ..ROW
    },
    Parameter {
        key: "cull_front_faces",
        label: "cull front faces in the shadow pass",
        values: Values::Switch,
        control: Control::Checkbox,
        section: "Bias",
        field: Some(|s| Field::Switch(&mut s.cull_front_faces)),
        ..ROW
    },
    Parameter {
        key: "clamp_outside",
        label: "outside the light frustum = lit",
        values: Values::Switch,
        control: Control::Checkbox,
        section: "Bias",
        field: Some(|s| Field::Switch(&mut s.clamp_outside)),
        ..ROW
    },
    Parameter {
        key: "depth_storage",
        label: "depth storage",
        section: "Bias",
        field: Some(|s| Field::DepthStorage(&mut s.depth_storage)),
        ..ROW
    },
    Parameter {
        key: "pcf_kernel",
        label: "kernel",
        section: "PCF",
        field: Some(|s| Field::Kernel(&mut s.pcf_kernel)),
        ..ROW
    },
    Parameter {
        key: "samples",
        label: "samples",
        values: Values::Whole { lo: 1, hi: MAX_TAPS as i64 },
        control: Control::Slider { lo: 1.0, hi: MAX_TAPS as f32, log: false },
        section: "PCF",
        field: Some(|s| Field::Count(&mut s.samples)),
        ..ROW
    },
    Parameter {
        key: "radius_texels",
        label: "radius (texels)",
        unit: "texels",
        values: Values::Real { lo: 0.0, hi: 256.0 },
        control: Control::Slider { lo: 0.0, hi: 32.0, log: false },
        section: "PCF",
        field: Some(|s| Field::Real(&mut s.radius_texels)),
        ..ROW
    },
    Parameter {
        key: "rotate_per_pixel",
        label: "rotate the pattern per pixel",
        values: Values::Switch,
        control: Control::Checkbox,
        section: "PCF",
        field: Some(|s| Field::Switch(&mut s.rotate_per_pixel)),
        ..ROW
    },
    Parameter {
        key: "noise_seed",
        label: "noise seed",
        values: Values::Whole { lo: 0, hi: u32::MAX as i64 },
        control: Control::Drag,
        section: "PCF",
        named: false,
        field: Some(|s| Field::Count(&mut s.noise_seed)),
        ..ROW
    },
    Parameter {
        key: "blocker_samples",
        label: "blocker samples",
        values: Values::Whole { lo: 1, hi: MAX_TAPS as i64 },
        control: Control::Slider { lo: 1.0, hi: MAX_TAPS as f32, log: false },
        section: "PCSS",
        field: Some(|s| Field::Count(&mut s.blocker_samples)),
        ..ROW
    },
    Parameter {
        key: "min_filter_radius_texels",
        label: "min filter radius (texels)",
        unit: "texels",
        values: Values::Real { lo: 0.0, hi: 256.0 },
        control: Control::Slider { lo: 0.0, hi: 16.0, log: false },
        section: "PCSS",
        field: Some(|s| Field::Real(&mut s.min_filter_radius_texels)),
        ..ROW
    },
    Parameter {
        key: "search_radius_scale",
        label: "search radius (× light cone)",
        unit: "× light cone",
        values: Values::Real { lo: 0.0, hi: 8.0 },
        control: Control::Slider { lo: 0.25, hi: 4.0, log: false },
        section: "PCSS",
        field: Some(|s| Field::Real(&mut s.search_radius_scale)),
        ..ROW
    },
    Parameter {
        key: "ortho_near_factor",
        label: "near / d on orthographic maps (NVIDIA's factor)",
        values: Values::Switch,
        control: Control::Checkbox,
        section: "PCSS",
        field: Some(|s| Field::Switch(&mut s.ortho_near_factor)),
        ..ROW
    },
    Parameter {
        key: "vsm_min_variance",
        label: "VSM min variance (NDC²)",
        unit: "NDC²",
        values: Values::Real { lo: 0.0, hi: 1.0 },
        control: Control::Slider { lo: 0.0, hi: 1e-3, log: true },
        section: "VSM",
        field: Some(|s| Field::Real(&mut s.vsm_min_variance)),
        ..ROW
    },
    Parameter {
        key: "vsm_bleed_reduction",
        label: "VSM bleed reduction",
        values: Values::Real { lo: 0.0, hi: 0.95 },
        control: Control::Slider { lo: 0.0, hi: 0.95, log: false },
        section: "VSM",
        field: Some(|s| Field::Real(&mut s.vsm_bleed_reduction)),
        ..ROW
    },
    Parameter {
        key: "reference_samples",
        label: "ground-truth samples",
        values: Values::Whole { lo: 1, hi: 1024 },
        control: Control::Slider { lo: 1.0, hi: 1024.0, log: true },
        field: Some(|s| Field::Count(&mut s.reference_samples)),
        ..ROW
    },
];

/// What the light's rows share.
const LIGHT_ROW: Parameter = Parameter { unit: "world units", section: "Lights", ..ROW };

pub static LIGHT_POSITION: Parameter = Parameter {
    key: "light.N.position",
    label: "position",
    values: Values::Point,
    control: Control::Point,
    ..LIGHT_ROW
};
pub static LIGHT_TARGET: Parameter = Parameter {
    key: "light.N.target",
    label: "target",
    values: Values::Point,
    control: Control::Point,
    ..LIGHT_ROW
};
pub static LIGHT_SHADOW_MAP_SIZE: Parameter = Parameter {
    key: "light.N.shadow_map_size",
    label: "shadow map (texels)",
    unit: "texels",
    values: Values::Whole { lo: 256, hi: 8192 },
    control: Control::Sizes(&[256, 512, 1024, 2048, 4096, 8192]),
    ..LIGHT_ROW
};
pub static LIGHT_EXTENT: Parameter = Parameter {
    key: "light.N.extent",
    label: "half-width (world units)",
    values: Values::Real { lo: 1e-3, hi: 1e6 },
    control: Control::Slider { lo: 1.0, hi: 300.0, log: false },
    ..LIGHT_ROW
};
pub static LIGHT_FOV: Parameter = Parameter {
    key: "light.N.fov_deg",
    label: "field of view (°)",
    unit: "°",
    values: Values::Real { lo: 1.0, hi: 160.0 },
    control: Control::Slider { lo: 5.0, hi: 150.0, log: false },
    named: false,
    ..LIGHT_ROW
};
pub static LIGHT_NEAR: Parameter = Parameter {
    key: "light.N.near",
    label: "near (world units)",
    values: Values::Real { lo: 1e-4, hi: 1e6 },
    control: Control::NearSlider { lo: 0.01, below_far: 0.9 },
    ..LIGHT_ROW
};
pub static LIGHT_FAR: Parameter = Parameter {
    key: "light.N.far",
    label: "far (world units)",
    values: Values::FarPlane { beyond_near: 1.001, hi: 1e7 },
    control: Control::FarSlider { beyond_near: 1.1, hi: 2000.0 },
    ..LIGHT_ROW
};
pub static LIGHT_WIDTH: Parameter = Parameter {
    key: "light.N.width",
    label: "light width (world units)",
    values: Values::Real { lo: 0.0, hi: 1e4 },
    control: Control::Slider { lo: 0.0, hi: 40.0, log: false },
    ..LIGHT_ROW
};
pub static LIGHT_ANGULAR_DIAMETER: Parameter = Parameter {
    key: "light.N.angular_diameter_deg",
    label: "angular diameter (°)",
    unit: "°",
    values: Values::Real { lo: 0.0, hi: 30.0 },
    control: Control::Slider { lo: 0.0, hi: 20.0, log: false },
    ..LIGHT_ROW
};
pub static LIGHT_INTENSITY: Parameter = Parameter {
    key: "light.N.intensity",
    label: "intensity",
    unit: "",
    values: Values::Real { lo: 0.0, hi: 1e4 },
    control: Control::Slider { lo: 0.0, hi: 4.0, log: false },
    ..LIGHT_ROW
};
pub static LIGHT_ORBIT: Parameter = Parameter {
    key: "light.N.orbit_deg_per_s",
    label: "orbit (°/s)",
    unit: "°/s",
    values: Values::Real { lo: -3600.0, hi: 3600.0 },
    control: Control::Slider { lo: -180.0, hi: 180.0, log: false },
    ..LIGHT_ROW
};
pub static LIGHT_CASCADES: Parameter = Parameter {
    key: "light.N.cascades",
    label: "cascades",
    unit: "",
    values: Values::Whole { lo: 1, hi: MAX_CASCADES as i64 },
    control: Control::Slider { lo: 1.0, hi: MAX_CASCADES as f32, log: false },
    ..LIGHT_ROW
};
pub static LIGHT_CASCADE_LAMBDA: Parameter = Parameter {
    key: "light.N.cascade_lambda",
    label: "cascade split λ (0 uniform, 1 logarithmic)",
    unit: "",
    values: Values::Real { lo: 0.0, hi: 1.0 },
    control: Control::Slider { lo: 0.0, hi: 1.0, log: false },
    ..LIGHT_ROW
};
pub static LIGHT_CASCADE_SELECTION: Parameter = Parameter {
    key: "light.N.cascade_selection",
    label: "cascade selection",
    unit: "",
    values: Values::Name,
    control: Control::Combo,
    ..LIGHT_ROW
};
/// Not in the inspector (its default, the camera's far plane, is no number a slider holds):
/// scene files and `--set` only.
pub static LIGHT_CASCADE_DISTANCE: Parameter = Parameter {
    key: "light.N.cascade_distance",
    label: "cascades reach (world units)",
    values: Values::Real { lo: 1e-3, hi: 1e7 },
    control: Control::Slider { lo: 1.0, hi: 2000.0, log: true },
    named: false,
    ..LIGHT_ROW
};
pub static CAMERA_FOV: Parameter = Parameter {
    key: "camera.fov_deg",
    label: "field of view (°)",
    unit: "°",
    values: Values::Real { lo: 1.0, hi: 170.0 },
    control: Control::Slider { lo: 10.0, hi: 120.0, log: false },
    section: "Camera",
    named: false,
    ..ROW
};

/// The light's and the camera's keys, in the inspector's order.
pub static LIGHT_AND_CAMERA: [&Parameter; 16] = [
    &LIGHT_POSITION,
    &LIGHT_TARGET,
    &LIGHT_SHADOW_MAP_SIZE,
    &LIGHT_EXTENT,
    &LIGHT_FOV,
    &LIGHT_NEAR,
    &LIGHT_FAR,
    &LIGHT_WIDTH,
    &LIGHT_ANGULAR_DIAMETER,
    &LIGHT_INTENSITY,
    &LIGHT_ORBIT,
    &LIGHT_CASCADES,
    &LIGHT_CASCADE_LAMBDA,
    &LIGHT_CASCADE_SELECTION,
    &LIGHT_CASCADE_DISTANCE,
    &CAMERA_FOV,
];
