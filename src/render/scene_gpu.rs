//! The scene's meshes, textures and per-object uniforms on the GPU.

use super::gpu_types::ObjectGpu;
use super::layouts::Layouts;
use crate::scene::{Mesh, Scene, TextureImage};
use glam::Vec3;
use std::collections::HashMap;
use std::sync::Arc;
use wgpu::util::DeviceExt;

struct MeshGpu {
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
}

/// One draw call: a part of an object's mesh with its material.
struct DrawItem {
    object: usize,
    mesh: usize,
    index_range: std::ops::Range<u32>,
    base_color: Vec3,
    textured: bool,
    uniform: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
}

pub struct SceneGpu {
    /// Identity of what was uploaded: each object's mesh pointer and colour.
    key: Vec<(usize, [u32; 3])>,
    /// Distinct for every upload (a new scene's textures invalidate cached albedo).
    pub generation: u64,
    meshes: Vec<MeshGpu>,
    draws: Vec<DrawItem>,
}

fn scene_key(scene: &Scene) -> Vec<(usize, [u32; 3])> {
    scene
        .objects
        .iter()
        .map(|o| (Arc::as_ptr(&o.mesh) as usize, o.color.to_array().map(f32::to_bits)))
        .collect()
}

fn upload_texture(device: &wgpu::Device, queue: &wgpu::Queue, image: &TextureImage) -> wgpu::TextureView {
    // Mip chain built on the CPU (box filter via image's triangle filter): tiled floors alias without it.
    let mut levels = vec![image.rgba8.clone()];
    let (mut w, mut h) = (image.width.max(1), image.height.max(1));
    let mut sizes = vec![(w, h)];
    let mut current = image::RgbaImage::from_raw(w, h, image.rgba8.clone());
    while w > 1 || h > 1 {
        let Some(img) = current.take() else { break };
        let (nw, nh) = ((w / 2).max(1), (h / 2).max(1));
        let next = image::imageops::resize(&img, nw, nh, image::imageops::FilterType::Triangle);
        levels.push(next.as_raw().clone());
        sizes.push((nw, nh));
        current = Some(next);
        (w, h) = (nw, nh);
    }
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("diffuse"),
        size: wgpu::Extent3d {
            width: image.width.max(1),
            height: image.height.max(1),
            depth_or_array_layers: 1,
        },
        mip_level_count: levels.len() as u32,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8UnormSrgb,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    for (mip, (data, (lw, lh))) in levels.iter().zip(sizes).enumerate() {
        queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &texture,
                mip_level: mip as u32,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            data,
            wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(4 * lw), rows_per_image: Some(lh) },
            wgpu::Extent3d { width: lw, height: lh, depth_or_array_layers: 1 },
        );
    }
    texture.create_view(&wgpu::TextureViewDescriptor::default())
}

fn transform_bits(object: &crate::scene::Object, t_s: f32) -> [u32; 16] {
    object.world_from_object(t_s).to_cols_array().map(f32::to_bits)
}

impl DrawItem {
    fn albedo_cacheable(&self, scene: &Scene) -> bool {
        self.textured && scene.objects.get(self.object).is_some_and(|o| o.is_still())
    }
}

impl SceneGpu {
    pub fn matches(&self, scene: &Scene) -> bool {
        self.key == scene_key(scene)
    }

    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, layouts: &Layouts, scene: &Scene) -> Self {
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("diffuse"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            anisotropy_clamp: 8,
            ..Default::default()
        });
        let white = upload_texture(
            device,
            queue,
            &TextureImage { path: "<white>".into(), width: 1, height: 1, rgba8: vec![255; 4] },
        );
        let mut mesh_index: HashMap<usize, usize> = HashMap::new();
        let mut texture_views: HashMap<usize, wgpu::TextureView> = HashMap::new();
        let mut meshes = Vec::new();
        let mut draws = Vec::new();
        for (object_index, object) in scene.objects.iter().enumerate() {
            let mesh: &Mesh = &object.mesh;
            let mesh_slot = *mesh_index.entry(Arc::as_ptr(&object.mesh) as usize).or_insert_with(|| {
                meshes.push(MeshGpu {
                    vertices: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                        label: Some(&mesh.name),
                        contents: bytemuck::cast_slice(&mesh.vertices),
                        usage: wgpu::BufferUsages::VERTEX,
                    }),
                    indices: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                        label: Some(&mesh.name),
                        contents: bytemuck::cast_slice(&mesh.indices),
                        usage: wgpu::BufferUsages::INDEX,
                    }),
                });
                meshes.len() - 1
            });
            for part in &mesh.parts {
                let material = part.material.and_then(|m| mesh.materials.get(m));
                let base_color = material.map_or(object.color, |m| m.diffuse);
                let texture = material.and_then(|m| m.diffuse_texture.as_ref());
                let view = match texture {
                    Some(t) => texture_views
                        .entry(Arc::as_ptr(t) as usize)
                        .or_insert_with(|| upload_texture(device, queue, t))
                        .clone(),
                    None => white.clone(),
                };
                let uniform = device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("object"),
                    size: std::mem::size_of::<ObjectGpu>() as u64,
                    usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
                let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("object"),
                    layout: &layouts.object,
                    entries: &[
                        wgpu::BindGroupEntry { binding: 0, resource: uniform.as_entire_binding() },
                        wgpu::BindGroupEntry {
                            binding: 1,
                            resource: wgpu::BindingResource::TextureView(&view),
                        },
                        wgpu::BindGroupEntry {
                            binding: 2,
                            resource: wgpu::BindingResource::Sampler(&sampler),
                        },
                    ],
                });
                draws.push(DrawItem {
                    object: object_index,
                    mesh: mesh_slot,
                    index_range: part.index_start..part.index_start + part.index_count,
                    base_color,
                    textured: texture.is_some(),
                    uniform,
                    bind_group,
                });
            }
        }
        static UPLOADS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
        let generation = UPLOADS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        Self { key: scene_key(scene), generation, meshes, draws }
    }

    /// Object transforms at time `t`.
    pub fn update(&self, queue: &wgpu::Queue, scene: &Scene, t_s: f32) {
        for draw in &self.draws {
            let Some(object) = scene.objects.get(draw.object) else { continue };
            let world_from_object = object.world_from_object(t_s);
            let gpu = ObjectGpu {
                world_from_object: world_from_object.to_cols_array_2d(),
                normal_from_object: world_from_object.inverse().transpose().to_cols_array_2d(),
                base_color: draw.base_color.extend(if draw.textured { 1.0 } else { 0.0 }).to_array(),
                object_index: draw.object as u32,
                _pad: [0; 3],
            };
            queue.write_buffer(&draw.uniform, 0, bytemuck::bytes_of(&gpu));
        }
    }

    /// Record every draw; the caller has set the pipeline and the other bind groups.
    pub fn draw<'a>(&'a self, pass: &mut wgpu::RenderPass<'a>, object_group: u32) {
        self.draw_where(pass, object_group, |_| true);
    }

    /// The parts whose albedo the camera view may cache: textured, on objects that do not move.
    pub fn has_cacheable_albedo(&self, scene: &Scene) -> bool {
        self.draws.iter().any(|d| d.albedo_cacheable(scene))
    }

    /// Record the draws whose albedo is cacheable (see [`Self::has_cacheable_albedo`]), or the
    /// others.
    pub fn draw_cacheable_albedo<'a>(
        &'a self,
        pass: &mut wgpu::RenderPass<'a>,
        object_group: u32,
        scene: &Scene,
        cacheable: bool,
    ) {
        self.draw_where(pass, object_group, |d| d.albedo_cacheable(scene) == cacheable);
    }

    /// Every object's world transform at `t_s`, as bits (part of the shadow maps' key).
    pub fn object_transforms(scene: &Scene, t_s: f32) -> Vec<[u32; 16]> {
        scene.objects.iter().map(|o| transform_bits(o, t_s)).collect()
    }

    /// World transforms of the objects with cacheable albedo (part of the cache's key; they are
    /// still, so any time gives the same).
    pub fn cacheable_albedo_transforms(&self, scene: &Scene) -> Vec<[u32; 16]> {
        let cacheable = self.draws.iter().filter(|d| d.albedo_cacheable(scene));
        cacheable.filter_map(|d| scene.objects.get(d.object)).map(|o| transform_bits(o, 0.0)).collect()
    }

    fn draw_where<'a>(
        &'a self,
        pass: &mut wgpu::RenderPass<'a>,
        object_group: u32,
        keep: impl Fn(&DrawItem) -> bool,
    ) {
        for draw in self.draws.iter().filter(|d| keep(d)) {
            let mesh = &self.meshes[draw.mesh];
            pass.set_bind_group(object_group, &draw.bind_group, &[]);
            pass.set_vertex_buffer(0, mesh.vertices.slice(..));
            pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(draw.index_range.clone(), 0, 0..1);
        }
    }
}
