// The pool scene: shared structs, the moving water, rays against the analytic spheres and the
// tiled box, shading. Appended to common.wgsl and optics.wgsl; each pool pass file follows it.
// f32 mirrors of crates/pool/src/{water,geometry,trace}.rs, which are the f64 references.
//
// Pool space: metres, y up, the water's rest level at y = 0, the pool centred on the origin.
// The frame uniform (group 0) is in pool space: in AR its view-projection already contains the
// model transform that stands the pool on the table, and eye and sun are given in pool space.
// No absolute time reaches this file: wave phases come reduced, ripple rings come with ages.

// POOL_MAX_SPHERES, POOL_MAX_RINGS, the faces of the box FACE_FLOOR ... FACE_SOUTH (as
// pool::Face) and FACE_NONE, ABSORPTION and the Phong and tile constants: generated from the
// Rust values (pool::wgsl::prelude).
const NO_HIT: f32 = -1.0;


struct PoolSphere {
    // Centre (pool space) and radius, metres.
    center_radius: vec4<f32>,
    // Linear RGB albedo.
    colour: vec4<f32>,
}

struct PoolRing {
    // Centre x, z (metres), age a_j (s), amplitude A_j (m).
    center_age_amp: vec4<f32>,
    // x: radius R of the sphere that made it (m).
    source: vec4<f32>,
}

// pool::gpu::PoolUniform.
struct Pool {
    // half_x, half_z, floor_y, rim_y (metres).
    box_: vec4<f32>,
    // Ripple k (rad/m), ω (rad/s), group speed (m/s), 1/τ (1/s).
    ripple: vec4<f32>,
    // Ripple σ (m), core ε (m), refractive index of the water, wall thickness (m).
    ripple2: vec4<f32>,
    // Half extents of the unfolded net (m), caustics map texels along x and z.
    net: vec4<f32>,
    // Half extents of the rest-point grids (m, the pool's), caustic grid cells per side, water
    // grid cells per side.
    grid: vec4<f32>,
    // Spheres, rings, waves, 1 when drawn over the AR camera image.
    counts: vec4<u32>,
    spheres: array<PoolSphere, 8>,
    rings: array<PoolRing, 256>,
}

@group(1) @binding(0) var<uniform> pool: Pool;
@group(2) @binding(0) var caustic_map: texture_2d<f32>;
@group(2) @binding(1) var caustic_sampler: sampler;

// ---- the water -----------------------------------------------------------------------------

// Ripple height η and gradient at horizontal point x: vec3(η, ∂η/∂x, ∂η/∂z) (pool::water).
fn ripples(x: vec2<f32>) -> vec3<f32> {
    let k = pool.ripple.x;
    let omega = pool.ripple.y;
    let cg = pool.ripple.z;
    let inv_tau = pool.ripple.w;
    let sigma2 = pool.ripple2.x * pool.ripple2.x;
    let eps2 = pool.ripple2.y * pool.ripple2.y;
    var out = vec3<f32>(0.0);
    for (var i = 0u; i < pool.counts.y; i = i + 1u) {
        let ring = pool.rings[i];
        let d = x - ring.center_age_amp.xy;
        let age = ring.center_age_amp.z;
        let r = sqrt(dot(d, d) + eps2);
        let big_r = ring.source.x;
        let spread = sqrt(big_r / (big_r + r));
        let u = r - cg * age;
        let envelope = exp(-u * u / (2.0 * sigma2));
        let phase = k * r - omega * age;
        let c = cos(phase);
        let a = ring.center_age_amp.w * exp(-age * inv_tau);
        let dspread = -spread / (2.0 * (big_r + r));
        let dh_dr = a * (dspread * envelope * c - spread * u / sigma2 * envelope * c
            - spread * envelope * k * sin(phase));
        out += vec3<f32>(a * spread * envelope * c, dh_dr * d / r);
    }
    return out;
}

struct WaterPoint {
    position: vec3<f32>,
    normal: vec3<f32>,
}

// Rest point (i, j) of a grid of n × n cells over the rest-point area.
fn grid_rest(i: u32, j: u32, n: f32) -> vec2<f32> {
    return vec2<f32>(
        -pool.grid.x + 2.0 * pool.grid.x * f32(i) / n,
        -pool.grid.y + 2.0 * pool.grid.y * f32(j) / n,
    );
}

// The surface point the waves carry rest point `rest` to, lifted by the ripples, with its
// normal (slopes add: Gerstner's −n.xz/n.y plus ∇η). Held inside the walls, and pinned to a
// wall when the rest point lies on it, so the mesh always reaches the walls
// (pool::PoolScene::mesh_point).
fn water_at(rest: vec2<f32>) -> WaterPoint {
    var p = vec3<f32>(rest.x, 0.0, rest.y);
    for (var i = 0u; i < pool.counts.z; i = i + 1u) {
        p += gerstner(waves[i], rest);
    }
    let g = normalize(surface_frame(rest, pool.counts.z, 0.0).up);
    let rip = ripples(p.xz);
    let slope = -g.xz / g.y + rip.yz;
    var out: WaterPoint;
    let half = pool.box_.xy;
    let on_wall = abs(rest) >= half * (1.0 - 1e-6);
    let xz = select(clamp(p.xz, -half, half), sign(rest) * half, on_wall);
    out.position = vec3<f32>(xz.x, p.y + rip.x, xz.y);
    out.normal = normalize(vec3<f32>(-slope.x, 1.0, -slope.y));
    return out;
}

// ---- rays ------------------------------------------------------------------------------------

// Distance to the nearest crossing of a sphere beyond a small epsilon, or NO_HIT.
fn hit_sphere(o: vec3<f32>, d: vec3<f32>, s: PoolSphere) -> f32 {
    let oc = o - s.center_radius.xyz;
    let b = dot(d, oc);
    let q = dot(oc, oc) - s.center_radius.w * s.center_radius.w;
    let disc = b * b - q;
    if disc < 0.0 {
        return NO_HIT;
    }
    let root = sqrt(disc);
    let near = -b - root;
    let far = -b + root;
    if near > 1e-4 {
        return near;
    }
    if far > 1e-4 {
        return far;
    }
    return NO_HIT;
}

// vec2(distance, index) of the nearest sphere, distance NO_HIT when none.
fn nearest_sphere(o: vec3<f32>, d: vec3<f32>) -> vec2<f32> {
    var best = vec2<f32>(NO_HIT, 0.0);
    for (var i = 0u; i < pool.counts.x; i = i + 1u) {
        let s = hit_sphere(o, d, pool.spheres[i]);
        if s > 0.0 && (best.x < 0.0 || s < best.x) {
            best = vec2<f32>(s, f32(i));
        }
    }
    return best;
}

struct BoxHit {
    s: f32,
    point: vec3<f32>,
    normal: vec3<f32>,
    face: u32,
}

// Where a ray from inside the box leaves it through a wall or the floor; face FACE_NONE when it
// leaves through the open top (pool::PoolBox::hit_inside).
fn box_inside(o: vec3<f32>, d: vec3<f32>) -> BoxHit {
    var h: BoxHit;
    h.s = 1e30;
    h.face = FACE_NONE;
    if d.x > 0.0 {
        h.s = (pool.box_.x - o.x) / d.x;
        h.face = FACE_EAST;
    } else if d.x < 0.0 {
        h.s = (-pool.box_.x - o.x) / d.x;
        h.face = FACE_WEST;
    }
    if d.z > 0.0 {
        let s = (pool.box_.y - o.z) / d.z;
        if s < h.s {
            h.s = s;
            h.face = FACE_SOUTH;
        }
    } else if d.z < 0.0 {
        let s = (-pool.box_.y - o.z) / d.z;
        if s < h.s {
            h.s = s;
            h.face = FACE_NORTH;
        }
    }
    if d.y < 0.0 {
        let s = (pool.box_.z - o.y) / d.y;
        if s < h.s {
            h.s = s;
            h.face = FACE_FLOOR;
        }
    } else if d.y > 0.0 {
        let s = (pool.box_.w - o.y) / d.y;
        if s < h.s {
            h.s = s;
            h.face = FACE_NONE;
        }
    }
    h.s = max(h.s, 0.0);
    h.point = o + d * h.s;
    h.normal = face_normal(h.face);
    return h;
}

fn face_normal(face: u32) -> vec3<f32> {
    switch face {
        case 0u: { return vec3<f32>(0.0, 1.0, 0.0); }
        case 1u: { return vec3<f32>(1.0, 0.0, 0.0); }
        case 2u: { return vec3<f32>(-1.0, 0.0, 0.0); }
        case 3u: { return vec3<f32>(0.0, 0.0, 1.0); }
        case 4u: { return vec3<f32>(0.0, 0.0, -1.0); }
        default: { return vec3<f32>(0.0); }
    }
}

// The point's coordinates in the box's unfolded net (pool::PoolBox::net_coords).
fn net_coords(face: u32, p: vec3<f32>) -> vec2<f32> {
    let up = p.y - pool.box_.z;
    switch face {
        case 1u: { return vec2<f32>(-pool.box_.x - up, p.z); }
        case 2u: { return vec2<f32>(pool.box_.x + up, p.z); }
        case 3u: { return vec2<f32>(p.x, -pool.box_.y - up); }
        case 4u: { return vec2<f32>(p.x, pool.box_.y + up); }
        default: { return p.xz; }
    }
}

// ---- shading ---------------------------------------------------------------------------------

// Tile albedo (pool::trace::tile_albedo).
fn tile_albedo(face: u32, p: vec3<f32>) -> vec3<f32> {
    var uv = p.xz;
    if face == FACE_EAST || face == FACE_WEST {
        uv = p.zy;
    } else if face == FACE_NORTH || face == FACE_SOUTH {
        uv = p.xy;
    }
    let f = uv / TILE - floor(uv / TILE);
    if min(f.x, f.y) * TILE < GROUT {
        return vec3<f32>(0.75, 0.78, 0.76);
    }
    let band = face != FACE_FLOOR && p.y > pool.box_.w - 2.0 * TILE;
    let lane = face == FACE_FLOOR && abs(p.z) < TILE && abs(p.x) < pool.box_.x - TILE;
    if band || lane {
        return vec3<f32>(0.03, 0.12, 0.35);
    }
    return vec3<f32>(0.55, 0.78, 0.82);
}

fn phong(albedo: vec3<f32>, light: f32, n: vec3<f32>, l: vec3<f32>, to_eye: vec3<f32>, spec: f32) -> vec3<f32> {
    let r = reflect_dir(-l, n);
    let s = select(0.0, SPECULAR * spec * pow(max(dot(r, to_eye), 0.0), SHININESS), light > 0.0);
    return albedo * (AMBIENT + DIFFUSE * light) + vec3<f32>(s);
}

// Irradiance / E of the caustics map at a point of a face.
fn caustic_light(face: u32, p: vec3<f32>) -> f32 {
    let q = net_coords(face, p);
    let uv = (q / pool.net.xy) * 0.5 + vec2<f32>(0.5);
    return textureSampleLevel(caustic_map, caustic_sampler, uv, 0.0).r;
}

// Colour along a ray in the air from a point inside the pool's opening (pool::trace::trace_air).
fn trace_air(o: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    let l = frame.sun.xyz;
    let wall = box_inside(o, d);
    let ball = nearest_sphere(o, d);
    if ball.x > 0.0 && (wall.face == FACE_NONE || ball.x < wall.s) {
        let s = pool.spheres[u32(ball.y)];
        let p = o + d * ball.x;
        let n = (p - s.center_radius.xyz) / s.center_radius.w;
        return phong(s.colour.rgb, max(dot(n, l), 0.0), n, l, -d, 1.0);
    }
    if wall.face != FACE_NONE {
        let albedo = tile_albedo(wall.face, wall.point);
        return phong(albedo, max(dot(wall.normal, l), 0.0), wall.normal, l, -d, 0.3);
    }
    return sky_colour(d);
}

// Colour along a ray under the water: lit by the caustics map, absorbed along the path
// (pool::trace::trace_water).
fn trace_water(o: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    let wall = box_inside(o, d);
    if wall.face == FACE_NONE {
        return sky_colour(d);
    }
    let ball = nearest_sphere(o, d);
    var s = wall.s;
    var c: vec3<f32>;
    if ball.x > 0.0 && ball.x < wall.s {
        let sp = pool.spheres[u32(ball.y)];
        let p = o + d * ball.x;
        let n = (p - sp.center_radius.xyz) / sp.center_radius.w;
        let ior = pool.ripple2.z;
        let sun = refract_dir(-frame.sun.xyz, vec3<f32>(0.0, 1.0, 0.0), N_AIR, ior);
        let to_sun = select(vec3<f32>(0.0, 1.0, 0.0), -sun.xyz, sun.w > 0.0);
        let t = 1.0 - fresnel_reflectance(frame.sun.y, N_AIR, ior);
        c = phong(sp.colour.rgb, t * max(dot(n, to_sun), 0.0), n, to_sun, -d, 1.0);
        s = ball.x;
    } else {
        let albedo = tile_albedo(wall.face, wall.point);
        c = albedo * (AMBIENT + DIFFUSE * caustic_light(wall.face, wall.point));
    }
    return c * exp(-ABSORPTION * s);
}

// Depth of a pool-space point, for frag_depth.
fn depth_of(p: vec3<f32>) -> f32 {
    let c = frame.view_proj * vec4<f32>(p, 1.0);
    return clamp(c.z / c.w, 0.0, 1.0);
}
