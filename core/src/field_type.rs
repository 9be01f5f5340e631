//! A field's type: a scalar kind ([`ScalarKind`]) and 1 to 4 components, by its Rust and WGSL
//! names. The vocabulary the codecs, the formats, the bit fields and the layout share: a leaf of
//! the crate, which none of them has to import another for.

/// What a shader sees when it reads a channel: the scalar type of the field that stores it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ScalarKind {
    /// `f32` (float and unsigned-normalized formats).
    Float,
    /// `u32` (the `ui` formats).
    Uint,
    /// `i32` (the `i` formats).
    Sint,
    /// `bool` (bit fields only).
    Bool,
}

impl ScalarKind {
    /// The WGSL scalar type.
    pub fn wgsl(self) -> &'static str {
        match self {
            ScalarKind::Float => "f32",
            ScalarKind::Uint => "u32",
            ScalarKind::Sint => "i32",
            ScalarKind::Bool => "bool",
        }
    }
}

/// The type of a field: a scalar or a vector of 2 to 4 components.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct FieldType {
    /// Float, unsigned or signed integer.
    pub scalar: ScalarKind,
    /// 1 to 4.
    pub components: usize,
}

impl FieldType {
    /// Every supported type: the scalars and vectors of f32, u32 and i32, and `bool`.
    pub const ALL: [FieldType; 13] = {
        let kinds = [ScalarKind::Float, ScalarKind::Uint, ScalarKind::Sint];
        let mut all = [FieldType {
            scalar: ScalarKind::Bool,
            components: 1,
        }; 13];
        let mut index = 0;
        while index < 12 {
            all[index] = FieldType {
                scalar: kinds[index / 4],
                components: index % 4 + 1,
            };
            index += 1;
        }
        all
    };

    /// A type of `components` scalars of kind `scalar` (1 to 4).
    pub fn new(scalar: ScalarKind, components: usize) -> Self {
        FieldType { scalar, components }
    }

    /// The Rust type's name as the derive sees it: `f32`, `Vec3`, `UVec2`, `i32`, `bool`, ...
    pub fn rust_name(self) -> &'static str {
        const NAMES: [[&str; 4]; 3] = [
            ["f32", "Vec2", "Vec3", "Vec4"],
            ["u32", "UVec2", "UVec3", "UVec4"],
            ["i32", "IVec2", "IVec3", "IVec4"],
        ];
        let row = match self.scalar {
            ScalarKind::Float => 0,
            ScalarKind::Uint => 1,
            ScalarKind::Sint => 2,
            ScalarKind::Bool => return "bool",
        };
        NAMES[row][self.components - 1]
    }

    /// Recognises a Rust type name (the last segment of its path).
    pub fn from_rust_name(name: &str) -> Option<FieldType> {
        FieldType::ALL.into_iter().find(|ty| ty.rust_name() == name)
    }

    /// The WGSL type: `f32`, `vec3<f32>`, ...
    pub fn wgsl(self) -> String {
        match self.components {
            1 => self.scalar.wgsl().to_string(),
            n => format!("vec{n}<{}>", self.scalar.wgsl()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn type_names_round_trip() {
        for ty in FieldType::ALL {
            assert_eq!(FieldType::from_rust_name(ty.rust_name()), Some(ty));
        }
        assert_eq!(FieldType::new(ScalarKind::Uint, 3).wgsl(), "vec3<u32>");
    }
}
