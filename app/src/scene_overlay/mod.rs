//! The race overlays: boat labels, team rings, trails, course, ahead/behind lines and the wind
//! (docs/overlays.md), drawn over the scene. The same code serves `regatta render` (headless),
//! the desktop window and the phone: [`frame`] turns (race, scene, settings) into the render
//! crate's generic segment layers (`render::passes::segments`: world-space lines and discs,
//! one pass per overlay) and the screen-space labels and texts that egui paints after the
//! frame ([`paint`]). "Overlay" in this project means these and nothing else (the egui panels
//! and bars are the `hud`).
//!
//! **Adding an overlay touches this file only**: a variant of [`OverlayKind`] and its row of
//! [`OVERLAYS`] (its `--overlays` name, the Scene panel's text, the least tier detail that
//! draws it, its pass's name and condition in the frame report, and the function that draws
//! it, usually in [`geometry`]). Everything else reads the table: `--overlays` parsing
//! ([`OverlaySet::parse`]), the Scene panel's switches ([`panel_toggles`]), the tiers
//! ([`OverlaySettings::shows`]), the render passes ([`layer_passes`]) and the drawing
//! ([`frame`]). The render crate knows no overlay.
//!
//! Picking ([`labels::pick`]) maps a screen point to the boat under it (label or hull), so a
//! click or tap selects; [`OverlaySettings::selected`] keeps up to two boats for "compare".

pub mod geometry;
pub mod labels;
pub mod live;
pub mod manoeuvres;
pub mod paint;

use quality::OverlayDetail;
use render::passes::segments::{Layer, LayerPass, Segment, SegmentLayers};

/// The race overlays, in drawing order (a later one is drawn over an earlier one: the labels'
/// rings over the trails).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum OverlayKind {
    Trails,
    Course,
    /// Ahead/behind lines across the current leg's axis.
    Lines,
    Wind,
    /// Boat labels: the GPU part is each boat's team-colour ring and the selected boats'
    /// highlight; the text is egui's, painted after the frame.
    Labels,
}

/// Everything one overlay is, in one row.
pub struct Overlay {
    pub kind: OverlayKind,
    /// The name `--overlays` and the Scene panel's switch use.
    pub name: &'static str,
    /// What the Scene panel's switch says.
    pub label: &'static str,
    /// The least overlay detail (`quality::OverlayDetail`, a tier's) that draws it.
    pub detail: OverlayDetail,
    /// Its segment pass in the frame report: name and what it needs to run.
    pub pass: LayerPass,
    /// Its layer this frame (the overlay is on and the tier's detail draws it).
    draw: fn(&Drawing, &mut Vec<SceneText>) -> Layer,
}

/// What an overlay's drawing reads.
struct Drawing<'a> {
    view: &'a geometry::View<'a>,
    settings: &'a OverlaySettings,
    debrief: Option<&'a race::Debrief>,
    wind: Option<WindInfo>,
}

/// The overlays, one row each, in the Scene panel's order (the drawing order is
/// [`OverlayKind`]'s).
///
/// The tier details, and why (a phone held over a table, the Low tier's OPPO A54 first):
/// - essential (Low): the labels and the course. Who is who and where the marks are answer
///   the first questions anyone asks of a race; both are a few discs and rings per boat or
///   mark.
/// - standard (Medium): adds the trails (with their manoeuvre marks) and the wind arrow. The
///   trails are the largest layer (up to 64 segments per boat) and read with the wind.
/// - full (High, Ultra): adds the ahead/behind lines: an analysis layer whose gap texts
///   crowd a small screen, for the phones (and desktops) with room to spare.
pub const OVERLAYS: [Overlay; 5] = [
    Overlay {
        kind: OverlayKind::Labels,
        name: "labels",
        label: "Boat labels",
        detail: OverlayDetail::Essential,
        pass: LayerPass {
            name: "overlay-labels",
            condition: "labels are on and a boat is in view",
        },
        draw: |d, _| geometry::rings(d.view, d.settings),
    },
    Overlay {
        kind: OverlayKind::Trails,
        name: "trails",
        label: "Trails",
        detail: OverlayDetail::Standard,
        pass: LayerPass {
            name: "overlay-trails",
            condition: "trails are on and a boat's recent track is in view",
        },
        draw: |d, texts| {
            let trails = geometry::trails(d.view, d.settings.trail_s);
            let marks = d.debrief.map_or_else(Vec::new, |b| {
                let s = d.settings;
                manoeuvres::marks(d.view, b, s.trail_s, &s.selected, texts)
            });
            with_marks(trails, marks)
        },
    },
    Overlay {
        kind: OverlayKind::Course,
        name: "course",
        label: "Course and marks",
        detail: OverlayDetail::Essential,
        pass: LayerPass {
            name: "overlay-course",
            condition: "the course is on, the race has marks and one is in view",
        },
        draw: |d, _| geometry::course(d.view, d.settings.rhumb_lines, d.wind),
    },
    Overlay {
        kind: OverlayKind::Lines,
        name: "lines",
        label: "Ahead/behind lines",
        detail: OverlayDetail::Full,
        pass: LayerPass {
            name: "overlay-lines",
            condition: "ahead/behind lines are on, the race has a course and a racing boat is in view",
        },
        draw: |d, texts| geometry::ahead_behind(d.view, texts),
    },
    Overlay {
        kind: OverlayKind::Wind,
        name: "wind",
        label: "Wind",
        detail: OverlayDetail::Standard,
        pass: LayerPass {
            name: "overlay-wind",
            condition: "the wind indicator is on and the wind is known (race data or the sea)",
        },
        draw: |d, texts| geometry::wind_arrow(d.view, d.wind, texts),
    },
];

impl OverlayKind {
    /// Every overlay, in drawing order, built from [`OVERLAYS`] (a kind with two rows, or
    /// rows whose kinds leave a gap in the drawing order, does not compile).
    pub const ALL: [OverlayKind; OVERLAYS.len()] = {
        let mut all = [OverlayKind::Trails; OVERLAYS.len()];
        let mut found = [false; OVERLAYS.len()];
        let mut row = 0;
        while row < OVERLAYS.len() {
            let k = OVERLAYS[row].kind as usize;
            assert!(!found[k], "an overlay kind with two rows in OVERLAYS");
            found[k] = true;
            all[k] = OVERLAYS[row].kind;
            row += 1;
        }
        all
    };

    /// Its row of [`OVERLAYS`].
    pub fn overlay(self) -> &'static Overlay {
        OVERLAYS
            .iter()
            .find(|o| o.kind == self)
            .expect("every kind has its row (OverlayKind::ALL checks it)")
    }

    /// The name `--overlays` and the Scene panel use.
    pub fn name(self) -> &'static str {
        self.overlay().name
    }

    pub fn from_name(name: &str) -> Option<OverlayKind> {
        OVERLAYS.iter().find(|o| o.name == name).map(|o| o.kind)
    }
}

/// The overlays' segment passes in drawing order, for
/// `render::passes::segments::add_segment_passes`.
pub fn layer_passes() -> [LayerPass; OVERLAYS.len()] {
    OverlayKind::ALL.map(|k| k.overlay().pass)
}

/// Adds the overlays' segment passes to `renderer` (once), fed by `layers`.
pub fn add_passes(renderer: &mut render::Renderer, gpu: &render::Gpu, layers: &SegmentLayers) {
    render::passes::segments::add_segment_passes(renderer, gpu, layers, &layer_passes());
}

/// The Scene panel's overlay switches: every overlay, on or off as `settings` has it.
pub fn panel_toggles(set: OverlaySet) -> Vec<ui::EffectToggle> {
    OVERLAYS
        .iter()
        .map(|o| ui::EffectToggle::new(o.name, o.label, set.is_on(o.kind)))
        .collect()
}

/// Which overlays are drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OverlaySet {
    on: [bool; OVERLAYS.len()],
}

impl Default for OverlaySet {
    fn default() -> Self {
        OverlaySet::ALL
    }
}

impl OverlaySet {
    pub const ALL: OverlaySet = OverlaySet {
        on: [true; OVERLAYS.len()],
    };
    pub const NONE: OverlaySet = OverlaySet {
        on: [false; OVERLAYS.len()],
    };

    pub fn is_on(&self, kind: OverlayKind) -> bool {
        self.on[kind as usize]
    }

    pub fn with(mut self, kind: OverlayKind, on: bool) -> Self {
        self.on[kind as usize] = on;
        self
    }

    /// `--overlays LIST`: comma-separated names of [`OVERLAYS`], or `all` / `none` alone.
    pub fn parse(list: &str) -> Result<OverlaySet, String> {
        let names: Vec<&str> = list.split(',').map(str::trim).collect();
        let shown = input::quote(list);
        if names.len() > 1
            && let Some(whole) = names.iter().find(|n| matches!(**n, "all" | "none"))
        {
            return Err(format!(
                "--overlays {shown} is contradictory: \"{whole}\" stands alone, not in a list"
            ));
        }
        let mut set = OverlaySet::NONE;
        for name in names {
            match name {
                "all" => set = OverlaySet::ALL,
                "none" => {}
                _ => match OverlayKind::from_name(name) {
                    Some(k) => set = set.with(k, true),
                    None => {
                        let valid: Vec<&str> = OverlayKind::ALL.map(OverlayKind::name).to_vec();
                        return Err(format!(
                            "--overlays names the unknown overlay {}; the overlays are: {}, all, none",
                            input::quote(name),
                            valid.join(", ")
                        ));
                    }
                },
            }
        }
        Ok(set)
    }
}

/// Default length of the trails, seconds of race time.
pub const DEFAULT_TRAIL_S: f64 = 120.0;
/// How many boats "compare" holds.
pub use ui::MAX_SELECTED;

/// A text anchored at a world point (a gap, the wind): placed by `geometry`, painted by `paint`.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneText {
    pub at: glam::DVec3,
    /// Where the text starts from `at`'s pixel, points (right, down): clear of a mark there.
    pub offset_pt: [f64; 2],
    pub text: String,
    /// Linear RGB.
    pub colour: [f32; 3],
}

/// What the user chose (overlays on, trail length, rhumb lines, selected boats) and the
/// overlay detail of the tier drawn.
#[derive(Debug, Clone, PartialEq)]
pub struct OverlaySettings {
    pub set: OverlaySet,
    /// The tier's overlay detail (`TierRender::overlay`): an overlay is drawn where it is on
    /// and its [`Overlay::detail`] is at most this. `Full` (every overlay the user chose) where
    /// no tier is drawn.
    pub detail: OverlayDetail,
    /// Trail length, seconds of race time (the last N minutes).
    pub trail_s: f64,
    /// Draw the rhumb lines between consecutive course marks.
    pub rhumb_lines: bool,
    /// Selected boats (indices into `Race::boats`), oldest first, at most [`MAX_SELECTED`].
    pub selected: Vec<usize>,
}

impl Default for OverlaySettings {
    fn default() -> Self {
        OverlaySettings {
            set: OverlaySet::ALL,
            detail: OverlayDetail::Full,
            trail_s: DEFAULT_TRAIL_S,
            rhumb_lines: true,
            selected: Vec::new(),
        }
    }
}

impl OverlaySettings {
    /// Whether `kind` is drawn: on, and at the tier's detail.
    pub fn shows(&self, kind: OverlayKind) -> bool {
        self.set.is_on(kind) && kind.overlay().detail <= self.detail
    }

    /// The overlays drawn, in drawing order.
    pub fn shown(&self) -> Vec<OverlayKind> {
        OverlayKind::ALL
            .into_iter()
            .filter(|k| self.shows(*k))
            .collect()
    }

    /// Why `kind` is not drawn (the frame report's reason), or `None` where it is.
    fn why_hidden(&self, kind: OverlayKind) -> Option<String> {
        let o = kind.overlay();
        if !self.set.is_on(kind) {
            Some(format!("turned off (\"{}\" not in --overlays)", o.name))
        } else if o.detail > self.detail {
            Some(format!(
                "the tier's overlay detail is {}; the {} overlay needs {}",
                detail_name(self.detail),
                o.name,
                detail_name(o.detail)
            ))
        } else {
            None
        }
    }

    /// Turns the overlay `name` on or off (the Effects panel's toggles, by name).
    pub fn set_overlay(&mut self, name: &str, on: bool) -> Result<(), String> {
        let kind = OverlayKind::from_name(name)
            .ok_or_else(|| format!("there is no overlay named {}", input::quote(name)))?;
        self.set = self.set.with(kind, on);
        Ok(())
    }

    /// A click or tap on `boat` (or on the water: `None`): a selected boat is deselected,
    /// another is added (the oldest of [`MAX_SELECTED`] dropped); the water clears the selection.
    pub fn click(&mut self, boat: Option<usize>) {
        match boat {
            None => self.selected.clear(),
            Some(b) => ui::toggle_selection(&mut self.selected, b),
        }
    }
}

/// Where the wind figure comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum WindSource {
    /// The race file states it.
    Race,
    /// Estimated from the fleet's headings (`race::debrief::wind`): direction only, and said.
    Estimated,
    /// The sea's dominant wave travels downwind (direction only).
    Sea,
}

/// The wind the scene shows (and the panel prints).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct WindInfo {
    /// Compass direction the wind blows from, degrees.
    pub from_deg: f64,
    /// Metres per second, where known.
    pub speed_mps: Option<f64>,
    pub source: WindSource,
    /// One sigma of the direction, degrees, where estimated.
    pub uncertainty_deg: Option<f64>,
}

impl WindInfo {
    /// Every wind label names its source: "wind 8.7 kn from 0° (from the race's data)",
    /// "wind from 59° (estimated from the fleet ±2.0°)", "wind from 225° (the sea's waves)".
    pub fn text(&self) -> String {
        let speed = self
            .speed_mps
            .map_or(String::new(), |v| format!("{:.1} kn ", v * 3600.0 / 1852.0));
        let source = match self.source {
            WindSource::Race => ui::wind_source_text(race::debrief::WindSource::Data, 0.0),
            WindSource::Estimated => ui::wind_source_text(
                race::debrief::WindSource::Estimated,
                self.uncertainty_deg.unwrap_or(f64::NAN),
            ),
            WindSource::Sea => "the sea's waves".to_string(),
        };
        format!("wind {speed}from {:.0}° ({source})", self.from_deg)
    }
}

/// The wind of the race: the files' (a stated wind, or the logs' TWD channels), else the
/// fleet's estimate (said "estimated"), else the direction the sea's dominant wave (largest
/// amplitude) comes from; `None` for a race without wind or sailing on a calm sea.
pub fn wind_of(race: &race::Race, sea: &ocean::WaveSet) -> Option<WindInfo> {
    if let Some(w) = race.wind {
        return Some(WindInfo {
            from_deg: w.from_deg,
            speed_mps: Some(w.speed_mps),
            source: WindSource::Race,
            uncertainty_deg: None,
        });
    }
    if let Some(w) = race.wind_model() {
        return Some(WindInfo {
            from_deg: w.from_deg,
            speed_mps: w.speed_mps,
            source: match w.source {
                race::debrief::WindSource::Data => WindSource::Race,
                race::debrief::WindSource::Estimated => WindSource::Estimated,
            },
            uncertainty_deg: Some(w.uncertainty_deg),
        });
    }
    let amplitude = |w: &ocean::Wave| w.steepness * w.wavelength / std::f64::consts::TAU;
    let dominant = sea
        .waves
        .iter()
        .filter(|w| w.steepness > 0.0)
        .max_by(|a, b| amplitude(a).total_cmp(&amplitude(b)))?;
    let d = dominant.direction;
    Some(WindInfo {
        from_deg: race::track::bearing_deg([-d[0], -d[1]]),
        speed_mps: None,
        source: WindSource::Sea,
        uncertainty_deg: None,
    })
}

/// The name `--tier`'s table and docs give an overlay detail.
pub fn detail_name(detail: OverlayDetail) -> &'static str {
    match detail {
        OverlayDetail::Essential => "essential",
        OverlayDetail::Standard => "standard",
        OverlayDetail::Full => "full",
    }
}

/// Everything the overlays show in one frame: the GPU layers and the screen items.
#[derive(Debug, Clone, PartialEq)]
pub struct OverlayFrame {
    /// Per overlay, in drawing order ([`OverlayKind::ALL`]).
    pub layers: Vec<(OverlayKind, Layer)>,
    /// The boats' labels to measure and place when egui paints ([`labels::place`]).
    pub labels: Vec<labels::LabelCandidate>,
    /// Every boat on screen (for picking hulls).
    pub hulls: Vec<labels::Hull>,
    /// Texts anchored in the scene (gaps on the ahead/behind lines, the wind figure), on
    /// screen.
    pub texts: Vec<paint::ScreenText>,
    pub wind: Option<WindInfo>,
}

impl OverlayFrame {
    /// Hands the layers to the render passes.
    pub fn push(&self, layers: &SegmentLayers) {
        for (kind, layer) in &self.layers {
            layers.set(kind.overlay().pass.name, layer.clone());
        }
    }
}

/// The overlays of `race` over `scene` (its camera, time and boats as drawn) on a `size`
/// pixel frame at `pixels_per_point`; with the race's `debrief` (worked out once per race by
/// the caller) the trails carry its tacks and gybes ([`manoeuvres`]).
pub fn frame(
    race: &race::Race,
    scene: &render::Scene,
    size: [u32; 2],
    pixels_per_point: f64,
    settings: &OverlaySettings,
    debrief: Option<&race::Debrief>,
) -> OverlayFrame {
    let view = geometry::View::new(race, scene, size, pixels_per_point);
    let wind = wind_of(race, &scene.sea);
    let mut texts = Vec::new();
    let drawing = Drawing {
        view: &view,
        settings,
        debrief,
        wind,
    };
    let layers = OverlayKind::ALL
        .into_iter()
        .map(|kind| {
            let layer = match settings.why_hidden(kind) {
                Some(why) => Layer::Hidden(why),
                None => (kind.overlay().draw)(&drawing, &mut texts),
            };
            (kind, layer)
        })
        .collect();
    let hulls = labels::hulls(&view);
    let labels = if settings.shows(OverlayKind::Labels) {
        labels::candidates(&view, &hulls, &settings.selected)
    } else {
        Vec::new()
    };
    let texts = texts
        .into_iter()
        .filter_map(|t| {
            let (at, _) = view.project(t.at)?;
            let pos = [0, 1].map(|k| at[k] + t.offset_pt[k] * pixels_per_point);
            view.on_screen(at).then_some(paint::ScreenText {
                pos,
                text: t.text,
                colour: t.colour,
            })
        })
        .collect();
    OverlayFrame {
        layers,
        labels,
        hulls,
        texts,
        wind,
    }
}

/// The trails' layer with the manoeuvre marks drawn over it.
fn with_marks(trails: Layer, marks: Vec<Segment>) -> Layer {
    match trails {
        Layer::Draw(mut segments) => {
            segments.extend(marks);
            Layer::Draw(segments)
        }
        other if marks.is_empty() => other,
        _ => Layer::Draw(marks),
    }
}

/// Draws `scene` headless with the overlays of `settings` (`regatta render`): adds the
/// overlay passes to `renderer`, feeds them, draws, and paints the labels and texts with egui
/// over the frame, at the pixel scale [`paint::headless_pixels_per_point`] gives `size`. The
/// race comes with its debrief, where the caller worked it out (the trails' manoeuvre marks).
pub fn render_headless(
    gpu: &render::Gpu,
    renderer: &mut render::Renderer,
    race: (&race::Race, Option<&race::Debrief>),
    scene: &render::Scene,
    size: [u32; 2],
    settings: &OverlaySettings,
) -> Result<(image::RgbaImage, render::FrameReport), render::GpuError> {
    render_headless_with(
        gpu,
        renderer,
        &SegmentLayers::default(),
        race,
        scene,
        size,
        settings,
    )
}

/// [`render_headless`] through `layers`, for a renderer that draws frame after frame (a clip):
/// the overlay passes are added once and keep the handle they were added with, so every frame
/// must push its overlays through that same handle, not a fresh one.
pub fn render_headless_with(
    gpu: &render::Gpu,
    renderer: &mut render::Renderer,
    layers: &SegmentLayers,
    (race, debrief): (&race::Race, Option<&race::Debrief>),
    scene: &render::Scene,
    size: [u32; 2],
    settings: &OverlaySettings,
) -> Result<(image::RgbaImage, render::FrameReport), render::GpuError> {
    add_passes(renderer, gpu, layers);
    let ppp = paint::headless_pixels_per_point(size);
    let f = frame(race, scene, size, ppp, settings, debrief);
    f.push(layers);
    let (img, report, _) = paint::render_with_overlays(gpu, renderer, scene, size, &f, ppp)?;
    Ok((img, report))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each tier draws the overlays its detail has, of those the user chose. Truth: the tier
    /// table of `crates/quality` (which detail each tier has) and the details as
    /// docs/overlays.md states them (essential: labels and course; standard: + trails and
    /// wind; full: + ahead/behind lines).
    #[test]
    fn each_tier_draws_the_overlays_its_detail_has() {
        use OverlayKind::{Course, Labels, Lines, Trails, Wind};
        use quality::Tier;
        let stated = |d: OverlayDetail| -> Vec<OverlayKind> {
            match d {
                OverlayDetail::Essential => vec![Course, Labels],
                OverlayDetail::Standard => vec![Trails, Course, Wind, Labels],
                OverlayDetail::Full => vec![Trails, Course, Lines, Wind, Labels],
            }
        };
        let expected = [
            (Tier::Low, OverlayDetail::Essential),
            (Tier::Medium, OverlayDetail::Standard),
            (Tier::High, OverlayDetail::Full),
            (Tier::Ultra, OverlayDetail::Full),
        ];
        for (tier, detail) in expected {
            let t = crate::tier_render::TierRender::of(tier);
            assert_eq!(t.overlay, detail, "{tier}: quality's table changed");
            let settings = OverlaySettings {
                detail: t.overlay,
                ..Default::default()
            };
            assert_eq!(settings.shown(), stated(detail), "{tier}");
            // What the user turned off stays off at every tier.
            let no_course = OverlaySettings {
                set: OverlaySet::ALL.with(Course, false),
                ..settings.clone()
            };
            let mut without = stated(detail);
            without.retain(|k| *k != Course);
            assert_eq!(no_course.shown(), without, "{tier}");
        }
    }

    /// A tier's hidden overlays reach the frame report with the reason, and the labels' egui
    /// texts go with their rings.
    #[test]
    fn an_overlay_the_tier_hides_says_why_and_draws_nothing() {
        let race = race::Race::sample();
        let world = crate::world::RaceWorld::new(race.clone(), ocean::WaveSet::default_sea());
        let scene = world.scene_at(world.middle_time(), None);
        let settings = OverlaySettings {
            detail: OverlayDetail::Essential,
            ..Default::default()
        };
        let f = frame(&race, &scene, [640, 360], 1.0, &settings, None);
        let layer = |k: OverlayKind| {
            f.layers
                .iter()
                .find(|(kind, _)| *kind == k)
                .unwrap()
                .1
                .clone()
        };
        assert_eq!(
            layer(OverlayKind::Trails),
            Layer::Hidden(
                "the tier's overlay detail is essential; the trails overlay needs standard".into()
            )
        );
        assert_eq!(
            layer(OverlayKind::Lines),
            Layer::Hidden(
                "the tier's overlay detail is essential; the lines overlay needs full".into()
            )
        );
        assert!(matches!(layer(OverlayKind::Course), Layer::Draw(_)));
        assert!(!f.labels.is_empty(), "essential keeps the labels");
        let passes: Vec<&str> = layer_passes().iter().map(|p| p.name).collect();
        assert_eq!(
            passes,
            [
                "overlay-trails",
                "overlay-course",
                "overlay-lines",
                "overlay-wind",
                "overlay-labels"
            ],
            "drawing order: the labels' rings over the trails"
        );
    }

    /// The Scene panel's switches are the table's, in its order, and every name round-trips.
    #[test]
    fn the_panel_and_the_names_read_the_table() {
        let toggles = panel_toggles(OverlaySet::ALL.with(OverlayKind::Wind, false));
        let keys: Vec<&str> = toggles.iter().map(|t| t.key.as_str()).collect();
        assert_eq!(keys, ["labels", "trails", "course", "lines", "wind"]);
        assert!(toggles.iter().all(|t| t.enabled == (t.key != "wind")));
        for k in OverlayKind::ALL {
            assert_eq!(OverlayKind::from_name(k.name()), Some(k));
        }
        assert_eq!(OverlayKind::from_name("wakes"), None);
    }

    #[test]
    fn overlays_parse_and_bad_lists_name_the_flag_and_the_name() {
        assert_eq!(OverlaySet::parse("all").unwrap(), OverlaySet::ALL);
        assert_eq!(OverlaySet::parse("none").unwrap(), OverlaySet::NONE);
        let s = OverlaySet::parse("labels, trails").unwrap();
        assert!(s.is_on(OverlayKind::Labels) && s.is_on(OverlayKind::Trails));
        assert!(!s.is_on(OverlayKind::Wind) && !s.is_on(OverlayKind::Course));
        let e = OverlaySet::parse("labels,wakes").unwrap_err();
        assert!(
            e.starts_with("--overlays") && e.contains("\"wakes\""),
            "{e}"
        );
        assert!(!e.contains('\n'));
        let e = OverlaySet::parse("all,labels").unwrap_err();
        assert!(e.contains("contradictory"), "{e}");
        let e = OverlaySet::parse("tr\u{1b}ails").unwrap_err();
        assert!(!e.contains('\u{1b}'), "control characters are escaped: {e}");
        let e = OverlaySet::parse("").unwrap_err();
        assert!(e.contains("--overlays"), "{e}");
    }

    #[test]
    fn clicks_select_up_to_two_boats() {
        let mut s = OverlaySettings::default();
        s.click(Some(3));
        s.click(Some(5));
        assert_eq!(s.selected, [3, 5]);
        s.click(Some(1));
        assert_eq!(s.selected, [5, 1], "the oldest gives way");
        s.click(Some(5));
        assert_eq!(s.selected, [1], "a second click deselects");
        s.click(None);
        assert!(s.selected.is_empty());
        assert!(s.set_overlay("trails", false).is_ok());
        assert!(!s.set.is_on(OverlayKind::Trails));
        assert!(s.set_overlay("wakes", false).is_err());
    }

    #[test]
    fn the_wind_comes_from_the_race_or_against_the_dominant_wave() {
        let race = race::Race::sample();
        let w = wind_of(&race, &ocean::WaveSet::default_sea()).unwrap();
        assert_eq!((w.from_deg, w.speed_mps), (0.0, Some(4.5)));
        // Every label names its source: the sample's file states its wind.
        assert_eq!(w.text(), "wind 8.7 kn from 0° (from the race's data)");
        // Without a stated wind, the fleet's estimate, said so: the generated breeze blows from
        // 0° (oscillating by a few degrees).
        let mut no_wind = race::Race::sample();
        no_wind.wind = None;
        let w = wind_of(&no_wind, &ocean::WaveSet::default_sea()).unwrap();
        assert_eq!(w.source, WindSource::Estimated);
        assert!(
            race::debrief::wind::angle_diff(w.from_deg, 0.0).abs() < 5.0,
            "{w:?}"
        );
        let sigma = no_wind.wind_model().unwrap().uncertainty_deg;
        assert_eq!(
            w.text(),
            format!(
                "wind from {:.0}° (estimated from the fleet ±{sigma:.1}°)",
                w.from_deg
            )
        );
        // A race with too little sailing to estimate: one boat, three fixes.
        let gpx = r#"<?xml version="1.0"?><gpx version="1.1" creator="t" xmlns="http://www.topografix.com/GPX/1/1"><trk><trkseg>
<trkpt lat="39.40" lon="-0.30"><time>2025-06-21T11:00:00Z</time></trkpt>
<trkpt lat="39.40001" lon="-0.30"><time>2025-06-21T11:00:01Z</time></trkpt>
<trkpt lat="39.40002" lon="-0.30"><time>2025-06-21T11:00:02Z</time></trkpt>
</trkseg></trk></gpx>"#;
        let no_wind = race::Race::from_files(&[("t.gpx", gpx.as_bytes())]).unwrap();
        assert!(no_wind.wind_model().is_none());
        // One wave travelling east (+x): the wind blows from the west, 270°.
        let sea = ocean::WaveSet {
            gravity: 9.81,
            depth: None,
            waves: vec![ocean::Wave {
                direction: [1.0, 0.0],
                steepness: 0.1,
                wavelength: 20.0,
                phase: 0.0,
            }],
        };
        let w = wind_of(&no_wind, &sea).unwrap();
        assert!((w.from_deg - 270.0).abs() < 1e-9 && w.speed_mps.is_none());
        assert_eq!(w.text(), "wind from 270° (the sea's waves)");
        let calm = ocean::WaveSet {
            waves: Vec::new(),
            ..sea
        };
        assert!(wind_of(&no_wind, &calm).is_none());
    }
}
