//! What `gbuffer codegen` and the build-script API write for a layout, and how: every file
//! is written atomically (a temporary file renamed over it), and a file whose contents are
//! unchanged is left alone, so build timestamps stay put.

use std::io;
use std::path::{Path, PathBuf};

use gbuffer_codegen::emit::glsl::local_read::LocalRead;
use gbuffer_codegen::emit::glsl::{self, Include};
use gbuffer_codegen::emit::rust;
use gbuffer_codegen::CompiledLayout;
use gbuffer_codegen::TranslationError;
use gbuffer_core::layout::Layout;
use gbuffer_core::report::Report;
use gbuffer_core::Conversions;

/// One kind of output.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Output {
    /// `<snake>.wgsl`: the same text the derive produces.
    Wgsl,
    /// `<snake>.pls_inout.glsl`, `.pls_in.glsl`, `.pls_out.glsl`: EXT_shader_pixel_local_storage blocks.
    GlslPixelLocalStorage,
    /// `<snake>.fetch.glsl` (packed words) and `<snake>.fetch_native.glsl` (one attachment per
    /// field): EXT_shader_framebuffer_fetch attachments and functions.
    GlslFramebufferFetch,
    /// `<snake>.vulkan.glsl` and `<snake>.vulkan_native.glsl`: Vulkan GLSL subpass inputs and
    /// functions, each with its `.local_read.json`: what the host sets to read them in one
    /// dynamic rendering (`VK_KHR_dynamic_rendering_local_read`).
    GlslVulkan,
    /// `<snake>.webgl_pls.glsl` and `<snake>.webgl_pls.js`: WebGL 2's pixel local storage
    /// (ANGLE's GLSL extension) and the host module that drives it.
    WebGlPixelLocalStorage,
    /// `<snake>.rs` (and the `.wgsl` it includes): the Rust mirror without the derive.
    Rust,
    /// `<snake>.report.txt`: the bit report.
    Report,
}

impl Output {
    /// Every output, in the order the codegen writes them.
    pub const ALL: [Output; 7] = [
        Output::Wgsl,
        Output::GlslPixelLocalStorage,
        Output::GlslFramebufferFetch,
        Output::GlslVulkan,
        Output::WebGlPixelLocalStorage,
        Output::Rust,
        Output::Report,
    ];

    /// Whether this output writes the GLSL include `include`.
    pub fn includes(self, include: Include) -> bool {
        match include {
            Include::PixelLocalStorage(_) => self == Output::GlslPixelLocalStorage,
            Include::FetchPacked | Include::FetchNative => self == Output::GlslFramebufferFetch,
            Include::SubpassPacked | Include::SubpassNative => self == Output::GlslVulkan,
            Include::WebGlPixelLocalStorage => self == Output::WebGlPixelLocalStorage,
        }
    }
}

/// A file to write: its name in the output folder and its contents.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GeneratedFile {
    /// The file's name, e.g. `mobile_metallic.wgsl`.
    pub name: String,
    /// Its text.
    pub contents: String,
}

/// The files of the chosen outputs for a checked layout, with the chosen conversions.
pub fn generate(
    layout: &Layout,
    conversions: Conversions,
    outputs: &[Output],
) -> Result<Vec<GeneratedFile>, TranslationError> {
    // Compiled once, for every output: its WGSL is the file's, its translation every include's.
    let compiled = CompiledLayout::new(layout, conversions)?;
    let symbols = compiled.lowered().symbols();
    let wgsl_file = compiled.wgsl().to_string() + "\n";
    let mut files = Vec::new();
    let mut add = |name: String, contents: String| {
        if !files.iter().any(|file: &GeneratedFile| file.name == name) {
            files.push(GeneratedFile { name, contents });
        }
    };
    for output in Output::ALL
        .into_iter()
        .filter(|output| outputs.contains(output))
    {
        match output {
            Output::Wgsl => add(symbols.wgsl_file(), wgsl_file.clone()),
            Output::GlslPixelLocalStorage | Output::GlslFramebufferFetch | Output::GlslVulkan => {
                for include in Include::ALL
                    .into_iter()
                    .filter(|include| output.includes(*include))
                {
                    let (text, interface) = glsl::include(&compiled, include, 0)?;
                    add(include.file_name(symbols, "glsl"), text);
                    if let Some(local_read) = LocalRead::of(&compiled, &interface, 0) {
                        add(LocalRead::file_name(symbols, include), local_read.to_json());
                    }
                }
            }
            Output::WebGlPixelLocalStorage => {
                let include = Include::WebGlPixelLocalStorage;
                let (text, interface) = glsl::include(&compiled, include, 0)?;
                add(include.file_name(symbols, "glsl"), text);
                add(
                    include.file_name(symbols, "js"),
                    glsl::webgl::host_module(&compiled, &interface),
                );
            }
            Output::Rust => {
                add(symbols.wgsl_file(), wgsl_file.clone());
                add(symbols.file("rs"), rust::emit_source(&compiled));
            }
            Output::Report => add(symbols.file("report.txt"), Report::new(layout).to_string()),
        }
    }
    Ok(files)
}

/// Whether [`write_if_changed`] wrote the file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WriteOutcome {
    /// The file was new or changed, and was written.
    Written,
    /// The file already held these contents and was left alone.
    Unchanged,
}

/// Whether the file at `path` holds exactly `contents` (so that writing it would change nothing).
pub fn holds(path: &Path, contents: &str) -> bool {
    std::fs::read(path).is_ok_and(|held| held == contents.as_bytes())
}

/// Writes `contents` to `path` unless it already holds exactly that, through a temporary file
/// in the same folder renamed over the target, so a reader never sees half a file.
pub fn write_if_changed(path: &Path, contents: &str) -> io::Result<WriteOutcome> {
    if holds(path, contents) {
        return Ok(WriteOutcome::Unchanged);
    }
    let folder = path
        .parent()
        .filter(|parent| !parent.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    std::fs::create_dir_all(folder)?;
    let file_name = path
        .file_name()
        .and_then(|name| name.to_str())
        .unwrap_or("output");
    let temporary: PathBuf = folder.join(format!(".{file_name}.{}.tmp", std::process::id()));
    std::fs::write(&temporary, contents)?;
    std::fs::rename(&temporary, path).inspect_err(|_| {
        let _ = std::fs::remove_file(&temporary);
    })?;
    Ok(WriteOutcome::Written)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unchanged_files_keep_their_timestamp() {
        let folder =
            std::env::temp_dir().join(format!("codegen-write-test-{}", std::process::id()));
        let path = folder.join("a.txt");
        assert_eq!(
            write_if_changed(&path, "one").unwrap(),
            WriteOutcome::Written
        );
        let modified = std::fs::metadata(&path).unwrap().modified().unwrap();
        std::thread::sleep(std::time::Duration::from_millis(20));
        assert_eq!(
            write_if_changed(&path, "one").unwrap(),
            WriteOutcome::Unchanged
        );
        assert_eq!(
            std::fs::metadata(&path).unwrap().modified().unwrap(),
            modified
        );
        assert_eq!(
            write_if_changed(&path, "two").unwrap(),
            WriteOutcome::Written
        );
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "two");
        assert_eq!(
            std::fs::read_dir(&folder).unwrap().count(),
            1,
            "no temporary file is left behind"
        );
        std::fs::remove_dir_all(folder).unwrap();
    }
}
