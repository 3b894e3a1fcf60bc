//! Triangle meshes for the GLB: boxes (4 vertices a face, with the face's normal) and
//! cylinders (smooth sides, flat caps), in glTF's frame (+Y up), and the binary buffer that
//! holds them (each buffer view aligned to 4 bytes, positions with their exact min/max).

use serde_json::{json, Value};

/// semsim's frame (z up) to glTF's (+Y up, right-handed): (x, y, z) -> (x, z, -y).
pub(crate) fn to_gltf(p: [f64; 3]) -> [f64; 3] {
    [p[0], p[2], -p[1]]
}

/// An indexed triangle list with a normal per vertex, in glTF's frame.
#[derive(Debug, Default, Clone)]
pub(crate) struct Mesh {
    pub positions: Vec<[f32; 3]>,
    pub normals: Vec<[f32; 3]>,
    pub indices: Vec<u32>,
}

/// A rotation about z by `yaw` (radians) then a translation, in semsim's frame.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Placement {
    pub origin_m: [f64; 3],
    pub yaw_rad: f64,
}

impl Placement {
    fn point(&self, p: [f64; 3]) -> [f64; 3] {
        let (s, c) = self.yaw_rad.sin_cos();
        let o = self.origin_m;
        [
            o[0] + c * p[0] - s * p[1],
            o[1] + s * p[0] + c * p[1],
            o[2] + p[2],
        ]
    }

    fn direction(&self, d: [f64; 3]) -> [f64; 3] {
        let (s, c) = self.yaw_rad.sin_cos();
        [c * d[0] - s * d[1], s * d[0] + c * d[1], d[2]]
    }
}

fn f32x3(p: [f64; 3]) -> [f32; 3] {
    p.map(|v| v as f32)
}

/// A unit vector in f32 (the validator checks normals are unit length).
fn unit(d: [f64; 3]) -> [f32; 3] {
    let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    f32x3(d.map(|v| v / n))
}

impl Mesh {
    fn quad(&mut self, corners: [[f64; 3]; 4], normal: [f64; 3]) {
        let base = self.positions.len() as u32;
        let n = unit(to_gltf(normal));
        for c in corners {
            self.positions.push(f32x3(to_gltf(c)));
            self.normals.push(n);
        }
        self.indices
            .extend([base, base + 1, base + 2, base, base + 2, base + 3]);
    }

    /// A box of half extents `half` (its own axes), placed.
    pub(crate) fn add_box(&mut self, at: &Placement, half: [f64; 3]) {
        let [hx, hy, hz] = half;
        // Each face: its outward axis and two in-plane axes whose cross product is outward
        // (so the corners run counter-clockwise seen from outside).
        let faces: [([f64; 3], [f64; 3], [f64; 3]); 6] = [
            ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
            ([-1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]),
            ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
            ([0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
            ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
            ([0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]),
        ];
        let scale = |v: [f64; 3]| [v[0] * hx, v[1] * hy, v[2] * hz];
        for (outward, u, v) in faces {
            let (n, u, v) = (scale(outward), scale(u), scale(v));
            let corner = |a: f64, b: f64| {
                at.point([
                    n[0] + a * u[0] + b * v[0],
                    n[1] + a * u[1] + b * v[1],
                    n[2] + a * u[2] + b * v[2],
                ])
            };
            let normal = at.direction(outward);
            self.quad(
                [
                    corner(-1.0, -1.0),
                    corner(1.0, -1.0),
                    corner(1.0, 1.0),
                    corner(-1.0, 1.0),
                ],
                normal,
            );
        }
    }

    /// A cylinder with its axis along semsim's y (a wheel), centred at the origin.
    pub(crate) fn add_wheel(&mut self, radius_m: f64, width_m: f64, segments: u32) {
        let h = width_m / 2.0;
        let ring = |i: u32| {
            let a = std::f64::consts::TAU * f64::from(i) / f64::from(segments);
            (a.cos(), a.sin())
        };
        // The tyre: a quad per segment, normals radial.
        for i in 0..segments {
            let base = self.positions.len() as u32;
            for j in [i, i + 1] {
                let (c, s) = ring(j % segments);
                let n = unit(to_gltf([c, 0.0, s]));
                for y in [-h, h] {
                    self.positions
                        .push(f32x3(to_gltf([radius_m * c, y, radius_m * s])));
                    self.normals.push(n);
                }
            }
            // Vertices: (i, -h), (i, +h), (i+1, -h), (i+1, +h); outward is radial.
            self.indices
                .extend([base, base + 1, base + 2, base + 1, base + 3, base + 2]);
        }
        // The two flat sides: a fan each.
        for side in [-1.0, 1.0] {
            let center = self.positions.len() as u32;
            let n = unit(to_gltf([0.0, side, 0.0]));
            self.positions.push(f32x3(to_gltf([0.0, side * h, 0.0])));
            self.normals.push(n);
            for i in 0..segments {
                let (c, s) = ring(i);
                self.positions
                    .push(f32x3(to_gltf([radius_m * c, side * h, radius_m * s])));
                self.normals.push(n);
            }
            for i in 0..segments {
                let a = center + 1 + i;
                let b = center + 1 + (i + 1) % segments;
                if side > 0.0 {
                    self.indices.extend([center, b, a]);
                } else {
                    self.indices.extend([center, a, b]);
                }
            }
        }
    }
}

/// The binary chunk being filled, with its buffer views and accessors (as glTF JSON).
#[derive(Default)]
pub(crate) struct Buffer {
    pub bytes: Vec<u8>,
    pub views: Vec<Value>,
    pub accessors: Vec<Value>,
}

const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
const FLOAT: u32 = 5126;
const UNSIGNED_SHORT: u32 = 5123;
const UNSIGNED_INT: u32 = 5125;

impl Buffer {
    fn view(&mut self, data: &[u8], target: u32) -> usize {
        self.bytes.resize(self.bytes.len().next_multiple_of(4), 0);
        let offset = self.bytes.len();
        self.bytes.extend_from_slice(data);
        self.views.push(json!({
            "buffer": 0,
            "byteOffset": offset,
            "byteLength": data.len(),
            "target": target,
        }));
        self.views.len() - 1
    }

    fn vec3(&mut self, values: &[[f32; 3]], bounds: bool) -> usize {
        let data: Vec<u8> = values
            .iter()
            .flat_map(|v| v.iter().flat_map(|c| c.to_le_bytes()))
            .collect();
        let view = self.view(&data, ARRAY_BUFFER);
        let mut accessor = json!({
            "bufferView": view,
            "componentType": FLOAT,
            "count": values.len(),
            "type": "VEC3",
        });
        if bounds {
            let mut min = [f32::INFINITY; 3];
            let mut max = [f32::NEG_INFINITY; 3];
            for v in values {
                for k in 0..3 {
                    min[k] = min[k].min(v[k]);
                    max[k] = max[k].max(v[k]);
                }
            }
            accessor["min"] = json!(min.map(f64::from));
            accessor["max"] = json!(max.map(f64::from));
        }
        self.accessors.push(accessor);
        self.accessors.len() - 1
    }

    fn indices(&mut self, indices: &[u32], vertices: usize) -> usize {
        let (data, component): (Vec<u8>, u32) = if vertices <= usize::from(u16::MAX) {
            (
                indices
                    .iter()
                    .flat_map(|i| (*i as u16).to_le_bytes())
                    .collect(),
                UNSIGNED_SHORT,
            )
        } else {
            (
                indices.iter().flat_map(|i| i.to_le_bytes()).collect(),
                UNSIGNED_INT,
            )
        };
        let view = self.view(&data, ELEMENT_ARRAY_BUFFER);
        self.accessors.push(json!({
            "bufferView": view,
            "componentType": component,
            "count": indices.len(),
            "type": "SCALAR",
        }));
        self.accessors.len() - 1
    }

    /// Adds a mesh's data; returns its primitive's `attributes` and `indices` JSON.
    pub(crate) fn primitive(&mut self, mesh: &Mesh, material: usize) -> Value {
        let position = self.vec3(&mesh.positions, true);
        let normal = self.vec3(&mesh.normals, false);
        let indices = self.indices(&mesh.indices, mesh.positions.len());
        json!({
            "attributes": { "POSITION": position, "NORMAL": normal },
            "indices": indices,
            "material": material,
            "mode": 4,
        })
    }
}

/// The GLB container: 12-byte header, the JSON chunk (padded with spaces), the BIN chunk
/// (padded with zeros; left out when there is no binary data).
pub(crate) fn glb(json: &[u8], bin: &[u8]) -> Vec<u8> {
    let pad = |n: usize| (4 - n % 4) % 4;
    let json_len = json.len() + pad(json.len());
    let bin_len = bin.len() + pad(bin.len());
    let total = 12 + 8 + json_len + if bin.is_empty() { 0 } else { 8 + bin_len };
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json_len as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(json);
    out.resize(out.len() + pad(json.len()), b' ');
    if !bin.is_empty() {
        out.extend_from_slice(&(bin_len as u32).to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(bin);
        out.resize(out.len() + pad(bin.len()), 0);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_box_has_outward_counter_clockwise_faces() {
        let mut m = Mesh::default();
        let at = Placement {
            origin_m: [1.0, 2.0, 3.0],
            yaw_rad: 0.3,
        };
        m.add_box(&at, [0.5, 0.25, 1.0]);
        assert_eq!((m.positions.len(), m.indices.len()), (24, 36));
        for t in m.indices.chunks(3) {
            let (_, cross) = corners_and_normal(&m, t);
            let n = m.normals[t[0] as usize].map(f64::from);
            let dot: f64 = (0..3).map(|k| cross[k] * n[k]).sum();
            assert!(dot > 0.0, "triangle {t:?} faces inwards");
        }
    }

    /// A triangle's corners and its (unnormalised) normal by the right-hand rule.
    fn corners_and_normal(m: &Mesh, t: &[u32]) -> ([[f64; 3]; 3], [f64; 3]) {
        let p = |i: u32| m.positions[i as usize].map(f64::from);
        let (a, b, c) = (p(t[0]), p(t[1]), p(t[2]));
        let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
        let cross = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        ([a, b, c], cross)
    }

    #[test]
    fn a_wheel_faces_outwards_too() {
        let mut m = Mesh::default();
        m.add_wheel(0.1, 0.05, 16);
        for t in m.indices.chunks(3) {
            let ([a, b, c], cross) = corners_and_normal(&m, t);
            let centroid: Vec<f64> = (0..3).map(|k| (a[k] + b[k] + c[k]) / 3.0).collect();
            let dot: f64 = (0..3).map(|k| cross[k] * centroid[k]).sum();
            assert!(dot > 0.0, "triangle {t:?} faces inwards");
        }
    }

    #[test]
    fn glb_chunks_are_padded() {
        let out = glb(b"{}", &[1, 2, 3]);
        assert_eq!(out.len(), 12 + 8 + 4 + 8 + 4);
        assert_eq!(&out[20..24], b"{}  ");
        assert_eq!(&out[32..36], &[1, 2, 3, 0]);
    }
}
