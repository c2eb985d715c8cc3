//! Findings on a PCSS's penumbrae, from the slabs' shadows (`light_width`): as hard as a hard
//! shadow, or not following similar triangles (no contact hardening).

use super::ids;
use super::{FindingKind, Found, Judged, SLAB_KEYS, has};
use crate::i18n::{Lang, fill};
use std::collections::BTreeMap;

/// Findings on the numbers or the lookup itself leave nothing to say about the penumbra.
fn penumbra_judged(j: &Judged<'_>, earlier: &[super::Finding]) -> bool {
    j.pcss()
        && !super::functions::search_broken(earlier)
        && ![
            ids::VISIBILITY_OUT_OF_RANGE,
            ids::VISIBILITY_SCALED,
            ids::SHADOWS_MISSING,
            ids::UMBRA_NOT_DARK,
            ids::LIGHT_MODEL_MATRIX,
            ids::PETER_PANNING,
            // Acne darkens the lit side of every slab's penumbra: its widths are the acne's.
            ids::SELF_SHADOWING,
            // A filter narrower than its own search's light: the cause of narrow penumbrae.
            ids::SEARCH_AND_FILTER_LIGHTS_DIFFER,
            ids::FILTER_IGNORES_BLOCKER,
        ]
        .iter()
        .any(|id| has(earlier, id))
}

/// A PCSS whose penumbrae are under the resolution on every slab, the highest included: as hard
/// as a hard shadow (a filter under a texel).
pub const NO_PENUMBRA: FindingKind =
    FindingKind { id: ids::NO_PENUMBRA, lesson: "pcss", step: 5, judge: no_penumbra };

fn no_penumbra(j: &Judged<'_>, earlier: &[super::Finding], lang: Lang) -> Option<Found> {
    if !penumbra_judged(j, earlier) {
        return None;
    }
    let fit = j.e.light.width?;
    let highest = fit.slabs.iter().max_by(|a, b| a.ratio.total_cmp(&b.ratio))?;
    let widest = highest.width_world?;
    if widest >= fit.resolution_world {
        return None;
    }
    Some(Found::new(
        None,
        BTreeMap::from([
            ("highest_slab_penumbra_world", f64::from(widest)),
            ("resolution_world", f64::from(fit.resolution_world)),
        ]),
        fill(
            lang,
            "Your PCSS draws hard shadows: even the {}'s penumbra is {:.2} world units wide, under the {:.2} a texel or a pixel covers here. The filter is under a texel wide: a light size or filter radius far too small for the map, or the penumbra estimate lost before filtering.",
            &[&highest.name, &widest, &fit.resolution_world],
        ),
    ))
}

/// The penumbrae do not widen with the gap as similar triangles say: constant widths (a PCF of
/// one radius), widths that shrink, or noise.
pub const NO_CONTACT_HARDENING: FindingKind =
    FindingKind { id: ids::NO_CONTACT_HARDENING, lesson: "pcss", step: 1, judge: no_contact_hardening };

fn no_contact_hardening(j: &Judged<'_>, earlier: &[super::Finding], lang: Lang) -> Option<Found> {
    // Taps on a line make penumbrae soft one way and hard the other: that finding says why; a
    // blocker depth that is no blocker's, or a filter radius that collapses, is why the widths do
    // not follow similar triangles, and those findings say so.
    if !penumbra_judged(j, earlier)
        || has(earlier, ids::NO_PENUMBRA)
        || has(earlier, ids::SAMPLES_NOT_AROUND_RECEIVER)
        || has(earlier, ids::BLOCKER_DEPTH_WRONG)
        || has(earlier, ids::PENUMBRA_ESTIMATE_WRONG)
        || has(earlier, ids::PENUMBRA_LAW_WRONG)
        || has(earlier, ids::RECEIVER_COUNTS_AS_BLOCKER)
    {
        return None;
    }
    let fit = j.e.light.width?;
    if fit.law_holds != Some(false) {
        return None;
    }
    let light = fit.implied_light_width_world.unwrap_or(0.0);
    let mut figures = BTreeMap::from([("implied_light_width_world", f64::from(light))]);
    if let Some(r2) = fit.r_squared {
        figures.insert("r_squared", f64::from(r2));
    }
    let mut widths = Vec::new();
    for (key, s) in SLAB_KEYS.iter().zip(&fit.slabs) {
        if let Some(w) = s.width_world {
            figures.insert(key.width_world, f64::from(w));
            figures.insert(key.law_width_world, f64::from(light * s.ratio));
            widths.push(format!("{w:.2} ({:.0} high)", s.height_world));
        }
    }
    let measured = if widths.is_empty() { "-".to_string() } else { widths.join(", ") };
    let explanation = fill(
        lang,
        "Your penumbrae do not widen with the distance from blocker to receiver as similar triangles say (w = w_light (d_r - d_b) / d_b): under the slabs they are {} world units wide (where a light's disk explains their shape at all), and no one light width fits them. Contact hardening is what PCSS is for: check the blocker search (its radius, and what it counts as a blocker) and the penumbra's formula.",
        &[&measured],
    );
    Some(Found::new(Some("PCSS"), figures, explanation))
}
