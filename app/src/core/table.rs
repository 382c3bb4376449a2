//! Where the race (or the pool) stands on the table: one mapping, `ar::arcore::CoursePlacement`
//! (race metres → AR metres: scale, turn about the vertical, anchor), for the desktop feed and
//! the phone alike. Both fit the race's own bounds (every track and mark, [`RACE_MARGIN`] of
//! the table left free around them) onto a table: the desktop onto a recorded table, the phone
//! onto the room on the tapped plane about the tapped point ([`TableRoom`]). The sea stays larger than the race, but
//! only its part over the table is drawn ([`table_area`]: the scene's play area on the table).
//! Both keep the sea `table_depth` above the table top.

use ar::arcore::CoursePlacement;
use glam::{DQuat, DVec2, DVec3};
use render::Camera;

use super::ar::DisplayCamera;

/// Length of a boat model on the table, AR metres: a real boat at table scale is a fraction of
/// a millimetre, so boats are drawn as 5 cm models (their positions stay exact).
pub const MODEL_BOAT_M: f64 = 0.05;
/// Width of the table the course is first fitted to on the phone, AR metres.
pub const FIRST_TABLE_M: f64 = 1.0;
/// Share of the table's side left free around the race's bounds: they fill (1 − RACE_MARGIN)
/// of the table along the side that binds, with RACE_MARGIN / 2 of it on each side. 10 %: on
/// the phone's 1 m first table that is 5 cm a side, one model boat ([`MODEL_BOAT_M`]), so a
/// boat at the far end of its track, heading anywhere, is still whole on the water with its
/// team ring (0.7 model lengths around it); 4 cm on the synthetic feed's 0.8 m deep table. A
/// larger margin only shrinks the race.
pub const RACE_MARGIN: f64 = 0.1;
/// Least extent of the race fitted on a table, race metres: a race without tracks or one boat
/// standing still gets 200 m of sea (twenty hulls), not a point.
pub const MIN_RACE_SIDE_M: f64 = 200.0;
/// AR metres per pool metre when the pool is first placed: the 2 m × 1.6 m pool becomes a
/// 30 cm tub on the table.
pub const POOL_TO_TABLE: f64 = 0.15;

/// The world of the camera-image backdrop: AR metres as they are.
pub const AR_AS_IS: CoursePlacement = CoursePlacement {
    anchor: DVec3::ZERO,
    yaw: 0.0,
    course_to_table: 1.0,
};

/// The sea stands this far above the table top, race metres: the default real sea's depth
/// (`WaterLook::default`, the phone's table effects: `ArConfig::on_table`).
pub fn table_depth() -> f64 {
    render::water_look::WaterLook::default().depth_m
}

/// The centre of `area` (`[min x, min z, max x, max z]`, race metres) at the table's depth
/// below the sea: the race point that sits on the table's centre (or the tapped point).
pub fn course_pivot(area: [f64; 4], table_depth: f64) -> DVec3 {
    let [ax, az, bx, bz] = area;
    DVec3::new(0.5 * (ax + bx), -table_depth, 0.5 * (az + bz))
}

/// How race bounds lie on a table: race metres per table metre, and whether the race is
/// turned a quarter turn so that its longer side lies along the table's longer side.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Fit {
    race_per_table: f64,
    quarter_turn: bool,
}

impl Fit {
    /// `race_bounds` on a table of `extent` (AR metres, x and z): the side that binds fills
    /// (1 − [`RACE_MARGIN`]) of the table; turned a quarter when that draws the race larger.
    fn of(race_bounds: [f64; 4], extent: DVec2) -> Fit {
        let [ax, az, bx, bz] = race_bounds;
        let extent = extent.max(DVec2::splat(1e-9));
        let size = DVec2::new(bx - ax, bz - az);
        let least = MIN_RACE_SIDE_M / extent.max_element();
        let per = |table: DVec2| {
            (size.x / table.x).max(size.y / table.y).max(least) / (1.0 - RACE_MARGIN)
        };
        let (straight, turned) = (per(extent), per(DVec2::new(extent.y, extent.x)));
        Fit {
            race_per_table: straight.min(turned),
            quarter_turn: turned < straight,
        }
    }

    /// The placement's turn about the vertical: a quarter turn takes race +z (south) to the
    /// table's +x.
    fn yaw(self) -> f64 {
        if self.quarter_turn {
            std::f64::consts::FRAC_PI_2
        } else {
            0.0
        }
    }
}

/// The table of `extent` (AR metres) in race metres once `race_bounds` are fitted on it
/// ([`fit_on_table`]), `[min x, min z, max x, max z]`: the bounds with the margin, grown to
/// the table's shape about their centre. The table scene's play area: the water drawn is cut
/// to it, so it covers the table to its edges and spills nowhere.
pub fn table_area(race_bounds: [f64; 4], extent: DVec2) -> [f64; 4] {
    let [ax, az, bx, bz] = race_bounds;
    let fit = Fit::of(race_bounds, extent);
    let along_race = if fit.quarter_turn {
        DVec2::new(extent.y, extent.x)
    } else {
        extent
    };
    let half = 0.5 * along_race * fit.race_per_table;
    let c = 0.5 * DVec2::new(ax + bx, az + bz);
    [c.x - half.x, c.y - half.y, c.x + half.x, c.y + half.y]
}

/// The phone's table under the course: the room on the tapped plane, a rectangle centred on
/// the tapped point along the plane's own axes, so the water drawn on it stays on the table.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TableRoom {
    /// Size along the plane's x and z axes, AR metres (at most [`FIRST_TABLE_M`] a side).
    pub extent: DVec2,
    /// The plane's turn about the vertical (its x axis against AR +x), radians, as
    /// [`CoursePlacement::yaw`] counts it.
    pub yaw: f64,
}

impl TableRoom {
    /// No plane known: the [`FIRST_TABLE_M`] square along the AR axes.
    pub const FIRST: TableRoom = TableRoom {
        extent: DVec2::splat(FIRST_TABLE_M),
        yaw: 0.0,
    };

    /// The room around `point` on `plane`: on each of the plane's axes twice the distance to
    /// the nearer edge of its extent rectangle (ARCore's `ArPlane_getExtentX/Z`; the boundary
    /// polygon is not used), at most [`FIRST_TABLE_M`] and at least [`MIN_ROOM_M`] (a tap
    /// at the very edge still gets a course). `None` when `point` is not on the plane.
    pub fn on_plane(point: DVec3, plane: &ar::DetectedPlane) -> Option<TableRoom> {
        let pose = plane.center_pose.as_dmat4();
        let local = pose.inverse().transform_point3(point);
        let half = 0.5 * plane.extent.as_dvec2();
        let inside = local.y.abs() < 1e-3 && local.x.abs() <= half.x && local.z.abs() <= half.y;
        if !inside {
            return None;
        }
        let room = |h: f64, at: f64| (2.0 * (h - at.abs())).clamp(MIN_ROOM_M, FIRST_TABLE_M);
        let x_axis = pose.transform_vector3(DVec3::X);
        Some(TableRoom {
            extent: DVec2::new(room(half.x, local.x), room(half.y, local.z)),
            yaw: (-x_axis.z).atan2(x_axis.x),
        })
    }

    /// The room under the tapped `point` on the first of `planes` that holds it, else
    /// [`TableRoom::FIRST`].
    pub fn under(point: DVec3, planes: &[ar::DetectedPlane]) -> TableRoom {
        planes
            .iter()
            .find_map(|p| TableRoom::on_plane(point, p))
            .unwrap_or(TableRoom::FIRST)
    }

    /// The water on this room once `race_bounds` are fitted on it: [`table_area`], in race
    /// metres, so it scales and turns with the course.
    pub fn area(&self, race_bounds: [f64; 4]) -> [f64; 4] {
        table_area(race_bounds, self.extent)
    }
}

/// The smallest side of a [`TableRoom`], AR metres: 10 cm, two model boats.
pub const MIN_ROOM_M: f64 = 0.1;

/// The race's bounds `[min x, min z, max x, max z]` (race metres: every track and mark)
/// fitted onto a table of `extent` (AR metres, x and z) whose centre is `table_centre`: the
/// bounds' centre on the table's, the side that binds filling (1 − [`RACE_MARGIN`]) of the
/// table, the race turned a quarter when its longer side then lies along the table's longer
/// side and is drawn larger ([`table_area`] maps exactly onto the table).
pub fn fit_on_table(
    race_bounds: [f64; 4],
    table_centre: DVec3,
    extent: DVec2,
    table_depth: f64,
) -> CoursePlacement {
    let fit = Fit::of(race_bounds, extent);
    let mut p = CoursePlacement {
        anchor: DVec3::ZERO,
        yaw: fit.yaw(),
        course_to_table: 1.0 / fit.race_per_table,
    };
    p.put(course_pivot(race_bounds, table_depth), table_centre);
    p
}

/// The course with its pivot on `point` (AR metres): the turn and scale of `current` once
/// placed, else its bounds fitted to `room`, turned with the plane.
pub fn place_course(
    current: Option<CoursePlacement>,
    point: DVec3,
    race_bounds: [f64; 4],
    table_depth: f64,
    room: TableRoom,
) -> CoursePlacement {
    let mut p = match current {
        Some(p) => p,
        None => {
            let mut p = fit_on_table(race_bounds, point, room.extent, table_depth);
            p.yaw += room.yaw;
            p
        }
    };
    p.put(course_pivot(race_bounds, table_depth), point);
    p
}

/// The pool with its centre on `point` (AR metres), keeping the turn and scale of `current`.
pub fn place_pool(current: Option<CoursePlacement>, point: DVec3) -> CoursePlacement {
    let mut p = current.unwrap_or(CoursePlacement {
        anchor: DVec3::ZERO,
        yaw: 0.0,
        course_to_table: POOL_TO_TABLE,
    });
    p.put(DVec3::ZERO, point);
    p
}

/// The render camera (race metres) for the display-oriented AR camera.
pub fn display_camera(placement: &CoursePlacement, view: &DisplayCamera) -> Camera {
    Camera::from_view_projection(view.view * placement.race_to_ar(), view.projection_gl)
}

/// The AR light direction turned into race axes (the placement's turn undone).
pub fn sun(placement: &CoursePlacement, towards_ar: DVec3) -> DVec3 {
    (DQuat::from_rotation_y(-placement.yaw) * towards_ar).normalize()
}

/// Smallest boat length to draw, race metres, so boats stay visible as table models.
pub fn model_boat_length(placement: &CoursePlacement) -> f64 {
    MODEL_BOAT_M / placement.course_to_table
}

/// Boats drawn at least as table models.
pub fn boats_as_models(scene: &mut render::Scene, placement: &CoursePlacement) {
    let min_len = model_boat_length(placement);
    for b in &mut scene.boats {
        b.length = b.length.max(min_len);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The race point (x, z), at the table's depth under the sea, on the table (AR metres).
    fn on_table(p: &CoursePlacement, x: f64, z: f64, depth: f64) -> DVec3 {
        p.race_to_ar().transform_point3(DVec3::new(x, -depth, z))
    }

    #[test]
    fn fitting_puts_the_race_bounds_on_the_table_with_the_margin_and_the_sea_above_it() {
        // A 3 km × 1 km race on a 1.5 m × 1 m table centred at (2, 0.7, −1). By hand: x binds
        // (3000 / 1.5 = 2000 race m per table m against 1000 / 1 along z), and the race fills
        // 90 % of the table's width: 3000 m on 1.35 m, 2222.2 race m per AR m.
        let bounds = [-1000.0, 0.0, 2000.0, 1000.0];
        let centre = DVec3::new(2.0, 0.7, -1.0);
        let p = fit_on_table(bounds, centre, DVec2::new(1.5, 1.0), 0.8);
        assert!((p.course_to_table - 1.35 / 3000.0).abs() < 1e-15);
        // The bounds' centre (500, 500), 0.8 race metres under the sea, is the table's centre.
        let c = p.ar_to_race().transform_point3(centre);
        assert!((c - DVec3::new(500.0, -0.8, 500.0)).length() < 1e-9, "{c}");
        // The bounds' corners: 7.5 cm (5 % of 1.5 m) inside the west and east edges; along z
        // 1000 m are 0.45 m, centred: 27.5 cm inside the 1 m table's edges.
        let sw = on_table(&p, -1000.0, 0.0, 0.8);
        let ne = on_table(&p, 2000.0, 1000.0, 0.8);
        let want_sw = DVec3::new(2.0 - 0.75 + 0.075, 0.7, -1.0 - 0.225);
        let want_ne = DVec3::new(2.0 + 0.75 - 0.075, 0.7, -1.0 + 0.225);
        assert!((sw - want_sw).length() < 1e-12, "{sw} vs {want_sw}");
        assert!((ne - want_ne).length() < 1e-12, "{ne} vs {want_ne}");
        // The table in race metres: the centre ± (0.75, 0.5) × 2222.2 m.
        let area = table_area(bounds, DVec2::new(1.5, 1.0));
        let want = [
            -1_166.666_666_7,
            -611.111_111_1,
            2_166.666_666_7,
            1_611.111_111_1,
        ];
        for (got, want) in area.iter().zip(want) {
            assert!((got - want).abs() < 1e-6, "{area:?}");
        }
        // ... and it maps exactly onto the table's corners.
        let lo = on_table(&p, area[0], area[1], 0.8);
        let hi = on_table(&p, area[2], area[3], 0.8);
        assert!((lo - DVec3::new(1.25, 0.7, -1.5)).length() < 1e-12, "{lo}");
        assert!((hi - DVec3::new(2.75, 0.7, -0.5)).length() < 1e-12, "{hi}");
    }

    #[test]
    fn a_race_longer_across_the_table_is_turned_to_lie_along_it() {
        // 300 m × 900 m on the synthetic feed's 1.2 m × 0.8 m table. Unturned, z binds
        // (900 / 0.8 = 1125 race m per table m); a quarter turn lays the 900 m along the 1.2 m
        // (900 / 1.2 = 750 against 300 / 0.8 = 375), 900 m on 90 % of 1.2 m: 833.3 race m per
        // AR m against 1250 unturned: the race drawn 1.5 times larger.
        let bounds = [0.0, 0.0, 300.0, 900.0];
        let extent = DVec2::new(1.2, 0.8);
        let p = fit_on_table(bounds, DVec3::ZERO, extent, 1.0);
        assert!((p.course_to_table - 1.08 / 900.0).abs() < 1e-15);
        assert_eq!(p.yaw, std::f64::consts::FRAC_PI_2);
        // Race +z goes to the table's +x, race +x to its −z. The bounds' corner (0, 900) is
        // (−150, 450) m from their centre: on the table (0.54, 0.18) m from its centre, 6 cm
        // (5 % of 1.2 m) inside the +x edge.
        let corner = on_table(&p, 0.0, 900.0, 1.0);
        assert!(
            (corner - DVec3::new(0.54, 0.0, 0.18)).length() < 1e-12,
            "{corner}"
        );
        // The table in race metres: the centre (150, 450) ± (0.4, 0.6) × 833.3 m, which maps
        // onto the table's corners.
        let area = table_area(bounds, extent);
        let want = [150.0 - 1000.0 / 3.0, -50.0, 150.0 + 1000.0 / 3.0, 950.0];
        for (got, want) in area.iter().zip(want) {
            assert!((got - want).abs() < 1e-9, "{area:?}");
        }
        let corners = [
            on_table(&p, area[0], area[1], 1.0),
            on_table(&p, area[2], area[3], 1.0),
        ];
        for c in corners {
            assert!(
                (c.x.abs() - 0.6).abs() < 1e-12 && (c.z.abs() - 0.4).abs() < 1e-12,
                "{c}"
            );
        }
        // A race already lying along the table is not turned.
        let wide = fit_on_table([0.0, 0.0, 900.0, 300.0], DVec3::ZERO, extent, 1.0);
        assert_eq!((wide.yaw, wide.course_to_table), (0.0, p.course_to_table));
    }

    #[test]
    fn a_race_without_extent_gets_the_least_patch_of_sea() {
        // One point: 200 m on 90 % of a 1 m table.
        let area = table_area([5.0, 7.0, 5.0, 7.0], DVec2::ONE);
        let half = 0.5 * MIN_RACE_SIDE_M / 0.9;
        assert_eq!(area, [5.0 - half, 7.0 - half, 5.0 + half, 7.0 + half]);
    }

    #[test]
    fn the_phone_fits_the_race_on_a_first_table_and_its_water_is_that_table() {
        // A 1 km square on the 1 m first table: 1000 m on 0.9 m.
        let bounds = [-500.0, -500.0, 500.0, 500.0];
        let point = DVec3::new(0.1, 0.0, 0.2);
        let first = place_course(None, point, bounds, 1.0, TableRoom::FIRST);
        assert!((first.course_to_table - 0.9e-3).abs() < 1e-15);
        // Its water is the 1 m square around the tapped point.
        let [ax, az, bx, bz] = TableRoom::FIRST.area(bounds);
        let lo = on_table(&first, ax, az, 1.0);
        let hi = on_table(&first, bx, bz, 1.0);
        assert!((lo - DVec3::new(-0.4, 0.0, -0.3)).length() < 1e-12, "{lo}");
        assert!((hi - DVec3::new(0.6, 0.0, 0.7)).length() < 1e-12, "{hi}");
    }

    #[test]
    fn a_new_tap_moves_the_course_keeping_turn_and_scale() {
        let bounds = [-500.0, -500.0, 500.0, 500.0];
        let first = place_course(
            None,
            DVec3::new(0.1, 0.0, 0.2),
            bounds,
            1.0,
            TableRoom::FIRST,
        );
        let mut turned = first;
        turned.apply_gesture(2.0, 0.5);
        let moved = place_course(
            Some(turned),
            DVec3::new(-0.3, 0.1, 0.0),
            bounds,
            1.0,
            TableRoom::FIRST,
        );
        assert_eq!(
            (moved.yaw, moved.course_to_table),
            (turned.yaw, turned.course_to_table)
        );
        let pivot = moved
            .race_to_ar()
            .transform_point3(course_pivot(bounds, 1.0));
        assert!(
            (pivot - DVec3::new(-0.3, 0.1, 0.0)).length() < 1e-12,
            "{pivot}"
        );
    }

    /// A 0.6 m × 0.4 m table turned 30° about the vertical, tapped 10 cm along its x axis and
    /// 5 cm along its z from its centre: the room is 0.4 m × 0.3 m (twice the distance to the
    /// nearer edges), the course is turned with the table, and its water's corners land on the
    /// room's corners, inside the table.
    #[test]
    fn the_phone_fits_the_race_to_the_room_on_the_tapped_plane() {
        let turn = 30f64.to_radians();
        let centre = DVec3::new(0.2, 0.75, -0.1);
        let pose = glam::DMat4::from_rotation_translation(DQuat::from_rotation_y(turn), centre);
        let plane = ar::DetectedPlane {
            center_pose: pose.as_mat4(),
            extent: glam::Vec2::new(0.6, 0.4),
            polygon: Vec::new(),
            kind: ar::PlaneKind::HorizontalUp,
        };
        let tap = pose.transform_point3(DVec3::new(0.1, 0.0, 0.05));
        let room = TableRoom::under(tap, std::slice::from_ref(&plane));
        assert!(
            (room.extent - DVec2::new(0.4, 0.3)).length() < 1e-6,
            "{room:?}"
        );
        assert!((room.yaw - turn).abs() < 1e-6, "{}", room.yaw);
        // Off the plane: the first-table square.
        let off = pose.transform_point3(DVec3::new(0.5, 0.0, 0.0));
        assert_eq!(
            TableRoom::under(off, std::slice::from_ref(&plane)),
            TableRoom::FIRST
        );
        // A 1 km × 500 m race: its longer side along the room's longer (x), filling 90 % of it.
        let bounds = [-500.0, -250.0, 500.0, 250.0];
        let p = place_course(None, tap, bounds, 1.0, room);
        assert!((p.course_to_table - 0.9 * 0.4 / 1000.0).abs() < 1e-9);
        let to_plane = |x: f64, z: f64| pose.inverse().transform_point3(on_table(&p, x, z, 1.0));
        let [ax, az, bx, bz] = room.area(bounds);
        for (x, z) in [(ax, az), (ax, bz), (bx, az), (bx, bz)] {
            let q = to_plane(x, z);
            // A corner of the room: 0.1 ± 0.2 along x, 0.05 ± 0.15 along z, the table's top 1 m
            // of race water below the sea (1 race m = 0.36 mm here).
            assert!(((q.x - 0.1).abs() - 0.2).abs() < 1e-6, "{q}");
            assert!(((q.z - 0.05).abs() - 0.15).abs() < 1e-6, "{q}");
            // Inside the table (to the f32 precision of ARCore's plane pose).
            assert!(q.x.abs() <= 0.3 + 1e-6 && q.z.abs() <= 0.2 + 1e-6, "{q}");
        }
        // The race's own corners lie inside the room with the margin.
        for (x, z) in [(-500.0, -250.0), (500.0, 250.0)] {
            let q = to_plane(x, z);
            assert!(
                (q.x - 0.1).abs() <= 0.9 * 0.2 + 1e-6 && (q.z - 0.05).abs() <= 0.15,
                "{q}"
            );
        }
    }
}
