// The boats pass: instanced procedural hulls, sails and buoys, each placed by a model matrix
// in local metres that the CPU built from the race (position, heading) and the sea (float
// height, pitch, roll). In the open sea, Phong-style lighting under the sun and sky; over the
// camera image (frame.room_light.w = 1), the room's light that the water takes (view_light.rs's
// boat_in_room, its f64 reference). Appended to common.wgsl.

struct MeshVertex {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    // 0 = hull (boat colour), 1 = sail (sailcloth tinted with the team colour), 2 = deck/mast (dark).
    @location(2) part: u32,
}

struct Instance {
    @location(3) m0: vec4<f32>,
    @location(4) m1: vec4<f32>,
    @location(5) m2: vec4<f32>,
    @location(6) m3: vec4<f32>,
    @location(7) colour: vec4<f32>,
}

struct BoatOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) normal: vec3<f32>,
    @location(1) colour: vec3<f32>,
    @location(2) world: vec3<f32>,
}

@vertex
fn vs_main(v: MeshVertex, inst: Instance) -> BoatOut {
    let model = mat4x4<f32>(inst.m0, inst.m1, inst.m2, inst.m3);
    let world = model * vec4<f32>(v.position, 1.0);
    var out: BoatOut;
    out.clip = frame.view_proj * world;
    out.normal = normalize((model * vec4<f32>(v.normal, 0.0)).xyz);
    out.world = world.xyz;
    var c = inst.colour.rgb;
    if v.part == 1u {
        // The team colour on the sails too, so a boat reads as its team from any angle.
        c = mix(vec3<f32>(0.92, 0.92, 0.88), inst.colour.rgb, 0.45);
    } else if v.part == 2u {
        c = vec3<f32>(0.12, 0.12, 0.13);
    }
    out.colour = c;
    return out;
}

@fragment
fn fs_main(in: BoatOut, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    // Sails are single sheets: light both faces.
    let n = select(-in.normal, in.normal, front);
    let l = frame.sun.xyz;
    if frame.room_light.w > 0.5 {
        return vec4<f32>(boat_in_room(in.colour, n, l, frame.room_light.rgb), 1.0);
    }
    let v = normalize(frame.eye.xyz - in.world);
    let diffuse = max(dot(n, l), 0.0);
    let h = normalize(l + v);
    let specular = pow(max(dot(n, h), 0.0), 32.0) * 0.3;
    let ambient = 0.35 * sky_colour(normalize(vec3<f32>(n.x, abs(n.y) + 0.2, n.z)));
    return vec4<f32>(in.colour * (ambient + 0.8 * diffuse * frame.sun.w) + specular * frame.sun.w, 1.0);
}

// A boat's colour in a room of diffuse radiance `room` (what the water over the camera image
// takes), `l` the room's main light: hemisphere plus main light (view_light::boat_in_room).
fn boat_in_room(albedo: vec3<f32>, n: vec3<f32>, l: vec3<f32>, room: vec3<f32>) -> vec3<f32> {
    let shade = (1.0 - ROOM_DIRECTIONAL_SHARE) * 0.5 * (1.0 + n.y) + ROOM_DIRECTIONAL_SHARE * max(dot(n, l), 0.0);
    return albedo * room * shade;
}
