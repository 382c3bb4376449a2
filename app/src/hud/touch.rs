//! Touch for egui and the scene on the phone: Android's motion events (pointer down, move and
//! up, several fingers) become egui's raw input, and each gesture, from the first finger down
//! to the last one up, belongs either to the panels or to the scene (tap to place, pinch and
//! twist the course, drag a ball), never to both.
//!
//! As egui-winit does with winit's touches: every finger is reported as an `egui::Event::Touch`
//! (egui's own multi-touch gestures), and the first finger of a gesture also drives egui's
//! pointer (press, move, release), so a tap on a button is a click and a drag on the timeline
//! scrubs; a second finger never presses the pointer, so it never clicks. Positions arrive in
//! physical pixels and are divided by `pixels_per_point`.

use egui::{Event, Modifiers, PointerButton, Pos2, RawInput, Rect, TouchDeviceId, TouchId};

/// What one motion event did (Android's `MotionEvent` actions), with the index into
/// [`Touch::fingers`] of the finger that went down or up.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TouchAction {
    /// The first finger went down (`ACTION_DOWN`).
    Down(usize),
    /// Another finger went down (`ACTION_POINTER_DOWN`).
    PointerDown(usize),
    /// Fingers moved (`ACTION_MOVE`).
    Move,
    /// A finger went up while others stay (`ACTION_POINTER_UP`).
    PointerUp(usize),
    /// The last finger went up (`ACTION_UP`).
    Up(usize),
    /// The system took the gesture away (`ACTION_CANCEL`).
    Cancel,
}

/// One finger: Android's pointer id (stable from down to up) and where it is, in physical
/// pixels from the top-left corner of the window.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Finger {
    pub id: i32,
    pub px: [f32; 2],
}

/// One motion event: what happened and every finger on the screen (the one going up included).
#[derive(Clone, Debug, PartialEq)]
pub struct Touch {
    pub action: TouchAction,
    pub fingers: Vec<Finger>,
}

/// Who a gesture belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Owner {
    /// It began on a panel: only egui sees it (scrubbing never moves the course).
    Ui,
    /// It began over the scene: egui sees it too (it ignores touches outside its panels), and
    /// the app places, scales and turns the course or drags a ball with it.
    Scene,
}

/// The touch state between events: which finger drives egui's pointer, who owns the gesture,
/// and the egui events waiting for the next frame.
#[derive(Clone, Debug)]
pub struct TouchInput {
    /// Physical pixels per egui point (the display's density / 160 on Android).
    pub pixels_per_point: f32,
    /// The window's part free of the status bar, navigation bar and display cutout (Android's
    /// content rect: left, top, right, bottom in physical pixels); `None`: all of it.
    pub content_px: Option<[i32; 4]>,
    pointer_finger: Option<i32>,
    owner: Option<Owner>,
    events: Vec<Event>,
}

impl TouchInput {
    pub fn new(pixels_per_point: f32) -> Self {
        Self {
            pixels_per_point: pixels_per_point.max(0.1),
            content_px: None,
            pointer_finger: None,
            owner: None,
            events: Vec::new(),
        }
    }

    /// Who owns the gesture under way, if one is.
    pub fn owner(&self) -> Option<Owner> {
        self.owner
    }

    fn points(&self, f: &Finger) -> Pos2 {
        Pos2::new(f.px[0], f.px[1]) / self.pixels_per_point
    }

    /// Takes one motion event: queues its egui events and returns whether the scene gets it too
    /// (the gesture began outside the panels). `over_ui` says whether a point (egui points) is
    /// on a panel, from the last frame's layout ([`over_egui`]).
    pub fn on_touch(&mut self, touch: &Touch, over_ui: impl Fn(Pos2) -> bool) -> bool {
        let changed = match touch.action {
            TouchAction::Down(i)
            | TouchAction::PointerDown(i)
            | TouchAction::PointerUp(i)
            | TouchAction::Up(i) => touch.fingers.get(i).copied(),
            TouchAction::Move | TouchAction::Cancel => None,
        };
        if let (TouchAction::Down(_), Some(f)) = (touch.action, changed) {
            // A new gesture: a left-over state (a lost `Up`) must not leak into it.
            self.pointer_finger = None;
            self.owner = Some(if over_ui(self.points(&f)) {
                Owner::Ui
            } else {
                Owner::Scene
            });
        }
        let owner = self.owner;
        match (touch.action, changed) {
            (TouchAction::Down(_) | TouchAction::PointerDown(_), Some(f)) => {
                self.finger_event(&f, egui::TouchPhase::Start);
                if self.pointer_finger.is_none() {
                    self.pointer_finger = Some(f.id);
                    let pos = self.points(&f);
                    self.events.push(Event::PointerMoved(pos));
                    self.events.push(button(pos, true));
                }
            }
            (TouchAction::PointerUp(_) | TouchAction::Up(_), Some(f)) => {
                self.finger_event(&f, egui::TouchPhase::End);
                if self.pointer_finger == Some(f.id) {
                    self.pointer_finger = None;
                    self.events.push(button(self.points(&f), false));
                    // No hover effects after the finger left.
                    self.events.push(Event::PointerGone);
                }
            }
            (TouchAction::Move, _) => {
                for f in &touch.fingers {
                    self.finger_event(f, egui::TouchPhase::Move);
                    if self.pointer_finger == Some(f.id) {
                        self.events.push(Event::PointerMoved(self.points(f)));
                    }
                }
            }
            (TouchAction::Cancel, _) => {
                for f in &touch.fingers {
                    self.finger_event(f, egui::TouchPhase::Cancel);
                }
                if self.pointer_finger.take().is_some() {
                    self.events.push(Event::PointerGone);
                }
            }
            // A down or up naming no finger: malformed, ignored.
            _ => {}
        }
        if matches!(touch.action, TouchAction::Up(_) | TouchAction::Cancel) {
            self.owner = None;
        }
        owner == Some(Owner::Scene)
    }

    fn finger_event(&mut self, f: &Finger, phase: egui::TouchPhase) {
        self.events.push(Event::Touch {
            device_id: TouchDeviceId(0),
            id: TouchId(f.id as u64),
            phase,
            pos: self.points(f),
            force: None,
        });
    }

    /// The egui events queued since the last call.
    pub fn take_events(&mut self) -> Vec<Event> {
        std::mem::take(&mut self.events)
    }

    /// The next frame's raw input for a window of `size` physical pixels at time `time`
    /// (seconds), with the queued events.
    pub fn take_raw_input(&mut self, size: [u32; 2], time: f64) -> RawInput {
        let ppp = self.pixels_per_point;
        let mut raw = RawInput {
            screen_rect: Some(Rect::from_min_size(
                Pos2::ZERO,
                egui::vec2(size[0] as f32, size[1] as f32) / ppp,
            )),
            time: Some(time),
            events: self.take_events(),
            focused: true,
            safe_area_insets: Some(self.safe_area(size)),
            ..RawInput::default()
        };
        raw.viewports
            .entry(egui::ViewportId::ROOT)
            .or_default()
            .native_pixels_per_point = Some(ppp);
        raw
    }
}

impl TouchInput {
    /// egui's safe-area insets (points) for a window of `size` pixels: what lies outside the
    /// content rect, so that `Context::content_rect` (where the bar, the banner and the panels
    /// are laid out) leaves the system bars and the cutout alone (issue 26, defect 5).
    pub fn safe_area(&self, size: [u32; 2]) -> egui::SafeAreaInsets {
        let Some([left, top, right, bottom]) = self.content_px else {
            return egui::SafeAreaInsets::default();
        };
        let (w, h) = (size[0] as i32, size[1] as i32);
        // An empty or inverted rect (before Android's first layout) says nothing.
        if right <= left || bottom <= top {
            return egui::SafeAreaInsets::default();
        }
        let ppp = self.pixels_per_point;
        let inset = |px: i32| px.clamp(0, w.max(h)) as f32 / ppp;
        egui::SafeAreaInsets(egui::epaint::MarginF32 {
            left: inset(left),
            right: inset(w - right),
            top: inset(top),
            bottom: inset(h - bottom),
        })
    }
}

fn button(pos: Pos2, pressed: bool) -> Event {
    Event::PointerButton {
        pos,
        button: PointerButton::Primary,
        pressed,
        modifiers: Modifiers::NONE,
    }
}

/// Whether `pos` (points) lies on an egui panel or window in `ctx`'s last frame. `free` is the
/// root ui's rect left after the panels (`Ui::available_rect_before_wrap` at the end of the
/// frame): the background layer covers the whole screen, but only its panels count. This is
/// `Context::is_pointer_over_egui` for a point that is not (yet) the pointer.
pub fn over_egui(ctx: &egui::Context, free: Rect, pos: Pos2) -> bool {
    match ctx.layer_id_at(pos) {
        None => false,
        Some(layer) if layer.order == egui::Order::Background => !free.contains(pos),
        Some(_) => true,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn touch(action: TouchAction, fingers: &[(i32, f32, f32)]) -> Touch {
        Touch {
            action,
            fingers: fingers
                .iter()
                .map(|&(id, x, y)| Finger { id, px: [x, y] })
                .collect(),
        }
    }

    fn buttons(events: &[Event]) -> Vec<(Pos2, bool)> {
        events
            .iter()
            .filter_map(|e| match e {
                Event::PointerButton { pos, pressed, .. } => Some((*pos, *pressed)),
                _ => None,
            })
            .collect()
    }

    #[test]
    fn a_tap_presses_and_releases_the_pointer_at_points() {
        let mut t = TouchInput::new(2.5);
        let scene = t.on_touch(&touch(TouchAction::Down(0), &[(7, 300.0, 600.0)]), |_| {
            false
        });
        assert!(scene, "a tap outside the panels reaches the scene");
        let down = t.take_events();
        assert_eq!(down[1], Event::PointerMoved(Pos2::new(120.0, 240.0)));
        assert_eq!(buttons(&down), vec![(Pos2::new(120.0, 240.0), true)]);
        assert!(matches!(
            down[0],
            Event::Touch { id: TouchId(7), phase: egui::TouchPhase::Start, pos, .. } if pos == Pos2::new(120.0, 240.0)
        ));
        t.on_touch(&touch(TouchAction::Up(0), &[(7, 300.0, 600.0)]), |_| false);
        let up = t.take_events();
        assert_eq!(buttons(&up), vec![(Pos2::new(120.0, 240.0), false)]);
        assert_eq!(up.last(), Some(&Event::PointerGone));
        assert_eq!(t.owner(), None);
    }

    #[test]
    fn a_second_finger_never_presses_the_pointer() {
        let mut t = TouchInput::new(1.0);
        t.on_touch(&touch(TouchAction::Down(0), &[(1, 10.0, 10.0)]), |_| false);
        t.take_events();
        let two = [(1, 10.0, 10.0), (2, 50.0, 60.0)];
        t.on_touch(&touch(TouchAction::PointerDown(1), &two), |_| false);
        t.on_touch(&touch(TouchAction::Move, &two), |_| false);
        t.on_touch(&touch(TouchAction::PointerUp(1), &two), |_| false);
        let events = t.take_events();
        assert!(buttons(&events).is_empty(), "{events:?}");
        // egui still hears the finger (its own multi-touch), and the pointer follows finger 1.
        assert!(events.iter().any(|e| matches!(
            e,
            Event::Touch {
                id: TouchId(2),
                phase: egui::TouchPhase::End,
                ..
            }
        )));
        assert!(!events.contains(&Event::PointerMoved(Pos2::new(50.0, 60.0))));
        // When the first finger lifts first, the second one still does not click.
        let mut t = TouchInput::new(1.0);
        t.on_touch(&touch(TouchAction::Down(0), &[(1, 10.0, 10.0)]), |_| false);
        t.on_touch(&touch(TouchAction::PointerDown(1), &two), |_| false);
        t.on_touch(&touch(TouchAction::PointerUp(0), &two), |_| false);
        t.take_events();
        t.on_touch(&touch(TouchAction::Up(0), &[(2, 50.0, 60.0)]), |_| false);
        assert!(buttons(&t.take_events()).is_empty());
    }

    #[test]
    fn pinch_and_twist_reach_the_scene_unless_they_began_on_a_panel() {
        let panel = |p: Pos2| p.y > 900.0;
        let one = [(1, 100.0, 100.0)];
        let two = [(1, 100.0, 100.0), (2, 300.0, 300.0)];
        let moved = [(1, 90.0, 80.0), (2, 330.0, 290.0)];
        let mut t = TouchInput::new(1.0);
        assert!(t.on_touch(&touch(TouchAction::Down(0), &one), panel));
        assert!(t.on_touch(&touch(TouchAction::PointerDown(1), &two), panel));
        assert!(t.on_touch(&touch(TouchAction::Move, &moved), panel));
        assert!(t.on_touch(&touch(TouchAction::PointerUp(1), &moved), panel));
        assert!(t.on_touch(&touch(TouchAction::Up(0), &one), panel));
        // Begun on the timeline: the whole gesture is egui's, even where it leaves the panel.
        let low = [(1, 100.0, 950.0)];
        let low_two = [(1, 100.0, 950.0), (2, 300.0, 300.0)];
        assert!(!t.on_touch(&touch(TouchAction::Down(0), &low), panel));
        assert!(!t.on_touch(&touch(TouchAction::PointerDown(1), &low_two), panel));
        assert!(!t.on_touch(&touch(TouchAction::Move, &moved), panel));
        assert!(!t.on_touch(&touch(TouchAction::Up(0), &low), panel));
        // The next gesture is judged afresh.
        assert!(t.on_touch(&touch(TouchAction::Down(0), &one), panel));
    }

    #[test]
    fn raw_input_carries_the_screen_in_points_and_the_density() {
        let mut t = TouchInput::new(2.0);
        t.on_touch(&touch(TouchAction::Down(0), &[(0, 2.0, 4.0)]), |_| false);
        let raw = t.take_raw_input([1080, 2340], 1.5);
        assert_eq!(
            raw.screen_rect,
            Some(Rect::from_min_size(Pos2::ZERO, egui::vec2(540.0, 1170.0)))
        );
        assert_eq!(
            raw.viewports[&egui::ViewportId::ROOT].native_pixels_per_point,
            Some(2.0)
        );
        assert_eq!(raw.events.len(), 3);
        assert!(t.take_raw_input([1080, 2340], 1.6).events.is_empty());
    }

    /// The timeline scrubber of `crates/ui` in a real egui context, driven by a finger: a drag
    /// along the track scrubs race time and never reaches the scene; a tap above the panel does;
    /// a second finger tapping the Play button does not press it.
    #[test]
    fn a_finger_scrubs_the_real_timeline_and_the_scene_never_sees_it() {
        let ctx = egui::Context::default();
        let mut clock = ui::RaceClock::new((0.0, 1000.0));
        clock.pause();
        let mut t = TouchInput::new(2.0);
        let size = [800, 1200];
        // One frame; returns the panel's content rect and the root ui's rect left free.
        let frame = |t: &mut TouchInput, clock: &mut ui::RaceClock, now: f64| {
            let (mut track, mut free) = (Rect::NOTHING, Rect::NOTHING);
            let out = ctx.run_ui(t.take_raw_input(size, now), |ui| {
                egui::Panel::bottom("timeline").show(ui, |ui| {
                    ui::timeline_ui(ui, clock, &[]);
                    track = ui.min_rect();
                });
                free = ui.available_rect_before_wrap();
            });
            out.drop_without_applying_deltas();
            (track, free)
        };
        frame(&mut t, &mut clock, 0.0);
        let (track, free) = frame(&mut t, &mut clock, 0.02);
        // The track is the panel's last 26 points (TRACK_HEIGHT), full width.
        let y = (track.bottom() - 13.0) * 2.0;
        let x = |s: f32| (track.left() + s * track.width()) * 2.0;
        let over = |p: Pos2| over_egui(&ctx, free, p);
        assert!(!t.on_touch(&touch(TouchAction::Down(0), &[(3, x(0.1), y)]), over));
        frame(&mut t, &mut clock, 0.04);
        for (i, s) in [0.2, 0.35, 0.5].into_iter().enumerate() {
            assert!(!t.on_touch(&touch(TouchAction::Move, &[(3, x(s), y)]), over));
            frame(&mut t, &mut clock, 0.06 + 0.02 * i as f64);
        }
        assert!(!t.on_touch(&touch(TouchAction::Up(0), &[(3, x(0.5), y)]), over));
        frame(&mut t, &mut clock, 0.2);
        assert!((clock.time() - 500.0).abs() < 2.0, "{}", clock.time());
        // Above the panel is the scene.
        let above = [(4, x(0.5), (track.top() - 100.0) * 2.0)];
        assert!(t.on_touch(&touch(TouchAction::Down(0), &above), over));
        assert!(t.on_touch(&touch(TouchAction::Up(0), &above), over));
        frame(&mut t, &mut clock, 0.3);
        assert!(!clock.is_playing());
    }
}
