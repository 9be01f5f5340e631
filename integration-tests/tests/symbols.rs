//! Every name a layout's `Symbols` gives is an item the outputs define: callers ask
//! `Symbols` for the names they call, so a name here that no emitter makes would fail only at
//! run time, in a shader. The WGSL's items are read back through naga's parser
//! (`gbuffer_translate::items::wgsl_items`: its functions, structs, constants and textures
//! by name); the GLSL includes, which no parser here reads, by their
//! definitions' lines (`<type> <name>(<parameters>) {`), which the items each include says it
//! declares (`Interface::declares`) are held to.

use gbuffer::layout::{Direction, Layout, Symbols};
use gbuffer::GBufferLayout;
use gbuffer_build::output::{generate, Output};
use gbuffer_codegen::emit::glsl;
use gbuffer_codegen::emit::glsl::{Include, PlsBlock};
use gbuffer_codegen::CompiledLayout;
use gbuffer_core::Conversions;
use gbuffer_testkit::layouts::{seeds_and_every_format, AWKWARD_LAYOUT_NAMES};
use gbuffer_translate::items::{wgsl_items, ItemKind};

/// The layouts checked: the seeds, the engines', every format and encoding, and the seed
/// `MobileMetallic` under every name GLSL reserves.
fn layouts() -> Vec<Layout> {
    let mut layouts = seeds_and_every_format();
    let mobile = gbuffer::seed_layouts::MobileMetallic::layout();
    layouts.extend(AWKWARD_LAYOUT_NAMES.iter().map(|name| Layout {
        name: name.to_string(),
        ..mobile.clone()
    }));
    layouts
}

/// The names of the functions a GLSL text defines, by their definitions' lines: a reference
/// independent of the include's list of what it declares.
fn glsl_functions(text: &str) -> Vec<String> {
    text.lines()
        .filter(|line| !line.starts_with(' ') && line.ends_with(") {"))
        .filter_map(|line| line.split('(').next()?.split_whitespace().last())
        .map(str::to_string)
        .collect()
}

#[test]
fn every_wgsl_name_is_an_item_of_the_wgsl_and_the_lighting_source() {
    for layout in layouts() {
        let symbols = layout.symbols();
        let wgsl = format!(
            "{}\n{}",
            gbuffer_codegen::wgsl::emit(&layout),
            gbuffer::targets::lighting_wgsl(&layout, 0, 0)
        );
        let items = wgsl_items(&wgsl).unwrap_or_else(|error| panic!("{}: {error}", layout.name));
        let named = |kind: ItemKind| -> Vec<&str> {
            items
                .iter()
                .filter(|item| item.kind == kind)
                .map(|item| item.name.as_str())
                .collect()
        };
        let (functions, types) = (named(ItemKind::Function), named(ItemKind::Struct));
        let (constants, globals) = (named(ItemKind::Constant), named(ItemKind::Texture));

        let mut wanted_functions = vec![
            symbols.pack(),
            symbols.unpack(),
            symbols.pack_targets(),
            symbols.unpack_targets(),
            symbols.words_from_targets(),
            symbols.load_targets(),
            symbols.read_targets(),
        ];
        wanted_functions.extend(
            layout
                .fields
                .iter()
                .map(|field| symbols.load_field(&field.name)),
        );
        // Each word's and bit field's conversions, both ways (these layouts set no field's
        // own conversions, so no name has a mode suffix).
        for direction in [Direction::Encode, Direction::Decode] {
            for (index, field) in layout.fields.iter().enumerate() {
                wanted_functions.push(match field.format() {
                    Some(format) => symbols.format_word(direction, format, ""),
                    None => symbols.bit_field(direction, index),
                });
            }
        }
        for function in &wanted_functions {
            assert!(
                functions.contains(&function.as_str()),
                "{}: no WGSL function `{function}`",
                layout.name
            );
        }
        for ty in [symbols.texel().to_string(), symbols.targets()] {
            assert!(
                types.contains(&ty.as_str()),
                "{}: no WGSL struct `{ty}`",
                layout.name
            );
        }
        let constant = symbols.words_constant();
        assert!(
            constants.contains(&constant.as_str()),
            "{}: no WGSL constant `{constant}`",
            layout.name
        );
        for target in (0..layout.targets()).map(|index| symbols.target(index)) {
            assert!(
                globals.contains(&target.as_str()),
                "{}: no WGSL texture `{target}`",
                layout.name
            );
        }
    }
}

#[test]
fn every_glsl_name_is_defined_by_the_includes_that_read_or_write() {
    for layout in layouts() {
        let symbols = layout.symbols();
        let compiled = CompiledLayout::new(&layout, Conversions::Exact).unwrap();
        let names = compiled.names();
        for include in Include::ALL {
            let (text, interface) = glsl::include(&compiled, include, 0)
                .unwrap_or_else(|error| panic!("{} {include:?}: {error}", layout.name));
            let functions = glsl_functions(&text);
            let defined = |name: &str| functions.iter().any(|function| function == name);
            // What the include says it declares: its functions are the ones its text defines,
            // and each item's text stands in the include, in order.
            let declared: Vec<&str> = interface
                .declares
                .iter()
                .filter(|item| item.kind == ItemKind::Function)
                .map(|item| item.glsl.as_str())
                .collect();
            assert_eq!(declared, functions, "{} {include:?}", layout.name);
            let mut rest = text.as_str();
            for item in &interface.declares {
                let at = rest.find(&item.text).unwrap_or_else(|| {
                    panic!(
                        "{} {include:?}: `{}` out of order or not in the text",
                        layout.name, item.glsl
                    )
                });
                rest = &rest[at + item.text.len()..];
            }
            let kinds = |kind: ItemKind| {
                interface
                    .declares
                    .iter()
                    .filter(|item| item.kind == kind)
                    .count()
            };
            let attachments = interface.attachments.len() + interface.planes.len();
            assert_eq!(
                kinds(ItemKind::Attachment),
                attachments,
                "{} {include:?}",
                layout.name
            );
            let blocks = usize::from(matches!(include, Include::PixelLocalStorage(_)));
            assert_eq!(
                kinds(ItemKind::Block),
                blocks,
                "{} {include:?}",
                layout.name
            );
            let (reads, writes) = match include {
                Include::PixelLocalStorage(_) => (false, false),
                Include::SubpassPacked | Include::SubpassNative => (true, false),
                Include::FetchPacked | Include::FetchNative | Include::WebGlPixelLocalStorage => {
                    (true, true)
                }
            };
            assert_eq!(
                defined(&symbols.load()),
                reads,
                "{} {include:?}: `{}`",
                layout.name,
                symbols.load()
            );
            assert_eq!(
                defined(&symbols.store()),
                writes,
                "{} {include:?}: `{}`",
                layout.name,
                symbols.store()
            );
            // The layout's WGSL functions, as naga translates them.
            if !matches!(
                include,
                Include::PixelLocalStorage(_) | Include::WebGlPixelLocalStorage
            ) {
                let mut translated = vec![
                    symbols.pack(),
                    symbols.unpack(),
                    symbols.pack_targets(),
                    symbols.unpack_targets(),
                    symbols.words_from_targets(),
                ];
                translated.extend(
                    layout
                        .fields
                        .iter()
                        .map(|field| symbols.load_field(&field.name)),
                );
                for wgsl in &translated {
                    let name = compiled.glsl().glsl_name(wgsl).unwrap_or_else(|| {
                        panic!("{}: the translation has no `{wgsl}`", layout.name)
                    });
                    assert!(defined(name), "{} {include:?}: no `{name}`", layout.name);
                    // naga's writer gives a name ending in a digit a `_` (`proc::Namer::call`),
                    // and the generated names are no GLSL keyword.
                    let expected = match wgsl.ends_with(|c: char| c.is_ascii_digit()) {
                        true => format!("{wgsl}_"),
                        false => wgsl.clone(),
                    };
                    assert_eq!(name, expected, "{}", layout.name);
                }
            }
            if include.is_packed() {
                let names: Vec<&str> = interface
                    .attachments
                    .iter()
                    .map(|attachment| attachment.name.as_str())
                    .collect();
                let targets: Vec<String> = (0..layout.targets())
                    .map(|index| symbols.target(index))
                    .collect();
                assert_eq!(names, targets, "{} {include:?}", layout.name);
                assert!(
                    text.contains(&format!(" {};", symbols.target(0))),
                    "{} {include:?}",
                    layout.name
                );
            }
            // The pixel local storage includes' loads of one field: the WebGL include's of
            // every field, a readable EXT block's of each bit field.
            let loaded: Vec<usize> = match include {
                Include::WebGlPixelLocalStorage => (0..layout.fields.len()).collect(),
                Include::PixelLocalStorage(PlsBlock::In | PlsBlock::InOut) => {
                    (0..layout.fields.len())
                        .filter(|&index| layout.fields[index].bit_field().is_some())
                        .collect()
                }
                _ => Vec::new(),
            };
            for index in loaded {
                let load = symbols.load_pls(&names.fields[index]);
                assert!(defined(&load), "{} {include:?}: no `{load}`", layout.name);
            }
            if let Include::PixelLocalStorage(_) = include {
                let block = Symbols::pixel_local_storage_block(&names.layout);
                assert!(
                    text.contains(&format!(" {block} {{")),
                    "{} {include:?}: no block `{block}`",
                    layout.name
                );
            }
        }
    }
}

#[test]
fn every_file_name_is_a_file_the_codegen_writes() {
    let layout = gbuffer::seed_layouts::MobileMetallic::layout();
    let symbols = layout.symbols();
    let files: Vec<String> = generate(&layout, Conversions::Exact, &Output::ALL)
        .unwrap()
        .into_iter()
        .map(|file| file.name)
        .collect();
    let mut wanted = vec![
        symbols.wgsl_file(),
        symbols.file("rs"),
        symbols.file("report.txt"),
    ];
    wanted.extend(
        Include::ALL
            .iter()
            .map(|include| symbols.file(&format!("{}.glsl", include.file_suffix()))),
    );
    for file in wanted {
        assert!(files.contains(&file), "no file `{file}` in {files:?}");
    }
}
