//! Manoeuvre marks on the trails (issue 28): each tack and gybe `race::debrief` found, as a
//! small mark on the boat's trail where the boat was head to wind (tack) or dead downwind
//! (gybe), in the boat's colour, for as long as the trail shows that part of the track. A tack
//! is a filled dot, a gybe a ring (a dot with a dark centre); both have a dark edge and a fixed
//! size on screen, like the buoys' discs. The selected boats' marks carry the metres the
//! manoeuvre cost (`−12 m`). The marks are part of the `trails` overlay: they go on and off
//! with it.
//!
//! The debrief is worked out once per race by the caller (`ui::DebriefView`, or once per
//! `regatta render`); here it is only read.

use glam::{DVec2, DVec3};
use race::debrief::ManoeuvreKind;
use render::passes::segments::Segment;

use super::geometry::View;
use super::{OverlaySettings, SceneText};

/// A mark's diameter on screen, points: the dark edge; the boat's colour inside is
/// [`MARK_FILL_PT`], a gybe's dark centre [`GYBE_HOLE_PT`].
pub const MARK_PT: f64 = 13.0;
pub const MARK_FILL_PT: f64 = 9.0;
pub const GYBE_HOLE_PT: f64 = 4.5;
/// The loss text starts this far right of the mark's centre, points (clear of the mark).
pub const LOSS_TEXT_OFFSET_PT: f64 = 9.0;

const EDGE: [f32; 4] = [0.03, 0.03, 0.03, 0.9];

/// One manoeuvre the trails show.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ManoeuvreMark {
    /// Index into `Race::boats`.
    pub boat: usize,
    pub kind: ManoeuvreKind,
    /// When the boat crossed the wind (head to wind or dead downwind), race seconds.
    pub t: f64,
    /// Where the boat was then (its track at `t`), race metres.
    pub position: [f64; 2],
    /// Metres the manoeuvre cost (negative: gained).
    pub loss_m: f64,
}

/// The debrief of `race` where `settings` show the trails (and so their marks), else `None`:
/// for a caller that draws one picture or one clip and has no debrief of the race at hand.
pub fn debrief_if_shown(race: &race::Race, settings: &OverlaySettings) -> Option<race::Debrief> {
    settings
        .shows(super::OverlayKind::Trails)
        .then(|| race::Debrief::of(race))
}

/// The manoeuvres of `debrief` whose crossing lies in the trails' window at `t`: from
/// `t − window_s` to `t`, the span whose fixes [`super::geometry::trail_polylines`] draws
/// (both ends included), and not in a gap of the boat's track (where its trail is broken).
/// In boat order, then time.
pub fn in_trail_window(
    race: &race::Race,
    debrief: &race::Debrief,
    t: f64,
    window_s: f64,
) -> Vec<ManoeuvreMark> {
    let mut out = Vec::new();
    for bm in &debrief.manoeuvres {
        let Some(boat) = race.boats.get(bm.boat) else {
            continue;
        };
        for m in &bm.manoeuvres {
            if !(t - window_s..=t).contains(&m.t) {
                continue;
            }
            let state = boat.state_at(m.t);
            if state.in_gap {
                continue;
            }
            out.push(ManoeuvreMark {
                boat: bm.boat,
                kind: m.kind,
                t: m.t,
                position: state.position,
                loss_m: m.loss_m,
            });
        }
    }
    out
}

/// "−12 m" for 12 metres lost, "+3 m" for 3 gained, "0 m" under half a metre either way.
pub fn loss_text(loss_m: f64) -> String {
    let m = loss_m.round();
    if m > 0.0 {
        format!("\u{2212}{m:.0} m")
    } else if m < 0.0 {
        format!("+{:.0} m", -m)
    } else {
        "0 m".to_string()
    }
}

/// Where a mark is drawn: above the boat's position on the water, by as much as the disc
/// reaches down in the world plus the overlays' lift. The overlay pass draws a disc facing the
/// camera at its centre's depth, so a disc centred on the water is cut in half by the water in
/// front of it when the camera looks along the sea; lifted by its radius times how much the
/// screen's up leans to the world's (0 looking straight down, 1 looking level), its lowest
/// point stays above the water and the disc sits on its trail point, whole. On screen the
/// mark then moves up from the trail by at most its radius.
pub fn mark_point(v: &View, position: [f64; 2]) -> DVec3 {
    let on_water = v.on_water(DVec2::from(position));
    let cam = &v.scene.camera;
    let forward = (cam.target - cam.eye).normalize_or_zero();
    let screen_up = forward.cross(cam.up).cross(forward).normalize_or_zero();
    let depth = (on_water - cam.eye).dot(forward).max(cam.near);
    let metres_per_px = 2.0 * depth * (cam.fov_y / 2.0).tan() / f64::from(v.size[1].max(1));
    let radius_m = 0.5 * f64::from(v.px(MARK_PT)) * metres_per_px;
    on_water + DVec3::Y * (radius_m * screen_up.y.max(0.0) + v.lift())
}

/// The marks of the manoeuvres in the trails' window (`window_s` seconds up to the scene's
/// time), fading with age as the trails do but never below half opacity; the loss texts of
/// the `selected` boats' marks go to `texts`.
pub fn marks(
    v: &View,
    debrief: &race::Debrief,
    window_s: f64,
    selected: &[usize],
    texts: &mut Vec<SceneText>,
) -> Vec<Segment> {
    let t = v.scene.t;
    let mut out = Vec::new();
    for m in in_trail_window(v.race, debrief, t, window_s) {
        let colour = crate::world::linear_colour(&v.race.boats[m.boat].color);
        let alpha = (0.5 + 0.45 * (1.0 - (t - m.t) / window_s)).clamp(0.5, 0.95) as f32;
        let p = mark_point(v, m.position);
        out.push(Segment::disc(
            p,
            [EDGE[0], EDGE[1], EDGE[2], EDGE[3] * alpha],
            v.px(MARK_PT),
        ));
        out.push(Segment::disc(
            p,
            [colour[0], colour[1], colour[2], alpha],
            v.px(MARK_FILL_PT),
        ));
        if m.kind == ManoeuvreKind::Gybe {
            out.push(Segment::disc(
                p,
                [EDGE[0], EDGE[1], EDGE[2], alpha],
                v.px(GYBE_HOLE_PT),
            ));
        }
        if selected.contains(&m.boat) {
            texts.push(SceneText {
                at: p,
                offset_pt: [LOSS_TEXT_OFFSET_PT, 0.0],
                text: loss_text(m.loss_m),
                colour,
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn loss_texts_say_lost_with_a_minus_and_gained_with_a_plus() {
        assert_eq!(loss_text(12.4), "\u{2212}12 m");
        assert_eq!(loss_text(-3.2), "+3 m");
        assert_eq!(loss_text(0.3), "0 m");
        assert_eq!(loss_text(-0.4), "0 m");
    }
}
