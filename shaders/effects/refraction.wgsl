// Refraction of the real table (f64 reference: effects/refraction.rs). The view ray is bent
// by Snell's law (n = N_WATER) through the surface normal, followed down to the table plane
// `depth` below the rest level and projected into the camera image. Outside the image the
// refracted point is clamped to the edge and fades to the unrefracted one over EDGE_FADE:
// weight w as in the reference, but one texture sample at the point w of the way from the
// unrefracted uv to the clamped refracted one, where the reference blends the two samples
// (each sample of the camera image is a large part of this pass's cost on lavapipe). The two
// agree wherever w is 0 or 1; inside the band they differ by at most the image's colour change
// along that segment (in the demo view, under 1 % of the water's pixels are in the band).
// Returns the table colour (rgb) and the length of the path in the water (w).

// Where the ray from p along unit d meets the table plane (y = −table depth): its (x, z) and
// the distance s along d, as ray_plane gives them for that plane (s = −1: parallel to it; s ≤
// 0: none ahead), with the plane's normal (0, 1, 0) folded in: one division and two products.
fn table_hit(p: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    let s = select(-1.0, -(p.y + fx.table.x) / d.y, abs(d.y) >= 1e-12);
    return vec3<f32>(p.xz + s * d.xz, s);
}

// The camera-image point of the table straight behind screen uv `screen`, homogeneous: the map
// fx.straight_image formed on the CPU, (s, t, 1) -> (u w, v w, w) (three columns where a
// ray-plane solve and camera_uv took 46 operations). Any positive multiple names the same
// point: the AR water's vertices hand the pixels this map of their clip position
// (straight_image_of_clip), which the rasteriser's perspective-correct interpolation turns into
// the pixel's own map times its clip w, so a pixel forms none of it.
fn straight_image_at(screen: vec2<f32>) -> vec3<f32> {
    return fx.straight_image[0].xyz * screen.x + fx.straight_image[1].xyz * screen.y
        + fx.straight_image[2].xyz;
}

// straight_image_at of a vertex's screen point times its clip w, from its clip position: the
// screen uv times w is (½(x + w), ½(w − y)) (v grows downwards), so the product is linear in
// the clip coordinates, exact under the rasteriser's interpolation and its near-plane clipping
// (both linear in clip space), and w > 0 for every pixel drawn keeps the sign of the last
// component.
fn straight_image_of_clip(clip: vec4<f32>) -> vec3<f32> {
    return fx.straight_image[0].xyz * (0.5 * (clip.x + clip.w))
        + fx.straight_image[1].xyz * (0.5 * (clip.w - clip.y)) + fx.straight_image[2].xyz * clip.w;
}

// The table straight through the water at this pixel, as if there were no refraction: xy,
// the camera-image uv of the table point on the eye's ray through the pixel whose
// straight_image_at (any positive multiple) is `h`; the image's centre where that point is
// behind the camera, where no table is ahead (the map is zero) or where the view does not run
// down (as table_hit finds no plane for |d.y| < 1e-12). z, the path from p along the unit view
// ray down to the table (0 where the table is not ahead of p: a trough below it).
fn straight_through(p: vec3<f32>, view: vec3<f32>, h: vec3<f32>) -> vec3<f32> {
    let down = view.y <= -1e-12;
    let uv = select(vec2<f32>(0.5), h.xy / h.z, down && h.z > 0.0);
    // Where the view does not run down the division's value is never used.
    let s = -(p.y + fx.table.x) / view.y;
    return vec3<f32>(uv, select(0.0, max(s, 0.0), down));
}

fn refracted_table(p: vec3<f32>, view: vec3<f32>, screen: vec2<f32>, n: vec3<f32>) -> vec4<f32> {
    return refracted_table_along(p, view, straight_image_at(screen), refract_dir(view, n, N_AIR, N_WATER));
}

// refracted_table with the refracted ray t = refract_dir(view, n, N_AIR, N_WATER) and the
// pixel's straight_image_at (`straight_h`, any positive multiple) given: the AR water needs t
// again for the table point the caustics light, refracts once, and has the map interpolated.
fn refracted_table_along(p: vec3<f32>, view: vec3<f32>, straight_h: vec3<f32>, t: vec4<f32>) -> vec4<f32> {
    let hit = table_hit(p, t.xyz);
    // Without a table along the refracted ray (or behind the camera): w = 0, the unrefracted
    // sample and the ray's path along the view direction (ar_water puts q there). No early
    // return: one exit per function (see camera_uv in effects_common.wgsl).
    let found = t.w != 0.0 && hit.z > 0.0;
    let uv = table_uv(hit.xy);
    let w = select(0.0, edge_weight(uv.xy) * uv.z, found);
    let refracted = clamp(uv.xy, vec2<f32>(0.0), vec2<f32>(1.0));
    // At w = 1 (w is 0 where no table is found) the sample is the refracted point and the
    // path the refracted ray's, as mix(straight, refracted, 1) and the select below give:
    // the straight-through point (straight_through) only where the refracted point is in the
    // fade band, outside it or missing, under 1 % of the water's pixels in the demo view. (The
    // budget model counts a branch's costlier side; a GPU skips the block for each SIMD group
    // that has w = 1 throughout.)
    var at = refracted;
    var path = hit.z;
    if w < 1.0 {
        let straight = straight_through(p, view, straight_h);
        at = select(straight.xy, mix(straight.xy, refracted, w), w > 0.0);
        path = select(straight.z, hit.z, found);
    }
    return vec4<f32>(sample_camera(at), path);
}
