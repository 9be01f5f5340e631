#!/usr/bin/env bash
# The GPU drivers and tools the tests and the examples need on a Debian 12 machine without a GPU,
# in one command (as root): Mesa 25.0 from Debian 12's backports (lavapipe for Vulkan, llvmpipe
# for GL and GLES through EGL), the Vulkan and EGL loaders, glslang and spirv-tools. Skips what
# is already in place; packages named as arguments are installed with them (CI adds chromium).
# `.ci/run` installs the drivers with it, and every document points to the guide's testing
# chapter, which gives it.
#
# Why backports: Debian 12's own Mesa is 22.3, whose lavapipe Dawn's Vulkan backend refuses
# ("shaderUniform*ArrayDynamicIndexing required"), and the tests are written against Mesa 25.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/debian.sh

mesa=(mesa-vulkan-drivers libgl1-mesa-dri libegl-mesa0 libglx-mesa0 libgbm1)
others=(libvulkan1 libegl1 libgles2 glslang-tools spirv-tools "$@")
mapfile -t missing < <(missing_packages "${mesa[@]}" -- "${others[@]}")
if ((${#missing[@]} == 0)); then
    echo "install-drivers: Mesa 25, the loaders, glslang and spirv-tools are in place"
    exit 0
fi
add_backports install-drivers "install Mesa 25 or later (its Vulkan drivers, lavapipe, and its GL \
and EGL drivers, llvmpipe), the Vulkan, EGL and GLES loaders, glslang and spirv-tools from \
your system's packages"
retry apt-get update -qq || { echo "install-drivers: could not update the package lists" >&2; exit 1; }
# Backports' versions where it has them (Mesa's packages only), Debian 12's otherwise.
retry apt-get install -y -qq --no-install-recommends -t bookworm-backports "${mesa[@]}" "${others[@]}" \
    || { echo "install-drivers: could not install ${missing[*]}" >&2; exit 1; }
echo "install-drivers: installed ${missing[*]}"
