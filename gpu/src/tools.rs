//! The Khronos command-line tools: `glslangValidator` (Debian's `glslang-tools`) compiles GLSL
//! and Vulkan GLSL, `spirv-opt` and `spirv-val` (`spirv-tools`) optimise and check SPIR-V. A
//! missing tool is an error naming the package that brings it.

use std::path::{Path, PathBuf};
use std::process::Command;

/// Runs `tool` with `arguments`: whether it succeeded and what it printed, or, where the tool
/// cannot be run, an error naming the Debian `package` to install.
fn run(tool: &str, arguments: &[&str], package: &str) -> Result<(bool, String), String> {
    let output = Command::new(tool).args(arguments).output().map_err(|error| {
        format!("cannot run `{tool}` ({error}): install Debian's `{package}` (apt-get install -y {package})")
    })?;
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    Ok((output.status.success(), text))
}

/// Compiles a shader of `stage` (`vert`, `frag`, `comp`) with glslang: to SPIR-V for Vulkan
/// when `vulkan` is set (the bytes are returned), otherwise only checked (no bytes). The error
/// is glslang's log followed by the numbered source.
pub fn glslang(source: &str, stage: &str, vulkan: bool) -> Result<Vec<u8>, String> {
    let folder = Scratch::new()?;
    let path = folder.write(&format!("shader.{stage}"), source.as_bytes())?;
    let spirv = folder.path("shader.spv");
    let mut arguments = vec![utf8(&path)?];
    if vulkan {
        arguments.extend(["-V", "-o", utf8(&spirv)?]);
    }
    let (ok, text) = run("glslangValidator", &arguments, "glslang-tools")?;
    if !ok {
        return Err(format!("{text}\n{}", numbered(source)));
    }
    if vulkan {
        std::fs::read(&spirv).map_err(|error| format!("reading glslang's SPIR-V: {error}"))
    } else {
        Ok(Vec::new())
    }
}

/// Optimises a SPIR-V module with `spirv-opt -O`; the error is its log.
pub fn spirv_opt(module: &[u8]) -> Result<Vec<u8>, String> {
    let folder = Scratch::new()?;
    let input = folder.write("in.spv", module)?;
    let output = folder.path("out.spv");
    let (ok, log) = run(
        "spirv-opt",
        &["-O", utf8(&input)?, "-o", utf8(&output)?],
        "spirv-tools",
    )?;
    if !ok {
        return Err(format!("spirv-opt: {log}"));
    }
    std::fs::read(&output).map_err(|error| format!("reading spirv-opt's output: {error}"))
}

/// Checks a SPIR-V module with spirv-val for Vulkan 1.1; the error is its log.
pub fn spirv_val(module: &[u8]) -> Result<(), String> {
    let folder = Scratch::new()?;
    let path = folder.write("module.spv", module)?;
    let (ok, text) = run(
        "spirv-val",
        &["--target-env", "vulkan1.1", utf8(&path)?],
        "spirv-tools",
    )?;
    if ok {
        Ok(())
    } else {
        Err(text)
    }
}

/// The source with line numbers, as drivers' and compilers' logs cite them.
pub fn numbered(source: &str) -> String {
    source
        .lines()
        .enumerate()
        .map(|(index, line)| format!("{:4} {line}\n", index + 1))
        .collect()
}

/// A folder of its own under the system's temporary folder, removed when dropped: the tools
/// read and write files.
struct Scratch(PathBuf);

impl Scratch {
    fn new() -> Result<Scratch, String> {
        use std::sync::atomic::{AtomicUsize, Ordering};
        static NEXT: AtomicUsize = AtomicUsize::new(0);
        let name = format!(
            "gbuffer-{}-{}",
            std::process::id(),
            NEXT.fetch_add(1, Ordering::Relaxed)
        );
        let path = std::env::temp_dir().join(name);
        std::fs::create_dir_all(&path)
            .map_err(|error| format!("cannot create {}: {error}", path.display()))?;
        Ok(Scratch(path))
    }

    fn path(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }

    fn write(&self, name: &str, contents: &[u8]) -> Result<PathBuf, String> {
        let path = self.path(name);
        std::fs::write(&path, contents)
            .map_err(|error| format!("cannot write {}: {error}", path.display()))?;
        Ok(path)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn utf8(path: &Path) -> Result<&str, String> {
    path.to_str()
        .ok_or_else(|| format!("the temporary path {} is not UTF-8", path.display()))
}
