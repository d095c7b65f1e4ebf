//! A truck of recorded or simulated traffic, as weigh-in-motion records and traffic
//! simulators (PyBTLS's CASTOR, BeDIT, DITIS and MON files; vbi's CSV) give it: when it
//! arrives, in which lane and direction, how fast, and its axles' spacings and loads. A
//! lifetime analysis ([`crate::lifetime`]) reads a stream of them.

use super::TravelDirection;

/// One truck of a traffic record, in SI units (converted once from the file's units at input).
#[derive(Debug, Clone, PartialEq)]
pub struct RecordedTruck {
    /// Time at which the front axle reaches the deck entry of its direction [s], counted from
    /// the start of the record's first day (day d's midnight is d × 86 400 s).
    pub arrival_time: f64,
    /// The lane, numbered from 1 as the record numbers them.
    pub lane: usize,
    /// Direction of travel: forward enters at x = 0, backward at x = L.
    pub direction: TravelDirection,
    /// Speed [m/s], constant over the deck; positive.
    pub speed: f64,
    /// Distance from each axle to the next [m] (one fewer than the axles); positive.
    pub axle_spacings: Vec<f64>,
    /// Static load of each axle [N], front first; non-negative.
    pub axle_loads: Vec<f64>,
}

impl RecordedTruck {
    /// Gross weight [N]: the sum of the axle loads.
    pub fn gross_weight(&self) -> f64 {
        self.axle_loads.iter().sum()
    }

    /// Distance from the front axle to the last [m].
    pub fn wheelbase(&self) -> f64 {
        self.axle_spacings.iter().sum()
    }

    /// Each axle's distance behind the front axle [m], front first (0 for the front axle).
    pub fn axle_offsets(&self) -> Vec<f64> {
        let mut offsets = Vec::with_capacity(self.axle_loads.len());
        let mut behind = 0.0;
        offsets.push(0.0);
        for spacing in &self.axle_spacings {
            behind += spacing;
            offsets.push(behind);
        }
        offsets
    }

    /// What is wrong with the truck, if anything: at least one axle, one spacing fewer than
    /// axles, finite positive speed and spacings, finite non-negative loads, a finite
    /// non-negative time and a lane from 1.
    pub fn check(&self) -> Result<(), String> {
        if self.axle_loads.is_empty() {
            return Err("a truck needs at least one axle".into());
        }
        if self.axle_spacings.len() + 1 != self.axle_loads.len() {
            return Err(format!(
                "{} axle loads need {} spacings, got {}",
                self.axle_loads.len(),
                self.axle_loads.len() - 1,
                self.axle_spacings.len()
            ));
        }
        if !(self.speed.is_finite() && self.speed > 0.0) {
            return Err(format!(
                "the speed must be positive, got {} m/s",
                self.speed
            ));
        }
        if let Some(s) = self
            .axle_spacings
            .iter()
            .find(|s| !(s.is_finite() && **s > 0.0))
        {
            return Err(format!("an axle spacing must be positive, got {s} m"));
        }
        if let Some(w) = self
            .axle_loads
            .iter()
            .find(|w| !(w.is_finite() && **w >= 0.0))
        {
            return Err(format!("an axle load must be non-negative, got {w} N"));
        }
        if !(self.arrival_time.is_finite() && self.arrival_time >= 0.0) {
            return Err(format!(
                "the time must be non-negative, got {} s",
                self.arrival_time
            ));
        }
        if self.lane == 0 {
            return Err("lanes are numbered from 1".into());
        }
        Ok(())
    }
}
