//! What a frame uploads before it draws: the scene's buffers, the shadow-map array and the
//! view's targets (kept while they fit), the lights and the shadow parameters as the GPU and the
//! twin will see them (the one place `ShadowParamsGpu` is made from a scene's settings for a
//! frame), the kernel table and the camera.

use super::*;

impl Renderer {
    /// Whether this frame reads the view's albedo cache, and whether it fills it first. Only whole
    /// views use it (a probe's one-pixel render samples directly), and only when the camera, the
    /// view's size and the still textured objects are as they were last frame.
    pub(super) fn plan_albedo_cache(&mut self, scene: &Scene, request: &FrameRequest) -> (bool, bool) {
        let (Some(scene_gpu), Some(targets)) = (&self.scene_gpu, &mut self.targets) else {
            return (false, false);
        };
        let usable =
            request.final_color && request.only_pixel.is_none() && scene_gpu.has_cacheable_albedo(scene);
        let key = usable.then(|| {
            let aspect = request.size.0 as f32 / request.size.1 as f32;
            targets::AlbedoKey {
                clip_from_world: scene.camera.clip_from_world(aspect).to_cols_array().map(f32::to_bits),
                scene_upload: scene_gpu.generation,
                object_transforms: scene_gpu.cacheable_albedo_transforms(scene),
            }
        });
        targets.albedo_cache.plan(key)
    }

    /// Upload what this frame needs; returns its lights and parameters as the GPU will see them.
    pub(super) fn prepare(
        &mut self,
        scene: &Scene,
        request: &FrameRequest,
    ) -> (Vec<LightGpu>, Vec<ShadowViewGpu>, ShadowParamsGpu) {
        let device = &self.device;
        if !self.scene_gpu.as_ref().is_some_and(|s| s.matches(scene)) {
            self.scene_gpu = Some(SceneGpu::new(device, &self.queue, &self.layouts, scene));
        }
        let atlas_size = scene.lights.iter().map(|l| l.shadow_map_size).max().unwrap_or(256);
        let layers = views_needed(&scene.lights).max(1);
        let maps_changed =
            !self.shadow_maps.as_ref().is_some_and(|m| m.atlas_size == atlas_size && m.layers == layers);
        if maps_changed {
            self.shadow_maps = Some(ShadowMaps::new(device, atlas_size, layers));
        }
        // The moments are made the first time a frame uses VSM (and kept after), a placeholder
        // stands in before.
        let vsm = scene.shadow.technique.uses_moments();
        let moments_wanted = vsm && self.moments.as_ref().is_none_or(Moments::is_placeholder);
        if let Some(maps) = self.shadow_maps.as_ref().filter(|_| maps_changed || moments_wanted) {
            let moments = if vsm {
                Moments::new(device, &self.pipelines.moments, maps)
            } else {
                Moments::placeholder(device)
            };
            self.lights_bind_group = Some(self.shadow_inputs_group(
                &self.layouts.lights,
                self.lights_buffer.as_entire_binding(),
                &self.params_buffer,
                maps,
                Some(&moments),
            ));
            self.moments = Some(moments);
        }
        if self.targets.as_ref().is_none_or(|t| t.size != request.size) {
            let reuse = self.spare_targets.take().filter(|t| t.size == request.size);
            let targets =
                reuse.unwrap_or_else(|| ViewTargets::new(device, request.size, &self.layouts.albedo_cache));
            self.spare_targets = self.targets.replace(targets);
        }
        let t = request.time_s;
        let aspect = request.size.0 as f32 / request.size.1 as f32;
        let (frame_lights, frame_views) = frame_lights(scene, aspect, t, atlas_size);
        let mut lights = [bytemuck::Zeroable::zeroed(); MAX_LIGHTS];
        lights[..frame_lights.len()].copy_from_slice(&frame_lights);
        self.queue.write_buffer(&self.lights_buffer, 0, bytemuck::cast_slice(&lights));
        let mut views = [bytemuck::Zeroable::zeroed(); MAX_SHADOW_VIEWS];
        views[..frame_views.len()].copy_from_slice(&frame_views);
        self.queue.write_buffer(&self.views_buffer, 0, bytemuck::cast_slice(&views));
        // The shadow pass binds one view at a time (a dynamic offset per view).
        for (i, view) in frame_views.iter().enumerate() {
            self.queue.write_buffer(
                &self.shadow_view_buffer,
                i as u64 * DYNAMIC_STRIDE,
                bytemuck::bytes_of(view),
            );
        }
        let params = ShadowParamsGpu::new(&scene.shadow);
        self.queue.write_buffer(&self.params_buffer, 0, bytemuck::bytes_of(&params));
        self.write_kernel_table(&scene.shadow);
        let frame = FrameGpu {
            clip_from_world: scene.camera.clip_from_world(aspect).to_cols_array_2d(),
            camera_position: scene.camera.position.extend(1.0).to_array(),
            ambient: scene.ambient.extend(1.0).to_array(),
            light_count: scene.lights.len() as u32,
            selected_light: request.selected_light.min(MAX_LIGHTS - 1) as u32,
            _pad: [0; 2],
        };
        self.queue.write_buffer(&self.frame_buffer, 0, bytemuck::bytes_of(&frame));
        if let Some(scene_gpu) = &self.scene_gpu {
            scene_gpu.update(&self.queue, scene, t);
        }
        (frame_lights, frame_views, params)
    }

    /// The filter's and the blocker search's patterns for these settings (what `kernel_offset`
    /// in shaders/shadow_filter.wgsl turns per pixel).
    pub(super) fn write_kernel_table(&self, shadow: &ShadowSettings) {
        let search_kernel = crate::shadow::search_kernel(shadow.pcf_kernel);
        let filter = kernel_table(shadow.pcf_kernel, filter_taps(shadow.pcf_kernel, shadow.samples));
        let search = kernel_table(search_kernel, filter_taps(search_kernel, shadow.blocker_samples));
        // Tap i: filter in xy, search in zw.
        let mut table = vec![[0.0f32; 4]; MAX_TAPS as usize];
        for (slot, tap) in table.iter_mut().zip(&filter) {
            slot[..2].copy_from_slice(&tap.to_array());
        }
        for (slot, tap) in table.iter_mut().zip(&search) {
            slot[2..].copy_from_slice(&tap.to_array());
        }
        self.queue.write_buffer(&self.kernel_table_buffer, 0, bytemuck::cast_slice(&table));
    }

    /// Group 1 of the camera and reference shaders: light(s), parameters, maps, compare sampler,
    /// kernel table, and where the layout has them (the camera's) the VSM moments and the
    /// lights' shadow views.
    pub(super) fn shadow_inputs_group(
        &self,
        layout: &wgpu::BindGroupLayout,
        lights: wgpu::BindingResource<'_>,
        params: &wgpu::Buffer,
        maps: &ShadowMaps,
        moments: Option<&Moments>,
    ) -> wgpu::BindGroup {
        let moments = moments.map(|m| {
            [
                wgpu::BindGroupEntry { binding: 5, resource: wgpu::BindingResource::TextureView(&m.view) },
                wgpu::BindGroupEntry { binding: 6, resource: self.views_buffer.as_entire_binding() },
            ]
        });
        let entries: Vec<_> = [
            wgpu::BindGroupEntry { binding: 0, resource: lights },
            wgpu::BindGroupEntry { binding: 1, resource: params.as_entire_binding() },
            wgpu::BindGroupEntry {
                binding: 2,
                resource: wgpu::BindingResource::TextureView(&maps.array_view),
            },
            wgpu::BindGroupEntry {
                binding: 3,
                resource: wgpu::BindingResource::Sampler(&self.compare_sampler),
            },
            wgpu::BindGroupEntry { binding: 4, resource: self.kernel_table_buffer.as_entire_binding() },
        ]
        .into_iter()
        .chain(moments.into_iter().flatten())
        .collect();
        self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("shadow inputs"),
            layout,
            entries: &entries,
        })
    }
}
