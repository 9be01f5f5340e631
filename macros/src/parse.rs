//! Stage 1 of the derive: the struct and its attributes to a [`Layout`], with the span of each
//! part so that the check's diagnostics can point at it.

use gbuffer_core::Conversions;
use gbuffer_core::Named;
use gbuffer_core::{
    BitField, Encoding, Field, FieldType, Format, Layout, ScalarKind, Storage, Subject,
    DEFAULT_BUDGET,
};
use proc_macro2::{Span, TokenStream};
use quote::ToTokens;
use syn::spanned::Spanned;
use syn::{Data, DeriveInput, Fields};

use crate::combine;

/// The spans the check's [`Subject`]s refer to.
pub struct Spans {
    name: Span,
    budget: Option<Span>,
    /// Per field of the layout: its name, its format and its type.
    fields: Vec<[Span; 3]>,
    /// Per field, its `#[bits(...)]` attribute where it has one: a bit field's errors
    /// underline the whole attribute.
    bits_attributes: Vec<Option<TokenStream>>,
}

impl Spans {
    /// The error `message` at what `subject` names.
    pub fn error(&self, subject: Subject, message: String) -> syn::Error {
        let span = match subject {
            Subject::Name => self.name,
            Subject::Budget => self.budget.unwrap_or(self.name),
            Subject::FieldName(index) => self.fields[index][0],
            Subject::FieldFormat(index) => match &self.bits_attributes[index] {
                Some(attribute) => return syn::Error::new_spanned(attribute, message),
                None => self.fields[index][1],
            },
            Subject::FieldType(index) => self.fields[index][2],
        };
        syn::Error::new(span, message)
    }
}

/// What parsing produced: the layout, the spans, and the errors found on the way. A field
/// whose format or type is in error stands in the layout as an `r32f` `f32`, so that the
/// budget check still counts its word.
pub struct Parsed {
    pub layout: Layout,
    pub conversions: Conversions,
    /// The path of the `gbuffer` crate, as `#[gbuffer(crate = "...")]` gives it.
    pub crate_path: TokenStream,
    pub spans: Spans,
    pub errors: Option<syn::Error>,
}

/// Reads the input. Returns `Err` only when there is no struct to read at all.
pub fn parse(input: &DeriveInput) -> syn::Result<Parsed> {
    let named_fields =
        match &input.data {
            Data::Struct(data) => match &data.fields {
                Fields::Named(fields) => fields.named.iter().collect::<Vec<_>>(),
                Fields::Unnamed(fields) => return Err(syn::Error::new(
                    fields.span(),
                    "a G-buffer layout needs named fields: they name the WGSL struct's members \
                     and functions",
                )),
                Fields::Unit => Vec::new(),
            },
            Data::Enum(data) => return Err(syn::Error::new(
                data.enum_token.span,
                "`GBufferLayout` can only be derived for a struct with named fields, not an enum",
            )),
            Data::Union(data) => return Err(syn::Error::new(
                data.union_token.span,
                "`GBufferLayout` can only be derived for a struct with named fields, not a union",
            )),
        };

    let mut errors = None;
    if !input.generics.params.is_empty() || input.generics.where_clause.is_some() {
        combine(
            &mut errors,
            syn::Error::new(
                input.generics.span(),
                "a G-buffer layout cannot be generic: its WGSL struct needs concrete field types",
            ),
        );
    }

    let options = parse_gbuffer_attributes(input, &mut errors);
    let mut layout = Layout {
        name: input.ident.to_string(),
        budget: options.budget,
        fields: Vec::new(),
    };
    let mut spans = Spans {
        name: input.ident.span(),
        budget: options.budget_span,
        fields: Vec::new(),
        bits_attributes: Vec::new(),
    };

    for field in named_fields {
        let Some(ident) = &field.ident else { continue };
        let name = ident.to_string().trim_start_matches("r#").to_string();
        let storage = parse_storage_attribute(field, &name, &mut errors);
        let ty = parse_field_type(&field.ty, &mut errors);
        let bits_attribute = field
            .attrs
            .iter()
            .find(|attribute| attribute.path().is_ident("bits"))
            .map(ToTokens::to_token_stream);
        let (storage, storage_span, conversions, ty) = match (storage, ty) {
            (Some((storage, storage_span, conversions)), Some(ty)) => {
                (storage, storage_span, conversions, ty)
            }
            // The error is reported; a stand-in keeps the field's word in the budget check.
            _ => (
                Storage::Word(Format::R32f),
                ident.span(),
                None,
                FieldType::new(ScalarKind::Float, 1),
            ),
        };
        layout.fields.push(Field {
            name,
            storage,
            ty,
            conversions,
        });
        spans
            .fields
            .push([ident.span(), storage_span, field.ty.span()]);
        spans.bits_attributes.push(bits_attribute);
    }
    Ok(Parsed {
        layout,
        conversions: options.conversions,
        crate_path: options.crate_path,
        spans,
        errors,
    })
}

/// The options of `#[gbuffer(...)]`.
pub struct Options {
    pub budget: u32,
    /// The span of the budget's value, where one is given.
    pub budget_span: Option<Span>,
    pub conversions: Conversions,
    /// The path of the `gbuffer` crate in the generated code: `::gbuffer` unless
    /// `crate = "..."` names another (a renamed dependency, a re-export).
    pub crate_path: TokenStream,
}

/// `#[gbuffer(budget = 128, conversions = exact, crate = "::gbuffer")]`, each optional.
fn parse_gbuffer_attributes(input: &DeriveInput, errors: &mut Option<syn::Error>) -> Options {
    let mut options = Options {
        budget: DEFAULT_BUDGET,
        budget_span: None,
        conversions: Conversions::Exact,
        crate_path: gbuffer_codegen::emit::rust::default_crate_path(),
    };
    let mut seen = (false, false, false, false); // the attribute, budget, conversions, crate
    for attribute in input
        .attrs
        .iter()
        .filter(|attribute| attribute.path().is_ident("gbuffer"))
    {
        if seen.0 {
            combine(
                errors,
                syn::Error::new_spanned(
                    attribute,
                    "`#[gbuffer]` is given twice: merge its options into one attribute",
                ),
            );
            continue;
        }
        seen.0 = true;
        let result = attribute.parse_nested_meta(|meta| {
            if meta.path.is_ident("budget") {
                let expression: syn::Expr = meta.value()?.parse()?;
                let value = budget_value(&expression).ok_or_else(|| {
                    syn::Error::new_spanned(&expression, "budget must be a positive multiple of 32 bits, written as a number, e.g. `budget = 128`")
                })?;
                if std::mem::replace(&mut seen.1, true) {
                    return Err(syn::Error::new_spanned(&expression, "`budget` is given twice"));
                }
                options.budget = value;
                options.budget_span = Some(expression.span());
                Ok(())
            } else if meta.path.is_ident("conversions") {
                let value: syn::Expr = meta.value()?.parse()?;
                options.conversions = conversions_value(&value)?;
                if std::mem::replace(&mut seen.2, true) {
                    return Err(syn::Error::new_spanned(&value, "`conversions` is given twice"));
                }
                Ok(())
            } else if meta.path.is_ident("crate") {
                let literal: syn::LitStr = meta.value()?.parse()?;
                let path: syn::Path = literal.parse().map_err(|_| {
                    syn::Error::new_spanned(&literal, format!("`crate` must be a path, e.g. `crate = \"::gbuffer\"`; `{}` is not one", literal.value()))
                })?;
                if std::mem::replace(&mut seen.3, true) {
                    return Err(syn::Error::new_spanned(&literal, "`crate` is given twice"));
                }
                options.crate_path = path.to_token_stream();
                Ok(())
            } else {
                Err(meta.error("unknown `gbuffer` option: expected `budget = <bits>`, `conversions = exact | fast` or `crate = \"<path>\"`"))
            }
        });
        if let Err(error) = result {
            combine(errors, error);
        }
    }
    options
}

/// `fast` or `exact`, written as a path or a string (`conversions = "fast"`).
fn conversions_value(value: &syn::Expr) -> syn::Result<Conversions> {
    let name = match value {
        syn::Expr::Group(group) => return conversions_value(&group.expr),
        syn::Expr::Path(path) => path.path.get_ident().map(ToString::to_string),
        syn::Expr::Lit(syn::ExprLit {
            lit: syn::Lit::Str(literal),
            ..
        }) => Some(literal.value()),
        _ => None,
    };
    match name.as_deref().and_then(Conversions::from_name) {
        Some(conversions) => Ok(conversions),
        None => {
            let given = name.map_or_else(|| "this".to_string(), |name| format!("`{name}`"));
            Err(syn::Error::new_spanned(value, format!("unknown conversions {given}: expected `exact` (the default: bit-identical everywhere) or `fast` (WGSL's pack builtins where they exist)")))
        }
    }
}

/// A budget written as an integer literal that fits a u32.
fn budget_value(expression: &syn::Expr) -> Option<u32> {
    match expression {
        // A value that came through a `macro_rules!` fragment (`$budget:literal`) arrives in
        // an invisible group.
        syn::Expr::Group(group) => budget_value(&group.expr),
        syn::Expr::Lit(syn::ExprLit {
            lit: syn::Lit::Int(literal),
            ..
        }) => literal.base10_parse().ok(),
        _ => None,
    }
}

/// A field's storage from its `#[pls(...)]` or `#[bits(...)]` attribute (exactly one of them),
/// the span its diagnostics point at, and the field's own conversions.
fn parse_storage_attribute(
    field: &syn::Field,
    name: &str,
    errors: &mut Option<syn::Error>,
) -> Option<(Storage, Span, Option<Conversions>)> {
    let attributes: Vec<&syn::Attribute> = field
        .attrs
        .iter()
        .filter(|attribute| attribute.path().is_ident("pls") || attribute.path().is_ident("bits"))
        .collect();
    let Some(first) = attributes.first() else {
        combine(
            errors,
            syn::Error::new(
                field.ident.span(),
                format!("field `{name}` needs `#[pls(<format>)]` (a whole word, e.g. `#[pls(rgba8)]`) or `#[bits(<bits>, <encoding>)]` (a bit field, e.g. `#[bits(4, unorm)]`)"),
            ),
        );
        return None;
    };
    for repeated in &attributes[1..] {
        combine(
            errors,
            syn::Error::new_spanned(
                repeated,
                format!("field `{name}` has more than one `#[pls]` or `#[bits]` attribute: a field is one word or one bit field"),
            ),
        );
    }
    if first.path().is_ident("bits") {
        return parse_bits_attribute(first, errors);
    }
    let arguments = first.parse_args_with(|input: syn::parse::ParseStream| {
        let format: syn::Ident = input.parse()?;
        Ok((format, parse_conversions_option(input, "pls")?))
    });
    let usage = || {
        format!("expected `#[pls(<format>)]` or `#[pls(<format>, conversions = fast)]` with a format among: {}", format_list())
    };
    let (format_ident, conversions) = arguments_or_usage(arguments, errors, first, usage)?;
    let format_name = format_ident.to_string();
    match Format::from_name(&format_name) {
        Some(format) => Some((Storage::Word(format), format_ident.span(), conversions)),
        None => {
            let nearest = Format::nearest(&format_name);
            combine(
                errors,
                syn::Error::new(
                    format_ident.span(),
                    format!("unknown pixel local storage format `{format_name}`; did you mean `{nearest}`? The formats are: {}", format_list()),
                ),
            );
            None
        }
    }
}

/// `, conversions = fast` after an attribute's main arguments, if present.
fn parse_conversions_option(
    input: syn::parse::ParseStream,
    attribute: &str,
) -> syn::Result<Option<Conversions>> {
    if input.is_empty() {
        return Ok(None);
    }
    input.parse::<syn::Token![,]>()?;
    let key: syn::Ident = input.parse()?;
    if key != "conversions" {
        return Err(syn::Error::new(
            key.span(),
            format!("unknown `{attribute}` option `{key}`: expected `conversions = exact | fast`"),
        ));
    }
    input.parse::<syn::Token![=]>()?;
    let value: syn::Expr = input.parse()?;
    Ok(Some(conversions_value(&value)?))
}

/// `#[bits(4, unorm)]`, `#[bits(32, rgbm(8.0))]`, `#[bits(24, octahedral, conversions =
/// fast)]`: a bit field's width and encoding (the model checks that they suit the type).
fn parse_bits_attribute(
    attribute: &syn::Attribute,
    errors: &mut Option<syn::Error>,
) -> Option<(Storage, Span, Option<Conversions>)> {
    let parsed = attribute.parse_args_with(|input: syn::parse::ParseStream| {
        let width: syn::LitInt = input.parse()?;
        input.parse::<syn::Token![,]>()?;
        let encoding: syn::Ident = input.parse()?;
        let range = if input.peek(syn::token::Paren) {
            let content;
            syn::parenthesized!(content in input);
            let literal: syn::Lit = content.parse()?;
            let value = match &literal {
                syn::Lit::Float(float) => float.base10_parse::<f32>()?,
                syn::Lit::Int(int) => int.base10_parse::<f32>()?,
                _ => {
                    return Err(syn::Error::new_spanned(
                        &literal,
                        "a range is a number, e.g. `rgbm(8.0)`",
                    ))
                }
            };
            Some((value, literal.span()))
        } else {
            None
        };
        let conversions = parse_conversions_option(input, "bits")?;
        Ok((width, encoding, range, conversions))
    });
    let usage = || {
        format!("expected `#[bits(<bits>, <encoding>)]`, e.g. `#[bits(4, unorm)]` or `#[bits(32, rgbm(8.0))]`, with an encoding among: {}", Encoding::names().join(", "))
    };
    let (width, encoding_ident, range, conversions) =
        arguments_or_usage(parsed, errors, attribute, usage)?;
    let bits = match width.base10_parse::<u32>() {
        Ok(bits) => bits,
        Err(_) => {
            combine(
                errors,
                syn::Error::new(width.span(), "a bit field has 1 to 32 bits"),
            );
            return None;
        }
    };
    let encoding =
        match Encoding::from_name(&encoding_ident.to_string(), range.map(|(value, _)| value)) {
            Ok(encoding) => encoding,
            Err(message) => {
                let span = match range {
                    Some((_, span))
                        if Encoding::names().contains(&encoding_ident.to_string().as_str()) =>
                    {
                        span
                    }
                    _ => encoding_ident.span(),
                };
                combine(errors, syn::Error::new(span, message));
                return None;
            }
        };
    Some((
        Storage::Bits(BitField { bits, encoding }),
        encoding_ident.span(),
        conversions,
    ))
}

fn format_list() -> String {
    Format::names().join(", ")
}

/// The field's type, recognised by the last segment of its path.
fn parse_field_type(ty: &syn::Type, errors: &mut Option<syn::Error>) -> Option<FieldType> {
    let recognised = match ty {
        syn::Type::Path(path) if path.qself.is_none() => path
            .path
            .segments
            .last()
            .filter(|segment| segment.arguments.is_none())
            .and_then(|segment| FieldType::from_rust_name(&segment.ident.to_string())),
        _ => None,
    };
    if recognised.is_none() {
        combine(
            errors,
            syn::Error::new(
                ty.span(),
                "unsupported G-buffer field type: use `f32`, `Vec2`, `Vec3` or `Vec4` for float and \
                 unorm formats, `u32` or `UVec2`..`UVec4` for the `ui` formats, `i32` or \
                 `IVec2`..`IVec4` for the `i` formats (glam types, re-exported as `gbuffer::glam`), \
                 and `bool` for a `bool` bit field",
            ),
        );
    }
    recognised
}

/// An attribute's parsed arguments; or, where they did not parse, `None` with the error added
/// to `errors`: the parser's own where it names the problem (an unknown option, a bad range),
/// otherwise `usage` at the whole attribute.
fn arguments_or_usage<T>(
    parsed: syn::Result<T>,
    errors: &mut Option<syn::Error>,
    attribute: &syn::Attribute,
    usage: impl Fn() -> String,
) -> Option<T> {
    match parsed {
        Ok(arguments) => Some(arguments),
        Err(error) => {
            let message = error.to_string();
            let named = message.starts_with("unknown") || message.starts_with("a range");
            let error = match named {
                true => error,
                false => syn::Error::new_spanned(attribute, usage()),
            };
            combine(errors, error);
            None
        }
    }
}
