//! The class report's page, in English or Chinese: the findings ranked by how many students have
//! them, a table of the students, then a section per student (their light, their findings, their
//! pictures). Static HTML with its style inline: no script, nothing fetched from elsewhere.

use super::{
    ClassRow, FindingPart, Ranked, Severity, Status, StudentReport, WidthPart, description, lesson_of, number,
};
use crate::export::html::{escape, rich};
use crate::i18n::{Lang, fill, tr};
use std::fmt::Write;

const STYLE: &str = "
body{margin:0;font-family:system-ui,'Noto Sans CJK SC','Noto Sans',sans-serif;
background:#eceee9;color:#14181c;line-height:1.5}
header{background:#263238;color:#fff;padding:1rem 2rem}
header h1{margin:0;font-size:1.6rem}
header p{margin:.3rem 0 0;color:#b0bec5}
header a{color:#ffd180}
main{padding:0 2rem 4rem;max-width:1400px;margin:auto}
h2{margin:2rem 0 .6rem}
table{border-collapse:collapse;background:#fafaf6;width:100%}
th,td{border:1px solid #c8ccc4;padding:.3rem .5rem;text-align:left;vertical-align:top}
th{background:#e0e3dc}
td.n{text-align:right;white-space:nowrap}
section.student{background:#fafaf6;margin:1.5rem 0;padding:1rem 1.2rem;
border-left:6px solid #263238}
section.student h3{margin:.2rem 0 .4rem}
.status{display:inline-block;padding:0 .5em;border-radius:.3em;color:#fff;background:#546e7a;
white-space:nowrap}
.status.s-ok{background:#2e7d32}.status.s-compile{background:#c62828}
.status.s-refuse{background:#6a1b9a}.status.s-fail{background:#ad1457}.status.s-time{background:#ef6c00}
.message{font-family:ui-monospace,'DejaVu Sans Mono',monospace;font-size:.9rem;color:#545c64;
overflow-wrap:anywhere}
ul.findings{padding-left:1.2rem}
ul.findings li{margin:.5rem 0}
.sev-m{color:#b71c1c;font-weight:600}.sev-l{color:#6d4c41;font-weight:600}
.figures,.lesson{font-size:.9rem;color:#545c64}
.pictures{display:flex;flex-wrap:wrap;gap:.8rem}
.pictures figure{margin:0}
.pictures img{width:240px;height:auto;display:block;border:1px solid #a0a6ac}
.pictures figcaption{font-size:.85rem;color:#545c64}
code{font-family:ui-monospace,'DejaVu Sans Mono',monospace;background:#e8eae4;padding:0 .2em}
";

/// The page's language tag, not a translation.
fn lang_tag(lang: Lang) -> &'static str {
    match lang {
        Lang::En => "en",
        Lang::Zh => "zh-Hans",
    }
}

/// Between the items of a list (punctuation, not a translation).
fn list_separator(lang: Lang) -> &'static str {
    match lang {
        Lang::En => ", ",
        Lang::Zh => "，",
    }
}

/// A path under the page's folder as a relative link: each part percent-encoded (a name may hold
/// `#`, `?`, `%` or spaces), then escaped for the attribute.
fn href(parts: &[&str]) -> String {
    let mut out = String::new();
    for (i, part) in parts.iter().enumerate() {
        if i > 0 {
            out.push('/');
        }
        for byte in part.bytes() {
            if byte.is_ascii_alphanumeric() || b"-._~".contains(&byte) {
                out.push(byte as char);
            } else {
                let _ = write!(out, "%{byte:02X}");
            }
        }
    }
    escape(&out)
}

/// The anchor of student `i`'s section (names may hold anything: the anchor is a number).
fn anchor(i: usize) -> String {
    format!("student-{}", i + 1)
}

fn severity(lang: Lang, s: Severity) -> String {
    let (css, key) = match s {
        Severity::Mistake => ("sev-m", "mistake@class"),
        Severity::Latent => ("sev-l", "latent@class"),
    };
    format!("<span class=\"{css}\">{}</span>", escape(tr(lang, key)))
}

fn lesson_text(lang: Lang, id: &str, finding: Option<&FindingPart>) -> String {
    lesson_of(id, finding)
        .map_or(String::new(), |(lesson, step)| fill(lang, "lesson {}, step {}", &[&lesson, &step]))
}

/// The whole page in `lang`; `reports_in` is the language of the students' explanations.
pub(super) fn html(lang: Lang, rows: &[ClassRow], reports_in: Lang) -> String {
    let mut h = String::new();
    let title = tr(lang, "Class report");
    let (other, other_name, other_tag) = match lang {
        Lang::En => (super::INDEX_ZH, "中文", lang_tag(Lang::Zh)),
        Lang::Zh => (super::INDEX_EN, "English", lang_tag(Lang::En)),
    };
    let counts: Vec<String> = Status::ALL
        .iter()
        .map(|s| (s, rows.iter().filter(|r| r.status == *s).count()))
        .filter(|(_, n)| *n > 0)
        .map(|(s, n)| format!("{n} {}", s.shown(lang)))
        .collect();
    let _ = write!(
        h,
        "<!DOCTYPE html>\n<html lang=\"{}\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>{}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n<header>\n<h1>{}</h1>\n\
         <p>{}: {}</p>\n<p><a href=\"{other}\" hreflang=\"{other_tag}\" lang=\"{other_tag}\">{other_name}</a></p>\n\
         </header>\n<main>\n",
        lang_tag(lang),
        escape(title),
        escape(title),
        escape(&fill(lang, "{} submissions", &[&rows.len()])),
        escape(&counts.join(list_separator(lang))),
    );
    // The bonus: who made several lights or moved one, and how their lights fared on checks of
    // their own.
    let several: Vec<(usize, usize, usize)> =
        rows.iter().filter_map(|r| r.report.as_ref().filter(|r| r.compiled)?.bonus()).collect();
    if !several.is_empty() {
        let checked: usize = several.iter().map(|(_, c, _)| c).sum();
        let clean: usize = several.iter().map(|(.., n)| n).sum();
        let _ = writeln!(
            h,
            "<p class=\"bonus\">{}</p>",
            escape(&fill(
                lang,
                "Submissions with several or moving lights (the bonus): {}; of their {} light checks, {} without a finding",
                &[&several.len(), &checked, &clean]
            ))
        );
    }
    ranked_table(&mut h, lang, rows);
    students_table(&mut h, lang, rows);
    for (i, row) in rows.iter().enumerate() {
        student(&mut h, lang, i, row, reports_in);
    }
    h.push_str("</main>\n</body>\n</html>\n");
    h
}

fn ranked_table(h: &mut String, lang: Lang, rows: &[ClassRow]) {
    let _ = writeln!(h, "<h2 id=\"findings\">{}</h2>", escape(tr(lang, "Findings across the class")));
    let ranked = super::ranked(rows);
    if ranked.is_empty() {
        let _ = writeln!(h, "<p>{}</p>", escape(tr(lang, "No student has a finding.")));
        return;
    }
    let headings =
        ["finding", "kind@class", "students", "share of the class", "what it is", "taught in", "who"];
    h.push_str("<table class=\"ranked\">\n<tr>");
    for heading in headings {
        let _ = write!(h, "<th>{}</th>", escape(tr(lang, heading)));
    }
    h.push_str("</tr>\n");
    for Ranked { id, severity: kind, students } in &ranked {
        let share = 100.0 * students.len() as f64 / rows.len().max(1) as f64;
        let names: Vec<String> = students
            .iter()
            .map(|&i| format!("<a href=\"#{}\">{}</a>", anchor(i), escape(&rows[i].name)))
            .collect();
        let example =
            students.first().and_then(|&i| rows[i].report.as_ref()?.findings.iter().find(|f| f.id == *id));
        let _ = writeln!(
            h,
            "<tr id=\"finding-{}\"><td><code>{}</code></td><td>{}</td><td class=\"n\">{}</td>\
             <td class=\"n\">{share:.0}%</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            escape(id),
            escape(id),
            severity(lang, *kind),
            students.len(),
            escape(description(lang, id).unwrap_or("")),
            escape(&lesson_text(lang, id, example)),
            names.join(list_separator(lang)),
        );
    }
    h.push_str("</table>\n");
}

fn students_table(h: &mut String, lang: Lang, rows: &[ClassRow]) {
    let _ = writeln!(
        h,
        "<h2 id=\"students\">{}</h2>\n<table class=\"students\">\n<tr>",
        escape(tr(lang, "Students"))
    );
    for heading in ["name@class", "status@class", "mistakes", "latent findings", "message@class"] {
        let _ = write!(h, "<th>{}</th>", escape(tr(lang, heading)));
    }
    h.push_str("</tr>\n");
    for (i, row) in rows.iter().enumerate() {
        let count = |s: Severity| {
            row.report
                .as_ref()
                .filter(|r| r.compiled)
                .map_or(String::new(), |r| r.findings.iter().filter(|f| f.severity == s).count().to_string())
        };
        let _ = writeln!(
            h,
            "<tr><td><a href=\"#{}\">{}</a></td><td><span class=\"status {}\">{}</span></td>\
             <td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"message\">{}</td></tr>",
            anchor(i),
            escape(&row.name),
            row.status.css(),
            escape(row.status.shown(lang)),
            count(Severity::Mistake),
            count(Severity::Latent),
            escape(&row.message),
        );
    }
    h.push_str("</table>\n");
}

/// What the student's light was, in one line.
fn light_line(lang: Lang, report: &StudentReport) -> Option<String> {
    let light = report.light.as_ref()?;
    let mut parts = vec![fill(lang, "light from {}", &[&light.from])];
    if let Some(f) = &light.frustum {
        let depth = f.depth_range_world.map_or("n/a".to_string(), number);
        parts.push(match (f.kind.as_str(), f.width_world, f.fov_deg) {
            ("orthographic", Some(w), _) => {
                fill(lang, "orthographic frustum {} wide, depth range {}", &[&number(w), &depth])
            }
            ("perspective", _, Some(fov)) => {
                fill(lang, "perspective frustum of {}°, depth range {}", &[&number(fov), &depth])
            }
            (kind, _, _) => fill(lang, "{} frustum, depth range {}", &[&kind, &depth]),
        });
    }
    let width = report.light_width.as_ref();
    parts.push(match (width.and_then(WidthPart::measured), width.and_then(|w| w.narrower_than_world)) {
        (_, Some(bound)) => fill(
            lang,
            "their penumbrae imply a light narrower than {}, too narrow for this map",
            &[&number(bound)],
        ),
        (Some(w), None) => fill(lang, "their penumbrae imply a light {} wide", &[&number(w)]),
        (None, None) => tr(lang, "no light width implied").to_string(),
    });
    let mut line = escape(&parts.join(match lang {
        Lang::En => "; ",
        Lang::Zh => "；",
    }));
    if let Some(error) = &light.error {
        let _ = write!(line, "<br>{}", escape(&fill(lang, "their light was not used: {}", &[error])));
    }
    Some(line)
}

/// The bonus: each light the page made, with what its own check found.
fn lights_list(h: &mut String, lang: Lang, report: &StudentReport) {
    let _ = writeln!(h, "<p>{}</p>\n<ul class=\"lights\">", escape(tr(lang, "The lights their page made:")));
    for light in &report.lights {
        let verdict = light.verdict(
            tr(lang, "no findings"),
            tr(lang, "not checked (a point light, or a light without matrices)"),
            |t| fill(lang, "at {} s", &[&t]),
        );
        let _ = writeln!(
            h,
            "<li><code>{}</code> {}: {}</li>",
            escape(&light.made_at),
            escape(&light.kind),
            escape(&verdict)
        );
    }
    h.push_str("</ul>\n");
}

fn student(h: &mut String, lang: Lang, i: usize, row: &ClassRow, reports_in: Lang) {
    let _ = write!(
        h,
        "<section class=\"student\" id=\"{}\">\n<h3>{} <span class=\"status {}\">{}</span></h3>\n",
        anchor(i),
        escape(&row.name),
        row.status.css(),
        escape(row.status.shown(lang)),
    );
    if !row.message.is_empty() {
        let _ = writeln!(h, "<p class=\"message\">{}</p>", escape(&row.message));
    }
    let report = row.report.as_ref();
    if let Some(error) = report.and_then(|r| r.error.as_ref()).filter(|_| row.message.is_empty()) {
        let line = error.line.map_or(String::new(), |l| format!(":{l}"));
        let _ =
            writeln!(h, "<p class=\"message\">{}{line}: {}</p>", escape(&error.file), escape(&error.message));
    }
    if let Some(report) = report.filter(|r| r.compiled) {
        if let Some(line) = light_line(lang, report) {
            let _ = writeln!(h, "<p>{line}</p>");
        }
        if report.bonus().is_some() {
            lights_list(h, lang, report);
        }
        findings(h, lang, report, reports_in);
    }
    if !row.pictures.is_empty() {
        h.push_str("<div class=\"pictures\">\n");
        for picture in &row.pictures {
            let caption = escape(tr(lang, picture_caption(picture)));
            let link = href(&[&row.folder, picture]);
            let _ = writeln!(
                h,
                "<figure><a href=\"{link}\"><img src=\"{link}\" alt=\"{caption}\" loading=\"lazy\"></a>\
                 <figcaption>{caption}</figcaption></figure>"
            );
        }
        h.push_str("</div>\n");
    }
    h.push_str("</section>\n");
}

fn picture_caption(file: &str) -> &'static str {
    match file {
        "student.png" => "their picture",
        "student_lossless_map.png" => "their picture over a lossless map",
        "ground_truth.png" => "ground truth",
        _ => "difference to the ground truth",
    }
}

fn findings(h: &mut String, lang: Lang, report: &StudentReport, reports_in: Lang) {
    if report.findings.is_empty() {
        let _ = writeln!(h, "<p>{}</p>", escape(tr(lang, "No findings.")));
        return;
    }
    h.push_str("<ul class=\"findings\">\n");
    for f in &report.findings {
        // The report's own explanation where it is in the page's language, else the description.
        let text = match description(lang, &f.id) {
            Some(text) if lang != reports_in => escape(text),
            _ => rich(&f.explanation),
        };
        let figures: Vec<String> = f
            .figures
            .iter()
            .map(|(name, v)| format!("{} = {}", escape(name), v.map_or("n/a".to_string(), number)))
            .collect();
        let _ = writeln!(
            h,
            "<li><a href=\"#finding-{}\"><code>{}</code></a> {}: {text}<br>\
             <span class=\"figures\">{}</span> <span class=\"lesson\">({})</span></li>",
            escape(&f.id),
            escape(&f.id),
            severity(lang, f.severity),
            figures.join(" · "),
            escape(&lesson_text(lang, &f.id, Some(f))),
        );
    }
    h.push_str("</ul>\n");
}
