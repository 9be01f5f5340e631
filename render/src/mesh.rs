//! The reference scene as triangles: every backend rasterises these with a depth test, and the
//! CPU reference casts its rays against the very same triangles (in f64, from the same f32
//! vertices), so what the GPU covers at a pixel centre is what the reference hits.
//!
//! A vertex carries its world position, its unit normal and the object it belongs to: a sphere
//! (`row * COLUMNS + column`) or the ground ([`GROUND`]). Materials are functions of the object
//! and the world position (`scene::surface_at`), so no texture coordinates are needed.

use glam::DVec3;

use crate::scene::{sphere_centre, COLUMNS, GROUND, ROWS, SPHERE_RADIUS};

/// Segments around a sphere's vertical axis.
pub const SPHERE_SEGMENTS: u32 = 48;
/// Rings from pole to pole.
pub const SPHERE_RINGS: u32 = 24;
/// The ground is the square |x|, |z| < this, at y = 0.
pub const GROUND_EXTENT: f32 = 30.0;

/// One vertex, as the vertex buffers hold it (28 bytes, no padding).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Vertex {
    /// World position.
    pub position: [f32; 3],
    /// Unit normal (the analytic sphere's at the vertex; +y on the ground).
    pub normal: [f32; 3],
    /// The object: a sphere index or [`GROUND`].
    pub object: u32,
}

/// The scene's triangles: vertices, and three indices per triangle.
#[derive(Clone, Debug)]
pub struct Mesh {
    /// The vertices.
    pub vertices: Vec<Vertex>,
    /// Three per triangle (no backend culls, so the winding does not matter).
    pub indices: Vec<u32>,
    /// Per sphere, the range of `indices` its triangles take.
    sphere_ranges: Vec<std::ops::Range<usize>>,
    ground_range: std::ops::Range<usize>,
}

/// Where a ray meets the mesh.
#[derive(Clone, Copy, Debug)]
pub struct Hit {
    /// The object hit.
    pub object: u32,
    /// Distance along the (unit) ray.
    pub distance: f64,
    /// The vertex normals interpolated at the hit, normalised.
    pub normal: DVec3,
}

impl Mesh {
    /// Tessellates the spheres (latitude-longitude, [`SPHERE_SEGMENTS`] x [`SPHERE_RINGS`])
    /// and the ground (two triangles).
    pub fn scene() -> Mesh {
        let mut mesh = Mesh {
            vertices: Vec::new(),
            indices: Vec::new(),
            sphere_ranges: Vec::new(),
            ground_range: 0..0,
        };
        for row in 0..ROWS {
            for column in 0..COLUMNS {
                let start = mesh.indices.len();
                mesh.add_sphere(sphere_centre(column, row), (row * COLUMNS + column) as u32);
                mesh.sphere_ranges.push(start..mesh.indices.len());
            }
        }
        let start = mesh.indices.len();
        let base = mesh.vertices.len() as u32;
        for (x, z) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            mesh.vertices.push(Vertex {
                position: [x * GROUND_EXTENT, 0.0, z * GROUND_EXTENT],
                normal: [0.0, 1.0, 0.0],
                object: GROUND,
            });
        }
        mesh.indices
            .extend([0, 2, 1, 0, 3, 2].map(|index| base + index));
        mesh.ground_range = start..mesh.indices.len();
        mesh
    }

    fn add_sphere(&mut self, centre: DVec3, object: u32) {
        let base = self.vertices.len() as u32;
        for ring in 0..=SPHERE_RINGS {
            let theta = std::f64::consts::PI * f64::from(ring) / f64::from(SPHERE_RINGS);
            for segment in 0..=SPHERE_SEGMENTS {
                let phi = std::f64::consts::TAU * f64::from(segment) / f64::from(SPHERE_SEGMENTS);
                let normal = DVec3::new(
                    theta.sin() * phi.cos(),
                    theta.cos(),
                    theta.sin() * phi.sin(),
                );
                self.vertices.push(Vertex {
                    position: (centre + normal * SPHERE_RADIUS).as_vec3().to_array(),
                    normal: normal.as_vec3().to_array(),
                    object,
                });
            }
        }
        let stride = SPHERE_SEGMENTS + 1;
        for ring in 0..SPHERE_RINGS {
            for segment in 0..SPHERE_SEGMENTS {
                let a = base + ring * stride + segment;
                let b = a + stride;
                // The pole rings' degenerate triangles are left out.
                if ring != 0 {
                    self.indices.extend([a, a + 1, b]);
                }
                if ring != SPHERE_RINGS - 1 {
                    self.indices.extend([a + 1, b + 1, b]);
                }
            }
        }
    }

    /// The nearest triangle a ray from `origin` along the unit `direction` meets in front of
    /// it. Spheres whose bounding sphere the ray misses are skipped.
    pub fn intersect(&self, origin: DVec3, direction: DVec3) -> Option<Hit> {
        let mut nearest: Option<Hit> = None;
        let mut test = |range: std::ops::Range<usize>| {
            for triangle in self.indices[range].chunks_exact(3) {
                if let Some(hit) = self.intersect_triangle(triangle, origin, direction) {
                    if nearest.is_none_or(|best| hit.distance < best.distance) {
                        nearest = Some(hit);
                    }
                }
            }
        };
        for (index, range) in self.sphere_ranges.iter().enumerate() {
            let centre = sphere_centre(index % COLUMNS, index / COLUMNS);
            let offset = origin - centre;
            let b = offset.dot(direction);
            let bound = SPHERE_RADIUS * 1.001;
            if b * b - (offset.dot(offset) - bound * bound) > 0.0 {
                test(range.clone());
            }
        }
        test(self.ground_range.clone());
        nearest
    }

    /// Möller-Trumbore in f64 on the f32 vertices: the hit and its interpolated normal.
    fn intersect_triangle(&self, triangle: &[u32], origin: DVec3, direction: DVec3) -> Option<Hit> {
        let vertex = |index: u32| &self.vertices[index as usize];
        let position = |index: u32| DVec3::from_array(vertex(index).position.map(f64::from));
        let normal = |index: u32| DVec3::from_array(vertex(index).normal.map(f64::from));
        let [a, b, c] = [triangle[0], triangle[1], triangle[2]];
        let (edge1, edge2) = (position(b) - position(a), position(c) - position(a));
        let p = direction.cross(edge2);
        let determinant = edge1.dot(p);
        if determinant.abs() < 1e-14 {
            return None;
        }
        let to_origin = origin - position(a);
        let u = to_origin.dot(p) / determinant;
        let q = to_origin.cross(edge1);
        let v = direction.dot(q) / determinant;
        if u < 0.0 || v < 0.0 || u + v > 1.0 {
            return None;
        }
        let distance = edge2.dot(q) / determinant;
        (distance > 1e-9).then(|| Hit {
            object: vertex(a).object,
            distance,
            normal: (normal(a) * (1.0 - u - v) + normal(b) * u + normal(c) * v).normalize(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ray_at_a_sphere_centre_hits_its_front_within_the_tessellation() {
        let mesh = Mesh::scene();
        let centre = sphere_centre(2, 1);
        let origin = centre - DVec3::Z * 3.0;
        let hit = mesh.intersect(origin, DVec3::Z).expect("a hit");
        assert_eq!(hit.object, (COLUMNS + 2) as u32);
        let sag = SPHERE_RADIUS * (1.0 - (std::f64::consts::PI / f64::from(SPHERE_RINGS)).cos());
        assert!(
            (hit.distance - (3.0 - SPHERE_RADIUS)).abs() <= sag,
            "{hit:?}"
        );
        assert!(hit.normal.dot(-DVec3::Z) > 0.99);
    }

    #[test]
    fn a_ray_down_hits_the_ground_and_a_ray_up_misses() {
        let mesh = Mesh::scene();
        let origin = DVec3::new(3.5, 2.0, -3.0);
        let hit = mesh.intersect(origin, -DVec3::Y).expect("the ground");
        assert_eq!(hit.object, GROUND);
        assert!((hit.distance - 2.0).abs() < 1e-9);
        assert!(mesh.intersect(origin, DVec3::Y).is_none());
    }
}
