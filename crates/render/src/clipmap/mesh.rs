//! Building the frame's mesh from the tiles that survive culling.

use glam::{DVec2, I64Vec2};

use super::ClipMapConfig;
use super::tiles::{Culling, LevelStats};

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
    /// `culling`. Each lattice vertex of a level that a drawn cell uses is emitted once, shared
    /// by the cells around it across tile borders (its morphed rest point and fade depend only
    /// on its level and lattice index): the compute stage displaces each once. (One vertex per
    /// tile corner and per unused vertex of a partly drawn tile made the sample race's A54
    /// frame 54,351 vertices for 37,111 distinct ones.)
    pub fn build(&self, eye: DVec2, culling: &Culling) -> ClipMesh {
        let origin = self.origin_for(eye);
        let origin_lattice = self.centre_lattice(self.levels() - 1, eye);
        let to_world = self.world_rotation();
        let (mut vertices, mut indices) = (Vec::new(), Vec::new());
        let centres: Vec<I64Vec2> = (0..self.levels())
            .map(|l| self.centre_index(l, eye))
            .collect();
        // The index of each lattice vertex of the level being visited (levels come in order),
        // or NONE before a cell uses it: (n + 1)² slots for the level's n × n cells.
        const NONE: u32 = u32::MAX;
        let (mut slots, mut slots_level) = (Vec::new(), None);
        let levels = self.visit_tiles(eye, culling, |l, [i0, i1, j0, j1], cells| {
            let t = self.tile_cells(l);
            let c = centres[l as usize];
            let lo = self.lattice_min(l, c);
            let side = self.cells[l as usize] as usize + 1;
            if slots_level != Some(l) {
                slots.clear();
                slots.resize(side * side, NONE);
                slots_level = Some(l);
            }
            let mut vertex = |i: i64, j: i64| -> u32 {
                let slot = &mut slots[(j - lo.y) as usize * side + (i - lo.x) as usize];
                if *slot == NONE {
                    let (p, fade) = self.morphed_vertex(l, i, j, c);
                    let q = to_world(p - origin_lattice);
                    *slot = vertices.len() as u32;
                    vertices.push(ClipVertex {
                        rest: [q.x as f32, q.y as f32],
                        fade: fade as f32,
                        level: l,
                    });
                }
                *slot
            };
            for j in j0..j1 {
                for i in i0..i1 {
                    if cells & (1 << ((j - j0) * t + (i - i0))) == 0 {
                        continue;
                    }
                    let (a, b) = (vertex(i, j), vertex(i + 1, j));
                    let (d, e) = (vertex(i, j + 1), vertex(i + 1, j + 1));
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
