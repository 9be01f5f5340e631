// Included by `shading::mirror` (Float = f32) and `shading::reference` (Float = f64), with
// `Vec2`, `Vec3`, `Vec4` the glam vectors of that float.

/// `constants.wgsl`: PI and the clamps the other modules share.
pub mod constants {
    use super::*;
    include!("constants.rs");
}
/// `colour.wgsl`: transfer functions and luminance.
pub mod colour {
    use super::*;
    include!("colour.rs");
}
/// `hdr.wgsl`: RGBM, rgb9e5 and HDR range scaling.
pub mod hdr {
    use super::*;
    include!("hdr.rs");
}
/// `microfacet.wgsl`: GGX distribution, visibility and Fresnel.
pub mod microfacet {
    use super::constants::*;
    use super::*;
    include!("microfacet.rs");
}
/// `mobile.wgsl`: the approximate forms for mobile GPUs.
pub mod mobile {
    use super::*;
    include!("mobile.rs");
}
/// `environment.wgsl`: image-based lighting (split-sum LUT and EnvBRDFApprox).
pub mod environment {
    use super::constants::*;
    use super::microfacet::*;
    use super::*;
    include!("environment.rs");
}
/// `material.wgsl`: the metallic and specular workflows.
pub mod material {
    use super::*;
    include!("material.rs");
}
/// `normals.wgsl`: normal encodings (octahedral, ...).
pub mod normals {
    use super::*;
    include!("normals.rs");
}
/// `tonemap.wgsl`: tone mapping.
pub mod tonemap {
    use super::*;
    include!("tonemap.rs");
}
/// `shading.wgsl`: the composed sun and image-based light.
pub mod shading {
    use super::constants::*;
    use super::microfacet::*;
    use super::mobile::*;
    use super::*;
    include!("shading.rs");
}
