//! The pictures of one lesson step, rendered deterministically (the step's time, the scene's
//! noise seed): the camera view, the light's shadow map, the probe under one pixel and the
//! diagram inputs taken from it.

use crate::diagrams::{DiagramInputs, DiagramKind, live};
use crate::i18n::{Lang, tr};
use crate::lessons::live::{FrameValues, Namespace, Sources};
use crate::lessons::{Lesson, Step};
use crate::probe::{ProbeReport, probe};
use crate::render::{Analysis, FrameRequest, RenderError, Renderer};
use crate::scene::{Scene, Technique};
use crate::views::overlays::Overlay;
use crate::views::{self, Legend, View};
use image::RgbaImage;

pub use crate::lessons::PROBE_FRAME;

/// Everything a slide shows of a step, except its text.
pub struct StepPictures {
    /// The view in the camera panel.
    pub view: View,
    pub camera: RgbaImage,
    /// The view's legend line(s), where it prints one.
    pub camera_summary: Option<String>,
    /// The shadow map of the step's light (full resolution) and its depth range; `None` for a
    /// scene without lights.
    pub shadow_map: Option<(RgbaImage, Legend)>,
    /// The light's shadow views (the picture tiles several by `MapsLayout`) and the index of its
    /// first in the frame's.
    pub shadow_map_views: Vec<crate::shadow::ShadowViewGpu>,
    pub first_view: usize,
    pub light: usize,
    /// The probed pixel in the lesson's 960x540 frame ([`PROBE_FRAME`]), and whether the
    /// lesson chose it.
    pub probe_pixel: Option<(u32, u32)>,
    pub probe_from_lesson: bool,
    pub probe: Option<ProbeReport>,
    /// The surface under the probe, named in the slide's language (the scene's `name_zh`).
    pub probe_object: Option<String>,
    /// The numbers of the camera panel as its legend gives them (the mean error against the
    /// ground truth where the panel shows it, at the panel's size).
    pub frame: FrameValues,
    pub technique: Technique,
    pub diagram: DiagramKind,
    pub inputs: DiagramInputs,
}

impl StepPictures {
    /// What the step's live numbers are filled from: the probe and the camera panel shown.
    pub fn live(&self) -> Sources<'_> {
        Sources { probe: self.probe.as_ref(), frame: self.frame }
    }
}

/// The view shown in the camera panel: the step's, except that the shadow map has its own
/// panel (the camera panel then shows the shaded scene) and a scene without lights has only
/// the shaded view.
pub fn camera_view(step: &Step, scene: &Scene) -> View {
    // The slide's camera panel has the camera's frame; the map has a panel of its own and the
    // moments' two square panels would not fit.
    let own_frame = matches!(step.view, View::ShadowMap | View::Moments);
    if own_frame || scene.lights.is_empty() { View::Final } else { step.view }
}

/// The step's diagram; a step without one keeps the previous step's, and a lesson that names
/// none gets the one that fits its scene (several lights, then the technique).
pub fn diagram_for(lesson: &Lesson, step_index: usize, scene: &Scene) -> DiagramKind {
    let named = |i: usize| lesson.steps.get(i).and_then(|s| s.diagram);
    let earlier = (0..=step_index).rev().find_map(named);
    earlier.or_else(|| (step_index..lesson.steps.len()).find_map(named)).unwrap_or(
        if scene.lights.len() > 1 {
            DiagramKind::MultiLight
        } else {
            match scene.shadow.technique {
                Technique::None | Technique::Hard => DiagramKind::TwoPass,
                Technique::Pcf | Technique::Vsm => DiagramKind::PcfKernel,
                Technique::Pcss | Technique::Vssm => DiagramKind::PcssTriangles,
            }
        },
    )
}

/// A pixel worth probing when the lesson names none: on a soft shadow's penumbra, else on a
/// hard shadow's edge (shadowed, next to a lit pixel), else any surface — the one nearest the
/// centre of the image.
pub fn pick_probe_pixel(a: &Analysis) -> Option<(u32, u32)> {
    let (w, h) = (a.width, a.height);
    let vis = |x: u32, y: u32| {
        let i = a.index(x, y);
        a.hit(i).then(|| a.shadow[i][0])
    };
    let centre = |&(x, y): &(u32, u32)| {
        let (dx, dy) = (i64::from(x) * 2 - i64::from(w), i64::from(y) * 2 - i64::from(h));
        (dx * dx + dy * dy, y, x)
    };
    let pixels = || (0..h).flat_map(move |y| (0..w).map(move |x| (x, y)));
    let penumbra =
        pixels().filter(|&(x, y)| vis(x, y).is_some_and(|v| v > 0.05 && v < 0.95)).min_by_key(centre);
    let edge = || {
        pixels()
            .filter(|&(x, y)| {
                vis(x, y).is_some_and(|v| v < 0.5)
                    && [(1i64, 0i64), (-1, 0), (0, 1), (0, -1)].iter().any(|(dx, dy)| {
                        let (nx, ny) = (i64::from(x) + dx, i64::from(y) + dy);
                        (0..i64::from(w)).contains(&nx)
                            && (0..i64::from(h)).contains(&ny)
                            && vis(nx as u32, ny as u32).is_some_and(|v| v >= 0.5)
                    })
            })
            .min_by_key(centre)
    };
    let surface = || pixels().filter(|&(x, y)| vis(x, y).is_some()).min_by_key(centre);
    penumbra.or_else(edge).or_else(surface)
}

/// Render step `step_index` of `lesson` (whose scene, overrides applied, is `scene`) with the
/// camera view at `size`, and probe it for the diagram; overlay legends in `lang`.
pub fn render_step(
    renderer: &mut Renderer,
    lesson: &Lesson,
    step_index: usize,
    scene: &Scene,
    size: (u32, u32),
    lang: Lang,
) -> Result<StepPictures, RenderError> {
    let step = lesson.steps.get(step_index).ok_or_else(|| {
        RenderError::Usage(format!("lesson `{}` has no step {}", lesson.id, step_index + 1))
    })?;
    let time_s = step.time_s;
    let light = step.light.min(scene.lights.len().saturating_sub(1));
    let has_lights = !scene.lights.is_empty();
    // The probe works in the lesson's own 960x540 frame, so its numbers are the ones the lesson
    // text quotes (`shadowlab probe --lesson ID --step N` gives the same), whatever the slide size.
    let request = FrameRequest {
        time_s,
        size: PROBE_FRAME,
        selected_light: light,
        final_color: false,
        analysis: true,
        ..Default::default()
    };
    let (probe_pixel, probe_from_lesson) = match step.probe {
        Some([x, y]) => (Some((x.min(PROBE_FRAME.0 - 1), y.min(PROBE_FRAME.1 - 1))), true),
        None if has_lights => {
            renderer.render(scene, &request)?;
            (pick_probe_pixel(&renderer.read_analysis()?), false)
        }
        None => (None, false),
    };
    let view = camera_view(step, scene);
    // The ground truth at the probe where the slide shows it: beside the reference and error
    // views, and wherever the text quotes it.
    let with_reference = view.needs_reference() || step.quotes(Namespace::Probe, "visibility_reference");
    let report = match probe_pixel {
        Some(pixel) if has_lights => Some(probe(renderer, scene, &request, pixel, with_reference)?),
        _ => None,
    };
    let light_probe = report.as_ref().and_then(|r| r.lights.iter().find(|l| l.light == light));
    let normal = report.as_ref().and_then(|r| r.normal);
    // The slide's picture and its probe render at PROBE_FRAME's shape; the diagram fits the
    // cascades as they did.
    let aspect = PROBE_FRAME.0 as f32 / PROBE_FRAME.1 as f32;
    let inputs = live::inputs_from_scene(scene, light, time_s, light_probe, normal, aspect);

    let rendered = views::render_view_measured(renderer, scene, view, light, time_s, size, lang)?;
    let (mut camera, mut camera_summary) = (rendered.image, rendered.summary);
    // A step that checks a homework shows the student's picture, as the app does.
    if let Some(hw) = step.homework.as_ref().filter(|_| view == View::Final) {
        camera = crate::homework::homework_picture(
            renderer,
            &hw.fragment,
            hw.shadow_fragment.as_deref(),
            scene,
            size,
            time_s,
        )
        .map_err(RenderError::Usage)?;
    }
    let mut frame = FrameValues { mean_abs_error: rendered.mean_abs_error };
    // The step's overlays, as the app draws them over the view (legends in the caption).
    let overlays: Vec<Overlay> =
        step.overlays.iter().copied().filter(|&o| !views::overlays::hidden_by_view(view, o)).collect();
    let analysis_overlays: Vec<Overlay> =
        overlays.iter().copied().filter(|&o| o != Overlay::LightFrustum).collect();
    if has_lights && !analysis_overlays.is_empty() {
        let request = FrameRequest {
            time_s,
            size,
            selected_light: light,
            final_color: false,
            analysis: true,
            ..Default::default()
        };
        let rendered_frame = renderer.render(scene, &request)?;
        let mut analysis = renderer.read_analysis()?;
        if analysis_overlays.contains(&Overlay::Bleeding) {
            analysis.bleeding = views::overlays::bleeding_of_last_frame(renderer, &analysis, light)?;
        }
        let reference = if analysis_overlays.iter().any(|o| o.needs_reference()) {
            Some(renderer.render_reference(scene, light)?)
        } else {
            None
        };
        if let Some(reference) = &reference {
            frame.mean_abs_error = Some(views::mean_abs_error(&analysis, reference));
        }
        let light_view = rendered_frame.first_view_of(light).map(|(_, view)| *view);
        let (image, legends) = views::overlays::compose(
            lang,
            &analysis_overlays,
            &analysis,
            light_view.as_ref(),
            reference.as_deref(),
        );
        views::overlays::blend_onto(&mut camera, &image);
        let lines = camera_summary.into_iter().chain(legends);
        camera_summary = Some(lines.collect::<Vec<_>>().join("\n")).filter(|s| !s.is_empty());
    }
    if has_lights && overlays.contains(&Overlay::LightFrustum) {
        let shadow_views = renderer.last_frame().map(|f| f.views.clone()).unwrap_or_default();
        let aspect = size.0 as f32 / size.1.max(1) as f32;
        views::overlays::draw_light_frusta(
            &mut camera,
            &scene.camera.clip_from_world(aspect),
            &shadow_views,
            light,
        );
        let legend = tr(lang, "frusta: yellow = this light, blue = the others").to_string();
        camera_summary = Some(camera_summary.map_or(legend.clone(), |s| format!("{s}\n{legend}")));
    }
    let (shadow_map, first_view, shadow_map_views) = if has_lights {
        let (first_view, views) = renderer
            .last_frame()
            .and_then(|f| f.views_of(light).map(|(first, v)| (first, v.to_vec())))
            .ok_or_else(|| RenderError::Usage(format!("light {light} was not rendered")))?;
        let maps = renderer.read_light_maps(light)?;
        (Some(views::light_maps_image(&maps, &views)), first_view, views)
    } else {
        (None, 0, Vec::new())
    };
    Ok(StepPictures {
        view,
        camera,
        camera_summary,
        shadow_map,
        shadow_map_views,
        first_view,
        light,
        probe_pixel,
        probe_from_lesson,
        probe_object: report
            .as_ref()
            .and_then(|r| r.object.as_deref())
            .map(|name| scene.object_label(name, lang).to_string()),
        probe: report,
        frame,
        technique: scene.shadow.technique,
        diagram: diagram_for(lesson, step_index, scene),
        inputs,
    })
}
