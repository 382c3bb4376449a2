//! Latitude/longitude to local metres: an east-north-up tangent plane on the WGS84 ellipsoid,
//! all in f64. Race metres are x east, z south (docs/command-line.md), so z = -north.
//!
//! The plane is the true local tangent plane (ECEF difference rotated into ENU at the origin,
//! the up component dropped), so distances within a course are exact to the order of
//! (d / R)^2 ≈ 2.5e-6 relative at 10 km; `tests/geo.rs` checks this against Vincenty's geodesic.

use serde::{Deserialize, Serialize};

/// WGS84 semi-major axis, metres.
pub const WGS84_A: f64 = 6_378_137.0;
/// WGS84 flattening.
pub const WGS84_F: f64 = 1.0 / 298.257_223_563;
const E2: f64 = WGS84_F * (2.0 - WGS84_F);

/// A geographic point in degrees (WGS84).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GeoPoint {
    pub lat: f64,
    pub lon: f64,
}

impl GeoPoint {
    pub fn new(lat: f64, lon: f64) -> Self {
        GeoPoint { lat, lon }
    }
    /// Finite and inside [-90, 90] × [-180, 180].
    pub fn is_valid(&self) -> bool {
        self.lat.is_finite()
            && self.lon.is_finite()
            && self.lat.abs() <= 90.0
            && self.lon.abs() <= 180.0
    }
}

fn ecef(lat_deg: f64, lon_deg: f64) -> [f64; 3] {
    let (sp, cp) = lat_deg.to_radians().sin_cos();
    let (sl, cl) = lon_deg.to_radians().sin_cos();
    let n = WGS84_A / (1.0 - E2 * sp * sp).sqrt();
    [n * cp * cl, n * cp * sl, n * (1.0 - E2) * sp]
}

/// The local tangent plane around a course origin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalFrame {
    origin: GeoPoint,
    o: [f64; 3],
    sin_lat: f64,
    cos_lat: f64,
    sin_lon: f64,
    cos_lon: f64,
}

impl LocalFrame {
    pub fn new(origin: GeoPoint) -> Self {
        let (sin_lat, cos_lat) = origin.lat.to_radians().sin_cos();
        let (sin_lon, cos_lon) = origin.lon.to_radians().sin_cos();
        LocalFrame {
            origin,
            o: ecef(origin.lat, origin.lon),
            sin_lat,
            cos_lat,
            sin_lon,
            cos_lon,
        }
    }

    pub fn origin(&self) -> GeoPoint {
        self.origin
    }

    /// (east, north) metres of a geographic point.
    pub fn east_north(&self, p: GeoPoint) -> (f64, f64) {
        let q = ecef(p.lat, p.lon);
        let d = [q[0] - self.o[0], q[1] - self.o[1], q[2] - self.o[2]];
        let e = -self.sin_lon * d[0] + self.cos_lon * d[1];
        let n = -self.sin_lat * self.cos_lon * d[0] - self.sin_lat * self.sin_lon * d[1]
            + self.cos_lat * d[2];
        (e, n)
    }

    /// Race metres `[x east, z south]` of a geographic point.
    pub fn to_local(&self, p: GeoPoint) -> [f64; 2] {
        let (e, n) = self.east_north(p);
        [e, -n]
    }

    /// The geographic point whose race metres are `xz` (the inverse of [`to_local`]),
    /// by Newton iteration on the ellipsoid; converges to well below a millimetre within a
    /// few hundred kilometres of the origin.
    ///
    /// [`to_local`]: LocalFrame::to_local
    pub fn to_geo(&self, xz: [f64; 2]) -> GeoPoint {
        let (te, tn) = (xz[0], -xz[1]);
        let mut p = self.origin;
        for _ in 0..8 {
            let (e, n) = self.east_north(p);
            let (de, dn) = (te - e, tn - n);
            if de.abs() < 1e-7 && dn.abs() < 1e-7 {
                break;
            }
            let s = p.lat.to_radians().sin();
            let w = (1.0 - E2 * s * s).sqrt();
            let m = WGS84_A * (1.0 - E2) / (w * w * w); // meridian radius
            let nn = WGS84_A / w; // prime vertical radius
            let cl = p.lat.to_radians().cos().max(1e-12);
            p.lat += (dn / m).to_degrees();
            p.lon += (de / (nn * cl)).to_degrees();
        }
        p
    }
}
