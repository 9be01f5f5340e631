//! Bevy's and HDRP's G-buffers, declared with this crate (`gbuffer::engine_layouts`), against
//! encoders and decoders written here from each engine's documented bit layout (Bevy's
//! `pbr_deferred_types.wgsl` and `rgb9e5.wgsl`; HDRP's `Lit.hlsl`, `NormalBuffer.hlsl` and
//! `Packing.hlsl`), in the engines' own f32 arithmetic.
//!
//! Where both sides round the exact value to nearest, the words are equal (a field may differ
//! by one code where the engine's f32 product lands within its rounding of a half). Where an
//! engine's formula differs (Bevy truncates its normal's coordinates; HDRP spreads them over
//! three bytes), each side's decoder reads the other's words within the quantisation bound of
//! the field. The layouts' WGSL and GLSL equal this mirror bit for bit (the seed and engine
//! layouts run through `gpu_packing`, `gles_includes` and `vulkan_includes`).

use gbuffer::engine_layouts::{BevyDeferred, HdrpLit};
use gbuffer::glam::{Vec2, Vec3, Vec4};
use gbuffer::GBufferLayout;
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};

const TEXELS: usize = 200_000;

/// `u32(x)` of a WGSL or HLSL float: truncation, saturating.
fn truncate(value: f32) -> u32 {
    value as u32
}

fn saturate(value: f32) -> f32 {
    value.clamp(0.0, 1.0)
}

/// Cigolle et al.'s octahedral encode in f32, as both engines write it, to [-1, 1].
fn engine_octahedral(normal: Vec3) -> Vec2 {
    let projected = normal / (normal.x.abs() + normal.y.abs() + normal.z.abs());
    if projected.z >= 0.0 {
        return projected.truncate();
    }
    let sign = |value: f32| if value >= 0.0 { 1.0 } else { -1.0 };
    Vec2::new(
        (1.0 - projected.y.abs()) * sign(projected.x),
        (1.0 - projected.x.abs()) * sign(projected.y),
    )
}

/// The engines' octahedral decode (Stubbe's unfolding), from [-1, 1].
fn engine_octahedral_decode(folded: Vec2) -> Vec3 {
    let z = 1.0 - folded.x.abs() - folded.y.abs();
    let fold = (-z).max(0.0);
    let unfold = |value: f32| {
        if value >= 0.0 {
            value - fold
        } else {
            value + fold
        }
    };
    Vec3::new(unfold(folded.x), unfold(folded.y), z).normalize()
}

fn random_unit(rng: &mut SmallRng) -> Vec3 {
    loop {
        let v = Vec3::new(
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
        );
        if (0.01..=1.0).contains(&v.length_squared()) {
            return v.normalize();
        }
    }
}

/// The angle between two vectors in radians, in f64 from their cross and dot products
/// (accurate for small angles, where `acos` of an f32 dot product is not).
fn angle(a: Vec3, b: Vec3) -> f32 {
    let (a, b) = (a.as_dvec3(), b.as_dvec3());
    a.cross(b).length().atan2(a.dot(b)) as f32
}

/// The octahedral bound (see `convert`'s tests): sqrt(18) half-steps of a coordinate, doubled
/// for an encoder that truncates.
fn octahedral_bound(bits: u32, truncating: bool) -> f32 {
    let steps = if truncating { 2.0 } else { 1.0 };
    steps * 18f32.sqrt() / ((1u32 << bits) - 1) as f32 + 1e-5
}

// ---- Bevy ----

/// `pack_unorm4x8_`: `vec4<u32>(saturate(v) * 255.0 + 0.5)`, r in the low byte.
fn bevy_pack_unorm4x8(v: Vec4) -> u32 {
    v.to_array()
        .iter()
        .enumerate()
        .fold(0, |word, (index, &c)| {
            word | (truncate(saturate(c) * 255.0 + 0.5) << (8 * index))
        })
}

fn bevy_unpack_unorm4x8(word: u32) -> Vec4 {
    Vec4::from_array([0, 8, 16, 24].map(|shift| ((word >> shift) & 0xff) as f32 / 255.0))
}

/// `vec3_to_rgb9e5_`: EXT_texture_shared_exponent's algorithm in f32.
fn bevy_rgb9e5(rgb: Vec3) -> u32 {
    let rgb = rgb.clamp(Vec3::ZERO, Vec3::splat(65408.0));
    let largest = rgb.max_element();
    let floor_log2 = ((largest.to_bits() & 0x7f80_0000) >> 23) as i32 - 127;
    let mut exponent = (-16).max(floor_log2) + 16;
    let mut denominator = 2f32.powi(exponent - 24);
    if (largest / denominator + 0.5).floor() as i32 == 512 {
        denominator *= 2.0;
        exponent += 1;
    }
    let n = (rgb / denominator + Vec3::splat(0.5)).floor();
    ((exponent as u32) << 27) | ((n.z as u32) << 18) | ((n.y as u32) << 9) | n.x as u32
}

fn bevy_rgb9e5_decode(word: u32) -> Vec3 {
    let scale = 2f32.powi((word >> 27) as i32 - 24);
    Vec3::new(
        (word & 0x1ff) as f32,
        ((word >> 9) & 0x1ff) as f32,
        ((word >> 18) & 0x1ff) as f32,
    ) * scale
}

/// `pack_unorm3x4_plus_unorm_20_`.
fn bevy_pack_props(v: Vec4) -> u32 {
    let small = |c: f32| truncate(saturate(c) * 15.0 + 0.5);
    let depth = truncate(saturate(v.w) * 1_048_575.0 + 0.5);
    (depth << 12) | (small(v.z) << 8) | (small(v.y) << 4) | small(v.x)
}

fn bevy_unpack_props(word: u32) -> Vec4 {
    Vec4::new(
        (word & 0xf) as f32 / 15.0,
        ((word >> 4) & 0xf) as f32 / 15.0,
        ((word >> 8) & 0xf) as f32 / 15.0,
        ((word >> 12) & 0xfffff) as f32 / 1_048_575.0,
    )
}

/// `octa_encode` then `pack_24bit_nor_and_flags`: coordinates truncated to 12 bits.
fn bevy_pack_normal_and_flags(normal: Vec3, flags: u32) -> u32 {
    let unit = engine_octahedral(normal) * 0.5 + Vec2::splat(0.5);
    let x = truncate(saturate(unit.x) * 4095.0);
    let y = truncate(saturate(unit.y) * 4095.0);
    (x & 0xfff) | ((y & 0xfff) << 12) | ((flags & 0xff) << 24)
}

fn bevy_unpack_normal(word: u32) -> Vec3 {
    let unit = Vec2::new((word & 0xfff) as f32, ((word >> 12) & 0xfff) as f32) / 4095.0;
    engine_octahedral_decode(unit * 2.0 - Vec2::ONE)
}

/// Bevy's `deferred_gbuffer_from_pbr_input`, from the values it stores.
fn bevy_words(texel: &BevyDeferred) -> [u32; 4] {
    [
        bevy_pack_unorm4x8(texel.base_color_roughness),
        bevy_rgb9e5(texel.emissive),
        bevy_pack_props(Vec4::new(
            texel.reflectance,
            texel.metallic,
            texel.occlusion,
            texel.depth,
        )),
        bevy_pack_normal_and_flags(texel.normal, texel.flags),
    ]
}

/// Bevy's `pbr_input_from_deferred_gbuffer`, down to the stored values.
fn bevy_decode(words: &[u32; 4]) -> BevyDeferred {
    let props = bevy_unpack_props(words[2]);
    BevyDeferred {
        base_color_roughness: bevy_unpack_unorm4x8(words[0]),
        emissive: bevy_rgb9e5_decode(words[1]),
        reflectance: props.x,
        metallic: props.y,
        occlusion: props.z,
        depth: props.w,
        normal: bevy_unpack_normal(words[3]),
        flags: words[3] >> 24,
    }
}

fn random_bevy(rng: &mut SmallRng) -> BevyDeferred {
    let mut unit = || rng.random::<f32>();
    let base = Vec4::new(unit(), unit(), unit(), unit());
    let (reflectance, metallic, occlusion, depth) = (unit(), unit(), unit(), unit());
    let scale = 2f32.powi(rng.random_range(-12..16));
    BevyDeferred {
        base_color_roughness: base,
        emissive: Vec3::new(rng.random(), rng.random(), rng.random()) * scale,
        reflectance,
        metallic,
        occlusion,
        depth,
        normal: random_unit(rng),
        flags: rng.random_range(0..256),
    }
}

/// Checks that `decoded` holds `texel` within the bounds of Bevy's fields; `truncating` when
/// the normal went through Bevy's truncating encoder.
fn check_bevy(
    texel: &BevyDeferred,
    decoded: &BevyDeferred,
    truncating: bool,
) -> Result<(), String> {
    let unorm = |bits: u32, a: f32, b: f32, what: &str| {
        let bound = 0.5 / ((1u32 << bits) - 1) as f32 + 1e-6;
        if (a - b).abs() > bound {
            return Err(format!("{what}: {a} decoded as {b} (bound {bound})"));
        }
        Ok(())
    };
    for (a, b) in texel
        .base_color_roughness
        .to_array()
        .iter()
        .zip(decoded.base_color_roughness.to_array())
    {
        unorm(8, *a, b, "base_color_roughness")?;
    }
    unorm(4, texel.reflectance, decoded.reflectance, "reflectance")?;
    unorm(4, texel.metallic, decoded.metallic, "metallic")?;
    unorm(4, texel.occlusion, decoded.occlusion, "occlusion")?;
    unorm(20, texel.depth, decoded.depth, "depth")?;
    let emissive_bound = texel.emissive.max_element() / 256.0 + 1e-7;
    if (texel.emissive - decoded.emissive).abs().max_element() > emissive_bound {
        return Err(format!(
            "emissive: {} decoded as {}",
            texel.emissive, decoded.emissive
        ));
    }
    let normal_error = angle(texel.normal, decoded.normal);
    if normal_error > octahedral_bound(12, truncating) {
        return Err(format!(
            "normal: {} decoded as {} ({normal_error} rad)",
            texel.normal, decoded.normal
        ));
    }
    if texel.flags != decoded.flags {
        return Err(format!(
            "flags: {} decoded as {}",
            texel.flags, decoded.flags
        ));
    }
    Ok(())
}

#[test]
fn bevy_deferred_is_bevys_bit_layout() {
    let layout = BevyDeferred::layout();
    assert_eq!(
        (layout.words(), layout.bits(), layout.used_bits()),
        (4, 128, 128)
    );
    let mut rng = SmallRng::seed_from_u64(21);
    // Words (of 4 per texel) equal to Bevy's, and fields whose codes differ by one.
    let mut equal_words = [0usize; 4];
    let mut failures = Vec::new();
    for _ in 0..TEXELS {
        let texel = random_bevy(&mut rng);
        let ours = texel.pack();
        let bevys = bevy_words(&texel);
        for (word, (a, b)) in ours.iter().zip(&bevys).enumerate() {
            equal_words[word] += usize::from(a == b);
        }
        // The flags byte is an integer: always the same bits.
        assert_eq!(ours[3] >> 24, bevys[3] >> 24);
        // Each side reads the other's words.
        let checks = [
            check_bevy(&texel, &BevyDeferred::unpack(&bevys), true),
            check_bevy(&texel, &bevy_decode(&ours), false),
            check_bevy(&texel, &BevyDeferred::unpack(&ours), false),
        ];
        for (what, check) in ["ours of Bevy's words", "Bevy's of ours", "ours of ours"]
            .iter()
            .zip(checks)
        {
            if let Err(error) = check {
                if failures.len() < 10 {
                    failures.push(format!("{what}: {error}"));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    eprintln!("words equal to Bevy's, of {TEXELS}: {equal_words:?}");
    // rgb9e5 divides by powers of two and rounds exactly in f32: Bevy's formula is exact, and
    // the words agree. The unorm fields round `x * (2^n - 1) + 0.5` in f32, inexact where the
    // product has more bits than f32 keeps (often for the 20-bit depth), and the normal is
    // truncated: there the codes differ by one at most (checked through the decoded values
    // above), and the words mostly agree.
    assert_eq!(equal_words[1], TEXELS, "rgb9e5 words");
    assert!(
        equal_words[0] as f64 >= 0.999 * TEXELS as f64,
        "{equal_words:?}"
    );
}

// ---- HDRP ----

/// `PackFloat2To888`: two 12-bit codes `u32(f * 4095.5)`, their low bytes in r and g and
/// their top nibbles in b (x's low).
fn hdrp_pack_float2_to_888(f: Vec2) -> [u32; 3] {
    let x = truncate(f.x * 4095.5);
    let y = truncate(f.y * 4095.5);
    [x & 255, y & 255, (x >> 8) | ((y >> 8) << 4)]
}

fn hdrp_unpack_888_to_float2(bytes: [u32; 3]) -> Vec2 {
    let x = bytes[0] | ((bytes[2] & 15) << 8);
    let y = bytes[1] | ((bytes[2] >> 4) << 8);
    Vec2::new(x as f32, y as f32) / 4095.0
}

/// A unorm render target's conversion, done by the hardware: the exact value rounded to
/// nearest (D3D's and GL's rule; f64 holds every product exactly).
fn rt_unorm8(value: f32) -> u32 {
    (f64::from(saturate(value)) * 255.0).round() as u32
}

/// An `R11G11B10_FLOAT` render target's conversion of a channel: round to nearest even,
/// denormals kept, clamped to the largest finite value, negatives and NaN to 0 (in f64, the
/// textbook way).
fn rt_small_float(value: f32, mantissa_bits: u32) -> u32 {
    let largest = (2.0 - 2f64.powi(-(mantissa_bits as i32))) * 32768.0;
    let value = f64::from(value);
    if value.is_nan() || value <= 0.0 {
        return 0;
    }
    let max_code = (30 << mantissa_bits) | ((1 << mantissa_bits) - 1);
    if value >= largest {
        return max_code;
    }
    let exponent = value.log2().floor().max(-14.0);
    let quotient = value / (exponent - f64::from(mantissa_bits)).exp2();
    let mut rounded = quotient.round();
    if quotient - quotient.floor() == 0.5 && rounded % 2.0 != 0.0 {
        rounded -= 1.0;
    }
    ((((exponent + 14.0) as u32) << mantissa_bits) + rounded as u32).min(max_code)
}

/// HDRP's `EncodeIntoGBuffer` for the standard material, from the values it stores.
fn hdrp_words(texel: &HdrpLit) -> [u32; 4] {
    let rt = |rgba: [u32; 4]| rgba[0] | (rgba[1] << 8) | (rgba[2] << 16) | (rgba[3] << 24);
    let base = texel
        .base_color_specular_occlusion
        .to_array()
        .map(rt_unorm8);
    let unit = engine_octahedral(texel.normal) * 0.5 + Vec2::splat(0.5);
    let [r, g, b] = hdrp_pack_float2_to_888(unit.clamp(Vec2::ZERO, Vec2::ONE));
    let normal = [r, g, b, rt_unorm8(texel.perceptual_roughness)];
    let coat = truncate(saturate(texel.coat_mask) * 31.0 + 0.5) << 3;
    let fresnel = texel.fresnel0.to_array().map(rt_unorm8);
    let rt2 = [
        fresnel[0],
        fresnel[1],
        fresnel[2],
        coat | texel.material_feature_id,
    ];
    let light = texel.baked_diffuse_lighting;
    let light = rt_small_float(light.x, 6)
        | (rt_small_float(light.y, 6) << 11)
        | (rt_small_float(light.z, 5) << 22);
    [rt(base), rt(normal), rt(rt2), light]
}

/// HDRP's `DecodeFromGBuffer`, down to the stored values.
fn hdrp_decode(words: &[u32; 4]) -> HdrpLit {
    let bytes = |word: u32| [0, 8, 16, 24].map(|shift| (word >> shift) & 0xff);
    let unorm = |code: u32| code as f32 / 255.0;
    let rt1 = bytes(words[1]);
    let folded = hdrp_unpack_888_to_float2([rt1[0], rt1[1], rt1[2]]) * 2.0 - Vec2::ONE;
    let rt2 = bytes(words[2]);
    let light = gbuffer::layout::Format::R11fG11fB10f.decode::<f32>(words[3]);
    HdrpLit {
        base_color_specular_occlusion: Vec4::from_array(bytes(words[0]).map(unorm)),
        normal: engine_octahedral_decode(folded),
        perceptual_roughness: unorm(rt1[3]),
        fresnel0: Vec3::new(unorm(rt2[0]), unorm(rt2[1]), unorm(rt2[2])),
        material_feature_id: rt2[3] & 7,
        coat_mask: (rt2[3] >> 3) as f32 / 31.0,
        baked_diffuse_lighting: Vec3::new(light[0], light[1], light[2]),
    }
}

fn random_hdrp(rng: &mut SmallRng) -> HdrpLit {
    let mut unit = || rng.random::<f32>();
    let base = Vec4::new(unit(), unit(), unit(), unit());
    let (roughness, coat) = (unit(), unit());
    let fresnel = Vec3::new(unit(), unit(), unit());
    // HDRP keeps the normal's z away from 0 (its seam threshold, 1/1024) before encoding.
    let mut normal = random_unit(rng);
    normal.z = normal.z.abs().max(1.0 / 1024.0).copysign(normal.z);
    HdrpLit {
        base_color_specular_occlusion: base,
        normal: normal.normalize(),
        perceptual_roughness: roughness,
        fresnel0: fresnel,
        material_feature_id: rng.random_range(0..8),
        coat_mask: coat,
        baked_diffuse_lighting: Vec3::new(rng.random(), rng.random(), rng.random())
            * 2f32.powi(rng.random_range(-10..15)),
    }
}

fn check_hdrp(texel: &HdrpLit, decoded: &HdrpLit) -> Result<(), String> {
    let unorm = |bits: u32, a: f32, b: f32, what: &str| {
        let bound = 0.5 / ((1u32 << bits) - 1) as f32 + 1e-6;
        if (a - b).abs() > bound {
            return Err(format!("{what}: {a} decoded as {b} (bound {bound})"));
        }
        Ok(())
    };
    let base = texel.base_color_specular_occlusion.to_array();
    for (a, b) in base
        .iter()
        .zip(decoded.base_color_specular_occlusion.to_array())
    {
        unorm(8, *a, b, "base_color_specular_occlusion")?;
    }
    for (a, b) in texel
        .fresnel0
        .to_array()
        .iter()
        .zip(decoded.fresnel0.to_array())
    {
        unorm(8, *a, b, "fresnel0")?;
    }
    unorm(
        8,
        texel.perceptual_roughness,
        decoded.perceptual_roughness,
        "perceptual_roughness",
    )?;
    unorm(5, texel.coat_mask, decoded.coat_mask, "coat_mask")?;
    if texel.material_feature_id != decoded.material_feature_id {
        return Err("material_feature_id".into());
    }
    // HDRP's `u32(f * 4095.5)` is within a code of rounding.
    let normal_error = angle(texel.normal, decoded.normal);
    if normal_error > octahedral_bound(12, true) {
        return Err(format!(
            "normal: {} decoded as {} ({normal_error} rad)",
            texel.normal, decoded.normal
        ));
    }
    let light = texel.baked_diffuse_lighting;
    if (light - decoded.baked_diffuse_lighting).abs().max_element() > light.max_element() / 32.0 {
        return Err(format!(
            "baked_diffuse_lighting: {light} decoded as {}",
            decoded.baked_diffuse_lighting
        ));
    }
    Ok(())
}

#[test]
fn hdrp_lit_is_hdrps_bit_layout_but_for_the_normals_byte_order() {
    let layout = HdrpLit::layout();
    assert_eq!((layout.words(), layout.bits()), (4, 128));
    let mut rng = SmallRng::seed_from_u64(23);
    let mut equal_words = [0usize; 4];
    let mut failures = Vec::new();
    for _ in 0..TEXELS {
        let texel = random_hdrp(&mut rng);
        let ours = texel.pack();
        let hdrps = hdrp_words(&texel);
        for (word, (a, b)) in ours.iter().zip(&hdrps).enumerate() {
            equal_words[word] += usize::from(a == b);
        }
        // The normal's word: roughness in the top byte as HDRP's alpha; the coordinates
        // rearranged from HDRP's bytes are within a code of ours.
        assert_eq!(ours[1] >> 24, hdrps[1] >> 24, "roughness byte");
        let theirs = [
            hdrps[1] & 0xff,
            (hdrps[1] >> 8) & 0xff,
            (hdrps[1] >> 16) & 0xff,
        ];
        let (x, y) = (
            theirs[0] | ((theirs[2] & 15) << 8),
            theirs[1] | ((theirs[2] >> 4) << 8),
        );
        assert!((ours[1] & 0xfff).abs_diff(x) <= 1 && ((ours[1] >> 12) & 0xfff).abs_diff(y) <= 1);
        let checks = [
            check_hdrp(&texel, &HdrpLit::unpack(&ours)),
            check_hdrp(&texel, &hdrp_decode(&hdrps)),
        ];
        for (what, check) in ["ours", "HDRP's"].iter().zip(checks) {
            if let Err(error) = check {
                if failures.len() < 10 {
                    failures.push(format!("{what}: {error}"));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    eprintln!("words equal to HDRP's, of {TEXELS}: {equal_words:?}");
    // The render targets' own conversions (RT0, RT2's colour, RT3) round exactly, as this
    // layout does: those words agree but where HDRP's shader rounds the coat mask in f32.
    assert_eq!(
        (equal_words[0], equal_words[3]),
        (TEXELS, TEXELS),
        "{equal_words:?}"
    );
    assert!(
        equal_words[2] as f64 >= 0.999 * TEXELS as f64,
        "{equal_words:?}"
    );
}
