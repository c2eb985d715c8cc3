//! `index.html`: one self-contained page with every exported slide in order, its text, and
//! links to the pictures (relative paths, so the folder can be moved or served as is).

use crate::i18n::{Lang, fill, tr};
use std::fmt::Write;

/// One exported step.
pub struct SlideEntry {
    pub title: String,
    pub body: String,
    pub try_this: Vec<String>,
    /// Paths relative to the index: slide, camera view, shadow map, diagram.
    pub slide: String,
    pub camera: String,
    pub shadow_map: String,
    pub diagram: String,
}

/// One exported lesson.
pub struct LessonEntry {
    pub id: String,
    pub title: String,
    pub summary: String,
    pub slides: Vec<SlideEntry>,
}

/// Escape text for HTML element content and quoted attribute values.
pub fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// Escape text and show `code` spans in a fixed-width font.
pub fn rich(s: &str) -> String {
    if !s.matches('`').count().is_multiple_of(2) {
        return escape(s);
    }
    s.split('`')
        .enumerate()
        .map(|(i, part)| if i % 2 == 1 { format!("<code>{}</code>", escape(part)) } else { escape(part) })
        .collect()
}

const STYLE: &str = "
body{margin:0;font-family:system-ui,'Noto Sans CJK SC','Noto Sans',sans-serif;
background:#eceee9;color:#14181c;line-height:1.5}
header{background:#263238;color:#fff;padding:1rem 2rem}
header h1{margin:0;font-size:1.6rem}
header p{margin:.3rem 0 0;color:#b0bec5}
nav{padding:1rem 2rem;background:#fafaf6;border-bottom:1px solid #ccc}
nav ol{margin:0;padding-left:1.4rem}
main{padding:0 2rem 4rem;max-width:1400px;margin:auto}
h2{margin:2.5rem 0 .2rem}
.summary{margin:0 0 1rem;color:#545c64}
section.slide{background:#fafaf6;margin:1.5rem 0;padding:1rem 1.2rem;
border-left:6px solid #263238;scroll-margin-top:.5rem}
section.slide:focus,section.slide.current{border-left-color:#e69f00;outline:none}
section.slide h3{margin:.2rem 0 .6rem}
section.slide img{width:100%;height:auto;display:block;border:1px solid #a0a6ac}
.try{background:#fff3d6;border-left:4px solid #e69f00;padding:.4rem 1rem;margin:.8rem 0}
.try h4{margin:.3rem 0}
.files{font-size:.9rem;color:#545c64}
.files a{margin-right:1rem}
.hint{font-size:.9rem;color:#b0bec5}
code{font-family:ui-monospace,'DejaVu Sans Mono',monospace;background:#e8eae4;padding:0 .2em}
";

const SCRIPT: &str = "
const slides=[...document.querySelectorAll('section.slide')];
let current=-1;
function go(i){if(!slides.length)return;current=Math.max(0,Math.min(slides.length-1,i));
slides.forEach((s,k)=>s.classList.toggle('current',k===current));
slides[current].scrollIntoView({block:'start'});history.replaceState(null,'','#'+slides[current].id);}
document.addEventListener('keydown',e=>{if(e.altKey||e.ctrlKey||e.metaKey)return;
if(e.key==='ArrowRight'||e.key==='PageDown'){go(current+1);e.preventDefault();}
if(e.key==='ArrowLeft'||e.key==='PageUp'){go(current-1);e.preventDefault();}});
const start=slides.findIndex(s=>'#'+s.id===location.hash);if(start>=0)current=start;
";

/// The whole page.
pub fn index_html(lang: Lang, lessons: &[LessonEntry]) -> String {
    let mut h = String::new();
    let title = tr(lang, "shadowlab lessons");
    let count: usize = lessons.iter().map(|l| l.slides.len()).sum();
    let _ = write!(
        h,
        "<!DOCTYPE html>\n<html lang=\"{}\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>{}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n<header>\n<h1>{}</h1>\n<p>{}</p>\n\
         <p class=\"hint\">{}</p>\n</header>\n<nav>\n<ol>\n",
        // The page's language tag, not a translation.
        match lang {
            Lang::En => "en",
            Lang::Zh => "zh-Hans",
        },
        escape(title),
        escape(title),
        escape(&fill(lang, "{} lessons, {} slides", &[&lessons.len(), &count])),
        escape(tr(lang, "Left / Right arrow keys: previous / next slide")),
    );
    for lesson in lessons {
        let _ = writeln!(
            h,
            "<li><a href=\"#{}\">{}</a> ({})</li>",
            escape(&lesson.id),
            escape(&lesson.title),
            lesson.slides.len()
        );
    }
    h.push_str("</ol>\n</nav>\n<main>\n");
    for lesson in lessons {
        let _ = writeln!(
            h,
            "<h2 id=\"{}\">{}</h2>\n<p class=\"summary\">{}</p>",
            escape(&lesson.id),
            escape(&lesson.title),
            escape(&lesson.summary)
        );
        let n = lesson.slides.len();
        for (i, s) in lesson.slides.iter().enumerate() {
            let heading = fill(lang, "Step {}/{}: {}", &[&(i + 1), &n, &s.title]);
            let _ = write!(
                h,
                "<section class=\"slide\" id=\"{}-{}\" tabindex=\"-1\">\n<h3>{}</h3>\n\
                 <a href=\"{}\"><img src=\"{}\" alt=\"{}\" loading=\"lazy\"></a>\n<p>{}</p>\n",
                escape(&lesson.id),
                i + 1,
                escape(&heading),
                escape(&s.slide),
                escape(&s.slide),
                escape(&heading),
                rich(&s.body).replace('\n', "<br>\n"),
            );
            if !s.try_this.is_empty() {
                let _ = write!(h, "<div class=\"try\">\n<h4>{}</h4>\n<ul>\n", escape(tr(lang, "Try this")));
                for t in &s.try_this {
                    let _ = writeln!(h, "<li>{}</li>", rich(t));
                }
                h.push_str("</ul>\n</div>\n");
            }
            let _ = writeln!(
                h,
                "<p class=\"files\"><a href=\"{}\">{}</a><a href=\"{}\">{}</a>\
                 <a href=\"{}\">{}</a><a href=\"{}\">{}</a></p>\n</section>",
                escape(&s.slide),
                escape(tr(lang, "slide")),
                escape(&s.camera),
                escape(tr(lang, "camera view@slides")),
                escape(&s.shadow_map),
                escape(tr(lang, "shadow map")),
                escape(&s.diagram),
                escape(tr(lang, "diagram")),
            );
        }
    }
    let _ = write!(h, "</main>\n<script>{SCRIPT}</script>\n</body>\n</html>\n");
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_is_escaped_and_paths_are_relative() {
        let lesson = LessonEntry {
            id: "a-b".into(),
            title: "<b>&".into(),
            summary: "\"quoted\"".into(),
            slides: vec![SlideEntry {
                title: "x < y".into(),
                body: "1 & 2".into(),
                try_this: vec!["<script>".into()],
                slide: "a-b/step-01-slide.png".into(),
                camera: "a-b/step-01-camera.png".into(),
                shadow_map: "a-b/step-01-shadow-map.png".into(),
                diagram: "a-b/step-01-diagram.png".into(),
            }],
        };
        let html = index_html(Lang::Zh, &[lesson]);
        assert!(html.contains("<html lang=\"zh-Hans\">"));
        assert!(html.contains("&lt;b&gt;&amp;"));
        assert!(html.contains("&quot;quoted&quot;"));
        assert!(html.contains("&lt;script&gt;"));
        assert!(html.contains("src=\"a-b/step-01-slide.png\""));
        assert_eq!(html.matches("<script>").count(), 1);
        assert_eq!(rich("set `a<b` now"), "set <code>a&lt;b</code> now");
        assert_eq!(rich("one ` tick"), "one ` tick");
    }
}
