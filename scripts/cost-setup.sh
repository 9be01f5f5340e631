#!/usr/bin/env bash
# Installs what the cost model (`gbuffer cost`, the gbuffer-cost package) needs to run real GPU
# compilers on a Debian 12 machine with no GPU, and skips what is already there:
#
# - host packages: Mesa 25's drm-shim (bookworm-backports), which fakes a GPU's kernel driver
#   so that Mesa's production compilers run; qemu-user-static, which runs arm64 programs; the
#   arm64 C compiler and the GL/EGL/Vulkan headers that build the helper;
# - $GBUFFER_COST_ROOT/arm64 (default /opt/gbuffer-cost/arm64): Debian's arm64 Mesa (freedreno
#   and panfrost GL, turnip and panvk Vulkan, their drm-shims) and what it links against,
#   unpacked into a private folder: no foreign architecture is registered with dpkg;
# - $GBUFFER_COST_ROOT/bin/shader-stats-{x86_64,aarch64}: cost/helper/shader_stats.c, built for
#   each side (amd64 runs RADV, radeonsi and nouveau natively; arm64 runs under qemu).
#
# Run as root (apt-get). About 110 MB of host packages and 60 MB of arm64 ones; under a minute
# on a fresh machine, a second when everything is in place. Exit status 1 names what failed.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/debian.sh

root=${GBUFFER_COST_ROOT:-/opt/gbuffer-cost}
# Mesa's packages must be backports' (the drm-shim's version must be the drivers'), the
# others may be Debian 12's.
mesa_packages=(mesa-drm-shim mesa-vulkan-drivers libgl1-mesa-dri libegl-mesa0)
host_packages=(qemu-user-static gcc-aarch64-linux-gnu libc6-dev-arm64-cross libvulkan-dev
    libegl-dev libgles-dev)
arm64_packages=(libegl1 libegl-mesa0 libgles2 libgl1-mesa-dri mesa-vulkan-drivers libvulkan1
    mesa-drm-shim)

fail() {
    echo "cost-setup: $*" >&2
    exit 1
}

# 1. Host packages, from backports where it has them.
mapfile -t missing < <(missing_packages "${mesa_packages[@]}" -- "${host_packages[@]}")
if ((${#missing[@]})); then
    add_backports cost-setup "the cost model needs Mesa 25.0's drm-shim and its compilers, for \
the host and for arm64 under qemu-user: run it on Debian 12 (a container of it will do)"
    retry apt-get update -qq || fail "could not update the package lists"
    retry apt-get install -y -qq --no-install-recommends -t bookworm-backports "${missing[@]}" \
        >/dev/null || fail "could not install ${missing[*]}"
fi

# 2. The arm64 side: a private apt state (its own lists, an empty dpkg status, arm64 only), so
#    that apt resolves the packages' whole dependency closure and downloads it without touching
#    the host's dpkg; then each .deb is unpacked into one folder that qemu uses as its root.
stamp_of() {
    { printf '%s\n' "${arm64_packages[@]}"; sha256sum cost/helper/shader_stats.c; } | sha256sum
}
stamp=$(stamp_of)
if [ "$(cat "$root/stamp" 2>/dev/null)" = "$stamp" ] && [ -x "$root/bin/shader-stats-aarch64" ]; then
    echo "cost-setup: $root is in place"
    exit 0
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/lists/partial" "$work/cache/archives/partial" "$work/arm64" "$work/bin"
touch "$work/status"
printf 'deb [arch=arm64 signed-by=/usr/share/keyrings/debian-archive-keyring.gpg] http://deb.debian.org/debian %s main\n' \
    bookworm bookworm-backports >"$work/sources.list"
apt_arm64=(-o APT::Architecture=arm64 -o APT::Architectures::=arm64
    -o Dir::State::Lists="$work/lists" -o Dir::State::status="$work/status"
    -o Dir::Cache="$work/cache" -o Dir::Etc::SourceList="$work/sources.list"
    -o Dir::Etc::SourceParts=/dev/null -o Dir::Etc::Preferences=/dev/null
    -o Dir::Etc::PreferencesParts=/dev/null -o APT::Sandbox::User=root)
retry apt-get "${apt_arm64[@]}" update -qq || fail "could not update the arm64 package lists"
retry apt-get "${apt_arm64[@]}" install -y -qq --download-only --no-install-recommends \
    -t bookworm-backports "${arm64_packages[@]}" >/dev/null ||
    fail "could not download the arm64 packages ${arm64_packages[*]}"
for deb in "$work"/cache/archives/*.deb; do
    dpkg-deb -x "$deb" "$work/arm64" || fail "could not unpack $deb"
done

# 3. The helper, for both sides. The headers are the host's (they are the same on every
#    architecture); the cross compiler does not search /usr/include, so it gets a folder of
#    links to just those.
mkdir -p "$work/include"
for folder in EGL KHR GLES2 GLES3 vulkan vk_video; do
    ln -s "/usr/include/$folder" "$work/include/$folder"
done
flags=(-O2 -std=c11 -Wall -Wextra -Werror -isystem "$work/include")
gcc "${flags[@]}" -o "$work/bin/shader-stats-x86_64" cost/helper/shader_stats.c ||
    fail "could not build the amd64 helper"
aarch64-linux-gnu-gcc "${flags[@]}" -o "$work/bin/shader-stats-aarch64" cost/helper/shader_stats.c ||
    fail "could not build the arm64 helper"

# Everything or nothing: the new folders replace the old ones only once all of them are built.
mkdir -p "$root"
rm -rf "$root/arm64" "$root/bin"
mv "$work/arm64" "$root/arm64"
mv "$work/bin" "$root/bin"
echo "$stamp" >"$root/stamp"
echo "cost-setup: installed $root ($(du -sh "$root" | cut -f1))"
