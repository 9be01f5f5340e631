// The textbook forms, in f64, of the functions the shading library takes from the codecs:
// what the codecs' f32 forms are measured against. Included by `shading::reference`.

/// `hdr`'s codec functions.
pub mod hdr {
    use glam::{DVec3, DVec4};

    /// RGBM encode (Karis 2009): the multiplier rounded up to its 8-bit step (at least one
    /// step), the channels divided by it, unrounded.
    pub fn rgbm_encode(linear: DVec3, range: f64) -> DVec4 {
        let largest = linear.max_element();
        let multiplier = ((largest / range).clamp(0.0, 1.0) * 255.0).ceil().max(1.0) / 255.0;
        (linear / (multiplier * range))
            .clamp(DVec3::ZERO, DVec3::ONE)
            .extend(multiplier)
    }

    /// RGBM decode (Karis 2009): rgb * m * range.
    pub fn rgbm_decode(rgbm: DVec4, range: f64) -> DVec3 {
        rgbm.truncate() * (rgbm.w * range)
    }
}

/// `normals`' codec functions.
pub mod normals {
    use glam::{DVec2, DVec3};

    /// +1 or -1 per component, +1 for zero.
    fn sign_not_zero(value: DVec2) -> DVec2 {
        DVec2::new(
            if value.x >= 0.0 { 1.0 } else { -1.0 },
            if value.y >= 0.0 { 1.0 } else { -1.0 },
        )
    }

    /// Octahedral encode (Cigolle et al. 2014) to [-1, 1]^2, the lower hemisphere folded.
    pub fn octahedral_encode(normal: DVec3) -> DVec2 {
        let projected = normal.truncate() / normal.abs().element_sum();
        if normal.z >= 0.0 {
            return projected;
        }
        (DVec2::ONE - DVec2::new(projected.y, projected.x).abs()) * sign_not_zero(projected)
    }

    /// Octahedral decode (Cigolle et al. 2014).
    pub fn octahedral_decode(encoded: DVec2) -> DVec3 {
        let z = 1.0 - encoded.x.abs() - encoded.y.abs();
        let xy = if z < 0.0 {
            (DVec2::ONE - DVec2::new(encoded.y, encoded.x).abs()) * sign_not_zero(encoded)
        } else {
            encoded
        };
        xy.extend(z).normalize()
    }
}
