//! The overlays' world-space geometry: segments on the water (at the sea's height under them,
//! lifted a little) for the render crate's segment passes, and the screen projection the
//! labels and texts share.

use glam::{DMat4, DVec2, DVec3};
use race::{MarkKind, Standing};
use render::passes::boats::MASTHEAD;
use render::passes::segments::{Layer, Segment};
use render::scene::{float_matrix, float_pose};

use super::{OverlaySettings, SceneText, WindInfo};

/// One boat as the overlays see it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoatAt {
    /// Index into `Race::boats`.
    pub index: usize,
    pub state: race::BoatState,
    pub colour: [f32; 3],
}

/// What every overlay of a frame shares: the race at the scene's time, the boats as drawn,
/// the camera's projection and the pixel scale.
pub struct View<'a> {
    pub race: &'a race::Race,
    pub scene: &'a render::Scene,
    pub size: [u32; 2],
    pub pixels_per_point: f64,
    /// Boats with data at t (not in a gap), as the scene draws them.
    pub boats: Vec<BoatAt>,
    pub standings: Vec<Standing>,
    /// Hull length the boats are drawn with, metres (table scenes draw models larger).
    pub boat_length: f64,
    /// World to clip, relative to `origin`.
    view_proj: DMat4,
    origin: DVec2,
}

impl<'a> View<'a> {
    pub fn new(
        race: &'a race::Race,
        scene: &'a render::Scene,
        size: [u32; 2],
        pixels_per_point: f64,
    ) -> View<'a> {
        let boats = race
            .boats
            .iter()
            .enumerate()
            .filter(|(_, b)| !b.fixes().is_empty())
            .map(|(index, b)| BoatAt {
                index,
                state: b.state_at(scene.t),
                colour: crate::world::linear_colour(&b.color),
            })
            .filter(|b| !b.state.in_gap)
            .collect();
        let boat_length = scene
            .boats
            .iter()
            .map(|b| b.length)
            .fold(crate::world::BOAT_LENGTH_M, f64::max);
        let origin = DVec2::new(scene.camera.eye.x, scene.camera.eye.z);
        let aspect = f64::from(size[0].max(1)) / f64::from(size[1].max(1));
        View {
            race,
            scene,
            size,
            pixels_per_point,
            boats,
            standings: race.standings(scene.t),
            boat_length,
            view_proj: scene.camera.view_proj_local(origin, aspect),
            origin,
        }
    }

    /// Framebuffer pixel (x right, y down) of a world point, and its depth in [0, 1]; `None`
    /// behind the camera.
    pub fn project(&self, p: DVec3) -> Option<([f64; 2], f64)> {
        let c = self.view_proj * (p - DVec3::new(self.origin.x, 0.0, self.origin.y)).extend(1.0);
        if c.w <= 1e-9 || c.z < 0.0 {
            return None;
        }
        let (x, y) = (c.x / c.w, c.y / c.w);
        let [w, h] = self.size.map(f64::from);
        Some(([(x * 0.5 + 0.5) * w, (0.5 - y * 0.5) * h], c.z / c.w))
    }

    /// Whether a pixel lies on the frame.
    pub fn on_screen(&self, p: [f64; 2]) -> bool {
        let [w, h] = self.size.map(f64::from);
        (0.0..w).contains(&p[0]) && (0.0..h).contains(&p[1])
    }

    /// The sea's height at world (x, z), metres (rest level where the inverse fails).
    pub fn sea_height(&self, p: DVec2) -> f64 {
        self.scene
            .sea
            .height_at([p.x, p.y], self.scene.t)
            .unwrap_or(0.0)
    }

    /// How far above the sea overlay lines float: a twentieth of a drawn hull, so they stay
    /// above the water between the points where their height is taken.
    pub fn lift(&self) -> f64 {
        0.05 * self.boat_length
    }

    /// A point on the water at (x, z), lifted by [`View::lift`].
    pub fn on_water(&self, p: DVec2) -> DVec3 {
        DVec3::new(p.x, self.sea_height(p) + self.lift(), p.y)
    }

    /// The masthead of boat `b` as drawn (floating on the sea), world metres.
    pub fn masthead(&self, b: &BoatAt) -> DVec3 {
        masthead(
            self.scene,
            b.state.position,
            b.state.heading_deg,
            self.boat_length,
        )
    }

    /// A line width of `points` points, in pixels.
    pub fn px(&self, points: f64) -> f32 {
        (points * self.pixels_per_point) as f32
    }

    /// The standing of boat `index`.
    pub fn standing(&self, index: usize) -> Option<&Standing> {
        self.standings.iter().find(|s| s.boat == index)
    }
}

/// The masthead of a boat of drawn `length` at `position` heading `heading_deg` on the scene's
/// sea: the boats pass's own float pose and model matrix applied to [`MASTHEAD`].
pub fn masthead(scene: &render::Scene, position: [f64; 2], heading_deg: f64, length: f64) -> DVec3 {
    let p = DVec2::from(position);
    let heading = heading_deg.to_radians();
    let pose = float_pose(&scene.sea, scene.t, p, heading, length, length * 0.32);
    float_matrix(p, heading, &pose, DVec2::ZERO).transform_point3(DVec3::from(MASTHEAD) * length)
}

/// `colour` with alpha `a`.
fn rgba(c: [f32; 3], a: f32) -> [f32; 4] {
    [c[0], c[1], c[2], a]
}

const WHITE: [f32; 3] = [1.0, 1.0, 1.0];

/// A polyline on the water from `a` to `b` in `n` pieces, so it follows the waves.
fn water_line(
    v: &View,
    a: DVec2,
    b: DVec2,
    n: usize,
    colour: [f32; 4],
    width: f32,
) -> Vec<Segment> {
    let pts: Vec<DVec3> = (0..=n)
        .map(|k| v.on_water(a.lerp(b, k as f64 / n as f64)))
        .collect();
    pts.windows(2)
        .map(|w| Segment::line(w[0], w[1], colour, width))
        .collect()
}

/// A ring of `radius` metres around `centre` on the water.
fn ring(v: &View, centre: DVec2, radius: f64, colour: [f32; 4], width: f32) -> Vec<Segment> {
    const N: usize = 24;
    let pts: Vec<DVec3> = (0..=N)
        .map(|k| {
            let a = k as f64 / N as f64 * std::f64::consts::TAU;
            v.on_water(centre + radius * DVec2::new(a.cos(), a.sin()))
        })
        .collect();
    pts.windows(2)
        .map(|w| Segment::line(w[0], w[1], colour, width))
        .collect()
}

/// The labels' GPU part: a team-colour ring on the water around every boat, and a white one
/// around each selected boat.
pub fn rings(v: &View, settings: &OverlaySettings) -> Layer {
    if v.boats.is_empty() {
        return Layer::Hidden("no boat has data at this time".into());
    }
    let mut out = Vec::new();
    for b in &v.boats {
        let c = DVec2::from(b.state.position);
        out.extend(ring(
            v,
            c,
            0.7 * v.boat_length,
            rgba(b.colour, 0.95),
            v.px(3.0),
        ));
        if settings.selected.contains(&b.index) {
            out.extend(ring(
                v,
                c,
                0.95 * v.boat_length,
                rgba(WHITE, 1.0),
                v.px(4.0),
            ));
        }
    }
    Layer::Draw(out)
}

/// One boat's trail: the fixes of the last `window_s` seconds up to `t` and the boat's position
/// at `t`, as polylines of (race time, position), broken where the importer marked a gap; at
/// most about 64 points per window (a fix is kept when it is the first, next to a gap, or
/// `window_s / 64` after the last kept one).
pub fn trail_polylines(boat: &race::Boat, t: f64, window_s: f64) -> Vec<Vec<(f64, [f64; 2])>> {
    let fixes = boat.fixes();
    let a = fixes.partition_point(|f| f.t < t - window_s);
    let b = fixes.partition_point(|f| f.t <= t);
    let step = window_s / 64.0;
    let mut lines: Vec<Vec<(f64, [f64; 2])>> = Vec::new();
    let mut current: Vec<(f64, [f64; 2])> = Vec::new();
    let mut last_t = f64::NEG_INFINITY;
    for (i, f) in fixes.iter().enumerate().take(b).skip(a) {
        let at_gap = boat.gap_after(i) || (i > 0 && boat.gap_after(i - 1));
        if current.is_empty() || at_gap || f.t - last_t >= step || i + 1 == b {
            current.push((f.t, f.pos()));
            last_t = f.t;
        }
        if boat.gap_after(i) {
            lines.push(std::mem::take(&mut current));
        }
    }
    // The boat where it is now, unless t lies in a gap or past its track.
    let state = boat.state_at(t);
    if b > 0 && !state.in_gap && state.racing && !boat.gap_after(b - 1) {
        current.push((t, state.position));
    }
    lines.push(current);
    lines.retain(|l| l.len() >= 2);
    lines
}

/// Every boat's trail over the last `window_s` seconds, in its team colour, fading with age.
pub fn trails(v: &View, window_s: f64) -> Layer {
    let t = v.scene.t;
    let mut out = Vec::new();
    for b in &v.race.boats {
        if b.fixes().is_empty() {
            continue;
        }
        let colour = crate::world::linear_colour(&b.color);
        let fade = |tp: f64| {
            rgba(
                colour,
                (0.9 * (1.0 - (t - tp) / window_s)).clamp(0.0, 0.9) as f32,
            )
        };
        for line in trail_polylines(b, t, window_s) {
            let pts: Vec<(f64, DVec3)> = line
                .iter()
                .map(|&(tp, p)| (tp, v.on_water(DVec2::from(p))))
                .collect();
            out.extend(pts.windows(2).map(|w| Segment {
                a: w[0].1,
                b: w[1].1,
                colour_a: fade(w[0].0),
                colour_b: fade(w[1].0),
                width_px: v.px(2.5),
            }));
        }
    }
    if out.is_empty() {
        return Layer::Hidden(format!("no boat has fixes in the last {:.0} s", window_s));
    }
    Layer::Draw(out)
}

const BUOY: [f32; 3] = [1.0, 0.42, 0.05];
const START: [f32; 3] = [0.2, 0.9, 0.3];
const FINISH: [f32; 3] = [0.3, 0.5, 1.0];
const BOUNDARY: [f32; 3] = [0.95, 0.2, 0.2];

/// A buoy seen from afar: a dark-edged orange disc at least 10 points across on top of it.
fn buoy_disc(v: &View, p: DVec2, out: &mut Vec<Segment>) {
    let top = v.on_water(p) + DVec3::Y * render::passes::boats::BUOY_DIAMETER;
    out.push(Segment::disc(top, [0.05, 0.05, 0.05, 0.9], v.px(12.0)));
    out.push(Segment::disc(top, rgba(BUOY, 1.0), v.px(9.0)));
}

/// Close-hauled angle off the true wind that laylines are drawn at, degrees.
pub const LAYLINE_ANGLE_DEG: f64 = 45.0;

/// The course: buoys (gates as pairs), start and finish lines, rhumb lines between the marks
/// in rounding order (`rhumb`), the boundary, and laylines to the next windward mark (the
/// leader's next mark when its leg heads within 60° of the wind).
pub fn course(v: &View, rhumb: bool, wind: Option<WindInfo>) -> Layer {
    let race = v.race;
    if race.marks.is_empty() && race.boundary.is_empty() {
        return Layer::Hidden("the race has no marks and no boundary".into());
    }
    let mut out = Vec::new();
    let width = v.px(2.0);
    for m in &race.marks {
        for p in m.buoys() {
            buoy_disc(v, DVec2::from(p), &mut out);
        }
        if let Some([a, b]) = m.ends {
            let (colour, w) = match m.kind {
                MarkKind::StartLine => (rgba(START, 0.9), v.px(3.0)),
                MarkKind::FinishLine => (rgba(FINISH, 0.9), v.px(3.0)),
                _ => (rgba(BUOY, 0.5), width),
            };
            out.extend(water_line(v, DVec2::from(a), DVec2::from(b), 8, colour, w));
        }
    }
    if rhumb {
        let pts: Vec<DVec2> = race
            .course_marks()
            .map(|m| DVec2::from(m.position))
            .collect();
        for w in pts.windows(2) {
            out.extend(water_line(v, w[0], w[1], 24, [1.0, 1.0, 1.0, 0.35], width));
        }
    }
    let n = race.boundary.len();
    for k in 0..n {
        let (a, b) = (race.boundary[k], race.boundary[(k + 1) % n]);
        out.extend(water_line(
            v,
            DVec2::from(a),
            DVec2::from(b),
            16,
            rgba(BOUNDARY, 0.7),
            width,
        ));
    }
    if let (Some(w), Some(mark)) = (wind, next_windward_mark(v, wind)) {
        let leg = race
            .leg_lengths()
            .into_iter()
            .fold(0.0, f64::max)
            .max(10.0 * v.boat_length);
        for side in [-1.0, 1.0] {
            // From the mark downwind, LAYLINE_ANGLE_DEG either side of the wind's direction.
            let bearing = (w.from_deg + side * LAYLINE_ANGLE_DEG).to_radians();
            let dir = DVec2::new(bearing.sin(), -bearing.cos());
            let end = mark + dir * 0.6 * leg;
            out.extend(water_line(v, mark, end, 16, [1.0, 0.9, 0.3, 0.55], width));
        }
    }
    Layer::Draw(out)
}

/// The next mark of the leading boat's leg when that leg heads within 60° of the wind's
/// direction (a beat): where the laylines go.
fn next_windward_mark(v: &View, wind: Option<WindInfo>) -> Option<DVec2> {
    let w = wind?;
    let race = v.race;
    let leader = v.standings.iter().find(|s| s.rank == 1 && s.racing)?;
    let k = leader.legs_completed;
    if k == 0 || k >= race.course.len() {
        return None;
    }
    let a = DVec2::from(race.marks[race.course[k - 1]].position);
    let b = DVec2::from(race.marks[race.course[k]].position);
    let leg_bearing = race::track::bearing_deg((b - a).into());
    let off = (leg_bearing - w.from_deg + 540.0).rem_euclid(360.0) - 180.0;
    (off.abs() < 60.0).then_some(b)
}

/// Gap texts and ahead/behind lines: across each racing boat's current leg axis, through the
/// boat, with its course distance behind the leader in metres and seconds (the leader's speed
/// along its own leg's axis turns metres into seconds).
pub fn ahead_behind(v: &View, texts: &mut Vec<SceneText>) -> Layer {
    let race = v.race;
    if race.course.len() < 2 {
        return Layer::Hidden("the race has no course: no legs to measure along".into());
    }
    let axis_of = |k: usize| -> Option<(DVec2, f64)> {
        if k == 0 || k >= race.course.len() {
            return None;
        }
        let a = DVec2::from(race.marks[race.course[k - 1]].position);
        let b = DVec2::from(race.marks[race.course[k]].position);
        let d = b - a;
        (d.length() > 1e-6).then(|| (d / d.length(), d.length()))
    };
    let leader = v.standings.iter().find(|s| s.rank == 1);
    let leader_speed = leader.and_then(|l| {
        let s = v.boats.iter().find(|b| b.index == l.boat)?;
        let (axis, _) = axis_of(l.legs_completed)?;
        let along = DVec2::from(s.state.velocity).dot(axis);
        (along > 0.2).then_some(along)
    });
    let mut out = Vec::new();
    for b in &v.boats {
        let Some(st) = v.standing(b.index).filter(|s| s.racing && !s.finished) else {
            continue;
        };
        let Some((axis, leg_len)) = axis_of(st.legs_completed) else {
            continue;
        };
        let p = DVec2::from(b.state.position);
        let across = DVec2::new(-axis.y, axis.x);
        let half = (0.12 * leg_len).max(3.0 * v.boat_length);
        let is_leader = st.rank == 1;
        let colour = if is_leader {
            rgba(WHITE, 0.6)
        } else {
            rgba(b.colour, 0.5)
        };
        out.extend(water_line(
            v,
            p - across * half,
            p + across * half,
            12,
            colour,
            v.px(1.5),
        ));
        let text = if is_leader {
            "leader".to_string()
        } else {
            match leader_speed {
                Some(s) => format!("+{:.0} m  +{:.0} s", st.distance_m, st.distance_m / s),
                None => format!("+{:.0} m", st.distance_m),
            }
        };
        texts.push(SceneText {
            at: v.on_water(p + across * half),
            offset_pt: [0.0, 0.0],
            text,
            colour: b.colour,
        });
    }
    if out.is_empty() {
        return Layer::Hidden("no boat is racing a leg at this time".into());
    }
    Layer::Draw(out)
}

/// The wind indicator: an arrow on the water pointing downwind, between the camera and what
/// it looks at (so it is in view whatever the camera does), a sixth of that distance long,
/// with the wind's figure at its tail.
pub fn wind_arrow(v: &View, wind: Option<WindInfo>, texts: &mut Vec<SceneText>) -> Layer {
    let Some(w) = wind else {
        return Layer::Hidden("no wind in the race and a calm sea".into());
    };
    let cam = &v.scene.camera;
    // Where the view's centre meets the sea level (the AR camera's target is one metre ahead).
    let forward = (cam.target - cam.eye).normalize();
    let look = if forward.y < -1e-3 {
        cam.eye + forward * (-cam.eye.y / forward.y)
    } else {
        cam.target
    };
    let (eye, target) = (DVec2::new(cam.eye.x, cam.eye.z), DVec2::new(look.x, look.z));
    let centre = target.lerp(eye, 0.35);
    let from = w.from_deg.to_radians();
    let upwind = DVec2::new(from.sin(), -from.cos());
    let len = (eye.distance(target) / 6.0).max(2.0 * v.boat_length);
    let tail = centre + upwind * len / 2.0;
    let head = tail - upwind * len;
    let side = DVec2::new(-upwind.y, upwind.x);
    let barbs = [-1.0, 1.0].map(|s| head + (upwind + side * s * 0.6) * 0.3 * len);
    let mut out = Vec::new();
    // A dark edge under a white arrow: it reads on bright water and on dark.
    for (colour, width) in [
        ([0.0, 0.02, 0.05, 0.6], v.px(8.0)),
        ([0.95, 0.97, 1.0, 0.95], v.px(5.0)),
    ] {
        out.extend(water_line(v, tail, head, 8, colour, width));
        for barb in barbs {
            out.extend(water_line(v, head, barb, 2, colour, width));
        }
    }
    texts.push(SceneText {
        at: v.on_water(tail),
        offset_pt: [0.0, 0.0],
        text: w.text(),
        colour: WHITE,
    });
    Layer::Draw(out)
}
