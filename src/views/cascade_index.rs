//! The cascade-index view: which of the selected light's shadow maps the lookup at each pixel
//! reads, one colour per map. A sun's cascades show as bands along the ground, the sharpest (1)
//! nearest the camera; a point light's cube faces as the parts of the room each face sees.

use super::NO_SURFACE;
use crate::i18n::{Lang, fill, tr};
use crate::render::Analysis;
use crate::shadow::{LightGpu, ShadowViewGpu, light_dir_to, view_covering};
use glam::Vec3;
use image::{Rgba, RgbaImage};

/// One colour per view, from the light's first, with its name for the legend: six hues far
/// enough apart that they stay apart when shaded (tested below).
pub const PALETTE: [([u8; 3], &str); 6] = [
    ([230, 159, 0], "orange"),
    ([86, 180, 233], "sky blue"),
    ([0, 158, 115], "green"),
    ([240, 228, 66], "yellow"),
    ([150, 90, 200], "purple"),
    ([210, 55, 55], "red"),
];

/// The brightness of a surface facing away from the light; one facing it takes the full colour.
/// Above 0 so that every colour stays recognisable.
const SHADE_MIN: f32 = 0.65;

/// Index from the light's first view of the view its lookup at pixel `i` reads; None where no
/// surface was hit.
pub fn cascade_index_at(a: &Analysis, i: usize, light: &LightGpu, views: &[ShadowViewGpu]) -> Option<usize> {
    if !a.hit(i) {
        return None;
    }
    let position = Vec3::from_slice(&a.position[i][..3]);
    Some(view_covering(light, views, position).saturating_sub(light.first_view as usize))
}

/// The colour of view `index`, darkened towards SHADE_MIN as `lit` (the cosine between the
/// surface's normal and the direction to the light) falls from 1 to 0.
pub fn index_color(index: usize, lit: f32) -> Rgba<u8> {
    let shade = SHADE_MIN + (1.0 - SHADE_MIN) * if lit.is_finite() { lit.clamp(0.0, 1.0) } else { 0.0 };
    let [r, g, b] = PALETTE[index % PALETTE.len()].0.map(|c| (f32::from(c) * shade).round() as u8);
    Rgba([r, g, b, 255])
}

/// What each of the light's views is called in the legend: its cascade, its cube face, or the
/// light's one map.
pub fn view_names(light: &LightGpu, views: &[ShadowViewGpu], lang: Lang) -> Vec<String> {
    let count = light.view_count.max(1) as usize;
    let cube = views.get(light.first_view as usize).is_some_and(|v| v.cube == 1);
    (0..count)
        .map(|k| {
            if cube {
                fill(lang, "face {}", &[&crate::probe::CUBE_FACE_NAMES[k % 6]])
            } else if count > 1 {
                fill(lang, "cascade {}", &[&(k + 1)])
            } else {
                tr(lang, "one map").to_string()
            }
        })
        .collect()
}

/// After a colour's name, and between the items of the legend's list (punctuation, not a
/// translation).
fn punctuation(lang: Lang) -> (&'static str, &'static str) {
    match lang {
        Lang::En => (": ", ", "),
        Lang::Zh => ("：", "，"),
    }
}

/// The cascade-index view of the selected light, and its legend: what the colours mean, then
/// each colour's view.
pub fn cascade_index_image(
    a: &Analysis,
    light: &LightGpu,
    views: &[ShadowViewGpu],
    lang: Lang,
) -> (RgbaImage, String) {
    let image = RgbaImage::from_fn(a.width, a.height, |x, y| {
        let i = a.index(x, y);
        let Some(index) = cascade_index_at(a, i, light, views) else { return NO_SURFACE };
        let position = Vec3::from_slice(&a.position[i][..3]);
        let normal = Vec3::from_slice(&a.normal[i][..3]).normalize_or_zero();
        index_color(index, normal.dot(light_dir_to(light, position)))
    });
    let names = view_names(light, views, lang);
    let (colon, separator) = punctuation(lang);
    let key: Vec<String> = names
        .iter()
        .enumerate()
        .map(|(k, name)| format!("{}{colon}{name}", tr(lang, PALETTE[k % PALETTE.len()].1)))
        .collect();
    let text = if names.len() > 1 {
        fill(
            lang,
            "cascade index: which of the light's {} shadow maps each pixel reads, darker where the surface turns from the light (dark grey: no surface)",
            &[&names.len()],
        )
    } else {
        tr(lang, "cascade index: the light has one shadow map, read at every pixel, darker where the surface turns from the light (dark grey: no surface)").to_string()
    };
    (image, format!("{text}\n{}", key.join(separator)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shadow::{frame_lights, view_axis_depth};

    const ASPECT: f32 = 16.0 / 9.0;
    const ATLAS_TEXELS: u32 = 1024;

    fn scene(name: &str) -> crate::scene::Scene {
        crate::scene::load_scene(&crate::shipped_path(&format!("assets/scenes/{name}")), &[]).expect("scene")
    }

    /// One row of pixels on surfaces at `points`, each lit head-on (normal towards `light`).
    fn row_at(points: &[Vec3], light: &LightGpu) -> Analysis {
        let position: Vec<[f32; 4]> = points.iter().map(|p| p.extend(1.0).to_array()).collect();
        let normal = points.iter().map(|&p| light_dir_to(light, p).extend(0.0).to_array()).collect();
        let shadow = vec![[1.0, 0.0, 0.0, 0.0]; points.len()];
        let width = points.len() as u32;
        Analysis { width, height: 1, shadow, position, normal, moments: None, bleeding: None }
    }

    fn indices(a: &Analysis, light: &LightGpu, views: &[ShadowViewGpu]) -> Vec<Option<usize>> {
        (0..a.shadow.len()).map(|i| cascade_index_at(a, i, light, views)).collect()
    }

    /// Down the avenue from the camera's feet the lookup reads cascade 1, 2, 3, then 4, never
    /// going back to a sharper one; the picture shows four colours.
    #[test]
    fn down_the_avenue_the_cascades_follow_each_other_sharpest_first() {
        let (lights, views) = frame_lights(&scene("sun_avenue.toml"), ASPECT, 0.0, ATLAS_TEXELS);
        let sun = &lights[0];
        assert_eq!(sun.view_count, 4);
        let ground: Vec<Vec3> = (0..150).map(|k| Vec3::new(0.0, 0.0, -1.0 - k as f32)).collect();
        let a = row_at(&ground, sun);
        let seen: Vec<usize> = indices(&a, sun, &views).into_iter().map(|i| i.expect("a surface")).collect();
        assert!(seen.windows(2).all(|w| w[0] <= w[1]), "{seen:?}");
        assert_eq!((seen[0], seen[seen.len() - 1]), (0, 3), "{seen:?}");
        let (image, legend) = cascade_index_image(&a, sun, &views, Lang::En);
        let mut colours: Vec<[u8; 4]> = image.pixels().map(|p| p.0).collect();
        colours.dedup();
        assert_eq!(colours.len(), 4, "{colours:?}");
        assert!(
            legend.ends_with("orange: cascade 1, sky blue: cascade 2, green: cascade 3, yellow: cascade 4")
        );
    }

    /// By interval, the index along the avenue's ground steps exactly where the point's depth
    /// along the camera's view axis passes a split: it counts the splits nearer than the point.
    /// By map, the same ground reads each cascade well past its slice's end (the map covers its
    /// slice's bounding sphere): cascade 1 out to about twice its split.
    #[test]
    fn by_interval_the_index_steps_at_the_splits_and_by_map_it_runs_past_them() {
        let load = |selection: &str| {
            let overrides = [("light.0.cascade_selection".to_string(), selection.to_string())];
            let path = crate::shipped_path("assets/scenes/sun_avenue.toml");
            crate::scene::load_scene(&path, &overrides).expect("scene")
        };
        // Every 5 cm of the ground down the middle of the avenue, 0.5 to 150 units ahead.
        let ground: Vec<Vec3> = (10..3000).map(|k| Vec3::new(0.0, 0.0, 6.0 - 0.05 * k as f32)).collect();
        for selection in ["interval", "map"] {
            let (lights, views) = frame_lights(&load(selection), ASPECT, 0.0, ATLAS_TEXELS);
            let sun = &lights[0];
            let cascades = &views[sun.first_view as usize..][..sun.view_count as usize];
            let a = row_at(&ground, sun);
            let seen: Vec<usize> =
                indices(&a, sun, &views).into_iter().map(|i| i.expect("a surface")).collect();
            let depth: Vec<f32> = ground.iter().map(|&p| view_axis_depth(&cascades[0], p)).collect();
            // The depth of the last point that reads cascade i, world units.
            let last_read = |i: usize| {
                seen.iter().zip(&depth).filter(|(s, _)| **s == i).map(|(_, d)| *d).fold(f32::NAN, f32::max)
            };
            if selection == "interval" {
                for (k, (&index, &d)) in seen.iter().zip(&depth).enumerate() {
                    let nearer = cascades[..3].iter().filter(|v| v.split_far_world <= d).count();
                    assert_eq!(index, nearer, "point {k} at depth {d}: {seen:?}");
                }
                for (i, v) in cascades[..3].iter().enumerate() {
                    let step = last_read(i);
                    assert!(step < v.split_far_world && step > v.split_far_world - 0.06, "{i}: {step}");
                }
            } else {
                // Cascade 1 ends at 13.1 and is read to about twice that; cascade 2 likewise.
                let (split_1, split_2) = (cascades[0].split_far_world, cascades[1].split_far_world);
                assert!((split_1 - 13.1).abs() < 0.1 && (split_2 - 28.9).abs() < 0.1, "{split_1} {split_2}");
                assert!(last_read(0) > 1.5 * split_1, "cascade 1 read to {}", last_read(0));
                assert!(last_read(1) > 1.5 * split_2, "cascade 2 read to {}", last_read(1));
                assert!(seen.windows(2).all(|w| w[0] <= w[1]), "{seen:?}");
            }
        }
    }

    /// Around the lamp each direction reads its own face, counted from the light's first view
    /// (here the second of the frame's views), in the order of the face names.
    #[test]
    fn around_a_point_light_each_axis_reads_its_face_from_the_lights_first_view() {
        let (lights, lamp_views) = frame_lights(&scene("point_lamp.toml"), ASPECT, 0.0, ATLAS_TEXELS);
        let mut lamp = lights[0];
        let mut views = vec![lamp_views[0]];
        views.extend(lamp_views);
        lamp.first_view += 1;
        let centre = glam::Vec4::from(lamp.position).truncate();
        let around: Vec<Vec3> = [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z]
            .iter()
            .map(|d| centre + 3.0 * *d + 0.2 * d.any_orthonormal_vector())
            .collect();
        let a = row_at(&around, &lamp);
        assert_eq!(indices(&a, &lamp, &views), (0..6).map(Some).collect::<Vec<_>>());
        let names = view_names(&lamp, &views, Lang::En);
        assert_eq!(names, ["face +X", "face -X", "face +Y", "face -Y", "face +Z", "face -Z"]);
    }

    /// A spot light and a sun without cascades have one map, and its name; in Chinese too.
    #[test]
    fn a_light_with_one_map_reads_it_everywhere() {
        for (name, light) in [("contact.toml", 0), ("games202.toml", 0), ("multi_light.toml", 1)] {
            let (lights, views) = frame_lights(&scene(name), ASPECT, 0.0, ATLAS_TEXELS);
            let l = &lights[light];
            let points: Vec<Vec3> =
                (0..20).map(|k| Vec3::new(k as f32 - 10.0, 0.0, 3.0 - k as f32)).collect();
            assert!(indices(&row_at(&points, l), l, &views).iter().all(|&i| i == Some(0)), "{name}");
            assert_eq!(view_names(l, &views, Lang::En), ["one map"], "{name}");
            assert_eq!(view_names(l, &views, Lang::Zh), ["一张图"], "{name}");
        }
        let (lights, views) = frame_lights(&scene("sun_avenue.toml"), ASPECT, 0.0, ATLAS_TEXELS);
        assert_eq!(view_names(&lights[0], &views, Lang::Zh)[0], "级联 1");
    }

    /// The six colours stay apart whatever the lighting (the darkest of one against the
    /// brightest of another); a pixel without a surface is the background.
    #[test]
    fn the_colours_stay_apart_in_light_and_shade() {
        let distance = |p: Rgba<u8>, q: Rgba<u8>| {
            (0..3).map(|c| (f32::from(p[c]) - f32::from(q[c])).powi(2)).sum::<f32>().sqrt()
        };
        for j in 0..PALETTE.len() {
            for k in 0..PALETTE.len() {
                if j != k {
                    for (lit_j, lit_k) in [(0.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
                        let d = distance(index_color(j, lit_j), index_color(k, lit_k));
                        assert!(d > 60.0, "colours {j} and {k} lit {lit_j} and {lit_k}: {d}");
                    }
                }
            }
        }
        assert_eq!(index_color(2, f32::NAN), index_color(2, -1.0));
        let (lights, views) = frame_lights(&scene("contact.toml"), ASPECT, 0.0, ATLAS_TEXELS);
        let mut a = row_at(&[Vec3::ZERO, Vec3::ONE], &lights[0]);
        a.position[1] = [0.0; 4];
        let (image, _) = cascade_index_image(&a, &lights[0], &views, Lang::En);
        assert_eq!(*image.get_pixel(1, 0), NO_SURFACE);
        assert_ne!(*image.get_pixel(0, 0), NO_SURFACE);
    }
}
