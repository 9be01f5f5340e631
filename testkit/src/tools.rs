//! The Khronos command-line tools the tests run: `glslangValidator` (Debian's
//! `glslang-tools`) compiles GLSL and Vulkan GLSL, `spirv-val` (`spirv-tools`) checks SPIR-V.
//! `.ci/run` installs both; a missing tool fails the test with the package to install.

use std::process::Command;

/// Runs `tool` with `arguments`: whether it succeeded, and what it printed.
pub fn run(tool: &str, arguments: &[&str], package: &str) -> (bool, String) {
    let output = Command::new(tool).args(arguments).output().unwrap_or_else(|error| {
        panic!("cannot run `{tool}` ({error}): install Debian's `{package}` (apt-get install -y {package})")
    });
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    (output.status.success(), text)
}

/// Compiles a shader of `stage` (`vert`, `frag`, `comp`) with glslang: to SPIR-V for Vulkan
/// when `vulkan` is set (the bytes are returned), otherwise only checked (no bytes). The error
/// is glslang's log followed by the numbered source.
pub fn glslang(source: &str, stage: &str, vulkan: bool) -> Result<Vec<u8>, String> {
    let folder = tempfile::tempdir().expect("a temporary folder");
    let path = folder.path().join(format!("shader.{stage}"));
    let spirv = folder.path().join("shader.spv");
    std::fs::write(&path, source).expect("writing the shader");
    let mut arguments = vec![path.to_str().expect("a UTF-8 path")];
    if vulkan {
        arguments.extend(["-V", "-o", spirv.to_str().expect("a UTF-8 path")]);
    }
    let (ok, text) = run("glslangValidator", &arguments, "glslang-tools");
    if !ok {
        return Err(format!("{text}\n{}", crate::gles::numbered(source)));
    }
    Ok(if vulkan {
        std::fs::read(spirv).expect("glslang wrote the SPIR-V")
    } else {
        Vec::new()
    })
}

/// Checks a SPIR-V module with spirv-val for Vulkan 1.1; the error is its log.
pub fn spirv_val(module: &[u8]) -> Result<(), String> {
    let folder = tempfile::tempdir().expect("a temporary folder");
    let path = folder.path().join("module.spv");
    std::fs::write(&path, module).expect("writing the module");
    let (ok, text) = run(
        "spirv-val",
        &[
            "--target-env",
            "vulkan1.1",
            path.to_str().expect("a UTF-8 path"),
        ],
        "spirv-tools",
    );
    if ok {
        Ok(())
    } else {
        Err(text)
    }
}
