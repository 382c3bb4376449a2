// Pool water pass: the surface grid, displaced in the vertex shader by the Gerstner waves and
// the ripples; each fragment splits the view ray (full Fresnel, Snell, total internal
// reflection from below) and traces both rays against the spheres and the box
// (pool::trace::shade_water is the f64 reference).

struct WaterOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) position: vec3<f32>,
    @location(1) rest: vec2<f32>,
}

// Indexed draw: vertex v is grid point (v mod (n + 1), v div (n + 1)), evaluated once.
@vertex
fn vs_main(@builtin(vertex_index) v: u32) -> WaterOut {
    let n = u32(pool.grid.w);
    let rest = grid_rest(v % (n + 1u), v / (n + 1u), pool.grid.w);
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
