//! The GPUs a shader can be costed on: each one a Mesa driver, the drm-shim that fakes its
//! kernel driver, the environment that picks the GPU model, and what the driver must call
//! itself for its numbers to be trusted (a shim that fails falls back to llvmpipe or lavapipe
//! without a word).

use serde::Serialize;

/// Which API the shader goes through, and so which form of it the compiler sees.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Api {
    /// OpenGL ES through EGL: GLSL ES (WGSL translated by naga to GLSL ES 3.10, the newest
    /// panfrost accepts).
    Gles,
    /// Vulkan: SPIR-V (WGSL translated by naga).
    Vulkan,
}

/// The compiler family, which says how its statistics read.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Compiler {
    /// panfrost's Bifrost compiler (Mali-G52): cycles split into arithmetic, texture,
    /// varying and load/store.
    Bifrost,
    /// panfrost's Valhall compiler (Mali-G57, G610): cycles split into fma, cvt, sfu,
    /// varying, texture and load/store.
    Valhall,
    /// freedreno's ir3 (Adreno), through GL's shader-db messages.
    Ir3,
    /// ir3 through turnip's pipeline executable statistics.
    Turnip,
    /// RADV's ACO (AMD), through pipeline executable statistics.
    Aco,
    /// nouveau's codegen (NVIDIA), through GL's debug messages.
    Nouveau,
}

/// Which side the driver runs on: natively, or as Debian's arm64 build under qemu-user.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Architecture {
    /// amd64: RADV and nouveau.
    X86_64,
    /// arm64 under qemu: freedreno, turnip, panfrost (Debian builds them only for arm).
    Aarch64,
}

/// One GPU model on one driver.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub struct Target {
    /// The name users give: `mali-g610`, `adreno-740-vulkan`, `amd-navi21`...
    pub name: &'static str,
    /// The GPU, in its vendor's words.
    pub gpu: &'static str,
    /// The API the shader is compiled through.
    pub api: Api,
    /// The compiler, which says how the statistics read.
    pub compiler: Compiler,
    /// The side the driver runs on.
    pub architecture: Architecture,
    /// The drm-shim library's name (in the side's library folder).
    #[serde(skip)]
    pub shim: &'static str,
    /// The environment variables that pick the GPU model and switch the statistics on.
    #[serde(skip)]
    pub environment: &'static [(&'static str, &'static str)],
    /// What the driver's renderer or device name contains when it is this GPU: anything else
    /// (llvmpipe, lavapipe, another model) is refused.
    #[serde(skip)]
    pub expected_device: &'static str,
}

const PANFROST: &str = "libpanfrost_noop_drm_shim.so";
const FREEDRENO: &str = "libfreedreno_noop_drm_shim.so";
const AMDGPU: &str = "libamdgpu_noop_drm_shim.so";
const NOUVEAU: &str = "libnouveau_noop_drm_shim.so";
const FREEDRENO_ICD: &str = "/usr/share/vulkan/icd.d/freedreno_icd.json";
const RADEON_ICD: &str = "/usr/share/vulkan/icd.d/radeon_icd.json";

const fn mali(
    name: &'static str,
    gpu: &'static str,
    compiler: Compiler,
    environment: &'static [(&'static str, &'static str)],
) -> Target {
    Target {
        name,
        gpu,
        api: Api::Gles,
        compiler,
        architecture: Architecture::Aarch64,
        shim: PANFROST,
        environment,
        expected_device: gpu,
    }
}

const fn adreno(
    name: &'static str,
    gpu: &'static str,
    api: Api,
    environment: &'static [(&'static str, &'static str)],
    expected_device: &'static str,
) -> Target {
    Target {
        name,
        gpu,
        api,
        compiler: match api {
            Api::Gles => Compiler::Ir3,
            Api::Vulkan => Compiler::Turnip,
        },
        architecture: Architecture::Aarch64,
        shim: FREEDRENO,
        environment,
        expected_device,
    }
}

const fn amd(
    name: &'static str,
    gpu: &'static str,
    environment: &'static [(&'static str, &'static str)],
    expected_device: &'static str,
) -> Target {
    Target {
        name,
        gpu,
        api: Api::Vulkan,
        compiler: Compiler::Aco,
        architecture: Architecture::X86_64,
        shim: AMDGPU,
        environment,
        expected_device,
    }
}

/// Every target, the list first. The GPU models are the shims' names for them:
/// `PAN_GPU_ID` (hex product id), `FD_GPU_ID`, `AMDGPU_GPU_ID`, `NOUVEAU_CHIPSET`.
pub const TARGETS: [Target; 12] = [
    mali(
        "mali-g52",
        "Mali-G52",
        Compiler::Bifrost,
        &[("PAN_GPU_ID", "7212")],
    ),
    mali(
        "mali-g57",
        "Mali-G57",
        Compiler::Valhall,
        &[("PAN_GPU_ID", "9093")],
    ),
    mali(
        "mali-g610",
        "Mali-G610",
        Compiler::Valhall,
        &[("PAN_GPU_ID", "a867")],
    ),
    adreno(
        "adreno-630",
        "Adreno 630",
        Api::Gles,
        &[("FD_GPU_ID", "630")],
        "FD630",
    ),
    adreno(
        "adreno-660",
        "Adreno 660",
        Api::Gles,
        &[("FD_GPU_ID", "660")],
        "FD660",
    ),
    adreno(
        "adreno-740",
        "Adreno 740",
        Api::Gles,
        &[("FD_GPU_ID", "740")],
        "FD740",
    ),
    adreno(
        "adreno-750",
        "Adreno 750",
        Api::Gles,
        &[("FD_GPU_ID", "750")],
        "FD750",
    ),
    adreno(
        "adreno-630-vulkan",
        "Adreno 630",
        Api::Vulkan,
        &[("FD_GPU_ID", "630"), ("VK_ICD_FILENAMES", FREEDRENO_ICD)],
        "Adreno (TM) 630",
    ),
    adreno(
        "adreno-740-vulkan",
        "Adreno 740",
        Api::Vulkan,
        &[("FD_GPU_ID", "740"), ("VK_ICD_FILENAMES", FREEDRENO_ICD)],
        "Adreno (TM) 740",
    ),
    amd(
        "amd-navi21",
        "AMD Radeon RX 6800 (navi21, RDNA2)",
        &[
            ("AMDGPU_GPU_ID", "navi21"),
            ("VK_ICD_FILENAMES", RADEON_ICD),
        ],
        "NAVI21",
    ),
    amd(
        "amd-navi31",
        "AMD Radeon RX 7900 (navi31, RDNA3)",
        &[
            ("AMDGPU_GPU_ID", "navi31"),
            ("VK_ICD_FILENAMES", RADEON_ICD),
        ],
        "NAVI31",
    ),
    Target {
        name: "nvidia-tu102",
        gpu: "NVIDIA TU102 (Turing)",
        api: Api::Gles,
        compiler: Compiler::Nouveau,
        architecture: Architecture::X86_64,
        shim: NOUVEAU,
        environment: &[("NOUVEAU_CHIPSET", "0x162")],
        expected_device: "NV162",
    },
];

/// The targets costed when none are named: Mali-G52 and G610, Adreno 630 and 740 on GL and
/// Vulkan, AMD navi21 (RADV/ACO) and NVIDIA (nouveau GL).
pub const DEFAULT_TARGETS: [&str; 8] = [
    "mali-g52",
    "mali-g610",
    "adreno-630",
    "adreno-740",
    "adreno-630-vulkan",
    "adreno-740-vulkan",
    "amd-navi21",
    "nvidia-tu102",
];

impl Target {
    /// The target called `name`, or an error listing every name.
    pub fn named(name: &str) -> Result<Target, String> {
        TARGETS
            .iter()
            .find(|target| target.name == name)
            .copied()
            .ok_or_else(|| {
                let names: Vec<&str> = TARGETS.iter().map(|target| target.name).collect();
                format!("no target `{name}`: the targets are {}", names.join(", "))
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_found() {
        for (index, target) in TARGETS.iter().enumerate() {
            assert_eq!(Target::named(target.name), Ok(*target));
            assert!(TARGETS[..index]
                .iter()
                .all(|other| other.name != target.name));
        }
        assert!(DEFAULT_TARGETS
            .iter()
            .all(|name| Target::named(name).is_ok()));
        assert!(Target::named("mali-t880")
            .unwrap_err()
            .contains("mali-g610"));
    }
}
