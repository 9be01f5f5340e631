//! Every function of the WGSL shading library as a test case: how to call it in WGSL, the
//! domain its arguments are sampled over, its f32 mirror, its f64 reference, and how close
//! the adapter must come to the mirror.

use gbuffer_shading::mirror as m;
use gbuffer_shading::reference as r;
use glam::{DVec2, DVec3, DVec4, Vec2, Vec3, Vec4};

use gbuffer_gpu::values::{fibonacci_sphere, halton};

/// How one argument is sampled.
#[derive(Clone, Copy, Debug)]
pub enum Argument {
    /// An f32 on a uniform grid over [low, high], both ends included.
    Scalar {
        /// The grid's first value.
        low: f32,
        /// Its last value.
        high: f32,
    },
    /// A vec3 from a fixed set of colours spanning [0, scale].
    Colour {
        /// The largest channel value.
        scale: f32,
    },
    /// A vec2 on a grid over [low, high]^2.
    Pair {
        /// The grid's first value on each axis.
        low: f32,
        /// Its last value.
        high: f32,
    },
    /// A unit vec3, spread over the sphere (a Fibonacci lattice).
    Direction,
    /// A vec4 tangent: a unit xyz and a sign in w.
    Tangent,
    /// A vec4 from a fixed set of RGBM texels.
    Rgbm,
    /// A u32 on a grid over [low, high].
    Unsigned {
        /// The grid's first value.
        low: u32,
        /// Its last value.
        high: u32,
    },
}

impl Argument {
    /// Components in the flattened argument list.
    pub fn components(self) -> usize {
        match self {
            Argument::Scalar { .. } | Argument::Unsigned { .. } => 1,
            Argument::Pair { .. } => 2,
            Argument::Colour { .. } | Argument::Direction => 3,
            Argument::Tangent | Argument::Rgbm => 4,
        }
    }

    /// The WGSL expression that reads this argument from `inputs[base + offset..]`.
    pub fn wgsl(self, offset: usize) -> String {
        let load = |index: usize| format!("inputs[base + {}u]", offset + index);
        let float = |index: usize| format!("bitcast<f32>({})", load(index));
        match self {
            Argument::Unsigned { .. } => load(0),
            Argument::Scalar { .. } => float(0),
            _ => {
                let count = self.components();
                let parts: Vec<String> = (0..count).map(float).collect();
                format!("vec{count}<f32>({})", parts.join(", "))
            }
        }
    }

    /// `count` sample values, each as its components' bits.
    pub fn samples(self, count: usize) -> Vec<Vec<u32>> {
        let steps =
            |count: usize| (0..count).map(move |index| index as f64 / (count.max(2) - 1) as f64);
        match self {
            Argument::Scalar { low, high } => steps(count)
                .map(|t| vec![lerp(low, high, t).to_bits()])
                .collect(),
            Argument::Unsigned { low, high } => steps(count)
                .map(|t| vec![(f64::from(low) + t * f64::from(high - low)).round() as u32])
                .collect(),
            Argument::Pair { low, high } => {
                let side = (count as f64).sqrt().ceil() as usize;
                let values: Vec<f32> = steps(side).map(|t| lerp(low, high, t)).collect();
                values
                    .iter()
                    .flat_map(|&x| values.iter().map(move |&y| vec![x.to_bits(), y.to_bits()]))
                    .collect()
            }
            // The named colours first, then a low-discrepancy spread over the cube.
            Argument::Colour { scale } => COLOURS
                .into_iter()
                .chain((1..).map(|index| [2, 3, 5].map(|base| halton(index, base) as f32)))
                .take(count.max(2))
                .map(|colour| colour.map(|c| (c * scale).to_bits()).to_vec())
                .collect(),
            Argument::Direction => fibonacci_sphere(count)
                .into_iter()
                .map(|d| d.to_array().map(f32::to_bits).to_vec())
                .collect(),
            Argument::Tangent => fibonacci_sphere(count)
                .into_iter()
                .enumerate()
                .map(|(index, d)| {
                    d.extend(if index % 2 == 0 { 1.0 } else { -1.0 })
                        .to_array()
                        .map(f32::to_bits)
                        .to_vec()
                })
                .collect(),
            Argument::Rgbm => RGBM_TEXELS
                .iter()
                .map(|texel| texel.map(f32::to_bits).to_vec())
                .collect(),
        }
    }
}

fn lerp(low: f32, high: f32, t: f64) -> f32 {
    (f64::from(low) + t * (f64::from(high) - f64::from(low))) as f32
}

/// Colours in [0, 1]: black, white, primaries, greys, a gold and a dark stone.
#[rustfmt::skip] // eight colours of a small table
const COLOURS: [[f32; 3]; 8] = [
    [0.0, 0.0, 0.0], [1.0, 1.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0],
    [0.5, 0.5, 0.5], [1.0, 0.766, 0.336], [0.05, 0.04, 0.03],
];

const RGBM_TEXELS: [[f32; 4]; 6] = [
    [0.0, 0.0, 0.0, 0.0],
    [1.0, 1.0, 1.0, 1.0],
    [0.5, 0.25, 0.125, 0.2],
    [1.0, 0.0, 0.5, 0.003_921_569],
    [0.1, 0.9, 0.4, 0.75],
    [0.8, 0.8, 0.8, 0.5],
];

/// The function's values as f32 bits (floats) or raw u32 (integers).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Output {
    /// This many f32 components.
    Floats(usize),
    /// One u32.
    Unsigned,
}

/// An f64 reference over the widened arguments.
pub type Reference = fn(&[f64]) -> Vec<f64>;

/// One function under test.
pub struct Case {
    /// The WGSL module it lives in (composed with its dependencies).
    pub module: &'static str,
    /// The WGSL expression over the arguments `a0`, `a1`, ...
    pub call: String,
    /// How each argument is sampled.
    pub arguments: &'static [Argument],
    /// What it returns.
    pub output: Output,
    /// The f32 mirror, over the arguments' bits.
    pub mirror: fn(&[u32]) -> Vec<u32>,
    /// The f64 reference, over the same arguments widened to f64 (None for integer-exact
    /// functions, which are their own reference).
    pub reference: Option<Reference>,
    /// The adapter may differ from the mirror by this many ulp...
    pub ulps: u32,
    /// ... or by this much absolutely (for results near zero, where ulps are tiny).
    pub absolute: f32,
}

impl Case {
    /// The function's name: the call up to its parenthesis.
    pub fn name(&self) -> &str {
        self.call.split('(').next().unwrap_or(&self.call)
    }
}

/// A type of the f32 mirror's arguments and results, as the bits of its components.
trait Bits: Sized {
    /// What a result of this type is, for the harness.
    const OUTPUT: Output;
    /// Its components.
    const COMPONENTS: usize;
    fn from_bits(bits: &[u32]) -> Self;
    fn into_bits(self) -> Vec<u32>;
}

/// A type of the f64 reference's arguments and results, as f64 components.
trait Wide: Sized {
    const COMPONENTS: usize;
    fn from_wide(values: &[f64]) -> Self;
    fn into_wide(self) -> Vec<f64>;
}

impl Bits for u32 {
    const OUTPUT: Output = Output::Unsigned;
    const COMPONENTS: usize = 1;
    fn from_bits(bits: &[u32]) -> Self {
        bits[0]
    }
    fn into_bits(self) -> Vec<u32> {
        vec![self]
    }
}

impl Wide for u32 {
    const COMPONENTS: usize = 1;
    fn from_wide(values: &[f64]) -> Self {
        values[0] as u32
    }
    fn into_wide(self) -> Vec<f64> {
        vec![f64::from(self)]
    }
}

impl Bits for f32 {
    const OUTPUT: Output = Output::Floats(1);
    const COMPONENTS: usize = 1;
    fn from_bits(bits: &[u32]) -> Self {
        f32::from_bits(bits[0])
    }
    fn into_bits(self) -> Vec<u32> {
        vec![self.to_bits()]
    }
}

impl Wide for f64 {
    const COMPONENTS: usize = 1;
    fn from_wide(values: &[f64]) -> Self {
        values[0]
    }
    fn into_wide(self) -> Vec<f64> {
        vec![self]
    }
}

/// `Bits` for glam's f32 vectors and `Wide` for its f64 ones, of `n` components.
macro_rules! float_types {
    ($($narrow:ty, $wide:ty, $n:literal;)+) => {$(
        impl Bits for $narrow {
            const OUTPUT: Output = Output::Floats($n);
            const COMPONENTS: usize = $n;
            fn from_bits(bits: &[u32]) -> Self {
                let components: [f32; $n] = std::array::from_fn(|index| f32::from_bits(bits[index]));
                <$narrow>::from(components)
            }
            fn into_bits(self) -> Vec<u32> {
                let components: [f32; $n] = self.into();
                components.map(f32::to_bits).to_vec()
            }
        }
        impl Wide for $wide {
            const COMPONENTS: usize = $n;
            fn from_wide(values: &[f64]) -> Self {
                let components: [f64; $n] = std::array::from_fn(|index| values[index]);
                <$wide>::from(components)
            }
            fn into_wide(self) -> Vec<f64> {
                let components: [f64; $n] = self.into();
                components.to_vec()
            }
        }
    )+};
}

float_types! {
    Vec2, DVec2, 2;
    Vec3, DVec3, 3;
    Vec4, DVec4, 4;
}

/// The mirror's next argument, from the point's bits at `at`.
fn take<T: Bits>(bits: &[u32], at: &mut usize) -> T {
    let value = T::from_bits(&bits[*at..]);
    *at += T::COMPONENTS;
    value
}

/// The reference's next argument, from the widened point at `at`.
fn take_wide<T: Wide>(values: &[f64], at: &mut usize) -> T {
    let value = T::from_wide(&values[*at..]);
    *at += T::COMPONENTS;
    value
}

/// What the mirror `function` returns.
fn output_of<T: Bits>(_function: fn(&[u32]) -> T) -> Output {
    T::OUTPUT
}

/// `function(a0, a1, ...)` and the field taken from its result, the harness's WGSL call.
fn wgsl_call(function: &str, arguments: usize, field: &str) -> String {
    let names: Vec<String> = (0..arguments).map(|index| format!("a{index}")).collect();
    format!("{function}({}){field}", names.join(", "))
}

/// One case, written once: `module::function(ARGUMENT, ...)`, with `.field` where the function
/// returns a struct, names the WGSL call, the f32 mirror (`mirror::module::function`) and the
/// f64 reference (`reference::module::function`), each over the arguments in order. Then how
/// close the adapter must come to the mirror (`ulps N, absolute X`), or `exact` for an integer
/// function, its own reference; `reference |values| ...` replaces the library's reference.
macro_rules! case {
    ($module:ident::$function:ident($($argument:expr),+) $(.$field:ident)?; exact) => {
        case!(@case $module::$function($($argument),+) $(.$field)?, None, 0, 0.0)
    };
    (
        $module:ident::$function:ident($($argument:expr),+) $(.$field:ident)?;
        ulps $ulps:literal, absolute $absolute:literal $(; reference $reference:expr)?
    ) => {
        case!(
            @case $module::$function($($argument),+) $(.$field)?,
            Some(case!(@reference $module::$function($($argument),+) $(.$field)? $(, $reference)?)),
            $ulps,
            $absolute
        )
    };
    (@reference $module:ident::$function:ident($($argument:expr),+) $(.$field:ident)?) => {
        |values| {
            Wide::into_wide(case!(
                @call r::$module::$function, take_wide, values, ($($argument),+) $(.$field)?
            ))
        }
    };
    (@reference $module:ident::$function:ident($($argument:expr),+) $(.$field:ident)?, $reference:expr) => {
        $reference
    };
    // The function at `path` on one argument per `argument`, each taken from `values` in turn
    // by `take`, and the field of its result.
    (@call $path:path, $take:ident, $values:ident, ($($argument:expr),+) $(.$field:ident)?) => {{
        let mut at = 0;
        $path($({ let _: Argument = $argument; $take($values, &mut at) }),+)$(.$field)?
    }};
    (@case $module:ident::$function:ident($($argument:expr),+) $(.$field:ident)?, $reference:expr, $ulps:expr, $absolute:expr) => {
        Case {
            module: stringify!($module),
            call: wgsl_call(
                stringify!($function),
                [$(stringify!($argument)),+].len(),
                concat!($(".", stringify!($field))?),
            ),
            arguments: &[$($argument),+],
            output: output_of(|bits| {
                case!(@call m::$module::$function, take, bits, ($($argument),+) $(.$field)?)
            }),
            mirror: |bits| {
                Bits::into_bits(case!(
                    @call m::$module::$function, take, bits, ($($argument),+) $(.$field)?
                ))
            },
            reference: $reference,
            ulps: $ulps,
            absolute: $absolute,
        }
    };
}

use Argument::{Colour, Direction, Pair, Rgbm, Scalar, Tangent, Unsigned};

const UNIT: Argument = Scalar {
    low: 0.0,
    high: 1.0,
};
const ROUGHNESS: Argument = Scalar {
    low: 0.045,
    high: 1.0,
};
const COSINE: Argument = Scalar {
    low: 0.001,
    high: 1.0,
};
const HDR_COLOUR: Argument = Colour { scale: 6.0 };
const LIGHT_COLOUR: Argument = Colour { scale: 3.0 };
const COLOUR: Argument = Colour { scale: 1.0 };
/// A split-sum (scale, bias) pair: both in [0, 1] (their sum too, in the real LUT).
const ENV_BRDF: Argument = Pair {
    low: 0.0,
    high: 0.5,
};

/// Every function of the library.
pub fn cases() -> Vec<Case> {
    vec![
        // colour
        case!(colour::srgb_to_linear(COLOUR); ulps 16, absolute 1e-6),
        case!(colour::linear_to_srgb(COLOUR); ulps 16, absolute 1e-6),
        case!(colour::gamma_2_2_to_linear(COLOUR); ulps 16, absolute 1e-6),
        case!(colour::linear_to_gamma_2_2(COLOUR); ulps 16, absolute 1e-6),
        case!(colour::pseudo_gamma_to_linear(COLOUR); ulps 1, absolute 0.0),
        case!(colour::linear_to_pseudo_gamma(COLOUR); ulps 4, absolute 0.0),
        case!(colour::luminance(HDR_COLOUR); ulps 4, absolute 1e-7),
        // hdr
        case!(hdr::rgbm_encode(HDR_COLOUR, Scalar { low: 1.0, high: 8.0 }); ulps 8, absolute 1e-6),
        case!(hdr::rgbm_decode(Rgbm, Scalar { low: 1.0, high: 8.0 }); ulps 2, absolute 0.0),
        case!(
            hdr::rgbm_squared_encode(HDR_COLOUR, Scalar { low: 1.0, high: 8.0 });
            ulps 8, absolute 1e-6
        ),
        case!(hdr::rgbm_squared_decode(Rgbm, Scalar { low: 1.0, high: 8.0 }); ulps 4, absolute 0.0),
        case!(
            hdr::scale_hdr_to_unit(HDR_COLOUR, Scalar { low: 1.0, high: 16.0 });
            ulps 4, absolute 0.0
        ),
        case!(
            hdr::scale_unit_to_hdr(COLOUR, Scalar { low: 1.0, high: 16.0 });
            ulps 1, absolute 0.0
        ),
        case!(hdr::rgb9e5_encode(Colour { scale: 70000.0 }); exact),
        case!(hdr::rgb9e5_decode(Unsigned { low: 0, high: u32::MAX }); exact),
        // microfacet
        case!(microfacet::d_ggx(UNIT, ROUGHNESS); ulps 8, absolute 0.0),
        case!(microfacet::v_smith_ggx_correlated(COSINE, COSINE, ROUGHNESS); ulps 16, absolute 0.0),
        case!(microfacet::v_schlick_ggx(UNIT, UNIT, ROUGHNESS); ulps 8, absolute 0.0),
        case!(
            microfacet::schlick_weight(UNIT);
            ulps 8, absolute 1e-7; reference |a| vec![(1.0 - a[0]).powi(5)]
        ),
        case!(microfacet::f_schlick(COLOUR, UNIT); ulps 8, absolute 1e-7),
        case!(
            microfacet::f_schlick_roughness(COLOUR, Scalar { low: -0.5, high: 1.0 }, UNIT);
            ulps 8, absolute 1e-7
        ),
        case!(microfacet::lambert_diffuse(COLOUR); ulps 1, absolute 0.0),
        // mobile
        case!(mobile::env_brdf_approx(COLOUR, UNIT, UNIT); ulps 16, absolute 1e-6),
        case!(mobile::env_brdf_approx_nonmetal(UNIT, UNIT); ulps 16, absolute 1e-6),
        case!(mobile::fully_rough_diffuse_colour(COLOUR, COLOUR); ulps 2, absolute 0.0),
        case!(
            mobile::d_approx(Scalar { low: 0.0625, high: 1.0 }, Scalar { low: -1.0, high: 1.0 });
            ulps 64, absolute 1e-30
        ),
        // environment
        case!(
            environment::ibl_mip_level(UNIT, Scalar { low: 1.0, high: 12.0 });
            ulps 1, absolute 0.0
        ),
        case!(
            environment::hammersley(Unsigned { low: 0, high: 4095 }, Unsigned { low: 4096, high: 4096 });
            ulps 1, absolute 0.0
        ),
        case!(
            environment::importance_sample_ggx(Pair { low: 0.0, high: 0.999 }, ROUGHNESS);
            ulps 64, absolute 2e-6
        ),
        case!(
            environment::integrate_env_brdf(UNIT, COSINE, Unsigned { low: 64, high: 64 });
            ulps 256, absolute 1e-5
        ),
        case!(
            environment::ibl_specular_seed(HDR_COLOUR, COLOUR, UNIT, UNIT);
            ulps 8, absolute 1e-6
        ),
        // material
        case!(
            material::metallic_workflow(COLOUR, UNIT, Scalar { low: 0.0, high: 0.08 }).diffuse;
            ulps 2, absolute 0.0
        ),
        case!(
            material::metallic_workflow(COLOUR, UNIT, Scalar { low: 0.0, high: 0.08 }).f0;
            ulps 4, absolute 1e-8
        ),
        case!(material::dielectric_f0_from_specular(UNIT); ulps 1, absolute 0.0),
        case!(material::specular_workflow(COLOUR, COLOUR).diffuse; ulps 2, absolute 0.0),
        // normals
        case!(normals::reconstruct_tangent_z(Pair { low: -1.0, high: 1.0 }); ulps 8, absolute 1e-6),
        case!(normals::tangent_to_world(Direction, Direction, Tangent); ulps 64, absolute 1e-5),
        case!(normals::octahedral_encode(Direction); ulps 8, absolute 1e-7),
        case!(normals::octahedral_decode(Pair { low: -1.0, high: 1.0 }); ulps 16, absolute 1e-6),
        case!(normals::normal_to_unorm(Direction); ulps 2, absolute 1e-7),
        case!(normals::unorm_to_normal(Colour { scale: 1.0 }); ulps 16, absolute 1e-6),
        // tonemap
        case!(tonemap::tonemap_reinhard(HDR_COLOUR); ulps 4, absolute 0.0),
        case!(tonemap::tonemap_aces_fitted(HDR_COLOUR); ulps 8, absolute 1e-7),
        // shading
        case!(shading::half_vector_of(Direction, Direction); ulps 8, absolute 1e-6),
        case!(shading::diffuse_share(Colour { scale: 1.5 }); ulps 1, absolute 1e-7),
        case!(shading::specular_albedo(COLOUR, ENV_BRDF); ulps 2, absolute 1e-7),
        case!(
            shading::shade_directional(Direction, Direction, Direction, LIGHT_COLOUR, COLOUR, COLOUR, ROUGHNESS, ENV_BRDF);
            ulps 256, absolute 1e-5
        ),
        case!(
            shading::shade_directional_mobile(Direction, Direction, Direction, LIGHT_COLOUR, COLOUR, COLOUR, ROUGHNESS);
            ulps 256, absolute 1e-5
        ),
        case!(
            shading::shade_ibl(COLOUR, COLOUR, HDR_COLOUR, HDR_COLOUR, Pair { low: 0.0, high: 1.0 });
            ulps 8, absolute 1e-6
        ),
        case!(
            shading::shade_ibl_mobile(COLOUR, COLOUR, UNIT, UNIT, HDR_COLOUR, HDR_COLOUR);
            ulps 32, absolute 1e-5
        ),
        case!(
            shading::point_light_falloff(Scalar { low: 0.0, high: 12.0 }, Scalar { low: 0.5, high: 10.0 });
            ulps 16, absolute 1e-6
        ),
    ]
}

/// The case's input grid: the cartesian product of each argument's samples, with about
/// `target` points in all. Each point is the flattened arguments' bits.
pub fn grid(case: &Case, target: usize) -> Vec<Vec<u32>> {
    // Fixed sets (RGBM texels, constant integers) have their own sizes; the other arguments
    // share what is left of the target.
    let fixed_size = |argument: &Argument| match argument {
        Argument::Rgbm => Some(RGBM_TEXELS.len()),
        Argument::Unsigned { low, high } if low == high => Some(1),
        _ => None,
    };
    let fixed: usize = case.arguments.iter().filter_map(fixed_size).product();
    let free = case
        .arguments
        .iter()
        .filter(|argument| fixed_size(argument).is_none())
        .count();
    let per_argument = if free == 0 {
        1
    } else {
        ((target / fixed) as f64)
            .powf(1.0 / free as f64)
            .ceil()
            .max(2.0) as usize
    };
    let mut points: Vec<Vec<u32>> = vec![Vec::new()];
    for argument in case.arguments {
        let samples = argument.samples(fixed_size(argument).unwrap_or(per_argument));
        points = points
            .iter()
            .flat_map(|point| {
                samples.iter().map(move |sample| {
                    let mut extended = point.clone();
                    extended.extend_from_slice(sample);
                    extended
                })
            })
            .collect();
    }
    points
}

/// A compute shader that evaluates the case at every point of `inputs` (the flattened
/// arguments' bits) into `outputs`; bindings as [`gbuffer_gpu::Gpu::run_compute`] expects.
pub fn compute_harness(case: &Case) -> String {
    let mut wgsl = gbuffer_shading::compose(&[case.module]).expect("the case's module exists");
    let stride: usize = case
        .arguments
        .iter()
        .map(|argument| argument.components())
        .sum();
    wgsl.push_str("\n// ---- test harness ----\n");
    wgsl.push_str("@group(0) @binding(0) var<storage, read> inputs: array<u32>;\n");
    wgsl.push_str("@group(0) @binding(1) var<storage, read_write> outputs: array<u32>;\n");
    wgsl.push_str("@group(0) @binding(2) var<uniform> count: vec4<u32>;\n\n");
    wgsl.push_str("@compute @workgroup_size(64)\nfn harness_main(@builtin(global_invocation_id) id: vec3<u32>) {\n");
    wgsl.push_str("    let index = id.x;\n    if index >= count.x {\n        return;\n    }\n");
    wgsl.push_str(&format!("    let base = index * {stride}u;\n"));
    let mut offset = 0;
    for (position, argument) in case.arguments.iter().enumerate() {
        wgsl.push_str(&format!(
            "    let a{position} = {};\n",
            argument.wgsl(offset)
        ));
        offset += argument.components();
    }
    wgsl.push_str(&format!("    let result = {};\n", case.call));
    match case.output {
        Output::Unsigned => wgsl.push_str("    outputs[index] = result;\n"),
        Output::Floats(1) => wgsl.push_str("    outputs[index] = bitcast<u32>(result);\n"),
        Output::Floats(components) => {
            for component in 0..components {
                wgsl.push_str(&format!("    outputs[index * {components}u + {component}u] = bitcast<u32>(result[{component}]);\n"));
            }
        }
    }
    wgsl.push_str("}\n");
    wgsl
}

/// How far the f32 mirror strays from the f64 reference over the case's grid.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MirrorError {
    /// The largest |mirror - reference|.
    pub max_absolute: f64,
    /// The largest |mirror - reference| over the result's largest component (at least 1e-3:
    /// below that, a product of small inputs would turn f32 rounding into large ratios).
    pub max_relative: f64,
    /// Root mean square of |mirror - reference|.
    pub rms_absolute: f64,
}

/// The mirror's error against the reference over `points`, or None for a case without a
/// reference (integer-exact functions) or an integer result.
pub fn mirror_error(case: &Case, points: &[Vec<u32>]) -> Option<MirrorError> {
    let reference = case.reference?;
    if case.output == Output::Unsigned {
        return None;
    }
    let mut error = MirrorError::default();
    let mut squares = 0.0;
    let mut count = 0usize;
    for point in points {
        // Integer arguments stay integers; float arguments widen exactly.
        let widened: Vec<f64> = widen(case, point);
        let expected = reference(&widened);
        let got = (case.mirror)(point);
        // Relative to the result's largest component: a vector's small components are not
        // held to a tighter standard than its large ones.
        let magnitude = expected
            .iter()
            .fold(1e-3f64, |largest, value| largest.max(value.abs()));
        for (&want, &have) in expected.iter().zip(&got) {
            let have = f64::from(f32::from_bits(have));
            if !want.is_finite() || !have.is_finite() {
                continue;
            }
            let absolute = (have - want).abs();
            error.max_absolute = error.max_absolute.max(absolute);
            error.max_relative = error.max_relative.max(absolute / magnitude);
            squares += absolute * absolute;
            count += 1;
        }
    }
    error.rms_absolute = (squares / count.max(1) as f64).sqrt();
    Some(error)
}

/// A point's arguments as f64: floats widened, unsigned integers converted.
pub fn widen(case: &Case, point: &[u32]) -> Vec<f64> {
    let mut widened = Vec::with_capacity(point.len());
    let mut offset = 0;
    for argument in case.arguments {
        for component in 0..argument.components() {
            let bits = point[offset + component];
            widened.push(match argument {
                Argument::Unsigned { .. } => f64::from(bits),
                _ => f64::from(f32::from_bits(bits)),
            });
        }
        offset += argument.components();
    }
    widened
}

/// Components per result.
pub fn output_components(case: &Case) -> usize {
    match case.output {
        Output::Unsigned => 1,
        Output::Floats(components) => components,
    }
}

/// The distance in ulp between two f32s (0 for equal bits, NaN to NaN, or +0 to -0).
pub fn ulp_distance(a: f32, b: f32) -> u64 {
    if a.is_nan() && b.is_nan() || a == b {
        return 0;
    }
    let ordered = |value: f32| {
        let bits = value.to_bits() as i64;
        if bits < 0x8000_0000 {
            bits
        } else {
            0x8000_0000 - bits
        }
    };
    ordered(a).abs_diff(ordered(b))
}
