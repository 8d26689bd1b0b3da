//! Text any output may hold: characters no format may hold raw, and no terminal
//! should receive raw, written as visible escapes. Every name a writer puts in a file
//! and every value a message quotes goes through [`visible`].

use std::fmt::Write;

/// Whether `c` is written as a visible escape ([`visible`]).
fn hidden(c: char) -> bool {
    c.is_control()
        || matches!(c, '\u{fffe}' | '\u{ffff}')
        || matches!(c, '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}')
}

/// `s` with each `hidden` character written as `\u{…}` (lowercase hex).
///
/// ```
/// use primdecomp_files::visible;
/// assert_eq!(visible("a\u{1b}[31mb\u{0}"), "a\\u{1b}[31mb\\u{0}");
/// assert_eq!(visible("plain name, 日本"), "plain name, 日本");
/// ```
pub fn visible(s: &str) -> String {
    if !s.chars().any(hidden) {
        return s.to_string();
    }
    let mut out = String::with_capacity(s.len() + 8);
    for c in s.chars() {
        if hidden(c) {
            let _ = write!(out, "\\u{{{:x}}}", c as u32);
        } else {
            out.push(c);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hidden_characters_become_visible_escapes() {
        assert_eq!(visible("a\tb\nc\rd"), "a\\u{9}b\\u{a}c\\u{d}d");
        assert_eq!(
            visible("\u{7f}\u{85}\u{fffe}\u{ffff}"),
            "\\u{7f}\\u{85}\\u{fffe}\\u{ffff}"
        );
        assert_eq!(visible("\u{202e}abc"), "\\u{202e}abc");
        // Other characters, quotes and markup included, are the writers' business.
        assert_eq!(
            visible("<!--<script> \"q\" & 'a' \\ é"),
            "<!--<script> \"q\" & 'a' \\ é"
        );
    }
}
