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

/// Implements [`Named`] for an enum of unit variants from one list of its variants and their
/// names, in the order [`Named::ALL`] gives them. The `name` it writes is a `match` on every
/// variant listed, so a variant added to the enum and not to the list fails to compile, and
/// `ALL` cannot leave one out. Doc comments before the enum's name document `name`.
///
/// ```
/// use gbuffer_core::Named;
///
/// #[derive(Clone, Copy, Debug, PartialEq)]
/// enum Mode {
///     Exact,
///     Fast,
/// }
/// gbuffer_core::named!(
///     /// The mode's name on the command line.
///     Mode {
///         Exact => "exact",
///         Fast => "fast",
///     }
/// );
/// assert_eq!(Mode::ALL, &[Mode::Exact, Mode::Fast]);
/// assert_eq!(Mode::from_name("fast"), Some(Mode::Fast));
/// ```
#[macro_export]
macro_rules! named {
    ($(#[doc = $doc:literal])* $enum:ident { $($variant:ident => $name:literal),+ $(,)? }) => {
        impl $crate::Named for $enum {
            const ALL: &'static [Self] = &[$($enum::$variant),+];

            $(#[doc = $doc])*
            fn name(self) -> &'static str {
                match self {
                    $($enum::$variant => $name),+
                }
            }
        }
    };
}
