// Pool water pass: the surface grid, displaced in the vertex shader by the Gerstner waves and
// the ripples; each fragment splits the view ray (full Fresnel, Snell, total internal
// reflection from below) and traces both rays against the spheres and the box
// (pool::trace::shade_water is the f64 reference).

struct WaterOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) position: vec3<f32>,
    @location(1) rest: vec2<f32>,
}

@vertex
fn vs_main(@builtin(vertex_index) v: u32) -> WaterOut {
    let n = u32(pool.net.w);
    let cell = v / 6u;
    let corner = v % 6u;
    // Two triangles per cell: (00, 10, 11) and (00, 11, 01).
    var offsets = array<vec2<u32>, 6>(
        vec2<u32>(0u, 0u), vec2<u32>(1u, 0u), vec2<u32>(1u, 1u),
        vec2<u32>(0u, 0u), vec2<u32>(1u, 1u), vec2<u32>(0u, 1u),
    );
    let ij = vec2<u32>(cell % n, cell / n) + offsets[corner];
    let rest = vec2<f32>(
        -pool.box_.x + 2.0 * pool.box_.x * f32(ij.x) / f32(n),
        -pool.box_.y + 2.0 * pool.box_.y * f32(ij.y) / f32(n),
    );
    let w = water_at(rest);
    var out: WaterOut;
    out.clip = frame.view_proj * vec4<f32>(w.position, 1.0);
    out.position = w.position;
    out.rest = rest;
    return out;
}

@fragment
fn fs_main(in: WaterOut) -> @location(0) vec4<f32> {
    let normal = water_at(in.rest).normal;
    let d = normalize(in.position - frame.eye.xyz);
    let ior = pool.ripple2.z;
    let from_below = dot(d, normal) > 0.0;
    var n1 = N_AIR;
    var n2 = ior;
    if from_below {
        n1 = ior;
        n2 = N_AIR;
    }
    let r = fresnel_reflectance(dot(d, normal), n1, n2);
    let rdir = reflect_dir(d, normal);
    let t = refract_dir(d, normal, n1, n2);
    var colour: vec3<f32>;
    if from_below {
        colour = r * trace_water(in.position, rdir);
        if t.w > 0.0 {
            colour += (1.0 - r) * trace_air(in.position, t.xyz);
        }
    } else {
        colour = r * trace_air(in.position, rdir);
        if t.w > 0.0 {
            colour += (1.0 - r) * trace_water(in.position, t.xyz);
        }
    }
    return vec4<f32>(colour, 1.0);
}
