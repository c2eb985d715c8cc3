//! The slide's probe panel: where the step's probe landed and its numbers, as the lesson quotes
//! them (one decimal for depths, four for a bias).

use super::*;

pub(super) fn probe_panel(p: &mut Canvas, layout: &SlideLayout, pictures: &StepPictures) {
    let technique = pictures.technique;
    let lang = p.lang;
    let u = |v: f32| layout.px(v);
    let r = layout.probe;
    p.fill_rgb([r.x as f32, r.y as f32, r.w as f32, r.h as f32], pal::PANEL);
    p.frame(r, pal::FRAME, u(2.0));
    let pad = u(18.0);
    let head = u(26.0);
    let mut y = r.y as f32 + pad + head;
    p.marker([r.x as f32 + pad + u(10.0), y - head * 0.35], u(12.0));
    let title = tr(lang, "Probe");
    p.run(title, r.x as f32 + pad + u(30.0), y, head, pal::INK, true);
    let technique_name = match technique {
        Technique::None => tr(lang, "no shadows"),
        Technique::Hard => tr(lang, "hard shadows"),
        Technique::Pcf => "PCF",
        Technique::Pcss => "PCSS",
        Technique::Vsm => "VSM",
        Technique::Vssm => "VSSM",
    };
    let tx = r.x as f32 + pad + u(30.0) + p.text_width(title, head) + u(14.0);
    let tech = p.fit_label(technique_name, u(22.0), r.right() - pad - tx);
    p.run(&tech, tx, y, u(22.0), pal::MUTED, false);

    let mut rows: Vec<(&str, String)> = Vec::new();
    let report = pictures.probe.as_ref();
    let light = report.and_then(|rep| rep.lights.iter().find(|l| l.light == pictures.light));
    match (pictures.probe_pixel, report, light) {
        (None, _, _) => rows.push(("", tr(lang, "nothing to probe").into())),
        (Some(_), Some(rep), _) if !rep.hit => rows.push(("", tr(lang, "no surface under the probe").into())),
        (Some((x, y)), Some(_), Some(l)) => {
            let source = match pictures.probe_from_lesson {
                true => tr(lang, " (lesson)"),
                false => tr(lang, " (auto)"),
            };
            rows.push((tr(lang, "pixel"), format!("{x}, {y}{source}")));
            if let Some(object) = &pictures.probe_object {
                rows.push((tr(lang, "surface"), object.clone()));
            }
            let [mu, mv] = l.shadow_map_uv;
            rows.push((tr(lang, "map uv"), format!("{mu:.3}, {mv:.3}")));
            let angle = l.n_dot_l.clamp(-1.0, 1.0).acos().to_degrees();
            rows.push((tr(lang, "light angle"), format!("{angle:.0}°  (N·L {:.2})", l.n_dot_l)));
            let depth = |linear: f32, ndc: f32| format!("{}  (NDC {ndc:.4})", depth_num(linear));
            rows.push((tr(lang, "receiver depth"), depth(l.receiver_depth_linear, l.receiver_depth_ndc)));
            rows.push((tr(lang, "stored depth@slides"), depth(l.stored_depth_linear, l.stored_depth_ndc)));
            rows.push((tr(lang, "bias"), format!("{} NDC", bias_num(l.bias_ndc))));
            let texels = tr(lang, "texels");
            match technique {
                Technique::None | Technique::Hard => {}
                Technique::Pcf => {
                    rows.push((
                        tr(lang, "filter radius"),
                        format!("{} {texels}", short_num(l.filter_radius_texels)),
                    ));
                    rows.push((tr(lang, "samples"), l.filter_samples.to_string()));
                }
                Technique::Vsm => {
                    rows.push((
                        tr(lang, "filter radius"),
                        format!("{} {texels}", short_num(l.filter_radius_texels)),
                    ));
                    if let Some(v) = &l.vsm {
                        rows.push((
                            tr(lang, "bound / true"),
                            format!("{:.3} / {:.3}", v.chebyshev_bound, v.true_lit_fraction),
                        ));
                    }
                }
                Technique::Pcss | Technique::Vssm => {
                    // VSSM estimates its blockers from the moments: there is no count.
                    if technique == Technique::Pcss {
                        rows.push((
                            tr(lang, "blockers@slides"),
                            format!("{} / {}", l.blockers_found, l.blocker_samples),
                        ));
                    }
                    if let Some(d) = l.avg_blocker_depth_linear {
                        rows.push((tr(lang, "blocker depth"), depth_num(d)));
                    }
                    rows.push((tr(lang, "penumbra"), short_num(l.penumbra_width_world)));
                    rows.push((
                        tr(lang, "filter radius"),
                        format!("{} {texels}", short_num(l.filter_radius_texels)),
                    ));
                }
            }
            let mut vis = format!("{:.2}", l.visibility_twin);
            if let Some(t) = l.visibility_reference {
                vis += &fill(lang, "  (truth {})", &[&format!("{t:.2}")]);
            }
            rows.push((tr(lang, "visibility@slides"), vis));
            if !l.inside_light_frustum {
                rows.push(("", tr(lang, "outside the light's frustum").into()));
            }
        }
        _ => rows.push(("", tr(lang, "no light to probe").into())),
    }

    // The largest size at which the rows fit the panel, down and across.
    let avail = r.bottom() - pad - y - u(12.0);
    let widest = |p: &Canvas, px: f32| {
        let label_w = rows.iter().map(|(l, _)| p.text_width(l, px)).fold(0.0f32, f32::max);
        let gap = if label_w > 0.0 { u(16.0) } else { 0.0 };
        let row_w =
            |(l, v): &(&str, String)| if l.is_empty() { 0.0 } else { label_w + gap } + p.text_width(v, px);
        (label_w + gap, rows.iter().map(row_w).fold(0.0f32, f32::max))
    };
    let mut px = u(24.0);
    while px > u(16.0)
        && (rows.len() as f32 * p.leading(px) > avail || widest(p, px).1 > r.w as f32 - 2.0 * pad)
    {
        px -= u(1.0);
    }
    let vx = r.x as f32 + pad + widest(p, px).0;
    y += u(12.0);
    for (label, value) in rows {
        y += p.leading(px);
        if y > r.bottom() - pad * 0.5 {
            break;
        }
        if label.is_empty() {
            let value = p.fit_label(&value, px, r.right() - pad - (r.x as f32 + pad));
            p.run(&value, r.x as f32 + pad, y, px, pal::INK, true);
            continue;
        }
        p.run(label, r.x as f32 + pad, y, px, pal::MUTED, false);
        let value = p.fit_label(&value, px, r.right() - pad - vx);
        p.run(&value, vx, y, px, pal::INK, false);
    }
}

/// Linear depths: one decimal, as the lessons quote them.
fn depth_num(v: f32) -> String {
    if v.abs() >= 1000.0 { format!("{v:.0}") } else { format!("{v:.1}") }
}

/// A bias in NDC: four decimals, or scientific notation when smaller.
fn bias_num(v: f32) -> String {
    if v == 0.0 || v.abs() >= 0.001 { format!("{v:.4}") } else { format!("{v:.1e}") }
}
