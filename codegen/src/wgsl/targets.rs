//! What a lighting pass declares to read a layout's packed render targets (the wgpu helpers'
//! targets: words 4t to 4t + 3 in target t), and the functions that load and unpack a texel.

use crate::LoweredLayout;

/// The lighting pass's WGSL for a layout's packed render targets, to put after the layout's
/// own WGSL ([`emit`](super::emit)): one `texture_2d<u32>` per target (`<snake>_target<t>`, in
/// `group`, from `first_binding`), `load_<snake>_targets(pixel: vec2<u32>) -> <Name>Targets`,
/// the words as stored, and `read_<snake>_targets(pixel: vec2<u32>) -> <Name>`, which loads
/// and unpacks a texel. `GBufferTargets::lighting_wgsl` (gbuffer-runtime's, which the facade
/// re-exports) is this for a derived layout.
pub fn lighting_targets(lowered: &LoweredLayout, group: u32, first_binding: u32) -> String {
    let symbols = lowered.symbols();
    let name = symbols.texel();
    let mut out =
        format!("// The G-buffer targets of layout `{name}`, read by the lighting pass.\n");
    let mut loads = Vec::new();
    for index in 0..lowered.targets() {
        let binding = first_binding + index as u32;
        let target = symbols.target(index);
        out.push_str(&format!(
            "@group({group}) @binding({binding}) var {target}: texture_2d<u32>;\n"
        ));
        loads.push(format!("textureLoad({target}, pixel, 0)"));
    }
    let (targets, load_targets) = (symbols.targets(), symbols.load_targets());
    out.push_str(&format!(
        "\n// The words at `pixel` as stored (channels a narrow target lacks read as 0 or 1 and lie\n\
         // past the layout's words).\n\
         fn {load_targets}(pixel: vec2<u32>) -> {targets} {{\n    \
         return {targets}({});\n}}\n\n\
         // The texel at `pixel`, unpacked.\n\
         fn {}(pixel: vec2<u32>) -> {name} {{\n    \
         return {}({load_targets}(pixel));\n}}\n",
        loads.join(", "),
        symbols.read_targets(),
        symbols.unpack_targets(),
    ));
    out
}
