//! The static cost of a shader: naga IR expressions reachable from a function or entry point,
//! and SPIR-V instructions after unused functions, types and constants are compacted away.

use naga::{Block, Handle, Module, Statement};

/// What a shader costs, statically.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Cost {
    /// naga IR expressions of the root and every function it calls.
    pub expressions: usize,
    /// Instructions of the whole module's SPIR-V, compacted.
    pub spirv_instructions: usize,
}

/// Validates `source`, compacts it and counts: expressions reachable from `root` (an entry
/// point's or a function's name) and SPIR-V instructions.
pub fn measure(source: &str, root: &str) -> Result<Cost, String> {
    let (module, words) = compile_compacted(source)?;
    Ok(Cost {
        expressions: naga_expressions(&module, root),
        spirv_instructions: spirv_instructions(&words),
    })
}

/// The validated module, and the SPIR-V of its compacted copy.
pub fn compile_compacted(source: &str) -> Result<(Module, Vec<u32>), String> {
    let validated =
        crate::validate_wgsl(source).map_err(|problem| format!("{problem}\n{}", problem.detail))?;
    let mut compacted = validated.module.clone();
    naga::compact::compact(&mut compacted, naga::compact::KeepUnused::No);
    let flags = naga::valid::ValidationFlags::all();
    let info = naga::valid::Validator::new(flags, naga::valid::Capabilities::all())
        .validate(&compacted)
        .map_err(|error| error.emit_to_string(source))?;
    let words = naga::back::spv::write_vec(&compacted, &info, &Default::default(), None)
        .map_err(|error| error.to_string())?;
    Ok((validated.module, words))
}

/// The functions `body` calls, directly.
fn callees(body: &Block, found: &mut Vec<Handle<naga::Function>>) {
    for statement in body.iter() {
        match statement {
            Statement::Call { function, .. } => found.push(*function),
            Statement::Block(block) => callees(block, found),
            Statement::If { accept, reject, .. } => {
                callees(accept, found);
                callees(reject, found);
            }
            Statement::Loop {
                body, continuing, ..
            } => {
                callees(body, found);
                callees(continuing, found);
            }
            Statement::Switch { cases, .. } => {
                cases.iter().for_each(|case| callees(&case.body, found))
            }
            _ => {}
        }
    }
}

/// naga IR expressions of `root` (an entry point or a function) and every function it reaches;
/// 0 when there is no such root.
pub fn naga_expressions(module: &Module, root: &str) -> usize {
    let named = |function: &naga::Function| function.name.as_deref() == Some(root);
    let (mut total, mut pending) = match module.entry_points.iter().find(|entry| entry.name == root)
    {
        Some(entry) => {
            let mut pending = Vec::new();
            callees(&entry.function.body, &mut pending);
            (entry.function.expressions.len(), pending)
        }
        None => match module
            .functions
            .iter()
            .find(|(_, function)| named(function))
        {
            Some((handle, _)) => (0, vec![handle]),
            None => return 0,
        },
    };
    let mut reached = Vec::new();
    while let Some(handle) = pending.pop() {
        if reached.contains(&handle) {
            continue;
        }
        reached.push(handle);
        total += module.functions[handle].expressions.len();
        callees(&module.functions[handle].body, &mut pending);
    }
    total
}

/// The opcodes of a SPIR-V module's instructions, in order: after the 5-word header, each
/// instruction's first word holds its length in words (high half) and its opcode (low half).
/// A zero length, which no valid module has, ends the walk.
pub fn spirv_opcodes(words: &[u32]) -> impl Iterator<Item = u32> + '_ {
    let mut index = 5;
    std::iter::from_fn(move || {
        let first = *words.get(index)?;
        let length = (first >> 16) as usize;
        if length == 0 {
            return None;
        }
        index += length;
        Some(first & 0xffff)
    })
}

/// SPIR-V instructions in a module (all of them, header excluded).
pub fn spirv_instructions(words: &[u32]) -> usize {
    spirv_opcodes(words).count()
}
