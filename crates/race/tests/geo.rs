//! The tangent plane against an independent geodesic: Vincenty's inverse formula on WGS84
//! (T. Vincenty, Survey Review 23(176), 1975), written here from the paper, not from geo.rs.

use race::{GeoPoint, LocalFrame};

fn vincenty(p: GeoPoint, q: GeoPoint) -> f64 {
    let a = 6_378_137.0f64;
    let f = 1.0 / 298.257_223_563;
    let b = a * (1.0 - f);
    let l = (q.lon - p.lon).to_radians();
    let u1 = ((1.0 - f) * p.lat.to_radians().tan()).atan();
    let u2 = ((1.0 - f) * q.lat.to_radians().tan()).atan();
    let (su1, cu1) = u1.sin_cos();
    let (su2, cu2) = u2.sin_cos();
    let mut lambda = l;
    for _ in 0..200 {
        let (sl, cl) = lambda.sin_cos();
        let sin_sigma = ((cu2 * sl).powi(2) + (cu1 * su2 - su1 * cu2 * cl).powi(2)).sqrt();
        if sin_sigma == 0.0 {
            return 0.0;
        }
        let cos_sigma = su1 * su2 + cu1 * cu2 * cl;
        let sigma = sin_sigma.atan2(cos_sigma);
        let sin_alpha = cu1 * cu2 * sl / sin_sigma;
        let cos2_alpha = 1.0 - sin_alpha * sin_alpha;
        let cos_2sm = if cos2_alpha != 0.0 {
            cos_sigma - 2.0 * su1 * su2 / cos2_alpha
        } else {
            0.0
        };
        let c = f / 16.0 * cos2_alpha * (4.0 + f * (4.0 - 3.0 * cos2_alpha));
        let prev = lambda;
        lambda = l
            + (1.0 - c)
                * f
                * sin_alpha
                * (sigma
                    + c * sin_sigma * (cos_2sm + c * cos_sigma * (-1.0 + 2.0 * cos_2sm * cos_2sm)));
        if (lambda - prev).abs() < 1e-13 {
            let u2s = cos2_alpha * (a * a - b * b) / (b * b);
            let aa = 1.0 + u2s / 16384.0 * (4096.0 + u2s * (-768.0 + u2s * (320.0 - 175.0 * u2s)));
            let bb = u2s / 1024.0 * (256.0 + u2s * (-128.0 + u2s * (74.0 - 47.0 * u2s)));
            let ds = bb
                * sin_sigma
                * (cos_2sm
                    + bb / 4.0
                        * (cos_sigma * (-1.0 + 2.0 * cos_2sm * cos_2sm)
                            - bb / 6.0
                                * cos_2sm
                                * (-3.0 + 4.0 * sin_sigma * sin_sigma)
                                * (-3.0 + 4.0 * cos_2sm * cos_2sm)));
            return b * aa * (sigma - ds);
        }
    }
    panic!("Vincenty did not converge");
}

/// A point `d` metres from `o` at bearing `brg` (spherical first guess is enough: the test
/// compares the plane with Vincenty between whatever points these are).
fn offset(o: GeoPoint, d: f64, brg: f64) -> GeoPoint {
    let r = 6_371_000.0;
    let dn = d * brg.to_radians().cos();
    let de = d * brg.to_radians().sin();
    GeoPoint::new(
        o.lat + (dn / r).to_degrees(),
        o.lon + (de / (r * o.lat.to_radians().cos())).to_degrees(),
    )
}

#[test]
fn plane_distances_match_vincenty_within_0_1_percent_over_10_km() {
    // Valencia, Gdańsk, Auckland, the equator and 70° N.
    let origins = [
        GeoPoint::new(39.408, -0.3188),
        GeoPoint::new(54.37, 18.78),
        GeoPoint::new(-36.84, 174.76),
        GeoPoint::new(0.0, 0.0),
        GeoPoint::new(70.0, 25.0),
    ];
    let mut worst: f64 = 0.0;
    for o in origins {
        let f = LocalFrame::new(o);
        for brg in (0..360).step_by(15) {
            let brg = brg as f64;
            // From the origin to 10 km, and across the origin (5 km each side).
            for (p, q) in [
                (o, offset(o, 10_000.0, brg)),
                (offset(o, 5_000.0, brg), offset(o, 5_000.0, brg + 180.0)),
                (offset(o, 7_000.0, brg), offset(o, 7_000.0, brg + 90.0)),
            ] {
                let (a, b) = (f.to_local(p), f.to_local(q));
                let plane = (a[0] - b[0]).hypot(a[1] - b[1]);
                let geod = vincenty(p, q);
                let rel = (plane - geod).abs() / geod;
                worst = worst.max(rel);
                assert!(rel <= 1e-3, "{o:?} {brg}: plane {plane} geodesic {geod}");
            }
        }
    }
    // The tangent plane is far better than the 0.1 % goal: report what it is.
    eprintln!("worst relative distance error over 10 km: {worst:.2e}");
    assert!(worst < 1e-5);
}

#[test]
fn axes_are_east_and_south_and_the_inverse_round_trips() {
    let o = GeoPoint::new(39.408, -0.3188);
    let f = LocalFrame::new(o);
    let north = f.to_local(GeoPoint::new(39.418, -0.3188));
    assert!(north[1] < -1000.0 && north[0].abs() < 1e-6, "{north:?}");
    let east = f.to_local(GeoPoint::new(39.408, -0.3088));
    assert!(east[0] > 800.0 && east[1].abs() < 1.0, "{east:?}");
    assert_eq!(f.to_local(o), [0.0, 0.0]);
    for xz in [[1234.5, -987.6], [-5000.0, 4000.0], [0.25, 0.0]] {
        let back = f.to_local(f.to_geo(xz));
        assert!(
            (back[0] - xz[0]).abs() < 1e-6 && (back[1] - xz[1]).abs() < 1e-6,
            "{back:?}"
        );
    }
}
