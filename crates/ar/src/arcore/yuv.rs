//! The camera image's YUV colour (BT.601) and plane layout helpers, kept in
//! `crates/camera_image` (shared with the renderer, which converts in the shader); re-exported
//! here where the ARCore code looks for them.

pub use camera_image::yuv::*;
