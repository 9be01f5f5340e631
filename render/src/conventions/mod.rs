//! How the renderer's surface goes into each layout it renders: the seed layouts' conventions
//! ([`seed`]) and the engines' ([`engine`]), each written as WGSL beside its Rust mirror. The
//! trade-off study reads them too, so that what it measures is what the renderer stores.

pub mod engine;
pub mod seed;
