//! Limits on how large one statement of a shader may be, checked before naga sees it. naga
//! parses a chain of binary operators in a loop but lowers and validates the tree it builds
//! recursively, so `return 1.0 + 1.0 + ...` with a hundred thousand terms overflows any
//! stack; and its parser stops deep nesting with an error that has no line. Here both get a
//! line and column, at limits far past what a real shader writes.

use crate::{Problem, Stage};

/// The most binary-operator characters one statement may hold (a statement ends at `;`, `{`
/// or `}`); each is at most one level of the tree naga walks.
pub const MAX_OPERATORS: usize = 4096;

/// The deepest nesting of `(`, `[` and `{`.
pub const MAX_NESTING: usize = 64;

/// Refuses a source with a statement past [`MAX_OPERATORS`] or nesting past [`MAX_NESTING`],
/// at the statement's or the bracket's line and column. Comments are skipped.
pub fn check(source: &str) -> Result<(), Problem> {
    let characters: Vec<char> = source.chars().collect();
    let (mut line, mut column) = (1u32, 1u32);
    let mut statement: Option<((u32, u32), usize)> = None;
    let mut depth = 0;
    let mut comments = 0;
    let mut index = 0;
    while index < characters.len() {
        let character = characters[index];
        let next = characters.get(index + 1).copied();
        let position = (line, column);
        index += 1;
        (line, column) = if character == '\n' {
            (line + 1, 1)
        } else {
            (line, column + 1)
        };
        // Comments: `//` to the end of the line, `/* */` nested as WGSL nests them.
        if comments == 0 && character == '/' && next == Some('/') {
            while index < characters.len() && characters[index] != '\n' {
                index += 1;
            }
            continue;
        }
        if character == '/' && next == Some('*')
            || comments > 0 && character == '*' && next == Some('/')
        {
            comments = if character == '/' {
                comments + 1
            } else {
                comments - 1
            };
            index += 1;
            column += 1;
            continue;
        }
        if comments > 0 || character.is_whitespace() {
            continue;
        }
        let (start, operators) = statement.get_or_insert((position, 0));
        match character {
            ';' | '{' | '}' => statement = None,
            '+' | '-' | '*' | '/' | '%' | '&' | '|' | '^' | '<' | '>' | '=' | '!' => {
                *operators += 1;
                if *operators > MAX_OPERATORS {
                    return Err(refusal(
                        *start,
                        format!(
                            "this statement has more than {MAX_OPERATORS} operators: split it \
                             (naga checks expressions recursively, so their size is limited \
                             rather than left to overflow the stack)"
                        ),
                    ));
                }
            }
            _ => {}
        }
        match character {
            '(' | '[' | '{' => {
                depth += 1;
                if depth > MAX_NESTING {
                    return Err(refusal(
                        position,
                        format!("brackets nest more than {MAX_NESTING} deep here"),
                    ));
                }
            }
            ')' | ']' | '}' => depth = usize::saturating_sub(depth, 1),
            _ => {}
        }
    }
    Ok(())
}

fn refusal((line, column): (u32, u32), message: String) -> Problem {
    Problem {
        stage: Stage::Parse,
        location: Some((line, column)),
        message,
        labels: Vec::new(),
        notes: Vec::new(),
        detail: String::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_chains_and_deep_nesting_are_refused_where_they_start() {
        let chain = format!(
            "fn f() -> f32 {{\n    return {};\n}}\n",
            vec!["1.0"; 5000].join(" + ")
        );
        let problem = check(&chain).unwrap_err();
        assert_eq!(problem.location, Some((2, 5)), "{problem}");
        let nested = format!(
            "fn f() -> f32 {{\n    return {}1.0{};\n}}\n",
            "(".repeat(100),
            ")".repeat(100)
        );
        let problem = check(&nested).unwrap_err();
        assert_eq!(problem.location, Some((2, 75)), "{problem}");
        // Operators in comments do not count; a real shader passes.
        let commented = format!(
            "// {}\n/* {} /* */ */ fn f() {{}}\n",
            "+".repeat(9000),
            "-".repeat(9000)
        );
        check(&commented).unwrap();
        for module in gbuffer_shading::wgsl::modules() {
            check(&module.source).unwrap();
        }
    }
}
