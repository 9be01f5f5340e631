//! The encodings' rows: transfer curves through 8-bit storage, normal storage and HDR
//! storage, each against the f64 reference over its domain.

use gbuffer_core::{BitField, Encoding, Field, FieldType, Format, Layout, ScalarKind, Storage};
use gbuffer_shading::{mirror as m, reference as r};
use glam::{DVec3, Vec3, Vec4};

use gbuffer_gpu::values::halton;

use super::{angle_degrees, quantize, quantize3, wgsl, Accumulator, Row};
use crate::plot::Plot;

// ---- transfer curves through 8-bit storage ----

type Curve = fn(Vec3) -> Vec3;

pub(super) fn transfer_rows() -> Vec<Row> {
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

pub(super) fn normal_rows() -> Vec<Row> {
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
        gbuffer_codegen::wgsl::emit(layout),
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

pub(super) fn hdr_rows() -> Vec<Row> {
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
        gbuffer_codegen::wgsl::emit(&rg16f),
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
