//! Include resolution for user shaders: a line `#include <gbuffer/NAME>` pulls in a module of
//! the shading library (with its dependencies), `#include "PATH.toml"` the generated WGSL of a
//! layout file, and `#include "PATH.wgsl"` another WGSL file (itself resolved). Paths are
//! relative to the including file, and the file they name must lie inside one of the include
//! roots: the folder of the file given, the current folder (the project a build runs in) and
//! any folder the caller adds (`gbuffer validate --include-dir`), so that a shader cannot
//! read files elsewhere on the machine. Each module and file is included once; files nest at
//! most [`MAX_INCLUDE_DEPTH`] deep. Files are read as every input is
//! ([`gbuffer_files::input::read_input`]).
//!
//! The result keeps a map from its lines back to where they came from, so a problem in the
//! combined source is reported at its file and line.

use std::path::{Path, PathBuf};

use gbuffer_files::input::read_input;
use gbuffer_layout_file::read_layout_file;

use crate::{FileProblem, Stage};

/// Where a run of lines of the resolved source came from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Segment {
    /// A file path, `<gbuffer/NAME>` or `<generated from PATH>`.
    pub origin: String,
    /// The first line of the run in the resolved source (1-based).
    pub first_line: usize,
    /// The number of lines in the run.
    pub lines: usize,
    /// The line in the origin that the run's first line is (1-based).
    pub origin_line: usize,
}

/// A resolved shader: one WGSL source and its line map.
#[derive(Clone, Debug, Default)]
pub struct Resolved {
    /// The combined source: every include replaced by the text it names.
    pub source: String,
    /// Where each run of lines of the combined source comes from.
    pub segments: Vec<Segment>,
}

impl Resolved {
    /// The origin and origin line of a line of the resolved source. The line after the last
    /// (where a parser finds the source ended too soon) is the last origin's next line.
    pub fn origin_of(&self, line: usize) -> Option<(&str, usize)> {
        let end_of_source = |segment: &&Segment| line == segment.first_line + segment.lines;
        self.segments
            .iter()
            .find(|segment| {
                (segment.first_line..segment.first_line + segment.lines).contains(&line)
            })
            .or_else(|| self.segments.last().filter(end_of_source))
            .map(|segment| {
                (
                    segment.origin.as_str(),
                    segment.origin_line + line - segment.first_line,
                )
            })
    }

    fn push(&mut self, origin: &str, origin_line: usize, text: &str) {
        let lines = text.lines().count();
        if lines == 0 {
            return;
        }
        let first_line = self.source.lines().count() + 1;
        for line in text.lines() {
            self.source.push_str(line);
            self.source.push('\n');
        }
        self.segments.push(Segment {
            origin: origin.to_string(),
            first_line,
            lines,
            origin_line,
        });
    }
}

/// An include that could not be resolved, as a problem of the `Include` stage at the line of its
/// directive in `file` (no line for a file that could not be read).
fn include_problem(file: &Path, line: Option<usize>, message: String) -> Box<FileProblem> {
    Box::new(FileProblem {
        origin: file.display().to_string(),
        location: line.map(|line| (line, 1)),
        stage: Stage::Include,
        message,
        labels: Vec::new(),
        notes: Vec::new(),
    })
}

/// How deep `#include "FILE"` may nest: a chain longer than any project's, and short enough
/// that resolving it cannot exhaust the stack.
pub const MAX_INCLUDE_DEPTH: usize = 64;

/// Reads `path` and resolves its includes, confined to `path`'s folder, the current folder and
/// `include_dirs`.
pub fn resolve_file(path: &Path, include_dirs: &[PathBuf]) -> Result<Resolved, Box<FileProblem>> {
    let source = read_input(path)
        .map_err(|error| include_problem(path, None, format!("cannot read the file: {error}")))?;
    resolve_source(path, &source, include_dirs)
}

/// Resolves the includes of `source`, read from `path`, confined to `path`'s folder, the
/// current folder and `include_dirs`.
pub fn resolve_source(
    path: &Path,
    source: &str,
    include_dirs: &[PathBuf],
) -> Result<Resolved, Box<FileProblem>> {
    let folder = path
        .parent()
        .filter(|parent| !parent.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let mut resolver = Resolver {
        roots: std::iter::once(folder.to_path_buf())
            .chain(std::env::current_dir().ok())
            .chain(include_dirs.iter().cloned())
            .map(|root| canonical(&root))
            .collect(),
        ..Resolver::default()
    };
    resolver.included_files.push(canonical(path));
    resolver.resolve(path, source, 0)?;
    Ok(resolver.finish())
}

/// `path` with links and `..` resolved, where it exists.
fn canonical(path: &Path) -> PathBuf {
    path.canonicalize().unwrap_or_else(|_| path.to_path_buf())
}

#[derive(Default)]
struct Resolver {
    resolved: Resolved,
    /// The folders included files must lie in, canonical.
    roots: Vec<PathBuf>,
    included_modules: Vec<&'static str>,
    included_files: Vec<PathBuf>,
    /// `enable` directives of included modules: WGSL wants them before every declaration.
    directives: Vec<&'static str>,
}

impl Resolver {
    /// The resolved source with the gathered directives on its first lines.
    fn finish(mut self) -> Resolved {
        if self.directives.is_empty() {
            return self.resolved;
        }
        let header: String = self
            .directives
            .iter()
            .map(|line| format!("{line}\n"))
            .collect();
        for segment in &mut self.resolved.segments {
            segment.first_line += self.directives.len();
        }
        self.resolved.segments.insert(
            0,
            Segment {
                origin: "<gbuffer directives>".into(),
                first_line: 1,
                lines: self.directives.len(),
                origin_line: 1,
            },
        );
        self.resolved.source.insert_str(0, &header);
        self.resolved
    }

    /// Resolves `source`, read from `path`, which `depth` includes led to.
    fn resolve(&mut self, path: &Path, source: &str, depth: usize) -> Result<(), Box<FileProblem>> {
        let origin = path.display().to_string();
        let mut pending = String::new();
        let mut pending_start = 1;
        for (index, line) in source.lines().enumerate() {
            let line_number = index + 1;
            let Some(target) = line.trim().strip_prefix("#include") else {
                if pending.is_empty() {
                    pending_start = line_number;
                }
                pending.push_str(line);
                pending.push('\n');
                continue;
            };
            self.resolved
                .push(&origin, pending_start, &std::mem::take(&mut pending));
            let error = |message: String| include_problem(path, Some(line_number), message);
            let target = target.trim();
            if let Some(module) = target
                .strip_prefix("<gbuffer/")
                .and_then(|rest| rest.strip_suffix('>'))
            {
                let modules = gbuffer_shading::wgsl::dependency_order(&[module])
                    .map_err(|problem| error(problem.to_string()))?;
                for module in modules {
                    if !self.included_modules.contains(&module.name) {
                        self.included_modules.push(module.name);
                        for directive in module.directives() {
                            if !self.directives.contains(&directive) {
                                self.directives.push(directive);
                            }
                        }
                        self.resolved.push(
                            &format!("<gbuffer/{}>", module.name),
                            0,
                            &module.with_banner(),
                        );
                    }
                }
            } else if let Some(relative) = target
                .strip_prefix('"')
                .and_then(|rest| rest.strip_suffix('"'))
            {
                let included = path.parent().unwrap_or(Path::new(".")).join(relative);
                let key = included.canonicalize().map_err(|problem| {
                    error(format!(
                        "cannot read included file `{}`: {problem}",
                        included.display()
                    ))
                })?;
                if !self.roots.iter().any(|root| key.starts_with(root)) {
                    let roots: Vec<String> = self
                        .roots
                        .iter()
                        .map(|root| root.display().to_string())
                        .collect();
                    return Err(error(format!(
                        "cannot include `{relative}`: it lies outside the include roots ({}); \
                         add its folder with --include-dir",
                        roots.join(", ")
                    )));
                }
                if self.included_files.contains(&key) {
                    continue;
                }
                if depth + 1 > MAX_INCLUDE_DEPTH {
                    return Err(error(format!(
                        "cannot include `{relative}`: includes nest more than {MAX_INCLUDE_DEPTH} files deep"
                    )));
                }
                self.included_files.push(key);
                match included.extension().and_then(|extension| extension.to_str()) {
                    Some("toml") => {
                        let file = read_layout_file(&included).map_err(|problem| error(format!("in included layout: {problem}")))?;
                        let wgsl = gbuffer_codegen::wgsl::emit_with(&file.layout, file.conversions);
                        self.resolved.push(&format!("<generated from {}>", included.display()), 1, &wgsl);
                    }
                    Some("wgsl") => {
                        let text = read_input(&included)
                            .map_err(|problem| error(format!("cannot read included file `{}`: {problem}", included.display())))?;
                        self.resolve(&included, &text, depth + 1)?;
                    }
                    _ => return Err(error(format!("cannot include `{relative}`: only .wgsl and .toml (layout) files can be included"))),
                }
            } else {
                return Err(error(format!(
                    "malformed include `{target}`: write `#include <gbuffer/MODULE>` or `#include \"relative/path.wgsl\"` (or .toml)"
                )));
            }
        }
        self.resolved.push(&origin, pending_start, &pending);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shaderlib_modules_are_included_once_with_their_dependencies() {
        let source = "#include <gbuffer/shading>\n#include <gbuffer/microfacet>\nfn f() -> f32 { return d_ggx(1.0, 0.5); }\n";
        let resolved = resolve_source(Path::new("user.wgsl"), source, &[]).unwrap();
        assert_eq!(
            resolved
                .source
                .matches("gbuffer shading module `microfacet`")
                .count(),
            1
        );
        let last_line = resolved.source.lines().count();
        assert_eq!(resolved.origin_of(last_line), Some(("user.wgsl", 3)));
        crate::validate_wgsl(&resolved.source).unwrap();
    }

    #[test]
    fn bad_includes_name_their_line() {
        let error = resolve_source(
            Path::new("user.wgsl"),
            "fn f() {}\n#include <gbuffer/brdf>\n",
            &[],
        )
        .unwrap_err();
        assert_eq!(error.location, Some((2, 1)));
        assert!(
            error.message.starts_with("unknown WGSL module `brdf`"),
            "{}",
            error.message
        );
        let error = resolve_source(Path::new("user.wgsl"), "#include shading\n", &[]).unwrap_err();
        assert!(
            error.message.starts_with("malformed include"),
            "{}",
            error.message
        );
    }
}
