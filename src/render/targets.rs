//! Offscreen targets the renderer owns: the camera view (colour, depth, analysis floats) and
//! the shadow-map array (one layer per light).

use super::pipelines::{ANALYSIS_FORMAT, ANALYSIS_TARGETS, COLOR_FORMAT, COLOR_TARGET_FORMAT, DEPTH_FORMAT};

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
}

impl ViewTargets {
    pub fn new(device: &wgpu::Device, size: (u32, u32)) -> Self {
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
        }
    }
}

pub struct ShadowMaps {
    /// Texels per side of every layer; a light with a smaller map uses the top-left corner.
    pub atlas_size: u32,
    pub layers: u32,
    pub texture: wgpu::Texture,
    pub array_view: wgpu::TextureView,
    pub layer_views: Vec<wgpu::TextureView>,
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
        Self { atlas_size, layers, texture, array_view, layer_views }
    }
}
