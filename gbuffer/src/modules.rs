//! The WGSL shading library as composable modules.
//!
//! Each file in `gbuffer/wgsl/` is one module; its header names the modules it needs:
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

/// One WGSL module of the library.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Module {
    /// The module's name, as `#include <gbuffer/NAME>` names it.
    pub name: &'static str,
    /// Its WGSL.
    pub source: &'static str,
}

macro_rules! modules {
    ($($name:literal),* $(,)?) => {
        [$(Module { name: $name, source: include_str!(concat!("../wgsl/", $name, ".wgsl")) }),*]
    };
}

/// Every module, dependencies before the modules that need them.
pub const MODULES: [Module; 11] = modules![
    "constants",
    "colour",
    "hdr",
    "microfacet",
    "mobile",
    "environment",
    "material",
    "normals",
    "tonemap",
    "shading",
    "mobile_half",
];

impl Module {
    /// The module by name.
    pub fn named(name: &str) -> Option<Module> {
        MODULES.into_iter().find(|module| module.name == name)
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
    pub fn directives(&self) -> Vec<&'static str> {
        self.source
            .lines()
            .filter(|line| line.starts_with("enable "))
            .collect()
    }

    /// The names on the header's `// requires:` line.
    pub fn requires(&self) -> Vec<&'static str> {
        self.source
            .lines()
            .filter(|line| !line.starts_with("enable "))
            .take_while(|line| line.starts_with("//"))
            .find_map(|line| line.strip_prefix("// requires:"))
            .map(|names| {
                names
                    .split(',')
                    .map(str::trim)
                    .filter(|name| !name.is_empty())
                    .collect()
            })
            .unwrap_or_default()
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
                let known: Vec<&str> = MODULES.iter().map(|module| module.name).collect();
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
    let bodies: Vec<String> = modules.iter().map(Module::with_banner).collect();
    let mut source = directives
        .iter()
        .map(|line| format!("{line}\n"))
        .collect::<String>();
    source.push_str(&bodies.join("\n"));
    Ok(source)
}

/// The named modules and everything they require, dependencies first, each once.
pub fn dependency_order(names: &[&str]) -> Result<Vec<Module>, ComposeError> {
    let mut ordered: Vec<Module> = Vec::new();
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
    module: Module,
    ordered: &mut Vec<Module>,
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
        for (index, module) in MODULES.iter().enumerate() {
            for required in module.requires() {
                let position = MODULES.iter().position(|other| other.name == required);
                assert!(
                    position.is_some_and(|position| position < index),
                    "{} requires {required}",
                    module.name
                );
            }
        }
    }
}
