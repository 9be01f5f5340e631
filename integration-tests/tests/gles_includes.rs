//! The framebuffer-fetch includes on a real GLES 3.2 driver (Mesa's llvmpipe through EGL
//! surfaceless), exactly as generated: each include is pasted unedited into small user
//! shaders under every preamble its header allows, and
//!
//! - pass 1 builds texels from input scalars (edge cases first: NaN, infinities, denormals,
//!   signed zeros, values beside rounding boundaries, integer extremes; then random values)
//!   and stores them with `store_<layout>()`;
//! - pass 2, in the same framebuffer, loads them through framebuffer fetch with
//!   `load_<layout>()`, stores them again and (where the GLSL has storage buffers) writes
//!   each decoded field's bits to a buffer.
//!
//! The words read back equal the Rust mirror's bit for bit, pass 2 changes no bit, and the
//! decoded fields equal the mirror's unpack. For the seed layouts, a layout of every format,
//! and layouts generated at random (with names GLSL reserves), for the packed include and the
//! native one (one attachment per field, converted by the driver).

use gbuffer::layout::{Field, Format, Layout, Storage};
use gbuffer_codegen::emit::glsl::{self, Include, Interface};
use gbuffer_codegen::CompiledLayout;
use gbuffer_core::Conversions;
use gbuffer_gpu::gles::{Framebuffer, Gles};
use gbuffer_gpu::harness::scalars_per_texel;
use gbuffer_gpu::values::Values;
use gbuffer_testkit::skip_without_driver;
use gbuffer_testkit::texels::{
    check_native_words, compare, compare_decoded, inputs, restore_changes, word_from_components,
};
use gbuffer_testkit::user_shaders::{fetch_user_shaders, has_storage_buffers, preambles};
use proptest::prelude::*;

const WIDTH: i32 = 48;
const HEIGHT: i32 = 48;

fn gles() -> Option<Gles> {
    match Gles::new() {
        Ok(gles) if gles.has_extension("GL_EXT_shader_framebuffer_fetch") => Some(gles),
        Ok(gles) => {
            skip_without_driver(
                "framebuffer fetch",
                &format!("{} lacks GL_EXT_shader_framebuffer_fetch", gles.describe()),
            );
            None
        }
        Err(error) => {
            skip_without_driver("GLES 3.2 through EGL", &error);
            None
        }
    }
}

/// How to read an attachment back so that its bits come out as the layout's word: the pixel
/// format and type, the bytes per pixel, and the word from one pixel's bytes.
fn read_format(format: Option<Format>) -> (u32, u32, usize) {
    let Some(format) = format else {
        return (glow::RGBA_INTEGER, glow::UNSIGNED_INT, 16); // RGBA32UI: four words
    };
    match format {
        Format::Rgb10A2 => (glow::RGBA, glow::UNSIGNED_INT_2_10_10_10_REV, 4),
        Format::Rgba8 => (glow::RGBA, glow::UNSIGNED_BYTE, 4),
        Format::Rg16 => (glow::RGBA, glow::UNSIGNED_SHORT, 8),
        Format::R32f => (glow::RGBA, glow::FLOAT, 16),
        Format::Rg16f => (glow::RGBA, glow::FLOAT, 16),
        Format::R11fG11fB10f => (glow::RGB, glow::UNSIGNED_INT_10F_11F_11F_REV, 4),
        Format::Rgb10A2ui => (glow::RGBA_INTEGER, glow::UNSIGNED_INT_2_10_10_10_REV, 4),
        Format::Rgba8i | Format::Rg16i => (glow::RGBA_INTEGER, glow::INT, 16),
        Format::Rgba8ui | Format::Rg16ui | Format::R32ui => {
            (glow::RGBA_INTEGER, glow::UNSIGNED_INT, 16)
        }
    }
}

/// The layout's word from one pixel of a native attachment read as [`read_format`] says.
fn word_from_pixel(format: Format, pixel: &[u8]) -> u32 {
    let u32_at = |index: usize| u32::from_le_bytes(pixel[index * 4..][..4].try_into().unwrap());
    let u16_at = |index: usize| {
        u32::from(u16::from_le_bytes(
            pixel[index * 2..][..2].try_into().unwrap(),
        ))
    };
    match format {
        Format::Rgb10A2 | Format::Rgba8 | Format::R11fG11fB10f | Format::Rgb10A2ui => u32_at(0),
        Format::Rg16 => u16_at(0) | (u16_at(1) << 16),
        // Four 32-bit components, floats (RG16F and R32F read back only as floats, which the
        // stored values converted to exactly) or integers: as the Vulkan test reads them.
        _ => word_from_components(format, &[u32_at(0), u32_at(1), u32_at(2), u32_at(3)]),
    }
}

/// The words of every texel, read back from the attachments.
fn read_words(
    gles: &Gles,
    framebuffer: &Framebuffer,
    layout: &Layout,
    interface: &Interface,
) -> Vec<u32> {
    let texels = (framebuffer.width * framebuffer.height) as usize;
    let word_count = layout.words();
    let mut words = vec![0u32; texels * word_count];
    for index in 0..interface.attachments.len() {
        let native = (!interface.include.is_packed()).then(|| layout.word_contents()[index].format);
        let (format, ty, bytes_per_pixel) = read_format(native);
        let mut bytes = vec![0u8; texels * bytes_per_pixel];
        gles.read_attachment(framebuffer, index as u32, format, ty, &mut bytes)
            .unwrap();
        for (texel, pixel) in bytes.chunks_exact(bytes_per_pixel).enumerate() {
            match native {
                Some(format) => words[texel * word_count + index] = word_from_pixel(format, pixel),
                None => {
                    for component in 0..4 {
                        let word = index * 4 + component;
                        if word < word_count {
                            words[texel * word_count + word] =
                                u32::from_le_bytes(pixel[component * 4..][..4].try_into().unwrap());
                        }
                    }
                }
            }
        }
    }
    words
}

/// Runs both passes of `include` for `layout` with `conversions` under `preamble`; pushes
/// mismatches onto `failures`. Prints why and returns when the driver has too few draw
/// buffers for the layout.
fn check(
    gles: &Gles,
    (layout, conversions): (&Layout, Conversions),
    include: Include,
    preamble: &str,
    seed: u64,
    failures: &mut Vec<String>,
) {
    let compiled = CompiledLayout::new(layout, conversions).unwrap();
    let (_, interface) = glsl::include(&compiled, include, 0).unwrap();
    let draw_buffers = gles.limit(glow::MAX_DRAW_BUFFERS) as usize;
    if interface.attachments.len() > draw_buffers {
        eprintln!(
            "{}: {include:?} needs {} attachments; the driver draws to {draw_buffers}",
            layout.name,
            interface.attachments.len()
        );
        return;
    }
    let what = format!("{include:?} under {:?}", preamble.replace('\n', " "));
    if gles.describe().contains("llvmpipe") && llvmpipe_crashes_compiling(layout, include, preamble)
    {
        eprintln!(
            "{what}: {}: not drawn: llvmpipe crashes compiling its reload shader (a driver bug)",
            layout.name
        );
        return;
    }
    let (store, reload) = fetch_user_shaders(layout, conversions, include, preamble, WIDTH);
    let store = gles
        .program(&store)
        .unwrap_or_else(|log| panic!("{what}: {log}"));
    let reload = gles
        .program(&reload)
        .unwrap_or_else(|log| panic!("{what}: {log}"));

    let scalars = scalars_per_texel(layout);
    let texels = (WIDTH * HEIGHT) as usize;
    let inputs = inputs(layout, 0, texels, &mut Values::new(seed));
    let formats: Vec<u32> = interface
        .attachments
        .iter()
        .map(|attachment| attachment.format.gl.internal_format)
        .collect();
    gles.uint_texture(&inputs, WIDTH * scalars as i32, HEIGHT)
        .unwrap();
    // Pass 1 alone, read back. A second framebuffer runs both passes back to back, as a
    // renderer does: llvmpipe's framebuffer fetch misreads some formats after a readback
    // between the draws, which no renderer does.
    let first = gles.framebuffer(&formats, WIDTH, HEIGHT).unwrap();
    gles.draw_fullscreen(store).unwrap();
    let stored = read_words(gles, &first, layout, &interface);
    let both = gles.framebuffer(&formats, WIDTH, HEIGHT).unwrap();
    let decode = has_storage_buffers(preamble);
    let buffer = decode.then(|| gles.storage_buffer(texels * scalars).unwrap());
    gles.draw_fullscreen(store).unwrap();
    gles.draw_fullscreen(reload).unwrap();
    let reloaded = read_words(gles, &both, layout, &interface);
    let decoded = buffer.map(|buffer| gles.read_storage_buffer(buffer, texels * scalars).unwrap());
    gles.delete(first);
    gles.delete(both);

    let fast = layout.fields.iter().any(|field| {
        let mode = field.conversions.unwrap_or(conversions);
        match field.storage {
            Storage::Word(format) => !mode.is_exact_for(format),
            Storage::Bits(bit_field) => !mode.is_exact_for_encoding(bit_field.encoding),
        }
    });
    if include.is_packed() && !fast {
        // The include's own conversions: the mirror's words, bit for bit.
        compare(
            &what,
            layout,
            &inputs,
            Some(&stored),
            decoded.as_deref(),
            failures,
            12,
        );
    } else {
        // The driver converts (native attachments, or the builtins of fast conversions): its
        // words are its own rounding (GLES lets either neighbour of the exact value stand, and
        // leaves NaN, infinities and out-of-range values to it), so they are held to one code
        // of the mirror on finite inputs in range, and what the shader decodes must equal the
        // mirror's decoding of the words the driver stored.
        check_native_words(&what, layout, &inputs, &stored, failures);
        if let Some(decoded) = &decoded {
            compare_decoded(&what, layout, &stored, decoded, failures, 24);
        }
    }
    let on_llvmpipe = gles.describe().contains("llvmpipe");
    let mut changed_by_driver_bug = 0;
    // Words llvmpipe rewrites wrongly are its bug; the rest must come back unchanged (or, for
    // twin codes, as the mirror re-encodes them).
    let words = layout.word_contents();
    let mut checked = reloaded.to_vec();
    for (index, (before, after)) in stored.iter().zip(checked.iter_mut()).enumerate() {
        let format = words[index % words.len()].format;
        if before != after
            && !include.is_packed()
            && on_llvmpipe
            && llvmpipe_miswrites_after_fetch(format)
        {
            changed_by_driver_bug += 1;
            *after = *before;
        }
    }
    let changed = restore_changes(layout, &stored, &checked).0;
    if changed > 0 {
        failures.push(format!(
            "{what}: {}: store(load()) changed {changed} of {} words",
            layout.name,
            stored.len()
        ));
    }
    if changed_by_driver_bug > 0 {
        eprintln!(
            "{what}: {}: llvmpipe rewrote {changed_by_driver_bug} words of its 8- and 10-bit \
             attachments wrongly after a fetch (a driver bug; the fetched values were right)",
            layout.name
        );
    }
}

/// The formats llvmpipe rewrites wrongly when a draw writes them after fetching them
/// (book/src/driver-notes.md): native 8- and 10-bit attachments.
fn llvmpipe_miswrites_after_fetch(format: Format) -> bool {
    matches!(
        format,
        Format::Rgba8 | Format::Rgb10A2 | Format::Rgba8i | Format::Rgba8ui | Format::Rgb10A2ui
    )
}

/// The shaders llvmpipe (Mesa 25.0) crashes compiling (book/src/driver-notes.md): under GLSL
/// ES 3.00, the native include's `store(load())` of an `rgba8` attachment of fewer than four
/// components first, alone or beside one of four 8- or 10-bit channels holding four components.
fn llvmpipe_crashes_compiling(layout: &Layout, include: Include, preamble: &str) -> bool {
    let four_narrow_channels = |field: &Field| {
        field.ty.components == 4
            && matches!(
                field.storage,
                Storage::Word(
                    Format::Rgba8
                        | Format::Rgb10A2
                        | Format::Rgba8i
                        | Format::Rgba8ui
                        | Format::Rgb10A2ui
                )
            )
    };
    include == Include::FetchNative
        && preamble.starts_with("#version 300 es")
        && match layout.fields.as_slice() {
            [first, rest @ ..] => {
                first.storage == Storage::Word(Format::Rgba8)
                    && first.ty.components < 4
                    && match rest {
                        [] => true,
                        [second] => four_narrow_channels(second),
                        _ => false,
                    }
            }
            [] => false,
        }
}

/// Every seed layout and layout of every format through `include` under every preamble. Each
/// include is a test of its own, so that the two run on two threads.
fn round_trips_bit_exactly_under_every_preamble(include: Include) {
    let Some(gles) = gles() else { return };
    eprintln!("GLES: {}", gles.describe());
    let mut failures = Vec::new();
    for (index, layout) in gbuffer_testkit::layouts::seeds_and_every_format()
        .iter()
        .enumerate()
    {
        for preamble in preambles(include) {
            check(
                &gles,
                (layout, Conversions::Exact),
                include,
                &preamble,
                index as u64,
                &mut failures,
            );
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn packed_fetch_include_round_trips_bit_exactly_on_gles_under_every_preamble() {
    round_trips_bit_exactly_under_every_preamble(Include::FetchPacked);
}

#[test]
fn native_fetch_include_round_trips_bit_exactly_on_gles_under_every_preamble() {
    round_trips_bit_exactly_under_every_preamble(Include::FetchNative);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, failure_persistence: None, ..ProptestConfig::default() })]

    /// Layouts the repo has never seen, named with words GLSL reserves.
    #[test]
    fn random_layouts_round_trip_bit_exactly_on_gles(
        layout in gbuffer_testkit::layouts::random_layout(),
        preamble_index in 0usize..9,
    ) {
        let Some(gles) = gles() else { return Ok(()) };
        let mut failures = Vec::new();
        for include in [Include::FetchPacked, Include::FetchNative] {
            let preambles = preambles(include);
            let preamble = &preambles[preamble_index % preambles.len()];
            check(&gles, (&layout, Conversions::Exact), include, preamble, 7, &mut failures);
        }
        prop_assert!(failures.is_empty(), "{}", failures.join("\n"));
    }
}

/// Fast conversions' includes on the driver under every preamble, as the exact ones are run:
/// under GLSL ES 3.00, which has no `packUnorm4x8`, rgba8 falls back to f32 arithmetic; from
/// 3.10 up the builtins serve. Every channel within one code of the mirror on finite inputs
/// in range, store(load()) changing no bit. For a fast layout, and for an exact one whose
/// fields choose fast conversions of their own.
#[test]
fn fast_includes_round_trip_within_one_code_on_gles_under_every_preamble() {
    use gbuffer::GBufferLayout;
    let Some(gles) = gles() else { return };
    let layouts = [
        (gbuffer_testkit::FastFormats::layout(), Conversions::Fast),
        (
            gbuffer_testkit::MixedConversions::layout(),
            Conversions::Exact,
        ),
    ];
    let mut failures = Vec::new();
    for (layout, conversions) in &layouts {
        for include in [Include::FetchPacked, Include::FetchNative] {
            for preamble in preambles(include) {
                check(
                    &gles,
                    (layout, *conversions),
                    include,
                    &preamble,
                    11,
                    &mut failures,
                );
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
