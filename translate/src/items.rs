//! What a shader text declares, as data: each item's kind, name and text. The GLSL printer
//! records its items as it prints them ([`crate::printer::Printed::items`]; gbuffer-codegen's
//! includes add their attachments, blocks and accessors as they write them); a WGSL text is
//! read back through naga's parser ([`wgsl_items`]). A caller asks for the items by name and
//! kind instead of searching the text.

/// What kind of declaration an emitted item is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ItemKind {
    /// A struct type.
    Struct,
    /// A named constant.
    Constant,
    /// A texture (in GLSL, a sampler uniform: the texture and its sampler together).
    Texture,
    /// A function.
    Function,
    /// A G-buffer attachment an include reads or writes: a framebuffer fetch `inout`, a
    /// subpass input, a WebGL pixel local storage plane.
    Attachment,
    /// A pixel local storage block.
    Block,
}

/// One declaration of a WGSL text.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct WgslItem {
    /// What it declares.
    pub kind: ItemKind,
    /// Its name.
    pub name: String,
    /// Its text: the comment lines right above it, its attributes and the declaration.
    pub text: String,
}

/// The structs, named constants, textures and functions `wgsl` declares, in its order, read
/// back through naga's parser and validator (with the capabilities generated code needs).
/// Entry points are not items: a shader has them, an emitted module does not.
pub fn wgsl_items(wgsl: &str) -> Result<Vec<WgslItem>, String> {
    let (module, _) = crate::wgsl::validate(wgsl, crate::wgsl::GENERATED_CODE_CAPABILITIES)?;
    let structs = module
        .types
        .iter()
        .filter(|(_, ty)| matches!(ty.inner, naga::TypeInner::Struct { .. }))
        .map(|(handle, ty)| (module.types.get_span(handle), ItemKind::Struct, &ty.name));
    let constants = module.constants.iter().map(|(handle, constant)| {
        let span = module.constants.get_span(handle);
        (span, ItemKind::Constant, &constant.name)
    });
    let textures = module
        .global_variables
        .iter()
        .filter(|(_, global)| {
            matches!(module.types[global.ty].inner, naga::TypeInner::Image { .. })
        })
        .map(|(handle, global)| {
            let span = module.global_variables.get_span(handle);
            (span, ItemKind::Texture, &global.name)
        });
    let functions = module.functions.iter().map(|(handle, function)| {
        let span = module.functions.get_span(handle);
        (span, ItemKind::Function, &function.name)
    });
    let mut found: Vec<(std::ops::Range<usize>, ItemKind, &str)> = structs
        .chain(constants)
        .chain(textures)
        .chain(functions)
        .filter_map(|(span, kind, name)| Some((span.to_range()?, kind, name.as_deref()?)))
        .collect();
    found.sort_by_key(|(range, _, _)| range.start);
    Ok(found
        .into_iter()
        .map(|(range, kind, name)| WgslItem {
            kind,
            name: name.to_string(),
            text: with_comment_and_attributes(wgsl, range),
        })
        .collect())
}

/// The text of a declaration spanning `range`, widened to the start of its first line (where
/// a global's attributes stand) and over the `//` lines right above it.
fn with_comment_and_attributes(wgsl: &str, range: std::ops::Range<usize>) -> String {
    let mut start = wgsl[..range.start]
        .rfind('\n')
        .map_or(0, |newline| newline + 1);
    while start > 0 {
        let above = wgsl[..start - 1]
            .rfind('\n')
            .map_or(0, |newline| newline + 1);
        if !wgsl[above..start].trim_start().starts_with("//") {
            break;
        }
        start = above;
    }
    format!("{}\n", &wgsl[start..range.end])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_items_come_in_order_with_their_comments() {
        let wgsl = "// A texel.\nstruct S {\n    a: f32,\n}\n\n// Words.\n// Four.\nconst N: u32 = 4u;\n\n@group(0) @binding(1) var t: texture_2d<f32>;\n\nfn f(x: f32) -> f32 {\n    return x * 2.0;\n}\n";
        let items = wgsl_items(wgsl).unwrap();
        let summary: Vec<(ItemKind, &str, &str)> = items
            .iter()
            .map(|item| (item.kind, item.name.as_str(), item.text.as_str()))
            .collect();
        assert_eq!(
            summary,
            [
                (
                    ItemKind::Struct,
                    "S",
                    "// A texel.\nstruct S {\n    a: f32,\n}\n"
                ),
                (
                    ItemKind::Constant,
                    "N",
                    "// Words.\n// Four.\nconst N: u32 = 4u;\n"
                ),
                (
                    ItemKind::Texture,
                    "t",
                    "@group(0) @binding(1) var t: texture_2d<f32>;\n"
                ),
                (
                    ItemKind::Function,
                    "f",
                    "fn f(x: f32) -> f32 {\n    return x * 2.0;\n}\n"
                ),
            ]
        );
    }
}
