//! Generates the includes of `layouts/mobile_metallic.toml` into OUT_DIR: the WGSL, the GLSL
//! ES includes, the report and the Rust mirror that `src/main.rs` includes. Cargo reruns this
//! when the layout file changes.

fn main() {
    if let Err(error) = gbuffer_codegen::Builder::new()
        .layout("layouts/mobile_metallic.toml")
        .build()
    {
        eprintln!("{error}");
        std::process::exit(1);
    }
}
