//! The fused frame in a browser: headless Chromium draws the reference scene in one WebGL 2
//! pixel local storage pass (`web/fused.mjs`, with the scene and programs `webgl::export`
//! writes and the layout's generated host module), on SwiftShader and on lavapipe; the frame is
//! held to the CPU reference at 320x180.

use std::collections::HashMap;
use std::time::Duration;

use gbuffer_core::Named;
use gbuffer_render::gbuffers::{GBuffer, PackedLayout};
use gbuffer_render::image::{compare, write_png};
use gbuffer_render::inputs::Inputs;
use gbuffer_render::options::{Frame, IblForm, Options, SunForm};
use gbuffer_render::recording::{Attachment, Call, Load, Recording};
use gbuffer_render::reference;
use gbuffer_render::scene::reference_features;
use gbuffer_render::webgl;
use gbuffer_testkit::chromium::{element_text, Backend, Chromium};
use gbuffer_testkit::or_skip;

const WIDTH: u32 = 320;
const HEIGHT: u32 = 180;

/// The page: renders the frame and writes its calls (JSON) and pixels (hex), a line each, into
/// `<pre id="results">`.
const PAGE: &str = r#"<!doctype html>
<html><body><pre id="results"></pre>
<script type="module">
import * as host from "./layout.webgl_pls.js";
import * as scene from "./scene.mjs";
import { renderFrame } from "./fused.mjs";
let text;
try {
  const gl = document.createElement("canvas").getContext("webgl2");
  const { pixels, calls } = renderFrame(gl, host, scene);
  const hex = Array.from(pixels, (value) => value.toString(16).padStart(2, "0")).join("");
  text = "ok " + JSON.stringify(calls) + "\n" + hex;
} catch (error) {
  text = "error " + (error && error.message ? error.message : String(error));
}
document.getElementById("results").textContent = text;
</script></body></html>
"#;

/// The page's calls as a [`Recording`].
fn recording(calls: &serde_json::Value) -> Recording {
    let names = |list: &serde_json::Value| -> Vec<String> {
        let items = list.as_array().unwrap();
        items
            .iter()
            .map(|name| name.as_str().unwrap().to_string())
            .collect()
    };
    let mut recording = Recording::default();
    for call in calls.as_array().unwrap() {
        recording.push(if let Some(list) = call.get("beginPass") {
            let attachments = list
                .as_array()
                .unwrap()
                .iter()
                .map(|entry| {
                    let attachment = Attachment {
                        name: entry[0].as_str().unwrap().to_string(),
                        bytes_per_pixel: entry[1].as_u64().unwrap() as u32,
                    };
                    let load = match entry[2].as_str().unwrap() {
                        "clear" => Load::Clear,
                        _ => Load::Load,
                    };
                    (attachment, load)
                })
                .collect();
            Call::BeginPass { attachments }
        } else if let Some(stage) = call.get("draw") {
            Call::Draw {
                program: stage.as_str().unwrap().to_string(),
            }
        } else if let Some(list) = call.get("invalidate") {
            Call::Invalidate(names(list))
        } else if let Some(list) = call.get("endPass") {
            Call::EndPass {
                stored: names(list),
            }
        } else {
            Call::ReadBack(call["readBack"].as_str().unwrap().to_string())
        });
    }
    recording
}

fn from_hex(hex: &str) -> Vec<u8> {
    hex.as_bytes()
        .chunks_exact(2)
        .map(|pair| u8::from_str_radix(std::str::from_utf8(pair).unwrap(), 16).unwrap())
        .collect()
}

#[test]
fn the_fused_frame_renders_in_chromium_within_40_db_of_the_reference() {
    let Some(chromium) = or_skip("headless Chromium", Chromium::find()) else {
        return;
    };
    let options = Options {
        gbuffer: GBuffer::Packed(PackedLayout::MobileMetallic),
        sun: SunForm::Ggx,
        ibl: IblForm::Lut,
        width: WIDTH,
        height: HEIGHT,
    };
    let mut files: HashMap<String, Vec<u8>> = webgl::export(&options, &Inputs::bake())
        .unwrap()
        .into_iter()
        .collect();
    files.insert(
        "fused.mjs".into(),
        include_bytes!("../../web/fused.mjs").to_vec(),
    );
    files.insert("index.html".into(), PAGE.as_bytes().to_vec());
    let reference = reference::render(WIDTH, HEIGHT, reference_features(), &|_| {});
    let mut failures = Vec::new();
    let mut figures = Vec::new();
    for &backend in Backend::ALL {
        let limit = Duration::from_secs(300);
        let result = chromium
            .dump_dom(files.clone(), "index.html", backend, limit)
            .and_then(|dom| element_text(&dom, "results").ok_or("no results".to_string()));
        let text = match result {
            Ok(text) => text,
            Err(error) => {
                failures.push(format!("{}: {error}", backend.name()));
                continue;
            }
        };
        let Some((calls, hex)) = text.strip_prefix("ok ").and_then(|ok| ok.split_once('\n')) else {
            failures.push(format!("{}: {text}", backend.name()));
            continue;
        };
        let recording = recording(&serde_json::from_str(calls).unwrap());
        // The planes are cleared on tile and never stored, depth is invalidated: the frame
        // moves its output alone, 1 BU, as the GLES and Vulkan fused paths do.
        let units = recording
            .traffic(WIDTH, HEIGHT)
            .bandwidth_units(WIDTH, HEIGHT);
        eprintln!(
            "{}: {units} BU, {} passes",
            backend.name(),
            recording.passes()
        );
        if units != 1.0 || recording.passes() != 1 {
            failures.push(format!(
                "{}: {units} BU in {} passes, where 1 BU in one pass was expected: {recording:?}",
                backend.name(),
                recording.passes()
            ));
        }
        let bytes = from_hex(hex);
        let frame = Frame {
            width: WIDTH,
            height: HEIGHT,
            pixels: bytes
                .chunks_exact(4)
                .map(|pixel| pixel.try_into().unwrap())
                .collect(),
        };
        let out = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
            .join(format!("webgl-{}.png", backend.name()));
        write_png(&out, &frame).unwrap();
        let comparison = compare(&frame, &reference);
        eprintln!(
            "{}: {:.2} dB against the CPU reference ({})",
            backend.name(),
            comparison.psnr,
            out.display()
        );
        figures.push(vec![
            backend.name().to_string(),
            format!("{:.1} dB", comparison.psnr),
            format!("{units} BU"),
        ]);
        if comparison.psnr < 40.0 {
            failures.push(format!(
                "{}: {:.2} dB against the CPU reference, 40 needed ({})",
                backend.name(),
                comparison.psnr,
                out.display()
            ));
        }
    }
    let header = [
        "Chromium's GPU",
        "PSNR against the CPU reference",
        "traffic",
    ];
    gbuffer_testkit::write_figures("webgl-frame", &header, &figures);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
