//! Building the frame's mesh from the tiles that survive culling.

use glam::{DVec2, I64Vec2};

use super::tiles::{Culling, LevelStats};
use super::{ClipMapConfig, TILE_CELLS};

/// One vertex of the clip-map mesh (16 bytes), as the water pass reads it.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ClipVertex {
    /// Morphed rest point, local metres (world minus the mesh origin).
    pub rest: [f32; 2],
    /// Weight of the waves the next coarser level drops: 1 − morph.
    pub fade: f32,
    /// Level index.
    pub level: u32,
}

/// The mesh of one frame.
#[derive(Debug, Clone, Default)]
pub struct ClipMesh {
    /// World (x, z) of the local origin: the coarsest level's snapped centre.
    pub origin: DVec2,
    pub vertices: Vec<ClipVertex>,
    pub indices: Vec<u32>,
    pub levels: Vec<LevelStats>,
}

impl ClipMesh {
    pub fn triangles(&self) -> u64 {
        (self.indices.len() / 3) as u64
    }
}

impl ClipMapConfig {
    /// Triangles that [`ClipMapConfig::build`] would emit, without building the mesh.
    pub(crate) fn triangles_drawn(&self, eye: DVec2, culling: &Culling) -> u64 {
        self.visit_tiles(eye, culling, |_, _, _| {})
            .iter()
            .map(|s| s.triangles)
            .sum()
    }

    /// Build the mesh for an eye at world (x, z) = `eye`, emitting only the tiles that survive
    /// `culling`.
    pub fn build(&self, eye: DVec2, culling: &Culling) -> ClipMesh {
        let origin = self.origin_for(eye);
        let origin_lattice = self.centre_lattice(self.levels() - 1, eye);
        let (mut vertices, mut indices) = (Vec::new(), Vec::new());
        let centres: Vec<I64Vec2> = (0..self.levels())
            .map(|l| self.centre_index(l, eye))
            .collect();
        let levels = self.visit_tiles(eye, culling, |l, [i0, i1, j0, j1], cells| {
            let t = i64::from(TILE_CELLS).min(i64::from(self.cells[l as usize]) / 2);
            let base = vertices.len() as u32;
            let wi = (i1 - i0 + 1) as u32;
            for j in j0..=j1 {
                for i in i0..=i1 {
                    let (p, fade) = self.morphed_vertex(l, i, j, centres[l as usize]);
                    let q = self.to_world(p - origin_lattice);
                    vertices.push(ClipVertex {
                        rest: [q.x as f32, q.y as f32],
                        fade: fade as f32,
                        level: l,
                    });
                }
            }
            for j in j0..j1 {
                for i in i0..i1 {
                    if cells & (1 << ((j - j0) * t + (i - i0))) == 0 {
                        continue;
                    }
                    let a = base + ((j - j0) as u32) * wi + (i - i0) as u32;
                    let (b, d, e) = (a + 1, a + wi, a + wi + 1);
                    // Every quad split along the same diagonal, at every level, so a fully
                    // morphed fine quad matches the coarse triangulation.
                    indices.extend_from_slice(&[a, d, e, a, e, b]);
                }
            }
        });
        ClipMesh {
            origin,
            vertices,
            indices,
            levels,
        }
    }
}
