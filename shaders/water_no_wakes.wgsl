// Wake hook of the water pass, without wakes (adapters with no storage buffers in vertex
// shaders, such as OpenGL ES 3.0): the same function, returning no wake.

fn wake_at(p: vec2<f32>) -> vec4<f32> {
    return vec4<f32>(0.0);
}
