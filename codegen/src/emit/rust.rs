//! The Rust mirror emitter: the `GBufferLayout` impl that packs and unpacks a layout on the
//! CPU with the bit-exact conversions of [`crate::convert`].
//!
//! The derive expands to these tokens, and the `codegen` tool prints them as source for crates
//! that do not use the proc-macro. Every path is absolute (`::shaderlib::...`,
//! `::core::primitive::f32`) so the code compiles under `#![no_implicit_prelude]` and beside
//! user types named `Format`, `Vec3` or `u32`.

use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::{format_ident, quote};

use crate::format::ScalarKind;
use crate::layout::{FieldType, Layout};

/// The path of a field type through `shaderlib`'s re-exports.
fn type_path(ty: FieldType) -> TokenStream {
    let name = format_ident!("{}", ty.rust_name());
    if ty.components == 1 {
        quote!(::core::primitive::#name)
    } else {
        quote!(::shaderlib::glam::#name)
    }
}

fn scalar_path(scalar: ScalarKind) -> TokenStream {
    type_path(FieldType::new(scalar, 1))
}

fn scalar_zero(scalar: ScalarKind) -> TokenStream {
    match scalar {
        ScalarKind::Float => quote!(0.0),
        ScalarKind::Uint | ScalarKind::Sint => quote!(0),
    }
}

/// `impl ::shaderlib::GBufferLayout for <Name> { ... }`. The layout must have passed
/// [`Layout::check`]; `wgsl` is its WGSL, embedded as `WGSL`.
pub fn emit_impl(layout: &Layout, wgsl: &str) -> TokenStream {
    let name = Ident::new(&layout.name, Span::call_site());
    let words = layout.words();
    let bits = layout.bits();
    let used_bits = layout.used_bits();
    let budget = layout.budget;
    let packing = quote!(::shaderlib::packing);

    let encoded_words = layout.fields.iter().map(|field| {
        let field_name = Ident::new(&field.name, Span::call_site());
        let format = format_ident!("{}", field.format.variant_name());
        let scalar = scalar_path(field.ty.scalar);
        let zero = scalar_zero(field.ty.scalar);
        let values: Vec<TokenStream> = (0..4)
            .map(|index| match (field.ty.components, index) {
                (1, 0) => quote!(self.#field_name),
                (components, index) if index < components => {
                    let axis = format_ident!("{}", &"xyzw"[index..=index]);
                    quote!(self.#field_name.#axis)
                }
                _ => zero.clone(),
            })
            .collect();
        quote!(#packing::Format::#format.encode::<#scalar>([#(#values),*]))
    });

    // A parameter is a pattern: a user's unit struct or const of the same name would capture
    // it. The reserved-looking name keeps clear of user items, as serde's `__deserializer`.
    let words_parameter = Ident::new("__gbuffer_words", Span::call_site());
    let decoded_fields = layout.fields.iter().enumerate().map(|(word, field)| {
        let field_name = Ident::new(&field.name, Span::call_site());
        let format = format_ident!("{}", field.format.variant_name());
        let scalar = scalar_path(field.ty.scalar);
        let ty = type_path(field.ty);
        let word = Literal::usize_unsuffixed(word);
        let channels = quote!(#packing::Format::#format.decode::<#scalar>(#words_parameter[#word]));
        let value = if field.ty.components == 1 {
            quote!(#channels[0])
        } else {
            let components = Literal::usize_unsuffixed(field.ty.components);
            quote!(#ty::from_slice(&#channels[..#components]))
        };
        quote!(#field_name: #value)
    });

    let described_fields = layout.fields.iter().map(|field| {
        let field_name = &field.name;
        let format = format_ident!("{}", field.format.variant_name());
        let scalar = format_ident!("{}", format!("{:?}", field.ty.scalar));
        let components = Literal::usize_unsuffixed(field.ty.components);
        quote!((#field_name, #packing::Format::#format, #packing::FieldType {
            scalar: #packing::ScalarKind::#scalar,
            components: #components,
        }))
    });
    let layout_name = &layout.name;

    quote! {
        impl ::shaderlib::GBufferLayout for #name {
            const BITS: ::core::primitive::u32 = #bits;
            const USED_BITS: ::core::primitive::u32 = #used_bits;
            const BUDGET: ::core::primitive::u32 = #budget;
            const WORDS: ::core::primitive::usize = #words;
            type Packed = [::core::primitive::u32; #words];
            const WGSL: &'static ::core::primitive::str = #wgsl;

            fn pack(&self) -> [::core::primitive::u32; #words] {
                [#(#encoded_words),*]
            }

            fn unpack(#words_parameter: &[::core::primitive::u32; #words]) -> Self {
                Self { #(#decoded_fields),* }
            }

            fn layout() -> #packing::Layout {
                #packing::Layout::from_parts(#layout_name, #budget, &[#(#described_fields),*])
            }
        }
    }
}
