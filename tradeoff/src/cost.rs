//! Static cost of a row's WGSL: naga IR expressions reachable from `row_eval`, and SPIR-V
//! instructions the row adds to a compute shader.

use naga::{Block, Handle, Module, Statement};

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

/// naga IR expressions of `row_eval` and every function it reaches.
pub fn naga_expressions(module: &Module) -> usize {
    let Some((root, _)) = module
        .functions
        .iter()
        .find(|(_, function)| function.name.as_deref() == Some("row_eval"))
    else {
        return 0;
    };
    let mut pending = vec![root];
    let mut reached = Vec::new();
    while let Some(handle) = pending.pop() {
        if reached.contains(&handle) {
            continue;
        }
        reached.push(handle);
        callees(&module.functions[handle].body, &mut pending);
    }
    reached
        .iter()
        .map(|&handle| module.functions[handle].expressions.len())
        .sum()
}

/// The number of instructions in a SPIR-V binary (after its 5-word header, each instruction's
/// first word holds its word count in the high 16 bits).
pub fn spirv_instructions(words: &[u32]) -> usize {
    let mut count = 0;
    let mut index = 5;
    while index < words.len() {
        let length = (words[index] >> 16) as usize;
        if length == 0 {
            break;
        }
        index += length;
        count += 1;
    }
    count
}
