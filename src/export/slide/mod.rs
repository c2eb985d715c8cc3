//! One slide per lesson step: a title bar, the camera view and the shadow map side by side with
//! captions, the diagram, the probe's numbers, the explanation and the try-this prompts.
//!
//! Laid out on a 1920x1080 design grid scaled uniformly onto the slide, so the proportions and
//! the text sizes hold at any size: body text is 34 units (17 px on a 960x540 slide; smaller only
//! when a long text needs it), captions 22. A slide of another shape keeps the grid centred
//! across, with the spare room at the bottom.

mod layout;
mod probe_panel;

pub use layout::{DESIGN, MIN_SIZE, Rect, SlideLayout, SlideText};

use super::step::{PROBE_FRAME, StepPictures};
use crate::diagrams::{Canvas, is_cjk};
use crate::i18n::{Lang, fill, tr};
use crate::scene::Technique;
use crate::views::View;
use image::RgbaImage;
use probe_panel::probe_panel;
use tiny_skia::{Color, Pixmap};

mod pal {
    pub const BG: [u8; 3] = [250, 250, 246];
    pub const INK: [u8; 3] = [20, 24, 28];
    pub const MUTED: [u8; 3] = [84, 92, 100];
    pub const TITLE_BG: [u8; 3] = [38, 50, 56];
    pub const TITLE_FG: [u8; 3] = [255, 255, 255];
    pub const TITLE_DIM: [u8; 3] = [176, 190, 197];
    pub const FRAME: [u8; 3] = [160, 166, 172];
    pub const PANEL: [u8; 3] = [238, 240, 236];
    pub const TRY_BG: [u8; 3] = [255, 243, 214];
    pub const TRY_EDGE: [u8; 3] = [230, 159, 0];
    pub const PROBE: [u8; 3] = [230, 159, 0];
}

fn rgb(c: [u8; 3]) -> Color {
    Color::from_rgba8(c[0], c[1], c[2], 255)
}

/// The view's name as the caption shows it: in Chinese the label the app's view menu shows.
pub fn view_label(view: View, lang: Lang) -> &'static str {
    tr(
        lang,
        match view {
            View::Final => "shaded",
            View::Visibility => "visibility",
            View::ShadowMap => "shadow map",
            View::BlockerRadius => "blocker-search radius",
            View::Penumbra => "penumbra width",
            View::Blockers => "blockers found",
            View::BlockerDepth => "average blocker depth",
            View::Moments => "VSM moments",
            View::TexelDensity => "texel density",
            View::CascadeIndex => "cascade index",
            View::Reference => "ground truth",
            View::Error => "error vs ground truth",
        },
    )
}

/// A number with about three significant digits.
pub fn short_num(v: f32) -> String {
    let a = v.abs();
    if !v.is_finite() {
        "–".into()
    } else if a == 0.0 {
        "0".into()
    } else if a >= 100.0 {
        format!("{v:.0}")
    } else if a >= 10.0 {
        format!("{v:.1}")
    } else if a >= 1.0 {
        format!("{v:.2}")
    } else if a >= 0.001 {
        format!("{v:.3}")
    } else {
        format!("{v:.1e}")
    }
}

/// A view's legend line, numbers shortened, in the slide's language.
pub fn legend_caption(summary: &str, lang: Lang) -> String {
    let shortened: Vec<String> = summary
        .split(['\n'])
        .map(|line| {
            line.split(' ')
                .map(|w| {
                    // A number right after a full-width colon ("深度：20.00") counts as a word.
                    let number = w.rsplit_once('：').map_or(w, |(_, n)| n);
                    let head = &w[..w.len() - number.len()];
                    match number.parse::<f32>() {
                        Ok(v) if number.contains('.') => format!("{head}{}", short_num(v)),
                        _ => w.to_string(),
                    }
                })
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect();
    // The legends come from the views in the slide's language; a Chinese range reads better
    // with 至 than "..", and full-width punctuation needs no space beside it.
    shortened
        .join(" · ")
        .replace("  ", " ")
        .replace("..", tr(lang, ".."))
        .replace("： ", "：")
        .replace(" （", "（")
}

/// Slide shorthands on the diagrams' canvas (in pixels): colours from the slide palette,
/// rectangles as laid out, and the slide's line spacing. Every pixel is drawn by the canvas.
trait SlideDraw {
    fn fill_rgb(&mut self, r: [f32; 4], c: [u8; 3]);
    /// A frame drawn outside `r`.
    fn frame(&mut self, r: Rect, c: [u8; 3], width: f32);
    /// A cross-hair with a dark outline, visible on light and dark pictures.
    fn marker(&mut self, p: [f32; 2], size: f32);
    fn run(&mut self, s: &str, x: f32, baseline: f32, px: f32, c: [u8; 3], bold: bool);
    /// Line height for `px`; Chinese needs more room between lines.
    fn leading(&self, px: f32) -> f32;
}

impl SlideDraw for Canvas {
    fn fill_rgb(&mut self, r: [f32; 4], c: [u8; 3]) {
        self.rect(r, Some(rgb(c)), None);
    }

    fn frame(&mut self, r: Rect, c: [u8; 3], width: f32) {
        let outer =
            [r.x as f32 - 0.5 * width, r.y as f32 - 0.5 * width, r.w as f32 + width, r.h as f32 + width];
        self.rect(outer, None, Some((rgb(c), width)));
    }

    fn marker(&mut self, p: [f32; 2], size: f32) {
        let (arm, gap) = (size, size * 0.35);
        let segments = [
            ([p[0] - arm, p[1]], [p[0] - gap, p[1]]),
            ([p[0] + gap, p[1]], [p[0] + arm, p[1]]),
            ([p[0], p[1] - arm], [p[0], p[1] - gap]),
            ([p[0], p[1] + gap], [p[0], p[1] + arm]),
        ];
        for (a, b) in segments {
            self.line(a, b, rgb(pal::INK), size * 0.32);
        }
        for (a, b) in segments {
            self.line(a, b, rgb(pal::PROBE), size * 0.16);
        }
    }

    fn run(&mut self, s: &str, x: f32, baseline: f32, px: f32, c: [u8; 3], bold: bool) {
        self.text_run(s, [x, baseline], px, rgb(c), bold);
    }

    fn leading(&self, px: f32) -> f32 {
        // Typography, not a translation: CJK lines need more room between them.
        px * if self.lang == Lang::Zh { 1.62 } else { 1.42 }
    }
}

fn at(r: Rect) -> [f32; 2] {
    [r.x as f32, r.y as f32]
}

/// Layout of the explanation and the prompts at one text size.
struct TextBlock {
    body: Vec<String>,
    prompts: Vec<Vec<String>>,
    body_px: f32,
    prompt_px: f32,
}

/// A composed slide.
pub struct Slide {
    pub pixmap: Pixmap,
    /// The explanation did not fit even at the smallest text size and was cut short.
    pub text_cut: bool,
    /// Titles, captions and probe values too long for their place, in full (each was drawn
    /// cut, with an ellipsis).
    pub shortened: Vec<String>,
}

/// Assemble the slide. The camera image is at `layout.camera`'s size, `map` is the shadow map
/// panel at `layout.shadow_map`'s size and `diagram` is drawn at `layout.diagram`'s size.
/// Where a map picture `img_w` x `img_h` lies in its panel `r`, its aspect kept and centred:
/// x, y, w, h in slide pixels (a cube's 4 x 3 cross, a sun's cascades in a row).
fn map_inner_rect(r: Rect, img_w: u32, img_h: u32) -> [f32; 4] {
    let aspect = img_h.max(1) as f32 / img_w.max(1) as f32;
    let w = (r.w as f32).min(r.h as f32 / aspect);
    let h = w * aspect;
    [r.x as f32 + 0.5 * (r.w as f32 - w), r.y as f32 + 0.5 * (r.h as f32 - h), w, h]
}

/// A map picture for a `w` x `h` panel: scaled to fit with its aspect kept, centred on the
/// panel's colour.
pub fn map_panel_image(img: &RgbaImage, w: u32, h: u32) -> RgbaImage {
    let [x, y, iw, ih] = map_inner_rect(Rect { x: 0, y: 0, w, h }, img.width(), img.height());
    let scaled = image::imageops::resize(
        img,
        (iw.round() as u32).max(1),
        (ih.round() as u32).max(1),
        image::imageops::FilterType::Triangle,
    );
    let mut panel = RgbaImage::from_pixel(w, h, image::Rgba([238, 240, 236, 255]));
    image::imageops::overlay(&mut panel, &scaled, x.round() as i64, y.round() as i64);
    panel
}

pub fn compose(
    layout: &SlideLayout,
    text: &SlideText,
    pictures: &StepPictures,
    map: Option<&RgbaImage>,
    diagram: &Pixmap,
) -> Option<Slide> {
    let camera = &pictures.camera;
    let (w, h) = layout.size;
    let lang = text.lang;
    let mut p = Canvas::in_pixels(Pixmap::new(w, h)?, lang, rgb(pal::BG));
    let u = |v: f32| layout.px(v);

    // Title bar: lesson title · step n/N · step title.
    let bar = layout.title_bar;
    p.fill_rgb([0.0, 0.0, w as f32, bar.h as f32], pal::TITLE_BG);
    let (tx, title_max) = (layout.camera.x as f32, layout.text.right() - layout.camera.x as f32);
    let counter = fill(lang, "step {}/{}", &[&text.step_number, &text.step_count]);
    let sep = "  ·  ";
    let mut px = u(38.0);
    let parts_width = |p: &Canvas, px: f32| {
        p.text_width(text.lesson_title, px)
            + p.text_width(&format!("{sep}{counter}{sep}"), px)
            + p.text_width(text.step_title, px)
    };
    // Smaller until the whole bar fits and the lesson title fits its share of it.
    let lesson_share = title_max * 0.45;
    while px > u(26.0)
        && (parts_width(&p, px) > title_max || p.text_width(text.lesson_title, px) > lesson_share)
    {
        px -= u(1.0);
    }
    let baseline = bar.h as f32 * 0.5 + px * 0.36;
    let lesson_title = p.fit_label(text.lesson_title, px, lesson_share);
    p.run(&lesson_title, tx, baseline, px, pal::TITLE_FG, true);
    let mut x = tx + p.text_width(&lesson_title, px);
    let middle = format!("{sep}{counter}{sep}");
    p.run(&middle, x, baseline, px, pal::TITLE_DIM, false);
    x += p.text_width(&middle, px);
    let step_title = p.fit_label(text.step_title, px, (tx + title_max - x).max(u(100.0)));
    p.run(&step_title, x, baseline, px, pal::TITLE_FG, true);

    // Pictures with frames and probe markers.
    p.image(camera, at(layout.camera));
    p.frame(layout.camera, pal::FRAME, u(2.0));
    match map {
        Some(img) => p.image(img, at(layout.shadow_map)),
        None => {
            let r = layout.shadow_map;
            p.fill_rgb([r.x as f32, r.y as f32, r.w as f32, r.h as f32], pal::PANEL);
            let msg = tr(lang, "no light, no shadow map");
            let m = p.fit_label(msg, u(24.0), r.w as f32 - u(20.0));
            let mx = r.x as f32 + (r.w as f32 - p.text_width(&m, u(24.0))) * 0.5;
            p.run(&m, mx, r.y as f32 + r.h as f32 * 0.5, u(24.0), pal::MUTED, false);
        }
    }
    p.frame(layout.shadow_map, pal::FRAME, u(2.0));
    let marker = u(18.0);
    if let Some((x, y)) = pictures.probe_pixel {
        let c = layout.camera;
        let sx = c.w as f32 / PROBE_FRAME.0 as f32;
        let sy = c.h as f32 / PROBE_FRAME.1 as f32;
        p.marker([c.x as f32 + (x as f32 + 0.5) * sx, c.y as f32 + (y as f32 + 0.5) * sy], marker);
    }
    let probe_light =
        pictures.probe.as_ref().and_then(|r| r.lights.iter().find(|l| l.light == pictures.light));
    if let (Some(l), Some((img, _))) = (probe_light, &pictures.shadow_map) {
        let [x, y, w, h] = map_inner_rect(layout.shadow_map, img.width(), img.height());
        let [u_, v_] = l.shadow_map_uv;
        if (0.0..=1.0).contains(&u_) && (0.0..=1.0).contains(&v_) {
            // On a light with several maps, its uv on the tile it read.
            let views = &pictures.shadow_map_views;
            let [u_, v_] = match (views.len() > 1, l.shadow_view.checked_sub(pictures.first_view)) {
                (true, Some(own)) => crate::views::MapsLayout::of(views).picture_uv(views, own, [u_, v_]),
                _ => [u_, v_],
            };
            p.marker([x + u_ * w, y + v_ * h], marker);
        }
    }

    // Captions.
    let mut first = format!("{}{}", tr(lang, "Camera view: "), view_label(pictures.view, lang));
    if let Some((x, y)) = pictures.probe_pixel {
        first += &fill(lang, "  ·  probe + at ({}, {}) in {}×{}", &[&x, &y, &PROBE_FRAME.0, &PROBE_FRAME.1]);
    }
    let legend = pictures.camera_summary.as_ref().map(|summary| legend_caption(summary, lang));
    caption(&mut p, layout, layout.camera_caption, &first, legend.as_deref());
    let (first, second) = match &pictures.shadow_map {
        Some((img, legend)) => {
            let kind = match pictures.inputs.orthographic {
                true => tr(lang, "orthographic"),
                false => tr(lang, "perspective"),
            };
            let views = &pictures.shadow_map_views;
            let first = match views.first().filter(|_| views.len() > 1) {
                Some(view) => {
                    let kind = tr(lang, if view.cube == 1 { "cube faces" } else { "cascade maps" });
                    let size = view.map_size_texels;
                    fill(
                        lang,
                        "Shadow map: light {} · {} {} of {}²",
                        &[&pictures.light, &views.len(), &kind, &size],
                    )
                }
                None => {
                    fill(lang, "Shadow map: light {} · {}² · {}", &[&pictures.light, &img.width(), &kind])
                }
            };
            let (lo, hi) = (short_num(legend.min), short_num(legend.max));
            let second = fill(lang, "depth from the light {} (dark) .. {} (bright)", &[&lo, &hi]);
            (first, second)
        }
        None => (tr(lang, "Shadow map").to_string(), String::new()),
    };
    caption(&mut p, layout, layout.shadow_map_caption, &first, Some(&second));

    // Diagram and probe numbers.
    p.picture(diagram, at(layout.diagram));
    p.frame(layout.diagram, pal::FRAME, u(2.0));
    probe_panel(&mut p, layout, pictures);

    // Explanation and prompts, at the largest size that fits.
    let text_cut = text_column(&mut p, layout, text);
    Some(Slide { pixmap: p.pixmap, text_cut, shortened: p.shortened })
}

/// A caption in `r`: a bold first line, then a muted second one. Each is 22 units high, smaller
/// (down to 17) where a long one needs it, and cut only past that.
fn caption(p: &mut Canvas, layout: &SlideLayout, r: Rect, first: &str, second: Option<&str>) {
    let (cap, min) = (layout.px(22.0), layout.px(17.0));
    let width = r.w as f32;
    let lines =
        [(first, pal::INK, true, 0.0), (second.unwrap_or(""), pal::MUTED, false, p.leading(cap) * 0.95)];
    for (s, color, bold, below) in lines {
        // A legend of several parts (" · ") too long for the line keeps its leading parts whole
        // rather than ending in the middle of one.
        let mut s = s.to_string();
        while p.text_width(&s, min) > width
            && let Some((head, _)) = s.rsplit_once(" · ")
        {
            s = head.to_string();
        }
        let mut px = cap;
        while px > min && p.text_width(&s, px) > width {
            px = (px - cap * 0.02).max(min);
        }
        let s = p.fit_label(&s, px, width);
        p.run(&s, r.x as f32, r.y as f32 + cap + below, px, color, bold);
    }
}

/// Draws the explanation and the prompts; true when the explanation had to be cut.
fn text_column(p: &mut Canvas, layout: &SlideLayout, text: &SlideText) -> bool {
    let lang = p.lang;
    let u = |v: f32| layout.px(v);
    let r = layout.text;
    let width = r.w as f32;
    let pad = u(22.0);
    let bullet_indent = u(30.0);
    let heading = u(28.0);
    // Paragraph breaks in the lesson text are kept; single newlines inside a paragraph are not.
    let body: String = text.body.split("\n\n").map(join_lines).collect::<Vec<_>>().join("\n");
    let block_at = |p: &Canvas, body_px: f32| {
        let prompt_px = (body_px * 0.93).max(u(18.0));
        TextBlock {
            body: p.wrap(&body, body_px, width),
            prompts: text
                .try_this
                .iter()
                .map(|t| p.wrap(&join_lines(t), prompt_px, width - 2.0 * pad - bullet_indent))
                .collect(),
            body_px,
            prompt_px,
        }
    };
    let heights = |p: &Canvas, b: &TextBlock| {
        let body_h = b.body.len() as f32 * p.leading(b.body_px);
        let lines: usize = b.prompts.iter().map(Vec::len).sum();
        let prompts_h = if b.prompts.is_empty() {
            0.0
        } else {
            pad * 2.0
                + p.leading(heading)
                + lines as f32 * p.leading(b.prompt_px)
                + (b.prompts.len() - 1) as f32 * u(10.0)
        };
        (body_h, prompts_h)
    };
    let mut body_px = u(34.0);
    let mut block = block_at(p, body_px);
    loop {
        let (body_h, prompts_h) = heights(p, &block);
        if body_h + prompts_h + u(20.0) <= r.h as f32 || body_px <= u(16.0) {
            break;
        }
        body_px -= u(0.5);
        block = block_at(p, body_px);
    }
    let (_, prompts_h) = heights(p, &block);

    let mut y = r.y as f32;
    let lead = p.leading(block.body_px);
    let bottom_of_body = r.bottom() - prompts_h - u(20.0);
    // Lines that fit (all of them unless the text is too long even at the smallest size; then
    // the last one shown ends in an ellipsis).
    let fitting = block
        .body
        .iter()
        .enumerate()
        .take_while(|(i, _)| r.y as f32 + *i as f32 * lead + block.body_px <= bottom_of_body)
        .count();
    for (i, line) in block.body.iter().take(fitting).enumerate() {
        // The first line's ascent sits at the top of the column.
        let baseline = y + block.body_px;
        let cut = i + 1 == fitting && fitting < block.body.len();
        let line = if cut { p.fit(&format!("{line} …"), block.body_px, width) } else { line.clone() };
        if !line.is_empty() {
            p.run(&line, r.x as f32, baseline, block.body_px, pal::INK, false);
        }
        y += lead;
    }

    let cut = fitting < block.body.len();
    if block.prompts.is_empty() {
        return cut;
    }
    let top = r.bottom() - prompts_h;
    p.fill_rgb([r.x as f32, top, width, prompts_h], pal::TRY_BG);
    p.fill_rgb([r.x as f32, top, u(6.0), prompts_h], pal::TRY_EDGE);
    let mut y = top + pad + heading;
    p.run(tr(lang, "Try this"), r.x as f32 + pad, y, heading, pal::INK, true);
    y += p.leading(heading) - heading;
    let lead = p.leading(block.prompt_px);
    for prompt in &block.prompts {
        for (i, line) in prompt.iter().enumerate() {
            y += lead;
            if i == 0 {
                p.run("•", r.x as f32 + pad + u(4.0), y, block.prompt_px, pal::TRY_EDGE, true);
            }
            p.run(line, r.x as f32 + pad + bullet_indent, y, block.prompt_px, pal::INK, false);
        }
        y += u(10.0);
    }
    p.frame(Rect { x: r.x, y: top as u32, w: r.w, h: prompts_h as u32 }, pal::TRY_EDGE, u(1.5));
    cut
}

/// Join the lines of a paragraph: with a space between Latin words, directly between Chinese
/// characters.
fn join_lines(s: &str) -> String {
    let mut out = String::new();
    for line in s.lines().map(str::trim).filter(|l| !l.is_empty()) {
        let glue = match (out.chars().last(), line.chars().next()) {
            (Some(a), Some(b)) if !(is_cjk(a) && is_cjk(b)) => " ",
            _ => "",
        };
        out.push_str(glue);
        out.push_str(line);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn legend_captions_shorten_numbers_in_either_language() {
        let en = "blocker-search radius: 0.0000 .. 107.6819 texels (dark blue .. yellow)";
        assert_eq!(
            legend_caption(en, Lang::En),
            "blocker-search radius: 0 .. 108 texels (dark blue .. yellow)"
        );
        let zh = "平均遮挡深度：20.00 .. 40.61 到光源的世界单位（深蓝 .. 黄；灰：没有遮挡物）";
        assert_eq!(
            legend_caption(zh, Lang::Zh),
            "平均遮挡深度：20.0 至 40.6 到光源的世界单位（深蓝 至 黄；灰：没有遮挡物）"
        );
        assert_eq!(legend_caption("a\nb", Lang::En), "a · b");
    }
}
