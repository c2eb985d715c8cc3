use super::*;
use crate::i18n::Lang;
use crate::scene::Technique;
use tiny_skia::Pixmap;

const BG: [u8; 3] = [250, 250, 246];

fn render(kind: DiagramKind, inp: &DiagramInputs, w: u32, h: u32) -> Pixmap {
    draw(kind, inp, Lang::En, w, h).unwrap_or_else(|e| panic!("{} at {w}x{h}: {e}", kind.id()))
}

/// Number of cells of a `cols` x `rows` grid (below the title bar) holding pixels that differ
/// clearly from the background.
fn busy_cells(pm: &Pixmap, cols: u32, rows: u32) -> usize {
    let (w, h) = (pm.width(), pm.height());
    let top = h / 10;
    let mut count = 0;
    for cy in 0..rows {
        for cx in 0..cols {
            let (x0, x1) = (cx * w / cols, (cx + 1) * w / cols);
            let (y0, y1) = (top + cy * (h - top) / rows, top + (cy + 1) * (h - top) / rows);
            let busy = (y0..y1).flat_map(|y| (x0..x1).map(move |x| (x, y))).any(|(x, y)| {
                pm.pixel(x, y).is_some_and(|p| {
                    let d = [p.red(), p.green(), p.blue()]
                        .iter()
                        .zip(BG)
                        .map(|(a, b)| (*a as i32 - b as i32).abs())
                        .max()
                        .unwrap_or(0);
                    d > 40
                })
            });
            count += busy as usize;
        }
    }
    count
}

fn differs(a: &Pixmap, b: &Pixmap) -> usize {
    a.data().chunks(4).zip(b.data().chunks(4)).filter(|(p, q)| p != q).count()
}

fn dark_pixels(pm: &Pixmap) -> usize {
    pm.pixels().iter().filter(|p| p.red() < 128 && p.green() < 128 && p.blue() < 128).count()
}

#[test]
fn every_kind_renders_at_both_sizes_with_content_spread_out() {
    for kind in DiagramKind::ALL {
        for (w, h) in [(960, 540), (320, 180)] {
            let pm = render(kind, &DiagramInputs::default(), w, h);
            assert_eq!((pm.width(), pm.height()), (w, h));
            let busy = busy_cells(&pm, 3, 3);
            assert!(busy >= 6, "{} at {w}x{h}: only {busy} of 9 regions drawn", kind.id());
            // The title bar is dark.
            let p = pm.pixel(w - 2, 2).expect("pixel");
            assert!(p.red() < 80, "{}: no title bar", kind.id());
        }
    }
}

#[test]
fn other_aspect_ratios_keep_the_design_centred() {
    for kind in DiagramKind::ALL {
        for (w, h) in [(540, 960), (1920, 600), (1, 1), (8192, 16)] {
            let pm = render(kind, &DiagramInputs::default(), w, h);
            assert_eq!((pm.width(), pm.height()), (w, h));
        }
    }
}

#[test]
fn bad_sizes_are_errors() {
    let inp = DiagramInputs::default();
    for (w, h) in [(0, 10), (10, 0), (0, 0), (8193, 100), (100, 8193), (u32::MAX, 1)] {
        match draw(DiagramKind::TwoPass, &inp, Lang::En, w, h) {
            Err(DiagramError::InvalidSize { width_px, height_px }) => {
                assert_eq!((width_px, height_px), (w, h))
            }
            other => panic!("{w}x{h}: expected InvalidSize, got {other:?}"),
        }
    }
}

#[test]
fn ids_titles_and_round_trip() {
    let ids: Vec<&str> = DiagramKind::ALL.iter().map(|k| k.id()).collect();
    assert_eq!(
        ids,
        ["two-pass", "acne-bias", "pcf-kernel", "pcss", "multi-light", "chebyshev", "shadow-views"]
    );
    for kind in DiagramKind::ALL {
        assert_eq!(DiagramKind::from_id(kind.id()), Some(kind));
        assert!(!kind.title().is_empty());
    }
    assert_eq!(DiagramKind::from_id("nope"), None);
    assert_eq!(DiagramKind::from_id(""), None);
}

#[test]
fn defaults_are_consistent() {
    let d = DiagramInputs::default();
    assert_eq!(d.pcf_samples.len(), 16);
    assert_eq!(d.sample_blocked.len(), 16);
    let lit = d.sample_blocked.iter().filter(|b| !**b).count();
    assert!((lit as f32 / 16.0 - d.visibility).abs() < 1e-6);
    assert!(d.pcf_samples.iter().all(|s| s[0].hypot(s[1]) <= 1.0));
    assert!(d.light_width_world.is_some() != d.light_angular_diameter_deg.is_some());
    let (w, b, r) = (2.0, 100.0, 113.0);
    assert!((w * (r - b) / b - d.penumbra_width_world).abs() < 1e-6);
    assert_eq!(d.lights.len(), 2);
}

#[test]
fn pcss_changes_with_receiver_and_blocker_depth() {
    let base = DiagramInputs::default();
    let a = render(DiagramKind::PcssTriangles, &base, 960, 540);
    let mut i = base.clone();
    i.receiver_depth_linear = 200.0;
    let b = render(DiagramKind::PcssTriangles, &i, 960, 540);
    assert!(differs(&a, &b) > 1000);
    let mut i = base.clone();
    i.blocker_depth_linear = Some(110.0);
    let close = render(DiagramKind::PcssTriangles, &i, 960, 540);
    i.blocker_depth_linear = Some(30.0);
    let far = render(DiagramKind::PcssTriangles, &i, 960, 540);
    assert!(differs(&close, &far) > 1000);
    let mut i = base;
    i.light_width_world = None;
    i.light_angular_diameter_deg = Some(0.53);
    assert!(differs(&a, &render(DiagramKind::PcssTriangles, &i, 960, 540)) > 1000);
}

#[test]
fn acne_bias_changes_with_bias_map_size_and_angle() {
    let mut i = DiagramInputs { bias_ndc: 0.0, ..DiagramInputs::default() };
    let none = render(DiagramKind::AcneBias, &i, 960, 540);
    i.bias_ndc = 0.01;
    let large = render(DiagramKind::AcneBias, &i, 960, 540);
    assert!(differs(&none, &large) > 1000);
    // Acne (magenta) shows only without bias.
    let magenta =
        |pm: &Pixmap| pm.pixels().iter().filter(|p| p.red() > 170 && p.green() < 60 && p.blue() > 90).count();
    assert!(magenta(&none) > magenta(&large) + 200);
    let mut i = DiagramInputs { bias_ndc: 0.0001, ..DiagramInputs::default() };
    let m2048 = render(DiagramKind::AcneBias, &i, 960, 540);
    i.shadow_map_size_texels = 4096;
    assert!(differs(&m2048, &render(DiagramKind::AcneBias, &i, 960, 540)) > 1000);
    i.light_angle_deg = 70.0;
    assert!(differs(&m2048, &render(DiagramKind::AcneBias, &i, 960, 540)) > 1000);
}

/// With the receiver-plane bias a tiny constant is enough at any slope: no acne in the drawing
/// and a verdict that says why; the same constant without the plane is too little.
#[test]
fn acne_bias_with_the_receiver_plane_shows_no_acne_at_a_grazing_angle() {
    let magenta =
        |pm: &Pixmap| pm.pixels().iter().filter(|p| p.red() > 170 && p.green() < 60 && p.blue() > 90).count();
    let mut i = DiagramInputs { bias_ndc: 0.0001, light_angle_deg: 79.0, ..DiagramInputs::default() };
    let texts = |i: &DiagramInputs| {
        let (pm, texts) = draw_traced(DiagramKind::AcneBias, i, Lang::En, [960, 540], 0.0).expect("draw");
        (magenta(&pm), texts.into_iter().map(|(t, _)| t).collect::<Vec<_>>())
    };
    let (acne_pixels, constant) = texts(&i);
    assert!(constant.iter().any(|t| t == "too little bias:"), "{constant:?}");
    i.receiver_plane = true;
    let (plane_pixels, plane) = texts(&i);
    assert!(plane.iter().any(|t| t == "receiver plane: each point is tested"), "{plane:?}");
    assert!(plane.iter().any(|t| t == "plane at texel centre"), "{plane:?}");
    assert!(!plane.iter().any(|t| t.starts_with("acne (")), "{plane:?}");
    assert!(
        acne_pixels > plane_pixels + 200,
        "acne drawn: {acne_pixels} without, {plane_pixels} with the plane"
    );
}

/// The texel grid is drawn where the probe's lookup really lies inside its texel.
#[test]
fn the_pcf_grid_follows_the_probe_inside_its_texel() {
    let centred =
        DiagramInputs { filter_radius_texels: 2.0, search_radius_texels: 2.0, ..DiagramInputs::default() };
    let corner = DiagramInputs { probe_in_texel: [0.1, 0.9], ..centred.clone() };
    let a = render(DiagramKind::PcfKernel, &centred, 960, 540);
    let b = render(DiagramKind::PcfKernel, &corner, 960, 540);
    assert!(differs(&a, &b) > 1000, "moving the probe inside its texel must move the grid");
}

/// A perspective map's texel grows with depth: the acne diagram uses the footprint at the
/// receiver (W_near / map * d / near), not at the near plane.
#[test]
fn the_acne_diagram_uses_the_texel_at_the_receivers_depth_for_a_perspective_map() {
    let i = DiagramInputs {
        orthographic: false,
        frustum_width_world: 28.0,
        light_near: 20.0,
        receiver_depth_linear: 56.0,
        shadow_map_size_texels: 2048,
        ..DiagramInputs::default()
    };
    let (_, texts) = draw_traced(DiagramKind::AcneBias, &i, Lang::En, [960, 540], 0.0).expect("draw");
    let texts: Vec<String> = texts.into_iter().map(|(t, _)| t).collect();
    assert!(texts.iter().any(|t| t == "texel = W_near / map size · d / near"), "{texts:?}");
    // 28 / 2048 * 56 / 20 = 0.0383 world units.
    assert!(texts.iter().any(|t| t.contains("= 0.038 world")), "{texts:?}");
}

#[test]
fn pcf_blocked_flags_change_sample_colours() {
    let base = DiagramInputs::default();
    let a = render(DiagramKind::PcfKernel, &base, 960, 540);
    let mut i = base.clone();
    i.sample_blocked = vec![false; i.pcf_samples.len()];
    i.visibility = 1.0;
    let b = render(DiagramKind::PcfKernel, &i, 960, 540);
    assert!(differs(&a, &b) > 300);
    let teal =
        |pm: &Pixmap| pm.pixels().iter().filter(|p| p.red() < 30 && p.green() > 140 && p.blue() > 95).count();
    assert!(teal(&b) > teal(&a));
    let mut i = base;
    i.filter_radius_texels = 2.0;
    assert!(differs(&a, &render(DiagramKind::PcfKernel, &i, 960, 540)) > 300);
}

#[test]
fn two_pass_and_multi_light_follow_their_inputs() {
    let base = DiagramInputs::default();
    let lit = render(DiagramKind::TwoPass, &base, 960, 540);
    let mut i = base.clone();
    i.stored_depth_linear = 100.0;
    let shadowed = render(DiagramKind::TwoPass, &i, 960, 540);
    assert!(differs(&lit, &shadowed) > 1000);
    i.orthographic = false;
    assert!(differs(&shadowed, &render(DiagramKind::TwoPass, &i, 960, 540)) > 1000);
    let m = render(DiagramKind::MultiLight, &base, 960, 540);
    let mut i = base;
    i.lights[1].position_xz = [60.0, -40.0];
    assert!(differs(&m, &render(DiagramKind::MultiLight, &i, 960, 540)) > 1000);
}

fn degenerate_inputs() -> Vec<(&'static str, DiagramInputs)> {
    let d = DiagramInputs::default;
    let mut out = Vec::new();
    let mut push = |name, f: &dyn Fn(&mut DiagramInputs)| {
        let mut i = d();
        f(&mut i);
        out.push((name, i));
    };
    push("zero light width", &|i| i.light_width_world = Some(0.0));
    push("no light model", &|i| i.light_width_world = None);
    push("no blockers", &|i| i.blocker_depth_linear = None);
    push("blocker at receiver", &|i| i.blocker_depth_linear = Some(113.0));
    push("blocker behind receiver", &|i| i.blocker_depth_linear = Some(500.0));
    push("blocker at zero", &|i| i.blocker_depth_linear = Some(0.0));
    push("huge", &|i| {
        i.receiver_depth_linear = 1e30;
        i.stored_depth_linear = f32::MAX;
        i.blocker_depth_linear = Some(1e20);
        i.light_width_world = Some(1e30);
        i.frustum_width_world = 1e35;
        i.filter_radius_texels = 1e30;
        i.search_radius_texels = f32::MAX;
        i.bias_ndc = 1e30;
        i.light_far = f32::MAX;
        i.lights[0].half_width_world = 1e30;
        i.objects_xz.push(([1e30, -1e30], 1e30));
        i.camera_xz = [1e30, 1e30];
    });
    push("nan and inf", &|i| {
        i.light_angle_deg = f32::NAN;
        i.receiver_depth_linear = f32::NAN;
        i.stored_depth_linear = f32::INFINITY;
        i.blocker_depth_linear = Some(f32::NEG_INFINITY);
        i.light_angular_diameter_deg = Some(f32::NAN);
        i.bias_ndc = f32::NAN;
        i.normal_offset_texels = f32::INFINITY;
        i.filter_radius_texels = f32::NAN;
        i.pcf_samples[0] = [f32::NAN, f32::INFINITY];
        i.lights[0].position_xz = [f32::NAN, 0.0];
        i.lights[1].color_rgb = [f32::NAN, 2.0, -1.0];
    });
    push("zeros", &|i| {
        i.shadow_map_size_texels = 0;
        i.frustum_width_world = 0.0;
        i.light_near = 0.0;
        i.light_far = 0.0;
        i.receiver_depth_linear = 0.0;
        i.stored_depth_linear = 0.0;
        i.filter_radius_texels = 0.0;
        i.search_radius_texels = 0.0;
        i.lights[1].half_width_world = 0.0;
        i.lights[1].target_xz = i.lights[1].position_xz;
    });
    push("negatives", &|i| {
        i.light_angle_deg = -60.0;
        i.bias_ndc = -0.01;
        i.normal_offset_texels = -3.0;
        i.light_width_world = Some(-2.0);
        i.filter_radius_texels = -5.0;
        i.objects_xz[0].1 = -4.0;
    });
    push("grazing angles", &|i| {
        i.light_angle_deg = 90.0;
        i.orthographic = false;
        i.light_near = 1e-9;
    });
    push("empty samples", &|i| {
        i.pcf_samples.clear();
        i.sample_blocked.clear();
    });
    push("mismatched lengths", &|i| i.sample_blocked.truncate(5));
    push("more flags than samples", &|i| i.sample_blocked.extend([true; 40]));
    push("empty scene", &|i| {
        i.lights.clear();
        i.objects_xz.clear();
    });
    push("many lights", &|i| {
        let l = i.lights[1].clone();
        i.lights.extend(std::iter::repeat_n(l, 12));
    });
    out
}

#[test]
fn degenerate_inputs_render_without_panic() {
    for (name, inp) in degenerate_inputs() {
        for kind in DiagramKind::ALL {
            for (w, h) in [(960, 540), (320, 180)] {
                let pm = render(kind, &inp, w, h);
                assert!(busy_cells(&pm, 3, 3) >= 2, "{name}: {} at {w}x{h} is blank", kind.id());
                assert!(encode_png(&pm).is_ok(), "{name}: {}", kind.id());
            }
        }
    }
}

#[test]
fn depth_conversions_stay_finite() {
    for (name, inp) in degenerate_inputs() {
        for d in [0.0, 1e-9, 113.0, 1e30, f32::MAX, f32::NAN, f32::INFINITY, -5.0] {
            let vals = [ndc_from_linear(&inp, d), bias_world(&inp, d), ndc_per_world(&inp, d)];
            assert!(vals.iter().all(|v| v.is_finite()), "{name}, d = {d}: {vals:?}");
        }
    }
    let i = DiagramInputs::default();
    assert!((ndc_from_linear(&i, 0.01)).abs() < 1e-6);
    assert!((bias_world(&i, 113.0) - 0.002 * 399.99).abs() < 1e-3);
}

#[test]
fn text_draws_dark_pixels_where_it_is_drawn() {
    let tr = TextRenderer::shared();
    let mut pm = Pixmap::new(300, 60).expect("pixmap");
    pm.fill(tiny_skia::Color::WHITE);
    let m = tr.measure("d_blocker = 100.0", 20.0);
    assert!(m.width_px > 100.0 && m.width_px < 250.0, "{m:?}");
    assert!(m.height_px() > 15.0);
    let black = tiny_skia::Color::BLACK;
    let regular = TextStyle { px: 20.0, color: black, bold: false };
    tr.draw(&mut pm, "d_blocker = 100.0", 10.0, 40.0, regular);
    let dark_at = |x0: u32, x1: u32| {
        (x0..x1)
            .flat_map(|x| (15..45).map(move |y| (x, y)))
            .any(|(x, y)| pm.pixel(x, y).is_some_and(|p| p.red() < 100))
    };
    assert!(dark_at(10, 40), "no ink at the start of the label");
    assert!(!dark_at(260, 300), "ink beyond the label's width");
    assert!(dark_pixels(&pm) > 100);
    // Nothing above the ascent or left of the start.
    let stray = (0..300).any(|x| pm.pixel(x, 2).is_some_and(|p| p.red() < 200));
    assert!(!stray, "ink above the text");
    // Maths symbols come from the fallback font.
    for ch in ['≈', '×', '·', '−', '≤', 'θ', '→', 'Σ'] {
        assert!(tr.covers(ch), "no glyph for {ch}");
    }
    // Bold is heavier.
    let mut bold = Pixmap::new(300, 60).expect("pixmap");
    bold.fill(tiny_skia::Color::WHITE);
    let heavy = TextStyle { px: 20.0, color: black, bold: true };
    tr.draw(&mut bold, "d_blocker = 100.0", 10.0, 40.0, heavy);
    assert!(dark_pixels(&bold) > dark_pixels(&pm));
    // Off-canvas and non-finite positions are ignored.
    tr.draw(&mut pm, "x", -1e9, f32::NAN, regular);
    let huge = TextStyle { px: f32::INFINITY, ..regular };
    tr.draw(&mut pm, "x", 1e9, 1e9, huge);
}

#[test]
fn cjk_fallback_renders_chinese_text() {
    let Some(cjk) = system_cjk_font() else {
        panic!(
            "no CJK font found in {CJK_FONT_PATHS:?}: install the Debian package fonts-noto-cjk \
             (apt-get install -y fonts-noto-cjk) so Chinese labels can render"
        );
    };
    let primary = epaint_default_fonts::UBUNTU_LIGHT.to_vec();
    let without = TextRenderer::from_font_data(primary.clone(), vec![]).expect("font");
    assert!(!without.covers('阴'));
    let faces: Vec<(FontBytes, u32)> =
        vec![(std::sync::Arc::new(primary), 0), (cjk.bytes.clone(), cjk.face_index)];
    let tr = TextRenderer::from_faces(faces).expect("cjk font");
    assert!(tr.covers('阴') && tr.covers('a'));
    assert!(TextRenderer::shared().covers('影'), "shared renderer lacks the CJK fallback");
    let mut pm = Pixmap::new(260, 50).expect("pixmap");
    pm.fill(tiny_skia::Color::WHITE);
    let st = TextStyle { px: 26.0, color: tiny_skia::Color::BLACK, bold: false };
    tr.draw(&mut pm, "阴影贴图 PCSS", 5.0, 36.0, st);
    assert!(dark_pixels(&pm) > 150, "Chinese text drew {} dark pixels", dark_pixels(&pm));
    // The CJK glyphs take the width of full-width characters.
    assert!(tr.measure("阴影贴图", 26.0).width_px > 80.0);
}

#[test]
fn png_round_trip() {
    let pm = render(DiagramKind::PcfKernel, &DiagramInputs::default(), 320, 180);
    let png = encode_png(&pm).expect("png");
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    let img = image::load_from_memory(&png).expect("decode").to_rgba8();
    assert_eq!(img.dimensions(), (320, 180));
    let p = img.get_pixel(300, 170);
    assert_eq!(p.0[3], 255);
}

#[test]
fn writes_default_pngs_for_inspection() {
    let dir = std::env::temp_dir().join("diagrams");
    std::fs::create_dir_all(&dir).expect("mkdir");
    let save = |name: &str, kind: DiagramKind, inp: &DiagramInputs| {
        let png = encode_png(&render(kind, inp, 960, 540)).expect("png");
        std::fs::write(dir.join(format!("{name}.png")), png).expect("write");
    };
    for kind in DiagramKind::ALL {
        save(kind.id(), kind, &DiagramInputs::default());
        let (zh, _) = draw_traced(kind, &DiagramInputs::default(), Lang::Zh, [960, 540], 0.0).expect("draw");
        std::fs::write(dir.join(format!("{}_zh.png", kind.id())), encode_png(&zh).expect("png"))
            .expect("write");
    }
    let mut i = DiagramInputs { blocker_depth_linear: Some(110.0), ..DiagramInputs::default() };
    save("pcss-close", DiagramKind::PcssTriangles, &i);
    i.blocker_depth_linear = Some(30.0);
    save("pcss-far", DiagramKind::PcssTriangles, &i);
    let mut i = DiagramInputs { stored_depth_linear: 100.0, ..DiagramInputs::default() };
    save("two-pass-shadowed", DiagramKind::TwoPass, &i);
    i.bias_ndc = 0.0;
    save("acne-bias-zero", DiagramKind::AcneBias, &i);
}

#[test]
fn acne_bias_with_front_faces_culled_shows_no_acne_whatever_the_bias() {
    let magenta =
        |pm: &Pixmap| pm.pixels().iter().filter(|p| p.red() > 170 && p.green() < 60 && p.blue() > 90).count();
    let acne = DiagramInputs { bias_ndc: 0.0, ..DiagramInputs::default() };
    let culled = DiagramInputs { cull_front_faces: true, ..acne.clone() };
    let with_acne = render(DiagramKind::AcneBias, &acne, 960, 540);
    let without = render(DiagramKind::AcneBias, &culled, 960, 540);
    assert!(magenta(&with_acne) > magenta(&without) + 200, "culling must remove the acne stripes");
}

/// Input cases that reach every label a diagram can draw: verdicts, the no-blocker and
/// directional PCSS formulas, the wrapped lookup, the "beyond view" notes, many lights.
fn label_cases() -> Vec<(&'static str, DiagramInputs)> {
    let d = DiagramInputs::default;
    let mut cases = degenerate_inputs();
    cases.push(("defaults", d()));
    cases.push((
        "directional",
        DiagramInputs { light_angular_diameter_deg: Some(2.0), light_width_world: None, ..d() },
    ));
    cases.push(("shadowed", DiagramInputs { stored_depth_linear: 100.0, ..d() }));
    cases.push(("shadowed, no bias", DiagramInputs { stored_depth_linear: 100.0, bias_ndc: 0.0, ..d() }));
    cases.push(("acne", DiagramInputs { bias_ndc: 0.0, ..d() }));
    cases.push(("peter panning", DiagramInputs { bias_ndc: 0.05, ..d() }));
    cases.push(("huge offset", DiagramInputs { normal_offset_texels: 40.0, bias_ndc: 0.2, ..d() }));
    cases.push(("culled", DiagramInputs { cull_front_faces: true, ..d() }));
    cases.push(("perspective", DiagramInputs { orthographic: false, light_near: 1.0, ..d() }));
    cases.push(("outside, lit", DiagramInputs { outside_map: true, ..d() }));
    for stored in [100.0, 120.0] {
        let wrapped =
            DiagramInputs { outside_map: true, clamp_outside: false, stored_depth_linear: stored, ..d() };
        cases.push(("outside, wrapped", wrapped));
    }
    // Lesson 1, steps 3 to 5: RGBA8 rounding of the receiver's own depth; off the map without
    // the clamp; off the map and past the far plane with it.
    cases.extend(lesson_1_cases());
    let past_far = DiagramInputs {
        outside_depth: true,
        receiver_depth_linear: 450.0,
        stored_depth_linear: 400.0,
        ..d()
    };
    cases.push(("past the far plane", past_far.clone()));
    cases.push(("past the far plane, not clamped", DiagramInputs { clamp_outside: false, ..past_far }));
    cases.push(("nothing stored", DiagramInputs { stored_depth_linear: 400.0, ..d() }));
    cases.push(("behind", DiagramInputs { stored_depth_linear: 118.0, cull_front_faces: true, ..d() }));
    cases.push((
        "pcf",
        DiagramInputs { technique: Technique::Pcf, blockers_found: 0, blocker_samples: 0, ..d() },
    ));
    cases.push((
        "pcf, nothing in front",
        DiagramInputs { technique: Technique::Pcf, blocker_depth_linear: None, blockers_found: 0, ..d() },
    ));
    cases.push(("hard", DiagramInputs { technique: Technique::Hard, filter_radius_texels: 0.0, ..d() }));
    cases.push(("vssm", DiagramInputs { technique: Technique::Vssm, blocker_samples: 0, ..d() }));
    cases.push((
        "pcss, no blockers",
        DiagramInputs { blocker_depth_linear: None, blockers_found: 0, filter_radius_texels: 0.0, ..d() },
    ));
    cases.push(("shader disagrees", DiagramInputs { penumbra_width_world: 9.0, visibility: 0.9, ..d() }));
    cases.push((
        "wide filter",
        DiagramInputs { filter_radius_texels: 60.0, search_radius_texels: 90.0, ..d() },
    ));
    cases
}

/// Words of English left in a Chinese label: ASCII words of three letters or more that are not
/// symbols (`d_receiver`), units shared by both languages (NDC, UV) or technique names.
fn english_words(label: &str) -> Vec<String> {
    const SHARED: [&str; 8] = ["NDC", "UV", "uv", "PCF", "PCSS", "VSM", "VSSM", "tan"];
    label
        .split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .filter(|w| w.len() >= 3 && !w.contains('_') && w.chars().all(|c| c.is_ascii_alphabetic()))
        .filter(|w| !SHARED.contains(w))
        .map(str::to_string)
        .collect()
}

#[test]
fn every_chinese_diagram_label_is_chinese() {
    let mut english = std::collections::BTreeSet::new();
    let mut count = 0;
    for (case, inp) in label_cases() {
        for kind in DiagramKind::ALL {
            let (_, texts) = draw_traced(kind, &inp, Lang::Zh, [960, 540], 0.0).expect("draw");
            count += texts.len();
            for (t, _) in texts {
                if !english_words(&t).is_empty() {
                    english.insert(format!("{} ({case}): {t}", kind.id()));
                }
            }
        }
    }
    assert!(count > 500, "only {count} labels drawn");
    assert!(
        english.is_empty(),
        "English left in Chinese diagrams (add it to src/i18n/diagrams_zh.rs): {english:#?}"
    );
    // The check itself finds English.
    let (_, en) =
        draw_traced(DiagramKind::PcssTriangles, &DiagramInputs::default(), Lang::En, [960, 540], 0.0)
            .expect("draw");
    assert!(en.iter().any(|(t, _)| !english_words(t).is_empty()));
}

#[test]
fn chinese_diagrams_keep_the_numbers_of_the_english_ones() {
    let digits = |texts: &[(String, f32)]| -> Vec<String> {
        let mut numbers: Vec<String> = texts
            .iter()
            .flat_map(|(t, _)| {
                t.split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-'))
                    .map(str::to_string)
                    .collect::<Vec<_>>()
            })
            .filter(|w| w.chars().any(|c| c.is_ascii_digit()))
            .collect();
        numbers.sort();
        numbers
    };
    for (case, inp) in label_cases().into_iter().take(30) {
        for kind in DiagramKind::ALL {
            let en = draw_canvas(kind, &inp, Lang::En, [960, 540], 0.0).expect("draw");
            let zh = draw_canvas(kind, &inp, Lang::Zh, [960, 540], 0.0).expect("draw");
            // A label may break over more lines in one language than in the other.
            let labels = |c: &Canvas| c.drawn.len() - c.continued;
            assert_eq!(labels(&en), labels(&zh), "{} ({case}): different label count", kind.id());
            let (en, zh) = (en.drawn, zh.drawn);
            assert_eq!(digits(&en), digits(&zh), "{} ({case}): numbers differ", kind.id());
        }
    }
}

#[test]
fn on_a_small_panel_text_grows_to_the_minimum_size() {
    for kind in DiagramKind::ALL {
        // 760x256: the diagram panel of a 1600x900 window; text would be 8 px at design size.
        let (_, plain) =
            draw_traced(kind, &DiagramInputs::default(), Lang::Zh, [760, 256], 0.0).expect("draw");
        let (_, grown) =
            draw_traced(kind, &DiagramInputs::default(), Lang::Zh, [760, 256], 14.0).expect("draw");
        let smallest = |t: &[(String, f32)]| t.iter().map(|(_, px)| *px).fold(f32::INFINITY, f32::min);
        assert!(smallest(&plain) < 9.0, "{}: {}", kind.id(), smallest(&plain));
        assert!(smallest(&grown) >= 14.0, "{}: {} px", kind.id(), smallest(&grown));
        // Growth is capped: on a tiny panel text stays at most MAX_TEXT_GROWTH times its size.
        let (_, tiny) =
            draw_traced(kind, &DiagramInputs::default(), Lang::En, [320, 180], 14.0).expect("draw");
        assert!(smallest(&tiny) < 14.0 && smallest(&tiny) <= 17.0 / 3.0 * MAX_TEXT_GROWTH + 0.01);
    }
}

#[test]
fn lines_break_by_the_unicode_rules_and_fit_their_width() {
    let t = TextRenderer::shared();
    let s = "The light renders the scene like a camera, but keeps only depth: \
             for every texel, the distance to the nearest surface.";
    let lines = t.wrap(s, 20.0, 200.0);
    assert!(lines.len() > 3, "{lines:?}");
    for l in &lines {
        assert!(t.measure(l, 20.0).width_px <= 200.0 + 0.01, "{l}");
    }
    // Latin text breaks between words only: the lines join back into the text.
    assert_eq!(lines.join(" "), s);
    // A word wider than the line is cut between characters.
    let long = t.wrap("aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa", 20.0, 100.0);
    assert!(long.len() > 1 && long.iter().all(|l| t.measure(l, 20.0).width_px <= 100.01), "{long:?}");
    // Newlines start paragraphs; an empty one stays as an empty line.
    assert_eq!(t.wrap("one\n\ntwo", 20.0, 500.0), ["one", "", "two"]);

    // Chinese breaks between characters, but never before a closing mark or after an opening
    // one, and keeps Latin words and numbers whole (UAX #14).
    let zh = "阴影贴图（shadow map）很重要，偏移 0.002 太小。近处暗，远处亮。";
    let closing = "，。）、；：！？";
    for width in (30..=400).step_by(7) {
        let lines = t.wrap(zh, 20.0, width as f32);
        assert_eq!(lines.concat().replace(' ', ""), zh.replace(' ', ""), "width {width}: {lines:?}");
        for l in &lines {
            assert!(t.measure(l, 20.0).width_px <= width as f32 + 0.01, "width {width}: {lines:?}");
        }
        // Narrower than "（shadow", the rules give way to cutting between characters.
        if width < 100 {
            continue;
        }
        for (i, l) in lines.iter().enumerate() {
            let first = l.chars().next();
            assert!(i == 0 || !first.is_some_and(|c| closing.contains(c)), "width {width}: {lines:?}");
            assert!(!l.ends_with('（'), "width {width}: {lines:?}");
            for word in ["shadow", "0.002"] {
                let cut = (1..word.len()).any(|k| l.ends_with(&word[..k]) && !l.ends_with(word));
                assert!(!cut, "{word} cut at width {width}: {lines:?}");
            }
        }
        if width < 300 {
            assert!(lines.len() > 1, "width {width}: {lines:?}");
        }
    }
}

#[test]
fn chinese_text_uses_the_simplified_chinese_face_at_the_latin_em() {
    let cjk = system_cjk_font().expect("a CJK font (fonts-noto-cjk)");
    let mut db = cosmic_text::fontdb::Database::new();
    db.load_font_source(cosmic_text::fontdb::Source::Binary(cjk.bytes.clone()));
    let face = db.faces().find(|f| f.index == cjk.face_index).expect("the chosen face");
    if db.faces().count() > 1 {
        // A collection: the face for Simplified Chinese, not the first (Japanese) one.
        assert!(face.families.iter().any(|(n, _)| n.ends_with(" SC")), "{:?}", face.families);
    }
    // Full-width characters advance by one em: the fallback font is not rescaled.
    let t = TextRenderer::shared();
    let w = t.measure("阴影贴图", 20.0).width_px;
    assert!((w - 80.0).abs() < 1.0, "four ideographs at 20 px are {w} px wide");
}

/// Rows of ink (any pixel darker than mid-grey), top to bottom.
fn inked_rows(pm: &Pixmap) -> (u32, u32) {
    let rows: Vec<u32> = (0..pm.height())
        .filter(|&y| (0..pm.width()).any(|x| pm.pixel(x, y).is_some_and(|p| p.red() < 128)))
        .collect();
    (rows.first().copied().unwrap_or(0), rows.last().copied().unwrap_or(0))
}

#[test]
fn text_follows_a_fractional_baseline_down_the_page() {
    let t = TextRenderer::shared();
    let st = TextStyle { px: 20.0, color: tiny_skia::Color::BLACK, bold: false };
    let drawn_at = |baseline: f32| {
        let mut pm = Pixmap::new(200, 60).expect("pixmap");
        pm.fill(tiny_skia::Color::WHITE);
        t.draw(&mut pm, "Hx阴", 5.0, baseline, st);
        inked_rows(&pm)
    };
    let whole = drawn_at(40.0);
    // A baseline moved down by less than half a pixel stays; by more, the ink moves down one
    // row: never up.
    for (dy, rows) in [(0.25, 0), (0.45, 0), (0.55, 1), (0.75, 1), (1.0, 1), (1.75, 2)] {
        let (top, bottom) = drawn_at(40.0 + dy);
        assert_eq!((top, bottom), (whole.0 + rows, whole.1 + rows), "baseline 40 + {dy}");
    }
}

#[test]
fn paragraph_breaks_of_every_kind_and_mixed_directions_are_safe() {
    let t = TextRenderer::shared();
    assert_eq!(t.wrap("one\r\ntwo\rthree", 20.0, 500.0), ["one", "two", "three"]);
    assert_eq!(t.wrap("one\u{2029}two\u{85}three\u{2028}four", 20.0, 500.0), ["one", "two", "three", "four"]);
    assert_eq!(t.wrap("a\tb", 20.0, 500.0), ["a b"]);
    // Several bidi paragraphs of different directions in what is measured or drawn as one line.
    for s in ["a\u{2029}שלום", "Hello\u{85}مرحبا", "x\u{1C}עברית\ny", "d_r − d_b\u{2029}"] {
        let m = t.measure(s, 20.0);
        assert!(m.width_px > 0.0, "{s:?}");
        let mut pm = Pixmap::new(300, 40).expect("pixmap");
        t.draw(&mut pm, s, 2.0, 30.0, TextStyle { px: 20.0, color: tiny_skia::Color::BLACK, bold: true });
        assert!(!t.wrap(s, 20.0, 60.0).is_empty(), "{s:?}");
    }
    // The same text with a newline measures as with a space.
    let (spaced, broken) = (t.measure("near far", 20.0), t.measure("near\nfar", 20.0));
    assert!((spaced.width_px - broken.width_px).abs() < 1e-3);
}

#[test]
fn fit_cuts_to_the_width_with_an_ellipsis() {
    let pm = Pixmap::new(960, 540).expect("pixmap");
    let c = Canvas::in_pixels(pm, Lang::En, tiny_skia::Color::WHITE);
    let s = "blocker search found 20 of 32 taps";
    assert_eq!(c.fit(s, 20.0, 1000.0), s);
    for max in [40.0, 90.0, 150.0, 250.0] {
        let cut = c.fit(s, 20.0, max);
        assert!(cut.ends_with('…') && c.text_width(&cut, 20.0) <= max, "{max}: {cut}");
        let kept = cut.trim_end_matches('…');
        assert!(s.starts_with(kept), "{max}: {cut}");
        // One more character (past any spaces, which the cut drops) would not fit.
        let rest = s[kept.len()..].trim_start();
        let longer = rest.chars().next().map(|ch| format!("{}{ch}…", &s[..s.len() - rest.len()]));
        assert!(longer.is_none_or(|l| c.text_width(&l, 20.0) > max), "{max}: {cut}");
    }
    assert_eq!(c.fit("中文标题很长很长", 20.0, 50.0).chars().last(), Some('…'));
}

/// The app's diagram panel: about 1000x300 points and smaller, text at least 14 px; the
/// design size; a 16:9 panel.
const PANEL_SIZES: [([u32; 2], f32); 7] = [
    ([1000, 300], 14.0),
    ([900, 260], 14.0),
    ([760, 256], 14.0),
    ([800, 230], 14.0),
    ([640, 360], 14.0),
    ([960, 540], 0.0),
    ([1280, 720], 14.0),
];

/// Lesson 2's floor (79° from the light, a 1024 map over 80 world units, far 200) under each of
/// its bias settings, and the diagram's own cases.
fn acne_cases() -> Vec<(&'static str, DiagramInputs)> {
    let floor = DiagramInputs {
        light_angle_deg: 78.84,
        shadow_map_size_texels: 1024,
        frustum_width_world: 80.0,
        light_near: 0.01,
        light_far: 200.0,
        receiver_depth_linear: 100.0,
        bias_ndc: 0.0,
        ..DiagramInputs::default()
    };
    let mut cases = vec![
        ("no bias", floor.clone()),
        ("too much bias", DiagramInputs { bias_ndc: 0.02, ..floor.clone() }),
        ("slope bias", DiagramInputs { bias_ndc: 0.0042, light_angle_deg: 80.72, ..floor.clone() }),
        ("adaptive", DiagramInputs { bias_ndc: 0.00029, ..floor.clone() }),
        ("receiver plane", DiagramInputs { bias_ndc: 0.0001, receiver_plane: true, ..floor.clone() }),
        ("normal offset", DiagramInputs { normal_offset_texels: 1.0, ..floor.clone() }),
        ("culled", DiagramInputs { cull_front_faces: true, ..floor.clone() }),
        ("shallow", DiagramInputs { light_angle_deg: 30.0, bias_ndc: 0.0005, ..floor }),
    ];
    cases.extend(label_cases().into_iter().filter(|(name, _)| !matches!(*name, "huge" | "nan and inf")));
    cases
}

/// At the app's panel sizes the acne diagram's labels, numbers, verdict and legend keep clear
/// of each other, in both languages: grown text used to push verdict lines apart (a dangling
/// "too little bias:" with the rest at the top right), lay "acne (...)" over "contact", and
/// hide the Chinese peter-panning gap under the legend.
#[test]
fn acne_bias_text_does_not_overlap_at_panel_sizes() {
    let mut bad = Vec::new();
    // Lesson 2's cases also at every panel height from 220 to 340 points.
    let sweep: Vec<([u32; 2], f32)> =
        [900, 1000].into_iter().flat_map(|w| (220..=340).step_by(8).map(move |h| ([w, h], 14.0))).collect();
    for (i, (case, inp)) in acne_cases().into_iter().enumerate() {
        let sizes = PANEL_SIZES.iter().chain(if i < 8 { &sweep[..] } else { &[] });
        for lang in [Lang::En, Lang::Zh] {
            for &(size, min_text) in sizes.clone() {
                let c = draw_canvas(DiagramKind::AcneBias, &inp, lang, size, min_text).expect("draw");
                for o in c.overlapping_text() {
                    bad.push(format!("{case}, {}, {size:?}: {o}", lang.code()));
                }
            }
        }
    }
    assert!(bad.is_empty(), "{} overlaps:\n{}", bad.len(), bad.join("\n"));
}

/// A verdict's two lines stay together, one under the other, whatever the panel's height: at
/// some heights the first line ("too little bias:") used to end one column and the second
/// start the next, at the top right.
#[test]
fn acne_bias_verdict_lines_stay_together() {
    let verdicts = [
        ["too little bias:", "acne (self-shadowing stripes)"],
        ["more bias than needed:", "shadow detaches (peter panning)"],
    ];
    let sizes = [900, 1000].into_iter().flat_map(|w| (220..=340).step_by(8).map(move |h| [w, h]));
    for (case, inp) in acne_cases().into_iter().take(2) {
        for lang in [Lang::En, Lang::Zh] {
            for size in sizes.clone() {
                let c = draw_canvas(DiagramKind::AcneBias, &inp, lang, size, 14.0).expect("draw");
                let find = |s: &str| {
                    let s = crate::i18n::tr(lang, s);
                    c.text_boxes.iter().find(|(t, _)| t == s).map(|(_, b)| *b)
                };
                for [first, second] in verdicts {
                    if let (Some(a), Some(b)) = (find(first), find(second)) {
                        let below = b[1] > a[1] + a[3] * 0.5 && b[1] < a[1] + a[3] * 2.5;
                        assert!(
                            a[0] == b[0] && below,
                            "{case}, {}, {size:?}: {first} at {a:?}, {second} at {b:?}",
                            lang.code()
                        );
                    }
                }
            }
        }
    }
}

/// Lesson 1's light (orthographic, near 0.01) at the probes of steps 3 to 5, as the probe
/// reports them.
fn lesson_1_cases() -> Vec<(&'static str, DiagramInputs)> {
    let light = DiagramInputs {
        technique: Technique::Hard,
        light_angle_deg: 45.0,
        shadow_map_size_texels: 2048,
        light_near: 0.01,
        bias_ndc: 0.001,
        blocker_depth_linear: None,
        ..DiagramInputs::default()
    };
    vec![
        (
            // Far 200, RGBA8 storage: the floor's own depth, rounded 0.0018 NDC nearer.
            "rgba8 rounding",
            DiagramInputs {
                frustum_width_world: 120.0,
                light_far: 200.0,
                receiver_depth_linear: 107.43808,
                stored_depth_linear: 107.061165,
                stored_depth_rgba8_error_ndc: Some(-0.0018153191),
                ..light.clone()
            },
        ),
        (
            // Extent 20, far 130, no clamp: uv.x 1.30 wraps onto the bunny's ears.
            "off the map, wrapped",
            DiagramInputs {
                frustum_width_world: 40.0,
                light_far: 130.0,
                receiver_depth_linear: 125.365616,
                stored_depth_linear: 100.11788,
                outside_map: true,
                clamp_outside: false,
                blocker_depth_linear: Some(100.11788),
                ..light.clone()
            },
        ),
        (
            // The clamp on: uv.y -0.49 and NDC depth 1.18, lit without a lookup.
            "off the map and past far, clamped",
            DiagramInputs {
                frustum_width_world: 40.0,
                light_far: 130.0,
                receiver_depth_linear: 152.89879,
                stored_depth_linear: 130.0,
                outside_map: true,
                outside_depth: true,
                clamp_outside: true,
                visibility: 1.0,
                ..light
            },
        ),
    ]
}

fn texts_of(kind: DiagramKind, inp: &DiagramInputs, lang: Lang) -> Vec<String> {
    let (_, texts) = draw_traced(kind, inp, lang, [960, 540], 0.0).expect("draw");
    texts.into_iter().map(|(t, _)| t).collect()
}

/// The two-pass verdict follows what the lookup really found: the receiver's own depth
/// (rounded by RGBA8) is not a blocker, a point off the map is said to be off it, and only a
/// nearer surface is the first hit's blocker.
#[test]
fn the_two_pass_verdict_says_what_the_lookup_found() {
    let cases: std::collections::HashMap<_, _> = label_cases().into_iter().collect();
    let says = |case: &str| texts_of(DiagramKind::TwoPass, &cases[case], Lang::En).join(" | ");
    let rgba8 = says("rgba8 rounding");
    assert!(rgba8.contains("(P itself, rounded by RGBA8: -0.0018 NDC)"), "{rgba8}");
    assert!(rgba8.contains("no → in shadow (P shadows itself)"), "{rgba8}");
    assert!(!rgba8.contains("blocker)"), "{rgba8}");
    let clamped = says("off the map and past far, clamped");
    assert!(clamped.contains("P lies off the light's map and outside its depth range"), "{clamped}");
    assert!(clamped.contains("outside the light frustum → lit"), "{clamped}");
    assert!(!clamped.contains("first hit"), "{clamped}");
    let wrapped = says("off the map, wrapped");
    assert!(wrapped.contains("(wrapped: another place's texel)"), "{wrapped}");
    assert!(wrapped.contains("no → in shadow (wrapped lookup!)"), "{wrapped}");
    assert!(!wrapped.contains("first hit") && !wrapped.contains("P lies off"), "{wrapped}");
    let past_far = says("past the far plane, not clamped");
    assert!(past_far.contains("(nothing stored: far plane)"), "{past_far}");
    assert!(past_far.contains("no → in shadow (depth outside 0..1!)"), "{past_far}");
    assert!(says("past the far plane").contains("P lies outside the light's depth range (NDC depth 1.1250)"));
    assert!(says("shadowed").contains("(first hit: blocker)"));
    assert!(says("defaults").contains("(first hit: P itself)"));
    assert!(says("behind").contains("(first hit: a surface behind P)"));
    assert!(says("nothing stored").contains("(nothing stored: far plane)"));

    // The classification itself, and the point drawn lit where the clamp makes it lit.
    assert_eq!(
        two_pass::lookup(&cases["rgba8 rounding"]),
        two_pass::Lookup::Itself { rgba8_error_ndc: Some(-0.0018153191) }
    );
    assert_eq!(two_pass::lookup(&cases["off the map and past far, clamped"]), two_pass::Lookup::NotRead);
    assert_eq!(two_pass::lookup(&cases["off the map, wrapped"]), two_pass::Lookup::Wrapped);
    assert_eq!(two_pass::lookup(&cases["shadowed"]), two_pass::Lookup::Blocker);
    // Without the RGBA8 error the same stored depth would be a surface 0.38 world units nearer:
    // more than the floor's own spread over a texel (0.059 at 45°), so a blocker.
    let float = DiagramInputs { stored_depth_rgba8_error_ndc: None, ..cases["rgba8 rounding"].clone() };
    assert_eq!(two_pass::lookup(&float), two_pass::Lookup::Blocker);
    let green =
        |pm: &Pixmap| pm.pixels().iter().filter(|p| p.red() < 30 && p.green() > 140 && p.blue() > 95).count();
    let magenta =
        |pm: &Pixmap| pm.pixels().iter().filter(|p| p.red() > 170 && p.green() < 60 && p.blue() > 90).count();
    let lit = render(DiagramKind::TwoPass, &cases["off the map and past far, clamped"], 960, 540);
    let shadowed = render(DiagramKind::TwoPass, &cases["off the map, wrapped"], 960, 540);
    assert!(green(&lit) > green(&shadowed) + 100, "P is drawn lit where the clamp lights it");
    assert!(
        magenta(&shadowed) > magenta(&lit) + 50,
        "P is drawn blocked where the wrapped lookup shadows it"
    );
}

/// At the app's panel sizes (wide and short) and at the design size, the two-pass diagram's
/// labels, verdict lines and legend keep clear of each other, in both languages, for lesson 1's
/// probes and the lookups the verdict tells apart.
#[test]
fn two_pass_text_does_not_overlap_at_panel_sizes() {
    let wide = PANEL_SIZES.iter().filter(|(s, _)| s[0] * 9 > s[1] * 16 || s[0] >= 960);
    let names = [
        "defaults",
        "shadowed",
        "outside, lit",
        "outside, wrapped",
        "past the far plane",
        "nothing stored",
        "behind",
    ];
    let cases = label_cases().into_iter().filter(|(n, _)| names.contains(n)).chain(lesson_1_cases());
    let mut bad = Vec::new();
    for (case, inp) in cases {
        for lang in [Lang::En, Lang::Zh] {
            for (size, min_text) in wide.clone() {
                let c = draw_canvas(DiagramKind::TwoPass, &inp, lang, *size, *min_text).expect("draw");
                for o in c.overlapping_text() {
                    bad.push(format!("{case}, {}, {size:?}: {o}", lang.code()));
                }
            }
        }
    }
    assert!(bad.is_empty(), "{} overlaps:\n{}", bad.len(), bad.join("\n"));
}

/// The PCSS diagram says what the technique does: PCF filters every pixel with its fixed
/// radius and neither searches for blockers nor estimates a penumbra (it used to say "the
/// filter step is skipped" beside "filter radius = 3.0 texels"), hard shadows take no filter,
/// and PCSS skips its filter only where its search found no blocker.
#[test]
fn the_pcss_diagram_says_what_the_technique_does() {
    let d = DiagramInputs::default;
    let says = |inp: &DiagramInputs| texts_of(DiagramKind::PcssTriangles, inp, Lang::En);
    let pcf = |blocker| DiagramInputs {
        technique: Technique::Pcf,
        filter_radius_texels: 3.0,
        search_radius_texels: 0.0,
        blocker_depth_linear: blocker,
        blockers_found: 0,
        blocker_samples: 0,
        ..d()
    };
    for inp in [pcf(None), pcf(Some(100.0))] {
        let t = says(&inp);
        assert!(t.iter().any(|l| l == "PCF: fixed filter radius = 3.0 texels"), "{t:?}");
        assert!(t.iter().any(|l| l == "(no blocker search, no w_penumbra)"), "{t:?}");
        for absent in
            ["skipped", "search region", "search radius", "w_search", "blockers found", "no blockers"]
        {
            assert!(!t.iter().any(|l| l.contains(absent)), "{absent}: {t:?}");
        }
    }
    assert!(says(&pcf(Some(100.0))).iter().any(|l| l == "what PCSS would estimate here:"));
    let hard = says(&DiagramInputs { technique: Technique::Hard, filter_radius_texels: 0.0, ..pcf(None) });
    assert!(hard.iter().any(|l| l == "hard shadows: one depth test, no filter"), "{hard:?}");
    assert!(!hard.iter().any(|l| l.contains("filter radius")), "{hard:?}");
    let none_found = says(&DiagramInputs { blocker_depth_linear: None, blockers_found: 0, ..d() });
    assert!(none_found.iter().any(|l| l == "(the filter step is skipped)"), "{none_found:?}");
    assert!(!none_found.iter().any(|l| l.contains("filter radius")), "{none_found:?}");
    let found = says(&d());
    assert!(found.iter().any(|l| l == "filter radius = 5.0 texels"), "{found:?}");
    assert!(found.iter().any(|l| l == "search region"), "{found:?}");
    assert!(!found.iter().any(|l| l.contains("skipped")), "{found:?}");
}

/// "slope = tan(A°) = S": the tangent of the angle as printed, printed, is the slope as printed
/// (79° used to print beside 5.07, the slope of 78.84°).
#[test]
fn the_acne_slope_is_the_tangent_of_the_angle_shown() {
    let mut angle = 0.0f32;
    while angle < 89.9 {
        let inp = DiagramInputs { light_angle_deg: angle, ..DiagramInputs::default() };
        let texts = texts_of(DiagramKind::AcneBias, &inp, Lang::En);
        let line = texts.iter().find(|t| t.starts_with("slope = tan(")).expect("slope line");
        let shown = line.trim_start_matches("slope = tan(");
        let (a, s) = shown.split_once("°) = ").unwrap_or_else(|| panic!("{line}"));
        let tan_shown = format!("{:.2}", a.parse::<f64>().expect("angle").to_radians().tan());
        assert_eq!(tan_shown, s, "{angle}°: {line}");
        // And within the last printed digit of the slope the numbers use.
        let exact = f64::from(angle).to_radians().tan();
        if angle < 85.0 {
            let shown: f64 = s.parse().expect("slope");
            assert!((shown - exact).abs() <= 0.0101, "{angle}°: {line}, exact {exact}");
        }
        angle += 0.37;
    }
    let teacher = DiagramInputs { light_angle_deg: 78.84, ..DiagramInputs::default() };
    let texts = texts_of(DiagramKind::AcneBias, &teacher, Lang::En);
    assert!(texts.iter().any(|t| t == "slope = tan(78.84°) = 5.07"), "{texts:?}");
}

/// On a laptop (1280x720, 1366x768, 1280x800) with the inspector and the homework panel open, the
/// diagram gets a few hundred points: text grown to 14 px used to push the PCSS formulas' second
/// column against the edge, a strip of a letter or two a line drawn over its own text. Now no
/// column is a strip and no text overlaps, in both languages, for every diagram.
#[test]
fn no_text_column_is_a_strip_in_a_laptop_sized_panel() {
    let mut bad = Vec::new();
    let sizes = [340, 420, 520, 640].into_iter().flat_map(|w| [180, 240, 300].map(move |h| [w, h]));
    for kind in DiagramKind::ALL {
        for lang in [Lang::En, Lang::Zh] {
            for size in sizes.clone() {
                let c = draw_canvas(kind, &DiagramInputs::default(), lang, size, 14.0).expect("draw");
                if c.cramped {
                    bad.push(format!("{kind:?}, {}, {size:?}: a text column is a strip", lang.code()));
                }
                for o in c.overlapping_text() {
                    bad.push(format!("{kind:?}, {}, {size:?}: {o}", lang.code()));
                }
            }
        }
    }
    assert!(bad.is_empty(), "{} problems:\n{}", bad.len(), bad.join("\n"));
}
