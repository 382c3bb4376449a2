// Pool caustics pass: the water surface grid's triangles, refracted to the box and drawn into
// the caustics map (the box's unfolded net) with additive blending. Each triangle adds the
// sunlight that crosses it, Φ = T · A⊥, spread over the area A_r it lands on: irradiance Φ/A_r
// (the area ratio). f64 reference: crates/pool/src/caustics.rs.
//
// Indexed grid, one refraction per vertex: vertex v is grid point (v mod (n + 1), v div (n + 1)),
// drawn at its landing point in the net. Inside a triangle the surface position is an affine
// function of the net position, so its screen derivatives are that map's exact Jacobian: the
// surface area A⊥ that one texel of the net receives light from is |(∂s/∂x × ∂s/∂y) · L|, and
// the irradiance is T · A⊥ / (texel area), constant over the triangle as on the CPU.

struct CausticOut {
    @builtin(position) clip: vec4<f32>,
    // Surface point the light crossed, pool metres.
    @location(0) surface: vec3<f32>,
    @location(1) transmittance: f32,
    // 1 where this vertex's light landed; a triangle with any other corner is dropped.
    @location(2) valid: f32,
    // One-hot wall of the landing (west, east, north, south); all 0 on the floor. A triangle
    // whose corners land on two different walls would cut across the net's empty corner.
    @location(3) wall: vec4<f32>,
}

@vertex
fn vs_main(@builtin(vertex_index) v: u32) -> CausticOut {
    let n = u32(pool.grid.z);
    let w = water_at(grid_rest(v % (n + 1u), v / (n + 1u), pool.grid.z));
    let l = frame.sun.xyz;
    let ior = pool.ripple2.z;
    var out: CausticOut;
    out.surface = w.position;
    out.valid = 0.0;
    out.transmittance = 0.0;
    out.wall = vec4<f32>(0.0);
    out.clip = vec4<f32>(w.position.x / pool.net.x, -w.position.z / pool.net.y, 0.5, 1.0);
    let cos_i = dot(w.normal, l);
    let t = refract_dir(-l, w.normal, N_AIR, ior);
    if cos_i <= 0.0 || t.w == 0.0 {
        return out;
    }
    let hit = box_inside(w.position, t.xyz);
    if hit.face == FACE_NONE {
        return out;
    }
    let q = net_coords(hit.face, hit.point);
    // Net row 0 is its −z edge, the top of the texture: NDC y = −z / half_z.
    out.clip = vec4<f32>(q.x / pool.net.x, -q.y / pool.net.y, 0.5, 1.0);
    out.valid = 1.0;
    out.transmittance = 1.0 - fresnel_reflectance(cos_i, N_AIR, ior);
    if hit.face != FACE_FLOOR {
        out.wall[hit.face - 1u] = 1.0;
    }
    return out;
}

@fragment
fn fs_main(in: CausticOut) -> @location(0) vec4<f32> {
    // Derivatives first, in uniform control flow.
    let ds = cross(dpdx(in.surface), dpdy(in.surface));
    let texel = 4.0 * pool.net.x * pool.net.y / (pool.net.z * pool.net.w);
    let walls = dot(step(vec4<f32>(1e-6), in.wall), vec4<f32>(1.0));
    if in.valid < 0.9999 || walls > 1.5 {
        discard;
    }
    return vec4<f32>(in.transmittance * abs(dot(ds, frame.sun.xyz)) / texel, 0.0, 0.0, 1.0);
}
