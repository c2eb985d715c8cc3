//! Golden images per technique, compared with a tolerance. On failure `*-actual.png` and
//! `*-diff.png` are written next to the reference; `UPDATE_SNAPSHOTS=1` rewrites the references.

mod common;

use image::{Rgba, RgbaImage};
use shadowlab::render::FrameRequest;

/// A pixel "differs" past this many levels in any channel (0..255).
const PIXEL_THRESHOLD: u8 = 24;
/// At most this fraction of pixels may differ (noise patterns, rasteriser rounding).
const MAX_DIFFERING_FRACTION: f64 = 0.005;

fn check(name: &str, scene: &str, overrides: &[(&str, &str)]) {
    render_and_compare(name, common::scene(scene, overrides), 0.0);
}

fn check_at(name: &str, scene: &str, time_s: f32) {
    render_and_compare(name, common::scene(scene, &[]), time_s);
}

fn render_and_compare(name: &str, scene: shadowlab::scene::Scene, time_s: f32) {
    let (_ctx, mut renderer) = common::gpu();
    let request =
        FrameRequest { time_s, size: (320, 180), final_color: true, analysis: false, ..Default::default() };
    renderer.render(&scene, &request).expect("render");
    compare_with_golden(name, renderer.read_color().expect("read back"));
}

fn compare_with_golden(name: &str, actual: RgbaImage) {
    let golden = common::repo_path(&format!("tests/golden/{name}.png"));
    if std::env::var("UPDATE_SNAPSHOTS").is_ok_and(|v| v == "1") {
        actual.save(&golden).expect("write golden");
        return;
    }
    let expected = image::open(&golden)
        .unwrap_or_else(|e| panic!("{}: {e} (run with UPDATE_SNAPSHOTS=1 to create it)", golden.display()))
        .to_rgba8();
    assert_eq!(expected.dimensions(), actual.dimensions(), "{name}: size changed");
    let mut differing = 0usize;
    let diff = RgbaImage::from_fn(actual.width(), actual.height(), |x, y| {
        let (a, e) = (actual.get_pixel(x, y), expected.get_pixel(x, y));
        let d = (0..3).map(|c| a[c].abs_diff(e[c])).max().unwrap_or(0);
        if d > PIXEL_THRESHOLD {
            differing += 1;
            Rgba([255, 0, 255, 255])
        } else {
            let g = e[1] / 3;
            Rgba([g, g, g, 255])
        }
    });
    let fraction = differing as f64 / (actual.width() * actual.height()) as f64;
    if fraction > MAX_DIFFERING_FRACTION {
        let stem = golden.with_extension("");
        actual.save(format!("{}-actual.png", stem.display())).expect("write actual");
        diff.save(format!("{}-diff.png", stem.display())).expect("write diff");
        panic!(
            "{name}: {:.2}% of pixels differ (limit {:.2}%); see {}-diff.png",
            fraction * 100.0,
            MAX_DIFFERING_FRACTION * 100.0,
            stem.display()
        );
    }
}

#[test]
fn games202_hard() {
    check("games202_hard", "games202", &[("technique", "hard")]);
}

#[test]
fn games202_pcf() {
    check("games202_pcf", "games202", &[("technique", "pcf"), ("radius_texels", "4")]);
}

#[test]
fn games202_pcss() {
    check("games202_pcss", "games202", &[("technique", "pcss")]);
}

#[test]
fn acne_without_bias() {
    check("acne_none", "acne", &[]);
}

#[test]
fn acne_with_slope_bias() {
    check("acne_slope", "acne", &[("bias_mode", "slope"), ("bias", "0.0005"), ("slope_bias", "0.004")]);
}

#[test]
fn contact_pcss() {
    check("contact_pcss", "contact", &[]);
}

/// A lamp's six cube faces: hard shadows on the floor and both walls, and PCSS across the seam
/// the torus hangs over.
#[test]
fn point_lamp_hard_and_pcss() {
    check("point_lamp_hard", "point_lamp", &[("technique", "hard")]);
    check(
        "point_lamp_pcss",
        "point_lamp",
        &[("technique", "pcss"), ("bias_mode", "receiver_plane"), ("bias", "0.0002")],
    );
}

/// A sun's four cascades down a long avenue (sharp shadows at the camera's feet and at the far
/// posts), and the same avenue under one map, whose near shadows are blocky.
#[test]
fn sun_avenue_cascades_and_one_map() {
    check("sun_avenue_cascades", "sun_avenue", &[("technique", "pcf")]);
    check("sun_avenue_one_map", "sun_avenue", &[("technique", "pcf"), ("light.0.cascades", "1")]);
}

#[test]
fn multi_light_at_two_seconds() {
    check_at("multi_light_t2", "multi_light", 2.0);
}

/// The diagrams at fixed inputs (their defaults, and a PCSS case with a far blocker), compared
/// with references like the renders above.
fn check_diagram(
    name: &str,
    kind: shadowlab::diagrams::DiagramKind,
    inputs: &shadowlab::diagrams::DiagramInputs,
    lang: shadowlab::i18n::Lang,
) {
    let pixmap = shadowlab::diagrams::draw(kind, inputs, lang, 960, 540).expect("draw");
    let png = shadowlab::diagrams::encode_png(&pixmap).expect("encode");
    let actual = image::load_from_memory(&png).expect("decode").to_rgba8();
    compare_with_golden(name, actual);
}

#[test]
fn diagrams_at_fixed_inputs() {
    let defaults = shadowlab::diagrams::DiagramInputs::default();
    let en = shadowlab::i18n::Lang::En;
    for kind in shadowlab::diagrams::DiagramKind::ALL {
        check_diagram(&format!("diagram_{}", kind.id()), kind, &defaults, en);
    }
    let far_blocker = shadowlab::diagrams::DiagramInputs { blocker_depth_linear: Some(40.0), ..defaults };
    check_diagram(
        "diagram_pcss_far_blocker",
        shadowlab::diagrams::DiagramKind::PcssTriangles,
        &far_blocker,
        en,
    );
    let lamp = shadowlab::diagrams::DiagramInputs {
        shadow_views: shadowlab::diagrams::ShadowViewsPlot::Cube { lamp_xz: [5.0, 5.0], probe_face: Some(1) },
        ..shadowlab::diagrams::DiagramInputs::default()
    };
    check_diagram("diagram_shadow-views_cube", shadowlab::diagrams::DiagramKind::ShadowViews, &lamp, en);
}

/// The same diagrams with Chinese labels (needs a CJK font: fonts-noto-cjk).
#[test]
fn diagrams_in_chinese() {
    let defaults = shadowlab::diagrams::DiagramInputs::default();
    for kind in shadowlab::diagrams::DiagramKind::ALL {
        check_diagram(&format!("diagram_{}_zh", kind.id()), kind, &defaults, shadowlab::i18n::Lang::Zh);
    }
}

/// The albedo cache is a speed-up, not a technique: a view drawn from the cache (the camera and
/// the floor still) is the same, byte for byte, as the one drawn by sampling the textures.
#[test]
fn the_albedo_cache_changes_no_pixel() {
    let (_ctx, mut renderer) = common::gpu();
    for (name, technique) in [("games202", "pcss"), ("homework", "hard"), ("multi_light", "pcf")] {
        let scene = common::scene(name, &[("technique", technique)]);
        let request = shadowlab::render::FrameRequest { size: (480, 270), time_s: 0.5, ..Default::default() };
        let mut images = Vec::new();
        let mut from_cache = Vec::new();
        for _ in 0..3 {
            let frame = renderer.render(&scene, &request).expect("render");
            from_cache.push(frame.albedo_from_cache);
            images.push(renderer.read_color().expect("read"));
        }
        // Sampled, then the cache filled and read, then read again.
        assert_eq!(from_cache, [false, true, true], "{name}");
        let differing =
            |a: &RgbaImage, b: &RgbaImage| a.pixels().zip(b.pixels()).filter(|(p, q)| p != q).count();
        assert_eq!(differing(&images[0], &images[1]), 0, "{name}: filling the cache changed the picture");
        assert_eq!(differing(&images[0], &images[2]), 0, "{name}: reading the cache changed the picture");
        // A moved camera samples again (and a still one refills the cache on its second frame).
        let mut moved = scene.clone();
        moved.camera.position += glam::Vec3::new(1.0, 0.0, 0.0);
        assert!(!renderer.render(&moved, &request).expect("render").albedo_from_cache, "{name}");
        assert!(renderer.render(&moved, &request).expect("render").albedo_from_cache, "{name}");
    }
}

/// The shadow maps are kept from one frame to the next exactly while nothing they depend on
/// changes, and a frame drawn with kept maps is the one a fresh renderer draws.
#[test]
fn shadow_maps_are_kept_only_while_nothing_they_depend_on_changes() {
    let (_ctx, mut renderer) = common::gpu();
    let (_ctx2, mut fresh) = common::gpu();
    let request = shadowlab::render::FrameRequest { size: (320, 180), ..Default::default() };
    let base = common::scene("multi_light", &[("technique", "pcss")]);
    let mut kept = |scene: &shadowlab::scene::Scene, time_s: f32| {
        let request = shadowlab::render::FrameRequest { time_s, ..request };
        let frame = renderer.render(scene, &request).expect("render");
        let image = renderer.read_color().expect("read");
        fresh.render(scene, &request).expect("render");
        assert_eq!(image, fresh.read_color().expect("read"), "kept maps changed the picture");
        frame.shadow_maps_kept
    };
    assert!(!kept(&base, 1.0), "the first frame draws its maps");
    assert!(kept(&base, 1.0), "an unchanged frame keeps them");
    // Camera-pass settings leave the maps alone.
    let mut filter = base.clone();
    filter.shadow.technique = shadowlab::scene::Technique::Pcf;
    filter.shadow.radius_texels = 6.0;
    assert!(kept(&filter, 1.0));
    // What the maps hold: a light, a map size, hardware bias, culling, the time (orbits, spins).
    let mut moved = filter.clone();
    moved.lights[0].position.x += 5.0;
    assert!(!kept(&moved, 1.0), "a moved light");
    let mut smaller = moved.clone();
    smaller.lights[1].shadow_map_size = 512;
    assert!(!kept(&smaller, 1.0), "a smaller map");
    let mut biased = smaller.clone();
    biased.shadow.depth_bias_constant = 8;
    assert!(!kept(&biased, 1.0), "hardware bias");
    let mut culled = biased.clone();
    culled.shadow.cull_front_faces = !culled.shadow.cull_front_faces;
    assert!(!kept(&culled, 1.0), "face culling");
    assert!(!kept(&culled, 2.0), "a later time");
    assert!(kept(&culled, 2.0));
}

/// A frame that wants its picture and its analysis draws both in one pass: the same colour as
/// the picture alone, the same floats as the analysis alone.
#[test]
fn one_pass_for_picture_and_analysis_gives_what_two_passes_give() {
    let (_ctx, mut renderer) = common::gpu();
    for (name, technique, light) in
        [("games202", "pcss", 0), ("multi_light", "pcf", 1), ("contact", "pcss", 0)]
    {
        let scene = common::scene(name, &[("technique", technique)]);
        let base =
            FrameRequest { size: (320, 180), time_s: 0.25, selected_light: light, ..Default::default() };
        let alone = |renderer: &mut shadowlab::render::Renderer, final_color, analysis| {
            renderer.render(&scene, &FrameRequest { final_color, analysis, ..base }).expect("render");
        };
        alone(&mut renderer, true, true);
        let (both_color, both_analysis) =
            (renderer.read_color().expect("read"), renderer.read_analysis().expect("read"));
        alone(&mut renderer, true, false);
        assert_eq!(both_color, renderer.read_color().expect("read"), "{name}: the colour changed");
        alone(&mut renderer, false, true);
        let analysis = renderer.read_analysis().expect("read");
        assert_eq!(format!("{both_analysis:?}"), format!("{analysis:?}"), "{name}: the analysis changed");
    }
}

/// Hard shadows and `none` skip the depth pre-pass (their one pass keeps the nearest fragment
/// itself). Each pixel is still the pre-pass's: a one-pixel render, which keeps the pre-pass,
/// gives the same colour at a grid of pixels over bunnies, floor and their edges.
#[test]
fn without_the_pre_pass_every_pixel_is_the_pre_pass_pixel() {
    let (_ctx, mut renderer) = common::gpu();
    for (name, technique) in [("homework", "hard"), ("games202", "none"), ("multi_light", "hard")] {
        let scene = common::scene(name, &[("technique", technique)]);
        let request = FrameRequest { size: (320, 180), time_s: 0.5, ..Default::default() };
        renderer.render(&scene, &request).expect("render");
        let whole = renderer.read_color().expect("read");
        for y in (3..180).step_by(11) {
            for x in (2..320).step_by(13) {
                renderer
                    .render(&scene, &FrameRequest { only_pixel: Some((x, y)), ..request })
                    .expect("render");
                let one = renderer.read_color().expect("read");
                assert_eq!(whole.get_pixel(x, y), one.get_pixel(x, y), "{name} {technique} at {x},{y}");
            }
        }
    }
}

/// The text stack on its own: a paragraph in each language broken to a column by the Unicode
/// rules, with maths symbols from the fallback font and a bold heading, drawn by the diagrams'
/// canvas as the slides draw their text.
#[test]
fn text_paragraphs_in_both_languages() {
    use shadowlab::diagrams::Canvas;
    use shadowlab::i18n::Lang;
    let ink = tiny_skia::Color::from_rgba8(20, 24, 28, 255);
    let paper = tiny_skia::Color::from_rgba8(250, 250, 246, 255);
    let mut c = Canvas::in_pixels(tiny_skia::Pixmap::new(640, 200).expect("pixmap"), Lang::Zh, paper);
    let columns = [
        (
            20.0,
            "PCSS, step 2",
            "The blocker search looks in the cone from the receiver to the light: \
             w_search = w_light · (d_r − near) / d_r ≈ 2.6 world units, 94.6 texels.",
        ),
        (
            330.0,
            "PCSS：第二步",
            "遮挡物搜索只看「接收点到光源」的锥体（search cone）里：\
             w_search = w_light · (d_r − near) / d_r ≈ 2.6 世界单位，即 94.6 个纹素。",
        ),
    ];
    for (x, heading, body) in columns {
        c.text_run(heading, [x, 40.0], 24.0, ink, true);
        for (i, line) in c.wrap(body, 18.0, 290.0).iter().enumerate() {
            assert!(c.text_width(line, 18.0) <= 290.0, "{line}");
            c.text_run(line, [x, 80.0 + 29.0 * i as f32], 18.0, ink, false);
        }
    }
    let png = shadowlab::diagrams::encode_png(&c.pixmap).expect("encode");
    compare_with_golden("text_paragraphs", image::load_from_memory(&png).expect("decode").to_rgba8());
}
