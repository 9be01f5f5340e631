//! Bevy's deferred renderer with its own G-buffer and with layouts in its place, on the
//! adapter at hand (lavapipe in CI), headless: (a) Bevy's G-buffer; (b) `BevyDeferred`, the
//! library's declaration of Bevy's WebGL2 G-buffer, through the plugin; (c) a layout that
//! spends the bits differently (16 + 16-bit octahedral normals, 8-bit metallic, reflectance
//! and clearcoat). The frames are written to `target/gbuffer-bevy/` and compared.

mod scene;

use bevy::app::App;
use scene::{features, spheres};

use gbuffer::engine_layouts::BevyDeferred;
// Bevy's glam is the library's: these are `gbuffer::glam`'s types too.
use bevy::math::{Vec3, Vec4};
use gbuffer::GBufferLayout;
use gbuffer_bevy::{functions, solve, GBufferPlugin, MappingError, Quantity};

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

/// A shader that loads Bevy's G-buffer and reads its words as Bevy's own bits (its emissive,
/// Bevy's second word in RGB9E5), not through the decode the plugin replaces.
const RAW_READER: &str = "
import bevy_pbr::render::{mesh_view_bindings::deferred_prepass_texture, rgb9e5};

@fragment
fn fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let words = textureLoad(deferred_prepass_texture, vec2<i32>(position.xy), 0);
    return vec4(rgb9e5::rgb9e5_to_vec3_(words.g), 1.0);
}
";

#[test]
#[should_panic(
    expected = "GBufferPlugin: raw_reader.wesl, line 7, reads Bevy's G-buffer as Bevy's own bits"
)]
fn a_shader_that_reads_bevys_words_stops_the_app() {
    use bevy::asset::{AssetApp, AssetPlugin, Assets};
    use bevy::shader::Shader;
    let mut app = App::new();
    app.add_plugins((bevy::MinimalPlugins, AssetPlugin::default()))
        .init_asset::<Shader>()
        .add_plugins(GBufferPlugin::<FineNormals>::new());
    // Held, as a pipeline holds its shader: an asset whose last handle drops is removed.
    let _reader = app
        .world_mut()
        .resource_mut::<Assets<Shader>>()
        .add(Shader::from_wesl(RAW_READER, "raw_reader.wesl"));
    for _ in 0..3 {
        app.update();
    }
}

/// Anisotropy's strength without its direction.
#[allow(dead_code)]
#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
struct HalfAnisotropy {
    #[bits(24, octahedral)]
    normal: Vec3,
    #[bits(8, unorm)]
    anisotropy_strength: f32,
}

/// A direction in unorm, light in unorm, and reflectance twice.
#[allow(dead_code)]
#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
struct Misencoded {
    #[bits(24, octahedral)]
    normal: Vec3,
    #[bits(24, unorm)]
    clearcoat_normal: Vec3,
    #[bits(24, unorm)]
    emissive: Vec3,
    #[bits(8, unorm)]
    reflectance: f32,
    #[bits(24, unorm)]
    reflectance_color: Vec3,
}

#[test]
fn quantities_that_do_not_fit_are_named() {
    let error = GBufferPlugin::<HalfAnisotropy>::new()
        .mapping()
        .unwrap_err();
    assert_eq!(
        error.to_string(),
        "layout `HalfAnisotropy`, field `anisotropy_strength`: `anisotropy_strength` is read \
         with `anisotropy_tangent`, which no field holds"
    );
    let error = GBufferPlugin::<Misencoded>::new().mapping().unwrap_err();
    assert_eq!(
        error.to_string(),
        "layout `Misencoded`, field `clearcoat_normal`: `unorm` cannot hold `clearcoat_normal`; \
         use octahedral or snorm"
    );
    let told =
        GBufferPlugin::<Misencoded>::new().with_field("clearcoat_normal", Quantity::BaseColor);
    let error = told.mapping().unwrap_err();
    assert!(
        error
            .to_string()
            .contains("field `emissive`: `unorm` cannot hold `emissive`"),
        "{error}"
    );
    let told = told.with_field("emissive", Quantity::DiffuseOcclusionColor);
    assert_eq!(
        told.mapping().unwrap_err(),
        MappingError::Repeated {
            layout: "Misencoded".into(),
            field: "reflectance_color".into(),
            quantity: Quantity::ReflectanceColor,
        }
    );
}

#[test]
fn the_features_module_reads_what_bevys_g_buffer_drops() {
    let plugin = GBufferPlugin::<features::BevyFeatures>::new();
    let module = plugin.deferred_functions().unwrap();
    for line in [
        "pbr.material.reflectance = vec3(texel.reflectance_color);",
        "pbr.diffuse_occlusion = vec3(texel.diffuse_occlusion_color);",
        "pbr.clearcoat_N = normalize(texel.clearcoat_normal);",
        "pbr.anisotropy_B = normalize(cross(N, pbr.anisotropy_T));",
        "if (texel.lightmapped != 0u && (ambient_flags & affects) == 0u) {",
    ] {
        assert!(module.contains(line), "{line}");
    }
    assert_eq!(
        plugin.shader_defs().unwrap(),
        [
            "STANDARD_MATERIAL_ANISOTROPY",
            "PBR_ANISOTROPY_TEXTURE_SUPPORTED",
            "STANDARD_MATERIAL_DIFFUSE_TRANSMISSION",
            "STANDARD_MATERIAL_DIFFUSE_OR_SPECULAR_TRANSMISSION",
        ]
    );
    // Bevy's own quantities only: no def, no anisotropy helper.
    let fine = GBufferPlugin::<FineNormals>::new();
    assert!(fine.shader_defs().unwrap().is_empty());
    assert!(!fine
        .deferred_functions()
        .unwrap()
        .contains("orthonormal_tangent"));
}

#[test]
fn the_module_packs_with_the_layouts_own_functions() {
    let module = GBufferPlugin::<BevyDeferred>::new()
        .deferred_functions()
        .unwrap();
    // Bevy derives the module path its shaders import from the asset the module replaces, Bevy's
    // own `functions.wesl`.
    let bevy_module = functions::asset_path(functions::MODULE_PATH);
    assert_eq!(bevy_module, "embedded://bevy_pbr/deferred/functions.wesl");
    let shader = bevy::shader::Shader::from_wesl(module.clone(), bevy_module);
    assert_eq!(
        shader.import_path,
        bevy::shader::ShaderImport::Custom(functions::MODULE_PATH.to_string())
    );
    // ...and from its text what it imports: the layout's module among Bevy's own.
    assert!(shader.imports.contains(&bevy::shader::ShaderImport::Custom(
        "gbuffer::bevy_deferred".to_string()
    )));
    assert!(module.contains(
        "import gbuffer::bevy_deferred::{BevyDeferred, pack_bevy_deferred, unpack_bevy_deferred};"
    ));
    // Bevy derives the layout module's path from the asset the plugin adds it at.
    let layout_module = BevyDeferred::wesl_module();
    let shader = bevy::shader::Shader::from_wesl(
        layout_module.source,
        functions::asset_path(&layout_module.path),
    );
    assert_eq!(
        shader.import_path,
        bevy::shader::ShaderImport::Custom("gbuffer::bevy_deferred".to_string())
    );
    assert!(module.contains("let words = pack_bevy_deferred(texel);"));
    assert!(module.contains("texel.depth = in.frag_coord.z;"));
    assert!(module.contains("unpack_bevy_deferred(array<u32, 4>("));
    // FineNormals stores no occlusion: Bevy's default stays.
    let fine = GBufferPlugin::<FineNormals>::new()
        .deferred_functions()
        .unwrap();
    assert!(fine.contains("pbr.diffuse_occlusion = vec3(pbr.diffuse_occlusion.r);"));
}

/// How two frames differ over the pixels of a region, in their colour channels.
struct Difference {
    /// PSNR in dB.
    psnr: f64,
    /// The largest difference of a channel, in 8-bit levels.
    largest: u8,
    /// How many pixels differ at all.
    differing: usize,
}

/// How `b` differs from `a` over the pixels where `region` is true.
fn compare(a: &scene::Pixels, b: &scene::Pixels, region: &[bool]) -> Difference {
    let (mut squares, mut channels, mut largest, mut differing) = (0.0, 0usize, 0u8, 0usize);
    for ((pa, pb), _) in a.iter().zip(b).zip(region).filter(|(_, inside)| **inside) {
        let pixel_largest = (0..3)
            .map(|channel| pa[channel].abs_diff(pb[channel]))
            .inspect(|difference| squares += f64::from(*difference).powi(2))
            .max()
            .unwrap_or(0);
        largest = largest.max(pixel_largest);
        differing += usize::from(pixel_largest > 0);
        channels += 3;
    }
    let mean = squares / channels as f64;
    Difference {
        psnr: 10.0 * (255.0 * 255.0 / mean).log10(),
        largest,
        differing,
    }
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

/// Where the tests write their frames and tables.
fn output(name: &str) -> std::path::PathBuf {
    let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target/gbuffer-bevy");
    std::fs::create_dir_all(&folder).unwrap();
    folder.join(name)
}

fn write_file(name: &str, text: &str) {
    std::fs::write(output(name), text).unwrap();
}

fn write_png(name: &str, pixels: &scene::Pixels) {
    let file = std::fs::File::create(output(name)).unwrap();
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
    let render = |plugin| scene::render(true, spheres::scene(), plugin, spheres::regions).pixels;
    let bevy = render(None);
    let through_bevy_deferred = render(Some(Box::new(|app: &mut App| {
        app.add_plugins(GBufferPlugin::<BevyDeferred>::new());
    })));
    let through_fine_normals = render(Some(Box::new(|app: &mut App| {
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
    let whole = vec![true; bevy.len()];
    let Difference {
        psnr: psnr_b,
        differing: differing_b,
        ..
    } = compare(&bevy, &through_bevy_deferred, &whole);
    let Difference {
        psnr: psnr_c,
        differing: differing_c,
        ..
    } = compare(&bevy, &through_fine_normals, &whole);
    // The README's table, which .ci/check-figures holds to this file.
    let pixels = |count: usize| {
        let digits = count.to_string();
        let mut grouped = String::new();
        for (index, digit) in digits.chars().enumerate() {
            if index > 0 && (digits.len() - index).is_multiple_of(3) {
                grouped.push(',');
            }
            grouped.push(digit);
        }
        grouped
    };
    let total = pixels(bevy.len());
    let table = format!(
        "| frame | PSNR against (a) | pixels that differ |\n| --- | ---: | ---: |\n\
         | (b) `BevyDeferred`, Bevy's WebGL2 G-buffer | {psnr_b:.2} dB | {} pixels of {total} |\n\
         | (c) `FineNormals` | {psnr_c:.2} dB | {} pixels of {total} |\n",
        pixels(differing_b),
        pixels(differing_c),
    );
    eprintln!("{table}");
    write_file("spheres.md", &table);
    // What holds on every machine, whatever the last digit: the layouts took Bevy's place
    // (their words differ from Bevy's), the frames stay close to Bevy's own, and the finer
    // normals of (c) keep it closer to (a) than the WebGL2 form (b) is.
    assert!(differing_b > 0 && differing_c > 0);
    assert!(psnr_b > 35.0 && psnr_c > 35.0);
    assert!(
        psnr_c > psnr_b && differing_c < differing_b,
        "(c) {psnr_c:.2} dB, {differing_c} pixels is no closer to (a) than (b) {psnr_b:.2} dB, {differing_b} pixels"
    );
}

/// The README's app is the specular tint example, character for character: what CI runs from
/// the README is what `cargo run --example specular_tint` runs.
#[test]
fn the_readmes_app_is_the_specular_tint_example() {
    let read = |path: &str| {
        std::fs::read_to_string(format!("{}/{path}", env!("CARGO_MANIFEST_DIR"))).unwrap()
    };
    let readme = read("README.md");
    let app = readme
        .split_once("```rust,no_run\n")
        .and_then(|(_, rest)| rest.split_once("```\n"))
        .expect("the README shows its app in a ```rust,no_run block")
        .0;
    assert_eq!(app, read("examples/specular_tint.rs"));
}

#[test]
fn the_features_layout_is_the_solvers_answer() {
    let solution = solve(&features::bevy_scene()).unwrap();
    let layout = features::BevyFeatures::layout();
    let solved: Vec<(String, String)> = solution
        .fields
        .iter()
        .map(|field| {
            (
                field.quantity.to_string(),
                format!("{}-bit {}", field.bits, field.encoding),
            )
        })
        .collect();
    let declared: Vec<(String, String)> = layout
        .fields
        .iter()
        .map(|field| (field.name.clone(), field.storage_name()))
        .collect();
    assert_eq!(solved, declared);
    write_file("features-budget.md", &solution.budget_table());
    assert_eq!((solution.bits(), solution.words), (128, 4));
}

#[test]
fn the_features_bevys_g_buffer_drops_render_through_a_layout() {
    if !adapter() {
        return;
    }
    let render =
        |deferred, plugin| scene::render(deferred, features::scene(), plugin, features::regions);
    let forward = render(false, None);
    let bevy = render(true, None).pixels;
    let layout = render(
        true,
        Some(Box::new(|app: &mut App| {
            app.add_plugins(GBufferPlugin::<features::BevyFeatures>::new());
        })),
    )
    .pixels;
    write_png("features-forward.png", &forward.pixels);
    write_png("features-bevy.png", &bevy);
    write_png("features-layout.png", &layout);
    write_png(
        "features-bevy-difference.png",
        &difference(&forward.pixels, &bevy),
    );
    write_png(
        "features-layout-difference.png",
        &difference(&forward.pixels, &layout),
    );

    let whole = vec![true; forward.pixels.len()];
    let mut table = String::from(
        "| region | (b) Bevy's G-buffer: PSNR, largest error | (c) `BevyFeatures`: PSNR, largest error |\n\
         | --- | ---: | ---: |\n",
    );
    let mut failures = Vec::new();
    for (name, region) in std::iter::once(("whole frame", &whole))
        .chain(forward.regions.iter().map(|(name, region)| (*name, region)))
    {
        let b = compare(&forward.pixels, &bevy, region);
        let c = compare(&forward.pixels, &layout, region);
        table.push_str(&format!(
            "| {name} | {:.2} dB, {} levels | {:.2} dB, {} levels |\n",
            b.psnr, b.largest, c.psnr, c.largest
        ));
        if c.psnr <= b.psnr || c.largest >= b.largest {
            failures.push(format!(
                "{name}: (c) {:.2} dB, largest error {}, is no closer than (b) {:.2} dB, {}",
                c.psnr, c.largest, b.psnr, b.largest
            ));
        }
        // (c) is (a) within what its fields store: the largest errors are on the clearcoat's
        // bumps and the anisotropic highlight, whose directions are held to 4 degrees.
        let (least_psnr, most_largest) = if name == "whole frame" {
            (45.0, u8::MAX)
        } else {
            (36.0, 64)
        };
        if c.psnr < least_psnr || c.largest > most_largest {
            failures.push(format!(
                "(c) on {name}: {:.2} dB, largest error {}",
                c.psnr, c.largest
            ));
        }
    }
    eprintln!("{table}");
    write_file("features.md", &table);
    assert!(failures.is_empty(), "{failures:#?}");
}

/// One glam in a Bevy app: a system hands Bevy's own `Vec3`s (a `Transform`'s translation, a
/// `Dir3`) to the CPU mirror of the example's layout, with no conversion, and the texel comes
/// back as the layout's encodings round it: the octahedral normal within its 18 bits' half
/// degree, the unorm base colour within half of its 6-bit step. The system runs once on the
/// app's world, not through a schedule: a schedule's executor would set up Bevy's global task
/// pools before the rendering tests beside it set them up their own way (their shaders then
/// failed to load).
#[test]
fn a_bevy_system_packs_bevy_vec3s_with_the_cpu_mirror() {
    use bevy::ecs::system::RunSystemOnce;
    use bevy::prelude::{Query, Transform};
    use features::BevyFeatures;

    // Each entity's texel, and the texel its words unpack to.
    fn pack_and_unpack(transforms: Query<&Transform>) -> Vec<(BevyFeatures, BevyFeatures)> {
        let round_trip = |transform: &Transform| {
            let normal: bevy::math::Dir3 = transform.forward();
            let texel = BevyFeatures {
                base_color: transform.translation,
                normal: *normal,
                clearcoat_normal: transform.up().into(),
                ..BevyFeatures::unpack(&[0; 4])
            };
            (texel, BevyFeatures::unpack(&texel.pack()))
        };
        transforms.iter().map(round_trip).collect()
    }

    let mut app = App::new();
    app.world_mut().spawn(
        Transform::from_translation(Vec3::new(0.25, 0.5, 0.75))
            .looking_at(Vec3::new(1.0, -2.0, 3.0), Vec3::Y),
    );
    let texels = app
        .world_mut()
        .run_system_once(pack_and_unpack)
        .expect("the system runs");

    assert_eq!(texels.len(), 1, "the system ran once, over the one entity");
    let (texel, back) = texels[0];
    let step = 1.0 / 63.0;
    assert!(
        (back.base_color - texel.base_color).abs().max_element() <= step / 2.0 + 1e-6,
        "{} came back as {}",
        texel.base_color,
        back.base_color
    );
    let degrees = |a: Vec3, b: Vec3| a.angle_between(b).to_degrees();
    assert!(
        degrees(back.normal, texel.normal) < 0.5,
        "{} -> {}",
        texel.normal,
        back.normal
    );
    assert!(degrees(back.clearcoat_normal, texel.clearcoat_normal) < 4.0);
}
