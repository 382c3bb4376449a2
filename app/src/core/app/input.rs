//! Touch on the phone, and the desktop's mouse as one finger: every gesture goes to egui (the
//! desktop's through the window system's own panel input); one that began outside the panels
//! also goes to the scene. A press that lifts within [`TAP_MAX_S`] and [`TAP_MAX_PX`] is a tap
//! (a click): it selects a boat; a longer or farther one drags the orbit. A tap places the course (or the pool) on the table under the finger; two
//! fingers scale and turn what stands on the table (or, before it is placed, zoom and turn the
//! 3D view); one finger orbits the 3D view or, in the pool, drags a moving ball.

use ar::arcore::TwoFingerGesture;
use glam::DVec2;
use render::OrbitCamera;

use super::App;
use crate::core::table;
use crate::hud::SceneChoice;
use crate::hud::touch::{Touch, TouchAction, over_egui};

/// A touch (or a click) is a tap when the finger moved less than this (pixels) …
pub const TAP_MAX_PX: f64 = 20.0;
/// … and lifted within this many seconds.
pub const TAP_MAX_S: f64 = 0.3;

/// The gesture under way.
#[derive(Default)]
pub(super) struct Gesture {
    /// One-finger drag: where the finger was last (pixels).
    drag: Option<DVec2>,
    pinch: Option<TwoFingerGesture>,
    /// Where and when (app seconds) the finger went down: a tap candidate.
    down: Option<(DVec2, f64)>,
    /// The finger holds a pool ball.
    holding_ball: bool,
}

impl App {
    pub(super) fn on_touch(&mut self, touch: &Touch) {
        let ctx = self.graphics.as_ref().map(|g| g.egui.ctx.clone());
        let free = self.ui_free;
        let over_ui = |p| ctx.as_ref().is_some_and(|c| over_egui(c, free, p));
        if self.touch.on_touch(touch, over_ui) {
            self.scene_touch(touch);
        }
    }

    fn scene_touch(&mut self, touch: &Touch) {
        let pts: Vec<DVec2> = touch
            .fingers
            .iter()
            .map(|f| DVec2::new(f64::from(f.px[0]), f64::from(f.px[1])))
            .collect();
        let pool = self.scene == SceneChoice::Pool;
        match (touch.action, pts.as_slice()) {
            (TouchAction::Down(_), [p]) => {
                self.gesture.down = Some((*p, self.now));
                self.gesture.holding_ball =
                    pool && self.pool.press(true, p.to_array(), self.pool_t);
                self.gesture.drag = (!self.gesture.holding_ball).then_some(*p);
            }
            (TouchAction::PointerDown(_), [a, b, ..]) => {
                self.release_ball();
                self.gesture.drag = None;
                self.gesture.down = None;
                self.gesture.pinch = Some(TwoFingerGesture::new(*a, *b));
            }
            (TouchAction::Move, [p]) => {
                if self.gesture.holding_ball {
                    self.pool.pointer_moved(p.to_array(), self.pool_t);
                } else if let Some(d) = self.gesture.drag.replace(*p) {
                    let delta = *p - d;
                    self.active_orbit().drag(delta.x, delta.y);
                }
            }
            (TouchAction::Move, [a, b, ..]) => {
                if let Some(g) = self.gesture.pinch.as_mut() {
                    let (pinch, twist) = g.update(*a, *b);
                    self.two_fingers(pinch, twist);
                }
            }
            (TouchAction::Up(_), [p]) => {
                if let Some((down, at)) = self.gesture.down.take()
                    && !self.gesture.holding_ball
                    && (*p - down).length() < TAP_MAX_PX
                    && self.now - at < TAP_MAX_S
                {
                    self.tap(*p);
                }
                self.end_gesture();
            }
            (TouchAction::Up(_) | TouchAction::Cancel, _) => self.end_gesture(),
            _ => {}
        }
    }

    fn release_ball(&mut self) {
        if self.gesture.holding_ball {
            self.pool.press(false, [0.0; 2], self.pool_t);
            self.gesture.holding_ball = false;
        }
    }

    pub(super) fn end_gesture(&mut self) {
        self.release_ball();
        self.gesture = Gesture::default();
    }

    pub(super) fn active_orbit(&mut self) -> &mut OrbitCamera {
        match self.scene {
            SceneChoice::Race => &mut self.orbit,
            SceneChoice::Pool => &mut self.pool_orbit,
        }
    }

    /// Two fingers: scale by `pinch` and turn by `twist` what stands on the table, or zoom and
    /// turn the 3D view.
    pub fn two_fingers(&mut self, pinch: f64, twist: f64) {
        let pivot = table::course_pivot(self.world.race_bounds, table::table_depth());
        match self.scene {
            SceneChoice::Race => match self.course.as_mut() {
                Some(p) => p.apply_gesture_about(pivot, pinch, twist),
                None => zoom_and_turn(&mut self.orbit, pinch, twist, (5.0, 5000.0)),
            },
            // The pool's origin is its placement's anchor: it scales and turns about it.
            SceneChoice::Pool => match self.pool_placement.as_mut() {
                Some(p) => p.apply_gesture(pinch, twist),
                None => zoom_and_turn(&mut self.pool_orbit, pinch, twist, (0.5, 30.0)),
            },
        }
    }

    /// A tap (or the desktop's click: the same thresholds) on the scene at `px` (view
    /// pixels). On the desktop it selects the boat under it or clears the selection. On the
    /// phone, once the course stands on the table, a tap
    /// on a boat's label or within its pick radius (the hull's drawn size, at least a
    /// fingertip: `scene_overlay::labels::MIN_PICK_RADIUS_PT`) selects or deselects that boat,
    /// as the desktop's click does. Anywhere else it stands the course (or the pool) on the
    /// table under the finger, where the backend's hit test finds one; the selection stays.
    fn tap(&mut self, px: DVec2) {
        if self.desktop.is_some() {
            // The desktop shows no table: a click selects the boat under it (or clears the
            // selection on the water).
            if self.scene == SceneChoice::Race {
                self.overlays.click(px.to_array());
            }
            return;
        }
        if self.scene == SceneChoice::Race
            && self.course.is_some()
            && let Some(boat) = self.overlays.pick(px.to_array())
        {
            ui::toggle_selection(&mut self.overlays.settings.selected, boat);
            return;
        }
        let [w, h] = self.view_size();
        let screen = px / DVec2::new(f64::from(w.max(1)), f64::from(h.max(1)));
        let Some(frame) = self.ar.frame.as_ref() else {
            return;
        };
        let Some(point) = self.backend.hit_test(frame, screen) else {
            log::info!("regatta: no table under the tap yet; move the phone slowly over it");
            return;
        };
        match self.scene {
            SceneChoice::Race => {
                if self.course.is_none() {
                    // The first placement fits the race to the room on the tapped plane.
                    self.table_room = table::TableRoom::under(point, &frame.planes);
                }
                let p = table::place_course(
                    self.course,
                    point,
                    self.world.race_bounds,
                    table::table_depth(),
                    self.table_room,
                );
                log::info!(
                    "regatta: course placed at {point:.3} (1:{:.0})",
                    1.0 / p.course_to_table
                );
                self.course = Some(p);
            }
            SceneChoice::Pool => {
                log::info!("regatta: pool placed at {point:.3}");
                self.pool_placement = Some(table::place_pool(self.pool_placement, point));
            }
        }
    }
}

fn zoom_and_turn(o: &mut OrbitCamera, pinch: f64, twist: f64, range: (f64, f64)) {
    o.distance = (o.distance / pinch).clamp(range.0, range.1);
    o.yaw += twist;
}
