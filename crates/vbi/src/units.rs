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
/// Pascals in one kip per square inch [Pa per ksi]: 4,448.2216152605 N over 0.0254² m² (the
/// stress unit of AASHTO LRFD's fatigue tables).
pub const KSI: f64 = 4_448.221_615_260_5 / (0.0254 * 0.0254);
/// Pascals in one gigapascal [Pa per GPa].
pub const GPA: f64 = 1.0e9;
/// Kilograms in one tonne [kg per t].
pub const TONNE: f64 = 1.0e3;
/// Standard gravity g [m/s²]; the value used by VBI-2D and the paper's loads.
pub const GRAVITY: f64 = 9.81;
/// Metres in one decimetre [m per dm] (the lengths of traffic files: CASTOR, BeDIT, DITIS).
pub const DM: f64 = 0.1;
/// Newtons of weight of one hundred kilograms [N per 100 kg]: 100 g (the axle weights of
/// CASTOR, BeDIT and DITIS traffic files; PyBTLS converts them with 0.981 kN, the same g).
pub const HUNDRED_KG_WEIGHT: f64 = 100.0 * GRAVITY;
/// Newtons of weight of one kilogram [N per kg]: g (the axle weights of MON traffic files).
pub const KG_WEIGHT: f64 = GRAVITY;
/// Seconds in one millisecond [s per ms].
pub const MILLISECOND: f64 = 1.0e-3;

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

/// A number as a message shows it: as written for everyday magnitudes, in exponent form beyond
/// (1e308 as `1e308`, not three hundred digits).
pub fn shown(value: f64) -> String {
    let magnitude = value.abs();
    if value.is_finite() && magnitude != 0.0 && !(1e-4..1e15).contains(&magnitude) {
        format!("{value:e}")
    } else {
        format!("{value}")
    }
}

/// Digits a number in a message may have before [`with_short_numbers`] rewrites it.
const LONGEST_NUMBER_DIGITS: usize = 24;

/// The text with every number of more than 24 digits (`100000…0` for 1e308, as Rust's and
/// serde's `Display` write a float) rewritten as [`shown`] writes it (`1e308`). Messages that
/// quote a value as the parser read it pass through this, so that none shows three hundred
/// digits (issue 47).
pub fn with_short_numbers(text: &str) -> std::borrow::Cow<'_, str> {
    let bytes = text.as_bytes();
    let mut out = String::new();
    let mut copied = 0;
    let mut i = 0;
    while i < bytes.len() {
        if !bytes[i].is_ascii_digit() {
            i += 1;
            continue;
        }
        // The number: an optional minus before it, digits, one point, digits.
        let start = if i > 0 && bytes[i - 1] == b'-' {
            i - 1
        } else {
            i
        };
        let mut end = i;
        let mut seen_point = false;
        while end < bytes.len()
            && (bytes[end].is_ascii_digit()
                || (bytes[end] == b'.'
                    && !seen_point
                    && bytes.get(end + 1).is_some_and(u8::is_ascii_digit)))
        {
            seen_point |= bytes[end] == b'.';
            end += 1;
        }
        let digits = bytes[i..end].iter().filter(|b| b.is_ascii_digit()).count();
        if digits > LONGEST_NUMBER_DIGITS {
            if let Ok(value) = text[start..end].parse::<f64>() {
                out.push_str(&text[copied..start]);
                out.push_str(&shown(value));
                copied = end;
            }
        }
        i = end;
    }
    if copied == 0 {
        std::borrow::Cow::Borrowed(text)
    } else {
        out.push_str(&text[copied..]);
        std::borrow::Cow::Owned(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eighty_kmh_is_22_2_metres_per_second() {
        assert!((kmh_to_metres_per_second(80.0) - 22.222_222_222_222_22).abs() < 1e-12);
    }

    #[test]
    fn numbers_of_more_than_24_digits_are_shown_in_exponent_form() {
        let huge = format!("{}", 1e308);
        let tiny = format!("{}", -1e-308);
        let text = format!("`{huge}` is not allowed; time {tiny} s, 12.5 m, 2024");
        assert_eq!(
            with_short_numbers(&text),
            "`1e308` is not allowed; time -1e-308 s, 12.5 m, 2024"
        );
        assert!(matches!(
            with_short_numbers("12345678901234567890 is 20 digits"),
            std::borrow::Cow::Borrowed(_)
        ));
    }
}
