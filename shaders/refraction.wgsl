// Refraction of the real table (f64 reference: effects/refraction.rs). The view ray is bent
// by Snell's law (n = 1.333) through the surface normal, followed down to the table plane
// `depth` below the rest level and projected into the camera image. Outside the image the
// sample is clamped to the edge and fades to the unrefracted one over EDGE_FADE.
// Returns the table colour (rgb) and the length of the path in the water (w).

fn table_point_straight(p: vec3<f32>, view: vec3<f32>) -> vec3<f32> {
    let hit = ray_plane(p, view, vec4<f32>(0.0, 1.0, 0.0, fx.table.x));
    return select(p, hit.xyz, hit.w > 0.0);
}

fn refracted_table(p: vec3<f32>, view: vec3<f32>, n: vec3<f32>) -> vec4<f32> {
    let straight_point = table_point_straight(p, view);
    let straight = camera_uv(straight_point).xy;
    let t = refract_dir(view, n, N_AIR, N_WATER);
    let hit = ray_plane(p, t.xyz, vec4<f32>(0.0, 1.0, 0.0, fx.table.x));
    if t.w == 0.0 || hit.w <= 0.0 {
        // No table along the refracted ray: the unrefracted sample, the ray's path along the
        // view direction (ar_water puts q there).
        return vec4<f32>(sample_camera(straight), length(straight_point - p));
    }
    let uv = camera_uv(hit.xyz);
    let w = edge_weight(uv.xy) * uv.z;
    let refracted = sample_camera(uv.xy);
    if w >= 1.0 {
        return vec4<f32>(refracted, hit.w);
    }
    return vec4<f32>(mix(sample_camera(straight), refracted, w), hit.w);
}
