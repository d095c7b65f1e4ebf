//! `vbi.Scenario`: one crossing in SI units, from a `[scenario]` file, a dict of that document,
//! or the built-in paper scenario; keys set one at a time through the library's key table, with
//! the same refusals as a scenario file.

use std::path::PathBuf;
use vbi::units::metres_per_second_to_kmh;

use pyo3::prelude::*;

use vbi::crossing::keys::{self, Allowed};
use vbi::crossing::KeyValue;
use vbi_input::resolve::Resolver;
use vbi_input::{scenario, InputError, SourceFile};

use crate::errors::input_error;
use crate::parts::{Bridge, Road, Vehicle};
use crate::source;

/// Where a key set from Python stands in messages.
const SET: &str = "<Scenario.set>";

/// One crossing: bridge (with its mesh and modal options), vehicle, road, motion, solver and
/// analysis options, SI units inside. `Scenario()` is the built-in paper scenario (3 × 30 m,
/// five-axle truck, 'medium' road, 80 km/h, seed 1, 50 modes); `Scenario(path)` reads a
/// `[scenario]` TOML file, `Scenario(dict)` the same document as a dict.
#[pyclass(module = "vbi", from_py_object)]
#[derive(Clone)]
pub struct Scenario {
    pub scenario: vbi::crossing::Scenario,
    /// SHA-256 of the scenario text and every file it names (the CLI's provenance hash).
    #[pyo3(get)]
    pub input_hash: String,
}

#[pymethods]
impl Scenario {
    #[new]
    #[pyo3(signature = (source = None))]
    fn new(source: Option<&Bound<'_, PyAny>>) -> PyResult<Scenario> {
        let loaded = match source {
            None => scenario::built_in_default(),
            Some(source) => {
                let file = source::of_kind(source, "scenario", "vbi.Scenario")?;
                scenario::load(&file).map_err(input_error)?
            }
        };
        Ok(Scenario {
            scenario: loaded.scenario,
            input_hash: loaded.input_hash,
        })
    }

    /// Sets one scenario key as a `[scenario]` file writes it (`speed_kmh`, `seed`, `modes`,
    /// `road`, ...; docs/input-format.md), checked as the file's key is; returns self.
    fn set<'py>(
        mut slf: PyRefMut<'py, Self>,
        key: &str,
        value: &Bound<'py, PyAny>,
    ) -> PyResult<PyRefMut<'py, Self>> {
        let value = key_value(value, key)?;
        slf.set_key(key, &value).map_err(input_error)?;
        Ok(slf)
    }

    /// A copy, to vary without changing this one.
    fn copy(&self) -> Scenario {
        self.clone()
    }

    /// Name for reports.
    #[getter]
    fn name(&self) -> String {
        self.scenario.name.clone()
    }

    /// The bridge.
    #[getter]
    fn get_bridge(&self) -> Bridge {
        Bridge {
            model: self.scenario.bridge.model.clone(),
            label: self.scenario.bridge_label.clone(),
        }
    }

    /// Replaces the bridge model, keeping the mesh and modal options.
    #[setter]
    fn set_bridge(&mut self, bridge: Bridge) {
        self.scenario.bridge.model = bridge.model;
        self.scenario.bridge_label = bridge.label;
    }

    /// The vehicle.
    #[getter]
    fn get_vehicle(&self) -> Vehicle {
        Vehicle {
            spec: self.scenario.vehicle.clone(),
        }
    }

    #[setter]
    fn set_vehicle(&mut self, vehicle: Vehicle) {
        self.scenario.vehicle = vehicle.spec;
    }

    /// The road (its seed is the crossing's seed).
    #[getter]
    fn get_road(&self) -> Road {
        Road {
            spec: self.scenario.road.clone(),
        }
    }

    #[setter]
    fn set_road(&mut self, road: Road) {
        self.scenario.road = road.spec;
    }

    /// Speed [m/s].
    #[getter]
    fn speed_m_s(&self) -> f64 {
        self.scenario.motion.speed
    }

    /// Road seed.
    #[getter]
    fn seed(&self) -> u64 {
        self.scenario.road.seed
    }

    /// Modes solved for.
    #[getter]
    fn mode_count(&self) -> usize {
        self.scenario.bridge.modal.mode_count
    }

    fn __repr__(&self) -> String {
        format!(
            "vbi.Scenario({:?}: {} on {} at {:.1} km/h, seed {})",
            self.scenario.name,
            self.scenario.vehicle.name,
            self.scenario.bridge_label,
            metres_per_second_to_kmh(self.scenario.motion.speed),
            self.scenario.road.seed
        )
    }
}

impl Scenario {
    /// A key of the key table: a part by name through the one resolver, anything else through
    /// [`vbi::crossing::Scenario::set`].
    fn set_key(&mut self, key: &str, value: &KeyValue) -> Result<(), InputError> {
        let at = set_source();
        let known = keys::names_for(true);
        let Some(entry) = keys::key(key).filter(|_| known.contains(&key)) else {
            return Err(at.error_at(
                key,
                format!("unknown key `{key}`; expected one of {}", known.join(", ")),
            ));
        };
        if !matches!(entry.allowed, Allowed::Name(_)) {
            return self
                .scenario
                .set(key, value)
                .map_err(|e| scenario::key_error(&at, "scenario", e));
        }
        let KeyValue::Text(name) = value else {
            return Err(at.error_at(
                key,
                format!("{value} is not allowed; expected {}", entry.expected()),
            ));
        };
        let mut resolver = Resolver::default();
        match key {
            "bridge" => {
                let named = resolver.bridge(&at, key, name)?;
                self.scenario.bridge.model = named.model;
                self.scenario.bridge_label = named.label;
            }
            "vehicle" => self.scenario.vehicle = resolver.vehicle(&at, key, name)?,
            _ => self.scenario.road = resolver.road(&at, key, name, &self.scenario.road)?,
        }
        Ok(())
    }
}

/// A Python value as a key's value: as the TOML value a file would hold, then read as the
/// scenario file reads it.
fn key_value(value: &Bound<'_, PyAny>, key: &str) -> PyResult<KeyValue> {
    let value = source::toml_value(value, key)?;
    scenario::key_value(&set_source(), key, &value).map_err(input_error)
}

/// The "file" of keys set from Python.
fn set_source() -> SourceFile {
    SourceFile::from_text(PathBuf::from(SET), String::new())
}
