//! Road surface roughness: ISO 8608 spectra (paper Eq. 21), seeded generation (Eq. 22), left and
//! right wheel tracks.

/// A wheel track.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Track {
    /// Left wheel track (y > 0 side of the vehicle).
    Left,
    /// Right wheel track.
    Right,
}

impl Track {
    /// The track of a wheel at a lateral offset from the vehicle centreline [m]; a wheel on the
    /// centreline (2D models) runs on the left track.
    pub fn of_lateral_offset(lateral_offset: f64) -> Track {
        if lateral_offset < 0.0 {
            Track::Right
        } else {
            Track::Left
        }
    }
}

/// Road elevation on two tracks, sampled at a uniform spacing.
#[derive(Debug, Clone, PartialEq)]
pub struct RoadProfile {
    /// Position x of the first sample [m], in bridge coordinates (negative on the approach).
    pub start: f64,
    /// Sample spacing [m].
    pub spacing: f64,
    /// Left track elevation [m], upwards positive.
    pub left: Vec<f64>,
    /// Right track elevation [m], upwards positive.
    pub right: Vec<f64>,
}

impl RoadProfile {
    /// A perfectly smooth road over [start, end] [m].
    pub fn smooth(start: f64, end: f64) -> RoadProfile {
        RoadProfile {
            start,
            spacing: (end - start).max(1.0),
            left: vec![0.0; 2],
            right: vec![0.0; 2],
        }
    }

    fn samples(&self, track: Track) -> &[f64] {
        match track {
            Track::Left => &self.left,
            Track::Right => &self.right,
        }
    }

    /// Elevation [m] and slope dr/dx [-] at x, linear between samples; zero outside the profile.
    pub fn elevation_and_slope(&self, track: Track, x: f64) -> (f64, f64) {
        let samples = self.samples(track);
        let s = (x - self.start) / self.spacing;
        if !(s >= 0.0) || samples.len() < 2 {
            return (0.0, 0.0);
        }
        let i = s.floor() as usize;
        if i + 1 >= samples.len() {
            return (0.0, 0.0);
        }
        let f = s - i as f64;
        let slope = (samples[i + 1] - samples[i]) / self.spacing;
        (samples[i] + f * (samples[i + 1] - samples[i]), slope)
    }
}
