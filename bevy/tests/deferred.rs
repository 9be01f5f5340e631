//! Bevy's deferred renderer with its own G-buffer and with layouts in its place, on the
//! adapter at hand (lavapipe in CI), headless: (a) Bevy's G-buffer; (b) `BevyDeferred`, the
//! library's declaration of Bevy's WebGL2 G-buffer, through the plugin; (c) a layout that
//! spends the bits differently (16 + 16-bit octahedral normals, 8-bit metallic, reflectance
//! and clearcoat). The frames are written to `target/gbuffer-bevy/` and compared.

mod scene;

use gbuffer::engine_layouts::BevyDeferred;
use gbuffer::glam::{Vec3, Vec4};
use gbuffer::GBufferLayout;
use gbuffer_bevy::{GBufferPlugin, MappingError, Quantity};

/// Bevy's quantities with the normal in 2 x 16 bits and 8-bit metallic, reflectance and
/// clearcoat; no occlusion, no clearcoat roughness (Bevy's defaults).
#[rustfmt::skip]
#[allow(dead_code)] // the fields are read on the GPU
#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
#[gbuffer(budget = 128)]
struct FineNormals {
    #[pls(rgba8)]           base_color_roughness: Vec4,
    #[bits(32, rgb9e5)]     emissive: Vec3,
    #[bits(32, octahedral)] normal: Vec3,
    #[bits(8, unorm)]       metallic: f32,
    #[bits(8, unorm)]       reflectance: f32,
    #[bits(8, unorm)]       clearcoat: f32,
    #[bits(8, uint)]        flags: u32,
}

/// A field none of Bevy's quantities names.
#[allow(dead_code)]
#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
struct Unmapped {
    #[bits(24, octahedral)]
    normal: Vec3,
    #[bits(8, unorm)]
    sheen: f32,
}

/// Two words more than Bevy's texel.
#[allow(dead_code)]
#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
#[gbuffer(budget = 192)]
struct TooWide {
    #[pls(r32f)]
    depth: f32,
    #[pls(rgba8)]
    base_color_roughness: Vec4,
    #[bits(32, octahedral)]
    normal: Vec3,
    #[pls(r32f)]
    metallic: f32,
    #[pls(r32f)]
    reflectance: f32,
    #[pls(r32f)]
    clearcoat: f32,
}

#[test]
fn a_layout_the_plugin_cannot_map_is_named() {
    let error = GBufferPlugin::<Unmapped>::new()
        .deferred_functions()
        .unwrap_err();
    assert_eq!(
        error,
        MappingError::UnknownField {
            layout: "Unmapped".into(),
            field: "sheen".into()
        }
    );
    assert!(error.to_string().contains("field `sheen`"), "{error}");
    // Told what it holds, the field maps.
    let told = GBufferPlugin::<Unmapped>::new().with_field("sheen", Quantity::Clearcoat);
    assert!(told.deferred_functions().is_ok());
    let told = GBufferPlugin::<Unmapped>::new().with_field("gloss", Quantity::Clearcoat);
    assert!(matches!(
        told.deferred_functions(),
        Err(MappingError::NoSuchField { .. })
    ));
    let wrong = GBufferPlugin::<Unmapped>::new().with_field("sheen", Quantity::Emissive);
    let error = wrong.deferred_functions().unwrap_err();
    assert!(
        error.to_string().contains("needs a `Vec3`, not a `f32`"),
        "{error}"
    );
    let error = GBufferPlugin::<TooWide>::new()
        .deferred_functions()
        .unwrap_err();
    assert!(error.to_string().contains("192 bits"), "{error}");
}

#[test]
fn the_module_packs_with_the_layouts_own_functions() {
    let module = GBufferPlugin::<BevyDeferred>::new()
        .deferred_functions()
        .unwrap();
    assert!(module.contains("#define_import_path bevy_pbr::pbr_deferred_functions"));
    assert!(module.contains(BevyDeferred::WGSL));
    assert!(module.contains("let words = pack_bevy_deferred(texel);"));
    assert!(module.contains("texel.depth = in.frag_coord.z;"));
    assert!(module.contains("unpack_bevy_deferred(array<u32, 4>("));
    // FineNormals stores no occlusion: Bevy's default stays.
    let fine = GBufferPlugin::<FineNormals>::new()
        .deferred_functions()
        .unwrap();
    assert!(fine.contains("pbr.diffuse_occlusion = vec3(pbr.diffuse_occlusion.r);"));
}

/// PSNR in dB of two frames over their colour channels, and how many pixels differ at all.
fn compare(a: &scene::Pixels, b: &scene::Pixels) -> (f64, usize) {
    let mut squares = 0.0;
    let mut differing = 0;
    for (pa, pb) in a.iter().zip(b) {
        let mut differs = false;
        for channel in 0..3 {
            let difference = f64::from(pa[channel].abs_diff(pb[channel]));
            squares += difference * difference;
            differs |= difference > 0.0;
        }
        differing += usize::from(differs);
    }
    let mean = squares / (3 * a.len()) as f64;
    (10.0 * (255.0 * 255.0 / mean).log10(), differing)
}

/// Where two frames differ, amplified 16 times.
fn difference(a: &scene::Pixels, b: &scene::Pixels) -> scene::Pixels {
    a.iter()
        .zip(b)
        .map(|(pa, pb)| {
            let channel = |index: usize| pa[index].abs_diff(pb[index]).saturating_mul(16);
            [channel(0), channel(1), channel(2), 255]
        })
        .collect()
}

fn write_png(name: &str, pixels: &scene::Pixels) {
    let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target/gbuffer-bevy");
    std::fs::create_dir_all(&folder).unwrap();
    let file = std::fs::File::create(folder.join(name)).unwrap();
    let mut encoder =
        png::Encoder::new(std::io::BufWriter::new(file), scene::SIZE.0, scene::SIZE.1);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().unwrap();
    let bytes: Vec<u8> = pixels.iter().flatten().copied().collect();
    writer.write_image_data(&bytes).unwrap();
}

/// Whether there is an adapter to render on. Without one the test skips with the reason,
/// except under `CI=true`, where it fails (as the main workspace's GPU tests do).
fn adapter() -> bool {
    let instance = wgpu::Instance::default();
    match bevy::tasks::block_on(instance.request_adapter(&Default::default())) {
        Ok(_) => true,
        Err(reason) if std::env::var("CI").is_ok_and(|ci| ci == "true") => {
            panic!("no adapter under CI=true: {reason}")
        }
        Err(reason) => {
            eprintln!("skipped: no adapter to render Bevy's frames on ({reason})");
            false
        }
    }
}

#[test]
fn layouts_render_in_bevys_deferred_renderer() {
    if !adapter() {
        return;
    }
    let bevy = scene::render(None);
    let through_bevy_deferred = scene::render(Some(Box::new(|app| {
        app.add_plugins(GBufferPlugin::<BevyDeferred>::new());
    })));
    let through_fine_normals = scene::render(Some(Box::new(|app| {
        app.add_plugins(GBufferPlugin::<FineNormals>::new());
    })));
    write_png("bevy.png", &bevy);
    write_png("bevy-deferred.png", &through_bevy_deferred);
    write_png("fine-normals.png", &through_fine_normals);
    write_png(
        "bevy-deferred-difference.png",
        &difference(&bevy, &through_bevy_deferred),
    );
    write_png(
        "fine-normals-difference.png",
        &difference(&bevy, &through_fine_normals),
    );
    let lit = bevy.iter().filter(|pixel| pixel[..3] != [0, 0, 0]).count();
    assert!(
        lit > bevy.len() / 2,
        "Bevy's own frame is mostly black: {lit} pixels lit"
    );
    let (psnr_b, differing_b) = compare(&bevy, &through_bevy_deferred);
    let (psnr_c, differing_c) = compare(&bevy, &through_fine_normals);
    eprintln!(
        "(b) BevyDeferred: PSNR {psnr_b:.2} dB against Bevy's own, {differing_b} pixels differ"
    );
    eprintln!(
        "(c) FineNormals: PSNR {psnr_c:.2} dB against Bevy's own, {differing_c} pixels differ"
    );
    // The layouts took Bevy's place (their words differ from Bevy's), and the frames stay
    // close to Bevy's own.
    assert!(differing_b > 0 && differing_c > 0);
    assert!(psnr_b > 35.0 && psnr_c > 35.0);
}
