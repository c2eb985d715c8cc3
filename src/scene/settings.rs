//! The `[shadow]` table: which technique and its parameters.
//! Defaults follow the GAMES202 homework framework [GAMES202-HW1] where it gives one; the sources
//! of the formulas are in docs/REFERENCES.md.

use serde::{Deserialize, Serialize};

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Technique {
    /// No shadow lookup: every light reaches every surface (what shadows add, and the cost floor).
    None,
    Hard,
    Pcf,
    Pcss,
    /// Variance shadow maps: Chebyshev's bound on the filtered mean and mean square of depth
    /// [Donnelly-2006].
    Vsm,
    /// Variance soft shadow mapping [Yang-2010]: PCSS's three steps with VSM's moments (the
    /// average blocker depth estimated from the moments over the search region, then a VSM filter
    /// of the penumbra's size).
    Vssm,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum BiasMode {
    None,
    Constant,
    Slope,
    Adaptive,
    /// The constant bias plus, per tap, the receiver's own plane at the texel the tap reads
    /// (receiver-plane depth bias): wide kernels stop finding the receiver itself.
    #[serde(rename = "receiver_plane")]
    ReceiverPlane,
}

/// How the shadow map keeps its depths.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum DepthStorage {
    /// A 32-bit float depth buffer (what engines and shadowlab use).
    Float32,
    /// The GAMES202 framework's way [GAMES202-HW1]: the depth split over the four 8-bit channels
    /// of an RGBA8 colour target by its `pack`, read back by `unpack` (without the 256/255
    /// correction three.js applies [ThreeJS-Packing], so the stored depth is off by up to about
    /// 1/255). Point-sampled taps only: the hardware kernel's comparison sampler reads the float
    /// map, as no sampler can compare an RGBA8 texture.
    Rgba8,
}

/// Sample pattern in the unit disk for PCF and the blocker search.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Kernel {
    /// The GAMES202 "poissonDiskSamples" spiral (not a true Poisson disk) [GAMES202-HW1].
    Poisson,
    /// GAMES202 "uniformDiskSamples": random points, uniform over the disk's area.
    Uniform,
    /// Golden-angle spiral [Vogel-1979].
    Vogel,
    /// Regular n x n grid (n = floor(sqrt(samples))), axis-aligned and never rotated.
    Grid,
    /// Vogel positions, each a bilinear 2x2 hardware comparison (`textureSampleCompare`).
    Hardware,
}

macro_rules! enum_names {
    ($t:ty, $($v:ident => $s:literal),*) => {
        impl $t {
            pub const ALL: &'static [$t] = &[$(<$t>::$v),*];
            pub fn name(self) -> &'static str { match self { $(<$t>::$v => $s),* } }
            pub fn from_name(name: &str) -> Option<Self> {
                match name { $($s => Some(<$t>::$v),)* _ => None }
            }
            /// The name as the panels show it in `lang` (the English panels show the name).
            pub fn label(self, lang: crate::i18n::Lang) -> &'static str {
                crate::i18n::tr(lang, self.name())
            }
        }
        impl std::fmt::Display for $t {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result { f.write_str(self.name()) }
        }
    };
}
impl Technique {
    /// Filters with the VSM moments (which are then built after the shadow pass).
    pub fn uses_moments(self) -> bool {
        matches!(self, Technique::Vsm | Technique::Vssm)
    }
}

enum_names!(
    Technique,
    None => "none",
    Hard => "hard",
    Pcf => "pcf",
    Pcss => "pcss",
    Vsm => "vsm",
    Vssm => "vssm"
);
enum_names!(
    BiasMode,
    None => "none",
    Constant => "constant",
    Slope => "slope",
    Adaptive => "adaptive",
    ReceiverPlane => "receiver_plane"
);
enum_names!(DepthStorage, Float32 => "float32", Rgba8 => "rgba8");
enum_names!(Kernel, Poisson => "poisson", Uniform => "uniform", Vogel => "vogel", Grid => "grid", Hardware => "hardware");

/// What each value may be, and the inspector's control for it: its row in `parameters.rs`
/// (which checks a whole `ShadowSettings`: `ShadowSettings::validate`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ShadowSettings {
    pub technique: Technique,
    pub bias_mode: BiasMode,
    /// Constant bias, NDC depth units (the GAMES202 framework's EPS is 1e-3); the floor of the
    /// slope mode and the margin of the receiver-plane mode.
    pub bias: f32,
    /// Slope-scaled mode: `bias = max(slope_bias * (1 - N.L), bias)`, NDC depth units.
    /// The 0.05 and 0.005 of [LearnOpenGL-ShadowMapping] suit its 7.5-unit light frustum; NDC
    /// biases do not carry over between depth ranges, so the defaults here are smaller.
    pub slope_bias: f32,
    /// Adaptive mode [DrFlower-HW1]: `bias_world = adaptive_c * max(A, A * (1 - N.L))`, A = half
    /// a texel (grown with the filter radius), world units; dimensionless.
    pub adaptive_c: f32,
    /// Lookup point moved along the surface normal by this many texels (in world units)
    /// [ThreeJS-NormalBias].
    pub normal_offset_texels: f32,
    /// Hardware depth bias in the shadow pass, in units of the depth format's resolution
    /// [Wgpu-ShadowExample].
    pub depth_bias_constant: i32,
    /// Hardware slope-scaled depth bias in the shadow pass.
    pub depth_bias_slope: f32,
    /// Render back faces only into the shadow map.
    pub cull_front_faces: bool,
    pub pcf_kernel: Kernel,
    /// PCF filter taps (PCSS step 3 too).
    pub samples: u32,
    /// PCF filter radius, shadow-map texels.
    pub radius_texels: f32,
    /// Rotate the pattern per pixel (trades banding for noise).
    pub rotate_per_pixel: bool,
    pub noise_seed: u32,
    /// PCSS blocker-search taps.
    pub blocker_samples: u32,
    /// PCSS never filters with a smaller radius than this, texels.
    pub min_filter_radius_texels: f32,
    /// PCSS blocker-search radius as a multiple of the light's cone (1: half the light's width
    /// carried to the map, as the geometry says; 2: the full width, as the homework's write-ups do).
    pub search_radius_scale: f32,
    /// How the shadow map keeps its depths.
    pub depth_storage: DepthStorage,
    /// Scale an orthographic map's PCSS filter radius by near / d_receiver too, as [NVIDIA-2008]'s
    /// sample does for every light (the copied bug: that factor carries a perspective light's
    /// penumbra onto its near plane; an orthographic map's uv are the same at every depth).
    pub ortho_near_factor: bool,
    /// VSM: the least variance Chebyshev's bound uses, NDC depth squared (keeps a flat receiver
    /// from shadowing itself where its filtered variance rounds to 0).
    pub vsm_min_variance: f32,
    /// VSM light-bleeding reduction [Lauritzen-2007]: bounds below this are taken as shadow and
    /// the rest are stretched back over 0..1, (p - a) / (1 - a). Dimensionless, 0: off.
    pub vsm_bleed_reduction: f32,
    /// True: points outside the light frustum are lit. False shows the classic bug (wrapped
    /// lookups and a dark band past the far plane).
    pub clamp_outside: bool,
    /// Hard shadows averaged for the ground truth.
    pub reference_samples: u32,
}

impl Default for ShadowSettings {
    fn default() -> Self {
        Self {
            technique: Technique::Pcss,
            bias_mode: BiasMode::Constant,
            bias: 0.001,
            slope_bias: 0.005,
            adaptive_c: 1.5,
            normal_offset_texels: 0.0,
            depth_bias_constant: 0,
            depth_bias_slope: 0.0,
            cull_front_faces: false,
            pcf_kernel: Kernel::Poisson,
            samples: 32,
            radius_texels: 3.0,
            rotate_per_pixel: true,
            noise_seed: 1,
            blocker_samples: 32,
            min_filter_radius_texels: 0.0,
            search_radius_scale: 1.0,
            depth_storage: DepthStorage::Float32,
            ortho_near_factor: false,
            vsm_min_variance: 1e-6,
            vsm_bleed_reduction: 0.0,
            clamp_outside: true,
            reference_samples: 256,
        }
    }
}

impl ShadowSettings {
    /// Taps the filter really takes (the grid uses a square number).
    pub fn effective_samples(&self) -> u32 {
        effective_samples(self.pcf_kernel, self.samples)
    }
}

pub fn effective_samples(kernel: Kernel, samples: u32) -> u32 {
    filter_taps(kernel, samples)
}

/// Most filter or blocker-search taps (the `samples` and `blocker_samples` limit); the GPU's
/// kernel table holds this many of each (MAX_TAPS in shaders/common.wgsl).
pub const MAX_TAPS: u32 = 128;

/// floor(sqrt(n)), computed as the shader does (rounded, then corrected) so both agree.
pub fn grid_side(n: u32) -> u32 {
    let mut side = ((n as f32).sqrt() + 0.5) as u32;
    if side * side > n {
        side -= 1;
    }
    side.max(1)
}

/// Taps a kernel takes for `samples`: the grid rounds down to a square.
pub fn filter_taps(kernel: Kernel, samples: u32) -> u32 {
    match kernel {
        Kernel::Grid => grid_side(samples) * grid_side(samples),
        _ => samples,
    }
}
