//! The names of option values (`mobile-metallic`, `two-pass`, `ggx`, `rgb10_a2`), written once
//! per enum, beside it: command lines, tables, messages and file formats all spell a value
//! through [`Named`], and read it back with [`Named::from_name`]. A leaf of the crate graph, so
//! that every package implements it where its enum is defined.

/// A value with one name, one of a fixed list.
pub trait Named: Copy + Sized + 'static {
    /// Every value, in the order a command line or a table lists them.
    const ALL: &'static [Self];

    /// The value's name.
    fn name(self) -> &'static str;

    /// The value a name stands for.
    fn from_name(name: &str) -> Option<Self> {
        Self::ALL.iter().copied().find(|value| value.name() == name)
    }

    /// Every name, in [`Self::ALL`]'s order.
    fn names() -> Vec<&'static str> {
        Self::ALL.iter().map(|value| value.name()).collect()
    }
}
