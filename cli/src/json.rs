//! JSON for `gbuffer validate --json`, written by hand so that the default command line builds
//! no serde: a value tree and its pretty printing (two-space indents, as
//! `serde_json::to_string_pretty` writes; strings as `gbuffer_files::json` writes them).
//! The tests read what it writes back with serde_json.

use std::fmt::Write as _;

use gbuffer_files::json::string;

/// A JSON value.
#[derive(Clone, Debug, PartialEq)]
pub enum Json {
    Null,
    Bool(bool),
    Unsigned(u64),
    String(String),
    Array(Vec<Json>),
    /// Keys in the order they are written.
    Object(Vec<(&'static str, Json)>),
}

impl Json {
    /// A string value.
    pub fn string(text: impl Into<String>) -> Json {
        Json::String(text.into())
    }

    /// A count or position, or null.
    pub fn unsigned(value: Option<usize>) -> Json {
        value.map_or(Json::Null, |value| Json::Unsigned(value as u64))
    }

    /// The value, pretty printed, without a final newline.
    pub fn pretty(&self) -> String {
        let mut out = String::new();
        self.write(&mut out, 0);
        out
    }

    fn write(&self, out: &mut String, depth: usize) {
        let indent = |out: &mut String, depth: usize| out.push_str(&"  ".repeat(depth));
        match self {
            Json::Null => out.push_str("null"),
            Json::Bool(value) => out.push_str(if *value { "true" } else { "false" }),
            Json::Unsigned(value) => {
                let _ = write!(out, "{value}");
            }
            Json::String(text) => out.push_str(&string(text)),
            Json::Array(items) if items.is_empty() => out.push_str("[]"),
            Json::Array(items) => {
                out.push_str("[\n");
                for (index, item) in items.iter().enumerate() {
                    indent(out, depth + 1);
                    item.write(out, depth + 1);
                    out.push_str(if index + 1 < items.len() { ",\n" } else { "\n" });
                }
                indent(out, depth);
                out.push(']');
            }
            Json::Object(members) if members.is_empty() => out.push_str("{}"),
            Json::Object(members) => {
                out.push_str("{\n");
                for (index, (key, value)) in members.iter().enumerate() {
                    indent(out, depth + 1);
                    out.push_str(&string(key));
                    out.push_str(": ");
                    value.write(out, depth + 1);
                    out.push_str(if index + 1 < members.len() {
                        ",\n"
                    } else {
                        "\n"
                    });
                }
                indent(out, depth);
                out.push('}');
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What is written reads back, through serde_json, as the same value: strings with every
    /// character class, numbers, nulls, nesting and empty containers.
    #[test]
    fn what_is_written_reads_back_through_serde_json() {
        let awkward = "quote \" backslash \\ newline \n tab \t bell \u{7} nul \u{0} é ∑ 🎨 \u{7f}";
        let value = Json::Object(vec![
            ("text", Json::string(awkward)),
            ("none", Json::Null),
            ("yes", Json::Bool(true)),
            ("big", Json::Unsigned(u64::MAX)),
            ("empty", Json::Array(vec![])),
            ("nothing", Json::Object(vec![])),
            (
                "nested",
                Json::Array(vec![Json::Object(vec![("line", Json::unsigned(Some(3)))])]),
            ),
        ]);
        let text = value.pretty();
        let read: serde_json::Value = serde_json::from_str(&text).unwrap();
        let expected = serde_json::json!({
            "text": awkward,
            "none": null,
            "yes": true,
            "big": u64::MAX,
            "empty": [],
            "nothing": {},
            "nested": [{"line": 3}],
        });
        assert_eq!(read, expected);
        // Laid out as serde_json's pretty printer lays it out (which sorts the keys).
        let pretty = serde_json::to_string_pretty(&expected).unwrap();
        assert_eq!(text.lines().count(), pretty.lines().count(), "{text}");
    }
}
