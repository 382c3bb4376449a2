//! Where the race (or the pool) stands on the table: one mapping, `ar::arcore::CoursePlacement`
//! (race metres → AR metres: scale, turn about the vertical, anchor), for the desktop feed and
//! the phone alike. The desktop fits the play area onto a recorded table; the phone puts the
//! play area's centre on a tapped point. Both keep the sea `table_depth` above the table top.

use ar::arcore::CoursePlacement;
use glam::{DQuat, DVec2, DVec3};
use render::Camera;

use super::ar::DisplayCamera;

/// Length of a boat model on the table, AR metres: a real boat at table scale is a fraction of
/// a millimetre, so boats are drawn as 5 cm models (their positions stay exact).
pub const MODEL_BOAT_M: f64 = 0.05;
/// Width of the table the course is first fitted to on the phone, AR metres.
pub const FIRST_TABLE_M: f64 = 1.0;
/// AR metres per pool metre when the pool is first placed: the 2 m × 1.6 m pool becomes a
/// 30 cm tub on the table.
pub const POOL_TO_TABLE: f64 = 0.15;

/// The world of the camera-image backdrop: AR metres as they are.
pub const AR_AS_IS: CoursePlacement = CoursePlacement {
    anchor: DVec3::ZERO,
    yaw: 0.0,
    course_to_table: 1.0,
};

/// The sea stands this far above the table top, race metres (the effect passes' table).
pub fn table_depth() -> f64 {
    effects::passes::ArConfig::default().table_depth
}

/// The play area's centre at the table's depth below the sea: the race point that sits on the
/// table's centre (or the tapped point).
pub fn course_pivot(play_area: [f64; 4], table_depth: f64) -> DVec3 {
    let [ax, az, bx, bz] = play_area;
    DVec3::new(0.5 * (ax + bx), -table_depth, 0.5 * (az + bz))
}

/// The play area `[min x, min z, max x, max z]` (race metres) fitted onto a table of `extent`
/// (AR metres, x and z) whose centre is `table_centre`, unturned: the larger side fills the table.
pub fn fit_on_table(
    play_area: [f64; 4],
    table_centre: DVec3,
    extent: DVec2,
    table_depth: f64,
) -> CoursePlacement {
    let [ax, az, bx, bz] = play_area;
    let race_per_ar = ((bx - ax) / extent.x).max((bz - az) / extent.y).max(1e-9);
    let mut p = CoursePlacement {
        anchor: DVec3::ZERO,
        yaw: 0.0,
        course_to_table: 1.0 / race_per_ar,
    };
    p.put(course_pivot(play_area, table_depth), table_centre);
    p
}

/// The course with its pivot on `point` (AR metres): the turn and scale of `current` once
/// placed, else fitted to a [`FIRST_TABLE_M`] table.
pub fn place_course(
    current: Option<CoursePlacement>,
    point: DVec3,
    play_area: [f64; 4],
    table_depth: f64,
) -> CoursePlacement {
    match current {
        Some(mut p) => {
            p.put(course_pivot(play_area, table_depth), point);
            p
        }
        None => fit_on_table(play_area, point, DVec2::splat(FIRST_TABLE_M), table_depth),
    }
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

    #[test]
    fn fitting_maps_the_play_area_onto_the_table_and_the_sea_above_it() {
        // A 3 km × 1 km play area on a 1.5 m × 1 m table centred at (2, 0.7, −1): 2000 race
        // metres per AR metre (the longer side fills the table).
        let area = [-1000.0, 0.0, 2000.0, 1000.0];
        let centre = DVec3::new(2.0, 0.7, -1.0);
        let p = fit_on_table(area, centre, DVec2::new(1.5, 1.0), 0.8);
        assert!((p.course_to_table - 1.0 / 2000.0).abs() < 1e-15);
        let to_race = p.ar_to_race();
        // The table's centre is the play area's centre, 0.8 race metres under the sea.
        let c = to_race.transform_point3(centre);
        assert!((c - DVec3::new(500.0, -0.8, 500.0)).length() < 1e-9, "{c}");
        // The table's east edge (0.75 AR m east) is the play area's east edge.
        let e = to_race.transform_point3(centre + DVec3::new(0.75, 0.0, 0.0));
        assert!((e.x - 2000.0).abs() < 1e-9, "{e}");
    }

    #[test]
    fn a_new_tap_moves_the_course_keeping_turn_and_scale() {
        let area = [-500.0, -500.0, 500.0, 500.0];
        let first = place_course(None, DVec3::new(0.1, 0.0, 0.2), area, 1.0);
        assert!((first.course_to_table - 1e-3).abs() < 1e-15);
        let mut turned = first;
        turned.apply_gesture(2.0, 0.5);
        let moved = place_course(Some(turned), DVec3::new(-0.3, 0.1, 0.0), area, 1.0);
        assert_eq!(
            (moved.yaw, moved.course_to_table),
            (turned.yaw, turned.course_to_table)
        );
        let pivot = moved.race_to_ar().transform_point3(course_pivot(area, 1.0));
        assert!(
            (pivot - DVec3::new(-0.3, 0.1, 0.0)).length() < 1e-12,
            "{pivot}"
        );
    }
}
