//! A NaN or infinity in one field (or channel) never changes another field's or channel's
//! bits, and the derived `pack`/`unpack` are the model's conversions exactly.

use gbuffer::glam::{IVec2, IVec4, UVec2, UVec4, Vec2, Vec3, Vec4};
use gbuffer::layout::{Layout, ScalarKind, Storage};
use gbuffer::{seed_layouts, GBufferLayout};
use gbuffer_gpu::harness::{expected_scalars, expected_words, scalars_per_texel};
use gbuffer_gpu::values::Values;
use gbuffer_testkit::AllFormats;

const POISONS: [f32; 4] = [f32::NAN, -f32::NAN, f32::INFINITY, f32::NEG_INFINITY];

/// Builds an `AllFormats` texel from its 33 scalars, in field order.
fn all_formats_from_scalars(s: &[u32]) -> AllFormats {
    let f = |index: usize| f32::from_bits(s[index]);
    let i = |index: usize| s[index] as i32;
    AllFormats {
        small_floats: Vec3::new(f(0), f(1), f(2)),
        single: f(3),
        halves: Vec2::new(f(4), f(5)),
        unorm_10_10_10_2: Vec4::new(f(6), f(7), f(8), f(9)),
        unorm_8: Vec4::new(f(10), f(11), f(12), f(13)),
        unorm_16: Vec2::new(f(14), f(15)),
        sint_8: IVec4::new(i(16), i(17), i(18), i(19)),
        sint_16: IVec2::new(i(20), i(21)),
        uint_10_10_10_2: UVec4::new(s[22], s[23], s[24], s[25]),
        uint_8: UVec4::new(s[26], s[27], s[28], s[29]),
        uint_16: UVec2::new(s[30], s[31]),
        uint_32: s[32],
    }
}

fn random_texel(layout: &Layout, values: &mut Values) -> Vec<u32> {
    layout
        .fields
        .iter()
        .flat_map(|field| std::iter::repeat_n(field.ty.scalar, field.ty.components))
        .map(|kind| values.bits(kind))
        .collect()
}

#[test]
fn derived_pack_and_unpack_are_the_model_conversions() {
    let layout = AllFormats::layout();
    assert_eq!(scalars_per_texel(&layout), 33);
    let mut values = Values::new(7);
    for _ in 0..100_000 {
        let scalars = random_texel(&layout, &mut values);
        let words = all_formats_from_scalars(&scalars).pack();
        assert_eq!(
            words.as_slice(),
            expected_words(&layout, &scalars),
            "{scalars:x?}"
        );
        let back = AllFormats::unpack(&words);
        let expected_back = all_formats_from_scalars(&expected_scalars(&layout, &words));
        // Compare bits, so NaN kept by r32f compares equal to itself.
        assert_eq!(format!("{back:?}"), format!("{expected_back:?}"));
        assert_eq!(back.single.to_bits(), expected_back.single.to_bits());
    }
}

#[test]
fn a_poisoned_channel_changes_no_other_bits() {
    let mut layouts = seed_layouts::all()
        .into_iter()
        .map(|(layout, _)| layout)
        .collect::<Vec<_>>();
    layouts.push(AllFormats::layout());
    let mut values = Values::new(11);
    for layout in &layouts {
        for _ in 0..2_000 {
            let texel = random_texel(layout, &mut values);
            let baseline = expected_words(layout, &texel);
            let mut slot = 0;
            for (field, (field_word, member)) in layout.fields.iter().zip(layout.field_locations())
            {
                for component in 0..field.ty.components {
                    // The bits this component may change: its channel, or its bit field.
                    let allowed_in_word = match field.storage {
                        Storage::Word(format) => {
                            let channel = format.channels()[component];
                            channel.mask() << channel.offset
                        }
                        Storage::Bits(_) => (u32::MAX >> (32 - member.bits)) << member.offset,
                    };
                    if field.ty.scalar == ScalarKind::Float {
                        for poison in POISONS {
                            let mut poisoned = texel.clone();
                            poisoned[slot] = poison.to_bits();
                            let words = expected_words(layout, &poisoned);
                            for (word, (&before, &after)) in baseline.iter().zip(&words).enumerate()
                            {
                                let changed = before ^ after;
                                let allowed = if word == field_word {
                                    allowed_in_word
                                } else {
                                    0
                                };
                                assert_eq!(
                                    changed & !allowed,
                                    0,
                                    "{}: {poison} in {} component {component} changed word {word}",
                                    layout.name,
                                    field.name,
                                );
                            }
                        }
                    }
                    slot += 1;
                }
            }
        }
    }
}

#[test]
fn a_poisoned_field_of_a_derived_layout_leaves_the_other_words_alone() {
    let texel = seed_layouts::MobileMetallic {
        light_accumulation: Vec3::new(0.1, 0.2, 0.3),
        depth: 0.5,
        normals_roughness: Vec4::new(0.25, 0.5, 0.75, 1.0),
        albedo_metallic: Vec4::new(1.0, 0.5, 0.25, 0.0),
    };
    let baseline = texel.pack();
    for poison in POISONS {
        let mut poisoned = texel;
        poisoned.normals_roughness.y = poison;
        let words = poisoned.pack();
        assert_eq!(
            [words[0], words[1], words[3]],
            [baseline[0], baseline[1], baseline[3]]
        );
        assert_eq!(
            words[2] & !0xff00,
            baseline[2] & !0xff00,
            "{poison} leaked out of channel g"
        );
        let mut poisoned = texel;
        poisoned.depth = poison;
        let words = poisoned.pack();
        assert_eq!(
            [words[0], words[2], words[3]],
            [baseline[0], baseline[2], baseline[3]]
        );
        assert_eq!(words[1], poison.to_bits(), "r32f keeps the bits");
    }
}
