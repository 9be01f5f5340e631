//! This package's tests are in `tests/`. Its library holds one thing: README.md's and the
//! guide's Rust examples, which rustdoc compiles and runs as doctests (`cargo test -p
//! gbuffer-integration-tests --doc`), so that the documents cannot drift from the code.

/// README.md's examples.
#[cfg(doctest)]
#[doc = include_str!("../../README.md")]
pub struct Readme;

/// The guide's introduction.
#[cfg(doctest)]
#[doc = include_str!("../../book/src/introduction.md")]
pub struct Introduction;

/// The guide's quick start (its build-script lines are checked by `examples/build-script`).
#[cfg(doctest)]
#[doc = include_str!("../../book/src/quick-start.md")]
pub struct QuickStart;

/// The guide's chapter on the layout contract.
#[cfg(doctest)]
#[doc = include_str!("../../book/src/layout-contract.md")]
pub struct LayoutContract;

/// The guide's chapter on engines' G-buffers and Bevy.
#[cfg(doctest)]
#[doc = include_str!("../../book/src/engines.md")]
pub struct Engines;

/// The guide's chapter on wgpu.
#[cfg(doctest)]
#[doc = include_str!("../../book/src/wgpu.md")]
pub struct Wgpu;

/// The guide's chapter on the shading library.
#[cfg(doctest)]
#[doc = include_str!("../../book/src/shading-library.md")]
pub struct ShadingLibrary;

/// The guide's chapter on the solver.
#[cfg(doctest)]
#[doc = include_str!("../../book/src/solver.md")]
pub struct Solver;

/// The guide's chapter on the reference renderer (its example splits a slice over threads).
#[cfg(doctest)]
#[doc = include_str!("../../book/src/reference-renderer.md")]
pub struct ReferenceRenderer;
