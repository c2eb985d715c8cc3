//! A homework's two passes on the GPU, as the framework draws them: the light pass writes packed
//! depth into an RGBA8 map that starts at 0 (the framework never clears it: texels no object
//! covers read 0) or, on request, at white; the camera pass runs the student's fragment shader
//! and keeps, beside the colour, what their `useShadowMap` / `PCF` / `PCSS` / `findBlocker`
//! returned at every pixel.

use super::interface::STUDENT_BLOCK_BINDING;
use super::pipeline::Pass;
use super::program::HomeworkProgram;
use super::{BindingKind, CLIP_Y_SIGN_OFFSET_BYTES, FRAMEWORK_UNIFORMS_SIZE_BYTES, SamplerFilter};
use crate::render::readback;
use crate::scene::{Object, Scene};
use glam::{Mat4, Vec3};
use wgpu::util::DeviceExt;

/// The framework's light: `uLightIntensity` is this times the light's colour and intensity.
pub const FRAMEWORK_LIGHT_INTENSITY: f32 = 5000.0;
/// WebGL's clear colour in the framework (the camera pass's background).
const CLEAR_COLOR: wgpu::Color = wgpu::Color { r: 0.0, g: 0.0, b: 0.0, a: 1.0 };
const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
const RETURNED_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
const CALLS_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Uint;
const MAP_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
pub(super) const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// GL clip space from wgpu's: z from 0..w to -w..w (the framework's matrices are GL's; the
/// vertex epilogue maps them back).
fn gl_from_wgpu_clip() -> Mat4 {
    Mat4::from_cols_array(&[1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, -1.0, 1.0])
}

/// What to render a homework with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HomeworkRequest {
    pub time_s: f32,
    /// Camera view size, pixels.
    pub size: (u32, u32),
    /// The light whose map the student's shader reads.
    pub light: usize,
    /// Clear the map to white before the light pass (the framework leaves it at 0).
    pub clear_map_white: bool,
}

/// The camera pass read back, per pixel, rows top first.
#[derive(Clone, Debug)]
pub struct HomeworkImages {
    pub width: u32,
    pub height: u32,
    /// What the student's shader wrote to `gl_FragColor` (gamma-encoded, as they computed it).
    pub color: Vec<[f32; 4]>,
    /// The last value each of `RECORDED_FUNCTIONS` returned there.
    pub returned: Vec<[f32; 4]>,
    /// A bit per recorded function that ran, the visibility function + 1, calls (at most 255),
    /// and 1 where the student's shader ran at all.
    pub calls: Vec<[u8; 4]>,
}

impl HomeworkImages {
    /// The student's shader ran at pixel `i` (a surface is there).
    pub fn covered(&self, i: usize) -> bool {
        self.calls[i][3] != 0
    }

    /// The visibility at pixel `i`: what the last `useShadowMap` / `PCF` / `PCSS` called from
    /// the level of `main` returned; None where none was.
    pub fn visibility(&self, i: usize) -> Option<f32> {
        let function = self.calls[i][1] as usize;
        (self.covered(i) && (1..=3).contains(&function)).then(|| self.returned[i][function - 1])
    }

    /// Which recorded functions ran anywhere (bits in `RECORDED_FUNCTIONS` order).
    pub fn ran_anywhere(&self) -> u8 {
        self.calls.iter().fold(0, |bits, c| bits | c[0])
    }
}

/// The homework's pipelines on a device.
pub struct HomeworkRenderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    light: Pass,
    camera: Pass,
    linear: wgpu::Sampler,
    nearest: wgpu::Sampler,
}

/// A GPU error in a homework's pipeline or draw, on one line.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct HomeworkGpuError(pub String);

impl From<crate::render::RenderError> for HomeworkGpuError {
    fn from(e: crate::render::RenderError) -> Self {
        HomeworkGpuError(e.to_string())
    }
}

/// One object's uniforms for one pass, std140 as `FRAMEWORK_UNIFORMS` lays them out.
fn framework_block(scene: &Scene, object: &Object, request: &HomeworkRequest, clip_y_sign: f32) -> Vec<u8> {
    let (w, h) = request.size;
    let camera = &scene.camera;
    let light = &scene.lights[request.light];
    let t = request.time_s;
    let model = object.world_from_object(t);
    let to_gl = gl_from_wgpu_clip();
    let mut block = vec![0.0f32; (FRAMEWORK_UNIFORMS_SIZE_BYTES / 4) as usize];
    let mut put = |offset_bytes: usize, values: &[f32]| {
        block[offset_bytes / 4..offset_bytes / 4 + values.len()].copy_from_slice(values);
    };
    put(0, &model.to_cols_array());
    put(64, &camera.view_from_world().to_cols_array());
    put(128, &(to_gl * camera.clip_from_view(w as f32 / h.max(1) as f32)).to_cols_array());
    put(192, &(to_gl * light.clip_from_world(t) * model).to_cols_array());
    put(256, &camera.position.to_array());
    put(272, &light.position_at(t).to_array());
    put(288, &(FRAMEWORK_LIGHT_INTENSITY * light.intensity * light.color).to_array());
    // uKs: the scene's materials have no specular colour (0); uKd: never set by the framework.
    put(304, &Vec3::ZERO.to_array());
    put(CLIP_Y_SIGN_OFFSET_BYTES as usize, &[clip_y_sign]);
    bytemuck::cast_slice(&block).to_vec()
}

impl HomeworkRenderer {
    /// The homework's pipelines; a shader wgpu refuses is an error on one line.
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        program: &HomeworkProgram,
    ) -> Result<Self, HomeworkGpuError> {
        let target =
            |format| Some(wgpu::ColorTargetState { format, blend: None, write_mask: wgpu::ColorWrites::ALL });
        let light = Pass::new(device, &program.light, &[target(MAP_FORMAT)], "homework light pass")?;
        let camera = Pass::new(
            device,
            &program.camera,
            &[target(COLOR_FORMAT), target(RETURNED_FORMAT), target(CALLS_FORMAT)],
            "homework camera pass",
        )?;
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
            camera,
            linear: sampler(wgpu::FilterMode::Linear),
            nearest: sampler(wgpu::FilterMode::Nearest),
        })
    }

    /// Both passes' pipelines were taken (Ready(Ok)), one was refused (Ready(Err)), or a page's
    /// browser has not answered yet: render only once they are taken.
    pub fn ready(&mut self) -> std::task::Poll<Result<(), HomeworkGpuError>> {
        match (self.light.ready(), self.camera.ready()) {
            (std::task::Poll::Ready(Err(e)), _) | (_, std::task::Poll::Ready(Err(e))) => {
                std::task::Poll::Ready(Err(e))
            }
            (std::task::Poll::Ready(Ok(())), std::task::Poll::Ready(Ok(()))) => {
                std::task::Poll::Ready(Ok(()))
            }
            _ => std::task::Poll::Pending,
        }
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

    /// Draw every object of `scene` with `pass` into `encoder`'s open render pass.
    #[allow(clippy::too_many_arguments)]
    fn draw(
        &self,
        pass: &Pass,
        render: &mut wgpu::RenderPass<'_>,
        scene: &Scene,
        request: &HomeworkRequest,
        clip_y_sign: f32,
        shadow_map: &wgpu::TextureView,
        keep: &mut Vec<wgpu::Buffer>,
    ) {
        let black = self.rgba8("unset texture", (1, 1), &[0, 0, 0, 255]).create_view(&Default::default());
        let student = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("homework student uniforms"),
            size: pass.student_block_bytes.max(16).next_multiple_of(16),
            usage: wgpu::BufferUsages::UNIFORM,
            mapped_at_creation: false,
        });
        render.set_pipeline(&pass.pipeline);
        for object in &scene.objects {
            let block = self.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("homework framework uniforms"),
                contents: &framework_block(scene, object, request, clip_y_sign),
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
                let material = material.and_then(|m| mesh.materials.get(m));
                let albedo = match material.and_then(|m| m.diffuse_texture.as_ref()) {
                    Some(t) => self.rgba8("homework albedo", (t.width, t.height), &t.rgba8),
                    None => {
                        // The object's colour, sRGB-encoded as a texture file would hold it.
                        let linear = material.map_or(object.color, |m| m.diffuse * object.color);
                        let byte = |c: f32| (255.0 * c.clamp(0.0, 1.0).powf(1.0 / 2.2)).round() as u8;
                        self.rgba8(
                            "homework colour",
                            (1, 1),
                            &[byte(linear.x), byte(linear.y), byte(linear.z), 255],
                        )
                    }
                };
                let albedo = albedo.create_view(&Default::default());
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
            keep.extend([block, vertices, indices]);
        }
        keep.push(student);
    }

    /// Render the homework: the light pass into a fresh map, then the camera pass; read back the
    /// camera pass's targets (waiting for them).
    pub fn render(
        &self,
        scene: &Scene,
        request: &HomeworkRequest,
    ) -> Result<HomeworkImages, HomeworkGpuError> {
        Ok(self.submit(scene, request)?.wait(&self.device)?)
    }

    /// `render`'s passes submitted, their read-back on its way (for a caller that cannot wait).
    pub fn submit(
        &self,
        scene: &Scene,
        request: &HomeworkRequest,
    ) -> Result<readback::Readback<HomeworkImages>, HomeworkGpuError> {
        let light = scene
            .lights
            .get(request.light)
            .ok_or_else(|| HomeworkGpuError(format!("the scene has no light {}", request.light)))?;
        let (w, h) = request.size;
        let map_size = (light.shadow_map_size, light.shadow_map_size);
        let attach = wgpu::TextureUsages::RENDER_ATTACHMENT;
        let map = self.texture(
            "homework shadow map",
            map_size,
            MAP_FORMAT,
            attach | wgpu::TextureUsages::TEXTURE_BINDING,
        );
        let map_depth = self.texture("homework light depth", map_size, DEPTH_FORMAT, attach);
        let color = self.texture(
            "homework colour",
            request.size,
            COLOR_FORMAT,
            attach | wgpu::TextureUsages::COPY_SRC,
        );
        let returned = self.texture(
            "homework returned",
            request.size,
            RETURNED_FORMAT,
            attach | wgpu::TextureUsages::COPY_SRC,
        );
        let calls = self.texture(
            "homework calls",
            request.size,
            CALLS_FORMAT,
            attach | wgpu::TextureUsages::COPY_SRC,
        );
        let depth = self.texture("homework depth", request.size, DEPTH_FORMAT, attach);
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let (map_view, color_view, returned_view, calls_view) =
            (view(&map), view(&color), view(&returned), view(&calls));

        let scope = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let mut keep = Vec::new();
        let mut encoder = self.device.create_command_encoder(&Default::default());
        let (map_depth_view, depth_view) = (view(&map_depth), view(&depth));
        let depth_ops =
            Some(wgpu::Operations { load: wgpu::LoadOp::Clear(1.0), store: wgpu::StoreOp::Discard });
        {
            // The framework's map is never cleared: a fresh texture reads 0, as WebGL's does.
            let map_start =
                if request.clear_map_white { wgpu::Color::WHITE } else { wgpu::Color::TRANSPARENT };
            let mut render = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("homework light pass"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &map_view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(map_start),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &map_depth_view,
                    depth_ops,
                    stencil_ops: None,
                }),
                ..Default::default()
            });
            self.draw(&self.light, &mut render, scene, request, -1.0, &map_view, &mut keep);
        }
        {
            fn clear(
                view: &wgpu::TextureView,
                value: wgpu::Color,
            ) -> Option<wgpu::RenderPassColorAttachment<'_>> {
                Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations { load: wgpu::LoadOp::Clear(value), store: wgpu::StoreOp::Store },
                })
            }
            let mut render = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("homework camera pass"),
                color_attachments: &[
                    clear(&color_view, CLEAR_COLOR),
                    clear(&returned_view, wgpu::Color::TRANSPARENT),
                    clear(&calls_view, wgpu::Color::TRANSPARENT),
                ],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &depth_view,
                    depth_ops,
                    stencil_ops: None,
                }),
                ..Default::default()
            });
            self.draw(&self.camera, &mut render, scene, request, 1.0, &map_view, &mut keep);
        }
        self.queue.submit([encoder.finish()]);
        if let Some(e) = crate::render::scope_error(scope.pop()) {
            return Err(HomeworkGpuError(format!("homework render: {}", crate::render::error_line(&e))));
        }
        // The three targets come back together (one wait for all).
        let read = |texture: &wgpu::Texture, bytes: u32| {
            let region = readback::Region::whole(0, (w, h), bytes, wgpu::TextureAspect::All);
            readback::Readback::texture(&self.device, &self.queue, texture, region, |m| Ok(m.to_vec()))
        };
        let targets = read(&color, 8).zip(read(&returned, 16)).zip(read(&calls, 4));
        Ok(targets.map(move |((color, returned), calls)| Ok(decode(w, h, &color, &returned, &calls))))
    }
}

/// The camera pass's targets as read back: half-float colour, f32 returns, u8 calls.
fn decode(w: u32, h: u32, color: &[u8], returned: &[u8], calls: &[u8]) -> HomeworkImages {
    let half = |b: &[u8]| half::f16::from_bits(u16::from_le_bytes([b[0], b[1]])).to_f32();
    HomeworkImages {
        width: w,
        height: h,
        color: color
            .chunks_exact(8)
            .map(|c| [half(&c[0..]), half(&c[2..]), half(&c[4..]), half(&c[6..])])
            .collect(),
        returned: readback::f32s(returned)
            .collect::<Vec<_>>()
            .chunks_exact(4)
            .map(|c| [c[0], c[1], c[2], c[3]])
            .collect(),
        calls: calls.chunks_exact(4).map(|c| [c[0], c[1], c[2], c[3]]).collect(),
    }
}
