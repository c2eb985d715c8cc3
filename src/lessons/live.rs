//! Live numbers in lesson text. A step quotes the probe by name, `{probe.penumbra_width_world:.2}`,
//! and whoever shows the step (the app, the slides and their HTML index) fills it from the probe it
//! has, so the text stays true after a student moves a slider. `{probe.light1.visibility}` reads
//! light 1 instead of the step's own light. `{frame.mean_abs_error:.3}` reads the picture as a
//! whole, as its legend shows it (its size is the shower's: the app's view, the slide's camera
//! panel). The loader rejects a name that is not listed here.

use super::Lang;
use crate::probe::{LightProbe, ProbeReport};

/// What a placeholder names, and the probe value behind it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Quantity {
    /// Receiver depth as the map would store it (NDC, 0..1).
    ReceiverDepthNdc,
    StoredDepthNdc,
    /// Receiver distance from the light along its axis, world units.
    ReceiverDepthWorld,
    StoredDepthWorld,
    /// Receiver minus stored depth, world units (> 0: the stored surface is nearer the light).
    DepthGapWorld,
    BiasNdc,
    /// Receiver-plane bias: the plane's depth change per texel, world units.
    PlaneDepthPerTexelWorld,
    /// RGBA8 depth storage: the stored depth's round-trip error, NDC.
    Rgba8ErrorNdc,
    NDotL,
    UvX,
    UvY,
    TexelX,
    TexelY,
    SearchRadiusTexels,
    BlockersFound,
    BlockerSamples,
    /// d_blocker, world units.
    AvgBlockerDepthWorld,
    /// d_receiver - d_blocker, world units: the gap the penumbra grows with.
    BlockerGapWorld,
    PenumbraWidthWorld,
    FilterRadiusTexels,
    FilterSamples,
    /// The GPU's visibility, 0 (shadowed) .. 1 (lit).
    Visibility,
    VisibilityReference,
    /// VSM: the filter window's mean depth (NDC) and variance (NDC²).
    VsmMeanNdc,
    VsmVarianceNdc2,
    /// VSM: Chebyshev's bound, the window's share at or behind t (what the bound bounds), and
    /// the visibility's excess over the share not nearer than the receiver's plane (light
    /// bleeding, as the overlay paints it).
    ChebyshevBound,
    TrueLitFraction,
    LightBleeding,
    /// VSSM: its blocker-depth estimate, the true average of the same footprint, PCSS's
    /// sampled average (world units).
    VssmBlockerDepthWorld,
    FootprintBlockerDepthWorld,
    PcssBlockerDepthWorld,
    /// "lit", "shadowed" or "partly lit", in the text's language.
    Verdict,
    /// The object under the probe.
    Object,
    /// A point light: the cube face the lookup read ("-X").
    CubeFace,
    /// A cascaded sun: the cascade the lookup read, from 1 (the sharpest), and its texel's
    /// width, world units.
    Cascade,
    CascadeTexelWorld,
}

const QUANTITIES: [(&str, Quantity); 36] = [
    ("receiver_depth_ndc", Quantity::ReceiverDepthNdc),
    ("stored_depth_ndc", Quantity::StoredDepthNdc),
    ("receiver_depth_world", Quantity::ReceiverDepthWorld),
    ("stored_depth_world", Quantity::StoredDepthWorld),
    ("depth_gap_world", Quantity::DepthGapWorld),
    ("bias_ndc", Quantity::BiasNdc),
    ("plane_depth_per_texel_world", Quantity::PlaneDepthPerTexelWorld),
    ("rgba8_error_ndc", Quantity::Rgba8ErrorNdc),
    ("n_dot_l", Quantity::NDotL),
    ("uv_x", Quantity::UvX),
    ("uv_y", Quantity::UvY),
    ("texel_x", Quantity::TexelX),
    ("texel_y", Quantity::TexelY),
    ("search_radius_texels", Quantity::SearchRadiusTexels),
    ("blockers_found", Quantity::BlockersFound),
    ("blocker_samples", Quantity::BlockerSamples),
    ("avg_blocker_depth_world", Quantity::AvgBlockerDepthWorld),
    ("blocker_gap_world", Quantity::BlockerGapWorld),
    ("penumbra_width_world", Quantity::PenumbraWidthWorld),
    ("filter_radius_texels", Quantity::FilterRadiusTexels),
    ("filter_samples", Quantity::FilterSamples),
    ("visibility", Quantity::Visibility),
    ("visibility_reference", Quantity::VisibilityReference),
    ("vsm_mean_ndc", Quantity::VsmMeanNdc),
    ("vsm_variance_ndc2", Quantity::VsmVarianceNdc2),
    ("chebyshev_bound", Quantity::ChebyshevBound),
    ("true_lit_fraction", Quantity::TrueLitFraction),
    ("light_bleeding", Quantity::LightBleeding),
    ("vssm_blocker_depth_world", Quantity::VssmBlockerDepthWorld),
    ("footprint_blocker_depth_world", Quantity::FootprintBlockerDepthWorld),
    ("pcss_blocker_depth_world", Quantity::PcssBlockerDepthWorld),
    ("verdict", Quantity::Verdict),
    ("object", Quantity::Object),
    ("cube_face", Quantity::CubeFace),
    ("cascade", Quantity::Cascade),
    ("cascade_texel_world", Quantity::CascadeTexelWorld),
];

/// What a `{frame.NAME}` placeholder names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum FrameQuantity {
    /// Mean |visibility - ground truth| over the surface in the picture (the error legend's).
    MeanAbsError,
}

const FRAME_QUANTITIES: [(&str, FrameQuantity); 1] = [("mean_abs_error", FrameQuantity::MeanAbsError)];

/// The names `{probe.NAME}` may use.
pub fn probe_names() -> impl Iterator<Item = &'static str> {
    QUANTITIES.iter().map(|(n, _)| *n)
}

/// The names `{frame.NAME}` may use.
pub fn frame_names() -> impl Iterator<Item = &'static str> {
    FRAME_QUANTITIES.iter().map(|(n, _)| *n)
}

/// Numbers about the whole picture shown, for `{frame.NAME}`: each as the picture's legend shows
/// it, None where it is not known (yet).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FrameValues {
    /// Mean |visibility - ground truth| over the surface in the picture, as the error view's and
    /// the error overlay's legends give it; known once the picture's ground truth is complete.
    pub mean_abs_error: Option<f32>,
}

/// What placeholders are filled from: the probe's report and the picture's numbers.
#[derive(Clone, Copy, Debug, Default)]
pub struct Sources<'a> {
    pub probe: Option<&'a ProbeReport>,
    pub frame: FrameValues,
}

impl<'a> From<Option<&'a ProbeReport>> for Sources<'a> {
    /// The probe alone: `{frame...}` placeholders show [`NO_VALUE`].
    fn from(probe: Option<&'a ProbeReport>) -> Self {
        Sources { probe, frame: FrameValues::default() }
    }
}

/// The probe's verdict on one light: what the text may claim about the probed point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Verdict {
    Lit,
    Shadowed,
    PartlyLit,
}

impl Verdict {
    /// From a visibility in 0..1 (exactly 0 or 1 for a hard test; anything between is partial).
    pub fn of(visibility: f32) -> Verdict {
        if visibility >= 1.0 {
            Verdict::Lit
        } else if visibility <= 0.0 {
            Verdict::Shadowed
        } else {
            Verdict::PartlyLit
        }
    }

    pub fn name(self, lang: Lang) -> &'static str {
        crate::i18n::tr(
            lang,
            match self {
                Verdict::Lit => "lit",
                Verdict::Shadowed => "shadowed",
                Verdict::PartlyLit => "partly lit",
            },
        )
    }
}

/// Where a placeholder's value comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Namespace {
    /// `{probe.NAME}`: one light's numbers at the probed pixel.
    Probe,
    /// `{frame.NAME}`: the picture as a whole.
    Frame,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum What {
    Probe(Quantity),
    Frame(FrameQuantity),
}

/// One `{probe...}` or `{frame...}` placeholder, parsed.
#[derive(Clone, Debug, PartialEq)]
pub struct Placeholder {
    /// Byte range of the whole `{...}` in the text.
    pub span: std::ops::Range<usize>,
    pub namespace: Namespace,
    /// The light it reads; None: the step's own light (and always None for `frame.`).
    pub light: Option<usize>,
    pub name: String,
    what: What,
    /// Digits after the point (floats only; default 2).
    pub decimals: Option<usize>,
}

/// A filled-in value: what the placeholder shows, and the number behind it where it is one.
#[derive(Clone, Debug, PartialEq)]
pub struct Filled {
    pub placeholder: Placeholder,
    pub text: String,
    pub value: Option<f64>,
}

/// Shown where the probe has no value yet (still rendering, or nothing under the probe).
pub const NO_VALUE: &str = "…";

/// Every placeholder in `text`, or a one-line reason naming the first bad one.
pub fn placeholders(text: &str) -> Result<Vec<Placeholder>, String> {
    let mut out = Vec::new();
    let mut rest = 0;
    while let Some(open) = text[rest..].find('{').map(|i| rest + i) {
        let close = text[open..]
            .find('}')
            .map(|i| open + i)
            .ok_or_else(|| format!("unclosed `{{` in `{}`", excerpt(&text[open..])))?;
        let inner = &text[open + 1..close];
        out.push(parse(inner, open..close + 1)?);
        rest = close + 1;
    }
    Ok(out)
}

fn excerpt(s: &str) -> String {
    s.chars().take(40).collect()
}

fn parse(inner: &str, span: std::ops::Range<usize>) -> Result<Placeholder, String> {
    let bad = |why: String| format!("`{{{inner}}}`: {why}");
    let (path, format) = match inner.split_once(':') {
        Some((p, f)) => (p, Some(f)),
        None => (inner, None),
    };
    let (namespace, light, name, what) = if let Some(path) = path.strip_prefix("probe.") {
        let (light, name) = match path.split_once('.') {
            Some((l, name)) => {
                let index = l.strip_prefix("light").and_then(|n| n.parse::<usize>().ok());
                match index {
                    Some(i) => (Some(i), name),
                    None => return Err(bad(format!("`{l}` is not `lightN`"))),
                }
            }
            None => (None, path),
        };
        let quantity = QUANTITIES.iter().find(|(n, _)| *n == name).map(|(_, q)| *q).ok_or_else(|| {
            bad(format!(
                "the probe has no `{name}` (it has {})",
                probe_names().collect::<Vec<_>>().join(", ")
            ))
        })?;
        (Namespace::Probe, light, name, What::Probe(quantity))
    } else if let Some(name) = path.strip_prefix("frame.") {
        let quantity =
            FRAME_QUANTITIES.iter().find(|(n, _)| *n == name).map(|(_, q)| *q).ok_or_else(|| {
                bad(format!(
                    "the frame has no `{name}` (it has {})",
                    frame_names().collect::<Vec<_>>().join(", ")
                ))
            })?;
        (Namespace::Frame, None, name, What::Frame(quantity))
    } else {
        return Err(bad(
            "only `{probe.NAME}`, `{frame.NAME}` or either with `:.N` may stand in braces".into()
        ));
    };
    let decimals = match format {
        None => None,
        Some(f) => Some(
            f.strip_prefix('.')
                .and_then(|d| d.parse::<usize>().ok())
                .filter(|d| *d <= 6)
                .ok_or_else(|| bad(format!("format `{f}` is not `.N` (N = 0..6 decimals)")))?,
        ),
    };
    Ok(Placeholder { span, namespace, light, name: name.to_string(), what, decimals })
}

/// `text` quotes `{NAMESPACE.NAME}` (of any light, with any format) somewhere.
pub fn quotes(text: &str, namespace: Namespace, name: &str) -> bool {
    placeholders(text).is_ok_and(|found| found.iter().any(|p| p.namespace == namespace && p.name == name))
}

enum Value {
    Number(f64, bool),
    Text(String),
}

fn value(q: Quantity, report: &ProbeReport, l: &LightProbe, lang: Lang) -> Option<Value> {
    let float = |v: f32| Some(Value::Number(f64::from(v), false));
    let int = |v: f64| Some(Value::Number(v, true));
    match q {
        Quantity::ReceiverDepthNdc => float(l.receiver_depth_ndc),
        Quantity::StoredDepthNdc => float(l.stored_depth_ndc),
        Quantity::ReceiverDepthWorld => float(l.receiver_depth_linear),
        Quantity::StoredDepthWorld => float(l.stored_depth_linear),
        Quantity::DepthGapWorld => float(l.receiver_depth_linear - l.stored_depth_linear),
        Quantity::BiasNdc => float(l.bias_ndc),
        Quantity::PlaneDepthPerTexelWorld => l.receiver_plane_depth_per_texel_world.and_then(float),
        Quantity::Rgba8ErrorNdc => l.stored_depth_rgba8_error_ndc.and_then(float),
        Quantity::NDotL => float(l.n_dot_l),
        Quantity::UvX => float(l.shadow_map_uv[0]),
        Quantity::UvY => float(l.shadow_map_uv[1]),
        Quantity::TexelX => int(f64::from(l.shadow_map_texel[0])),
        Quantity::TexelY => int(f64::from(l.shadow_map_texel[1])),
        Quantity::SearchRadiusTexels => float(l.blocker_search_radius_texels),
        Quantity::BlockersFound => int(f64::from(l.blockers_found)),
        Quantity::BlockerSamples => int(f64::from(l.blocker_samples)),
        Quantity::AvgBlockerDepthWorld => l.avg_blocker_depth_linear.and_then(float),
        Quantity::BlockerGapWorld => {
            l.avg_blocker_depth_linear.and_then(|d| float(l.receiver_depth_linear - d))
        }
        Quantity::PenumbraWidthWorld => float(l.penumbra_width_world),
        Quantity::FilterRadiusTexels => float(l.filter_radius_texels),
        Quantity::FilterSamples => int(f64::from(l.filter_samples)),
        Quantity::Visibility => float(l.visibility_gpu),
        Quantity::VisibilityReference => l.visibility_reference.and_then(float),
        Quantity::VsmMeanNdc => l.vsm.as_ref().and_then(|v| float(v.mean_depth_ndc)),
        Quantity::VsmVarianceNdc2 => l.vsm.as_ref().and_then(|v| float(v.variance_ndc2)),
        Quantity::ChebyshevBound => l.vsm.as_ref().and_then(|v| float(v.chebyshev_bound)),
        Quantity::TrueLitFraction => l.vsm.as_ref().and_then(|v| float(v.true_lit_fraction)),
        Quantity::LightBleeding => {
            // As the overlay and the Chebyshev diagram measure it: against the window's share
            // not nearer than the receiver's own plane.
            l.vsm.as_ref().and_then(|v| float((v.visibility - v.plane_lit_fraction).max(0.0)))
        }
        Quantity::VssmBlockerDepthWorld => {
            l.vssm.as_ref().and_then(|v| float(v.estimated_blocker_depth_linear))
        }
        Quantity::FootprintBlockerDepthWorld => {
            l.vssm.as_ref().and_then(|v| v.footprint_blocker_depth_linear).and_then(float)
        }
        Quantity::PcssBlockerDepthWorld => {
            l.vssm.as_ref().and_then(|v| v.pcss_blocker_depth_linear).and_then(float)
        }
        Quantity::Verdict => Some(Value::Text(Verdict::of(l.visibility_gpu).name(lang).into())),
        Quantity::Object => report.object.clone().map(Value::Text),
        Quantity::CubeFace => l.cube_face.clone().map(Value::Text),
        Quantity::Cascade => l.cascade.as_ref().and_then(|c| int(c.index as f64 + 1.0)),
        Quantity::CascadeTexelWorld => l.cascade.as_ref().and_then(|c| float(c.texel_world)),
    }
}

fn frame_value(q: FrameQuantity, frame: &FrameValues) -> Option<Value> {
    match q {
        FrameQuantity::MeanAbsError => frame.mean_abs_error.map(|v| Value::Number(f64::from(v), false)),
    }
}

/// `text` with every placeholder filled from `sources` (the probe's light `light` unless the
/// placeholder names one; the frame's numbers), and what each one became. Where a value is not
/// known (no report, no surface under the probe, a frame number not worked out yet) the
/// placeholder shows [`NO_VALUE`]. Text that fails [`placeholders`] is returned as it is.
pub fn fill<'a>(
    text: &str,
    sources: impl Into<Sources<'a>>,
    light: usize,
    lang: Lang,
) -> (String, Vec<Filled>) {
    let sources = sources.into();
    let report = sources.probe;
    let Ok(found) = placeholders(text) else { return (text.to_string(), Vec::new()) };
    let mut out = String::with_capacity(text.len());
    let mut filled = Vec::with_capacity(found.len());
    let mut at = 0;
    for p in found {
        out.push_str(&text[at..p.span.start]);
        at = p.span.end;
        let wanted = p.light.unwrap_or(light);
        let v = match p.what {
            What::Probe(quantity) => report
                .filter(|r| r.hit)
                .and_then(|r| r.lights.iter().find(|l| l.light == wanted).map(|l| (r, l)))
                .and_then(|(r, l)| value(quantity, r, l, lang)),
            What::Frame(quantity) => frame_value(quantity, &sources.frame),
        };
        let (shown, number) = match v {
            Some(Value::Number(x, true)) => (format!("{x:.0}"), Some(x)),
            Some(Value::Number(x, false)) => {
                let d = p.decimals.unwrap_or(2);
                let shown = format!("{x:.d$}");
                // The number as shown: what a reader (or a test) can compare.
                (shown.clone(), shown.parse().ok())
            }
            Some(Value::Text(s)) => (s, None),
            None => (NO_VALUE.to_string(), None),
        };
        out.push_str(&shown);
        filled.push(Filled { placeholder: p, text: shown, value: number });
    }
    out.push_str(&text[at..]);
    (out, filled)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Technique;

    fn light_probe(light: usize, visibility: f32) -> LightProbe {
        LightProbe {
            light,
            shadow_view: light,
            cube_face: None,
            cascade: None,
            shadow_map_uv: [0.25, 0.75],
            shadow_map_texel: [512, 1536],
            inside_light_frustum: true,
            n_dot_l: 0.19,
            receiver_depth_ndc: 0.3,
            receiver_depth_linear: 120.0,
            stored_depth_ndc: 0.25,
            stored_depth_linear: 100.0,
            bias_ndc: 0.001,
            receiver_plane_depth_per_texel_world: None,
            stored_depth_rgba8_error_ndc: None,
            vsm: None,
            vssm: None,
            blocker_search_radius_uv: 0.0,
            blocker_search_radius_texels: 94.625,
            blockers_found: 20,
            blocker_samples: 32,
            avg_blocker_depth_linear: Some(42.3),
            penumbra_width_world: 1.3649,
            filter_radius_uv: 0.0,
            filter_radius_texels: 17.5,
            filter_samples: 32,
            visibility_gpu: visibility,
            visibility_twin: visibility,
            visibility_reference: None,
            taps: Vec::new(),
        }
    }

    fn report() -> ProbeReport {
        ProbeReport {
            pixel: [1, 2],
            size: [960, 540],
            time_s: 0.0,
            technique: Technique::Pcss,
            hit: true,
            object: Some("floor".into()),
            world_position: Some([0.0; 3]),
            normal: Some([0.0, 1.0, 0.0]),
            lights: vec![light_probe(0, 0.22), light_probe(1, 1.0)],
        }
    }

    #[test]
    fn fills_names_with_their_decimals_and_the_named_light() {
        let r = report();
        let text = "w = {probe.penumbra_width_world:.2}, r = {probe.search_radius_texels:.1} texels, \
                    {probe.blockers_found} of {probe.blocker_samples}, on the {probe.object}: \
                    {probe.verdict}; light 1 is {probe.light1.verdict}";
        let (out, filled) = fill(text, Some(&r), 0, Lang::En);
        assert_eq!(out, "w = 1.36, r = 94.6 texels, 20 of 32, on the floor: partly lit; light 1 is lit");
        assert_eq!(filled[0].value, Some(1.36));
        assert_eq!(filled[2].value, Some(20.0));
        let (zh, _) = fill("{probe.verdict}", Some(&r), 1, Lang::Zh);
        assert_eq!(zh, "受光");
    }

    #[test]
    fn the_depth_gap_is_receiver_minus_stored() {
        let r = report();
        let (out, _) = fill("{probe.depth_gap_world:.1}", Some(&r), 0, Lang::En);
        assert_eq!(out, "20.0");
    }

    #[test]
    fn without_a_probe_the_values_are_pending() {
        let (out, filled) = fill("V = {probe.visibility}", None, 0, Lang::En);
        assert_eq!(out, format!("V = {NO_VALUE}"));
        assert_eq!(filled[0].value, None);
    }

    #[test]
    fn frame_values_fill_from_the_frame_and_wait_for_it() {
        let r = report();
        let text = "error {frame.mean_abs_error:.3} at V = {probe.visibility:.2}";
        let frame = FrameValues { mean_abs_error: Some(0.00755) };
        let (out, filled) = fill(text, Sources { probe: Some(&r), frame }, 0, Lang::En);
        assert_eq!(out, "error 0.008 at V = 0.22");
        assert_eq!(filled[0].placeholder.namespace, Namespace::Frame);
        assert_eq!(filled[0].value, Some(0.008));
        // Not worked out yet: pending, whatever the probe has.
        let (out, filled) = fill(text, Some(&r), 0, Lang::En);
        assert_eq!(out, format!("error {NO_VALUE} at V = 0.22"));
        assert_eq!(filled[0].value, None);
        // The frame's numbers do not need a surface under the probe, nor a probe at all.
        let mut missed = report();
        missed.hit = false;
        let (out, _) = fill(text, Sources { probe: Some(&missed), frame }, 0, Lang::En);
        assert_eq!(out, format!("error 0.008 at V = {NO_VALUE}"));
        let (out, _) = fill("{frame.mean_abs_error}", Sources { probe: None, frame }, 0, Lang::En);
        assert_eq!(out, "0.01");
    }

    #[test]
    fn frame_placeholders_are_checked_like_the_probes() {
        let found =
            placeholders("a {frame.mean_abs_error:.4} b {probe.light1.visibility_reference}").expect("valid");
        assert_eq!(found[0].namespace, Namespace::Frame);
        assert_eq!(
            (found[0].name.as_str(), found[0].light, found[0].decimals),
            ("mean_abs_error", None, Some(4))
        );
        assert_eq!(found[1].namespace, Namespace::Probe);
        assert_eq!((found[1].name.as_str(), found[1].light), ("visibility_reference", Some(1)));
        let bad = |text: &str| placeholders(text).expect_err(text);
        let e = bad("{frame.mean_error}");
        assert!(e.contains("the frame has no `mean_error`") && e.contains("mean_abs_error"), "{e}");
        // The frame is one picture: no light to name.
        assert!(bad("{frame.light1.mean_abs_error}").contains("the frame has no `light1.mean_abs_error`"));
        assert!(bad("{frame.mean_abs_error:3}").contains("`.N`"));
        assert!(bad("{view.mean_abs_error}").contains("`{frame.NAME}`"));
        // The probe's names are not the frame's, nor the other way round.
        assert!(bad("{frame.visibility}").contains("the frame has no"));
        assert!(bad("{probe.mean_abs_error}").contains("the probe has no"));
    }

    #[test]
    fn quotes_finds_a_name_in_either_namespace() {
        let text = "truth {probe.light1.visibility_reference:.2}, error {frame.mean_abs_error:.3}";
        assert!(quotes(text, Namespace::Probe, "visibility_reference"));
        assert!(quotes(text, Namespace::Frame, "mean_abs_error"));
        assert!(!quotes(text, Namespace::Probe, "visibility"));
        assert!(!quotes(text, Namespace::Frame, "visibility_reference"));
        assert!(!quotes("{probe.visibility_reference", Namespace::Probe, "visibility_reference"));
        assert!(probe_names().any(|n| n == "visibility_reference"));
        assert_eq!(frame_names().collect::<Vec<_>>(), ["mean_abs_error"]);
    }

    #[test]
    fn bad_placeholders_are_named() {
        let bad = |text: &str| placeholders(text).expect_err(text);
        let e = bad("x {probe.penumbra} y");
        assert!(e.contains("`{probe.penumbra}`") && e.contains("penumbra_width_world"), "{e}");
        assert!(bad("{probe.visibility:2}").contains("`.N`"));
        assert!(bad("{light.visibility}").contains("only `{probe.NAME}`"));
        assert!(bad("{probe.lamp1.visibility}").contains("`lamp1`"));
        assert!(bad("open { brace").contains("unclosed"));
        assert_eq!(placeholders("no braces at all"), Ok(Vec::new()));
    }
}
