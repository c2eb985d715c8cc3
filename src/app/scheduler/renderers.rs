//! The renderers a scheduler owns and the stages of a job (image, details, ground truths), the
//! same whichever scheduler runs them.

use super::{Details, MapView, Maps, ProbeOutcome, RenderEvent, RenderJob, RenderOutput};
use crate::probe;
use crate::render::{Analysis, FrameRequest, RenderError, Renderer};
use crate::scene::{Camera, Light, Mesh, Scene, ShadowSettings};
use crate::shadow::{DepthImage, LightGpu};
use crate::views;
use std::sync::Arc;
use std::time::Instant;

/// While dragging the map picture is built at this size at most.
const MAP_PREVIEW_TEXELS: u32 = 512;
/// Texels per side of a light's thumbnail.
const THUMBNAIL_TEXELS: u32 = 96;
/// Ground-truth samples in the first batch; each later batch doubles, up to `REFERENCE_BATCH_MAX`.
const REFERENCE_BATCH_FIRST: usize = 4;
const REFERENCE_BATCH_MAX: usize = 32;

/// Where a job is: the stage to run next.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Stage {
    /// The image (and the A/B side), then the maps: what goes on screen first.
    Image,
    /// The analysis the overlays draw and the probe.
    Details,
    /// The ground truth at the probe (right after the probe's frame).
    ProbeReference,
    /// The homework check, where the job carries one.
    Homework,
    /// The view's ground truth.
    ViewReference,
    Done,
}

/// The worker's renderers: `a` for the view, `b` for the A/B split's right side (made on first use).
pub(super) struct Renderers {
    device: wgpu::Device,
    queue: wgpu::Queue,
    a: Renderer,
    b: Option<Renderer>,
    /// What the last map picture sent was drawn from.
    last_map: Option<MapKey>,
    /// Ground truths at probes finished lately, newest last: what each depends on, the value at
    /// the probed pixel and the samples averaged.
    probe_truths: Vec<(ReferenceKey, f32, u32)>,
    /// The view's last finished ground truth.
    view_truth: Option<(ReferenceKey, Vec<f32>, u32)>,
    homework: super::homework::HomeworkRunner,
}

/// Probes' ground truths kept.
const PROBE_TRUTHS_KEPT: usize = 16;

/// Everything a ground truth depends on: the surface under each pixel (camera, frame, pixel,
/// objects, time), the light it averages over and the settings its hard shadows read
/// (`reference::settings_read`): the technique, filter and bias shown are not among them.
#[derive(Clone, Debug, PartialEq)]
struct ReferenceKey {
    camera: Camera,
    size: (u32, u32),
    /// The one pixel shaded (a probe); None: the whole view.
    pixel: Option<(u32, u32)>,
    time_bits: u32,
    objects: Vec<ObjectKey>,
    light_index: usize,
    light: Option<Light>,
    settings: ShadowSettings,
}

/// An object as the camera and the shadow passes see it: its mesh (kept alive here, so the
/// comparison by address cannot be fooled by a new mesh at a freed one's address) and placement.
#[derive(Clone)]
struct ObjectKey(Arc<Mesh>, [f32; 12]);

impl std::fmt::Debug for ObjectKey {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "ObjectKey({} at {:p}, {:?})", self.0.name, Arc::as_ptr(&self.0), self.1)
    }
}

impl PartialEq for ObjectKey {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0) && self.1 == other.1
    }
}

impl ReferenceKey {
    fn new(scene: &Scene, request: &FrameRequest, pixel: Option<(u32, u32)>, light_index: usize) -> Self {
        Self {
            camera: scene.camera,
            size: request.size,
            pixel,
            time_bits: request.time_s.to_bits(),
            objects: scene.objects.iter().map(|o| ObjectKey(o.mesh.clone(), placement(o))).collect(),
            light_index,
            light: scene.lights.get(light_index).copied(),
            settings: crate::reference::settings_read(&scene.shadow),
        }
    }
}

/// An object's translation, rotation, scale and spin, in a row.
fn placement(o: &crate::scene::Object) -> [f32; 12] {
    let mut placement = [0.0; 12];
    for (chunk, v) in placement.chunks_mut(3).zip([o.translate, o.rotate_deg, o.scale, o.spin_deg_per_s]) {
        chunk.copy_from_slice(&v.to_array());
    }
    placement
}

/// Everything the selected light's shadow map and its picture depend on. Dragging a value that
/// leaves the map alone (the light's width, a filter setting) then skips its read-back.
#[derive(Clone, Debug, PartialEq)]
struct MapKey {
    /// The light's view and depth range (not its colour or size, which the map does not see).
    light_clip_from_world: [[f32; 4]; 4],
    light_depth: (f32, f32, u32, f32),
    time_bits: u32,
    depth_bias: (i32, u32, bool),
    /// Per object: the mesh and its placement and spin.
    objects: Vec<(usize, [f32; 12])>,
    picture_texels: u32,
}

impl MapKey {
    fn new(scene: &Scene, light: &LightGpu, time_s: f32, picture_texels: u32) -> Self {
        let objects =
            scene.objects.iter().map(|o| (std::sync::Arc::as_ptr(&o.mesh) as usize, placement(o))).collect();
        let s = &scene.shadow;
        Self {
            light_clip_from_world: light.clip_from_world,
            light_depth: (light.near, light.far, light.orthographic, light.map_size_texels),
            time_bits: time_s.to_bits(),
            depth_bias: (s.depth_bias_constant, s.depth_bias_slope.to_bits(), s.cull_front_faces),
            objects,
            picture_texels,
        }
    }
}

pub(super) fn open(adapter: &wgpu::Adapter) -> Result<Renderers, RenderError> {
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("shadowlab render worker"),
        required_features: adapter.features() & crate::render::optional_features(),
        required_limits: adapter.limits(),
        ..Default::default()
    }))
    .map_err(|e| RenderError::Device(e.to_string()))?;
    let a = Renderer::new(&device, &queue)?;
    Ok(Renderers {
        device,
        queue,
        a,
        b: None,
        last_map: None,
        probe_truths: Vec::new(),
        view_truth: None,
        homework: Default::default(),
    })
}

impl Renderers {
    /// The job's image (and the A/B side): what goes on screen first.
    fn image(&mut self, id: u64, job: &RenderJob) -> Result<RenderOutput, RenderError> {
        let start = Instant::now();
        let scene = &job.scene;
        // The overlays' analysis comes from the same pass (one filtering, not two); `details`
        // reads it back after the image is on its way.
        let request =
            FrameRequest { final_color: true, analysis: job.analysis, timestamps: true, ..job.request };
        let rendered = self.a.render(scene, &request)?;
        let pass_times = self.a.last_pass_times()?;
        let color = self.a.read_color()?;
        let color_b = match job.technique_b {
            Some(technique) => {
                if self.b.is_none() {
                    self.b = Some(Renderer::new(&self.device, &self.queue)?);
                }
                let b = self.b.as_mut().ok_or_else(|| RenderError::Usage("no B renderer".into()))?;
                let mut scene_b = scene.clone();
                scene_b.shadow.technique = technique;
                b.render(&scene_b, &request)?;
                Some(b.read_color()?)
            }
            None => None,
        };
        Ok(RenderOutput {
            job: id,
            preview: job.preview,
            size: request.size,
            color,
            color_b,
            lights: rendered.lights,
            params: rendered.params,
            details_follow: job.wants_details(),
            pass_times,
            render_ms: start.elapsed().as_secs_f64() * 1e3,
        })
    }

    /// The maps of the frame `image` just rendered: the selected light's picture (unless it is
    /// the one sent last) and the thumbnails.
    fn maps(&mut self, id: u64, job: &RenderJob) -> Result<Maps, RenderError> {
        let scene = &job.scene;
        let lights = self.a.last_frame().map(|f| f.lights.clone()).unwrap_or_default();
        let limit = if job.preview { MAP_PREVIEW_TEXELS.min(job.map_texels) } else { job.map_texels };
        let map_key =
            lights.get(job.request.selected_light).map(|l| MapKey::new(scene, l, job.request.time_s, limit));
        let map_unchanged = map_key.is_some() && map_key == self.last_map;
        self.last_map = map_key;
        let map = match lights.get(job.request.selected_light).filter(|_| !map_unchanged) {
            Some(light) => {
                let depth = self.a.read_shadow_map(job.request.selected_light)?;
                let (image, legend) = views::shadow_map_image(&subsample(&depth, limit), light);
                Some(MapView { depth, light: *light, image, range: (legend.min, legend.max) })
            }
            None => None,
        };
        let mut thumbnails = Vec::new();
        if job.thumbnails && lights.len() > 1 {
            for (i, light) in lights.iter().enumerate() {
                let depth = self.a.read_shadow_map(i)?;
                let (image, _) = views::shadow_map_image(&subsample(&depth, 4 * THUMBNAIL_TEXELS), light);
                thumbnails.push(image::imageops::resize(
                    &image,
                    THUMBNAIL_TEXELS,
                    THUMBNAIL_TEXELS,
                    image::imageops::FilterType::Triangle,
                ));
            }
        }
        Ok(Maps { job: id, map, thumbnails })
    }
}

impl Renderers {
    /// The selected light's analysis for the overlays (drawn with the image), then the probe
    /// (one pixel of the analysis pass per light, which leaves the probe's frame as the last one
    /// rendered).
    fn details(&mut self, job: &RenderJob) -> Result<(ProbeOutcome, Option<Analysis>), RenderError> {
        let scene = &job.scene;
        let mut analysis = if job.analysis { Some(self.a.read_analysis()?) } else { None };
        if let Some(analysis) = analysis.as_mut().filter(|_| job.moments) {
            let light = job.request.selected_light;
            // Techniques without moments leave them out (the view says so); VSSM's radius varies
            // per pixel, so the view shows the level of the PCF radius and says which radius.
            analysis.moments = match self.a.read_moments_for_radius(light, scene.shadow.radius_texels) {
                Ok(level) => Some(level),
                Err(RenderError::Usage(_)) => None,
                Err(e) => return Err(e),
            };
        }
        if let Some(analysis) = analysis.as_mut().filter(|_| job.bleeding) {
            let light = job.request.selected_light;
            analysis.bleeding = crate::views::overlays::bleeding_of_last_frame(&self.a, analysis, light)?;
        }
        let request = FrameRequest { final_color: false, analysis: true, timestamps: false, ..job.request };
        let probe = job.probe.map(|spot| {
            let frame = FrameRequest { size: spot.frame, ..request };
            probe::probe(&mut self.a, scene, &frame, spot.pixel, false).map_err(|e| e.to_string())
        });
        Ok((probe, analysis))
    }

    /// The ground truth at the probe for each light the job asks for, right after `details` (the
    /// probe's frame is the last one rendered): `progress` hears (light, samples done, samples in
    /// all, the average at the pixel so far) after every batch, once for a ground truth kept from
    /// before; returning false stops it.
    fn probe_reference(
        &mut self,
        job: &RenderJob,
        progress: &mut dyn FnMut(usize, u32, u32, f32) -> bool,
    ) -> Result<(), RenderError> {
        let Some(spot) = job.probe else { return Ok(()) };
        let (x, y) = spot.pixel;
        let index = (y * spot.frame.0 + x) as usize;
        let frame = FrameRequest { size: spot.frame, ..job.request };
        for &light in &job.probe_reference {
            if light >= job.scene.lights.len() {
                continue;
            }
            let key = ReferenceKey::new(&job.scene, &frame, Some(spot.pixel), light);
            if let Some((_, value, total)) = self.probe_truths.iter().find(|(k, ..)| *k == key) {
                if !progress(light, *total, *total, *value) {
                    return Ok(());
                }
                continue;
            }
            let mut stopped = false;
            let done = self.ground_truth(&job.scene, light, &mut |done, all, values| {
                let go_on = progress(light, done, all, values.get(index).copied().unwrap_or(1.0));
                stopped |= !go_on;
                go_on
            })?;
            // Finished (even where the last report came after a newer job): keep it.
            if let Some((values, total)) = done {
                if self.probe_truths.len() >= PROBE_TRUTHS_KEPT {
                    self.probe_truths.remove(0);
                }
                self.probe_truths.push((key, values.get(index).copied().unwrap_or(1.0), total));
            }
            if stopped {
                return Ok(());
            }
        }
        Ok(())
    }

    /// Light `light`'s ground truth over the last analysis frame, batch after batch (each
    /// reported; false stops it): the values and the samples averaged, once complete.
    fn ground_truth(
        &mut self,
        scene: &Scene,
        light: usize,
        progress: &mut dyn FnMut(u32, u32, &[f32]) -> bool,
    ) -> Result<Option<(Vec<f32>, u32)>, RenderError> {
        let mut total = 0;
        let done = self.a.render_reference_progressive(
            scene,
            light,
            REFERENCE_BATCH_FIRST,
            REFERENCE_BATCH_MAX,
            &mut |done, all, values| {
                total = all;
                progress(done, all, values)
            },
        )?;
        Ok(done.map(|values| (values, total)))
    }

    /// The view's ground truth for the selected light (its analysis is drawn again where a probe
    /// rendered since), reported after every batch, or at once where nothing it depends on has
    /// changed since the last one finished.
    fn view_reference(
        &mut self,
        job: &RenderJob,
        progress: &mut dyn FnMut(u32, u32, &[f32]) -> bool,
    ) -> Result<(), RenderError> {
        let light = job.request.selected_light;
        let key = ReferenceKey::new(&job.scene, &job.request, None, light);
        if let Some((_, values, total)) = self.view_truth.as_ref().filter(|(k, ..)| *k == key) {
            progress(*total, *total, values);
            return Ok(());
        }
        if job.probe.is_some() {
            let request =
                FrameRequest { final_color: false, analysis: true, timestamps: false, ..job.request };
            self.a.render(&job.scene, &request)?;
        }
        if let Some((values, total)) = self.ground_truth(&job.scene, light, progress)? {
            self.view_truth = Some((key, values, total));
        }
        Ok(())
    }
}

impl RenderJob {
    /// The stage after the probe's: the homework check where there is one, then the view's
    /// ground truth.
    fn after_probe(&self) -> Stage {
        if self.homework.is_some() { Stage::Homework } else { Stage::ViewReference }
    }

    /// A probe or overlays to work out after the image.
    fn wants_details(&self) -> bool {
        !self.scene.lights.is_empty() && (self.probe.is_some() || self.analysis)
    }
}

/// Every `step`-th texel of a map, so that its picture is at most `limit` texels a side.
fn subsample(map: &DepthImage, limit: u32) -> DepthImage {
    let step = map.size.div_ceil(limit.max(1)).max(1);
    if step == 1 {
        return map.clone();
    }
    let size = map.size / step;
    let mut depth_ndc = Vec::with_capacity((size * size) as usize);
    for y in 0..size {
        let row = (y * step * map.size) as usize;
        depth_ndc.extend((0..size).map(|x| map.depth_ndc[row + (x * step) as usize]));
    }
    DepthImage { size, depth_ndc }
}

impl Renderers {
    /// Run `stage` of job `id`, telling `send` what it finished; returns the stage to run next.
    /// `cancelled` says a newer job is waiting (the details and ground truths are then moot).
    pub(super) fn run_stage(
        &mut self,
        id: u64,
        job: &RenderJob,
        stage: Stage,
        started: Instant,
        send: &mut dyn FnMut(RenderEvent),
        cancelled: &dyn Fn() -> bool,
    ) -> Stage {
        let failed = |send: &mut dyn FnMut(RenderEvent), e: RenderError| {
            send(RenderEvent::Failed { job: id, message: e.to_string() });
            Stage::Done
        };
        match stage {
            Stage::Image => {
                let maps = self.image(id, job).and_then(|output| {
                    send(RenderEvent::Frame(Box::new(output)));
                    self.maps(id, job)
                });
                match maps {
                    Ok(maps) => send(RenderEvent::Maps(Box::new(maps))),
                    Err(e) => {
                        // The views may not have what was last read back: read it all next time.
                        self.last_map = None;
                        return failed(send, e);
                    }
                }
                if job.wants_details() { Stage::Details } else { job.after_probe() }
            }
            Stage::Details => {
                // A newer request makes these details moot: it brings its own.
                if cancelled() {
                    return Stage::Done;
                }
                match self.details(job) {
                    Ok((probe, analysis)) => {
                        let probe_hit = matches!(&probe, Some(Ok(report)) if report.hit);
                        send(RenderEvent::Details(Box::new(Details {
                            job: id,
                            probe,
                            analysis,
                            render_ms: started.elapsed().as_secs_f64() * 1e3,
                        })));
                        if probe_hit && !job.probe_reference.is_empty() {
                            Stage::ProbeReference
                        } else {
                            job.after_probe()
                        }
                    }
                    Err(e) => failed(send, e),
                }
            }
            // It starts from the probe's own frame, which the probe has just rendered.
            Stage::ProbeReference => {
                if cancelled() {
                    return Stage::Done;
                }
                let result = self.probe_reference(job, &mut |light, done, total, value| {
                    send(RenderEvent::ProbeReference { job: id, light, done, total, value });
                    !cancelled()
                });
                match result {
                    Ok(()) => job.after_probe(),
                    Err(e) => failed(send, e),
                }
            }
            // On renderers of its own: the view's keeps its frame for the view's ground truth.
            Stage::Homework => {
                if cancelled() {
                    return Stage::Done;
                }
                if let Some(homework) = &job.homework {
                    let (size, time_s) = (job.request.size, job.request.time_s);
                    let outcome =
                        self.homework.run(&self.device, &self.queue, homework, &job.scene, size, time_s);
                    send(RenderEvent::Homework { job: id, generation: homework.generation, outcome });
                }
                Stage::ViewReference
            }
            Stage::ViewReference => {
                if !(job.reference && job.analysis) || cancelled() {
                    return Stage::Done;
                }
                let result = self.view_reference(job, &mut |done, total, values| {
                    send(RenderEvent::Reference { job: id, done, total, values: values.to_vec() });
                    !cancelled()
                });
                match result {
                    Ok(()) => Stage::Done,
                    Err(e) => failed(send, e),
                }
            }
            Stage::Done => Stage::Done,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Technique;

    #[test]
    fn the_map_key_follows_what_the_map_depends_on() {
        let path = crate::shipped_path("assets/scenes/games202.toml");
        let scene = crate::scene::load_scene(&path, &[]).expect("scene");
        let key = |scene: &Scene, time_s: f32| {
            let light = LightGpu::new(&scene.lights[0], time_s, 0, scene.lights[0].shadow_map_size);
            MapKey::new(scene, &light, time_s, 1024)
        };
        let base = key(&scene, 0.0);
        // The light's width and the filter do not change the map: no new read-back.
        let mut wider = scene.clone();
        wider.lights[0].size = crate::scene::LightSize::Width { width_world: 20.0 };
        wider.shadow.samples = 7;
        assert_eq!(key(&wider, 0.0), base);
        // Moving the light, an object, the time or the hardware bias does.
        let mut moved = scene.clone();
        moved.lights[0].position.x += 1.0;
        assert_ne!(key(&moved, 0.0), base);
        let mut shifted = scene.clone();
        shifted.objects[1].translate.y += 0.5;
        assert_ne!(key(&shifted, 0.0), base);
        assert_ne!(key(&scene, 1.0), base);
        let mut biased = scene.clone();
        biased.shadow.depth_bias_constant = 4;
        assert_ne!(key(&biased, 0.0), base);
    }

    #[test]
    fn the_ground_truths_key_follows_what_the_ground_truth_depends_on() {
        let path = crate::shipped_path("assets/scenes/contact.toml");
        let scene = crate::scene::load_scene(&path, &[]).expect("scene");
        let request = FrameRequest { size: (960, 540), ..Default::default() };
        let key = |scene: &Scene| ReferenceKey::new(scene, &request, Some((650, 200)), 0);
        let base = key(&scene);
        assert_eq!(key(&scene.clone()), base);
        // The technique's own settings do not change the ground truth: it is kept.
        let mut filtered = scene.clone();
        filtered.shadow.technique = Technique::Pcf;
        filtered.shadow.samples = 7;
        filtered.shadow.bias_mode = crate::scene::BiasMode::ReceiverPlane;
        filtered.shadow.blocker_samples = 8;
        assert_eq!(key(&filtered), base);
        // The light, the camera, an object, its mesh, the time, the pixel, the frame and the
        // samples averaged do.
        let mut wider = scene.clone();
        wider.lights[0].size = crate::scene::LightSize::Width { width_world: 8.0 };
        assert_ne!(key(&wider), base);
        let mut turned = scene.clone();
        turned.camera.position.x += 1.0;
        assert_ne!(key(&turned), base);
        let mut moved = scene.clone();
        moved.objects[1].translate.y += 0.5;
        assert_ne!(key(&moved), base);
        let mut remeshed = scene.clone();
        remeshed.objects[1].mesh = std::sync::Arc::new((*scene.objects[1].mesh).clone());
        assert_ne!(key(&remeshed), base);
        let mut more = scene.clone();
        more.shadow.reference_samples *= 2;
        assert_ne!(key(&more), base);
        let later = FrameRequest { time_s: 1.0, ..request };
        assert_ne!(ReferenceKey::new(&scene, &later, Some((650, 200)), 0), base);
        assert_ne!(ReferenceKey::new(&scene, &request, Some((651, 200)), 0), base);
        assert_ne!(ReferenceKey::new(&scene, &request, None, 0), base);
        let smaller = FrameRequest { size: (480, 270), ..request };
        assert_ne!(ReferenceKey::new(&scene, &smaller, Some((650, 200)), 0), base);
    }

    #[test]
    fn subsampling_keeps_every_nth_texel() {
        let map = DepthImage { size: 8, depth_ndc: (0..64).map(|i| i as f32).collect() };
        let small = subsample(&map, 4);
        assert_eq!(small.size, 4);
        assert_eq!(small.depth_ndc[..4], [0.0, 2.0, 4.0, 6.0]);
        assert_eq!(small.depth_ndc[4], 16.0);
        assert_eq!(subsample(&map, 8).depth_ndc, map.depth_ndc);
    }
}
