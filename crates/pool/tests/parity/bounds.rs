//! The parity bounds of the pool's ray functions: `hit_sphere`, `box_inside` and the edges of
//! `tile_albedo` evaluated again with `render::wgsl_accuracy::Inexact` numbers, so each case
//! gets the most a conforming GPU may differ from the f64 reference by WGSL's accuracy of each
//! operation (division 2.5 ULP, sqrt inherited from 1.0/inverseSqrt, the rest correctly
//! rounded) and the case's condition.

use render::wgsl_accuracy::{Inexact, dot, sub3};

/// What a case's bound decided, or `Undecided` when a branch of the function may go either way
/// on a conforming GPU.
pub enum Bounded<T> {
    Decided(T),
    Undecided,
}

fn v3(exact: glam::DVec3, gpu: [f32; 4]) -> [Inexact; 3] {
    [
        Inexact::input(exact.x, gpu[0]),
        Inexact::input(exact.y, gpu[1]),
        Inexact::input(exact.z, gpu[2]),
    ]
}

/// `hit_sphere(o, d, s)` of `pool_common.wgsl` (the reference's f64 ray and sphere, the GPU
/// given their f32): the distance to the first hit beyond 1e-4 m, or `None` for NO_HIT.
pub fn hit_sphere(
    origin: (glam::DVec3, [f32; 4]),
    dir: (glam::DVec3, [f32; 4]),
    sphere: (glam::DVec3, f64, [f32; 4]),
) -> Bounded<Option<Inexact>> {
    let o = v3(origin.0, origin.1);
    let d = v3(dir.0, dir.1);
    let c = v3(sphere.0, sphere.2);
    let r = Inexact::input(sphere.1, sphere.2[3]);
    let oc = sub3(o, c);
    let b = dot(&d, &oc);
    let q = dot(&oc, &oc) - r * r;
    let disc = b * b - q;
    match disc.above(-f64::MIN_POSITIVE) {
        None => return Bounded::Undecided,
        Some(false) => return Bounded::Decided(None),
        Some(true) => {}
    }
    let root = disc.sqrt();
    let near = -b - root;
    let far = -b + root;
    let threshold = f64::from(1e-4f32);
    match (near.above(threshold), far.above(threshold)) {
        (Some(true), _) => Bounded::Decided(Some(near)),
        (Some(false), Some(true)) => Bounded::Decided(Some(far)),
        (Some(false), Some(false)) => Bounded::Decided(None),
        _ => Bounded::Undecided,
    }
}

/// One exit candidate of `box_inside`: the face's number and its distance.
pub struct Exit {
    pub face: u32,
    pub s: Inexact,
}

/// The candidates of `box_inside(o, d)` (the box's half widths, floor and rim as the GPU gets
/// them, exact in both) for an f32 ray (the reference uses the same numbers): one per axis
/// the direction moves along, and which of them a conforming GPU may pick (its distance
/// within the errors of the smallest). `faces` = (west, east, north, south, floor, top).
pub fn box_exits(box_: [f32; 4], o: [f32; 4], d: [f32; 4], faces: [u32; 6]) -> Vec<Exit> {
    let (o, d) = (o.map(Inexact::of), d.map(Inexact::of));
    let b = box_.map(Inexact::of);
    let mut exits = Vec::new();
    let mut candidate = |bound: Inexact, axis: usize, face: u32| {
        exits.push(Exit {
            face,
            s: (bound - o[axis]) / d[axis],
        });
    };
    // The directions are f32 inputs: their signs are exact.
    if d[0].value > 0.0 {
        candidate(b[0], 0, faces[1]);
    } else if d[0].value < 0.0 {
        candidate(-b[0], 0, faces[0]);
    }
    if d[2].value > 0.0 {
        candidate(b[1], 2, faces[3]);
    } else if d[2].value < 0.0 {
        candidate(-b[1], 2, faces[2]);
    }
    if d[1].value < 0.0 {
        candidate(b[2], 1, faces[4]);
    } else if d[1].value > 0.0 {
        candidate(b[3], 1, faces[5]);
    }
    let least = exits
        .iter()
        .map(|e| e.s.value + e.s.error)
        .fold(f64::INFINITY, f64::min);
    exits.retain(|e| e.s.value - e.s.error <= least);
    exits
}

/// The exit point o + d·max(s, 0) for an exit's distance.
pub fn exit_point(o: [f32; 4], d: [f32; 4], s: Inexact) -> [Inexact; 3] {
    let s = s.max(Inexact::exact(0.0));
    [0, 1, 2].map(|i| Inexact::of(o[i]) + Inexact::of(d[i]) * s)
}

/// How far, metres, a conforming GPU may move an edge of `tile_albedo` at coordinates up to
/// `extent` metres from the origin: the tile fraction uv/TILE − floor(uv/TILE) (a division,
/// 2.5 ULP, and a subtraction; TILE and GROUT the f32 of the reference's f64) compared with
/// GROUT/TILE, and the band and lane comparisons of coordinates with the box's f32 rim and
/// half width.
pub fn tile_edge_width(extent: f64, tile: f64, grout: f64, rim: f64) -> f64 {
    let uv = Inexact::of(extent as f32);
    let tile_in = Inexact::input(tile, tile as f32);
    let q = uv / tile_in;
    // floor is exact; the fraction keeps q's error and rounds once more.
    let fraction = q - Inexact::exact(q.value.floor());
    let lhs = fraction * tile_in;
    let grout_in = Inexact::input(grout, grout as f32);
    let tile_edges = lhs.error + grout_in.error;
    let band = Inexact::of(rim as f32) - Inexact::exact(2.0) * tile_in;
    tile_edges.max(band.error) + f64::from(f32::EPSILON) * extent
}
