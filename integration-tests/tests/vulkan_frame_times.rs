//! The frame table's Vulkan paths (`gbuffer_tradeoff::vulkan_frames`) on lavapipe: every path
//! of a layout the on-tile paths keep gets a time by the protocol, a device without local read
//! gets none for the local-read paths (and says why), and a layout the on-tile paths do not
//! keep gets no row.

use std::cell::RefCell;

use gbuffer_gpu::timing::Protocol;
use gbuffer_gpu::vulkan::{OptionalExtensions, Vulkan};
use gbuffer_render::gbuffers::{GBuffer, PackedLayout};
use gbuffer_render::on_tile::Path;
use gbuffer_render::options::{IblForm, Options, SunForm};
use gbuffer_render::vulkan::VulkanRenderer;
use gbuffer_testkit::or_skip;
use gbuffer_tradeoff::vulkan_frames::{time_paths, PATHS};

fn options(layout: PackedLayout) -> Options {
    Options {
        gbuffer: GBuffer::Packed(layout),
        sun: SunForm::Ggx,
        ibl: IblForm::Lut,
        width: 64,
        height: 64,
    }
}

/// Each path, and whether it got a time.
type Timed = Vec<(Path, bool)>;

/// Which of `layout`'s paths got times on a device opened with `optional` (none: the on-tile
/// paths do not keep the layout), and what was reported.
fn times(
    optional: OptionalExtensions,
    layout: PackedLayout,
) -> Option<(Option<Timed>, Vec<String>)> {
    let vulkan = or_skip("Vulkan", Vulkan::with(optional))?;
    let renderer = VulkanRenderer::on(vulkan, &|_| {}).unwrap_or_else(|error| panic!("{error}"));
    let said = RefCell::new(Vec::new());
    let times = time_paths(&renderer, &options(layout), &Protocol::SHORT, &|line| {
        said.borrow_mut().push(line.to_string())
    })
    .unwrap_or_else(|error| panic!("{error}"));
    let times = times.map(|times| {
        assert_eq!(
            times.iter().map(|(path, _)| *path).collect::<Vec<_>>(),
            PATHS
        );
        times
            .into_iter()
            .map(|(path, time)| {
                if let Some(time) = time {
                    assert!(0.0 < time.min && time.min <= time.median && time.median <= time.max);
                }
                (path, time.is_some())
            })
            .collect()
    });
    Some((times, said.into_inner()))
}

#[test]
fn every_vulkan_path_is_timed_where_the_device_draws_it() {
    let Some((times, said)) = times(OptionalExtensions::Offered, PackedLayout::MobileMetallic)
    else {
        return;
    };
    // lavapipe offers local read and rasterization order.
    assert_eq!(
        times,
        Some(PATHS.map(|path| (path, true)).to_vec()),
        "{said:?}"
    );
}

#[test]
fn a_device_without_local_read_gets_no_local_read_times_and_says_why() {
    let Some((times, said)) = times(OptionalExtensions::None, PackedLayout::MobileMetallic) else {
        return;
    };
    let drawn = |path: Path| !matches!(path, Path::LocalRead | Path::LocalReadOrdered);
    assert_eq!(times, Some(PATHS.map(|path| (path, drawn(path))).to_vec()));
    // One line a path it cannot draw (a loaded machine may add that the times did not settle).
    let refused: Vec<&String> = (said.iter())
        .filter(|line| line.starts_with("frame table: no "))
        .collect();
    assert_eq!(refused.len(), 2, "{said:?}");
    assert!(refused[0].starts_with("frame table: no local-read frames: --path local-read needs"));
    assert!(refused[1]
        .starts_with("frame table: no local-read-ordered frames: --path local-read-ordered needs"));
}

#[test]
fn a_layout_the_on_tile_paths_do_not_keep_has_no_vulkan_times() {
    let Some((times, _)) = times(OptionalExtensions::Offered, PackedLayout::SpecularWorkflow)
    else {
        return;
    };
    assert_eq!(times, None);
}
