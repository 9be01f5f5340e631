//! JSON string literals (RFC 8259, section 7), which JavaScript reads too: for the generated
//! JavaScript modules and the tools' JSON output.

use std::fmt::Write as _;

/// `text` as a quoted JSON string: quotes, backslashes and control characters escaped, the rest
/// as it is (JSON text is UTF-8).
pub fn string(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + 2);
    out.push('"');
    for character in text.chars() {
        match character {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            control if u32::from(control) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", u32::from(control));
            }
            other => out.push(other),
        }
    }
    out.push('"');
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escapes_what_json_requires_and_nothing_else() {
        assert_eq!(string("plain é ∑"), "\"plain é ∑\"");
        assert_eq!(string("\"\\\n\r\t"), "\"\\\"\\\\\\n\\r\\t\"");
        assert_eq!(string("\u{0}\u{1f}\u{7f}"), "\"\\u0000\\u001f\u{7f}\"");
    }
}
