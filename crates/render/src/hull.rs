//! Procedural meshes for the boats pass: a keelboat hull with a mast and a mainsail, and a
//! course-mark buoy. Model space: bow along −z, starboard +x, up +y, waterline at y = 0, one
//! unit = one metre for a hull of length 1 (instances scale it).

/// One vertex of a procedural mesh (28 bytes).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct MeshVertex {
    pub position: [f32; 3],
    pub normal: [f32; 3],
    /// 0 = hull (instance colour), 1 = sail, 2 = deck and mast.
    pub part: u32,
}

pub(crate) const HULL: u32 = 0;
pub(crate) const SAIL: u32 = 1;
pub(crate) const DARK: u32 = 2;

/// A flat-shaded triangle list.
#[derive(Debug, Clone, Default)]
pub(crate) struct Mesh {
    pub vertices: Vec<MeshVertex>,
}

impl Mesh {
    fn tri(&mut self, a: [f32; 3], b: [f32; 3], c: [f32; 3], part: u32) {
        let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
        let n = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt().max(1e-12);
        let normal = [n[0] / len, n[1] / len, n[2] / len];
        for position in [a, b, c] {
            self.vertices.push(MeshVertex {
                position,
                normal,
                part,
            });
        }
    }

    fn quad(&mut self, a: [f32; 3], b: [f32; 3], c: [f32; 3], d: [f32; 3], part: u32) {
        self.tri(a, b, c, part);
        self.tri(a, c, d, part);
    }

    #[cfg(test)]
    pub(crate) fn triangles(&self) -> u64 {
        (self.vertices.len() / 3) as u64
    }
}

/// A hull of length 1 with a deck, a mast and a mainsail.
pub fn boat() -> Mesh {
    let mut m = Mesh::default();
    // Stations from bow (z = −0.5) to stern (z = +0.5): half-beam and draft.
    const N: usize = 9;
    let station = |i: usize| {
        let u = i as f32 / (N - 1) as f32; // 0 at the bow
        let z = -0.5 + u;
        let half_beam = 0.16 * (std::f32::consts::PI * u.powf(0.7)).sin().max(0.0) + 0.02 * u;
        let draft = 0.07 * (std::f32::consts::PI * u).sin();
        (z, half_beam, draft)
    };
    const FREEBOARD: f32 = 0.06;
    for i in 0..N - 1 {
        let (z0, b0, d0) = station(i);
        let (z1, b1, d1) = station(i + 1);
        for side in [-1.0f32, 1.0] {
            let g0 = [side * b0, FREEBOARD, z0];
            let g1 = [side * b1, FREEBOARD, z1];
            let k0 = [0.0, -d0, z0];
            let k1 = [0.0, -d1, z1];
            // Wind the topsides so their normals face outwards.
            if side > 0.0 {
                m.quad(g0, g1, k1, k0, HULL);
            } else {
                m.quad(g0, k0, k1, g1, HULL);
            }
        }
        m.quad(
            [-b0, FREEBOARD, z0],
            [-b1, FREEBOARD, z1],
            [b1, FREEBOARD, z1],
            [b0, FREEBOARD, z0],
            DARK,
        );
    }
    // Transom.
    let (zs, bs, ds) = station(N - 1);
    m.tri(
        [-bs, FREEBOARD, zs],
        [0.0, -ds, zs],
        [bs, FREEBOARD, zs],
        HULL,
    );
    // Mast: a thin square tube, a third of the way aft.
    let (mz, h, r) = (-0.12f32, 1.3f32, 0.012f32);
    let c = [[-r, -r], [r, -r], [r, r], [-r, r]];
    for k in 0..4 {
        let [x0, dz0] = c[k];
        let [x1, dz1] = c[(k + 1) % 4];
        m.quad(
            [x0, FREEBOARD, mz + dz0],
            [x1, FREEBOARD, mz + dz1],
            [x1, h, mz + dz1],
            [x0, h, mz + dz0],
            DARK,
        );
    }
    // Mainsail: from the mast's head and foot back to the boom end, slightly eased to port.
    m.tri(
        [0.0, h * 0.97, mz + r],
        [0.0, FREEBOARD + 0.1, mz + r],
        [-0.08, FREEBOARD + 0.12, 0.38],
        SAIL,
    );
    // Jib: forestay from the bow to 80 % up the mast.
    m.tri(
        [0.0, h * 0.8, mz - r],
        [0.0, FREEBOARD + 0.03, -0.48],
        [-0.06, FREEBOARD + 0.05, mz - 0.03],
        SAIL,
    );
    m
}

/// A buoy of diameter 1: an orange cylinder with a cone on top (part = hull, coloured by the
/// instance).
pub fn buoy() -> Mesh {
    let mut m = Mesh::default();
    const K: usize = 12;
    let ring = |k: usize, r: f32, y: f32| {
        let a = k as f32 / K as f32 * std::f32::consts::TAU;
        [r * a.cos(), y, r * a.sin()]
    };
    for k in 0..K {
        let (a0, a1) = (ring(k, 0.5, -0.3), ring(k + 1, 0.5, -0.3));
        let (b0, b1) = (ring(k, 0.5, 0.6), ring(k + 1, 0.5, 0.6));
        m.quad(a0, b0, b1, a1, HULL);
        m.tri(b0, [0.0, 1.5, 0.0], b1, HULL);
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hull_normals_point_away_from_the_centreline() {
        let m = boat();
        for t in m.vertices.chunks(3).filter(|t| t[0].part == HULL) {
            let cx = (t[0].position[0] + t[1].position[0] + t[2].position[0]) / 3.0;
            if cx.abs() > 0.01 {
                assert!(
                    cx * t[0].normal[0] > 0.0,
                    "inward-facing hull triangle {t:?}"
                );
            }
        }
        assert!(m.triangles() > 40);
    }
}
