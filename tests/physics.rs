//! Physics checks: the soft-shadow techniques against the similar-triangle formula, their
//! limits against the hard shadow, and the ground truth's convergence.

mod common;

use shadowlab::render::{Analysis, FrameRequest, Renderer};
use shadowlab::scene::Scene;

fn visibility(renderer: &mut Renderer, scene: &Scene, size: (u32, u32)) -> Analysis {
    renderer.render(scene, &common::analysis_request(size, 0)).expect("render");
    renderer.read_analysis().expect("analysis")
}

fn max_visibility_difference(a: &Analysis, b: &Analysis) -> f32 {
    a.shadow.iter().zip(&b.shadow).map(|(x, y)| (x[0] - y[0]).abs()).fold(0.0, f32::max)
}

#[test]
fn pcss_with_light_size_zero_equals_the_hard_shadow() {
    let (_ctx, mut renderer) = common::gpu();
    let hard = visibility(
        &mut renderer,
        &common::scene("games202", &[("technique", "hard"), ("light.0.width", "0")]),
        (320, 180),
    );
    let pcss = visibility(
        &mut renderer,
        &common::scene("games202", &[("technique", "pcss"), ("light.0.width", "0")]),
        (320, 180),
    );
    assert!(hard.shadow.iter().any(|s| s[0] < 0.5), "the hard shadow has no shadow in it");
    assert_eq!(max_visibility_difference(&hard, &pcss), 0.0);
}

#[test]
fn pcf_with_radius_zero_equals_the_hard_shadow() {
    let (_ctx, mut renderer) = common::gpu();
    let hard = visibility(&mut renderer, &common::scene("games202", &[("technique", "hard")]), (320, 180));
    for kernel in ["poisson", "uniform", "vogel", "grid"] {
        let pcf = visibility(
            &mut renderer,
            &common::scene(
                "games202",
                &[("technique", "pcf"), ("radius_texels", "0"), ("pcf_kernel", kernel)],
            ),
            (320, 180),
        );
        assert_eq!(max_visibility_difference(&hard, &pcf), 0.0, "kernel {kernel}");
    }
}

fn mean_abs(a: &[f32], b: &[f32]) -> f64 {
    a.iter().zip(b).map(|(x, y)| f64::from((x - y).abs())).sum::<f64>() / a.len() as f64
}

#[test]
fn the_ground_truth_reads_only_the_settings_its_key_names() {
    // The app keeps a ground truth while only settings it does not read change
    // (`reference::settings_read`): every one of them changed here must leave it bit for bit.
    let (_ctx, mut renderer) = common::gpu();
    let truth = |renderer: &mut Renderer, overrides: &[(&str, &str)]| {
        let mut all = vec![("reference_samples", "16"), ("light.0.shadow_map_size", "1024")];
        all.extend_from_slice(overrides);
        let scene = common::scene("contact", &all);
        renderer.render(&scene, &common::analysis_request((240, 136), 0)).expect("render");
        (
            shadowlab::reference::settings_read(&scene.shadow),
            renderer.render_reference(&scene, 0).expect("truth"),
        )
    };
    let (read, base) = truth(&mut renderer, &[]);
    let others: [&[(&str, &str)]; 4] = [
        &[("technique", "pcf"), ("samples", "7"), ("radius_texels", "9"), ("pcf_kernel", "grid")],
        &[
            ("bias_mode", "receiver_plane"),
            ("bias", "0.0001"),
            ("slope_bias", "0.05"),
            ("depth_bias_constant", "4"),
        ],
        &[
            ("technique", "vssm"),
            ("vsm_bleed_reduction", "0.4"),
            ("blocker_samples", "8"),
            ("cull_front_faces", "true"),
        ],
        &[
            ("search_radius_scale", "2"),
            ("min_filter_radius_texels", "4"),
            ("noise_seed", "7"),
            ("rotate_per_pixel", "false"),
        ],
    ];
    for overrides in others {
        let (read_here, values) = truth(&mut renderer, overrides);
        assert_eq!(read_here, read, "{overrides:?}: the key should not change");
        assert!(values == base, "{overrides:?}: the ground truth changed");
    }
    // What it does read changes it.
    let (read_here, values) = truth(&mut renderer, &[("light.0.width", "8")]);
    assert_eq!(read_here, read);
    assert!(values != base, "a wider light should change the ground truth");
}

#[test]
fn the_reference_converges_as_samples_grow() {
    let (_ctx, mut renderer) = common::gpu();
    let reference = |renderer: &mut Renderer, samples: &str| {
        let scene =
            common::scene("contact", &[("reference_samples", samples), ("light.0.shadow_map_size", "1024")]);
        renderer.render(&scene, &common::analysis_request((240, 136), 0)).expect("render");
        renderer.render_reference(&scene, 0).expect("reference")
    };
    let truth = reference(&mut renderer, "1024");
    let errors: Vec<f64> =
        ["4", "16", "64", "256"].iter().map(|n| mean_abs(&reference(&mut renderer, n), &truth)).collect();
    eprintln!("mean |reference_N - reference_1024| for N = 4, 16, 64, 256: {errors:?}");
    for pair in errors.windows(2) {
        assert!(pair[1] < pair[0], "error did not fall: {errors:?}");
    }
    assert!(errors[3] < 0.25 * errors[0], "256 samples should be far closer than 4: {errors:?}");
}

#[test]
fn the_progressive_reference_reports_each_batch_and_ends_where_the_whole_one_does() {
    let (_ctx, mut renderer) = common::gpu();
    let scene =
        common::scene("contact", &[("reference_samples", "100"), ("light.0.shadow_map_size", "1024")]);
    renderer.render(&scene, &common::analysis_request((160, 90), 0)).expect("render");
    let whole = renderer.render_reference(&scene, 0).expect("reference");
    let mut reports: Vec<(u32, u32, Vec<f32>)> = Vec::new();
    let last = renderer
        .render_reference_progressive(&scene, 0, 4, 32, &mut |done, total, values| {
            reports.push((done, total, values.to_vec()));
            true
        })
        .expect("progressive reference")
        .expect("not stopped");
    let done: Vec<u32> = reports.iter().map(|r| r.0).collect();
    // Batches of 4, 8, 16, 32, then what is left.
    assert_eq!(done, [4, 12, 28, 60, 92, 100]);
    assert!(reports.iter().all(|r| r.1 == 100));
    assert_eq!(last, whole, "the finished average is the one-shot ground truth");
    assert_eq!(reports.last().map(|r| &r.2), Some(&whole));
    // Partial averages are averages (in 0..1), and they approach the whole.
    let errors: Vec<f64> = reports.iter().map(|r| mean_abs(&r.2, &whole)).collect();
    assert!(reports.iter().all(|r| r.2.iter().all(|v| (0.0..=1.0).contains(v))));
    assert!(errors[3] < errors[0], "{errors:?}");
    // Stopping after the first batch ends it there.
    let mut calls = 0;
    let stopped = renderer
        .render_reference_progressive(&scene, 0, 4, 32, &mut |_, _, _| {
            calls += 1;
            false
        })
        .expect("stopped reference");
    assert!(stopped.is_none());
    assert_eq!(calls, 1);
}

/// Fraction of a unit disk's area with x below `u` (-1..1): the profile of a straight shadow
/// edge under a disk light, and under a disk filter.
fn disk_fraction(u: f64) -> f64 {
    let u = u.clamp(-1.0, 1.0);
    (u * (1.0 - u * u).sqrt() + u.asin() + std::f64::consts::FRAC_PI_2) / std::f64::consts::PI
}

/// Where the disk profile crosses `level`, in units of the disk's radius.
fn disk_crossing(level: f64) -> f64 {
    let (mut lo, mut hi) = (-1.0, 1.0);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if disk_fraction(mid) < level { lo = mid } else { hi = mid }
    }
    lo
}

/// Full penumbra width (world units) across a shadow edge parallel to x near `(x, z_edge)`,
/// seen from straight above: the 10%..90% width of the visibility profile along z, averaged
/// over columns, scaled to the full width of a disk's profile.
fn measured_penumbra(renderer: &mut Renderer, scene: Scene, x: f32, z_edge: f32, reference: bool) -> f32 {
    measured_penumbra_in(renderer, scene, x, z_edge, 2.0, reference)
}

/// The same over a window `window_world` long along z.
fn measured_penumbra_in(
    renderer: &mut Renderer,
    mut scene: Scene,
    x: f32,
    z_edge: f32,
    window_world: f32,
    reference: bool,
) -> f32 {
    scene.camera = shadowlab::scene::Camera {
        projection: shadowlab::scene::Projection::Orthographic { height_world: window_world },
        position: glam::Vec3::new(x, 60.0, z_edge),
        target: glam::Vec3::new(x, 0.0, z_edge),
        up: glam::Vec3::new(0.0, 0.0, -1.0),
        near: 1.0,
        far: 100.0,
    };
    let size = (96, 400);
    renderer
        .render(&scene, &FrameRequest { size, final_color: false, analysis: true, ..Default::default() })
        .expect("render");
    let analysis = renderer.read_analysis().expect("analysis");
    let values: Vec<f32> = if reference {
        renderer.render_reference(&scene, 0).expect("reference")
    } else {
        analysis.shadow.iter().map(|s| s[0]).collect()
    };
    // Rows run along +z (image up is -z). Average each row over the middle columns.
    let profile: Vec<(f32, f32)> = (0..size.1)
        .map(|y| {
            let row: Vec<usize> = (24..72).map(|x| analysis.index(x, y)).collect();
            let z = analysis.position[row[0]][2];
            let v = row.iter().map(|&i| values[i]).sum::<f32>() / row.len() as f32;
            (z, v)
        })
        .collect();
    let crossing = |level: f32| {
        profile.windows(2).find_map(|w| {
            let ((z0, v0), (z1, v1)) = (w[0], w[1]);
            ((v0 - level) * (v1 - level) <= 0.0 && v0 != v1)
                .then(|| z0 + (level - v0) / (v1 - v0) * (z1 - z0))
        })
    };
    let summary = || {
        format!(
            "profile z {:?}..{:?}, v {:?}",
            profile.first(),
            profile.last(),
            profile.iter().map(|p| (p.1 * 100.0).round() as i32).step_by(20).collect::<Vec<_>>()
        )
    };
    let (Some(z10), Some(z90)) = (crossing(0.1), crossing(0.9)) else {
        panic!("no 10%/90% crossing: {}", summary())
    };
    let radius_units = disk_crossing(0.9) - disk_crossing(0.1);
    ((z90 - z10).abs() as f64 * 2.0 / radius_units) as f32
}

/// The ground truth's and PCSS's penumbra widths both within 20% of the formula's.
fn assert_near_formula(case: &str, expected: f32, truth: f32, pcss: f32) {
    eprintln!("{case}: formula {expected:.3}, ground truth {truth:.3}, PCSS {pcss:.3} (world units)");
    for (what, measured) in [("ground truth", truth), ("PCSS", pcss)] {
        let ratio = measured / expected;
        assert!(
            (0.8..=1.2).contains(&ratio),
            "{case}: {what}'s penumbra {measured:.3} vs formula {expected:.3}"
        );
    }
}

#[test]
fn penumbra_grows_with_blocker_distance_as_similar_triangles_say() {
    // Light straight above the slabs, so depths along its axis are heights and the formula is
    // exact: w_penumbra = w_light * (d_receiver - d_blocker) / d_blocker.
    let overhead = [
        ("light.0.position", "[0, 40, 0]"),
        ("light.0.target", "[0, 0, 0]"),
        ("light.0.up", "[0, 0, -1]"),
        ("light.0.fov_deg", "70"),
        ("rotate_per_pixel", "false"),
        ("samples", "64"),
        ("pcf_kernel", "vogel"),
        ("reference_samples", "256"),
    ];
    let (_ctx, mut renderer) = common::gpu();
    let w_light = 4.0f32;
    let light_height = 40.0f32;
    // (slab centre x, slab mid-height, the slab's z edge away from the light's axis, whose
    // shadow falls on open floor)
    let slabs = [(-6.0f32, 3.0f32, -8.0f32), (6.0, 10.0, -8.0)];
    let mut widths = Vec::new();
    for (x, height, z_edge) in slabs {
        let d_blocker = light_height - height;
        let expected = w_light * (light_height - d_blocker) / d_blocker;
        // The edge's shadow on the floor, projected from the light's centre.
        let scale = light_height / d_blocker;
        let (shadow_x, shadow_z) = (x * scale, z_edge * scale);
        let scene = common::scene("contact", &overhead);
        let pcss = measured_penumbra(&mut renderer, scene.clone(), shadow_x, shadow_z, false);
        let truth = measured_penumbra(&mut renderer, scene, shadow_x, shadow_z, true);
        assert_near_formula(&format!("blocker at height {height}"), expected, truth, pcss);
        widths.push(pcss);
    }
    assert!(widths[1] > 3.0 * widths[0], "the higher slab's penumbra must be much wider: {widths:?}");
}

/// A spherical lamp (a point light of width 4, its six cube faces storing distances) over the
/// same slabs: the ground truth (point lights spread over the sphere so that every receiver sees
/// them evenly over its disk) and PCSS on the cube both give the similar triangles' penumbra
/// within 25%, and each other's within 25%. With the receiver-plane bias: the distance a face
/// stores is not constant over a flat floor (it grows away from the lamp's foot), so a bias that
/// does not follow the receiver lets the blocker search count the floor nearer the foot as
/// blockers, and PCSS's penumbra shrinks to about a third.
#[test]
fn a_spherical_lamps_penumbra_matches_the_ground_truth_and_similar_triangles() {
    let settings = [
        ("bias_mode", "receiver_plane"),
        ("bias", "0.0001"),
        ("rotate_per_pixel", "false"),
        ("samples", "64"),
        ("pcf_kernel", "vogel"),
        ("reference_samples", "256"),
    ];
    let (_ctx, mut renderer) = common::gpu();
    let (w_light, light_height) = (4.0f32, 40.0f32);
    let mut scene = common::scene("contact", &settings);
    let lamp = &mut scene.lights[0];
    lamp.kind = shadowlab::scene::LightKind::Point;
    lamp.position = glam::Vec3::new(0.0, light_height, 0.0);
    lamp.size = shadowlab::scene::LightSize::Width { width_world: w_light };
    // PCSS searches the cone from the receiver to the lamp cut at the near plane: as in the spot
    // light's case, a near plane just above the slabs keeps that cone to where blockers are.
    (lamp.near, lamp.far, lamp.shadow_map_size) = (20.0, 100.0, 2048);
    let slabs = [(-6.0f32, 3.0f32, -8.0f32), (6.0, 10.0, -8.0)];
    let mut results = Vec::new();
    for (x, height, z_edge) in slabs {
        let d_blocker = light_height - height;
        let expected = w_light * (light_height - d_blocker) / d_blocker;
        let scale = light_height / d_blocker;
        let (shadow_x, shadow_z) = (x * scale, z_edge * scale);
        let pcss = measured_penumbra(&mut renderer, scene.clone(), shadow_x, shadow_z, false);
        let truth = measured_penumbra(&mut renderer, scene.clone(), shadow_x, shadow_z, true);
        eprintln!(
            "lamp, blocker at height {height}: formula {expected:.3}, ground truth {truth:.3}, PCSS {pcss:.3}"
        );
        results.push((height, expected, truth, pcss));
    }
    for (height, expected, truth, pcss) in results {
        for (what, measured, against) in [
            ("ground truth", truth, expected),
            ("PCSS", pcss, expected),
            ("PCSS against the truth", pcss, truth),
        ] {
            let ratio = measured / against;
            assert!(
                (0.75..=1.25).contains(&ratio),
                "blocker at {height}: {what}: {measured:.3} vs {against:.3}"
            );
        }
    }
}

/// The same lamp off to the side, so that the high slab's far edge throws its shadow 42° off the
/// bottom face's axis, near the face's edge: there a width across the ray spans sec²(42°) = 1.8
/// times the face centre's uv radially (across this edge), and the radii at the centre's scale
/// gave a penumbra about half the truth's. The truth and PCSS against the similar triangles on
/// the floor, w_light h / (H - h) / cos(42°) (the floor tilted 42° from the ray's normal plane),
/// and PCSS against the truth, each within 25%.
#[test]
fn a_spherical_lamps_penumbra_near_a_faces_edge_matches_the_ground_truth() {
    let settings = [
        ("bias_mode", "receiver_plane"),
        ("bias", "0.0001"),
        ("rotate_per_pixel", "false"),
        ("samples", "64"),
        ("pcf_kernel", "vogel"),
        ("reference_samples", "256"),
    ];
    let (_ctx, mut renderer) = common::gpu();
    let (w_light, light_height, height) = (4.0f32, 40.0f32, 10.0f32);
    // The high slab's far edge: x 3..9 at z = -8. The lamp above x = 6, so that the edge runs
    // across the ray and the penumbra is measured along it, radially on the face.
    let (x, z_edge) = (6.0f32, -8.0f32);
    let theta = 42f32.to_radians();
    let z_lamp = z_edge + (light_height - height) * theta.tan();
    let mut scene = common::scene("contact", &settings);
    let lamp = &mut scene.lights[0];
    lamp.kind = shadowlab::scene::LightKind::Point;
    lamp.position = glam::Vec3::new(x, light_height, z_lamp);
    lamp.size = shadowlab::scene::LightSize::Width { width_world: w_light };
    (lamp.near, lamp.far, lamp.shadow_map_size) = (20.0, 100.0, 2048);
    let shadow_z = z_lamp - light_height * theta.tan();
    let expected = w_light * height / (light_height - height) / theta.cos();
    let pcss = measured_penumbra(&mut renderer, scene.clone(), x, shadow_z, false);
    let truth = measured_penumbra(&mut renderer, scene, x, shadow_z, true);
    eprintln!("lamp at 42°: formula {expected:.3}, ground truth {truth:.3}, PCSS {pcss:.3} (world units)");
    for (what, measured, against) in
        [("ground truth", truth, expected), ("PCSS", pcss, expected), ("PCSS against the truth", pcss, truth)]
    {
        let ratio = measured / against;
        assert!((0.75..=1.25).contains(&ratio), "lamp at 42°: {what}: {measured:.3} vs {against:.3}");
    }
}

/// Where a slab's far top edge (x, top, z) casts its shadow on the floor, seen from the light's
/// centre.
fn edge_shadow_on_floor(scene: &Scene, edge: glam::Vec3) -> glam::Vec3 {
    let light = &scene.lights[0];
    let ray = match light.kind {
        shadowlab::scene::LightKind::Directional { .. } => (light.target - light.position).normalize(),
        _ => (edge - light.position).normalize(),
    };
    edge + ray * (edge.y / -ray.y)
}

/// Blocker-search taps that found a blocker, summed over a patch of open floor far from any
/// shadow, seen from above (a flat receiver tilted to the light must find none).
fn blockers_on_open_floor(renderer: &mut Renderer, mut scene: Scene) -> (f32, usize) {
    scene.camera = shadowlab::scene::Camera {
        projection: shadowlab::scene::Projection::Orthographic { height_world: 4.0 },
        position: glam::Vec3::new(14.0, 60.0, 10.0),
        target: glam::Vec3::new(14.0, 0.0, 10.0),
        up: glam::Vec3::new(0.0, 0.0, -1.0),
        near: 1.0,
        far: 100.0,
    };
    renderer.render(&scene, &common::analysis_request((64, 64), 0)).expect("render");
    let analysis = renderer.read_analysis().expect("analysis");
    let found: f32 = analysis.shadow.iter().map(|s| s[3]).sum();
    (found, analysis.shadow.len())
}

/// PCSS on a floor tilted to the light: with a bias that does not grow with the kernel the
/// blocker search counts the floor itself and the filter darkens the lit side (a halo); the
/// receiver-plane bias compares each tap with the receiver's own plane at the texel it reads,
/// which gives the ground truth's penumbra for both light models.
#[test]
fn the_receiver_plane_bias_gives_pcss_the_ground_truths_penumbra_on_a_tilted_floor() {
    let (_ctx, mut renderer) = common::gpu();
    let mut report = Vec::new();
    for file in ["slab_edges_sun", "slab_edges_spot"] {
        let path = common::repo_path(&format!("tests/data/scenes/{file}.toml"));
        let adaptive = shadowlab::scene::load_scene(&path, &[]).expect("scene");
        let plane = shadowlab::scene::load_scene(
            &path,
            &[("bias_mode".into(), "receiver_plane".into()), ("bias".into(), "0.0002".into())],
        )
        .expect("scene");
        let (found_before, pixels) = blockers_on_open_floor(&mut renderer, adaptive.clone());
        let (found_after, _) = blockers_on_open_floor(&mut renderer, plane.clone());
        report.push(format!(
            "{file}: open floor, blocker taps per pixel: adaptive {:.1}, receiver plane {:.1}",
            found_before / pixels as f32,
            found_after / pixels as f32
        ));
        assert!(found_before > 0.0, "{file}: the adaptive bias should count the floor as its own blocker");
        assert_eq!(found_after, 0.0, "{file}: the receiver-plane bias must find no blocker on open floor");
        // The slabs at 5 and 10 units; their far edges (z = -8) cast the edges measured.
        for (x, top) in [(-6.0f32, 5.2f32), (6.0, 10.2)] {
            let on_floor = edge_shadow_on_floor(&plane, glam::Vec3::new(x, top, -8.0));
            let measure = |renderer: &mut Renderer, scene: &Scene, reference| {
                measured_penumbra_in(renderer, scene.clone(), on_floor.x, on_floor.z, 8.0, reference)
            };
            let truth = measure(&mut renderer, &plane, true);
            let before = measure(&mut renderer, &adaptive, false);
            let after = measure(&mut renderer, &plane, false);
            report.push(format!(
                "{file}, blocker {:.0} up: ground truth {truth:.2}, PCSS adaptive bias {before:.2} ({:+.0}%), \
                 receiver plane {after:.2} ({:+.0}%) world units",
                top - 0.2,
                (before / truth - 1.0) * 100.0,
                (after / truth - 1.0) * 100.0
            ));
            assert!(
                (0.75..=1.25).contains(&(after / truth)),
                "{file} at {top}: PCSS with the receiver-plane bias {after:.3} vs ground truth {truth:.3}\n{}",
                report.join("\n")
            );
        }
    }
    eprintln!("{}", report.join("\n"));
}

/// The angular model's similar triangles: w_penumbra = gap * 2 tan(theta / 2), the gap along
/// the light alone, for the ground truth and for PCSS (with the receiver-plane bias, so the floor
/// does not count itself). The sun is 18° off vertical, so the slab edges' shadows fall on open
/// floor; there a gap of h / cos 18° is seen stretched by 1 / cos 18° across the edge.
#[test]
fn an_angular_lights_penumbra_grows_with_the_gap_as_its_formula_says() {
    let (_ctx, mut renderer) = common::gpu();
    let path = common::repo_path("tests/data/scenes/slab_edges_sun.toml");
    let overrides: Vec<(String, String)> =
        [("light.0.angular_diameter_deg", "6"), ("bias_mode", "receiver_plane"), ("bias", "0.0002")]
            .iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect();
    let scene = shadowlab::scene::load_scene(&path, &overrides).expect("scene");
    let tan_half = (3.0f32).to_radians().tan();
    let cos_tilt = (18.0f32).to_radians().cos();
    let mut widths = Vec::new();
    for (x, top) in [(-6.0f32, 5.2f32), (6.0, 10.2)] {
        let expected = top / cos_tilt * 2.0 * tan_half / cos_tilt;
        let on_floor = edge_shadow_on_floor(&scene, glam::Vec3::new(x, top, -8.0));
        let measure = |renderer: &mut Renderer, reference| {
            measured_penumbra_in(renderer, scene.clone(), on_floor.x, on_floor.z, 4.0, reference)
        };
        let truth = measure(&mut renderer, true);
        let pcss = measure(&mut renderer, false);
        assert_near_formula(&format!("edge {top} up"), expected, truth, pcss);
        widths.push(pcss);
    }
    // About twice the gap, about twice the penumbra (no d_blocker in the angular model).
    let ratio = widths[1] / widths[0];
    assert!((1.6..=2.4).contains(&ratio), "penumbra ratio {ratio:.2} for edges 10.2 / 5.2 up: {widths:?}");
}

/// VSSM's penumbra against the ground truth on the slab edges: the blocker depth comes from the
/// moments over the search region and the filter from a mip chain, so it is looser than PCSS
/// with the receiver-plane bias; it stays within a factor 1.6 either way.
#[test]
fn vssm_penumbrae_stay_within_a_factor_of_the_ground_truth() {
    let (_ctx, mut renderer) = common::gpu();
    let mut report = Vec::new();
    for file in ["slab_edges_sun", "slab_edges_spot"] {
        let path = common::repo_path(&format!("tests/data/scenes/{file}.toml"));
        let overrides = vec![("technique".to_string(), "vssm".to_string())];
        let scene = shadowlab::scene::load_scene(&path, &overrides).expect("scene");
        for (x, top) in [(-6.0f32, 5.2f32), (6.0, 10.2)] {
            let on_floor = edge_shadow_on_floor(&scene, glam::Vec3::new(x, top, -8.0));
            let measure = |renderer: &mut Renderer, reference| {
                measured_penumbra_in(renderer, scene.clone(), on_floor.x, on_floor.z, 8.0, reference)
            };
            let truth = measure(&mut renderer, true);
            let vssm = measure(&mut renderer, false);
            report
                .push(format!("{file}, edge {top} up: ground truth {truth:.2}, VSSM {vssm:.2} world units"));
            let ratio = vssm / truth;
            assert!((1.0 / 1.6..=1.6).contains(&ratio), "{}", report.join("\n"));
        }
    }
    eprintln!("{}", report.join("\n"));
}

#[test]
fn a_directional_lights_ground_truth_tends_to_its_hard_shadow() {
    // The width is turned into the angle it subtends at the target, and the reference tilts the
    // orthographic map over it: a tiny light must give back the orthographic hard shadow.
    let (_ctx, mut renderer) = common::gpu();
    let mut errors = Vec::new();
    for width in ["0.01", "10"] {
        let scene = common::scene(
            "games202",
            &[
                ("technique", "hard"),
                ("light.0.width", width),
                ("reference_samples", "16"),
                ("bias_mode", "adaptive"),
            ],
        );
        renderer.render(&scene, &common::analysis_request((240, 136), 0)).expect("render");
        let analysis = renderer.read_analysis().expect("analysis");
        let truth = renderer.render_reference(&scene, 0).expect("reference");
        let surface: Vec<usize> = (0..analysis.shadow.len()).filter(|&i| analysis.hit(i)).collect();
        let hard: Vec<f32> = surface.iter().map(|&i| analysis.shadow[i][0]).collect();
        let truth: Vec<f32> = surface.iter().map(|&i| truth[i]).collect();
        errors.push(mean_abs(&hard, &truth));
    }
    eprintln!("mean |hard - reference| for width 0.01 and 10: {errors:?}");
    assert!(errors[0] < 0.01, "a tiny light's ground truth should be its hard shadow: {errors:?}");
    assert!(errors[1] > 3.0 * errors[0], "a wide light's ground truth should be soft: {errors:?}");
}

/// Light bleeding (Lauritzen 2007): Chebyshev's bound is exact for one occluder over a planar
/// receiver, and lets light through where a filter window holds two occluders at very different
/// depths with the receiver just behind the farther one. On bleeding.toml a wide slab 2 units up
/// lies in the shadow of a small one 14 units up: the bleeding must appear there and only there,
/// and vanish when the high slab is taken away.
#[test]
fn vsm_light_bleeding_appears_where_two_occluders_share_a_window_and_nowhere_else() {
    use glam::Vec3;
    use shadowlab::views::overlays::{BLEED_THRESHOLD, vsm_light_bleeding};
    let (_ctx, mut renderer) = common::gpu();
    let size = (480, 270);
    let bleeding_of = |renderer: &mut Renderer, scene: &Scene| {
        let frame = renderer.render(scene, &common::analysis_request(size, 0)).expect("render");
        let analysis = renderer.read_analysis().expect("analysis");
        let map = renderer.read_shadow_map(0).expect("map");
        let light = frame.light_view(0).expect("light 0");
        let bleeding = vsm_light_bleeding(&analysis, &map, &light, &frame.params);
        (analysis, map, light, frame.params, bleeding)
    };
    let both = common::scene("bleeding", &[]);
    let (analysis, map, light, params, bleeding) = bleeding_of(&mut renderer, &both);
    let twin = shadowlab::shadow::Twin::new(&light.light, &light.view, &params, &map);
    // The height of the surface a map texel stores: its light-space point taken back to the world.
    let world_from_clip = glam::Mat4::from_cols_array_2d(&light.view.clip_from_world).inverse();
    let height_of = |[x, y]: [u32; 2], z: f32| {
        let uv = (glam::Vec2::new(x as f32, y as f32) + 0.5) / light.view.map_size_texels;
        world_from_clip.project_point3(Vec3::new(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, z)).y
    };
    let mut strong = 0;
    for (i, excess) in bleeding.iter().enumerate() {
        if *excess < 0.3 {
            continue;
        }
        strong += 1;
        // Every strongly bleeding window holds texels of both slabs.
        let position = Vec3::from_slice(&analysis.position[i][..3]);
        let normal = Vec3::from_slice(&analysis.normal[i][..3]);
        let coord =
            shadowlab::shadow::light_space_lookup(&light.light, &light.view, &params, position, normal);
        let (mut high, mut wide) = (0.0, 0.0);
        twin.for_each_footprint_depth(&coord, params.radius_texels, |texel, z, w| {
            match height_of(texel, z) {
                h if (h - 14.2).abs() < 0.05 => high += w,
                h if (h - 2.2).abs() < 0.05 => wide += w,
                _ => {}
            }
        });
        // A sliver of the far occluder is enough: its distance makes the variance.
        assert!(
            high > 1e-4 && wide > 0.05,
            "pixel {i}: bleeding {excess:.2} with window shares {high:.4} (high slab), {wide:.4} (wide slab)"
        );
    }
    assert!(strong > 200, "only {strong} pixels bleed 0.3 or more");
    let max = bleeding.iter().copied().fold(0.0f32, f32::max);
    // With the high slab gone, each window holds one occluder over the floor: the bound is exact
    // but for the tilted floor's own spread of depths.
    let mut one = both.clone();
    one.objects.retain(|o| o.name != "high slab");
    let (_, _, _, _, alone) = bleeding_of(&mut renderer, &one);
    let max_alone = alone.iter().copied().fold(0.0f32, f32::max);
    let share_alone = alone.iter().filter(|e| **e >= BLEED_THRESHOLD).count() as f32 / alone.len() as f32;
    eprintln!(
        "light bleeding: max {max:.3}, {strong} pixels ≥ 0.3; one slab: max {max_alone:.3}, {:.2} % ≥ {BLEED_THRESHOLD}",
        100.0 * share_alone
    );
    assert!(max > 0.45, "the two slabs bleed only {max:.3}");
    // What is left is the floor's own spread of depths in each window (it is tilted to the light).
    assert!(max_alone < 0.15, "one slab bleeds up to {max_alone:.3}");
}

/// The bleed reduction turns every bound up to a into shadow and rescales the rest.
#[test]
fn the_bleed_reduction_darkens_the_bound_as_its_formula_says() {
    let (_ctx, mut renderer) = common::gpu();
    let plain = visibility(&mut renderer, &common::scene("bleeding", &[]), (240, 136));
    let reduced =
        visibility(&mut renderer, &common::scene("bleeding", &[("vsm_bleed_reduction", "0.4")]), (240, 136));
    let mut partial = 0;
    for (p, r) in plain.shadow.iter().zip(&reduced.shadow) {
        let expected = ((p[0] - 0.4) / 0.6).clamp(0.0, 1.0);
        assert!((r[0] - expected).abs() < 2e-5, "bound {} reduced to {}, expected {expected}", p[0], r[0]);
        partial += usize::from(p[0] > 0.05 && p[0] < 0.95);
    }
    assert!(partial > 100, "only {partial} soft pixels to check");
}
