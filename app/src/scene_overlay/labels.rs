//! Boat labels in screen space: anchored at each boat's masthead, placed so that no two
//! overlap (the selected boats first, then by rank, so the leader's wins), hidden for boats
//! outside the view; and picking: the boat under a screen point.

use super::geometry::View;

/// A boat on screen: its index, the pixel of its hull's centre and a radius that covers the
/// hull (at least [`MIN_PICK_RADIUS_PT`] points, so a tap hits a far boat).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hull {
    pub boat: usize,
    pub centre: [f64; 2],
    pub radius: f64,
    /// The masthead's pixel: the label's anchor.
    pub anchor: [f64; 2],
}

/// Smallest pick radius around a hull, points (a fingertip).
pub const MIN_PICK_RADIUS_PT: f64 = 12.0;
/// Label text size, points (≥ 12 dp on a phone).
pub const LABEL_TEXT_PT: f64 = 14.0;
/// Gap between the masthead and the label's bottom edge, points.
pub const STEM_PT: f64 = 10.0;
/// Padding inside a label box, points.
pub const PAD_PT: f64 = 4.0;
/// Width of the team-colour bar at a label's left, points.
pub const BAR_PT: f64 = 5.0;

/// Rows of candidate spots above a masthead: a bunched fleet stacks its labels this high
/// before one is hidden.
pub const ROWS: usize = 5;

/// A label placed on screen (pixels, y down).
#[derive(Debug, Clone, PartialEq)]
pub struct PlacedLabel {
    pub boat: usize,
    pub text: String,
    /// Linear RGB team colour.
    pub colour: [f32; 3],
    pub rank: Option<usize>,
    pub selected: bool,
    pub anchor: [f64; 2],
    /// min x, min y, max x, max y.
    pub rect: [f64; 4],
}

pub fn overlaps(a: &[f64; 4], b: &[f64; 4], margin: f64) -> bool {
    a[0] < b[2] + margin && b[0] < a[2] + margin && a[1] < b[3] + margin && b[1] < a[3] + margin
}

fn contains(r: &[f64; 4], p: [f64; 2]) -> bool {
    (r[0]..=r[2]).contains(&p[0]) && (r[1]..=r[3]).contains(&p[1])
}

/// Every boat of the view whose masthead projects onto the frame.
pub fn hulls(v: &View) -> Vec<Hull> {
    let min_r = MIN_PICK_RADIUS_PT * v.pixels_per_point;
    v.boats
        .iter()
        .filter_map(|b| {
            let (anchor, _) = v.project(v.masthead(b))?;
            let foot = glam::DVec2::from(b.state.position);
            let (centre, _) = v.project(v.on_water(foot))?;
            if !v.on_screen(anchor) && !v.on_screen(centre) {
                return None;
            }
            // Half the hull's length on screen, seen across (bow to stern at the same depth).
            let bow = glam::DVec3::new(foot.x, 0.0, foot.y)
                + v.scene
                    .camera
                    .up
                    .cross(v.scene.camera.target - v.scene.camera.eye)
                    .normalize()
                    * (0.5 * v.boat_length);
            let half = v
                .project(bow)
                .map_or(0.0, |(p, _)| (p[0] - centre[0]).hypot(p[1] - centre[1]));
            Some(Hull {
                boat: b.index,
                centre,
                radius: half.max(min_r),
                anchor,
            })
        })
        .collect()
}

/// What a boat's label says: its rank and its name, or its sail number where the name is long
/// or missing.
pub fn label_text(boat: &race::Boat, rank: Option<usize>) -> String {
    let name = boat.name.trim();
    let who = if name.is_empty() || name.chars().count() > 14 {
        boat.id.as_str()
    } else {
        name
    };
    match rank {
        Some(r) => format!("{r} {who}"),
        None => who.to_string(),
    }
}

/// One label to place: who, where its anchor is, how big its box is (pixels), its priority.
#[derive(Debug, Clone, PartialEq)]
pub struct LabelSpec {
    pub boat: usize,
    pub anchor: [f64; 2],
    pub size: [f64; 2],
    /// Lower goes first: selected boats, then by rank.
    pub priority: (usize, usize),
}

/// Places labels in priority order, each at the first candidate spot (above its anchor,
/// then shifted right and left by up to a label's width, and up to [`ROWS`] − 1 rows higher) that stays on the `screen` and
/// overlaps no label placed before it; a label with no free spot is hidden (`None`).
pub fn declutter(specs: &[LabelSpec], screen: [f64; 2], stem: f64) -> Vec<Option<[f64; 4]>> {
    let mut order: Vec<usize> = (0..specs.len()).collect();
    order.sort_by_key(|&k| (specs[k].priority, specs[k].boat));
    let mut placed: Vec<[f64; 4]> = Vec::new();
    let mut out = vec![None; specs.len()];
    for k in order {
        let s = &specs[k];
        let [w, h] = s.size;
        let [ax, ay] = s.anchor;
        let spot = (0..ROWS)
            .flat_map(|row| {
                let y = ay - stem - h - row as f64 * (h + 0.25 * stem);
                let g = 0.3 * stem;
                [
                    ax - w / 2.0,
                    ax + g,
                    ax - w - g,
                    ax + w + 2.0 * g,
                    ax - 2.0 * w - 2.0 * g,
                ]
                .map(move |x| [x, y])
            })
            .map(|[x, y]| {
                // Kept on the frame sideways (a boat at the edge keeps its label).
                let x = x.clamp(0.0, (screen[0] - w).max(0.0));
                [x, y, x + w, y + h]
            })
            .find(|r| {
                r[1] >= 0.0 && r[3] <= screen[1] && !placed.iter().any(|p| overlaps(p, r, 1.0))
            });
        if let Some(r) = spot {
            placed.push(r);
            out[k] = Some(r);
        }
    }
    out
}

/// A boat's label before it is measured and placed.
#[derive(Debug, Clone, PartialEq)]
pub struct LabelCandidate {
    pub boat: usize,
    pub text: String,
    pub colour: [f32; 3],
    pub rank: Option<usize>,
    /// Position among the selected boats, if selected.
    pub selected: Option<usize>,
    pub anchor: [f64; 2],
}

/// The labels the view's boats would have: those whose masthead is on the frame.
pub fn candidates(v: &View, hulls: &[Hull], selected: &[usize]) -> Vec<LabelCandidate> {
    hulls
        .iter()
        .filter(|h| v.on_screen(h.anchor))
        .map(|h| {
            let boat = &v.race.boats[h.boat];
            let rank = v
                .standing(h.boat)
                .filter(|s| s.racing || s.finished)
                .map(|s| s.rank);
            LabelCandidate {
                boat: h.boat,
                text: label_text(boat, rank),
                colour: crate::world::linear_colour(&boat.color),
                rank,
                selected: selected.iter().position(|&s| s == h.boat),
                anchor: h.anchor,
            }
        })
        .collect()
}

/// Measures and places `candidates` on a `screen` of pixels at `pixels_per_point`,
/// decluttered; `measure(text, pixels)` is a text's size in pixels at a font size of
/// `pixels`. Sorted by priority (selected, then rank).
pub fn place(
    candidates: &[LabelCandidate],
    screen: [f64; 2],
    pixels_per_point: f64,
    measure: &dyn Fn(&str, f64) -> [f64; 2],
) -> Vec<PlacedLabel> {
    let ppp = pixels_per_point;
    let font_px = LABEL_TEXT_PT * ppp;
    let specs: Vec<LabelSpec> = candidates
        .iter()
        .map(|c| {
            let [tw, th] = measure(&c.text, font_px);
            LabelSpec {
                boat: c.boat,
                anchor: c.anchor,
                size: [tw + (2.0 * PAD_PT + BAR_PT) * ppp, th + 2.0 * PAD_PT * ppp],
                priority: match c.selected {
                    Some(k) => (0, k),
                    None => (1, c.rank.unwrap_or(usize::MAX)),
                },
            }
        })
        .collect();
    let rects = declutter(&specs, screen, STEM_PT * ppp);
    let mut out: Vec<PlacedLabel> = candidates
        .iter()
        .zip(rects)
        .filter_map(|(c, r)| {
            Some(PlacedLabel {
                boat: c.boat,
                text: c.text.clone(),
                colour: c.colour,
                rank: c.rank,
                selected: c.selected.is_some(),
                anchor: c.anchor,
                rect: r?,
            })
        })
        .collect();
    out.sort_by_key(|l| (!l.selected, l.rank.unwrap_or(usize::MAX), l.boat));
    out
}

/// The boat under pixel `p`: a label's box first (the first in priority order), then the
/// nearest hull whose pick radius covers `p`.
pub fn pick(labels: &[PlacedLabel], hulls: &[Hull], p: [f64; 2]) -> Option<usize> {
    if let Some(l) = labels.iter().find(|l| contains(&l.rect, p)) {
        return Some(l.boat);
    }
    hulls
        .iter()
        .map(|h| (h, (h.centre[0] - p[0]).hypot(h.centre[1] - p[1])))
        .filter(|(h, d)| *d <= h.radius)
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(h, _)| h.boat)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(boat: usize, anchor: [f64; 2], rank: usize) -> LabelSpec {
        LabelSpec {
            boat,
            anchor,
            size: [80.0, 22.0],
            priority: (1, rank),
        }
    }

    #[test]
    fn bunched_labels_never_overlap_and_the_leader_keeps_its_spot() {
        // Eight boats within 30 px of each other, the leader (rank 1) listed last.
        let specs: Vec<LabelSpec> = (0..8)
            .map(|k| spec(k, [400.0 + 4.0 * k as f64, 300.0 + 3.0 * k as f64], 8 - k))
            .collect();
        let rects = declutter(&specs, [1280.0, 720.0], 10.0);
        let shown: Vec<[f64; 4]> = rects.iter().flatten().copied().collect();
        assert!(shown.len() >= 6, "most labels find a spot: {}", shown.len());
        for (i, a) in shown.iter().enumerate() {
            for b in &shown[i + 1..] {
                assert!(!overlaps(a, b, 0.0), "{a:?} overlaps {b:?}");
            }
        }
        // The leader's label sits centred right above its own masthead.
        let leader = rects[7].expect("the leader's label is shown");
        let a = specs[7].anchor;
        assert_eq!(leader, [a[0] - 40.0, a[1] - 32.0, a[0] + 40.0, a[1] - 10.0]);
    }

    #[test]
    fn a_selected_boat_wins_over_the_leader() {
        let mut specs = vec![spec(0, [200.0, 34.0], 1), spec(1, [200.0, 34.0], 5)];
        specs[1].priority = (0, 0);
        // One spot only: the anchors leave room for one row above them, and the frame is as
        // wide as a label.
        let rects = declutter(&specs, [80.0, 200.0], 10.0);
        assert!(rects[1].is_some(), "the selected boat's label is shown");
        assert!(rects[0].is_none(), "the leader's gives way: {rects:?}");
    }

    #[test]
    fn labels_stay_on_the_frame_and_picking_finds_label_then_hull() {
        let rects = declutter(&[spec(0, [3.0, 300.0], 1)], [1280.0, 720.0], 10.0);
        let r = rects[0].unwrap();
        assert!(r[0] >= 0.0, "{r:?}");
        let label = PlacedLabel {
            boat: 4,
            text: "1 AUR".into(),
            colour: [1.0, 0.0, 0.0],
            rank: Some(1),
            selected: false,
            anchor: [100.0, 100.0],
            rect: [60.0, 68.0, 140.0, 90.0],
        };
        let hulls = [
            Hull {
                boat: 4,
                centre: [100.0, 130.0],
                radius: 12.0,
                anchor: [100.0, 100.0],
            },
            Hull {
                boat: 2,
                centre: [120.0, 132.0],
                radius: 12.0,
                anchor: [120.0, 100.0],
            },
        ];
        assert_eq!(
            pick(std::slice::from_ref(&label), &hulls, [70.0, 80.0]),
            Some(4)
        );
        assert_eq!(
            pick(&[], &hulls, [117.0, 131.0]),
            Some(2),
            "the nearest hull"
        );
        assert_eq!(pick(&[], &hulls, [300.0, 300.0]), None, "the water");
    }
}
