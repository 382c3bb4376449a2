// Pool caustics pass: the water surface grid's triangles, refracted to the box and drawn into
// the caustics map (the box's unfolded net) with additive blending. Each triangle adds the
// sunlight that crosses it, Φ = T · A⊥, spread over the area A_r it lands on: irradiance Φ/A_r
// (the area ratio). f64 reference: crates/render/src/pool/caustics.rs.
//
// No vertex buffer: vertex v of the draw is corner v % 3 of triangle v / 3; triangle 2c and
// 2c + 1 split grid cell c. Every vertex refracts all three corners of its triangle, because
// the area ratio is a property of the whole triangle.

struct Landing {
    ok: bool,
    surface: vec3<f32>,
    transmittance: f32,
    face: u32,
    net: vec2<f32>,
}

fn land(rest: vec2<f32>) -> Landing {
    var out: Landing;
    out.ok = false;
    let w = water_at(rest);
    let l = frame.sun.xyz;
    let ior = pool.ripple2.z;
    let cos_i = dot(w.normal, l);
    if cos_i <= 0.0 {
        return out;
    }
    let t = refract_dir(-l, w.normal, N_AIR, ior);
    if t.w == 0.0 {
        return out;
    }
    let hit = box_inside(w.position, t.xyz);
    if hit.face == FACE_NONE {
        return out;
    }
    out.ok = true;
    out.surface = w.position;
    out.transmittance = 1.0 - fresnel_reflectance(cos_i, N_AIR, ior);
    out.face = hit.face;
    out.net = net_coords(hit.face, hit.point);
    return out;
}

struct CausticOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) @interpolate(flat) irradiance: f32,
}

@vertex
fn vs_main(@builtin(vertex_index) v: u32) -> CausticOut {
    let n = u32(pool.grid.z);
    let tri = v / 3u;
    let corner = v % 3u;
    let cell = tri / 2u;
    let ci = cell % n;
    let cj = cell / n;
    // The quad's corners 00, 10, 11, 01; triangles (0, 1, 2) and (0, 2, 3) as on the CPU.
    var quad = array<vec2<u32>, 4>(
        vec2<u32>(ci, cj), vec2<u32>(ci + 1u, cj), vec2<u32>(ci + 1u, cj + 1u), vec2<u32>(ci, cj + 1u),
    );
    var idx = vec3<u32>(0u, 1u, 2u);
    if tri % 2u == 1u {
        idx = vec3<u32>(0u, 2u, 3u);
    }
    let a = land(grid_rest(quad[idx.x].x, quad[idx.x].y, pool.grid.z));
    let b = land(grid_rest(quad[idx.y].x, quad[idx.y].y, pool.grid.z));
    let c = land(grid_rest(quad[idx.z].x, quad[idx.z].y, pool.grid.z));
    var out: CausticOut;
    // A degenerate triangle outside the map draws nothing.
    out.clip = vec4<f32>(2.0, 2.0, 0.5, 1.0);
    out.irradiance = 0.0;
    if !(a.ok && b.ok && c.ok) {
        return out;
    }
    // Corners on two different walls would cut across the net's empty corner: dropped.
    let fa = select(a.face, 99u, a.face == FACE_FLOOR);
    let fb = select(b.face, 99u, b.face == FACE_FLOOR);
    let fc = select(c.face, 99u, c.face == FACE_FLOOR);
    let walls_differ = (fa != 99u && fb != 99u && fa != fb) || (fa != 99u && fc != 99u && fa != fc)
        || (fb != 99u && fc != 99u && fb != fc);
    if walls_differ {
        return out;
    }
    let a_perp = 0.5 * abs(dot(cross(b.surface - a.surface, c.surface - a.surface), frame.sun.xyz));
    let flux = (a.transmittance + b.transmittance + c.transmittance) / 3.0 * a_perp;
    let e1 = b.net - a.net;
    let e2 = c.net - a.net;
    let area = 0.5 * abs(e1.x * e2.y - e2.x * e1.y);
    if area <= 0.0 {
        return out;
    }
    var q = a.net;
    if corner == 1u {
        q = b.net;
    } else if corner == 2u {
        q = c.net;
    }
    // Net row 0 is its −z edge, the top of the texture: NDC y = −z / half_z.
    out.clip = vec4<f32>(q.x / pool.net.x, -q.y / pool.net.y, 0.5, 1.0);
    out.irradiance = flux / area;
    return out;
}

@fragment
fn fs_main(in: CausticOut) -> @location(0) vec4<f32> {
    return vec4<f32>(in.irradiance, 0.0, 0.0, 1.0);
}
