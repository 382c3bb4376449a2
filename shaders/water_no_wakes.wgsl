// Wake hook of the water pass, without wakes (adapters with no storage buffers in vertex
// shaders, such as OpenGL ES 3.0): the same functions, returning no wake.

fn wake_height(p: vec2<f32>) -> f32 {
    return 0.0;
}

fn wake_foam(p: vec2<f32>) -> f32 {
    return 0.0;
}
