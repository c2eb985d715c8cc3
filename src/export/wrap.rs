//! Line breaking for the slides: between words for Latin text, between any two characters for
//! Chinese (keeping Latin words, numbers and closing punctuation with their neighbours).

use crate::diagrams::TextRenderer;

/// Han ideographs, kana, CJK punctuation and full-width forms: a line may break on either side.
pub fn is_cjk(c: char) -> bool {
    matches!(c as u32,
        0x2E80..=0x2FDF | 0x3000..=0x303F | 0x3040..=0x30FF | 0x3400..=0x4DBF | 0x4E00..=0x9FFF
        | 0xF900..=0xFAFF | 0xFE30..=0xFE4F | 0xFF00..=0xFFEF)
}

/// Punctuation that must not start a line.
fn closing(c: char) -> bool {
    "，。、；：！？）》」』】〕”’…,.;:!?)]}%·".contains(c)
}

/// Punctuation that must not end a line.
fn opening(c: char) -> bool {
    "（《「『【〔“‘([{".contains(c)
}

/// Pieces a line may break between, each with the spaces before it.
fn tokens(text: &str) -> Vec<(bool, String)> {
    let mut out: Vec<(bool, String)> = Vec::new();
    let mut space_before = false;
    let mut glue_next = false;
    for c in text.chars() {
        if c.is_whitespace() {
            space_before = !out.is_empty();
            glue_next = false;
            continue;
        }
        let last_is_word = out.last().is_some_and(|(_, t)| t.chars().last().is_some_and(|l| !is_cjk(l)));
        let join = match out.last_mut() {
            Some(_) if space_before => false,
            Some(_) if glue_next || closing(c) => true,
            // Latin words, numbers and symbols stay whole.
            Some(_) => !is_cjk(c) && last_is_word,
            None => false,
        };
        match out.last_mut() {
            Some((_, t)) if join => t.push(c),
            _ => out.push((space_before, c.to_string())),
        }
        space_before = false;
        glue_next = opening(c);
    }
    out
}

/// Split `text` into lines no wider than `max_width_px` at `px` (a single piece wider than
/// that is cut between characters). Newlines in `text` start new paragraphs.
pub fn wrap(text: &TextRenderer, s: &str, px: f32, max_width_px: f32) -> Vec<String> {
    let mut lines = Vec::new();
    for paragraph in s.split('\n') {
        let mut line = String::new();
        for (space, token) in tokens(paragraph) {
            let candidate = if line.is_empty() {
                token.clone()
            } else if space {
                format!("{line} {token}")
            } else {
                format!("{line}{token}")
            };
            if fits(text, &candidate, px, max_width_px) {
                line = candidate;
                continue;
            }
            if !line.is_empty() {
                lines.push(std::mem::take(&mut line));
            }
            if fits(text, &token, px, max_width_px) {
                line = token;
                continue;
            }
            // Cut an over-long piece between characters.
            for c in token.chars() {
                let next = format!("{line}{c}");
                if !line.is_empty() && !fits(text, &next, px, max_width_px) {
                    lines.push(std::mem::take(&mut line));
                    line.push(c);
                } else {
                    line = next;
                }
            }
        }
        lines.push(line);
    }
    lines
}

fn fits(text: &TextRenderer, token: &str, px: f32, max_width_px: f32) -> bool {
    text.measure(token, px).width_px <= max_width_px
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pieces(s: &str) -> Vec<String> {
        tokens(s).into_iter().map(|(_, t)| t).collect()
    }

    #[test]
    fn latin_breaks_between_words_and_chinese_between_characters() {
        assert_eq!(pieces("near surfaces are dark."), ["near", "surfaces", "are", "dark."]);
        assert_eq!(pieces("近处暗，远处亮。"), ["近", "处", "暗，", "远", "处", "亮。"]);
        assert_eq!(
            pieces("阴影贴图（shadow map）很重要"),
            ["阴", "影", "贴", "图", "（shadow", "map）", "很", "重", "要"]
        );
        assert_eq!(pieces("偏移 0.002 太小"), ["偏", "移", "0.002", "太", "小"]);
    }

    #[test]
    fn lines_fit_the_width() {
        let t = TextRenderer::shared();
        let s = "The light renders the scene like a camera, but keeps only depth: \
                 for every texel, the distance to the nearest surface.";
        let lines = wrap(t, s, 20.0, 200.0);
        assert!(lines.len() > 3);
        for l in &lines {
            assert!(t.measure(l, 20.0).width_px <= 200.0, "{l}");
        }
        assert_eq!(lines.join(" "), s);
        let long = wrap(t, "aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa", 20.0, 100.0);
        assert!(long.len() > 1);
    }
}
