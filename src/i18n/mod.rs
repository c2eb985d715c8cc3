//! Fixed strings in Simplified Chinese. English is the key: the code reads in English and [`tr`]
//! looks the Chinese up. Lesson text has its own translations (lessons/*.toml).
//! `tests/app.rs` walks the app in Chinese and fails on English text left on screen; the
//! diagram tests do the same for every label a diagram draws.

mod diagrams_zh;
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

fn table() -> &'static HashMap<&'static str, &'static str> {
    static TABLE: OnceLock<HashMap<&'static str, &'static str>> = OnceLock::new();
    TABLE.get_or_init(|| ui_zh::UI.iter().chain(diagrams_zh::DIAGRAMS).copied().collect())
}

/// `en` in `lang`. A string missing from the table shows in English (and fails the tests that
/// look for English in the Chinese app and diagrams).
pub fn tr(lang: Lang, en: &str) -> &str {
    match lang {
        Lang::En => en,
        Lang::Zh => table().get(en).copied().unwrap_or(en),
    }
}

/// `template` in `lang` with each `{}` replaced by the next of `args`, in order (the Chinese
/// templates keep the English order of their values).
pub fn fill(lang: Lang, template: &'static str, args: &[&dyn Display]) -> String {
    let mut out = String::new();
    let mut parts = tr(lang, template).split("{}");
    out.push_str(parts.next().unwrap_or(""));
    for (i, part) in parts.enumerate() {
        match args.get(i) {
            Some(a) => out.push_str(&a.to_string()),
            None => out.push_str("{}"),
        }
        out.push_str(part);
    }
    out
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
        for (en, zh) in ui_zh::UI.iter().chain(diagrams_zh::DIAGRAMS) {
            assert!(seen.insert(en), "`{en}` is in the table twice");
            assert!(is_chinese(zh), "`{en}` -> `{zh}`");
            let holes = |s: &str| s.matches("{}").count();
            assert_eq!(holes(en), holes(zh), "`{en}` -> `{zh}`: the values do not match");
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
    }
}
