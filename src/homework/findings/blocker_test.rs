//! Whether findBlocker counts the receiver's own surface as a blocker, and why: no test at all,
//! a bias the wrong way round, or a flat bias under what a surface sloped to the light moves in
//! depth across a wide search.

use super::functions::{FIND_BLOCKER, lookups_broken, search_broken};
use super::{FindingKind, Found, Judged, ids, median};
use crate::i18n::{Lang, fill, tr};
use std::collections::BTreeMap;

/// The blocker search as the findings name it (`judge` puts the student's own name in).
const FIND_BLOCKER_NAME: &str = "findBlocker";
/// `receiver_counts_as_blocker`: where the twin finds no blocker within the student's search
/// radius, findBlocker returns the receiver's own depth at more than this share...
const FINDS_ITSELF_SHARE: f64 = 0.5;
/// ...and where some of the disk is blocked, its average is pulled this far (median) from the
/// blockers' towards the receiver's depth. A flat bias on a floor sloped to the light lets a wide
/// search count some of the receiver's nearer texels (0.15 for 0.001 in depth); no bias at all
/// 0.25 to 0.4, a bias the wrong way 0.4 and more.
const PULL: f32 = 0.2;
/// findBlocker counts the receiver itself as a blocker: where the twin finds none over the same
/// disk it returns the receiver's own depth, and where some of the disk is blocked its average is
/// pulled towards the receiver's depth.
pub const RECEIVER_COUNTS_AS_BLOCKER: FindingKind = FindingKind {
    id: ids::RECEIVER_COUNTS_AS_BLOCKER,
    lesson: "pcss",
    step: 4,
    judge: receiver_counts_as_blocker,
};

fn receiver_counts_as_blocker(j: &Judged<'_>, earlier: &[super::Finding], lang: Lang) -> Option<Found> {
    if !j.pcss() || search_broken(earlier) || lookups_broken(earlier) {
        return None;
    }
    let (mut clear, mut found_itself) = (0usize, 0usize);
    let (mut pulls, mut spreads) = (Vec::new(), Vec::new());
    for (i, search) in j.twin() {
        let returned = j.e.student.returned[*i][FIND_BLOCKER];
        let receiver = j.receivers[*i].map_or(search.z_receiver, |r| r.depth);
        if search.blocked == 0.0 {
            clear += 1;
            spreads.push(search.receiver_spread);
            // A depth among the receiver's own texels (its plane across the disk, the packing's
            // rounding): what the receiver counted as a blocker averages to.
            found_itself += usize::from((returned - receiver).abs() <= search.receiver_spread + 0.002);
        } else if (0.2..0.8).contains(&search.blocked) && search.z_receiver - search.z_blocker > 0.002 {
            pulls.push((returned - search.z_blocker) / (search.z_receiver - search.z_blocker));
        }
    }
    let itself = found_itself as f64 / clear.max(1) as f64;
    let pull = median(pulls.clone())?;
    if !(clear >= 50 && pulls.len() >= 20 && itself > FINDS_ITSELF_SHARE && pull > PULL) {
        return None;
    }
    let mut figures = BTreeMap::from([
        ("returns_receiver_depth_share", itself),
        ("pull_towards_receiver_median", f64::from(pull)),
        ("pixels_compared", (clear + pulls.len()) as f64),
    ]);
    let mut explanation = fill(
        lang,
        "findBlocker counts the receiver as its own blocker: where nothing blocks the disk it searched, it returns the receiver's own depth at {:.0}% of the points, and where part of the disk is blocked its average lies {:.0}% of the way from the blockers' depth to the receiver's.",
        &[&(100.0 * itself), &(100.0 * pull)],
    );
    explanation += " ";
    let source = j.e.fragment_source;
    let spread = median(spreads).unwrap_or(0.0);
    // The bias its own test adds, where one constant is.
    let bias = super::source_lines::depth_test_constants(source)
        .into_iter()
        .find(|c| c.function == Some(FIND_BLOCKER_NAME) && c.added);
    if super::formula_lines::compares_in(source, FIND_BLOCKER_NAME) == Some(false) {
        explanation += tr(
            lang,
            "It compares nothing: every tap it reads goes into the average, the receiver's own surface with the blockers. Count a tap only where its depth is nearer than the receiver's by more than a bias.",
        );
    } else if let Some((c, (_, test_line))) = bias.as_ref().and_then(|c| {
        super::formula_lines::bias_tightens(source, FIND_BLOCKER_NAME, &c.text)
            .filter(|(tightens, _)| !tightens)
            .map(|t| (c, t))
    }) {
        figures.insert("bias_line", c.line as f64);
        figures.insert("test_line", test_line as f64);
        let code = source.lines().nth(test_line - 1).unwrap_or("").trim();
        explanation += &fill(
            lang,
            "Its bias, `{}` (line {}), is the wrong way round in line {}'s test, `{}`: it lets texels up to {:.4} behind the receiver count as blockers, so the receiver's own texels always do. Test depth + bias < z_receiver.",
            &[&c.text, &c.line, &test_line, &code, &c.value],
        );
    } else if let Some(c) = bias.filter(|c| c.value < 0.5 * f64::from(spread)) {
        figures.insert("bias_line", c.line as f64);
        figures.insert("bias_depth", c.value);
        figures.insert("receiver_spread_depth_median", f64::from(spread));
        explanation += &fill(
            lang,
            "Its bias, `{}` on line {} ({:.4} in [0, 1] depth), is far under how much the receiver's own surface, sloped to the light, moves in depth across the disk it searches: {:.4} (median). The nearer part of that surface passes the test as a blocker. A bias that grows with the slope and the search radius, or each tap compared with the receiver plane's depth there, keeps it out.",
            &[&c.text, &c.line, &c.value, &spread],
        );
        // A disk that wide because a sample count sizes it.
        if let Some((line, name, count)) = super::formula_lines::count_as_radius(source, FIND_BLOCKER_NAME) {
            figures.insert("radius_line", line as f64);
            explanation += " ";
            explanation += &fill(
                lang,
                "The disk is that wide because line {} sizes it with `{}`, a sample count ({}), as if it were a radius in texels.",
                &[&line, &name, &count],
            );
        }
    } else {
        explanation += tr(
            lang,
            "Test blockers as nearer than the receiver by more than a bias (depth + bias < z_receiver): a bias the other way, or none, lets the receiver's own texels in, and the penumbra shrinks.",
        );
    }
    Some(Found::new(Some(FIND_BLOCKER_NAME), figures, explanation))
}

/// findBlocker's loop reads only the first of the samples its disk holds: the framework's disk
/// orders them from the centre out (sample i at ((i + 1) / n)^0.75 of the radius), so the search
/// reaches a fraction of its radius. Confirmed where the search reaches under this share of the
/// light's half width the student's own filter implies.
const PART_OF_LIGHT: f32 = 0.6;

pub const SEARCH_READS_PART_OF_DISK: FindingKind =
    FindingKind { id: ids::SEARCH_RADIUS_WRONG, lesson: "pcss", step: 2, judge: search_reads_part_of_disk };

fn search_reads_part_of_disk(j: &Judged<'_>, earlier: &[super::Finding], lang: Lang) -> Option<Found> {
    if !j.pcss()
        || search_broken(earlier)
        || lookups_broken(earlier)
        || super::has(earlier, ids::SEARCH_RADIUS_WRONG)
    {
        return None;
    }
    let (line, array, read, size) =
        super::formula_lines::partial_sample_loop(j.e.fragment_source, FIND_BLOCKER_NAME)?;
    let texel = super::functions::texel_uv(j);
    let points = super::pcss_steps::searched_light_halves(j);
    if points.len() < 50 {
        return None;
    }
    let search = median(points.iter().map(|p| p.0).collect())?;
    let light = median(points.iter().map(|p| p.1).collect())?;
    if search >= PART_OF_LIGHT * light {
        return None;
    }
    let reach = (read as f32 / size as f32).powf(0.75);
    let figures = BTreeMap::from([
        ("line", line as f64),
        ("samples_read", read as f64),
        ("samples_in_disk", size as f64),
        ("search_radius_texels_median", f64::from(search / texel)),
        ("light_half_width_texels_median", f64::from(light / texel)),
    ]);
    let explanation = format!(
        "{} {}",
        tr(
            lang,
            "Hidden today by this scene: the blockers that shape each penumbra lie within the part it reads; a wider light or a higher blocker shows it:"
        ),
        fill(
            lang,
            "findBlocker's loop on line {} reads only the first {} of the {} samples in `{}`. The disk orders them from the centre out, so those reach {:.0}% of its radius: the search reads {:.1} texels around the receiver, where the light its filter behaves as is {:.1} texels wide (half). Loop over every sample the disk holds (BLOCKER_SEARCH_NUM_SAMPLES, and a disk of that many).",
            &[&line, &read, &size, &array, &(100.0 * reach), &(search / texel), &(light / texel)],
        ),
    );
    Some(Found { latent: true, ..Found::new(Some(FIND_BLOCKER_NAME), figures, explanation) })
}
