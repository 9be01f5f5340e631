//! `#[derive(GBufferLayout)]`, used through its re-export `gbuffer::GBufferLayout`.
//!
//! A derive in three stages, as serde_derive and thiserror do it:
//! 1. `parse`: read the struct and its `#[gbuffer]`, `#[pls]` and `#[bits]` attributes into a
//!    [`gbuffer_core::Layout`], remembering the span of everything a message may point at;
//! 2. check: [`gbuffer_core::Layout::check`] judges the layout (budget, types, names), the same
//!    check `gbuffer codegen` runs on layout files;
//! 3. expand: [`gbuffer_codegen::emit`] writes the WGSL and the Rust mirror.
//!
//! Every problem becomes a `syn::Error` at its span, and all of them are reported together.
//! The derive never panics.
//!
//! [The guide](https://docs.rs/gbuffer#the-guide) shows how the packages fit together.

mod parse;

use proc_macro::TokenStream;

/// Derives `gbuffer::GBufferLayout`: the bit budget check, the WGSL pack/unpack code and a
/// bit-exact Rust mirror of it. See the `gbuffer` crate for the attributes.
#[proc_macro_derive(GBufferLayout, attributes(gbuffer, pls, bits))]
pub fn derive_gbuffer_layout(input: TokenStream) -> TokenStream {
    let input = syn::parse_macro_input!(input as syn::DeriveInput);
    expand(&input)
        .unwrap_or_else(syn::Error::into_compile_error)
        .into()
}

fn expand(input: &syn::DeriveInput) -> syn::Result<proc_macro2::TokenStream> {
    let parsed = parse::parse(input)?;
    let mut errors = parsed.errors;
    for diagnostic in parsed.layout.check() {
        combine(
            &mut errors,
            parsed.spans.error(diagnostic.subject, diagnostic.message),
        );
    }
    if let Some(errors) = errors {
        return Err(errors);
    }
    // Lowered once (its words, its fields' places, its names) for both emitters.
    let lowered = gbuffer_codegen::LoweredLayout::new(&parsed.layout);
    let wgsl = gbuffer_codegen::wgsl::emit_lowered(&lowered, parsed.conversions);
    Ok(gbuffer_codegen::emit::rust::emit_impl(
        &lowered,
        quote::quote!(#wgsl),
        &parsed.crate_path,
    ))
}

/// Adds `error` to the collected errors.
fn combine(errors: &mut Option<syn::Error>, error: syn::Error) {
    match errors {
        Some(errors) => errors.combine(error),
        None => *errors = Some(error),
    }
}
