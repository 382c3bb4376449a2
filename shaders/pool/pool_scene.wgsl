// Pool scene pass: everything but the water, ray traced per pixel in a full-screen triangle:
// the analytic spheres, the tub (coping, outer walls) and, through its opening, the tiled walls
// and floor. Writes depth, so the water surface drawn next is hidden behind a sphere above it
// and hides what lies below it.

struct SceneOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) ndc: vec2<f32>,
}

@vertex
fn vs_main(@builtin(vertex_index) v: u32) -> SceneOut {
    let xy = vec2<f32>(f32((v << 1u) & 2u), f32(v & 2u)) * 2.0 - vec2<f32>(1.0);
    var out: SceneOut;
    out.clip = vec4<f32>(xy, 0.0, 1.0);
    out.ndc = xy;
    return out;
}

struct FragOut {
    @location(0) colour: vec4<f32>,
    @builtin(frag_depth) depth: f32,
}

// The tub's outside: ray against the box [lo, hi] from outside (slabs). vec4(normal, s), s < 0
// when missed.
fn tub_entry(o: vec3<f32>, d: vec3<f32>) -> vec4<f32> {
    let w = pool.ripple2.w;
    let lo = vec3<f32>(-pool.box_.x - w, pool.box_.z - w, -pool.box_.y - w);
    let hi = vec3<f32>(pool.box_.x + w, pool.box_.w, pool.box_.y + w);
    let inv = 1.0 / d;
    let t0 = (lo - o) * inv;
    let t1 = (hi - o) * inv;
    let tmin = min(t0, t1);
    let tmax = max(t0, t1);
    let enter = max(max(tmin.x, tmin.y), tmin.z);
    let exit = min(min(tmax.x, tmax.y), tmax.z);
    if enter > exit || exit < 0.0 {
        return vec4<f32>(0.0, 0.0, 0.0, NO_HIT);
    }
    var n = vec3<f32>(-sign(d.x), 0.0, 0.0);
    if enter == tmin.y {
        n = vec3<f32>(0.0, -sign(d.y), 0.0);
    } else if enter == tmin.z {
        n = vec3<f32>(0.0, 0.0, -sign(d.z));
    }
    return vec4<f32>(n, max(enter, 0.0));
}

fn in_opening(p: vec3<f32>) -> bool {
    return abs(p.x) < pool.box_.x && abs(p.z) < pool.box_.y;
}

@fragment
fn fs_main(in: SceneOut) -> FragOut {
    let o = frame.eye.xyz;
    let d = ray_dir(in.ndc);
    let l = frame.sun.xyz;
    var out: FragOut;
    out.colour = vec4<f32>(sky_colour(d), 1.0);
    out.depth = 1.0;
    var s_hit = 1e30;
    var colour = vec3<f32>(0.0);
    // The tub, and through its opening the inside of the pool.
    let inside_now = in_opening(o) && o.y < pool.box_.w && o.y > pool.box_.z;
    var entry = vec4<f32>(0.0, 1.0, 0.0, 0.0);
    if !inside_now {
        entry = tub_entry(o, d);
    }
    if entry.w >= 0.0 {
        let p = o + d * entry.w;
        if inside_now || (entry.y > 0.5 && in_opening(p)) {
            let wall = box_inside(p, d);
            if wall.face != FACE_NONE {
                s_hit = entry.w + wall.s;
                let albedo = tile_albedo(wall.face, wall.point);
                colour = phong(albedo, max(dot(wall.normal, l), 0.0), wall.normal, l, -d, 0.3);
            }
        } else {
            s_hit = entry.w;
            // Coping stones on top, darker tiles outside.
            var albedo = vec3<f32>(0.78, 0.74, 0.66);
            if entry.y < 0.5 {
                // Outer walls: the same tiles, laid in the wall's own plane, a shade darker.
                let face = select(FACE_NORTH, FACE_EAST, abs(entry.x) > 0.5);
                albedo = tile_albedo(face, p) * 0.8;
            }
            colour = phong(albedo, max(dot(entry.xyz, l), 0.0), entry.xyz, l, -d, 0.2);
        }
    }
    // The ground the tub stands on (the table in AR, where the camera image shows instead).
    let ground_y = pool.box_.z - pool.ripple2.w;
    if s_hit > 1e29 && d.y < 0.0 && o.y > ground_y && pool.counts.w == 0u {
        s_hit = (ground_y - o.y) / d.y;
        let up = vec3<f32>(0.0, 1.0, 0.0);
        colour = phong(vec3<f32>(0.5, 0.48, 0.42), max(l.y, 0.0), up, l, -d, 0.0);
    }
    let ball = nearest_sphere(o, d);
    if ball.x > 0.0 && ball.x < s_hit {
        let sp = pool.spheres[u32(ball.y)];
        let p = o + d * ball.x;
        let n = (p - sp.center_radius.xyz) / sp.center_radius.w;
        s_hit = ball.x;
        colour = phong(sp.colour.rgb, max(dot(n, l), 0.0), n, l, -d, 1.0);
    }
    if s_hit < 1e29 {
        out.colour = vec4<f32>(colour, 1.0);
        out.depth = depth_of(o + d * s_hit);
    } else if pool.counts.w == 1u {
        // AR: the camera image stays where the pool is not.
        discard;
    }
    return out;
}
