//! A check's figures, whatever it found: how the student's visibility compares with shadowlab's
//! technique and the ground truth, pixel by pixel, and a penumbra's width at one pixel.

use super::HomeworkImages;
use super::findings::{Judged, LIT, SOFT, mean, shadows};
use serde::Serialize;

/// The comparison's figures, whatever was found.
#[derive(Clone, Debug, Default, Serialize, PartialEq)]
pub struct Figures {
    /// Pixels the student's shader ran at.
    pub shaded_pixels: u64,
    /// Of those, pixels with a visibility (a recorded function returned one from `main`'s level).
    pub pixels_with_visibility: u64,
    /// Share of shaded pixels whose visibility is NaN or infinite.
    pub nan_fraction: f64,
    /// Mean |student - shadowlab's technique| and |student - ground truth| over the pixels with a
    /// finite visibility.
    pub mean_abs_difference: Option<f64>,
    pub mean_abs_difference_to_ground_truth: Option<f64>,
    /// The student's mean visibility where the ground truth is fully lit, and in its umbra (on
    /// surfaces facing the light).
    pub lit_area_mean: Option<f64>,
    pub umbra_mean: Option<f64>,
    /// Soft pixels (0.05 < v < 0.95): the ground truth's and the student's.
    pub penumbra_pixels_ground_truth: u64,
    pub penumbra_pixels: u64,
    /// Share of shaded pixels whose visibility changes by more than 0.1 over a white map.
    pub uncleared_map_share: f64,
    /// The penumbra's width across the shadow's edge at `penumbra_pixel` (the ground truth's soft
    /// pixel nearest the picture's centre), world units: the student's and the ground truth's.
    pub penumbra_pixel: Option<(u32, u32)>,
    pub penumbra_width_world: Option<f32>,
    pub penumbra_width_world_ground_truth: Option<f32>,
}

/// The penumbra's width at `pixel` (the student's, the ground truth's), world units, across the
/// ground truth's edge there; None where the ground truth has no edge at that pixel.
pub fn penumbra_widths(
    student: &HomeworkImages,
    ground_truth: &[f32],
    positions: &[Option<glam::Vec3>],
    pixel: (u32, u32),
) -> Option<(f32, f32)> {
    let field = super::penumbra::Field { width: student.width, height: student.height, positions };
    let truth = |i: usize| student.covered(i).then(|| ground_truth[i]);
    let theirs = |i: usize| student.visibility(i);
    let dir = field.across(&truth, pixel)?;
    let truth_width = field.width_along(&truth, pixel, dir, 3);
    Some((field.width_along(&theirs, pixel, dir, 20), truth_width))
}

/// The figures of the evidence `j` judges.
pub fn figures(j: &Judged<'_>) -> Figures {
    let e = j.e;
    let truth = |i: usize| e.ground_truth[i];
    let soft = |v: f32| v > SOFT.0 && v < SOFT.1;
    let mut f = Figures {
        shaded_pixels: j.shaded.len() as u64,
        pixels_with_visibility: (j.finite.len() + j.non_finite) as u64,
        nan_fraction: j.share(j.non_finite),
        mean_abs_difference: mean(j.finite.iter().map(|&(i, v)| f64::from((v - e.shadowlab[i]).abs()))),
        mean_abs_difference_to_ground_truth: mean(
            j.finite.iter().map(|&(i, v)| f64::from((v - truth(i)).abs())),
        ),
        lit_area_mean: mean(j.finite.iter().filter(|&&(i, _)| truth(i) >= LIT).map(|&(_, v)| f64::from(v))),
        umbra_mean: shadows::umbra_mean(j),
        penumbra_pixels_ground_truth: j.finite.iter().filter(|&&(i, _)| soft(truth(i))).count() as u64,
        penumbra_pixels: j.finite.iter().filter(|&&(_, v)| soft(v)).count() as u64,
        uncleared_map_share: shadows::uncleared_share(j),
        ..Figures::default()
    };
    let student = e.student;
    let field =
        super::penumbra::Field { width: student.width, height: student.height, positions: e.positions };
    f.penumbra_pixel = super::penumbra::default_pixel(&field, &|i| student.covered(i).then(|| truth(i)));
    let widths = |p| penumbra_widths(student, e.ground_truth, e.positions, p);
    if let Some((theirs, truth_width)) = f.penumbra_pixel.and_then(widths) {
        (f.penumbra_width_world, f.penumbra_width_world_ground_truth) = (Some(theirs), Some(truth_width));
    }
    f
}
