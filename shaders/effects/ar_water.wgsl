// The AR water: the water pass's mesh (water.wgsl's vs_main: waves and wakes) shaded once with
// the effects this frame needs, mixed by the full Fresnel equations (not Schlick's approximation):
// R·reflection + (1 − R)·the table seen through the water (refracted, lit by caustics,
// through clear water: water_look.wgsl), then foam. Replaces water.wgsl's fs_main when an effect runs, so
// no water pixel is shaded twice. Appended after the water pass's files and the effect files;
// the pass appends the pipeline's constants last:
//
//   const FX_MASK: u32            the effects this pipeline shades (FX_* bits);
//   const FX_CHEAP_CAUSTICS: bool the overhead-sun caustics instead of the area-ratio map.
//
// One pipeline per set of effects (effects::passes::pipelines::ArPipelines): the effects that do
// not run are constant-false branches, gone from the compiled shader (lavapipe runs both sides
// of a uniform branch under execution masks, so a flag in the uniform saves nothing there).
// Every function of the effect files has one exit: Mesa 22.3's lavapipe crashed drawing some
// of these pipelines when an inlined function returned early (see ArPipelines).

// Does this pipeline shade with effect `bit`?
fn fx_on(bit: u32) -> bool {
    return (FX_MASK & bit) != 0u;
}

// The water pass's vertex output and what the effects need of each vertex: the water's own
// five interpolated values (with the slope sums of the sea's longest waves,
// render::vertex_slopes), the flow's sample points and the straight-through table's map,
// seven where the twelfth session had three.
// (A fourth was avoided before: in about a third of the bench's runs on lavapipe one case's
// pass then ran up to 1.5× slower for the whole run, a per-process effect whose cause was not
// found; docs/quality.md, step 25, has timings since that do not show it. On a tile-based
// phone each value is written per vertex and read per pixel: 40 bytes a vertex more, which
// the budget model does not count.)
struct ArVertexOut {
    @builtin(position) clip: vec4<f32>,
    // xy: the rest point (local m); zw: the current around the marks (m/s, flow map), a
    // smooth field evaluated per vertex and interpolated (error bound:
    // effects::flowmap::current_interpolation_error).
    @location(0) rest_current: vec4<f32>,
    @location(1) world: vec3<f32>,
    @location(2) wake: vec3<f32>,
    // The slope sums of the sea's longest waves, as the water pass's VertexOut has them.
    @location(3) sea_sums: vec4<f32>,
    @location(4) sea_sums_z: vec2<f32>,
    // The flow's two sample points in the detail tile (flow_sample_points: affine in the
    // world point and the current, so interpolating them is forming them per pixel).
    @location(5) flow_points: vec4<f32>,
    // The camera-image point of the table straight behind the pixel, homogeneous
    // (straight_image_of_clip: the pixel's straight_image_at times its clip w).
    @location(6) straight_h: vec3<f32>,
}

@vertex
fn vs_ar(v: VertexIn) -> ArVertexOut {
    let w = water_vertex(v);
    var out: ArVertexOut;
    out.clip = w.clip;
    out.world = w.world;
    out.wake = w.wake;
    out.sea_sums = w.sea_sums;
    out.sea_sums_z = w.sea_sums_z;
    var current = vec2<f32>(0.0);
    var flow_points = vec4<f32>(0.0);
    if fx_on(FX_FLOWMAP) {
        current = current_at(w.world.xz);
        flow_points = flow_sample_points(w.world.xz, current);
    }
    out.rest_current = vec4<f32>(w.rest, current);
    out.flow_points = flow_points;
    out.straight_h = straight_image_of_clip(w.clip);
    return out;
}

@fragment
fn fs_ar(in: ArVertexOut) -> @location(0) vec4<f32> {
    let rest = in.rest_current.xy;
    let pa = frame.play_area;
    if rest.x < pa.x || rest.y < pa.y || rest.x > pa.z || rest.y > pa.w {
        discard;
    }
    let p = in.world;
    let view = normalize(p - frame.eye.xyz);
    let screen_uv = in.clip.xy * frame.viewport.zw;
    let across = dpdx(rest);
    let down = dpdy(rest);
    let footprint = sqrt(max(dot(across, across), dot(down, down)));
    let sf = surface_frame_from(rest, frame.counts.x, footprint, vertex_sums_in(in.sea_sums, in.sea_sums_z));
    // Sea, wake and flow-detail slopes add, as in water.wgsl: the sea's (∂h/∂x, ∂h/∂z) is
    // −(up.x, up.z)/up.y, the wake's is in.wake.xy, the detail's flow_slope; one normal of
    // their sum, (−∂/∂x, 1, −∂/∂z) normalised.
    var tilt = vec2<f32>(sf.up.x / sf.up.y - in.wake.x, sf.up.z / sf.up.y - in.wake.y);
    if fx_on(FX_FLOWMAP) {
        tilt -= flow_slope(in.flow_points, in.rest_current.zw);
    }
    // normalize(tilt.x, 1, tilt.y) with its y written as the scale itself (no product by 1).
    let unit = inverseSqrt(dot(tilt, tilt) + 1.0);
    let n = vec3<f32>(tilt.x * unit, unit, tilt.y * unit);
    // The view entering the water: the refracted ray (xyz) and the Fresnel reflectance (w).
    let entry = water_entry(view, n);
    let r = entry.w;

    // What the water mirrors: the reflection texture (room, sky, boats), else the sky.
    var reflected: vec3<f32>;
    if fx_on(FX_REFLECTION) {
        reflected = reflection_colour(screen_uv, n);
    } else {
        reflected = sky_colour_rough(reflect_dir(view, n), sf.slope_variance);
    }

    // The table under the water (q: its x and z, the table plane's height known), straight
    // through or refracted, and its colour and path length in the water (table.w). (One
    // refraction per pixel, a tenth of its work; the straight-through point by a map formed on
    // the CPU and carried by the vertices.)
    var q: vec2<f32>;
    var table: vec4<f32>;
    if fx_on(FX_REFRACTION) {
        table = refracted_table_along(p, view, in.straight_h, vec4<f32>(entry.xyz, 1.0));
        q = p.xz + entry.xz * table.w;
    } else {
        let straight = straight_through(p, view, in.straight_h);
        q = p.xz + view.xz * straight.z;
        table = vec4<f32>(sample_camera(straight.xy), straight.z);
    }
    var light = 1.0;
    if fx_on(FX_CAUSTICS) {
        light = caustic_light(q, n);
    }
    // The real sea's water by optical similarity (water_look.wgsl): the table through the
    // sea's depth and the column's own backscattered light. The room's radiance is the
    // camera's white (the assumption that makes the table's colour its albedo), folded into
    // the uniform's R∞.
    let transmitted = water_transmitted(table.rgb * light, table.w * fx.water.down_scale.w, fx.water);
    // R·reflected + (1 − R)·transmitted as one mix.
    var colour = mix(transmitted, reflected, r);
    // Foam of breaking crests (Jacobian) and of the boats' wakes, as the water pass draws it.
    let sun_in = max(dot(n, frame.sun.xyz), 0.0);
    let foam = foam_coverage(foam_from_jacobian(sf.jacobian), in.wake.z);
    colour = mix(colour, FOAM * (0.6 + 0.4 * sun_in), foam);
    return vec4<f32>(colour, 1.0);
}
