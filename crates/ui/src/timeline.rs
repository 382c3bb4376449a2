//! The race-timeline scrubber: transport buttons, speed (backwards too), the race clock, and a
//! track with a tick at every event (start, roundings, lead changes) that can be dragged or
//! clicked to scrub.

use egui::{Align2, FontId, Rect, Sense, Stroke, StrokeKind, Ui, Vec2, pos2};

use crate::clock::{RaceClock, SPEEDS, format_race_time};
pub use crate::events::TimelineEvent;

/// Height of the scrub track, points.
const TRACK_HEIGHT: f32 = 26.0;

/// Below this width (points; a phone held upright is about 400) the transport row wraps onto
/// several lines instead of running off the screen's edge.
pub const NARROW_WIDTH: f32 = 640.0;

/// Draws the timeline into `ui` (full width); returns true when the user moved race time or
/// changed play state.
pub fn timeline_ui(ui: &mut Ui, clock: &mut RaceClock, events: &[TimelineEvent]) -> bool {
    let before = (clock.time(), clock.is_playing(), clock.speed());
    let times: Vec<f64> = events.iter().map(|e| e.t).collect();
    let row = |ui: &mut Ui| {
        if ui
            .button("⏮ Start")
            .on_hover_text("Jump to the start signal")
            .clicked()
        {
            clock.jump_to_start();
        }
        if ui
            .button("⏪ Event")
            .on_hover_text("Jump to the previous event (start, rounding, lead change)")
            .clicked()
        {
            clock.jump_to_previous(&times);
        }
        if ui.button("◀ Step").on_hover_text("Step back").clicked() {
            clock.step(-1);
        }
        let play_label = match (clock.is_playing(), clock.is_reverse()) {
            (true, _) => "⏸ Pause",
            (false, false) => "▶ Play",
            (false, true) => "◀ Play back",
        };
        if ui.button(play_label).clicked() {
            clock.toggle();
        }
        if ui.button("Step ▶").on_hover_text("Step forward").clicked() {
            clock.step(1);
        }
        if ui
            .button("Event ⏩")
            .on_hover_text("Jump to the next event (start, rounding, lead change)")
            .clicked()
        {
            clock.jump_to_next(&times);
        }
        let mut speed = clock.speed();
        egui::ComboBox::new("race-speed", "speed")
            .selected_text(speed_text(speed))
            .width(60.0)
            .show_ui(ui, |ui| {
                ui.label("Speed (− plays back)");
                for s in SPEEDS.into_iter().rev() {
                    ui.selectable_value(&mut speed, s, speed_text(s));
                }
            });
        clock.set_speed(speed);
        if ui
            .button("◀▶")
            .on_hover_text("Play the other way (R)")
            .clicked()
        {
            clock.reverse();
        }
        ui.separator();
        let (_, end) = clock.span();
        // One piece: on a narrow screen the clock moves to the next line whole.
        ui.add(
            egui::Label::new(
                egui::RichText::new(format!(
                    "{} / {}",
                    format_race_time(clock.time()),
                    format_race_time(end)
                ))
                .monospace()
                .size(18.0)
                .strong(),
            )
            .extend(),
        );
    };
    if ui.available_width() < NARROW_WIDTH {
        ui.horizontal_wrapped(row);
    } else {
        ui.horizontal(row);
    }
    scrub_track(ui, clock, events);
    let after = (clock.time(), clock.is_playing(), clock.speed());
    before != after
}

/// `8×`, `−8×` (a true minus sign, easier to see than a hyphen).
pub fn speed_text(speed: f64) -> String {
    if speed < 0.0 {
        format!("−{}×", -speed)
    } else {
        format!("{speed}×")
    }
}

/// The scrub track: the span as a bar, elapsed part filled, ticks at events, a handle at now.
fn scrub_track(ui: &mut Ui, clock: &mut RaceClock, events: &[TimelineEvent]) {
    let width = ui.available_width();
    let (rect, response) =
        ui.allocate_exact_size(Vec2::new(width, TRACK_HEIGHT), Sense::click_and_drag());
    let (a, b) = clock.span();
    let x_of = |t: f64| rect.left() + ((t - a) / (b - a)).clamp(0.0, 1.0) as f32 * rect.width();
    if let Some(p) = response.interact_pointer_pos()
        && (response.dragged() || response.clicked())
    {
        let s = f64::from(((p.x - rect.left()) / rect.width()).clamp(0.0, 1.0));
        clock.scrub_to(a + s * (b - a));
    }
    let t = clock.time();
    response.widget_info(|| egui::WidgetInfo::slider(true, t, "Race time"));

    let painter = ui.painter_at(rect.expand(2.0));
    let visuals = ui.visuals();
    let bar = Rect::from_min_max(
        pos2(rect.left(), rect.center().y - 4.0),
        pos2(rect.right(), rect.center().y + 4.0),
    );
    painter.rect_filled(bar, 4.0, visuals.extreme_bg_color);
    let done = Rect::from_min_max(bar.min, pos2(x_of(t), bar.max.y));
    painter.rect_filled(done, 4.0, visuals.selection.bg_fill);
    for e in events {
        let x = x_of(e.t);
        painter.line_segment(
            [pos2(x, rect.top() + 2.0), pos2(x, bar.top())],
            Stroke::new(2.0, e.color),
        );
    }
    let handle = pos2(x_of(t), rect.center().y);
    painter.circle(
        handle,
        8.0,
        visuals.widgets.active.bg_fill,
        Stroke::new(2.0, visuals.strong_text_color()),
    );
    painter.rect_stroke(
        bar,
        4.0,
        Stroke::new(1.0, visuals.widgets.noninteractive.bg_stroke.color),
        StrokeKind::Inside,
    );
    if let Some(hover) = response.hover_pos() {
        // Name the nearest event under the pointer, if any is within 4 points.
        let near = events.iter().min_by(|p, q| {
            (x_of(p.t) - hover.x)
                .abs()
                .total_cmp(&(x_of(q.t) - hover.x).abs())
        });
        if let Some(e) = near.filter(|e| (x_of(e.t) - hover.x).abs() < 4.0) {
            painter.text(
                pos2(x_of(e.t), rect.top()),
                Align2::CENTER_BOTTOM,
                format!("{} {}", format_race_time(e.t), e.label),
                FontId::proportional(12.0),
                visuals.strong_text_color(),
            );
        }
    }
}
