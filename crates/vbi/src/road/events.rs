//! Deterministic road events (an expansion-joint step, an approach-settlement ramp, a bump or a
//! dip, a sine stretch) superposed on the road profile, and user (measured) profiles that replace
//! the random roughness.
//!
//! Positions are deck coordinates x [m] from the first support (negative on the approach);
//! elevations are in metres, positive upwards, like the roughness. An event is evaluated at the
//! profile's sample positions and added to the tracks it applies to; the slope comes from the
//! profile's interpolant ([`RoadProfile::elevation_and_slope`](super::RoadProfile)), so the
//! sample spacing must resolve each event's shortest feature ([`RESOLUTION_SAMPLES`]).

use std::f64::consts::PI;

use serde::{Deserialize, Serialize};

use super::{RoadError, Track};

/// Fewest sample spacings Δx per equivalent wavelength of an event's shortest feature: a sine's
/// wavelength λ ≥ 4Δx, a bump's length L ≥ 4Δx (one period of its cosine), a step's or a ramp's
/// transition length ≥ 2Δx (half a period). Four samples per wavelength keep a sampled cosine's
/// peak within 1 − cos(π/4) ≈ 29 % of its true value at worst, and twice Nyquist.
pub const RESOLUTION_SAMPLES: f64 = 4.0;

/// The wheel tracks an event applies to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum EventTracks {
    /// Both tracks (the default).
    Both,
    /// The left track only.
    Left,
    /// The right track only.
    Right,
}

impl EventTracks {
    /// Whether the event applies to `track`.
    pub fn includes(self, track: Track) -> bool {
        matches!(
            (self, track),
            (EventTracks::Both, _)
                | (EventTracks::Left, Track::Left)
                | (EventTracks::Right, Track::Right)
        )
    }
}

/// The shape of a bump.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BumpShape {
    /// h = H (1 − cos 2πs)/2: zero elevation and slope at both ends (the default).
    Cosine,
    /// h = H sin πs: zero elevation at both ends, slope ±πH/L there.
    HalfSine,
}

/// One deterministic event's shape; s denotes the local coordinate of the formula given.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum EventShape {
    /// An expansion-joint step of height H [m] at x_p [m], smoothed over a transition length
    /// L > 0 [m] centred on x_p: h = H (1 − cos πs)/2 with s = (x − x_p + L/2)/L clamped to
    /// [0, 1], so h = 0 before x_p − L/2 and H after x_p + L/2 (held to the profile's end).
    Step {
        /// Position x_p of the step's middle [m].
        position: f64,
        /// Height H [m] (positive: the road rises in the direction of travel).
        height: f64,
        /// Transition length L [m] > 0, at least 2 sample spacings.
        length: f64,
    },
    /// An approach settlement or any linear ramp: h = 0 for x ≤ x_a, H (x − x_a)/(x_b − x_a)
    /// on [x_a, x_b], and H for x ≥ x_b (held to the profile's end).
    Ramp {
        /// Start x_a of the ramp [m].
        start: f64,
        /// End x_b > x_a of the ramp [m], at least 2 sample spacings after x_a.
        end: f64,
        /// Elevation H reached at x_b [m] (negative for a settlement).
        height: f64,
    },
    /// A bump (positive H) or a dip or pothole (negative H) of length L centred on x_c, of
    /// the given shape with s = (x − x_c + L/2)/L ∈ [0, 1]; zero outside.
    Bump {
        /// Centre x_c [m].
        centre: f64,
        /// Length L [m] > 0, at least 4 sample spacings.
        length: f64,
        /// Height H [m] at the centre (negative: a dip).
        height: f64,
        /// The shape of the bump.
        shape: BumpShape,
    },
    /// A sine stretch: h = A sin(2π (x − x_a)/λ + φ) on [x_a, x_b], zero outside (the
    /// elevation jumps at an end where the sine is not zero: choose φ and a whole number of
    /// wavelengths for a continuous road).
    Sine {
        /// Start x_a [m].
        start: f64,
        /// End x_b > x_a [m].
        end: f64,
        /// Wavelength λ [m] > 0, at least 4 sample spacings.
        wavelength: f64,
        /// Amplitude A [m].
        amplitude: f64,
        /// Phase φ [rad] at x_a.
        phase: f64,
    },
}

/// A deterministic event on one or both wheel tracks.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RoadEvent {
    /// The tracks it applies to.
    pub tracks: EventTracks,
    /// Its shape and position.
    pub shape: EventShape,
}

/// (1 − cos πs)/2 for s clamped to [0, 1]: 0, rising smoothly to 1.
fn smooth_rise(s: f64) -> f64 {
    0.5 * (1.0 - (PI * s.clamp(0.0, 1.0)).cos())
}

impl EventShape {
    /// The elevation h(x) [m] of the event at deck position x [m] (the formulas above).
    pub fn elevation(&self, x: f64) -> f64 {
        match *self {
            EventShape::Step {
                position,
                height,
                length,
            } => height * smooth_rise((x - position + 0.5 * length) / length),
            EventShape::Ramp { start, end, height } => {
                height * ((x - start) / (end - start)).clamp(0.0, 1.0)
            }
            EventShape::Bump {
                centre,
                length,
                height,
                shape,
            } => {
                let s = (x - centre + 0.5 * length) / length;
                if !(0.0..=1.0).contains(&s) {
                    return 0.0;
                }
                match shape {
                    BumpShape::Cosine => height * 0.5 * (1.0 - (2.0 * PI * s).cos()),
                    BumpShape::HalfSine => height * (PI * s).sin(),
                }
            }
            EventShape::Sine {
                start,
                end,
                wavelength,
                amplitude,
                phase,
            } => {
                if x < start || x > end {
                    return 0.0;
                }
                amplitude * (2.0 * PI * (x - start) / wavelength + phase).sin()
            }
        }
    }

    /// Checks the event's numbers against the largest sample spacing Δx [m]; `index` is the
    /// event's place in the list, for the message.
    pub fn validate(&self, index: usize, spacing: f64) -> Result<(), RoadError> {
        let finite = |quantity: &'static str, value: f64| -> Result<(), RoadError> {
            if value.is_finite() {
                Ok(())
            } else {
                Err(RoadError::InvalidEvent {
                    index,
                    quantity,
                    value,
                    allowed: "a finite number".to_string(),
                })
            }
        };
        let resolved = |quantity: &'static str, value: f64, spacings: f64| {
            let least = spacings * spacing;
            if value.is_finite() && value >= least {
                Ok(())
            } else {
                Err(RoadError::InvalidEvent {
                    index,
                    quantity,
                    value,
                    allowed: format!(
                        "at least {spacings} sample spacings ({least} m at {spacing} m); a \
                         finer sample spacing resolves a shorter one"
                    ),
                })
            }
        };
        let half = 0.5 * RESOLUTION_SAMPLES;
        match *self {
            EventShape::Step {
                position,
                height,
                length,
            } => {
                finite("position", position)?;
                finite("height", height)?;
                resolved("transition length", length, half)
            }
            EventShape::Ramp { start, end, height } => {
                finite("start", start)?;
                finite("end", end)?;
                finite("height", height)?;
                resolved("length end - start", end - start, half)
            }
            EventShape::Bump {
                centre,
                length,
                height,
                ..
            } => {
                finite("centre", centre)?;
                finite("height", height)?;
                resolved("length", length, RESOLUTION_SAMPLES)
            }
            EventShape::Sine {
                start,
                end,
                wavelength,
                amplitude,
                phase,
            } => {
                finite("start", start)?;
                finite("end", end)?;
                finite("amplitude", amplitude)?;
                finite("phase", phase)?;
                resolved("wavelength", wavelength, RESOLUTION_SAMPLES)?;
                if end > start {
                    Ok(())
                } else {
                    Err(RoadError::InvalidEvent {
                        index,
                        quantity: "end",
                        value: end,
                        allowed: format!("a position after the start {start} m"),
                    })
                }
            }
        }
    }
}

/// Adds every event that applies to `track` to its samples at x_i = start + i·spacing.
pub fn add_events(
    events: &[RoadEvent],
    track: Track,
    start: f64,
    spacing: f64,
    samples: &mut [f64],
) {
    for event in events.iter().filter(|e| e.tracks.includes(track)) {
        for (i, sample) in samples.iter_mut().enumerate() {
            *sample += event.shape.elevation(start + i as f64 * spacing);
        }
    }
}

/// A user or measured profile in SI units: positions x [m] in deck coordinates, strictly
/// increasing, and the left and right elevations [m] there. It replaces the random roughness;
/// the generated profile interpolates it linearly at its own sample positions.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UserProfile {
    /// Positions x [m], strictly increasing, at least 2.
    pub positions: Vec<f64>,
    /// Left track elevation [m] at each position.
    pub left: Vec<f64>,
    /// Right track elevation [m] at each position.
    pub right: Vec<f64>,
}

impl UserProfile {
    /// Checks lengths, finiteness and increasing positions.
    pub fn validate(&self) -> Result<(), RoadError> {
        super::check_measured(&self.positions, &self.left, &self.right)
    }

    /// The extent [first, last position] [m].
    pub fn extent(&self) -> (f64, f64) {
        (
            self.positions.first().copied().unwrap_or(0.0),
            self.positions.last().copied().unwrap_or(0.0),
        )
    }

    /// Whether the profile covers [start, end] [m], to 10⁻⁹ of a sample spacing [m] (so that a
    /// profile written over exactly the extent is accepted despite round-off in the grid).
    pub fn covers(&self, start: f64, end: f64, spacing: f64) -> Result<(), RoadError> {
        let (first, last) = self.extent();
        let tolerance = 1e-9 * spacing;
        if first <= start + tolerance && last >= end - tolerance {
            Ok(())
        } else {
            Err(RoadError::ProfileDoesNotCover {
                start,
                end,
                first,
                last,
            })
        }
    }

    /// Both tracks interpolated linearly at x_i = start + i·spacing, i < count (positions
    /// beyond the ends by round-off take the end values).
    pub fn resampled(&self, start: f64, spacing: f64, count: usize) -> (Vec<f64>, Vec<f64>) {
        let grid: Vec<f64> = (0..count).map(|i| start + i as f64 * spacing).collect();
        (
            super::resample_linear(&self.positions, &self.left, &grid),
            super::resample_linear(&self.positions, &self.right, &grid),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tracks_select_the_track() {
        assert!(EventTracks::Both.includes(Track::Right));
        assert!(EventTracks::Left.includes(Track::Left));
        assert!(!EventTracks::Left.includes(Track::Right));
        assert!(!EventTracks::Right.includes(Track::Left));
    }

    #[test]
    fn validation_names_the_event_and_the_quantity() {
        let sine = EventShape::Sine {
            start: 0.0,
            end: 10.0,
            wavelength: 0.1,
            amplitude: 0.01,
            phase: 0.0,
        };
        match sine.validate(3, 0.05) {
            Err(RoadError::InvalidEvent {
                index: 3,
                quantity: "wavelength",
                ..
            }) => {}
            other => panic!("{other:?}"),
        }
        let bump = EventShape::Bump {
            centre: f64::NAN,
            length: 1.0,
            height: 0.01,
            shape: BumpShape::Cosine,
        };
        assert!(bump.validate(0, 0.05).is_err());
    }
}
