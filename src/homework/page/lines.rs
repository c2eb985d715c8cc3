//! Lines of a student's light script the report points to, read from its text: where
//! `CalcLightMVP` is defined, and its last `return`.

/// The line that defines `CalcLightMVP` (a method, or an assignment of a function), not a
/// comment or a call.
pub(super) fn method_line(text: &str) -> Option<usize> {
    const NAME: &str = "CalcLightMVP";
    text.lines()
        .position(|line| {
            let code = line.trim_start();
            if code.starts_with("//") || code.starts_with('*') || code.starts_with("/*") {
                return false;
            }
            code.match_indices(NAME).any(|(at, _)| {
                let after = code[at + NAME.len()..].trim_start();
                let called = code[..at].ends_with('.');
                after.starts_with('=') || (!called && (after.starts_with('(') || after.starts_with(':')))
            })
        })
        .map(|i| i + 1)
}

/// The line of the last `return` in the function whose definition starts on `from` (1-based):
/// its body's braces matched past strings, template literals and comments.
pub(super) fn last_return(text: &str, from: usize) -> Option<usize> {
    let lines: Vec<&str> = text.lines().collect();
    let (mut depth, mut opened, mut found) = (0usize, false, None);
    let mut in_block_comment = false;
    for (index, line) in lines.iter().enumerate().skip(from.checked_sub(1)?) {
        let chars: Vec<char> = line.chars().collect();
        let mut i = 0;
        let mut quote: Option<char> = None;
        while i < chars.len() {
            let (c, next) = (chars[i], chars.get(i + 1).copied());
            if in_block_comment {
                if c == '*' && next == Some('/') {
                    in_block_comment = false;
                    i += 1;
                }
            } else if let Some(q) = quote {
                if c == '\\' {
                    i += 1;
                } else if c == q {
                    quote = None;
                }
            } else if c == '/' && next == Some('/') {
                break;
            } else if c == '/' && next == Some('*') {
                in_block_comment = true;
                i += 1;
            } else if matches!(c, '\'' | '"' | '`') {
                quote = Some(c);
            } else if c == '{' {
                depth += 1;
                opened = true;
            } else if c == '}' {
                depth = depth.saturating_sub(1);
                if opened && depth == 0 {
                    return found;
                }
            } else if opened
                && chars[i..].starts_with(&['r', 'e', 't', 'u', 'r', 'n'])
                && (i == 0 || !(chars[i - 1].is_alphanumeric() || chars[i - 1] == '_'))
                && !chars.get(i + 6).is_some_and(|c| c.is_alphanumeric() || *c == '_')
            {
                found = Some(index + 1);
            }
            i += 1;
        }
    }
    found
}
