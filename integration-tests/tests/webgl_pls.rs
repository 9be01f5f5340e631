//! The WebGL pixel local storage include in a real browser: Debian's Chromium, headless, on
//! SwiftShader and on lavapipe (ANGLE over Vulkan on both), driven by the generated host module
//! exactly as generated, with the include pasted unedited into small user shaders under every
//! preamble its header allows.
//!
//! In one pixel local storage pass, the first draw builds texels from input scalars (the edge
//! sets first: NaN, infinities, denormals, signed zeros, rounding boundaries, integer extremes;
//! then random values) and stores them with `store_<layout>()`; the second loads each field
//! with its own `load_pls_<layout>_<field>()`, writes the decoded bits to a colour output, and
//! counts where they differ from `load_<layout>()`'s. The pass stores the planes, which are read
//! back: the words equal the Rust mirror's bit for bit (an rgba8 plane under fast conversions,
//! which the GPU converts, within one code), the decoded fields equal the mirror's unpack, and
//! the two loads agree.
//!
//! For the seed and engine layouts, layouts of every format and encoding, a fast and a mixed
//! layout, and random layouts (with names GLSL reserves): every one of up to seven words, since
//! planes and the colour output share Chromium's limit of eight.

use std::collections::HashMap;
use std::time::Duration;

use gbuffer::layout::Layout;
use gbuffer::GBufferLayout;
use gbuffer_codegen::emit::glsl::webgl::PlaneFormat;
use gbuffer_codegen::emit::glsl::{self, Include, Interface};
use gbuffer_codegen::CompiledLayout;
use gbuffer_core::Conversions;
use gbuffer_core::Named;
use gbuffer_gpu::harness::scalars_per_texel;
use gbuffer_gpu::values::Values;
use gbuffer_testkit::chromium::{element_text, Backend, Chromium};
use gbuffer_testkit::texels::{check_native_words, compare, compare_decoded, inputs};
use gbuffer_testkit::user_shaders::{preambles, scalars_of_texel, texel_from_scalars};
use gbuffer_testkit::{or_skip, skip_without_driver};
use proptest::strategy::{Strategy, ValueTree};
use proptest::test_runner::TestRunner;

/// Texels a row, and rows: 256 texels a case.
const TEXELS_PER_ROW: usize = 16;
const ROWS: usize = 16;
/// Planes and colour outputs together, in Chromium: the cases keep one output.
const MOST_WORDS: usize = 7;

/// One layout under one preamble: what the page runs, and what the test compares.
struct Case {
    name: String,
    layout: Layout,
    interface: Interface,
    /// Where it runs.
    backends: &'static [Backend],
    inputs: Vec<u32>,
    /// The layout's host module.
    host: String,
    /// The case's shaders and inputs, as the page's JSON.
    json: String,
}

/// Colour output pixels per texel: four decoded scalars each, and one more scalar for the count
/// of per-field loads that differ from the whole texel's load.
fn columns(layout: &Layout) -> usize {
    (scalars_per_texel(layout) + 1).div_ceil(4)
}

/// The two fragment shaders of a case: store, then load and decode.
fn user_shaders(compiled: &CompiledLayout, include: &str, preamble: &str) -> (String, String) {
    let (layout, names) = (compiled.layout(), compiled.names());
    let symbols = layout.symbols();
    let (load, store_texel) = (symbols.load(), symbols.store());
    let scalars = scalars_per_texel(layout);
    let columns = columns(layout);
    let texel = texel_from_scalars(layout, names, |index| format!("harness_scalar({index})"));
    let store = format!(
        "{preamble}{include}\n// The user's code.\nuniform highp usampler2D harness_inputs;\n\
         layout(location = 0) out highp uvec4 harness_out;\n\n\
         highp uint harness_scalar(highp int index) {{\n    highp ivec2 pixel = ivec2(gl_FragCoord.xy);\n    \
         return texelFetch(harness_inputs, ivec2((pixel.x / {columns}) * {scalars} + index, pixel.y), 0).x;\n}}\n\n\
         void main() {{\n    {store_texel}({texel});\n    harness_out = uvec4(0u);\n}}\n"
    );
    let texel_type = &names.layout;
    let per_field: Vec<String> = glsl::webgl::field_loads(compiled)
        .iter()
        .map(|load| format!("{load}()"))
        .collect();
    let loaded = scalars_of_texel(layout, names, "loaded");
    let whole = scalars_of_texel(layout, names, "whole");
    let differences: Vec<String> = loaded
        .iter()
        .zip(&whole)
        .map(|(loaded, whole)| format!("uint({loaded} != {whole})"))
        .collect();
    let length = columns * 4;
    let mut outputs = loaded.clone();
    outputs.push(differences.join(" + "));
    outputs.resize(length, "0u".to_string());
    let reload = format!(
        "{preamble}{include}\n// The user's code.\nlayout(location = 0) out highp uvec4 harness_out;\n\n\
         void main() {{\n    {texel_type} loaded = {texel_type}({});\n    {texel_type} whole = {load}();\n    \
         highp uint scalars[{length}] = uint[{length}]({});\n    \
         highp int column = (int(gl_FragCoord.x) % {columns}) * 4;\n    \
         harness_out = uvec4(scalars[column], scalars[column + 1], scalars[column + 2], scalars[column + 3]);\n}}\n",
        per_field.join(", "),
        outputs.join(", ")
    );
    (store, reload)
}

/// Every preamble's case of a layout.
fn cases(layout: &Layout, conversions: Conversions, seed: u64) -> Vec<Case> {
    // SwiftShader's packHalf2x16, which fast rg16f writes, misrounds the second half by up to
    // two codes (1 + 2^-11 gives 0x3c02 where 0x3c00 is right, 2^-25 gives 0x0002 for 0x0000;
    // the first half is right): beyond what any rounding allows, so the fast layout runs on
    // lavapipe alone.
    let backends: &'static [Backend] = match conversions {
        Conversions::Fast => &[Backend::Lavapipe],
        Conversions::Exact => Backend::ALL,
    };
    let include = Include::WebGlPixelLocalStorage;
    let compiled = CompiledLayout::new(layout, conversions).unwrap();
    let (text, interface) = glsl::include(&compiled, include, 0).unwrap();
    let host = glsl::webgl::host_module(&compiled, &interface);
    let texels = TEXELS_PER_ROW * ROWS;
    preambles(include)
        .into_iter()
        .enumerate()
        .map(|(index, preamble)| {
            let inputs = inputs(layout, 0, texels, &mut Values::new(seed + index as u64));
            let (store, reload) = user_shaders(&compiled, &text, &preamble);
            let name = format!("{} ({conversions:?}, preamble {index})", layout.name);
            let json = serde_json::json!({
                "name": name,
                "width": TEXELS_PER_ROW * columns(layout),
                "height": ROWS,
                "columns": columns(layout),
                "scalars": scalars_per_texel(layout),
                "outputs": scalars_per_texel(layout) + 1,
                "inputs": inputs,
                "store": store,
                "reload": reload,
            });
            Case {
                name,
                layout: layout.clone(),
                backends,
                interface: interface.clone(),
                inputs,
                host: host.clone(),
                json: json.to_string(),
            }
        })
        .collect()
}

/// Runs `cases` (those meant for `backend`) in one page on `backend` and compares what each
/// read back with the mirror.
fn run(chromium: &Chromium, backend: Backend, cases: &[Case]) -> Vec<String> {
    let cases: Vec<&Case> = cases
        .iter()
        .filter(|case| case.backends.contains(&backend))
        .collect();
    let mut files: HashMap<String, Vec<u8>> = HashMap::new();
    files.insert(
        "pls_round_trip.mjs".into(),
        include_bytes!("../webgl/pls_round_trip.mjs").to_vec(),
    );
    let mut imports = String::new();
    let mut entries = Vec::new();
    for (index, case) in cases.iter().enumerate() {
        files.insert(
            format!("case{index}.webgl_pls.js"),
            case.host.clone().into_bytes(),
        );
        imports.push_str(&format!(
            "import * as host{index} from \"./case{index}.webgl_pls.js\";\n"
        ));
        entries.push(format!("[host{index}, {}]", case.json));
    }
    let page = format!(
        "<!doctype html>\n<html><body><pre id=\"results\"></pre>\n<script type=\"module\">\n\
         import {{ run }} from \"./pls_round_trip.mjs\";\n{imports}run([{}]);\n</script></body></html>\n",
        entries.join(",\n")
    );
    files.insert("index.html".into(), page.into_bytes());
    let limit = Duration::from_secs(300);
    let dom = match chromium.dump_dom(files, "index.html", backend, limit) {
        Ok(dom) => dom,
        Err(error) => return vec![format!("{}: {error}", backend.name())],
    };
    let Some(text) = element_text(&dom, "results").filter(|text| !text.is_empty()) else {
        return vec![format!(
            "{}: the page wrote no results (its script failed to load or threw)",
            backend.name()
        )];
    };
    let report: serde_json::Value = serde_json::from_str(&text).unwrap();
    let renderer = report["renderer"].as_str().unwrap_or("?").to_string();
    eprintln!("{}: {renderer}", backend.name());
    let mut failures = Vec::new();
    for (case, result) in cases.iter().zip(report["results"].as_array().unwrap()) {
        let what = format!("{} on {renderer}", case.name);
        if let Some(error) = result["error"].as_str() {
            failures.push(format!("{what}: {error}"));
            continue;
        }
        let numbers = |key: &str| -> Vec<u32> {
            result[key]
                .as_array()
                .unwrap()
                .iter()
                .map(|value| value.as_u64().unwrap() as u32)
                .collect()
        };
        let (words, decoded) = (numbers("words"), numbers("decoded"));
        let layout = &case.layout;
        let scalars = scalars_per_texel(layout);
        let texels = case.inputs.len() / scalars;
        assert_eq!(words.len(), texels * layout.words(), "{what}");
        assert_eq!(decoded.len(), texels * (scalars + 1), "{what}");
        // The decoded scalars, and per texel the count of per-field loads that differ from
        // the whole texel's.
        let (fields, disagreements): (Vec<&[u32]>, Vec<u32>) = decoded
            .chunks_exact(scalars + 1)
            .map(|texel| (&texel[..scalars], texel[scalars]))
            .unzip();
        let fields: Vec<u32> = fields.concat();
        if let Some(texel) = disagreements.iter().position(|&count| count != 0) {
            failures.push(format!(
                "{what}: texel {texel}: {} per-field loads differ from {}()",
                disagreements[texel],
                layout.symbols().load()
            ));
        }
        let native = case
            .interface
            .planes
            .iter()
            .any(|plane| plane.format == PlaneFormat::Rgba8);
        // At most four lines a case, so that one broken case does not hide the others.
        let mut found = Vec::new();
        if native {
            check_native_words(&what, layout, &case.inputs, &words, &mut found);
            compare_decoded(&what, layout, &words, &fields, &mut found, 4);
        } else {
            let (words, fields) = (Some(words.as_slice()), Some(fields.as_slice()));
            compare(&what, layout, &case.inputs, words, fields, &mut found, 4);
        }
        failures.extend(found.into_iter().take(4));
    }
    failures
}

/// The layouts the browser runs: the seed and engine layouts, every format and encoding, a fast
/// and a mixed layout, and twelve random ones, each of up to seven words.
fn layouts() -> Vec<(Layout, Conversions)> {
    let mut layouts: Vec<(Layout, Conversions)> =
        gbuffer_testkit::layouts::seeds_and_every_format()
            .into_iter()
            .map(|layout| (layout, Conversions::Exact))
            .collect();
    layouts.push((gbuffer_testkit::FastFormats::layout(), Conversions::Fast));
    layouts.push((
        gbuffer_testkit::MixedConversions::layout(),
        Conversions::Exact,
    ));
    let mut runner = TestRunner::deterministic();
    let strategy = gbuffer_testkit::layouts::random_layout();
    let mut random = 0;
    while random < 12 {
        let layout = strategy.new_tree(&mut runner).unwrap().current();
        if layout.words() <= MOST_WORDS {
            layouts.push((layout, Conversions::Exact));
            random += 1;
        }
    }
    layouts.retain(|(layout, _)| layout.words() <= MOST_WORDS);
    layouts
}

#[test]
fn webgl_pixel_local_storage_round_trips_in_chromium_on_swiftshader_and_lavapipe() {
    let Some(chromium) = or_skip("headless Chromium", Chromium::find()) else {
        return;
    };
    let cases: Vec<Case> = layouts()
        .iter()
        .enumerate()
        .flat_map(|(index, (layout, conversions))| cases(layout, *conversions, index as u64))
        .collect();
    let mut failures = Vec::new();
    for &backend in Backend::ALL {
        let found = run(&chromium, backend, &cases);
        let unoffered = "WEBGL_shader_pixel_local_storage is not offered";
        if !found.is_empty() && found.iter().all(|failure| failure.contains(unoffered)) {
            skip_without_driver("WebGL pixel local storage", &found[0]);
            return;
        }
        failures.extend(found);
    }
    assert!(
        failures.is_empty(),
        "{} problems:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
