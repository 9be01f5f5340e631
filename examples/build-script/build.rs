//! Generates the includes of `layouts/mobile_metallic.toml` into OUT_DIR: the WGSL, the GLSL
//! ES includes, the report and the Rust mirror that `src/main.rs` includes. Cargo reruns this
//! when the layout file changes.

fn main() {
    if let Err(error) = gbuffer::build::generate(["layouts/mobile_metallic.toml"]) {
        eprintln!("{error}");
        std::process::exit(1);
    }
}
