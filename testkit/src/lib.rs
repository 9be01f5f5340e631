//! Shared pieces of the cross-crate tests: a layout with every format, test values with the
//! hard cases, WGSL harnesses around generated code, and a GPU runner.

pub mod chromium;
pub mod layouts;
pub mod shading_cases;
pub mod texels;
pub mod user_shaders;

use gbuffer_gpu::adapter::{Gpu, Request};

/// The one rule of the GPU tests: where a driver, a library or a tool is missing, a test prints
/// why and skips, except under `CI=true`, where `.ci/run` installs them all and a skip would
/// hide a broken set-up, so the test fails. Returns what was opened, or `None` to skip.
pub fn or_skip<T>(what: &str, opened: Result<T, String>) -> Option<T> {
    match opened {
        Ok(opened) => Some(opened),
        Err(error) => {
            skip_without_driver(what, &error);
            None
        }
    }
}

/// Prints why a GPU test skips for want of a driver, or panics under `CI=true` (see
/// [`or_skip`]).
pub fn skip_without_driver(what: &str, error: &str) {
    if std::env::var_os("CI").is_some_and(|value| value == "true") {
        panic!("{what}: {error} (under CI=true a missing driver is a failure)");
    }
    eprintln!("skipped: {what}: {error}");
}

/// Whether the cost model's GPU compilers are set up (`scripts/cost-setup.sh`); where they
/// are not, [`skip_without_driver`] says why (and fails under `CI=true`).
pub fn compilers_set_up() -> bool {
    match gbuffer_cost::Setup::find().missing() {
        None => true,
        Some(reason) => {
            skip_without_driver("the cost model's compilers", &reason);
            false
        }
    }
}

/// The adapter wgpu prefers, with its full limits (its name printed), or `None` to skip (see
/// [`or_skip`]).
pub fn gpu() -> Option<Gpu> {
    let gpu = or_skip("a wgpu adapter", Gpu::new())?;
    eprintln!("adapter: {}", gpu.describe());
    Some(gpu)
}

/// As [`gpu`], with the device's limits lowered to `limits` (where given) and those of
/// `features` the adapter has.
pub fn gpu_with(limits: Option<wgpu::Limits>, features: wgpu::Features) -> Option<Gpu> {
    let request = Request {
        label: "tests",
        limits,
        features,
        backends: None,
    };
    or_skip("a wgpu adapter", Gpu::open(&request))
}

use gbuffer::GBufferLayout;
use glam::{IVec2, IVec4, UVec2, UVec4, Vec2, Vec3, Vec4};

/// One field of each of the twelve formats, every channel used.
#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
#[gbuffer(budget = 384)]
pub struct AllFormats {
    /// `r11f_g11f_b10f`.
    #[pls(r11f_g11f_b10f)]
    pub small_floats: Vec3,
    /// `r32f`.
    #[pls(r32f)]
    pub single: f32,
    /// `rg16f`.
    #[pls(rg16f)]
    pub halves: Vec2,
    /// `rgb10_a2`.
    #[pls(rgb10_a2)]
    pub unorm_10_10_10_2: Vec4,
    /// `rgba8`.
    #[pls(rgba8)]
    pub unorm_8: Vec4,
    /// `rg16`.
    #[pls(rg16)]
    pub unorm_16: Vec2,
    /// `rgba8i`.
    #[pls(rgba8i)]
    pub sint_8: IVec4,
    /// `rg16i`.
    #[pls(rg16i)]
    pub sint_16: IVec2,
    /// `rgb10_a2ui`.
    #[pls(rgb10_a2ui)]
    pub uint_10_10_10_2: UVec4,
    /// `rgba8ui`.
    #[pls(rgba8ui)]
    pub uint_8: UVec4,
    /// `rg16ui`.
    #[pls(rg16ui)]
    pub uint_16: UVec2,
    /// `r32ui`.
    #[pls(r32ui)]
    pub uint_32: u32,
}

/// The workspace's root folder.
pub fn workspace() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("tests/ is in the workspace")
        .to_path_buf()
}

/// Writes a table of measured figures as `target/figures/<name>.md`, the file the guide's
/// table of the same figures names (`<!-- figures: target/figures/<name>.md -->`), which
/// `.ci/check-figures` holds the text to. `rows` are the cells of each row, `header` the
/// column names.
pub fn write_figures(name: &str, header: &[&str], rows: &[Vec<String>]) {
    let folder = workspace().join("target/figures");
    std::fs::create_dir_all(&folder).expect("target/figures can be made");
    let line = |cells: &[&str]| format!("| {} |\n", cells.join(" | "));
    let mut markdown = line(header) + &line(&vec!["---"; header.len()]);
    for row in rows {
        markdown += &line(&row.iter().map(String::as_str).collect::<Vec<_>>());
    }
    std::fs::write(folder.join(format!("{name}.md")), markdown).expect("the figures are written");
}

/// The solver's preset scene files (`solver/scenes/*.toml`), in order.
pub fn scene_presets() -> Vec<std::path::PathBuf> {
    let mut paths: Vec<std::path::PathBuf> = std::fs::read_dir(workspace().join("solver/scenes"))
        .expect("solver/scenes is there")
        .map(|entry| entry.expect("a readable folder entry").path())
        .collect();
    paths.sort();
    paths
}

/// Exact and fast conversions side by side: each field chooses its own, the layout's are
/// exact. rgba8 appears in both.
#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
#[gbuffer(budget = 128)]
pub struct MixedConversions {
    /// Exact, as the layout says.
    #[pls(rgba8)]
    pub exact_colour: Vec4,
    /// Fast: `pack4x8unorm` (f32 arithmetic under GLSL ES 3.00).
    #[pls(rgba8, conversions = fast)]
    pub fast_colour: Vec4,
    /// Fast: f32 rounding.
    #[pls(rgb10_a2, conversions = fast)]
    pub fast_normal: Vec4,
    /// Exact, said again.
    #[pls(r11f_g11f_b10f, conversions = exact)]
    pub light: Vec3,
}

/// The formats that fast conversions change: those WGSL has pack builtins for, rgb10_a2,
/// rounded in f32 arithmetic, and r11f_g11f_b10f, through cut halves.
#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
#[gbuffer(budget = 160, conversions = fast)]
pub struct FastFormats {
    /// `rgba8`, through `pack4x8unorm`.
    #[pls(rgba8)]
    pub unorm_8: Vec4,
    /// `rg16`, through `pack2x16unorm`.
    #[pls(rg16)]
    pub unorm_16: Vec2,
    /// `rg16f`, through `pack2x16float`.
    #[pls(rg16f)]
    pub halves: Vec2,
    /// `rgb10_a2`, through f32 arithmetic (WGSL has no builtin for it).
    #[pls(rgb10_a2)]
    pub unorm_10_10_10_2: Vec4,
    /// `r11f_g11f_b10f`, through `pack2x16float` and shifts.
    #[pls(r11f_g11f_b10f)]
    pub small_floats: Vec3,
}

/// A layout with every bit-field encoding at the widths where each is hardest (1 bit, the
/// largest, odd ones, vectors), beside whole words.
#[allow(missing_docs)] // each field's name says its encoding and width
#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
#[gbuffer(budget = 1024)]
pub struct EveryEncoding {
    #[bits(1, unorm)]
    pub unorm_1: f32,
    #[bits(4, unorm)]
    pub unorm_4: f32,
    #[bits(12, unorm)]
    pub unorm_12: f32,
    #[bits(20, unorm)]
    pub unorm_20: f32,
    #[bits(23, unorm)]
    pub unorm_23: f32,
    #[bits(30, unorm)]
    pub unorm_3x10: Vec3,
    #[bits(2, snorm)]
    pub snorm_2: f32,
    #[bits(8, snorm)]
    pub snorm_8: f32,
    #[bits(16, snorm)]
    pub snorm_16: f32,
    #[bits(24, snorm)]
    pub snorm_24: f32,
    #[bits(32, snorm)]
    pub snorm_4x8: Vec4,
    #[bits(1, sint)]
    pub sint_1: i32,
    #[bits(7, sint)]
    pub sint_7: i32,
    #[bits(32, sint)]
    pub sint_32: i32,
    #[bits(16, sint)]
    pub sint_2x8: IVec2,
    #[bits(1, uint)]
    pub uint_1: u32,
    #[bits(13, uint)]
    pub uint_13: u32,
    #[bits(32, uint)]
    pub uint_32: u32,
    #[bits(24, uint)]
    pub uint_4x6: UVec4,
    #[bits(1, bool)]
    pub flag: bool,
    #[bits(16, half)]
    pub half: f32,
    #[bits(32, half)]
    pub halves: Vec2,
    #[bits(32, rgb9e5)]
    pub shared_exponent: Vec3,
    #[bits(2, octahedral)]
    pub octahedral_2: Vec3,
    #[bits(16, octahedral)]
    pub octahedral_16: Vec3,
    #[bits(24, octahedral)]
    pub octahedral_24: Vec3,
    #[bits(32, octahedral)]
    pub octahedral_32: Vec3,
    #[bits(32, rgbm(6))]
    pub rgbm_6: Vec3,
    #[bits(32, rgbm(51.5))]
    pub rgbm_51_5: Vec3,
    #[bits(32, float32)]
    pub float32: f32,
    #[bits(6, unsigned_float)]
    pub unsigned_float_6: f32,
    #[bits(15, unsigned_float)]
    pub unsigned_float_15: f32,
    #[bits(30, unsigned_float)]
    pub unsigned_float_3x10: Vec3,
    #[bits(6, log_luminance)]
    pub log_luminance_6: f32,
    #[bits(24, log_luminance)]
    pub log_luminance_24: f32,
    #[bits(30, log_luminance)]
    pub log_luminance_3x10: Vec3,
    #[pls(rgba8)]
    pub whole_word: Vec4,
    #[bits(3, unorm)]
    pub after_a_whole_word: f32,
}

/// Bit fields of every encoding with a fast form, under fast conversions.
#[allow(missing_docs)] // each field's name says its encoding and width
#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
#[gbuffer(budget = 224, conversions = fast)]
pub struct FastBitFields {
    #[bits(12, unorm)]
    pub unorm_12: f32,
    #[bits(15, unorm)]
    pub unorm_3x5: Vec3,
    #[bits(16, half)]
    pub half: f32,
    #[bits(32, half)]
    pub halves: Vec2,
    #[bits(24, octahedral)]
    pub octahedral_24: Vec3,
    #[bits(32, octahedral)]
    pub octahedral_32: Vec3,
    #[bits(32, rgbm(6))]
    pub rgbm_6: Vec3,
    #[bits(32, rgbm(51.5))]
    pub rgbm_51_5: Vec3,
}

/// Runs the cost model's helper (`cost/helper/shader_stats.c`) for `target` by hand, with the
/// target's environment and the shader-db switches on, not through `gbuffer_cost`'s runner:
/// the tests hold the crate's readings to what the driver prints this way.
pub fn shader_stats_by_hand(
    target: &gbuffer_cost::Target,
    arguments: &[&str],
) -> std::process::Output {
    let setup = gbuffer_cost::Setup::find();
    let root = setup.root();
    let mut command = match target.architecture {
        gbuffer_cost::Architecture::X86_64 => {
            let mut command = std::process::Command::new(root.join("bin/shader-stats-x86_64"));
            command.env(
                "LD_PRELOAD",
                format!("/usr/lib/x86_64-linux-gnu/{}", target.shim),
            );
            command
        }
        gbuffer_cost::Architecture::Aarch64 => {
            let mut command = std::process::Command::new("/usr/bin/qemu-aarch64-static");
            command
                .arg("-L")
                .arg(root.join("arm64"))
                .arg("-E")
                .arg(format!(
                    "LD_PRELOAD=/usr/lib/aarch64-linux-gnu/{}",
                    target.shim
                ))
                .arg(root.join("bin/shader-stats-aarch64"));
            command
        }
    };
    command
        .env_remove("VK_ICD_FILENAMES")
        .env("GALLIUM_THREAD", "0")
        .env("MESA_SHADER_CACHE_DISABLE", "true")
        .env("BIFROST_MESA_DEBUG", "shaderdb")
        .env("FD_MESA_DEBUG", "shaderdb")
        .envs(target.environment.iter().copied())
        .args(arguments)
        .output()
        .unwrap()
}
