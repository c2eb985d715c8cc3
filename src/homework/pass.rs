//! A homework's two passes on the GPU, as the framework draws them: the light pass writes packed
//! depth into an RGBA8 map that starts at 0 (the framework never clears it: texels no object
//! covers read 0) or, on request, at white, or in floats (lossless); the camera pass runs the
//! student's fragment shader and keeps, beside the colour, what their `useShadowMap` / `PCF` /
//! `PCSS` / `findBlocker` returned at every pixel, or (the taps pass, the same shader again) where
//! those functions read the map.

use super::images::{HomeworkImages, PackedMap, TapImages, decode, decode_taps};
use super::instrument::TAPS_OUTPUT;
use super::interface::STUDENT_BLOCK_BINDING;
use super::light::{HomeworkLight, gl_from_wgpu_clip};
use super::pipeline::{DEPTH_FORMAT, Pass};
use super::program::HomeworkProgram;
use super::{
    BindingKind, CLIP_Y_SIGN_OFFSET_BYTES, FRAMEWORK_UNIFORMS_SIZE_BYTES, HomeworkGpuError, SamplerFilter,
};
use crate::render::readback;
use crate::scene::Scene;
use glam::Vec3;
use wgpu::util::DeviceExt;

/// The framework's light: `uLightIntensity` is this times the light's colour and intensity.
pub const FRAMEWORK_LIGHT_INTENSITY: f32 = 5000.0;
/// WebGL's clear colour in the framework (the camera pass's background).
const CLEAR_COLOR: wgpu::Color = wgpu::Color { r: 0.0, g: 0.0, b: 0.0, a: 1.0 };
const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
const RETURNED_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
const CALLS_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Uint;
const TAPS_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
const MAP_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
/// The map kept without loss: the packed channels as floats, so the student's own `unpack` reads
/// back the depth their `pack` was given (8 bits a channel round it, a bias of its own).
const LOSSLESS_MAP_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// The shadow map a homework's camera pass reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MapKind {
    /// As the framework has it: RGBA8, never cleared (texels no object covers read 0).
    Framework,
    /// RGBA8 cleared to white first: what depends on the framework's 0s changes.
    White,
    /// Never cleared, but kept in floats: what the 8-bit rounding hides shows.
    Lossless,
}

/// What to render a homework with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HomeworkRequest {
    pub time_s: f32,
    /// Camera view size, pixels.
    pub size: (u32, u32),
    /// The scene light whose map size the light pass uses.
    pub light: usize,
    pub map: MapKind,
}

/// The homework's pipelines on a device.
pub struct HomeworkRenderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    light: Pass,
    light_lossless: Pass,
    camera: Pass,
    /// The camera pass again, writing where the recorded functions read instead of what they
    /// returned (a pixel's targets may take 32 bytes: both do not fit at once).
    camera_taps: Pass,
    linear: wgpu::Sampler,
    nearest: wgpu::Sampler,
}

/// Object `index`'s uniforms for one pass, std140 as `FRAMEWORK_UNIFORMS` lays them out.
fn framework_block(
    scene: &Scene,
    light: &HomeworkLight,
    index: usize,
    request: &HomeworkRequest,
    clip_y_sign: f32,
) -> Vec<u8> {
    let (w, h) = request.size;
    let camera = &scene.camera;
    let model = scene.objects[index].world_from_object(request.time_s);
    let mut block = vec![0.0f32; (FRAMEWORK_UNIFORMS_SIZE_BYTES / 4) as usize];
    let mut put = |offset_bytes: usize, values: &[f32]| {
        block[offset_bytes / 4..offset_bytes / 4 + values.len()].copy_from_slice(values);
    };
    put(0, &model.to_cols_array());
    put(64, &camera.view_from_world().to_cols_array());
    put(128, &(gl_from_wgpu_clip() * camera.clip_from_view(w as f32 / h.max(1) as f32)).to_cols_array());
    put(192, &light.clip_from_object[index].to_cols_array());
    put(256, &camera.position.to_array());
    put(272, &light.position.to_array());
    put(288, &light.intensity.to_array());
    // uKs: the scene's materials have no specular colour (0); uKd: never set by the framework.
    put(304, &Vec3::ZERO.to_array());
    put(CLIP_Y_SIGN_OFFSET_BYTES as usize, &[clip_y_sign]);
    bytemuck::cast_slice(&block).to_vec()
}

fn colour_target(format: wgpu::TextureFormat) -> Option<wgpu::ColorTargetState> {
    Some(wgpu::ColorTargetState { format, blend: None, write_mask: wgpu::ColorWrites::ALL })
}

fn clear_to(view: &wgpu::TextureView, value: wgpu::Color) -> Option<wgpu::RenderPassColorAttachment<'_>> {
    Some(wgpu::RenderPassColorAttachment {
        view,
        depth_slice: None,
        resolve_target: None,
        ops: wgpu::Operations { load: wgpu::LoadOp::Clear(value), store: wgpu::StoreOp::Store },
    })
}

impl HomeworkRenderer {
    /// The homework's pipelines; a shader wgpu refuses is an error on one line.
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        program: &HomeworkProgram,
    ) -> Result<Self, HomeworkGpuError> {
        let light = Pass::new(device, &program.light, &[colour_target(MAP_FORMAT)], "homework light pass")?;
        let light_lossless = Pass::new(
            device,
            &program.light,
            &[colour_target(LOSSLESS_MAP_FORMAT)],
            "homework light pass (lossless)",
        )?;
        let camera = Pass::new(
            device,
            &program.camera,
            &[colour_target(COLOR_FORMAT), colour_target(RETURNED_FORMAT), colour_target(CALLS_FORMAT)],
            "homework camera pass",
        )?;
        let mut taps: Vec<Option<wgpu::ColorTargetState>> = vec![None; TAPS_OUTPUT as usize];
        taps.extend((0..4).map(|_| colour_target(TAPS_FORMAT)));
        let camera_taps = Pass::new(device, &program.camera, &taps, "homework camera pass (taps)")?;
        let sampler = |filter| {
            device.create_sampler(&wgpu::SamplerDescriptor {
                label: Some("homework sampler"),
                address_mode_u: wgpu::AddressMode::Repeat,
                address_mode_v: wgpu::AddressMode::Repeat,
                mag_filter: filter,
                min_filter: filter,
                ..Default::default()
            })
        };
        Ok(Self {
            device: device.clone(),
            queue: queue.clone(),
            light,
            light_lossless,
            camera,
            camera_taps,
            linear: sampler(wgpu::FilterMode::Linear),
            nearest: sampler(wgpu::FilterMode::Nearest),
        })
    }

    /// Every pass's pipeline was taken (Ready(Ok)), one was refused (Ready(Err)), or a page's
    /// browser has not answered yet: render only once they are taken.
    pub fn ready(&mut self) -> std::task::Poll<Result<(), HomeworkGpuError>> {
        let mut pending = false;
        for pass in [&mut self.light, &mut self.light_lossless, &mut self.camera, &mut self.camera_taps] {
            match pass.ready() {
                std::task::Poll::Ready(Err(e)) => return std::task::Poll::Ready(Err(e)),
                std::task::Poll::Pending => pending = true,
                std::task::Poll::Ready(Ok(())) => {}
            }
        }
        if pending { std::task::Poll::Pending } else { std::task::Poll::Ready(Ok(())) }
    }

    fn texture(
        &self,
        label: &str,
        size: (u32, u32),
        format: wgpu::TextureFormat,
        usage: wgpu::TextureUsages,
    ) -> wgpu::Texture {
        self.device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d { width: size.0.max(1), height: size.1.max(1), depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage,
            view_formats: &[],
        })
    }

    /// A texture of RGBA8 bytes, as WebGL uploads them (no sRGB decoding: the shader does it).
    fn rgba8(&self, label: &str, size: (u32, u32), bytes: &[u8]) -> wgpu::Texture {
        self.device.create_texture_with_data(
            &self.queue,
            &wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d { width: size.0, height: size.1, depth_or_array_layers: 1 },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: wgpu::TextureFormat::Rgba8Unorm,
                usage: wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            },
            wgpu::util::TextureDataOrder::LayerMajor,
            bytes,
        )
    }

    /// The object's albedo as the framework binds it: its texture, or its colour sRGB-encoded as a
    /// texture file would hold it.
    fn albedo(&self, object: &crate::scene::Object, material: Option<usize>) -> wgpu::TextureView {
        let mesh = &object.mesh;
        let material = material.and_then(|m| mesh.materials.get(m));
        let texture = match material.and_then(|m| m.diffuse_texture.as_ref()) {
            Some(t) => self.rgba8("homework albedo", (t.width, t.height), &t.rgba8),
            None => {
                let linear = material.map_or(object.color, |m| m.diffuse * object.color);
                let byte = |c: f32| (255.0 * c.clamp(0.0, 1.0).powf(1.0 / 2.2)).round() as u8;
                self.rgba8("homework colour", (1, 1), &[byte(linear.x), byte(linear.y), byte(linear.z), 255])
            }
        };
        texture.create_view(&Default::default())
    }

    /// Draw every object of `scene` with `pass` into an open render pass.
    #[allow(clippy::too_many_arguments)]
    fn draw(
        &self,
        pass: &Pass,
        render: &mut wgpu::RenderPass<'_>,
        scene: &Scene,
        light: &HomeworkLight,
        request: &HomeworkRequest,
        clip_y_sign: f32,
        shadow_map: &wgpu::TextureView,
        keep: &mut Vec<wgpu::Buffer>,
    ) {
        let black = self.rgba8("unset texture", (1, 1), &[0, 0, 0, 255]).create_view(&Default::default());
        // The student's own uniforms, as their page set them for this pass's program.
        let page = if clip_y_sign > 0.0 { &light.page_uniforms.camera } else { &light.page_uniforms.shadow };
        render.set_pipeline(&pass.pipeline);
        for (index, object) in scene.objects.iter().enumerate() {
            let student = self.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("homework student uniforms"),
                contents: &pass.student_block.bytes(&page.of(object, request.time_s)),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            let block = self.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("homework framework uniforms"),
                contents: &framework_block(scene, light, index, request, clip_y_sign),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            let mesh = &object.mesh;
            let vertices = self.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("homework vertices"),
                contents: bytemuck::cast_slice(&mesh.vertices),
                usage: wgpu::BufferUsages::VERTEX,
            });
            let indices = self.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("homework indices"),
                contents: bytemuck::cast_slice(&mesh.indices),
                usage: wgpu::BufferUsages::INDEX,
            });
            render.set_vertex_buffer(0, vertices.slice(..));
            render.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
            let whole = [(0u32, mesh.indices.len() as u32, None)];
            let parts: Vec<(u32, u32, Option<usize>)> = if mesh.parts.is_empty() {
                whole.to_vec()
            } else {
                mesh.parts.iter().map(|p| (p.index_start, p.index_count, p.material)).collect()
            };
            for (start, count, material) in parts {
                let albedo = self.albedo(object, material);
                let entries: Vec<wgpu::BindGroupEntry> = pass
                    .bindings
                    .iter()
                    .map(|(binding, name, kind)| wgpu::BindGroupEntry {
                        binding: *binding,
                        resource: match kind {
                            BindingKind::UniformBlock if *binding == STUDENT_BLOCK_BINDING => {
                                student.as_entire_binding()
                            }
                            BindingKind::UniformBlock => block.as_entire_binding(),
                            BindingKind::Texture if name == "uSampler" => {
                                wgpu::BindingResource::TextureView(&albedo)
                            }
                            BindingKind::Texture if name == "uShadowMap" && clip_y_sign > 0.0 => {
                                wgpu::BindingResource::TextureView(shadow_map)
                            }
                            BindingKind::Texture => wgpu::BindingResource::TextureView(&black),
                            BindingKind::Sampler(SamplerFilter::Nearest) => {
                                wgpu::BindingResource::Sampler(&self.nearest)
                            }
                            BindingKind::Sampler(SamplerFilter::Linear) => {
                                wgpu::BindingResource::Sampler(&self.linear)
                            }
                        },
                    })
                    .collect();
                let group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("homework bindings"),
                    layout: &pass.layout,
                    entries: &entries,
                });
                render.set_bind_group(0, &group, &[]);
                render.draw_indexed(start..start + count, 0, 0..1);
            }
            keep.extend([block, vertices, indices, student]);
        }
    }

    /// Render the homework: the light pass into a fresh map, then the camera pass; read back the
    /// camera pass's targets (waiting for them).
    pub fn render(
        &self,
        scene: &Scene,
        light: &HomeworkLight,
        request: &HomeworkRequest,
    ) -> Result<HomeworkImages, HomeworkGpuError> {
        Ok(self.submit(scene, light, request)?.wait(&self.device)?)
    }

    fn read(&self, texture: &wgpu::Texture, size: (u32, u32), bytes: u32) -> readback::Readback<Vec<u8>> {
        let region = readback::Region::whole(0, size, bytes, wgpu::TextureAspect::All);
        readback::Readback::texture(&self.device, &self.queue, texture, region, |m| Ok(m.to_vec()))
    }

    /// `render`'s passes submitted, their read-back on its way (for a caller that cannot wait).
    pub fn submit(
        &self,
        scene: &Scene,
        light: &HomeworkLight,
        request: &HomeworkRequest,
    ) -> Result<readback::Readback<HomeworkImages>, HomeworkGpuError> {
        Ok(self.submit_with_map(scene, light, request)?.map(|(images, _)| Ok(images)))
    }

    /// `submit`, with the map the light pass wrote read back too (the lossless one: its packed
    /// channels, rows as the student's uv lays them out).
    pub fn submit_with_map(
        &self,
        scene: &Scene,
        light: &HomeworkLight,
        request: &HomeworkRequest,
    ) -> Result<readback::Readback<(HomeworkImages, Option<PackedMap>)>, HomeworkGpuError> {
        let (w, h) = request.size;
        let formats = [COLOR_FORMAT, RETURNED_FORMAT, CALLS_FORMAT];
        let ([color, returned, calls], map) =
            self.draw_both(scene, light, request, &self.camera, 0, formats)?;
        // The targets come back together (one wait for all).
        let targets = self
            .read(&color, request.size, 8)
            .zip(self.read(&returned, request.size, 16))
            .zip(self.read(&calls, request.size, 4));
        let side = map.width();
        let map = match request.map {
            MapKind::Lossless => {
                self.read(&map, (side, side), 16).map(move |bytes| Ok(Some(PackedMap::decode(side, &bytes))))
            }
            MapKind::Framework | MapKind::White => readback::Readback::ready(None),
        };
        Ok(targets
            .zip(map)
            .map(move |(((color, returned), calls), map)| Ok((decode(w, h, &color, &returned, &calls), map))))
    }

    /// The taps pass submitted (where the recorded functions read the map), its read-back on its
    /// way.
    pub fn submit_taps(
        &self,
        scene: &Scene,
        light: &HomeworkLight,
        request: &HomeworkRequest,
    ) -> Result<readback::Readback<TapImages>, HomeworkGpuError> {
        let (w, h) = request.size;
        let (taps, _) =
            self.draw_both(scene, light, request, &self.camera_taps, TAPS_OUTPUT as usize, [TAPS_FORMAT; 4])?;
        let read = |k: usize| self.read(&taps[k], request.size, 8);
        let all = read(0).zip(read(1)).zip(read(2)).zip(read(3));
        Ok(all.map(move |(((a, b), c), d)| Ok(decode_taps(w, h, [&a, &b, &c, &d]))))
    }

    /// The light pass into a fresh map (as `request.map` asks), then `camera` into fresh targets
    /// of `formats` at locations `first..`, submitted; the targets and the map.
    fn draw_both<const N: usize>(
        &self,
        scene: &Scene,
        light: &HomeworkLight,
        request: &HomeworkRequest,
        camera: &Pass,
        first: usize,
        formats: [wgpu::TextureFormat; N],
    ) -> Result<([wgpu::Texture; N], wgpu::Texture), HomeworkGpuError> {
        let scene_light = scene
            .lights
            .get(request.light)
            .ok_or_else(|| HomeworkGpuError(format!("the scene has no light {}", request.light)))?;
        if light.clip_from_object.len() != scene.objects.len() {
            return Err(HomeworkGpuError(format!(
                "the light has {} object matrices for {} objects",
                light.clip_from_object.len(),
                scene.objects.len()
            )));
        }
        let map_size = (scene_light.shadow_map_size, scene_light.shadow_map_size);
        let attach = wgpu::TextureUsages::RENDER_ATTACHMENT;
        let (light_pass, map_format) = match request.map {
            MapKind::Lossless => (&self.light_lossless, LOSSLESS_MAP_FORMAT),
            MapKind::Framework | MapKind::White => (&self.light, MAP_FORMAT),
        };
        let map = self.texture(
            "homework shadow map",
            map_size,
            map_format,
            attach | wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_SRC,
        );
        let map_depth = self.texture("homework light depth", map_size, DEPTH_FORMAT, attach);
        let targets: [wgpu::Texture; N] = std::array::from_fn(|k| {
            self.texture(
                "homework camera target",
                request.size,
                formats[k],
                attach | wgpu::TextureUsages::COPY_SRC,
            )
        });
        let depth = self.texture("homework depth", request.size, DEPTH_FORMAT, attach);
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let (map_view, map_depth_view, depth_view) = (view(&map), view(&map_depth), view(&depth));
        let target_views: Vec<wgpu::TextureView> = targets.iter().map(view).collect();

        let scope = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let mut keep = Vec::new();
        let mut encoder = self.device.create_command_encoder(&Default::default());
        let depth_ops =
            Some(wgpu::Operations { load: wgpu::LoadOp::Clear(1.0), store: wgpu::StoreOp::Discard });
        {
            // The framework's map is never cleared: a fresh texture reads 0, as WebGL's does.
            let map_start =
                if request.map == MapKind::White { wgpu::Color::WHITE } else { wgpu::Color::TRANSPARENT };
            let mut render = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("homework light pass"),
                color_attachments: &[clear_to(&map_view, map_start)],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &map_depth_view,
                    depth_ops,
                    stencil_ops: None,
                }),
                ..Default::default()
            });
            self.draw(light_pass, &mut render, scene, light, request, -1.0, &map_view, &mut keep);
        }
        {
            // The colour starts at WebGL's clear colour, the rest at 0.
            let mut attachments: Vec<Option<wgpu::RenderPassColorAttachment>> = vec![None; first];
            for (k, view) in target_views.iter().enumerate() {
                attachments.push(clear_to(
                    view,
                    if first + k == 0 { CLEAR_COLOR } else { wgpu::Color::TRANSPARENT },
                ));
            }
            let mut render = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("homework camera pass"),
                color_attachments: &attachments,
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &depth_view,
                    depth_ops,
                    stencil_ops: None,
                }),
                ..Default::default()
            });
            self.draw(camera, &mut render, scene, light, request, 1.0, &map_view, &mut keep);
        }
        self.queue.submit([encoder.finish()]);
        if let Some(e) = crate::render::scope_error(scope.pop()) {
            return Err(HomeworkGpuError(format!("homework render: {}", crate::render::error_line(&e))));
        }
        Ok((targets, map))
    }
}
