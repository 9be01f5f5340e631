//! The rows of the trade-off report: each approximation or encoding, its error against the
//! f64 reference over a stated domain, the WGSL that costs and times it, and its CPU mirror.
//! One family a file: the encodings ([`encodings`]), the shading approximations ([`shading`]),
//! whole layouts ([`layouts`]); the error statistics in [`errors`].

mod encodings;
mod errors;
mod layouts;
mod shading;

pub use errors::Errors;
pub(crate) use layouts::layout_rows;

use errors::Accumulator;

use gbuffer_core::codecs::unorm;
use glam::{DVec3, Vec3, Vec4};

use crate::plot::Plot;

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

/// Every row, family by family.
pub fn rows() -> Vec<Row> {
    let mut rows = Vec::new();
    rows.extend(encodings::transfer_rows());
    rows.extend(encodings::normal_rows());
    rows.extend(encodings::hdr_rows());
    rows.extend(shading::env_brdf_rows());
    rows.extend(shading::specular_lobe_rows());
    rows.extend(shading::visibility_rows());
    rows.extend(layout_rows());
    rows
}

#[cfg(test)]
mod tests {
    use super::encodings::{hdr_rows, normal_rows, transfer_rows};
    use super::shading::{env_brdf_rows, specular_lobe_rows, visibility_rows};
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
