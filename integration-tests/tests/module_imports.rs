//! A layout's WGSL as a module other shaders import, in both module systems engines use: a
//! naga_oil composable module (Bevy up to 0.19) and a WESL module (Bevy 0.20 and the `wesl`
//! crate), each under `gbuffer::<snake>`. A user shader imports what it calls, and the
//! composed shader validates in naga and round-trips texels on the adapter as the Rust mirror
//! does.

use gbuffer::engine_layouts::HdrpLit;
use gbuffer::seed_layouts::{MobileMetallic, SpecularWorkflow};
use gbuffer::GBufferLayout;
use naga_oil::compose::{ComposableModuleDescriptor, Composer, NagaModuleDescriptor};
use rand::{Rng, SeedableRng};

/// The user shader's imports, in naga_oil's syntax.
const NAGA_OIL_IMPORTS: &str = "
#import gbuffer::mobile_metallic::{MobileMetallic, pack_mobile_metallic, unpack_mobile_metallic}
#import gbuffer::specular_workflow::SpecularWorkflow
";

/// The same imports in WESL's, and one more module (an engine layout's).
const WESL_IMPORTS: &str = "
import gbuffer::mobile_metallic::{MobileMetallic, pack_mobile_metallic, unpack_mobile_metallic};
import gbuffer::specular_workflow::SpecularWorkflow;
import gbuffer::hdrp_lit::unpack_hdrp_lit;
";

/// A compute shader that unpacks words with the imported layout and packs them again (after
/// the imports).
const USER_SHADER: &str = "
@group(0) @binding(0) var<storage, read> inputs: array<u32>;
@group(0) @binding(1) var<storage, read_write> outputs: array<u32>;
@group(0) @binding(2) var<uniform> count: vec4<u32>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= count.x {
        return;
    }
    let base = id.x * 4u;
    let texel: MobileMetallic = unpack_mobile_metallic(
        array<u32, 4>(inputs[base], inputs[base + 1u], inputs[base + 2u], inputs[base + 3u]));
    let words = pack_mobile_metallic(texel);
    for (var word = 0u; word < 4u; word++) {
        outputs[base + word] = words[word];
    }
}
";

/// The user shader composed with the layouts' naga_oil modules, as WGSL again.
fn composed_shader() -> String {
    let mut composer = Composer::default();
    for (file_path, module) in [
        ("mobile_metallic.wgsl", MobileMetallic::composable_wgsl()),
        (
            "specular_workflow.wgsl",
            SpecularWorkflow::composable_wgsl(),
        ),
    ] {
        let added = composer.add_composable_module(ComposableModuleDescriptor {
            source: &module,
            file_path,
            ..Default::default()
        });
        if let Err(error) = added {
            panic!("{file_path}: {}", error.emit_to_string(&composer));
        }
    }
    let module = composer
        .make_naga_module(NagaModuleDescriptor {
            source: &format!("{NAGA_OIL_IMPORTS}{USER_SHADER}"),
            file_path: "user.wgsl",
            ..Default::default()
        })
        .unwrap_or_else(|error| panic!("{}", error.emit_to_string(&composer)));
    let info = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
    .validate(&module)
    .expect("the composed module is valid");
    naga::back::wgsl::write_string(&module, &info, naga::back::wgsl::WriterFlags::empty())
        .expect("naga writes the composed module")
}

/// The user shader compiled by the `wesl` crate with the layouts' WESL modules registered at
/// their paths, checked by naga.
fn wesl_shader() -> String {
    let mut resolver = wesl::VirtualResolver::new();
    for module in [
        MobileMetallic::wesl_module(),
        SpecularWorkflow::wesl_module(),
        HdrpLit::wesl_module(),
    ] {
        let path = module.path.parse().expect("a WESL module path");
        resolver.add_module(path, module.source.into());
    }
    let main: wesl::ModulePath = "package::main".parse().expect("a WESL module path");
    resolver.add_module(main.clone(), format!("{WESL_IMPORTS}{USER_SHADER}").into());
    let compiled = wesl::compile(
        &main,
        &resolver,
        &wesl::EscapeMangler,
        &wesl::CompileOptions::default(),
    )
    .unwrap_or_else(|error| panic!("wesl: {error}"))
    .to_string();
    let module = naga::front::wgsl::parse_str(&compiled)
        .unwrap_or_else(|error| panic!("{}\n{compiled}", error.emit_to_string(&compiled)));
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
    .validate(&module)
    .unwrap_or_else(|error| panic!("{error:?}\n{compiled}"));
    compiled
}

/// Runs `shader` over random words; each texel must come back as the Rust mirror's
/// unpack-then-pack gives it.
fn round_trips_on_the_adapter(shader: &str) {
    let mut random = rand::rngs::SmallRng::seed_from_u64(5);
    let texels = 4096;
    let inputs: Vec<u32> = (0..texels * 4).map(|_| random.random()).collect();
    let Some(gpu) = gbuffer_testkit::gpu() else {
        return;
    };
    let outputs = gpu
        .run_compute(shader, "main", &inputs, &[inputs.len()], texels as u32)
        .expect("the adapter runs the harness");
    for (index, (words, got)) in inputs
        .chunks_exact(4)
        .zip(outputs[0].chunks_exact(4))
        .enumerate()
    {
        let words: [u32; 4] = words.try_into().unwrap();
        let expected = MobileMetallic::unpack(&words).pack();
        assert_eq!(got, expected, "texel {index}: words {words:08x?}");
    }
}

#[test]
fn layouts_import_as_naga_oil_modules_and_round_trip_on_the_adapter() {
    assert!(MobileMetallic::composable_wgsl()
        .starts_with("#define_import_path gbuffer::mobile_metallic\n"));
    round_trips_on_the_adapter(&composed_shader());
}

#[test]
fn layouts_import_as_wesl_modules_and_round_trip_on_the_adapter() {
    let module = MobileMetallic::wesl_module();
    assert_eq!(module.path, "gbuffer::mobile_metallic");
    assert!(module.source.ends_with(MobileMetallic::WGSL));
    round_trips_on_the_adapter(&wesl_shader());
}
