//! The WGSL shading library as composable modules.
//!
//! Each file in `shading/wgsl/` is one module; its header names the modules it needs:
//!
//! ```text
//! // microfacet: the terms of a Cook-Torrance specular BRDF ...
//! // requires: constants
//! ```
//!
//! [`compose`] returns the modules asked for with their dependencies first, each once, as
//! one WGSL source that naga, wgpu or any other WGSL consumer accepts as it is.
//!
//! Why a resolver of our own rather than naga_oil or WESL imports (the route Bevy took): the
//! library is ten small modules with a fixed dependency graph and no name clashes, so
//! textual inclusion in dependency order is all it needs. Its output is plain WGSL: no
//! preprocessor for the user's build, no pinned naga version beside wgpu's, and the same
//! text feeds naga's GLSL, MSL, HLSL and SPIR-V backends and the `validator` tool. A project
//! that already uses WESL can still import these files as they are.

use std::fmt;
use std::sync::LazyLock;

use gbuffer_codegen::wgsl::codecs::{octahedral, rgb9e5, rgbm};
use gbuffer_core::Symbols;

/// The prefix of the codec functions the library's modules call (`shading_library_...`), as a
/// layout's prefix names its own copies.
pub const CODEC_PREFIX: &str = "shading_library";

/// One WGSL module of the library.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Module {
    /// The module's name, as `#include <gbuffer/NAME>` names it.
    pub name: &'static str,
    /// Its WGSL: its file, then the WGSL of the codecs its header names (`// codecs:`).
    pub source: String,
}

/// The library's files, dependencies before the modules that need them.
const FILES: [(&str, &str); 11] = [
    ("constants", include_str!("../wgsl/constants.wgsl")),
    ("colour", include_str!("../wgsl/colour.wgsl")),
    ("hdr", include_str!("../wgsl/hdr.wgsl")),
    ("microfacet", include_str!("../wgsl/microfacet.wgsl")),
    ("mobile", include_str!("../wgsl/mobile.wgsl")),
    ("environment", include_str!("../wgsl/environment.wgsl")),
    ("material", include_str!("../wgsl/material.wgsl")),
    ("normals", include_str!("../wgsl/normals.wgsl")),
    ("tonemap", include_str!("../wgsl/tonemap.wgsl")),
    ("shading", include_str!("../wgsl/shading.wgsl")),
    ("mobile_half", include_str!("../wgsl/mobile_half.wgsl")),
];

/// The WGSL of a codec a module names, its functions prefixed with [`CODEC_PREFIX`]: the
/// library stores colours and normals with the layouts' own codecs (the WGSL back end's,
/// `gbuffer_codegen::wgsl::codecs`), never a second copy.
fn codec_functions(codec: &str) -> Vec<String> {
    // Named as a layout called `shading_library` would name its copies.
    let symbols = Symbols::new(CODEC_PREFIX);
    match codec {
        "rgb9e5" => rgb9e5::exact_functions(&symbols),
        "rgbm" => rgbm::exact_functions(&symbols),
        "octahedral" => octahedral::map_functions(&symbols),
        other => panic!("a shading module names codec `{other}`, which it has no WGSL for"),
    }
}

/// The names on a header line such as `// requires: a, b`.
fn header_list<'a>(source: &'a str, key: &str) -> Vec<&'a str> {
    source
        .lines()
        .filter(|line| !line.starts_with("enable "))
        .take_while(|line| line.starts_with("//"))
        .find_map(|line| line.strip_prefix(key))
        .map(|names| {
            names
                .split(',')
                .map(str::trim)
                .filter(|name| !name.is_empty())
                .collect()
        })
        .unwrap_or_default()
}

static MODULES: LazyLock<Vec<Module>> = LazyLock::new(|| {
    FILES
        .iter()
        .map(|&(name, file)| {
            let mut source = file.to_string();
            let mut written = Vec::new();
            for codec in header_list(file, "// codecs:") {
                for function in codec_functions(codec) {
                    if !written.contains(&function) {
                        source.push('\n');
                        source.push_str(function.trim_end());
                        source.push('\n');
                        written.push(function);
                    }
                }
            }
            Module { name, source }
        })
        .collect()
});

/// Every module, dependencies before the modules that need them.
pub fn modules() -> &'static [Module] {
    &MODULES
}

impl Module {
    /// The module by name.
    pub fn named(name: &str) -> Option<&'static Module> {
        modules().iter().find(|module| module.name == name)
    }

    /// The source under a one-line banner naming the module, without its `enable`
    /// directives (which [`compose`] gathers at the top).
    pub fn with_banner(&self) -> String {
        let body: Vec<&str> = self
            .source
            .lines()
            .filter(|line| !line.starts_with("enable "))
            .collect();
        format!(
            "// ---- gbuffer shading module `{}` ----\n{}\n",
            self.name,
            body.join("\n")
        )
    }

    /// The `enable` directives the module needs, e.g. `enable f16;`.
    pub fn directives(&self) -> Vec<&str> {
        self.source
            .lines()
            .filter(|line| line.starts_with("enable "))
            .collect()
    }

    /// The names on the header's `// requires:` line.
    pub fn requires(&self) -> Vec<&str> {
        header_list(&self.source, "// requires:")
    }
}

/// Why modules could not be composed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ComposeError {
    /// No module has this name; `required_by` is the module whose header named it, if any.
    UnknownModule {
        /// The module asked for.
        name: String,
        /// The module that requires it, when it is a dependency.
        required_by: Option<&'static str>,
    },
    /// The modules' requirements form a cycle, listed in order.
    Cycle(Vec<&'static str>),
}

impl fmt::Display for ComposeError {
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ComposeError::UnknownModule { name, required_by } => {
                let known: Vec<&str> = modules().iter().map(|module| module.name).collect();
                match required_by {
                    Some(module) => {
                        write!(out, "module `{module}` requires unknown module `{name}`")?
                    }
                    None => write!(out, "unknown WGSL module `{name}`")?,
                }
                write!(out, "; the modules are: {}", known.join(", "))
            }
            ComposeError::Cycle(cycle) => write!(
                out,
                "WGSL modules require each other in a cycle: {}",
                cycle.join(" -> ")
            ),
        }
    }
}

impl std::error::Error for ComposeError {}

/// The WGSL of the named modules and everything they require, dependencies first, each module
/// once, each under a banner naming it.
pub fn compose(names: &[&str]) -> Result<String, ComposeError> {
    let modules = dependency_order(names)?;
    // WGSL wants its `enable` directives before every declaration: they move to the top.
    let mut directives: Vec<&str> = Vec::new();
    for module in &modules {
        for line in module
            .source
            .lines()
            .filter(|line| line.starts_with("enable "))
        {
            if !directives.contains(&line) {
                directives.push(line);
            }
        }
    }
    let bodies: Vec<String> = modules.iter().map(|module| module.with_banner()).collect();
    let mut source = directives
        .iter()
        .map(|line| format!("{line}\n"))
        .collect::<String>();
    source.push_str(&bodies.join("\n"));
    Ok(source)
}

/// The named modules and everything they require, dependencies first, each once.
pub fn dependency_order(names: &[&str]) -> Result<Vec<&'static Module>, ComposeError> {
    let mut ordered: Vec<&'static Module> = Vec::new();
    let mut visiting: Vec<&'static str> = Vec::new();
    for name in names {
        let unknown = || ComposeError::UnknownModule {
            name: name.to_string(),
            required_by: None,
        };
        visit(
            Module::named(name).ok_or_else(unknown)?,
            &mut ordered,
            &mut visiting,
        )?;
    }
    Ok(ordered)
}

/// Depth-first: a module's requirements, then the module.
fn visit(
    module: &'static Module,
    ordered: &mut Vec<&'static Module>,
    visiting: &mut Vec<&'static str>,
) -> Result<(), ComposeError> {
    if ordered.contains(&module) {
        return Ok(());
    }
    if let Some(start) = visiting.iter().position(|name| *name == module.name) {
        let mut cycle = visiting[start..].to_vec();
        cycle.push(module.name);
        return Err(ComposeError::Cycle(cycle));
    }
    visiting.push(module.name);
    for required in module.requires() {
        let dependency = Module::named(required).ok_or_else(|| ComposeError::UnknownModule {
            name: required.to_string(),
            required_by: Some(module.name),
        })?;
        visit(dependency, ordered, visiting)?;
    }
    visiting.pop();
    ordered.push(module);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dependencies_come_first_and_once() {
        let wgsl = compose(&["shading", "microfacet"]).unwrap();
        let position = |name: &str| wgsl.find(&format!("module `{name}`")).unwrap();
        assert!(position("constants") < position("microfacet"));
        assert!(position("microfacet") < position("shading"));
        assert!(position("mobile") < position("shading"));
        assert_eq!(wgsl.matches("module `microfacet`").count(), 1);
        assert!(!wgsl.contains("module `colour`"));
    }

    /// f16 comes in only where asked for: no module requires the one that enables it, and
    /// the library composed without naming it enables nothing.
    #[test]
    fn only_naming_the_half_module_enables_f16() {
        let enables_f16 = |module: &Module| !module.directives().is_empty();
        let (half, others): (Vec<&Module>, Vec<&Module>) =
            modules().iter().partition(|module| enables_f16(module));
        assert_eq!(
            half.iter().map(|module| module.name).collect::<Vec<_>>(),
            ["mobile_half"]
        );
        let names: Vec<&str> = others.iter().map(|module| module.name).collect();
        assert!(!compose(&names).unwrap().contains("enable f16;"));
        assert!(compose(&["mobile_half"])
            .unwrap()
            .starts_with("enable f16;"));
    }

    #[test]
    fn unknown_modules_are_named() {
        let error = compose(&["brdf"]).unwrap_err();
        assert!(
            error
                .to_string()
                .starts_with("unknown WGSL module `brdf`; the modules are: constants,"),
            "{error}"
        );
    }

    #[test]
    fn every_requirement_names_a_module_listed_before_it() {
        for (index, module) in modules().iter().enumerate() {
            for required in module.requires() {
                let position = modules().iter().position(|other| other.name == required);
                assert!(
                    position.is_some_and(|position| position < index),
                    "{} requires {required}",
                    module.name
                );
            }
        }
    }
}
