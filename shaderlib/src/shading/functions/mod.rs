// Included by `shading::mirror` (Float = f32) and `shading::reference` (Float = f64), with
// `Vec2`, `Vec3`, `Vec4` the glam vectors of that float.

pub mod constants {
    use super::*;
    include!("constants.rs");
}
pub mod colour {
    use super::*;
    include!("colour.rs");
}
pub mod hdr {
    use super::*;
    include!("hdr.rs");
}
pub mod microfacet {
    use super::constants::*;
    use super::*;
    include!("microfacet.rs");
}
pub mod mobile {
    use super::*;
    include!("mobile.rs");
}
pub mod environment {
    use super::constants::*;
    use super::microfacet::*;
    use super::*;
    include!("environment.rs");
}
pub mod material {
    use super::*;
    include!("material.rs");
}
pub mod normals {
    use super::*;
    include!("normals.rs");
}
pub mod tonemap {
    use super::*;
    include!("tonemap.rs");
}
pub mod shading {
    use super::constants::*;
    use super::microfacet::*;
    use super::mobile::*;
    use super::*;
    include!("shading.rs");
}
