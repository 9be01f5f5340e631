//! The Rust mirror emitter: the `GBufferLayout` impl that packs and unpacks a layout on the
//! CPU with the bit-exact conversions of [`gbuffer_core::convert`].
//!
//! The derive expands to these tokens, and `gbuffer codegen` prints them as source for crates
//! that do not use the proc-macro. Every path is absolute (`::gbuffer::...`, or the path the
//! user gives with `#[gbuffer(crate = "...")]` for a renamed or re-exported crate;
//! `::core::primitive::f32`) so the code compiles under `#![no_implicit_prelude]` and beside
//! user types named `Format`, `Vec3` or `u32`.

use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{format_ident, quote};

use gbuffer_core::layout::{Field, Storage};
use gbuffer_core::{BitField, Encoding, FieldType, ScalarKind};

use crate::LoweredLayout;

/// The path of the `gbuffer` crate when the user names no other: `::gbuffer`.
pub fn default_crate_path() -> TokenStream {
    quote!(::gbuffer)
}

/// The path of a field type: a primitive, or a glam type through the crate's re-export.
fn type_path(ty: FieldType, krate: &TokenStream) -> TokenStream {
    let name = format_ident!("{}", ty.rust_name());
    if ty.components == 1 {
        quote!(::core::primitive::#name)
    } else {
        quote!(#krate::glam::#name)
    }
}

/// An enum value's variant, as `Format::Rgb10A2` names it: its `Debug` text.
fn variant(value: impl std::fmt::Debug) -> Ident {
    format_ident!("{}", format!("{value:?}"))
}

fn scalar_path(scalar: ScalarKind) -> TokenStream {
    type_path(FieldType::new(scalar, 1), &TokenStream::new())
}

fn scalar_zero(scalar: ScalarKind) -> TokenStream {
    match scalar {
        ScalarKind::Float => quote!(0.0),
        ScalarKind::Uint | ScalarKind::Sint | ScalarKind::Bool => quote!(0),
    }
}

/// `<texel>.<field>`'s components (`texel` is `self`, say), each as an expression of the
/// field's scalar type; zeros past its components, up to four.
fn components(texel: &TokenStream, field: &Field) -> Vec<TokenStream> {
    let field_name = Ident::new(&field.name, Span::call_site());
    let zero = scalar_zero(field.ty.scalar);
    (0..4)
        .map(|index| match (field.ty.components, index) {
            (1, 0) => quote!(#texel.#field_name),
            (components, index) if index < components => {
                let axis = format_ident!("{}", &"xyzw"[index..=index]);
                quote!(#texel.#field_name.#axis)
            }
            _ => zero.clone(),
        })
        .collect()
}

/// `value`, of the field's scalar type, as a codec's lane: an f32's bits, a u32, an i32's two's
/// complement, a bool as 0 or 1.
fn lane_bits(value: TokenStream, scalar: ScalarKind) -> TokenStream {
    match scalar {
        ScalarKind::Float => quote!(#value.to_bits()),
        ScalarKind::Uint => value,
        ScalarKind::Sint => quote!((#value as ::core::primitive::u32)),
        ScalarKind::Bool => quote!(::core::primitive::u32::from(#value)),
    }
}

/// A codec's lane as a value of `scalar`: the inverse of [`lane_bits`].
fn from_lane_bits(lane: TokenStream, scalar: ScalarKind) -> TokenStream {
    match scalar {
        ScalarKind::Float => quote!(::core::primitive::f32::from_bits(#lane)),
        ScalarKind::Uint => lane,
        ScalarKind::Sint => quote!((#lane as ::core::primitive::i32)),
        ScalarKind::Bool => quote!((#lane != 0)),
    }
}

/// `<packing>::BitField { bits: 4, encoding: <packing>::Encoding::Unorm }`.
fn bit_field_tokens(bit_field: BitField, packing: &TokenStream) -> TokenStream {
    let bits = Literal::u32_unsuffixed(bit_field.bits);
    let encoding = match bit_field.encoding {
        Encoding::Rgbm(range) => {
            let range = Literal::f32_suffixed(range.get());
            quote!(#packing::Encoding::Rgbm(#packing::RgbmRange::from_checked(#range)))
        }
        other => {
            let other = variant(other);
            quote!(#packing::Encoding::#other)
        }
    };
    quote!(#packing::BitField { bits: #bits, encoding: #encoding })
}

/// `impl <krate>::GBufferLayout for <Name> { ... }`. The layout must have passed
/// [`Layout::check`](gbuffer_core::Layout::check); `wgsl` is an expression for its WGSL text (a literal, or an
/// `include_str!` of the file beside the generated source); `krate` is the path of the
/// `gbuffer` crate ([`default_crate_path`] unless the user gives another).
pub fn emit_impl(lowered: &LoweredLayout, wgsl: TokenStream, krate: &TokenStream) -> TokenStream {
    let layout = lowered.layout();
    let name = Ident::new(&layout.name, Span::call_site());
    let words = Literal::usize_unsuffixed(lowered.words().len());
    let bits = Literal::u32_unsuffixed(lowered.bits());
    let used_bits = Literal::u32_unsuffixed(layout.used_bits());
    let budget = Literal::u32_unsuffixed(layout.budget);
    let packing = quote!(#krate::layout);

    let encoded_words = lowered.words().iter().map(|word| {
        let codes = word.members.iter().map(|member| {
            let field = &layout.fields[member.field];
            let values = components(&quote!(self), field);
            match field.storage {
                Storage::Word(format) => {
                    let format = variant(format);
                    quote!(#packing::Format::#format.encode([#(#values),*]))
                }
                Storage::Bits(bit_field) => {
                    // The values' lanes as bits; past the field's components, zeros.
                    let lanes = values.iter().enumerate().map(|(index, value)| {
                        if index >= field.ty.components {
                            return quote!(0);
                        }
                        lane_bits(value.clone(), field.ty.scalar)
                    });
                    let bit_field = bit_field_tokens(bit_field, &packing);
                    let components = Literal::usize_unsuffixed(field.ty.components);
                    let offset = Literal::u32_unsuffixed(member.offset);
                    quote!((#bit_field.encode([#(#lanes),*], #components) << #offset))
                }
            }
        });
        quote!(#(#codes)|*)
    });

    // A parameter is a pattern: a user's unit struct or const of the same name would capture
    // it. The reserved-looking name keeps clear of user items, as serde's `__deserializer`.
    let words_parameter = Ident::new("__gbuffer_words", Span::call_site());
    let decoded_fields = layout.fields.iter().zip(lowered.locations()).map(|(field, &(word, member))| {
        let field_name = Ident::new(&field.name, Span::call_site());
        let ty = type_path(field.ty, krate);
        let word = Literal::usize_unsuffixed(word);
        let value = match field.storage {
            Storage::Word(format) => {
                let format = variant(format);
                let scalar = scalar_path(field.ty.scalar);
                let channels =
                    quote!(#packing::Format::#format.decode::<#scalar>(#words_parameter[#word]));
                if field.ty.components == 1 {
                    quote!(#channels[0])
                } else {
                    let components = Literal::usize_unsuffixed(field.ty.components);
                    quote!(#ty::from_slice(&#channels[..#components]))
                }
            }
            Storage::Bits(bit_field) => {
                let bit_field = bit_field_tokens(bit_field, &packing);
                let offset = Literal::u32_unsuffixed(member.offset);
                let mask = Literal::u32_unsuffixed(gbuffer_core::codecs::max_code(member.bits));
                let components = Literal::usize_unsuffixed(field.ty.components);
                let lanes = quote!(#bit_field.decode((#words_parameter[#word] >> #offset) & #mask, #components));
                let scalar = |index: usize| {
                    from_lane_bits(quote!(__gbuffer_lanes[#index]), field.ty.scalar)
                };
                let value = if field.ty.components == 1 {
                    scalar(0)
                } else {
                    let each = (0..field.ty.components).map(scalar);
                    quote!(#ty::new(#(#each),*))
                };
                quote!({
                    let __gbuffer_lanes = #lanes;
                    #value
                })
            }
        };
        quote!(#field_name: #value)
    });

    let (pack_slice, unpack_slice) = emit_slices(lowered, krate);

    let described_fields = layout.fields.iter().map(|field| {
        let field_name = &field.name;
        let storage = match field.storage {
            Storage::Word(format) => {
                let format = variant(format);
                quote!(#packing::Storage::Word(#packing::Format::#format))
            }
            Storage::Bits(bit_field) => {
                let bit_field = bit_field_tokens(bit_field, &packing);
                quote!(#packing::Storage::Bits(#bit_field))
            }
        };
        let scalar = variant(field.ty.scalar);
        let components = Literal::usize_unsuffixed(field.ty.components);
        let conversions = match field.conversions {
            Some(own) => {
                let own = variant(own);
                quote!(::core::option::Option::Some(#packing::Conversions::#own))
            }
            None => quote!(::core::option::Option::None),
        };
        quote!((#field_name, #storage, #packing::FieldType {
            scalar: #packing::ScalarKind::#scalar,
            components: #components,
        }, #conversions))
    });
    let layout_name = &layout.name;

    quote! {
        impl #krate::GBufferLayout for #name {
            const BITS: ::core::primitive::u32 = #bits;
            const USED_BITS: ::core::primitive::u32 = #used_bits;
            const BUDGET: ::core::primitive::u32 = #budget;
            const WORDS: ::core::primitive::usize = #words;
            type Packed = [::core::primitive::u32; #words];
            const WGSL: &'static ::core::primitive::str = #wgsl;

            #[inline]
            fn pack(&self) -> [::core::primitive::u32; #words] {
                [#(#encoded_words),*]
            }

            #[inline]
            fn unpack(#words_parameter: &[::core::primitive::u32; #words]) -> Self {
                Self { #(#decoded_fields),* }
            }

            #pack_slice

            #unpack_slice

            fn layout() -> #packing::Layout {
                #packing::Layout::from_parts(#layout_name, #budget, &[#(#described_fields),*])
            }
        }
    }
}

/// The row column of component `component` of the field at `place` of a row columns constant
/// (`__GBUFFER_COLUMNS[place] + component`; the first component without the `+ 0`, which
/// Clippy calls an identity operation in the user's crate).
fn column_in(columns: &Ident, place: usize, component: usize) -> TokenStream {
    let place = Literal::usize_unsuffixed(place);
    if component == 0 {
        return quote!(#columns[#place]);
    }
    let component = Literal::usize_unsuffixed(component);
    quote!(#columns[#place] + #component)
}

/// The most columns of a texel's row `pack_slice` builds at once (see `emit_slices`).
const ROW_GROUP: usize = 12;

/// `pack_slice` and `unpack_slice`, `N` texels at a time (the loop's copy for the CPU picks
/// `N`: sixteen with AVX-512, eight elsewhere). Packing, the texels' components become rows of
/// lane bits (one row per texel through a `Row` impl per group of whole fields, the fields in
/// the order the texel's memory holds them) and are turned into one array of `N` lanes per
/// component (`Isa::lanes`); each word's channels (or bit fields) are converted over the lanes
/// at once (`Isa::encode`, which ORs in `Channel::encode_lanes`'s codes unless the CPU has an
/// exact form of its own, and `BitField::encode_lanes`, with each channel and bit field a
/// constant), the same conversions as `pack` lane by lane, which the compiler turns into vector
/// instructions; the words' lanes are turned back into each texel's words (`Isa::rows`).
/// Unpacking runs the same steps backwards. The texels left over go through `pack` and
/// `unpack`. The rows and the conversions are static functions of `Row` and `Lanes` impls, not
/// closures, so that they inline into the loop's copies compiled for AVX2 and AVX-512, whose
/// `Isa` they are passed.
fn emit_slices(lowered: &LoweredLayout, krate: &TokenStream) -> (TokenStream, TokenStream) {
    let layout = lowered.layout();
    let name = Ident::new(&layout.name, Span::call_site());
    let packing = quote!(#krate::layout);
    let private = quote!(#krate::__private);
    let lanes_n = Ident::new("N", Span::call_site());
    let words = Literal::usize_unsuffixed(lowered.words().len());
    let u32_ = quote!(::core::primitive::u32);
    let texels = Ident::new("__gbuffer_texels", Span::call_site());
    let index = Ident::new("__gbuffer_index", Span::call_site());
    let lanes = Ident::new("__gbuffer_lanes", Span::call_site());
    let rows = Ident::new("__gbuffer_rows", Span::call_site());
    let word_name = |word: usize| format_ident!("__gbuffer_word{}", word);
    let field_name = |field: usize| format_ident!("__gbuffer_field{}", field);
    // The fields in groups of at most `ROW_GROUP` components, in their order, a field never
    // split: packing reads each group's rows through its own `Row` impl (`__GbufferRow<g>`)
    // and turns them into its own lanes (`__gbuffer_lanes<g>`). The AVX2 copy's transposes
    // keep a dozen columns in registers; with the eight-format layout's 24 components in one
    // row they spilled, and its pack took twice as long (6.4 and 13 ns a texel in cache, on a
    // Zen 4 EPYC). Unpacking turns all its lanes into rows at once.
    let mut groups: Vec<Vec<usize>> = Vec::new();
    let mut filled = ROW_GROUP;
    for (number, field) in layout.fields.iter().enumerate() {
        if filled + field.ty.components > ROW_GROUP {
            groups.push(Vec::new());
            filled = 0;
        }
        filled += field.ty.components;
        groups.last_mut().expect("a group").push(number);
    }
    let group_of = |number: usize| {
        let group = groups
            .iter()
            .position(|members| members.contains(&number))
            .expect("every field in a group");
        let place = groups[group].iter().position(|&member| member == number);
        (group, place.expect("in its group"))
    };
    // Each field's first row column in its group (`__GBUFFER_COLUMNS<g>[place]`), or in the
    // whole row (`__GBUFFER_COLUMNS[field]`): the fields in the order the texel's memory holds
    // them, so that a row's runs of columns are runs of the texel's bytes and the loops' loads
    // and stores move them whole.
    let columns_const = |ident: Ident, members: &[usize]| {
        let offsets = members.iter().map(|&number| {
            let field = Ident::new(&layout.fields[number].name, Span::call_site());
            quote!(::core::mem::offset_of!(#name, #field))
        });
        let components_of = members
            .iter()
            .map(|&number| Literal::usize_unsuffixed(layout.fields[number].ty.components));
        let count = Literal::usize_unsuffixed(members.len());
        quote! {
            const #ident: [::core::primitive::usize; #count] =
                #private::row_columns([#(#offsets),*], [#(#components_of),*]);
        }
    };
    let every_field: Vec<usize> = (0..layout.fields.len()).collect();
    let row_columns = columns_const(format_ident!("__GBUFFER_COLUMNS"), &every_field);
    let group_columns = groups.iter().enumerate().map(|(group, members)| {
        columns_const(format_ident!("__GBUFFER_COLUMNS{}", group), members)
    });
    let group_columns = quote!(#(#group_columns)*);
    let column_of = |number: usize, component: usize| {
        column_in(&format_ident!("__GBUFFER_COLUMNS"), number, component)
    };
    // Component `component` of field `number` as a packing loop's lanes hold it, in its group.
    let group_lane = |number: usize, component: usize| {
        let (group, place) = group_of(number);
        let (lanes, columns) = (
            format_ident!("__gbuffer_lanes{}", group),
            format_ident!("__GBUFFER_COLUMNS{}", group),
        );
        let column = column_in(&columns, place, component);
        quote!(#lanes[#column])
    };
    let columns =
        Literal::usize_unsuffixed(layout.fields.iter().map(|field| field.ty.components).sum());
    // Component `component` of field `number` over the lanes, as the field's scalar
    // (`as_bits`: as a codec's lane, u32 bits); zeros past its components.
    let lane = |number: usize, component: usize, as_bits: bool| {
        let field = &layout.fields[number];
        if component >= field.ty.components {
            let zero = if as_bits {
                quote!(0)
            } else {
                scalar_zero(field.ty.scalar)
            };
            return quote!([#zero; #lanes_n]);
        }
        let lanes = group_lane(number, component);
        if as_bits {
            return lanes;
        }
        let zero = scalar_zero(field.ty.scalar);
        let value = from_lane_bits(quote!(#lanes[#index]), field.ty.scalar);
        quote!({
            let mut __gbuffer_values = [#zero; #lanes_n];
            for #index in 0..#lanes_n {
                __gbuffer_values[#index] = #value;
            }
            __gbuffer_values
        })
    };

    let texel_rows = groups.iter().enumerate().map(|(group, members)| {
        let width: usize = members
            .iter()
            .map(|&number| layout.fields[number].ty.components)
            .sum();
        let width = Literal::usize_unsuffixed(width);
        let texel = Ident::new("__gbuffer_texel", Span::call_site());
        let columns = format_ident!("__GBUFFER_COLUMNS{}", group);
        let sets = members.iter().enumerate().flat_map(|(place, &number)| {
            let field = &layout.fields[number];
            let columns = &columns;
            components(&quote!(#texel), field)
                .into_iter()
                .take(field.ty.components)
                .enumerate()
                .map(move |(component, value)| {
                    let column = column_in(columns, place, component);
                    let bits = lane_bits(value, field.ty.scalar);
                    quote!(__gbuffer_row[#column] = #bits;)
                })
        });
        let row = format_ident!("__GbufferRow{}", group);
        let group_lanes = format_ident!("__gbuffer_lanes{}", group);
        let row_impl = quote! {
            struct #row;
            impl #private::Row<#name, #width> for #row {
                #[inline(always)]
                fn row(#texel: &#name) -> [#u32_; #width] {
                    let mut __gbuffer_row = [0; #width];
                    #(#sets)*
                    __gbuffer_row
                }
            }
        };
        // `{ N }`: bare, a user's type named `N` beside the derive would be taken for the
        // argument (the hygiene test has one); braced, it is the loop's const parameter.
        let lanes = quote! {
            let #group_lanes: [[#u32_; #lanes_n]; #width] = I::lanes::<_, #row, { #lanes_n }, #width>(#texels);
        };
        (row_impl, lanes)
    });
    let (row_impls, texel_rows): (Vec<_>, Vec<_>) = texel_rows.unzip();
    let packed_words = lowered.words().iter().enumerate().map(|(word, contents)| {
        let word_ident = word_name(word);
        let members = contents.members.iter().map(|member| {
            let field = &layout.fields[member.field];
            match field.storage {
                Storage::Word(format) => {
                    let scalar = scalar_path(field.ty.scalar);
                    let channels = (0..format.channels().len()).map(|channel| {
                        let values = lane(member.field, channel, false);
                        let format = variant(format);
                        quote! {{
                            const __GBUFFER_CHANNEL: #packing::Channel = #packing::Format::#format.channels()[#channel];
                            I::encode::<#scalar, _>(__GBUFFER_CHANNEL, #values, &mut #word_ident);
                        }}
                    });
                    quote!(#(#channels)*)
                }
                Storage::Bits(bit_field) => {
                    let bit_field = bit_field_tokens(bit_field, &packing);
                    let components = Literal::usize_unsuffixed(field.ty.components);
                    let offset = Literal::u32_unsuffixed(member.offset);
                    let values = (0..4).map(|component| lane(member.field, component, true));
                    quote! {{
                        const __GBUFFER_FIELD: #packing::BitField = #bit_field;
                        let __gbuffer_codes = __GBUFFER_FIELD.encode_lanes([#(#values),*], #components);
                        for #index in 0..#lanes_n {
                            #word_ident[#index] |= __gbuffer_codes[#index] << #offset;
                        }
                    }}
                }
            }
        });
        quote! {
            let mut #word_ident: [#u32_; #lanes_n] = [0; #lanes_n];
            #(#members)*
        }
    });
    let word_idents: Vec<Ident> = (0..lowered.words().len()).map(word_name).collect();
    let pack_slice = quote! {
        fn pack_slice(#texels: &[Self], __gbuffer_packed: &mut [[#u32_; #words]]) {
            #group_columns
            #(#row_impls)*
            struct __GbufferPack;
            impl #private::Lanes<#name, [#u32_; #words]> for __GbufferPack {
                #[inline(always)]
                fn many<I: #private::Isa, const #lanes_n: ::core::primitive::usize>(#texels: &[#name; #lanes_n], __gbuffer_packed: &mut [[#u32_; #words]; #lanes_n]) {
                    #(#texel_rows)*
                    #(#packed_words)*
                    *__gbuffer_packed = I::rows(&[#(#word_idents),*]);
                }
                #[inline(always)]
                fn one(__gbuffer_texel: &#name) -> [#u32_; #words] {
                    #krate::GBufferLayout::pack(__gbuffer_texel)
                }
            }
            #private::check_slice_lengths("pack_slice", #texels.len(), __gbuffer_packed.len());
            #private::convert_lanes::<__GbufferPack, _, _>(#texels, __gbuffer_packed);
        }
    };

    let words_parameter = Ident::new("__gbuffer_words", Span::call_site());
    // Per field, its components over the lanes, `__gbuffer_field<n>[c][lane]`: a format's
    // channel values (its components only), or a bit field's codec lanes as u32 bits (four).
    let decoded = layout.fields.iter().zip(lowered.locations()).enumerate().map(|(number, (field, &(word, member)))| {
        let field_ident = field_name(number);
        let word = Literal::usize_unsuffixed(word);
        let word_lanes = quote!(__gbuffer_word_lanes[#word]);
        match field.storage {
            Storage::Word(format) => {
                let scalar = scalar_path(field.ty.scalar);
                let format = variant(format);
                let components = Literal::usize_unsuffixed(field.ty.components);
                let channels = (0..field.ty.components).map(|channel| {
                    quote! {{
                        const __GBUFFER_CHANNEL: #packing::Channel = #packing::Format::#format.channels()[#channel];
                        I::decode::<#scalar, _>(__GBUFFER_CHANNEL, #word_lanes)
                    }}
                });
                quote!(let #field_ident: [[#scalar; #lanes_n]; #components] = [#(#channels),*];)
            }
            Storage::Bits(bit_field) => {
                let bit_field = bit_field_tokens(bit_field, &packing);
                let offset = Literal::u32_unsuffixed(member.offset);
                let mask = Literal::u32_unsuffixed(gbuffer_core::codecs::max_code(member.bits));
                let components = Literal::usize_unsuffixed(field.ty.components);
                quote! {
                    let #field_ident: [[#u32_; #lanes_n]; 4] = {
                        let mut __gbuffer_codes: [#u32_; #lanes_n] = #word_lanes;
                        for #index in 0..#lanes_n {
                            __gbuffer_codes[#index] = (__gbuffer_codes[#index] >> #offset) & #mask;
                        }
                        const __GBUFFER_FIELD: #packing::BitField = #bit_field;
                        __GBUFFER_FIELD.decode_lanes(__gbuffer_codes, #components)
                    };
                }
            }
        }
    });
    // The decoded components as lanes of u32 bits, in the rows' order.
    let decoded_lanes = layout
        .fields
        .iter()
        .enumerate()
        .flat_map(|(number, field)| {
            let field_lanes = field_name(number);
            let (index, lanes_n, lanes, column_of) = (&index, &lanes_n, &lanes, &column_of);
            (0..field.ty.components).map(move |component| {
                let column = column_of(number, component);
                let component = Literal::usize_unsuffixed(component);
                let value = match field.storage {
                    Storage::Bits(_) => quote!(#field_lanes[#component]),
                    Storage::Word(_) => {
                        let bits =
                            lane_bits(quote!(#field_lanes[#component][#index]), field.ty.scalar);
                        quote!({
                            let mut __gbuffer_bits = [0; #lanes_n];
                            for #index in 0..#lanes_n {
                                __gbuffer_bits[#index] = #bits;
                            }
                            __gbuffer_bits
                        })
                    }
                };
                quote!(#lanes[#column] = #value;)
            })
        });
    let built_fields: Vec<TokenStream> = layout
        .fields
        .iter()
        .enumerate()
        .map(|(number, field)| {
            let field_ident = Ident::new(&field.name, Span::call_site());
            let component = |component: usize| {
                let column = column_of(number, component);
                from_lane_bits(quote!(#rows[#index][#column]), field.ty.scalar)
            };
            let value = if field.ty.components == 1 {
                component(0)
            } else {
                let ty = type_path(field.ty, krate);
                let each = (0..field.ty.components).map(component);
                quote!(#ty::new(#(#each),*))
            };
            quote!(#field_ident: #value)
        })
        .collect();
    let unpack_slice = quote! {
        fn unpack_slice(__gbuffer_packed: &[[#u32_; #words]], #texels: &mut [Self]) {
            #row_columns
            struct __GbufferUnpack;
            impl #private::Lanes<[#u32_; #words], #name> for __GbufferUnpack {
                #[inline(always)]
                fn many<I: #private::Isa, const #lanes_n: ::core::primitive::usize>(#words_parameter: &[[#u32_; #words]; #lanes_n], #texels: &mut [#name; #lanes_n]) {
                    let __gbuffer_word_lanes: [[#u32_; #lanes_n]; #words] = I::lanes::<_, #private::Words, { #lanes_n }, #words>(#words_parameter);
                    #(#decoded)*
                    let mut #lanes: [[#u32_; #lanes_n]; #columns] = [[0; #lanes_n]; #columns];
                    #(#decoded_lanes)*
                    let #rows: [[#u32_; #columns]; #lanes_n] = I::rows(&#lanes);
                    // Each texel whole: the layout need not be `Default`.
                    for #index in 0..#lanes_n {
                        #texels[#index] = #name { #(#built_fields),* };
                    }
                }
                #[inline(always)]
                fn one(__gbuffer_one: &[#u32_; #words]) -> #name {
                    <#name as #krate::GBufferLayout>::unpack(__gbuffer_one)
                }
            }
            #private::check_slice_lengths("unpack_slice", #texels.len(), __gbuffer_packed.len());
            #private::convert_lanes::<__GbufferUnpack, _, _>(__gbuffer_packed, #texels);
        }
    };
    (pack_slice, unpack_slice)
}

/// The layout as a struct that derives it: `#[derive(GBufferLayout)]` with `#[gbuffer(...)]`
/// and a `#[pls(...)]` or `#[bits(...)]` attribute per field, public fields of `gbuffer`'s
/// glam types. What the derive reads back as the same layout and WGSL.
#[cfg(feature = "tools")]
pub fn derive_source(
    layout: &gbuffer_core::Layout,
    conversions: gbuffer_core::layout::Conversions,
) -> String {
    use gbuffer_core::layout::Conversions;
    use gbuffer_core::Named;

    let mut options = format!("budget = {}", layout.budget);
    if conversions == Conversions::Fast {
        options.push_str(", conversions = fast");
    }
    let glam: std::collections::BTreeSet<&str> = layout
        .fields
        .iter()
        .filter(|field| field.ty.components > 1)
        .map(|field| field.ty.rust_name())
        .collect();
    let mut out = String::new();
    if !glam.is_empty() {
        let names: Vec<&str> = glam.into_iter().collect();
        out.push_str(&format!("use gbuffer::glam::{{{}}};\n", names.join(", ")));
    }
    out.push_str("use gbuffer::GBufferLayout;\n\n");
    out.push_str(&format!(
        "#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]\n#[gbuffer({options})]\npub struct {} {{\n",
        layout.name
    ));
    for field in &layout.fields {
        let own = field
            .conversions
            .map(|own| format!(", conversions = {}", own.name()))
            .unwrap_or_default();
        let attribute = match field.storage {
            Storage::Word(format) => format!("#[pls({format}{own})]"),
            Storage::Bits(bit_field) => {
                let encoding = match bit_field.encoding {
                    Encoding::Rgbm(range) => format!("rgbm({:?})", range.get()),
                    other => other.name().to_string(),
                };
                format!("#[bits({}, {encoding}{own})]", bit_field.bits)
            }
        };
        out.push_str(&format!(
            "    {attribute}\n    pub {}: {},\n",
            field.name,
            field.ty.rust_name()
        ));
    }
    out.push_str("}\n");
    out
}

/// A Rust source file for crates that do not use the derive: the struct, with public fields
/// of `gbuffer`'s glam types, and its `GBufferLayout` impl, whose WGSL is included from the
/// file `gbuffer codegen` writes beside it ([`gbuffer_core::Symbols::wgsl_file`]).
#[cfg(feature = "tools")]
pub fn emit_source(compiled: &crate::CompiledLayout) -> String {
    let (lowered, layout) = (compiled.lowered(), compiled.layout());
    let wgsl_file = lowered.symbols().wgsl_file();
    let krate = default_crate_path();
    let name = Ident::new(&layout.name, Span::call_site());
    let fields = layout.fields.iter().map(|field| {
        let field_name = Ident::new(&field.name, Span::call_site());
        let ty = type_path(field.ty, &krate);
        let doc = match field.storage {
            Storage::Word(format) => format!(" `{}`: a word of format `{format}`.", field.name),
            Storage::Bits(bit_field) => format!(" `{}`: a {bit_field} bit field.", field.name),
        };
        quote!(#[doc = #doc] pub #field_name: #ty)
    });
    let header = format!(
        " G-buffer layout `{}`: {} words, {} bits ({} used) of a {}-bit budget. Generated by `gbuffer codegen` from the layout file: edit that, not this file.",
        layout.name,
        lowered.words().len(),
        lowered.bits(),
        layout.used_bits(),
        layout.budget
    );
    let implementation = emit_impl(lowered, quote!(include_str!(#wgsl_file)), &krate);
    let tokens = quote! {
        #[doc = #header]
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct #name { #(#fields),* }

        #implementation
    };
    let file: syn::File = syn::parse2(tokens).expect("the emitted tokens are a valid Rust file");
    prettyplease::unparse(&file)
}
