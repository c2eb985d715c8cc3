//! Fixed strings in Simplified Chinese. English is the key: the code reads in English and [`tr`]
//! looks the Chinese up. Lesson text has its own translations (lessons/*.toml).
//! Where one English text needs two Chinese ones, the key ends in a context that is never shown:
//! "visibility@slides" reads "visibility" in English and has its own entry.
//! `tests/app.rs` walks the app in Chinese and fails on English text left on screen; the
//! diagram tests do the same for every label a diagram draws.

mod class_zh;
mod diagrams_zh;
mod homework_zh;
mod page_zh;
mod slides_zh;
mod ui_zh;

use std::collections::HashMap;
use std::fmt::Display;
use std::sync::OnceLock;

/// The languages shadowlab speaks.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
pub enum Lang {
    #[default]
    En,
    Zh,
}

impl Lang {
    pub fn code(self) -> &'static str {
        match self {
            Lang::En => "en",
            Lang::Zh => "zh",
        }
    }
    pub fn from_code(code: &str) -> Option<Lang> {
        match code {
            "en" => Some(Lang::En),
            "zh" => Some(Lang::Zh),
            _ => None,
        }
    }
}

/// Every entry of every table.
fn entries() -> impl Iterator<Item = &'static (&'static str, &'static str)> {
    ui_zh::UI
        .iter()
        .chain(diagrams_zh::DIAGRAMS)
        .chain(slides_zh::SLIDES)
        .chain(homework_zh::HOMEWORK)
        .chain(page_zh::PAGE)
        .chain(class_zh::CLASS)
}

fn table() -> &'static HashMap<&'static str, &'static str> {
    static TABLE: OnceLock<HashMap<&'static str, &'static str>> = OnceLock::new();
    TABLE.get_or_init(|| entries().copied().collect())
}

/// The English of `key`: the key without its context (`@...` at the end), if it has one.
fn english(key: &str) -> &str {
    match key.rsplit_once('@') {
        Some((en, _)) if table().contains_key(key) => en,
        _ => key,
    }
}

/// `en` in `lang`. A string missing from the table shows in English (and fails the tests that
/// look for English in the Chinese app and diagrams).
pub fn tr(lang: Lang, en: &str) -> &str {
    match lang {
        Lang::En => english(en),
        Lang::Zh => table().get(en).copied().unwrap_or_else(|| english(en)),
    }
}

/// `template` in `lang` with each hole replaced by the next of `args`, in order (the Chinese
/// templates keep the English order of their values). A hole is `{}`, or `{:.N}` for a number
/// the two languages show with different decimals.
pub fn fill(lang: Lang, template: &'static str, args: &[&dyn Display]) -> String {
    let mut out = String::new();
    let mut rest = tr(lang, template);
    let mut args = args.iter();
    while let Some((before, hole, after)) = next_hole(rest) {
        out.push_str(before);
        match (args.next(), hole.strip_prefix("{:.").and_then(|h| h.trim_end_matches('}').parse().ok())) {
            (Some(a), Some(decimals)) => out.push_str(&format!("{a:.decimals$}")),
            (Some(a), None) => out.push_str(&a.to_string()),
            (None, _) => out.push_str(hole),
        }
        rest = after;
    }
    out.push_str(rest);
    out
}

/// The first hole in `s` (`{}` or `{:.N}`): the text before it, the hole, the text after it.
fn next_hole(s: &str) -> Option<(&str, &str, &str)> {
    let mut from = 0;
    while let Some(start) = s[from..].find('{').map(|i| from + i) {
        let tail = &s[start..];
        let len = if tail.starts_with("{}") {
            Some(2)
        } else {
            tail.strip_prefix("{:.").and_then(|t| {
                let digits = t.bytes().take_while(u8::is_ascii_digit).count();
                (digits > 0 && t[digits..].starts_with('}')).then_some(4 + digits)
            })
        };
        if let Some(len) = len {
            return Some((&s[..start], &s[start..start + len], &s[start + len..]));
        }
        from = start + 1;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn is_chinese(zh: &str) -> bool {
        zh.chars().any(|c| ('\u{4e00}'..='\u{9fff}').contains(&c) || "←→".contains(c))
    }

    #[test]
    fn every_entry_is_translated_once() {
        let mut seen = std::collections::HashSet::new();
        for (en, zh) in entries() {
            assert!(seen.insert(en), "`{en}` is in the table twice");
            assert!(is_chinese(zh), "`{en}` -> `{zh}`");
            let holes = |mut s: &str| {
                let mut n = 0;
                while let Some((_, _, after)) = next_hole(s) {
                    (n, s) = (n + 1, after);
                }
                n
            };
            assert_eq!(holes(en), holes(zh), "`{en}` -> `{zh}`: the values do not match");
            if let Some((text, context)) = en.rsplit_once('@') {
                assert!(!text.is_empty() && !context.is_empty(), "`{en}`: text@context");
                assert!(!table().contains_key(text) || table()[text] != *zh, "`{en}` needs no context");
            }
        }
    }

    /// The names the files and the command line use are shown translated: every view, diagram
    /// tab and value of the inspector's combo boxes has an entry.
    #[test]
    fn every_view_diagram_and_setting_name_is_translated() {
        use crate::scene::{BiasMode, DepthStorage, Kernel, Technique};
        let names = crate::views::View::ALL
            .iter()
            .map(|v| v.name())
            .chain(crate::diagrams::DiagramKind::ALL.iter().map(|d| d.id()))
            .chain(Technique::ALL.iter().map(|t| t.name()))
            .chain(BiasMode::ALL.iter().map(|b| b.name()))
            .chain(Kernel::ALL.iter().map(|k| k.name()))
            .chain(DepthStorage::ALL.iter().map(|d| d.name()));
        for name in names {
            assert!(table().contains_key(name), "`{name}` has no Chinese label in ui_zh.rs");
        }
    }

    #[test]
    fn fill_puts_the_values_in_order() {
        assert_eq!(fill(Lang::En, "search r = {} texels", &[&2.5]), "search r = 2.5 texels");
        assert_eq!(fill(Lang::Zh, "search r = {} texels", &[&2.5]), "搜索半径 r = 2.5 纹素");
        assert_eq!(fill(Lang::En, "{} of {}", &[&1]), "1 of {}");
        assert_eq!(fill(Lang::En, "{:.3} and {} {:.1}", &[&0.5, &0.25, &2.0]), "0.500 and 0.25 2.0");
        assert_eq!(fill(Lang::En, "{a} {:.x} {:.2", &[&1.0]), "{a} {:.x} {:.2");
    }

    #[test]
    fn a_context_picks_the_entry_and_is_never_shown() {
        assert_eq!(tr(Lang::En, "visibility@slides"), "visibility");
        assert_ne!(tr(Lang::Zh, "visibility@slides"), tr(Lang::Zh, "visibility"));
        assert_eq!(tr(Lang::En, "a@b"), "a@b");
        assert_eq!(tr(Lang::Zh, "a@b"), "a@b");
    }
}
