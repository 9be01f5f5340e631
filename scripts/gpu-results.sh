#!/usr/bin/env bash
# The measurements that want a real GPU, in one command: the trade-off study with its frame
# table (`gbuffer report`), the renderer's bench and the packing times held against an
# independent round trip, written as one dated, adapter-named file.
#
#   scripts/gpu-results.sh build          # here: release binaries into .gpu/ (no GPU needed)
#   scripts/gpu-results.sh run [DIR]      # on the GPU machine: measure, write into DIR
#   scripts/gpu-results.sh adopt DIR      # here: DIR's results replace docs/gpu's in the guide
#   scripts/gpu-results.sh                # build and run, on a machine that has cargo and a GPU
#
# `run` writes DIR/<date>-<adapter>.md (the report's markdown, the frame table, the bench's
# table, the independent round trip's table and verdict), DIR/<date>-<adapter>.json
# (report.json), DIR/<date>-<adapter>/ (the report's plots, which the .md shows) and
# DIR/<date>-<adapter>-heatmaps.tar (the frame table's heat maps); DIR defaults to docs/gpu.
# It needs no Rust toolchain: it runs what `build` put in .gpu/, so a machine that only runs
# binaries (the device tool's) can run it: carry .gpu/ there and run
# `scripts/gpu-results.sh run "$OUT"`. `build` also fetches Debian's packages of the Vulkan
# loader and of glslang and spirv-tools into .gpu/debs, which `run` unpacks where the machine
# lacks them. With a Vulkan loader and an NVIDIA driver, wgpu picks the GPU;
# WGPU_BACKEND=vulkan forces it.
#
# `adopt DIR` takes the .md, .json and plots a run wrote into DIR (the device tool's files_at)
# in place of docs/gpu's set: it removes the old files, renames the old file in every figures
# marker and mention of the documents, and copies the new figures into the tables they show
# (`.ci/check-figures --update`). What it cannot do it names: a table whose columns the new
# file lacks, and the prose that quotes figures, are the writer's. The heat maps' tar (the
# bulk of a run's images) stays out of the repository.
set -euo pipefail

# Copies the executable cargo builds for `cargo ARGS... --message-format=json` whose file name
# starts with PREFIX to .gpu/NAME, without running it (cargo prints where it put it).
copy_executable() {
    local name=$1 prefix=$2
    shift 2
    local built
    built=$(cargo "$@" --message-format=json 2>/dev/null |
        sed -n "s/.*\"executable\":\"\([^\"]*\/$prefix-[^\"]*\)\".*/\1/p" | tail -n 1)
    [ -n "$built" ] || { echo "gpu-results: cargo $* built no $prefix executable" >&2; exit 1; }
    cp "$built" ".gpu/$name"
}

build() {
    cargo build --release -p gbuffer-cli --features report
    mkdir -p .gpu
    cp target/release/gbuffer .gpu/gbuffer
    copy_executable deferred-bench deferred bench --no-run -p gbuffer-render --bench deferred
    # The trade-off crate's tests, of which `run` runs one: the packing table against the
    # independent round trip (`tradeoff/src/independent_harness.rs`), on the GPU's adapter.
    copy_executable tradeoff-tests gbuffer_tradeoff test --release --no-run -p gbuffer-tradeoff --lib
    # (The scene presets the frame table solves are not copied: `run` reads them from the tree.)
    # The commit the binaries are built at, for the results' header: the GPU machine's copy of
    # the tree may have no history, or another commit's.
    local commit
    commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
    git diff --quiet HEAD 2>/dev/null || commit="$commit with uncommitted changes"
    echo "$commit" >.gpu/commit
    echo "gpu-results: built .gpu/gbuffer, .gpu/deferred-bench and .gpu/tradeoff-tests"
    debs
}

# What the GPU's machine may lack, as Debian 12's packages, into .gpu/debs (6 MB): the loaders
# (Vulkan's, and glvnd's for EGL and GLES), which `run` unpacks into / where no Vulkan loader is
# installed, and glslangValidator and spirv-opt (the renderer's Vulkan shaders), which it
# unpacks under /tmp where they are not on PATH. apt's lists go to a folder of their own, so
# the machine's are left alone. Without apt (another system) `run` needs them installed there.
debs() {
    local lists=/tmp/gpu-results-apt
    local options=(-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 "-oDir::State::Lists=$lists")
    rm -rf .gpu/debs
    mkdir -p "$lists/partial" .gpu/debs
    if ! { apt-get "${options[@]}" update -qq &&
        (cd .gpu/debs && apt-get "${options[@]}" download -qq \
            libvulkan1 libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2 glslang-tools spirv-tools); } \
        >/dev/null 2>&1; then
        rm -rf .gpu/debs
        echo "gpu-results: could not fetch the loaders' and tools' packages with apt-get; the GPU's machine needs a Vulkan loader, glslangValidator and spirv-opt of its own" >&2
        return
    fi
    echo "gpu-results: fetched $(ls .gpu/debs | wc -l) packages into .gpu/debs"
}

# Unpacks what .gpu/debs holds and the machine lacks (see `debs`).
unpack_debs() {
    [ -d .gpu/debs ] || return 0
    # grep reads all of ldconfig's list: with -q it would stop at the first match, and under
    # pipefail the SIGPIPE of ldconfig would read as no loader.
    if ! ldconfig -p | grep 'libvulkan\.so\.1' >/dev/null; then
        for deb in .gpu/debs/lib*.deb; do
            dpkg -x "$deb" /
        done
        ldconfig
        echo "gpu-results: unpacked the loaders into /"
    fi
    if ! command -v glslangValidator >/dev/null || ! command -v spirv-opt >/dev/null; then
        for deb in .gpu/debs/glslang-tools_*.deb .gpu/debs/spirv-tools_*.deb; do
            dpkg -x "$deb" /tmp/gpu-results-tools
        done
        export PATH="/tmp/gpu-results-tools/usr/bin:$PATH"
        echo "gpu-results: glslangValidator and spirv-opt from /tmp/gpu-results-tools"
    fi
}

run() {
    local folder=${1:-docs/gpu}
    [ -x .gpu/gbuffer ] && [ -x .gpu/deferred-bench ] && [ -x .gpu/tradeoff-tests ] ||
        { echo "gpu-results: run '$0 build' first (no .gpu/gbuffer)" >&2; exit 1; }
    unpack_debs
    local work
    work=$(mktemp -d)
    .gpu/gbuffer report --out "$work/report" | tee "$work/report.txt"
    # The adapter the study ran on: report.json's "adapter", made a file name.
    local adapter
    adapter=$(sed -n 's/^  "adapter": "\(.*\)",$/\1/p' "$work/report/report.json" | head -n 1)
    local slug
    slug=$(printf '%s' "${adapter:-unknown-adapter}" | tr -cs 'A-Za-z0-9' '-' | sed 's/^-//; s/-$//' | cut -c1-60)
    local name
    name="$(date -u +%Y-%m-%d)-$slug"
    .gpu/deferred-bench | tee "$work/bench.txt"
    # The test prints its table whether it passes or not; a failure is a finding to keep, not a
    # reason to lose the rest of the run. Under CI=true it fails, rather than skips, without an
    # adapter, so that no verdict is written of a test that did not run. `cargo test` leaves it
    # out (`#[ignore]`: it needs the machine to itself), hence `--include-ignored`.
    local verdict="every conversion agrees in both stages (within 15%)"
    CI=true .gpu/tradeoff-tests --include-ignored --exact --nocapture \
        independent_harness::tests::the_packing_times_agree_with_an_independent_round_trip \
        >"$work/independent.txt" 2>&1 || verdict="SOME CONVERSIONS READ APART (the test failed)"
    if grep -q "too busy a machine to tell" "$work/independent.txt"; then
        verdict="$verdict, but for those the last lines name, whose rounds spread too wide to tell"
    fi
    cat "$work/independent.txt"
    mkdir -p "$folder"
    rm -rf "${folder:?}/$name"
    mkdir "$folder/$name"
    find "$work/report" -maxdepth 1 -name '*.png' ! -name 'frame-*-heatmap.png' -exec cp -t "$folder/$name" {} +
    {
        echo "# GPU results: $adapter, $(date -u +%Y-%m-%d)"
        echo
        echo "Written by \`scripts/gpu-results.sh\`, its binaries built at commit $(cat .gpu/commit 2>/dev/null || echo unknown)."
        echo "Compare ratios between rows, not absolute times with another machine's."
        echo
        report_markdown "$name" <"$work/report/report.md"
        echo
        echo "## The renderer's bench"
        echo
        echo '```text'
        cat "$work/bench.txt"
        echo '```'
        echo
        echo "## The packing times against an independent round trip"
        echo
        echo "The report's pack plus unpack time of each conversion, in each stage, against chains"
        echo "of its own (\`tradeoff/src/independent_harness.rs\`), in ns a step: $verdict."
        echo
        echo '```text'
        cat "$work/independent.txt"
        echo '```'
    } >"$folder/$name.md"
    cp "$work/report/report.json" "$folder/$name.json"
    (cd "$work/report" && tar -cf - frame-*-heatmap.png) >"$folder/$name-heatmaps.tar"
    echo "gpu-results: wrote $folder/$name.md, $name.json, $name/ (the plots) and $name-heatmaps.tar"
}

# The report's markdown, from standard input, as the run named $1 keeps it: each plot's image
# link leads into the folder $1 beside the .md, where `run` copies the plots, and the frame
# table names each heat map by its file in the tar, which the repository does not keep, where
# a link would lead nowhere.
report_markdown() {
    sed -E -e "s#(!\[[^]]*\]\()([A-Za-z0-9_.-]+\.png\))#\1$1/\2#g" \
        -e 's#\[png\]\((frame-[A-Za-z0-9_.-]+-heatmap\.png)\)#`\1`#g'
}

# The documents that may name a run's file: those whose tables `.ci/check-figures` holds.
DOCUMENTS=(README.md bevy/README.md book/src/*.md)

adopt() {
    local from=${1%/}
    local found
    found=$(cd "$from" 2>/dev/null && ls -- [0-9][0-9][0-9][0-9]-[0-9][0-9]-[0-9][0-9]-*.md 2>/dev/null || true)
    if [ -z "$found" ] || [ "$(printf '%s\n' "$found" | wc -l)" != 1 ]; then
        echo "gpu-results: $from should hold the one <date>-<adapter>.md a run writes; it holds: $(echo ${found:-none})" >&2
        exit 1
    fi
    local name=${found%.md}
    [ -f "$from/$name.json" ] ||
        { echo "gpu-results: $from/$name.md has no $name.json beside it" >&2; exit 1; }
    local old_md old
    for old_md in docs/gpu/[0-9][0-9][0-9][0-9]-[0-9][0-9]-[0-9][0-9]-*.md; do
        [ -e "$old_md" ] || continue
        old=$(basename "$old_md" .md)
        [ "$old" = "$name" ] && continue
        rm -rf "docs/gpu/$old.md" "docs/gpu/$old.json" "docs/gpu/$old-heatmaps.tar" "docs/gpu/${old:?}"
        # The markers and the prose's mentions of the file, by its path.
        grep -l -F "docs/gpu/$old." "${DOCUMENTS[@]}" | xargs -r sed -i "s|docs/gpu/$old\.|docs/gpu/$name.|g" || true
        echo "gpu-results: docs/gpu/$old.md, .json and plots removed, the documents name docs/gpu/$name.md"
    done
    cp "$from/$name.md" "$from/$name.json" docs/gpu/
    # The plots, where the run kept them (runs before its folder had none).
    rm -rf "docs/gpu/${name:?}"
    [ ! -d "$from/$name" ] || cp -r "$from/$name" docs/gpu/
    echo "gpu-results: docs/gpu/$name.md, .json and its plots copied from $from"
    # Only the tables that quote the GPU's file: the others' files are other commands'.
    local status=0
    .ci/check-figures --update --source "docs/gpu/$name.md" || status=$?
    echo "gpu-results: the new run: $(sed -n '1s/^# GPU results: //p' "docs/gpu/$name.md"); $(sed -n 's/^Written by `scripts\/gpu-results.sh`, //p' "docs/gpu/$name.md" | head -n 1)"
    if ((status != 0)); then
        echo "gpu-results: rewrite by hand the tables named above (their columns are not the new file's), then run .ci/check-figures" >&2
    fi
    echo "gpu-results: then read again, by hand, the prose that quotes the GPU's figures (book/src/speed-and-accuracy.md, 'On a real GPU'; book/src/fused-renderer.md's paths) and docs/gpu/README.md's 'What is here'"
    return "$status"
}

# Sourced (`.ci/check-gpu-adopt` tests report_markdown so), it only defines its functions.
[ "${BASH_SOURCE[0]}" = "$0" ] || return 0
cd "$(dirname "$0")/.."
case "${1:-all}" in
build) build ;;
run) run "${2:-}" ;;
adopt) [ $# = 2 ] || { echo "usage: $0 adopt DIR" >&2; exit 2; }; adopt "$2" ;;
all) build && run "${2:-}" ;;
*) echo "usage: $0 [build | run [DIR] | adopt DIR | all [DIR]]" >&2; exit 2 ;;
esac
