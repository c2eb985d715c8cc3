// Shared structs, constants and noise. Composed in front of the other shader files.
// Keep the structs in sync with src/shadow/gpu.rs (lights, parameters) and
// src/render/gpu_types.rs (the rest); sizes are asserted there.

const PI: f32 = 3.14159265358979;
const TAU: f32 = 6.28318530717959;
const MAX_LIGHTS: u32 = 4u;
// Shadow views of all lights together (a light owns one or more).
const MAX_SHADOW_VIEWS: u32 = 24u;
const MAX_TAPS: u32 = 128u;       // most filter or blocker-search taps (src/shadow/kernels.rs)
const CASCADE_BORDER_TEXELS: u32 = 4u;  // a cascade holds points this far inside its map's edge

// Bias modes, kernels, techniques and size models: numbered in src/shadow/gpu.rs (tests/shaders.rs checks).
const BIAS_NONE: u32 = 0u;
const BIAS_CONSTANT: u32 = 1u;
const BIAS_SLOPE: u32 = 2u;
const BIAS_ADAPTIVE: u32 = 3u;
const BIAS_RECEIVER_PLANE: u32 = 4u;
const DEPTH_FLOAT32: u32 = 0u;
const DEPTH_RGBA8: u32 = 1u;
const KERNEL_POISSON: u32 = 0u;
const KERNEL_UNIFORM: u32 = 1u;
const KERNEL_VOGEL: u32 = 2u;
const KERNEL_GRID: u32 = 3u;
const KERNEL_HARDWARE: u32 = 4u;
const TECHNIQUE_HARD: u32 = 0u;
const TECHNIQUE_PCF: u32 = 1u;
const TECHNIQUE_PCSS: u32 = 2u;
const TECHNIQUE_NONE: u32 = 3u;
const TECHNIQUE_VSM: u32 = 4u;
const TECHNIQUE_VSSM: u32 = 5u;
const SIZE_MODEL_WIDTH: u32 = 0u;
const SIZE_MODEL_ANGULAR: u32 = 1u;
const CASCADE_BY_MAP: u32 = 0u;       // the sharpest cascade whose map holds the point
const CASCADE_BY_INTERVAL: u32 = 1u;  // the cascade whose slice holds its depth along the view axis

struct FrameGpu {
    clip_from_world: mat4x4<f32>,
    camera_position: vec4<f32>,   // xyz world
    ambient: vec4<f32>,           // rgb linear
    light_count: u32,
    selected_light: u32,          // which light the analysis outputs describe
    _pad0: u32,
    _pad1: u32,
}

// A light as all of its shadow views share it.
struct LightGpu {
    position: vec4<f32>,          // xyz world, at the frame's time
    direction: vec4<f32>,         // xyz unit, from the light towards its target
    color: vec4<f32>,             // rgb linear times intensity
    directional: u32,             // 1: parallel rays along direction; 0: rays from position
    size_model: u32,              // SIZE_MODEL_*
    light_width_world: f32,       // width model: area-light diameter
    tan_half_angle: f32,          // angular model: tan(angular_diameter / 2)
    first_view: u32,              // its shadow views: first_view .. first_view + view_count
    view_count: u32,
    cascade_selection: u32,       // a sun's cascades: CASCADE_BY_*
    _pad0: u32,
}

// One depth map a light renders: its projection and where it lies in the shadow-map array.
struct ShadowViewGpu {
    clip_from_world: mat4x4<f32>,
    origin: vec4<f32>,            // xyz world: where a perspective view looks from
    near: f32,                    // world units
    far: f32,
    frustum_width_world: f32,     // W: ortho width, or width at the near plane
    tan_half_fov: f32,            // perspective only; 0 for orthographic
    orthographic: u32,
    map_size_texels: f32,
    layer: u32,                   // shadow-map array layer
    atlas_scale: f32,             // map_size / array texture size
    moments_block: u32,           // map texels per side of a level-0 VSM moments texel
    light: u32,                   // the light that owns it
    cube: u32,                    // 1: a cube face (stores distance; projects with the face's axes)
    face: u32,                    // 0..6: +X, -X, +Y, -Y, +Z, -Z; the faces lie in layers layer - face ..
    view_axis_world: vec4<f32>,   // a cascade: the camera's view axis as a plane (xyz . p + w = depth, world)
    split_near_world: f32,        // a cascade: its slice along that axis, world units
    split_far_world: f32,
    _pad0: u32,
    _pad1: u32,
}

struct ShadowParamsGpu {
    technique: u32,
    bias_mode: u32,
    kernel: u32,
    samples: u32,                 // effective filter taps
    bias: f32,                    // NDC depth
    slope_bias: f32,              // NDC depth
    adaptive_c: f32,              // dimensionless
    normal_offset_texels: f32,
    radius_texels: f32,
    rotate_per_pixel: u32,
    noise_seed: u32,
    blocker_samples: u32,
    min_filter_radius_texels: f32,
    clamp_outside: u32,
    search_radius_scale: f32,     // blocker search, times the light's cone
    depth_storage: u32,           // DEPTH_*
    ortho_near_factor: u32,       // 1: near / d_receiver on orthographic maps too, the bug [NVIDIA-2008]
    vsm_min_variance: f32,        // NDC depth squared
    vsm_bleed_reduction: f32,     // dimensionless, 0 = off
    _pad0: u32,
}

struct ObjectGpu {
    world_from_object: mat4x4<f32>,
    normal_from_object: mat4x4<f32>, // inverse transpose of world_from_object
    base_color: vec4<f32>,           // rgb linear; w = 1 when the diffuse texture is used
    object_index: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

// PCG hash [Jarzynski-2020]: exact integer maths, so the CPU twin gets the same bits.
fn pcg_hash(v: u32) -> u32 {
    let state = v * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// Top 24 bits as a float in [0, 1).
fn unit_float(h: u32) -> f32 {
    return f32(h >> 8u) * (1.0 / 16777216.0);
}

// Seed of the noise at one pixel: fixed per pixel, or one value for the whole image.
fn pixel_seed(pixel: vec2<u32>, noise_seed: u32, rotate_per_pixel: bool) -> u32 {
    if rotate_per_pixel {
        return pcg_hash(pixel.x ^ pcg_hash(pixel.y ^ pcg_hash(noise_seed)));
    }
    return pcg_hash(noise_seed);
}
