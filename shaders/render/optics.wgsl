// Optics of the water surface: f32 mirrors of crates/render/src/optics.rs (the f64 reference
// they are tested against). Included by the water and effect passes.
//
// Conventions as in optics.rs: unit vectors; `n1` is the index on the side the ray comes from.

// N_AIR, N_WATER: from the generated prelude (render::optics).

// Unpolarised reflectance by the full Fresnel equations (not Schlick's approximation), 1.0 under total internal
// reflection. Rs = ((n1 ci − n2 ct)/(n1 ci + n2 ct))², Rp = ((n1 ct − n2 ci)/(n1 ct + n2 ci))².
fn fresnel_reflectance(cos_i_in: f32, n1: f32, n2: f32) -> f32 {
    let cos_i = min(abs(cos_i_in), 1.0);
    let eta = n1 / n2;
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    return fresnel_of_cosines(cos_i, sqrt(1.0 - sin2_t), n1, n2);
}

// The unpolarised reflectance from the incidence and refraction cosines.
fn fresnel_of_cosines(cos_i: f32, cos_t: f32, n1: f32, n2: f32) -> f32 {
    // Each of the four products once (the same values as written out in both ratios).
    let i1 = n1 * cos_i;
    let i2 = n2 * cos_i;
    let t1 = n1 * cos_t;
    let t2 = n2 * cos_t;
    let rs = (i1 - t2) / (i1 + t2);
    let rp = (t1 - i2) / (t1 + i2);
    return 0.5 * (rs * rs + rp * rp);
}

// Schlick's approximation, only for comparison with the full equations.
fn schlick_reflectance(cos_i_in: f32, n1: f32, n2: f32) -> f32 {
    let r0 = ((n1 - n2) / (n1 + n2)) * ((n1 - n2) / (n1 + n2));
    var c = min(abs(cos_i_in), 1.0);
    if n1 > n2 {
        let sin2_t = (n1 / n2) * (n1 / n2) * (1.0 - c * c);
        if sin2_t >= 1.0 {
            return 1.0;
        }
        c = sqrt(1.0 - sin2_t);
    }
    return r0 + (1.0 - r0) * pow(1.0 - c, 5.0);
}

// Mirror reflection of direction d about normal n (either orientation).
fn reflect_dir(d: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    return d - 2.0 * dot(d, n) * n;
}

// Snell refraction of d through a surface with normal n (turned to face the ray), from n1 into
// n2. Returns vec4(t, 1) with the transmitted unit direction, or vec4(0, 0, 0, 0) under total
// internal reflection (WGSL has no optionals).
fn refract_dir(d: vec3<f32>, n_in: vec3<f32>, n1: f32, n2: f32) -> vec4<f32> {
    // The normal turned to face the ray is side·n_in; the side goes on the scalars (one dot
    // product, no turned vector): the same values bit for bit, as negation is exact.
    let facing = dot(d, n_in);
    let side = select(1.0, -1.0, facing > 0.0);
    let eta = n1 / n2;
    let cos_i = -(side * facing);
    let k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
    if k < 0.0 {
        return vec4<f32>(0.0);
    }
    return vec4<f32>(eta * d + ((eta * cos_i - sqrt(k)) * side) * n_in, 1.0);
}

// The unit view ray d entering the water through the unit normal n (air to water): the
// refracted direction (xyz: refract_dir's) and the Fresnel reflectance (w:
// fresnel_reflectance's at the cosine max(−d·n, 0)), from one dot product and one square
// root, since refract_dir's k = 1 − η²(1 − cos²) is fresnel_reflectance's cos_t² (from air
// there is no total internal reflection: k ≥ 1 − η² > 0). A normal turned away from the eye
// (d·n ≥ 0) reflects everything (R = 1, what a cosine of 0 gives) and refracts about the
// turned normal, as the two functions do. The cosine is clamped to 1 as fresnel_reflectance
// clamps it, which moves the refraction only where d·n rounds past ±1.
fn water_entry(d: vec3<f32>, n: vec3<f32>) -> vec4<f32> {
    let facing = dot(d, n);
    let side = select(1.0, -1.0, facing > 0.0);
    let cos_i = min(-(side * facing), 1.0);
    let eta = N_AIR / N_WATER;
    let cos_t = sqrt(1.0 - eta * eta * (1.0 - cos_i * cos_i));
    let t = eta * d + ((eta * cos_i - cos_t) * side) * n;
    let r = fresnel_of_cosines(cos_i, cos_t, N_AIR, N_WATER);
    return vec4<f32>(t, select(r, 1.0, facing >= 0.0));
}

// Where the ray o + s d (s ≥ 0) meets the plane dot(p.xyz, x) + p.w = 0: vec4(point, s), or
// s < 0 when it misses (parallel or pointing away).
fn ray_plane(o: vec3<f32>, d: vec3<f32>, p: vec4<f32>) -> vec4<f32> {
    let denom = dot(p.xyz, d);
    if abs(denom) < 1e-12 {
        return vec4<f32>(o, -1.0);
    }
    let s = -(dot(p.xyz, o) + p.w) / denom;
    return vec4<f32>(o + s * d, s);
}
