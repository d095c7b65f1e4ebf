//! SI policy and the named unit conversions used at input and in reports.
//!
//! Inside the library every quantity is SI (m, kg, s, N, Pa, rad). Input keys that carry another
//! unit name it (`speed_kmh`), and the caller converts once with these factors.

/// Metres per second in one kilometre per hour [m/s per km/h].
pub const KMH: f64 = 1.0 / 3.6;
/// Metres in one millimetre [m per mm].
pub const MM: f64 = 1.0e-3;
/// Metres in one centimetre [m per cm].
pub const CM: f64 = 1.0e-2;
/// Newtons in one kilonewton [N per kN].
pub const KN: f64 = 1.0e3;
/// Pascals in one megapascal [Pa per MPa].
pub const MPA: f64 = 1.0e6;
/// Pascals in one gigapascal [Pa per GPa].
pub const GPA: f64 = 1.0e9;
/// Kilograms in one tonne [kg per t].
pub const TONNE: f64 = 1.0e3;
/// Standard gravity g [m/s²]; the value used by VBI-2D and the paper's loads.
pub const GRAVITY: f64 = 9.81;

/// Converts a speed from km/h to m/s.
pub fn kmh_to_metres_per_second(speed_kmh: f64) -> f64 {
    speed_kmh * KMH
}

/// A speed in m/s shown in km/h, for output only: v · 3.6 [km/h] (the one place outputs
/// convert it; the product by 3.6, not the division by [`KMH`], which can differ in the last
/// bit).
pub fn metres_per_second_to_kmh(speed: f64) -> f64 {
    speed * 3.6
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eighty_kmh_is_22_2_metres_per_second() {
        assert!((kmh_to_metres_per_second(80.0) - 22.222_222_222_222_22).abs() < 1e-12);
    }
}
