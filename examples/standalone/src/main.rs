//! A user's crate: the guide's dependency lines in Cargo.toml, a derived layout, its targets
//! created on the adapter at hand with no format or count written here, and a clear error for a
//! layout the adapter's limits cannot hold. Run with
//! `cargo run --manifest-path examples/standalone/Cargo.toml`.

use std::process::ExitCode;

use gbuffer::glam::{Vec3, Vec4};
use gbuffer::{GBufferLayout, GBufferTargets};

#[derive(GBufferLayout, Clone, Copy)]
#[gbuffer(budget = 128)]
struct MobileMetallic {
    #[pls(rgb10_a2)]
    light_accumulation: Vec3,
    #[pls(r32f)]
    depth: f32,
    #[pls(rgba8)]
    normals_roughness: Vec4,
    #[pls(rgba8)]
    albedo_metallic: Vec4,
}

/// Nine words: 36 bytes per sample, over WebGPU's default of 32.
#[derive(GBufferLayout, Clone, Copy)]
#[gbuffer(budget = 288)]
struct Wide {
    #[pls(rgba8)]
    albedo: Vec4,
    #[pls(rgba8)]
    normal: Vec4,
    #[pls(r32f)]
    depth: f32,
    #[pls(r32f)]
    roughness: f32,
    #[pls(r32f)]
    metallic: f32,
    #[pls(r32f)]
    occlusion: f32,
    #[pls(r32f)]
    emissive: f32,
    #[pls(r32f)]
    thickness: f32,
    #[pls(r32f)]
    clear_coat: f32,
}

fn main() -> ExitCode {
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter = match pollster::block_on(instance.request_adapter(&Default::default())) {
        Ok(adapter) => adapter,
        Err(error) => {
            eprintln!("no adapter: {error}");
            return ExitCode::FAILURE;
        }
    };
    // WebGPU's defaults, as a portable renderer requests them.
    let limits = wgpu::Limits::default();
    if let Err(error) = MobileMetallic::check_limits(&limits) {
        eprintln!("{error}");
        return ExitCode::FAILURE;
    }
    let (device, _queue) =
        match pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            required_limits: limits.clone(),
            ..Default::default()
        })) {
            Ok(device) => device,
            Err(error) => {
                eprintln!("no device: {error}");
                return ExitCode::FAILURE;
            }
        };
    // gbuffer::wgpu is this crate's wgpu: the types are the same.
    let device: &gbuffer::wgpu::Device = &device;
    let targets = MobileMetallic::create_targets(device, 640, 360, wgpu::TextureUsages::empty());
    println!(
        "{}: {} target(s) {:?} on {}",
        MobileMetallic::layout().name,
        targets.textures.len(),
        MobileMetallic::TARGET_FORMATS,
        adapter.get_info().name
    );
    match Wide::check_limits(&limits) {
        Ok(()) => {
            eprintln!("a 288-bit layout should not fit WebGPU's default limits");
            ExitCode::FAILURE
        }
        Err(error) => {
            println!("as expected: {error}");
            ExitCode::SUCCESS
        }
    }
}
