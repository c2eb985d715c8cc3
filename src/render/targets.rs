//! Offscreen targets the renderer owns: the camera view (colour, depth, analysis floats) and
//! the shadow-map array (one layer per light).

/// The camera view's texture: sRGB-encoded bytes in an Rgba8Unorm texture (what egui's native
/// textures expect and what is read back to PNG)...
pub const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
/// ...written through an sRGB view, so the encoding happens at the store and the shader
/// returns linear colour (no per-pixel `pow`).
pub const COLOR_TARGET_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
pub const ANALYSIS_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
/// The albedo cache keeps the texture's samples as the shader computed them (f32, exact).
pub const ALBEDO_CACHE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// Number of float targets of the analysis pass: shadow terms, position, normal.
pub const ANALYSIS_TARGETS: usize = 3;

fn texture(
    device: &wgpu::Device,
    label: &str,
    size: (u32, u32),
    layers: u32,
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
    view_formats: &[wgpu::TextureFormat],
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d { width: size.0, height: size.1, depth_or_array_layers: layers },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage,
        view_formats,
    })
}

pub struct ViewTargets {
    pub size: (u32, u32),
    /// sRGB-encoded bytes in an Rgba8Unorm texture (what egui's native textures expect),
    /// rendered through `color_view`, an sRGB view that encodes on store.
    pub color: wgpu::Texture,
    pub color_view: wgpu::TextureView,
    pub depth_view: wgpu::TextureView,
    pub analysis: Vec<wgpu::Texture>,
    pub analysis_views: Vec<wgpu::TextureView>,
    pub albedo_cache: AlbedoCache,
}

/// The albedo of the still textured objects at each pixel of this view, kept while the camera,
/// the size and those objects stay the same (see `ALBEDO_FROM_CACHE` in shaders/camera_fast_paths.wgsl).
pub struct AlbedoCache {
    pub view: wgpu::TextureView,
    /// Group 3 of the camera passes.
    pub bind_group: wgpu::BindGroup,
    /// What the cache holds; `None` until it is first filled.
    pub filled_for: Option<AlbedoKey>,
    /// What the previous frame drew: the cache is filled on the second frame with the same key,
    /// so a camera in motion does not pay for a cache it would throw away.
    pub last_seen: Option<AlbedoKey>,
}

/// Everything the cached albedo depends on, as bits.
#[derive(Clone, Debug, PartialEq)]
pub struct AlbedoKey {
    pub clip_from_world: [u32; 16],
    pub scene_upload: u64,
    pub object_transforms: Vec<[u32; 16]>,
}

impl AlbedoCache {
    /// What to do for a frame with `key`: `(read the cache, fill it first)`.
    pub fn plan(&mut self, key: Option<AlbedoKey>) -> (bool, bool) {
        // Frames that do not draw the colour view (analysis, a probe's pixel) leave it be.
        let Some(key) = key else { return (false, false) };
        let filled = self.filled_for.as_ref() == Some(&key);
        let steady = self.last_seen.as_ref() == Some(&key);
        self.last_seen = Some(key.clone());
        if !filled && steady {
            self.filled_for = Some(key);
        }
        (filled || steady, !filled && steady)
    }
}

impl ViewTargets {
    pub fn new(device: &wgpu::Device, size: (u32, u32), albedo_layout: &wgpu::BindGroupLayout) -> Self {
        let rw = wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::COPY_SRC
            | wgpu::TextureUsages::TEXTURE_BINDING;
        let color = texture(device, "camera color", size, 1, COLOR_FORMAT, rw, &[COLOR_TARGET_FORMAT]);
        let depth = texture(
            device,
            "camera depth",
            size,
            1,
            DEPTH_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
            &[],
        );
        let analysis: Vec<_> = (0..ANALYSIS_TARGETS)
            .map(|_| texture(device, "camera analysis", size, 1, ANALYSIS_FORMAT, rw, &[]))
            .collect();
        let cache_usage = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING;
        let cache = texture(device, "albedo cache", size, 1, ALBEDO_CACHE_FORMAT, cache_usage, &[]);
        let albedo_cache = AlbedoCache::new(device, &cache, albedo_layout);
        Self {
            size,
            color_view: color.create_view(&wgpu::TextureViewDescriptor {
                format: Some(COLOR_TARGET_FORMAT),
                ..Default::default()
            }),
            color,
            depth_view: depth.create_view(&Default::default()),
            analysis_views: analysis.iter().map(|t| t.create_view(&Default::default())).collect(),
            analysis,
            albedo_cache,
        }
    }
}

impl AlbedoCache {
    pub fn new(device: &wgpu::Device, texture: &wgpu::Texture, layout: &wgpu::BindGroupLayout) -> Self {
        let view = texture.create_view(&Default::default());
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("albedo cache"),
            layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(&view),
            }],
        });
        Self { view, bind_group, filled_for: None, last_seen: None }
    }

    /// A 1x1 cache that is never read: group 3 while the real one is being written.
    pub fn placeholder(device: &wgpu::Device, layout: &wgpu::BindGroupLayout) -> Self {
        let usage = wgpu::TextureUsages::TEXTURE_BINDING;
        Self::new(
            device,
            &texture(device, "albedo cache placeholder", (1, 1), 1, ALBEDO_CACHE_FORMAT, usage, &[]),
            layout,
        )
    }
}

pub struct ShadowMaps {
    /// What the maps hold; `None` until drawn. A frame with the same key keeps them.
    pub drawn_for: Option<ShadowMapsKey>,
    /// Texels per side of every layer; a light with a smaller map uses the top-left corner.
    pub atlas_size: u32,
    pub layers: u32,
    pub texture: wgpu::Texture,
    pub array_view: wgpu::TextureView,
    pub layer_views: Vec<wgpu::TextureView>,
}

/// How the maps are rasterised, what the shadow pipeline is built for: hardware depth bias and
/// face culling.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub struct ShadowPipelineKey {
    pub depth_bias_constant: i32,
    pub depth_bias_slope_bits: u32,
    pub cull_front_faces: bool,
    /// Cube faces: the fragment stage writes the distance to the light (the rasteriser's depth
    /// bias then has no effect: a written depth replaces the biased one).
    pub stores_distance: bool,
}

/// Everything the shadow maps depend on, as bits: each shadow view's matrix and map size, every
/// object's transform, the uploaded meshes and the shadow pipeline (hardware bias, culling).
#[derive(Clone, Debug, PartialEq)]
pub struct ShadowMapsKey {
    pub views: Vec<([u32; 16], u32)>,
    pub object_transforms: Vec<[u32; 16]>,
    pub scene_upload: u64,
    pub pipeline: ShadowPipelineKey,
}

impl ShadowMaps {
    pub fn new(device: &wgpu::Device, atlas_size: u32, layers: u32) -> Self {
        let texture = texture(
            device,
            "shadow maps",
            (atlas_size, atlas_size),
            layers,
            DEPTH_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
            &[],
        );
        let array_view = texture.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        });
        let layer_views = (0..layers)
            .map(|layer| {
                texture.create_view(&wgpu::TextureViewDescriptor {
                    dimension: Some(wgpu::TextureViewDimension::D2),
                    base_array_layer: layer,
                    array_layer_count: Some(1),
                    ..Default::default()
                })
            })
            .collect();
        Self { drawn_for: None, atlas_size, layers, texture, array_view, layer_views }
    }
}
