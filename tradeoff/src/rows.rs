//! The rows of the trade-off report: each approximation or encoding, its error against the
//! f64 reference over a stated domain, the WGSL that costs and times it, and its CPU mirror.

use gbuffer::codecs::unorm;
use gbuffer::glam::{DVec3, Vec2, Vec3, Vec4};
use gbuffer::layout::{BitField, Encoding, Field, FieldType, Format, Layout, ScalarKind, Storage};
use gbuffer_render::conventions::seed::{
    round_trip, Shading, Surface, SurfaceConvention, LIGHT_SCALE, SURFACE_WGSL,
};
use gbuffer_shading::env_brdf_lut::EnvBrdfLut;
use gbuffer_shading::{mirror as m, reference as r};

use gbuffer_gpu::values::halton;

use crate::plot::Plot;

/// The largest and root-mean-square error over a domain.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Errors {
    pub max: f64,
    pub rms: f64,
}

#[derive(Default)]
struct Accumulator {
    max: f64,
    sum_of_squares: f64,
    count: usize,
}

impl Accumulator {
    fn add(&mut self, error: f64) {
        self.max = self.max.max(error);
        self.sum_of_squares += error * error;
        self.count += 1;
    }

    fn finish(&self) -> Errors {
        Errors {
            max: self.max,
            rms: (self.sum_of_squares / self.count.max(1) as f64).sqrt(),
        }
    }
}

/// A CPU evaluation of the row's f32 mirror, for timing: four floats in the unit cube in, four
/// out, the row mapping them into its domain as its WGSL does.
pub type CpuEval = Box<dyn Fn(Vec4) -> Vec4>;

/// One row of the report.
pub struct Row {
    pub family: &'static str,
    pub name: String,
    /// Bits of storage, where the row is a storage format.
    pub bits: Option<u32>,
    pub domain: String,
    pub unit: &'static str,
    pub errors: Errors,
    /// WGSL defining `fn row_eval(x: vec4<f32>) -> vec4<f32>` over x in [0, 1)^4, with what
    /// it needs. It may sample `lut_texture` with `lut_sampler` (bound by the harness).
    pub wgsl: String,
    /// The environment BRDF LUT size the row samples, if any.
    pub lut_size: Option<usize>,
    pub cpu: CpuEval,
    /// An image of the error, where the report has one for the family.
    pub plot: Option<Plot>,
}

impl Row {
    /// Its bits as the tables write them: the number, or `-` where it is not a storage format.
    pub fn bits_cell(&self) -> String {
        self.bits
            .map_or_else(|| "-".to_string(), |bits| bits.to_string())
    }
}

/// Helpers every row's WGSL may use.
const PRELUDE: &str = "
// Storage in an n-bit unorm channel: what a render target or packing does to a value.
fn quantize3(value: vec3<f32>, max_code: f32) -> vec3<f32> {
    return round(clamp(value, vec3<f32>(0.0), vec3<f32>(1.0)) * max_code) / max_code;
}
fn quantize4(value: vec4<f32>, max_code: f32) -> vec4<f32> {
    return round(clamp(value, vec4<f32>(0.0), vec4<f32>(1.0)) * max_code) / max_code;
}
";

fn wgsl(modules: &[&str], body: &str) -> String {
    let library = gbuffer_shading::compose(modules).expect("the library's modules exist");
    format!("{library}\n{PRELUDE}\n{body}")
}

/// CPU storage in an n-bit unorm channel, with the exact conversions.
fn quantize(value: f32, bits: u32) -> f32 {
    unorm::f32_from_unorm(unorm::unorm_from_f32(value, bits), bits)
}

fn quantize3(value: Vec3, bits: u32) -> Vec3 {
    value
        .to_array()
        .map(|channel| quantize(channel, bits))
        .into()
}

/// The angle between two directions, robust near 0 (atan2 of the cross and dot products).
fn angle_degrees(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b)).to_degrees()
}

// ---- transfer curves through 8-bit storage ----

type Curve = fn(Vec3) -> Vec3;

fn transfer_rows() -> Vec<Row> {
    const SAMPLES: usize = 1 << 16;
    let curves: [(&str, Curve, Curve, &str, &str); 4] = [
        ("linear (no curve)", |c| c, |c| c, "", ""),
        (
            "sRGB exact",
            m::colour::linear_to_srgb,
            m::colour::srgb_to_linear,
            "linear_to_srgb",
            "srgb_to_linear",
        ),
        (
            "gamma 2.2",
            m::colour::linear_to_gamma_2_2,
            m::colour::gamma_2_2_to_linear,
            "linear_to_gamma_2_2",
            "gamma_2_2_to_linear",
        ),
        (
            "pseudo-gamma 2.0",
            m::colour::linear_to_pseudo_gamma,
            m::colour::pseudo_gamma_to_linear,
            "linear_to_pseudo_gamma",
            "pseudo_gamma_to_linear",
        ),
    ];
    curves
        .into_iter()
        .map(|(name, encode, decode, encode_wgsl, decode_wgsl)| {
            let mut errors = Accumulator::default();
            let mut per_code = vec![0.0f64; 256];
            for index in 0..=SAMPLES {
                let linear = index as f32 / SAMPLES as f32;
                let stored = quantize3(encode(Vec3::splat(linear)), 8);
                let decoded = decode(stored);
                // Display steps: both through the exact sRGB curve, in 8-bit code values.
                let error = (r::colour::linear_to_srgb(decoded.as_dvec3()).x - r::colour::linear_to_srgb(DVec3::splat(f64::from(linear))).x).abs() * 255.0;
                errors.add(error);
                let code = (stored.x * 255.0).round() as usize;
                per_code[code] = per_code[code].max(error);
            }
            let body = format!(
                "fn row_eval(x: vec4<f32>) -> vec4<f32> {{\n    let stored = quantize3({encode_wgsl}(x.xyz), 255.0);\n    return vec4<f32>({decode_wgsl}(stored), x.w);\n}}\n"
            );
            Row {
                family: "transfer curve",
                name: name.to_string(),
                bits: Some(8),
                domain: "linear [0, 1], 65537 values, stored in 8 bits".into(),
                unit: "8-bit sRGB steps",
                errors: errors.finish(),
                wgsl: wgsl(&["colour"], &body),
                lut_size: None,
                cpu: Box::new(move |x| decode(quantize3(encode(x.truncate()), 8)).extend(x.w)),
                plot: Some(Plot::Curve { x_label: "stored 8-bit code", y_label: "max error (8-bit sRGB steps)", points: per_code.into_iter().enumerate().map(|(code, error)| (code as f64, error)).collect() }),
            }
        })
        .collect()
}

// ---- normal storage ----

/// How a normal is stored: the naive xyz mapping in unorm channels, or the octahedral codec
/// in a bit field of two coordinates.
#[derive(Clone, Copy)]
enum NormalStorage {
    Xyz { bits: u32 },
    Octahedral { bits: u32 },
}

impl NormalStorage {
    /// The octahedral bit field (the xyz mapping is the shading library's, in unorm channels).
    fn bit_field(bits: u32) -> BitField {
        BitField {
            bits: 2 * bits,
            encoding: Encoding::Octahedral,
        }
    }

    fn round_trip(self, normal: Vec3) -> Vec3 {
        match self {
            NormalStorage::Xyz { bits } => {
                m::normals::unorm_to_normal(quantize3(m::normals::normal_to_unorm(normal), bits))
            }
            NormalStorage::Octahedral { bits } => {
                bit_field_round_trip(NormalStorage::bit_field(bits), normal)
            }
        }
    }
}

/// A `Vec3` through a bit field's codec, there and back: the Rust mirror of the layouts.
fn bit_field_round_trip(field: BitField, value: Vec3) -> Vec3 {
    let lanes = value.extend(0.0).to_array().map(f32::to_bits);
    let back = field.decode(field.encode(lanes, 3), 3);
    Vec3::from_array([back[0], back[1], back[2]].map(f32::from_bits))
}

/// The direction of equirectangular pixel (column, row) of a width x height map.
fn equirectangular_direction(column: usize, row: usize, width: usize, height: usize) -> DVec3 {
    let longitude =
        (column as f64 + 0.5) / width as f64 * std::f64::consts::TAU - std::f64::consts::PI;
    let latitude =
        std::f64::consts::FRAC_PI_2 - (row as f64 + 0.5) / height as f64 * std::f64::consts::PI;
    DVec3::new(
        latitude.cos() * longitude.cos(),
        latitude.cos() * longitude.sin(),
        latitude.sin(),
    )
}

fn normal_rows() -> Vec<Row> {
    let encodings = [
        ("xyz in rgba8", 24, NormalStorage::Xyz { bits: 8 }),
        ("xyz in rgb10_a2", 30, NormalStorage::Xyz { bits: 10 }),
        ("octahedral 2x8", 16, NormalStorage::Octahedral { bits: 8 }),
        (
            "octahedral 2x10",
            20,
            NormalStorage::Octahedral { bits: 10 },
        ),
        (
            "octahedral 2x12",
            24,
            NormalStorage::Octahedral { bits: 12 },
        ),
        (
            "octahedral 2x16",
            32,
            NormalStorage::Octahedral { bits: 16 },
        ),
    ];
    let directions = gbuffer_gpu::values::fibonacci_sphere(1 << 16);
    encodings
        .into_iter()
        .map(|(name, bits, encoding)| {
            let mut errors = Accumulator::default();
            for direction in &directions {
                let exact = direction.as_dvec3().normalize();
                errors.add(angle_degrees(exact, encoding.round_trip(exact.as_vec3()).as_dvec3()));
            }
            let (width, height) = (256, 128);
            let map: Vec<f64> = (0..width * height)
                .map(|pixel| {
                    let exact = equirectangular_direction(pixel % width, pixel / width, width, height);
                    angle_degrees(exact, encoding.round_trip(exact.as_vec3()).as_dvec3())
                })
                .collect();
            let (store, helpers) = match encoding {
                NormalStorage::Xyz { bits } => (
                    format!("unorm_to_normal(quantize3(normal_to_unorm(normal), {}.0))", (1u32 << bits) - 1),
                    String::new(),
                ),
                NormalStorage::Octahedral { bits } => {
                    let layout = one_field_layout("NormalOctahedral", Storage::Bits(NormalStorage::bit_field(bits)), 3);
                    layout_round_trip(&layout, "normal")
                }
            };
            let body = format!(
                "{helpers}\nfn row_eval(x: vec4<f32>) -> vec4<f32> {{\n    let normal = normalize(x.xyz * 2.0 - vec3<f32>(0.999));\n    return vec4<f32>({store} * 0.5 + vec3<f32>(0.5), x.w);\n}}\n"
            );
            Row {
                family: "normal storage",
                name: name.to_string(),
                bits: Some(bits),
                domain: "unit sphere, 65536 Fibonacci directions".into(),
                unit: "degrees",
                errors: errors.finish(),
                wgsl: wgsl(&["normals"], &body),
                lut_size: None,
                cpu: Box::new(move |x| {
                    let normal = (x.truncate() * 2.0 - Vec3::splat(0.999)).normalize();
                    (encoding.round_trip(normal) * 0.5 + Vec3::splat(0.5)).extend(x.w)
                }),
                plot: Some(Plot::Heatmap { width, height, values: map, x_label: "longitude", y_label: "latitude" }),
            }
        })
        .collect()
}

// ---- HDR storage ----

/// A layout of floats, one field a storage, whose generated code the rows time.
fn storage_layout(name: &str, fields: &[(&str, Storage, usize)]) -> Layout {
    Layout {
        name: name.to_string(),
        budget: 32 * fields.len() as u32,
        fields: fields
            .iter()
            .map(|&(field, storage, components)| Field {
                name: field.to_string(),
                storage,
                ty: FieldType::new(ScalarKind::Float, components),
                conversions: None,
            })
            .collect(),
    }
}

/// A layout of one float field, `value`.
fn one_field_layout(name: &str, storage: Storage, components: usize) -> Layout {
    storage_layout(name, &[("value", storage, components)])
}

/// The call of `<snake>_round_trip` on `argument` and what it needs: the generated WGSL of a
/// one-field layout and `fn <snake>_round_trip(value: T) -> T`, the field packed and unpacked
/// by it.
fn layout_round_trip(layout: &Layout, argument: &str) -> (String, String) {
    let symbols = layout.symbols();
    let function = format!("{}_round_trip", symbols.snake());
    let ty = layout.fields[0].ty.wgsl();
    let helpers = format!(
        "{}\nfn {function}(value: {ty}) -> {ty} {{\n    return {}({}({}(value))).value;\n}}\n",
        gbuffer_codegen::emit::wgsl::emit(layout),
        symbols.unpack(),
        symbols.pack(),
        symbols.texel()
    );
    (format!("{function}({argument})"), helpers)
}

/// An HDR storage row: its CPU round trip, and the WGSL that does the same to `colour` (an
/// expression, and the functions it calls beyond the library's).
struct HdrStorage {
    name: &'static str,
    bits: u32,
    round_trip: Box<dyn Fn(Vec3) -> Vec3>,
    helpers: String,
    expression: String,
    modules: &'static [&'static str],
}

fn hdr_rows() -> Vec<Row> {
    const RANGE: f32 = 6.0;
    // The packed float formats run through the generated layout code: pack, then unpack.
    let r11f = one_field_layout("HdrR11f", Storage::Word(Format::R11fG11fB10f), 3);
    let rg16f = storage_layout(
        "HdrRg16f",
        &[
            ("red_green", Storage::Word(Format::Rg16f), 2),
            ("blue", Storage::Word(Format::Rg16f), 1),
        ],
    );
    let log_luminance = BitField {
        bits: 30,
        encoding: Encoding::LogLuminance,
    };
    let (r11f_round_trip, r11f_helpers) = layout_round_trip(&r11f, "colour");
    let (log_luminance_round_trip, log_luminance_helpers) = layout_round_trip(
        &one_field_layout("HdrLogLuminance", Storage::Bits(log_luminance), 3),
        "colour",
    );
    let rg16f_symbols = rg16f.symbols();
    let rg16f_helpers = format!(
        "{}\nfn rg16f_round_trip(colour: vec3<f32>) -> vec3<f32> {{\n    let texel = {}({}({}(colour.rg, colour.b)));\n    return vec3<f32>(texel.red_green, texel.blue);\n}}\n",
        gbuffer_codegen::emit::wgsl::emit(&rg16f),
        rg16f_symbols.unpack(),
        rg16f_symbols.pack(),
        rg16f_symbols.texel()
    );
    let rgbm_round_trip = |encode: fn(Vec3, f32) -> Vec4,
                           decode: fn(Vec4, f32) -> Vec3|
     -> Box<dyn Fn(Vec3) -> Vec3> {
        Box::new(move |c| {
            decode(
                Vec4::from_array(
                    encode(c, RANGE)
                        .to_array()
                        .map(|channel| quantize(channel, 8)),
                ),
                RANGE,
            )
        })
    };
    let encodings = vec![
        HdrStorage {
            name: "scaled rgb10_a2 (range 6)",
            bits: 30,
            round_trip: Box::new(|c| {
                m::hdr::scale_unit_to_hdr(quantize3(m::hdr::scale_hdr_to_unit(c, RANGE), 10), RANGE)
            }),
            helpers: String::new(),
            expression: "scale_unit_to_hdr(quantize3(scale_hdr_to_unit(colour, 6.0), 1023.0), 6.0)"
                .into(),
            modules: &["hdr"],
        },
        HdrStorage {
            name: "r11f_g11f_b10f",
            bits: 32,
            round_trip: Box::new(|c| {
                let word = Format::R11fG11fB10f.encode(c.extend(0.0).to_array());
                Vec3::from_slice(&Format::R11fG11fB10f.decode::<f32>(word)[..3])
            }),
            helpers: r11f_helpers,
            expression: r11f_round_trip,
            modules: &[],
        },
        HdrStorage {
            name: "rg16f x 2 (r, g | b)",
            bits: 48,
            round_trip: Box::new(|c| {
                let red_green =
                    Format::Rg16f.decode::<f32>(Format::Rg16f.encode([c.x, c.y, 0.0, 0.0]));
                let blue = Format::Rg16f.decode::<f32>(Format::Rg16f.encode([c.z, 0.0, 0.0, 0.0]));
                Vec3::new(red_green[0], red_green[1], blue[0])
            }),
            helpers: rg16f_helpers,
            expression: "rg16f_round_trip(colour)".into(),
            modules: &[],
        },
        HdrStorage {
            name: "RGBM in rgba8 (range 6)",
            bits: 32,
            round_trip: rgbm_round_trip(m::hdr::rgbm_encode, m::hdr::rgbm_decode),
            helpers: String::new(),
            expression: "rgbm_decode(quantize4(rgbm_encode(colour, 6.0), 255.0), 6.0)".into(),
            modules: &["hdr"],
        },
        HdrStorage {
            name: "RGBM squared in rgba8 (range 6)",
            bits: 32,
            round_trip: rgbm_round_trip(m::hdr::rgbm_squared_encode, m::hdr::rgbm_squared_decode),
            helpers: String::new(),
            expression:
                "rgbm_squared_decode(quantize4(rgbm_squared_encode(colour, 6.0), 255.0), 6.0)"
                    .into(),
            modules: &["hdr"],
        },
        HdrStorage {
            name: "rgb9e5",
            bits: 32,
            round_trip: Box::new(|c| m::hdr::rgb9e5_decode(m::hdr::rgb9e5_encode(c))),
            helpers: String::new(),
            expression: "rgb9e5_decode(rgb9e5_encode(colour))".into(),
            modules: &["hdr"],
        },
        HdrStorage {
            name: "log luminance 3 x 10 bits",
            bits: 30,
            round_trip: Box::new(move |c| bit_field_round_trip(log_luminance, c)),
            helpers: log_luminance_helpers,
            expression: log_luminance_round_trip,
            modules: &[],
        },
    ];
    // Channels log-uniform over [2^-6, 6]: every format here holds that range.
    let low = (2f64).powi(-6).ln();
    let high = 6f64.ln();
    let colours: Vec<Vec3> = (1..=1u32 << 16)
        .map(|index| {
            let channel = |base| (low + halton(index, base) * (high - low)).exp() as f32;
            Vec3::new(channel(2), channel(3), channel(5))
        })
        .collect();
    encodings
        .into_iter()
        .map(|HdrStorage { name, bits, round_trip, helpers, expression, modules }| {
            let mut errors = Accumulator::default();
            for &colour in &colours {
                let decoded = round_trip(colour);
                let relative = (decoded.as_dvec3() - colour.as_dvec3()).abs() / colour.as_dvec3();
                errors.add(relative.max_element());
            }
            let body = format!(
                "{helpers}\nfn row_eval(x: vec4<f32>) -> vec4<f32> {{\n    let colour = exp2(x.xyz * 8.5 - vec3<f32>(6.0));\n    return vec4<f32>(log2({expression}) * 0.1, x.w);\n}}\n"
            );
            Row {
                family: "HDR storage",
                name: name.to_string(),
                bits: Some(bits),
                domain: "channels log-uniform in [2^-6, 6], 65536 colours".into(),
                unit: "relative",
                errors: errors.finish(),
                wgsl: wgsl(modules, &body),
                lut_size: None,
                cpu: Box::new(move |x| {
                    let colour = (x.truncate() * 8.5 - Vec3::splat(6.0)).exp2();
                    (round_trip(colour).map(f32::log2) * 0.1).extend(x.w)
                }),
                plot: None,
            }
        })
        .collect()
}

// ---- environment BRDF ----

const ENV_GRID: usize = 64;
const ENV_SAMPLES: u32 = 1024;

/// The reference split-sum (scale, bias) at the centre of cell (row: roughness, column: n.v).
fn env_reference() -> Vec<[f64; 2]> {
    (0..ENV_GRID * ENV_GRID)
        .map(|cell| {
            let (roughness, n_dot_v) = env_cell(cell);
            r::environment::integrate_env_brdf(roughness, n_dot_v, ENV_SAMPLES).to_array()
        })
        .collect()
}

fn env_cell(cell: usize) -> (f64, f64) {
    let centre = |index: usize| (index as f64 + 0.5) / ENV_GRID as f64;
    (centre(cell / ENV_GRID), centre(cell % ENV_GRID))
}

type EnvApproximation = Box<dyn Fn(f32, f32, f32) -> f32>;

/// An environment BRDF row: its name, the f0 values it covers, whether it holds for roughness 1
/// only, its CPU form, the WGSL of its reflectance and the LUT size it samples.
type EnvForm = (
    &'static str,
    &'static [f32],
    bool,
    EnvApproximation,
    &'static str,
    Option<usize>,
);

/// A lobe evaluated at (n.h, r.l, roughness).
type Lobe = fn(f32, f32, f32) -> f64;

/// A visibility form at (n.v, n.l, roughness).
type Visibility = fn(f32, f32, f32) -> f32;

fn env_brdf_rows() -> Vec<Row> {
    let reference = env_reference();
    let lut_16 = EnvBrdfLut::bake(16, ENV_SAMPLES);
    let lut_32 = EnvBrdfLut::bake(32, ENV_SAMPLES);
    let lut_row = |lut: EnvBrdfLut| -> EnvApproximation {
        Box::new(move |f0, roughness, n_dot_v| {
            let scale_bias = lut.sample(roughness, n_dot_v);
            f0 * scale_bias.x + scale_bias.y
        })
    };
    // (name, f0 values, roughness fixed to 1?, approximation, WGSL of the reflectance, LUT size)
    let approximations: Vec<EnvForm> = vec![
        (
            "LUT 16x16, bilinear",
            &[0.04, 1.0],
            false,
            lut_row(lut_16),
            "lut_reflectance(f0, roughness, n_dot_v)",
            Some(16),
        ),
        (
            "LUT 32x32, bilinear",
            &[0.04, 1.0],
            false,
            lut_row(lut_32),
            "lut_reflectance(f0, roughness, n_dot_v)",
            Some(32),
        ),
        (
            "env_brdf_approx",
            &[0.04, 1.0],
            false,
            Box::new(|f0, roughness, n_dot_v| {
                m::mobile::env_brdf_approx(Vec3::splat(f0), roughness, n_dot_v).x
            }),
            "env_brdf_approx(vec3<f32>(f0), roughness, n_dot_v).x",
            None,
        ),
        (
            "env_brdf_approx_nonmetal",
            &[0.04],
            false,
            Box::new(|_, roughness, n_dot_v| {
                m::mobile::env_brdf_approx_nonmetal(roughness, n_dot_v)
            }),
            "env_brdf_approx_nonmetal(roughness, n_dot_v)",
            None,
        ),
        (
            "fully rough (0.45 f0)",
            &[0.04, 1.0],
            true,
            Box::new(|f0, _, _| 0.45 * f0),
            "0.45 * f0",
            None,
        ),
    ];
    approximations
        .into_iter()
        .map(|(name, f0s, fully_rough, approximate, reflectance, lut_size)| {
            let mut errors = Accumulator::default();
            let mut map = vec![0.0; ENV_GRID * ENV_GRID];
            for (cell, [scale, bias]) in reference.iter().enumerate() {
                let (roughness, n_dot_v) = env_cell(cell);
                if fully_rough && cell / ENV_GRID != ENV_GRID - 1 {
                    continue; // the shortcut is for roughness 1: the top row of the grid
                }
                for &f0 in f0s {
                    let exact = f64::from(f0) * scale + bias;
                    let error = (f64::from(approximate(f0, roughness as f32, n_dot_v as f32)) - exact).abs();
                    errors.add(error);
                    map[cell] = f64::max(map[cell], error);
                }
            }
            let lut_function = "fn lut_reflectance(f0: f32, roughness: f32, n_dot_v: f32) -> f32 {\n    let scale_bias = textureSampleLevel(lut_texture, lut_sampler, vec2<f32>(n_dot_v, roughness), 0.0).xy;\n    return f0 * scale_bias.x + scale_bias.y;\n}\n";
            let body = format!(
                "{}fn row_eval(x: vec4<f32>) -> vec4<f32> {{\n    let f0 = x.z;\n    let roughness = x.x;\n    let n_dot_v = max(x.y, 0.01);\n    return vec4<f32>({reflectance}, x.yzw);\n}}\n",
                if lut_size.is_some() { lut_function } else { "" }
            );
            let domain = if fully_rough {
                "roughness 1, n.v in (0, 1] (64 cells), f0 in {0.04, 1}".to_string()
            } else if f0s.len() == 1 {
                "roughness x n.v in (0, 1]^2 (64x64 cell centres), f0 0.04".to_string()
            } else {
                "roughness x n.v in (0, 1]^2 (64x64 cell centres), f0 in {0.04, 1}".to_string()
            };
            let plot = (name == "env_brdf_approx").then_some(Plot::Heatmap { width: ENV_GRID, height: ENV_GRID, values: map, x_label: "n.v", y_label: "roughness" });
            Row {
                family: "environment BRDF",
                name: name.to_string(),
                bits: None,
                domain,
                unit: "absolute",
                errors: errors.finish(),
                wgsl: wgsl(&["mobile"], &body),
                lut_size,
                cpu: Box::new(move |x| Vec4::new(approximate(x.z, x.x, x.y.max(0.01)), x.y, x.z, x.w)),
                plot,
            }
        })
        .collect()
}

// ---- specular lobe ----

fn specular_lobe_rows() -> Vec<Row> {
    const GRID: usize = 64;
    const ANGLES: usize = 256;
    let lobes: [(&str, Lobe, &str); 2] = [
        (
            "GGX (f32)",
            |n_dot_h, _, roughness| f64::from(m::microfacet::d_ggx(n_dot_h, roughness)),
            "d_ggx(n_dot_h, roughness)",
        ),
        (
            "d_approx (spherical Gaussian)",
            |_, r_dot_l, roughness| {
                f64::from(m::mobile::d_approx(roughness, r_dot_l)) / std::f64::consts::PI
            },
            "d_approx(roughness, r_dot_l) * INV_PI",
        ),
    ];
    lobes
        .into_iter()
        .map(|(name, lobe, expression)| {
            let mut errors = Accumulator::default();
            let mut map = vec![0.0f64; GRID * GRID];
            for (cell, worst) in map.iter_mut().enumerate() {
                let roughness = 0.1 + 0.9 * (cell / GRID) as f64 / (GRID - 1) as f64;
                let n_dot_v = 0.05 + 0.95 * (cell % GRID) as f64 / (GRID - 1) as f64;
                let view = DVec3::new((1.0 - n_dot_v * n_dot_v).sqrt(), 0.0, n_dot_v);
                let reflected = DVec3::new(-view.x, 0.0, view.z);
                // The lobe over light directions in the plane of incidence, against the GGX
                // peak at this view.
                let samples: Vec<(f64, f64)> = (0..ANGLES)
                    .map(|index| {
                        let angle = -std::f64::consts::FRAC_PI_2 + std::f64::consts::PI * (index as f64 + 0.5) / ANGLES as f64;
                        let light = DVec3::new(angle.sin(), 0.0, angle.cos());
                        let half = (view + light).normalize();
                        let exact = r::microfacet::d_ggx(half.z, roughness);
                        (exact, lobe(half.z as f32, reflected.dot(light) as f32, roughness as f32))
                    })
                    .collect();
                let peak = samples.iter().map(|(exact, _)| *exact).fold(0.0, f64::max);
                for (exact, approximate) in samples {
                    let error = (approximate - exact).abs() / peak;
                    errors.add(error);
                    *worst = f64::max(*worst, error);
                }
            }
            let body = format!(
                "fn row_eval(x: vec4<f32>) -> vec4<f32> {{\n    let roughness = 0.1 + 0.9 * x.x;\n    let n_dot_h = x.y;\n    let r_dot_l = x.z;\n    return vec4<f32>({expression}, x.yzw);\n}}\n"
            );
            let plot = name.starts_with("d_approx").then_some(Plot::Heatmap { width: GRID, height: GRID, values: map, x_label: "n.v", y_label: "roughness" });
            Row {
                family: "specular lobe",
                name: name.to_string(),
                bits: None,
                domain: "roughness [0.1, 1] x n.v [0.05, 1] (64x64), light over the plane of incidence".into(),
                unit: "relative to the GGX peak",
                errors: errors.finish(),
                wgsl: wgsl(&["constants", "microfacet", "mobile"], &body),
                lut_size: None,
                cpu: Box::new(move |x| Vec4::new(lobe(x.y, x.z, 0.1 + 0.9 * x.x) as f32, x.y, x.z, x.w)),
                plot,
            }
        })
        .collect()
}

// ---- visibility ----

fn visibility_rows() -> Vec<Row> {
    const GRID: usize = 32;
    let forms: [(&str, Visibility, &str); 2] = [
        (
            "height-correlated Smith (f32)",
            m::microfacet::v_smith_ggx_correlated,
            "v_smith_ggx_correlated",
        ),
        (
            "separable Schlick-GGX",
            m::microfacet::v_schlick_ggx,
            "v_schlick_ggx",
        ),
    ];
    forms
        .into_iter()
        .map(|(name, form, function)| {
            let mut errors = Accumulator::default();
            let axis = |index: usize, low: f64| low + (1.0 - low) * index as f64 / (GRID - 1) as f64;
            for point in 0..GRID * GRID * GRID {
                let (n_dot_v, n_dot_l, roughness) = (axis(point % GRID, 0.01), axis(point / GRID % GRID, 0.01), axis(point / (GRID * GRID), 0.045));
                let exact = r::microfacet::v_smith_ggx_correlated(n_dot_v, n_dot_l, roughness);
                let value = f64::from(form(n_dot_v as f32, n_dot_l as f32, roughness as f32));
                errors.add((value - exact).abs() / exact);
            }
            let body = format!(
                "fn row_eval(x: vec4<f32>) -> vec4<f32> {{\n    return vec4<f32>({function}(max(x.x, 0.01), max(x.y, 0.01), max(x.z, 0.045)) * 0.01, x.yzw);\n}}\n"
            );
            Row {
                family: "visibility",
                name: name.to_string(),
                bits: None,
                domain: "n.v, n.l [0.01, 1] x roughness [0.045, 1] (32^3)".into(),
                unit: "relative",
                errors: errors.finish(),
                wgsl: wgsl(&["microfacet"], &body),
                lut_size: None,
                cpu: Box::new(move |x| Vec4::new(form(x.x.max(0.01), x.y.max(0.01), x.z.max(0.045)) * 0.01, x.y, x.z, x.w)),
                plot: None,
            }
        })
        .collect()
}

// ---- whole layouts ----

/// The light the texel shows: the stored light plus a white sun, tone mapped and encoded as
/// sRGB, in 8-bit steps: what the error of a layout looks like on screen.
fn displayed(shading: &Shading) -> DVec3 {
    let view = DVec3::new(0.0, 0.6, 0.8);
    let sun = DVec3::new(0.3, -0.4, 0.866).normalize();
    let normal = shading.normal.as_dvec3().normalize();
    let roughness = f64::from(shading.roughness);
    // The split-sum albedo the diffuse term is scaled by, as a renderer's LUT gives it.
    let env_brdf =
        r::environment::integrate_env_brdf(roughness.max(0.045), normal.dot(view).max(1e-4), 64);
    let shaded = r::shading::shade_directional(
        normal,
        view,
        sun,
        DVec3::splat(3.0),
        shading.diffuse.as_dvec3(),
        shading.f0.as_dvec3(),
        roughness,
        env_brdf,
    );
    r::colour::linear_to_srgb(r::tonemap::tonemap_reinhard(
        shaded + shading.light.as_dvec3(),
    )) * 255.0
}

/// The surfaces the layouts store: normals facing the viewer, roughness, metallic 0 or 1, base
/// colour and stored light below the seed layouts' light scale, spread by Halton sequences.
fn surfaces() -> Vec<Surface> {
    (1..=1u32 << 14)
        .map(|index| {
            let direction = |a: f64, b: f64| {
                let z = a; // upper hemisphere facing the viewer
                let angle = std::f64::consts::TAU * b;
                let radius = (1.0 - z * z).sqrt();
                DVec3::new(radius * angle.cos(), radius * angle.sin(), z).as_vec3()
            };
            let metallic = if index % 3 == 0 { 1.0 } else { 0.0 };
            Surface {
                normal: direction(halton(index, 2), halton(index, 3)),
                roughness: halton(index, 5) as f32,
                metallic,
                base_colour: Vec3::new(
                    halton(index, 7) as f32,
                    halton(index, 11) as f32,
                    halton(index, 13) as f32,
                ),
                light: Vec3::new(
                    halton(index, 17) as f32,
                    halton(index, 19) as f32,
                    halton(index, 23) as f32,
                ) * LIGHT_SCALE,
                distance: 0.5,
                position: Vec3::new(1.0, 2.0, 3.0),
            }
        })
        .collect()
}

/// A layout's row: its name, model, WGSL, bits and the Rust mirror of its convention.
struct LayoutRow {
    name: &'static str,
    layout: Layout,
    wgsl: &'static str,
    decode_wgsl: &'static str,
    bits: u32,
    round_trip: fn(&Surface) -> Shading,
}

impl LayoutRow {
    fn of<L: SurfaceConvention>(name: &'static str) -> LayoutRow {
        LayoutRow {
            name,
            layout: L::layout(),
            wgsl: L::WGSL,
            decode_wgsl: L::DECODE_WGSL,
            bits: L::BITS,
            round_trip: round_trip::<L>,
        }
    }
}

pub(crate) fn layout_rows() -> Vec<Row> {
    use gbuffer::engine_layouts::{BevyDeferred, HdrpLit};
    use gbuffer::seed_layouts::{ArmTileBlock, FutureMetallic, FutureSpecular, MobileMetallic};
    use gbuffer_render::coarse::CoarseNormals;
    // Each layout by its own convention (`gbuffer_render::conventions::seed`,
    // `gbuffer_render::conventions::engine`), as the renderer stores it.
    let layouts = [
        LayoutRow::of::<MobileMetallic>("Listing 2.2 (MobileMetallic)"),
        LayoutRow::of::<ArmTileBlock>("Arm tile block (ArmTileBlock)"),
        LayoutRow::of::<FutureMetallic>("Listing 2.7 (FutureMetallic)"),
        LayoutRow::of::<FutureSpecular>("Listing 2.8 (FutureSpecular)"),
        LayoutRow::of::<BevyDeferred>("Bevy, WebGL2 (BevyDeferred)"),
        LayoutRow::of::<HdrpLit>("HDRP Lit (HdrpLit)"),
        LayoutRow::of::<CoarseNormals>("2 x 8-bit normals (CoarseNormals)"),
    ];
    let surfaces = surfaces();
    layouts
        .into_iter()
        .map(|seed| {
            let round_trip = seed.round_trip;
            let mut errors = Accumulator::default();
            for surface in &surfaces {
                let difference =
                    displayed(&round_trip(surface)) - displayed(&Shading::of(surface));
                errors.add(difference.abs().max_element());
            }
            let unpack = seed.layout.symbols().unpack();
            let words = seed.layout.words();
            // The words come from the input's bits: the cost measured is unpack, decode, shade.
            let lanes: Vec<String> = (0..words).map(|word| format!("bitcast<u32>(x[{}]) ^ {word}u", word % 4)).collect();
            let body = format!(
                "{layout_wgsl}\n{SURFACE_WGSL}\n{decode_wgsl}\n\n\
                 fn row_eval(x: vec4<f32>) -> vec4<f32> {{\n\
                 \x20   let s = decode_texel({unpack}(array<u32, {words}>({lanes})));\n\
                 \x20   let shaded = shade_directional(s.normal, vec3<f32>(0.0, 0.6, 0.8), vec3<f32>(0.3, -0.4, 0.866), vec3<f32>(3.0), s.diffuse, s.f0, s.roughness, vec2<f32>(0.6, 0.1));\n\
                 \x20   return vec4<f32>(linear_to_srgb(tonemap_reinhard(shaded + s.light)), x.w);\n\
                 }}\n",
                layout_wgsl = seed.wgsl,
                decode_wgsl = seed.decode_wgsl,
                lanes = lanes.join(", "),
            );
            Row {
                family: "whole layout",
                name: seed.name.to_string(),
                bits: Some(seed.bits),
                domain: format!("16384 surfaces (normals facing the viewer, roughness, metallic 0/1, base colour, stored light < {LIGHT_SCALE}), sun and stored light, Reinhard, sRGB"),
                unit: "8-bit sRGB steps",
                errors: errors.finish(),
                wgsl: wgsl(&["shading", "material", "colour", "tonemap", "normals", "hdr", "constants"], &body),
                lut_size: None,
                cpu: Box::new(move |x| {
                    let surface = Surface {
                        normal: (x.truncate() * 2.0 - Vec3::splat(0.999)).normalize(),
                        roughness: x.w,
                        metallic: x.z,
                        base_colour: Vec3::splat(x.y),
                        light: Vec3::splat(x.x),
                        ..Surface::default()
                    };
                    let s = round_trip(&surface);
                    let shaded = m::shading::shade_directional(s.normal, Vec3::new(0.0, 0.6, 0.8), Vec3::new(0.3, -0.4, 0.866), Vec3::splat(3.0), s.diffuse, s.f0, s.roughness, Vec2::new(0.6, 0.1));
                    m::colour::linear_to_srgb(m::tonemap::tonemap_reinhard(shaded + s.light)).extend(x.w)
                }),
                plot: None,
            }
        })
        .collect()
}

/// Every row, family by family.
pub fn rows() -> Vec<Row> {
    let mut rows = Vec::new();
    rows.extend(transfer_rows());
    rows.extend(normal_rows());
    rows.extend(hdr_rows());
    rows.extend(env_brdf_rows());
    rows.extend(specular_lobe_rows());
    rows.extend(visibility_rows());
    rows.extend(layout_rows());
    rows
}

#[cfg(test)]
mod tests {
    use super::*;

    fn errors_of(rows: &[Row], name: &str) -> Errors {
        rows.iter()
            .find(|row| row.name == name)
            .unwrap_or_else(|| panic!("no row {name}"))
            .errors
    }

    #[test]
    fn storage_errors_fall_with_bits_and_match_their_quantization() {
        let transfer = transfer_rows();
        // Exact sRGB through 8 bits is off by the rounding alone: half a step.
        assert!((errors_of(&transfer, "sRGB exact").max - 0.5).abs() < 1e-3);
        assert!(
            errors_of(&transfer, "linear (no curve)").max > 5.0,
            "8-bit linear storage bands in the darks"
        );
        let normals = normal_rows();
        let octahedral: Vec<f64> = [8, 10, 12, 16]
            .map(|bits| errors_of(&normals, &format!("octahedral 2x{bits}")).max)
            .to_vec();
        assert!(
            octahedral.windows(2).all(|pair| pair[1] < pair[0] / 3.0),
            "{octahedral:?}"
        );
        assert!(
            errors_of(&normals, "octahedral 2x12").max < errors_of(&normals, "xyz in rgba8").max,
            "same 24 bits, better spent"
        );
        let hdr = hdr_rows();
        // Half floats keep 11 significant bits: 2^-11 relative.
        assert!(errors_of(&hdr, "rg16f x 2 (r, g | b)").max <= 2f64.powi(-11) * 1.0001);
        assert!(errors_of(&hdr, "r11f_g11f_b10f").max <= 2f64.powi(-6) * 1.0001);
    }

    #[test]
    fn finer_luts_are_closer_and_every_row_has_valid_wgsl() {
        let environment = env_brdf_rows();
        assert!(
            errors_of(&environment, "LUT 32x32, bilinear").rms
                < errors_of(&environment, "LUT 16x16, bilinear").rms
        );
        for row in environment
            .iter()
            .chain(&specular_lobe_rows())
            .chain(&visibility_rows())
        {
            let harness = crate::timing::harness(&row.wgsl);
            gbuffer_validator::validate_wgsl(&harness)
                .unwrap_or_else(|problem| panic!("{}: {problem}", row.name));
        }
    }
}
