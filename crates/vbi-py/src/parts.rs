//! The parts of a scenario, each given as the scenario file names it: a bridge preset
//! (`paper-3x30`), a vehicle preset or a road class, a path to a `.toml` file of that kind, or a
//! dict holding such a file's document.

use std::path::PathBuf;

use numpy::{IntoPyArray, PyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use vbi::model::BridgeModel;
use vbi::road::{generate, RoadSpec};
use vbi::vehicle::{assemble, VehicleSpec, PRESET_NAMES};
use vbi_input::resolve::Resolver;
use vbi_input::{bridge, road, vehicle, SourceFile};

use crate::arrays::matrix;
use crate::errors::{input_error, library_error};
use crate::source;

/// Where a name given from Python stands in messages (the resolver's "file").
const ARGUMENT: &str = "<argument>";

/// A name (a preset, a class, a path) or a dict, as Python gave it.
enum Given {
    Name(String),
    Document(SourceFile),
}

fn given(source: &Bound<'_, PyAny>, kind: &str, caller: &str) -> PyResult<Given> {
    if source.cast::<PyDict>().is_ok() {
        return source::of_kind(source, kind, caller).map(Given::Document);
    }
    let path: PathBuf = source.extract()?;
    Ok(Given::Name(path.display().to_string()))
}

/// The resolver's view of a name given as an argument: paths are relative to the working
/// directory.
fn argument_file() -> SourceFile {
    SourceFile::from_text(PathBuf::from(ARGUMENT), String::new())
}

/// A bridge model: a preset `paper-NxL` (N spans of L m), a `[bridge]` TOML file, or a dict of
/// that file's document (`{"bridge": {...}}`). SI units inside.
#[pyclass(module = "vbi", frozen, from_py_object)]
#[derive(Clone)]
pub struct Bridge {
    pub model: BridgeModel,
    /// How the bridge was named, for reports (`paper-3x30 (preset)`, a path, `<dict>`).
    #[pyo3(get)]
    pub label: String,
}

#[pymethods]
impl Bridge {
    #[new]
    fn new(source: &Bound<'_, PyAny>) -> PyResult<Bridge> {
        match given(source, "bridge", "vbi.Bridge")? {
            Given::Document(file) => Ok(Bridge {
                model: bridge::load(&file).map_err(input_error)?,
                label: file.name(),
            }),
            Given::Name(name) => {
                let named = Resolver::default()
                    .bridge(&argument_file(), "bridge", &name)
                    .map_err(input_error)?;
                Ok(Bridge {
                    model: named.model,
                    label: named.label,
                })
            }
        }
    }

    /// Span lengths [m], first to last.
    #[getter]
    fn span_lengths_m(&self) -> Vec<f64> {
        self.model.span_lengths().to_vec()
    }

    /// Length between the end supports [m], along the girders.
    #[getter]
    fn length_m(&self) -> f64 {
        self.model.length()
    }

    /// The deck's extent along x [m], where vehicles are on it: `length_m`, plus the offset of
    /// the outer girders' supports on a skewed grillage.
    #[getter]
    fn deck_length_m(&self) -> f64 {
        self.model.deck_length()
    }

    /// Support positions along the girders [m].
    #[getter]
    fn support_positions_m(&self) -> Vec<f64> {
        self.model.support_positions()
    }

    fn __repr__(&self) -> String {
        format!(
            "vbi.Bridge({:?}, spans_m={:?})",
            self.label,
            self.model.span_lengths()
        )
    }
}

/// A vehicle: a preset name (`vbi.vehicle_presets()`), a `[vehicle]` TOML file, or a dict of that
/// file's document (`{"vehicle": {...}}`).
#[pyclass(module = "vbi", frozen, from_py_object)]
#[derive(Clone)]
pub struct Vehicle {
    pub spec: VehicleSpec,
}

#[pymethods]
impl Vehicle {
    #[new]
    fn new(source: &Bound<'_, PyAny>) -> PyResult<Vehicle> {
        let spec = match given(source, "vehicle", "vbi.Vehicle")? {
            Given::Document(file) => vehicle::load(&file).map_err(input_error)?,
            Given::Name(name) => Resolver::default()
                .vehicle(&argument_file(), "vehicle", &name)
                .map_err(input_error)?,
        };
        Ok(Vehicle { spec })
    }

    /// Name (preset name or file stem).
    #[getter]
    fn name(&self) -> String {
        self.spec.name.clone()
    }

    /// Where the parameters come from.
    #[getter]
    fn source(&self) -> String {
        self.spec.source.clone()
    }

    /// The assembled model: `dof_names`, the mass [kg, kg·m²], damping [N·s/m, ...] and
    /// stiffness [N/m, ...] matrices (DOFs × DOFs) and the tyre contacts' longitudinal offsets
    /// from the front axle [m], lateral offsets [m] and static loads [N].
    fn model<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let model = assemble(&self.spec).map_err(|e| library_error(&e))?;
        let dict = PyDict::new(py);
        dict.set_item("dof_names", model.dof_names.clone())?;
        dict.set_item("mass_matrix", matrix(py, &model.mass_matrix)?)?;
        dict.set_item("damping_matrix", matrix(py, &model.damping_matrix)?)?;
        dict.set_item("stiffness_matrix", matrix(py, &model.stiffness_matrix)?)?;
        let column = |f: fn(&vbi::vehicle::TyreContact) -> f64| -> Bound<'py, PyArray1<f64>> {
            model
                .contacts
                .iter()
                .map(f)
                .collect::<Vec<_>>()
                .into_pyarray(py)
        };
        dict.set_item(
            "contact_longitudinal_offsets_m",
            column(|c| c.longitudinal_offset),
        )?;
        dict.set_item("contact_lateral_offsets_m", column(|c| c.lateral_offset))?;
        dict.set_item("contact_static_loads_n", column(|c| c.static_load))?;
        Ok(dict)
    }

    fn __repr__(&self) -> String {
        format!("vbi.Vehicle({:?})", self.spec.name)
    }
}

/// A road: an ISO 8608 class name (`"medium"`, `"A"`...), a `[road]` TOML file, or a dict of that
/// file's document (`{"road": {...}}`).
#[pyclass(module = "vbi", frozen, from_py_object)]
#[derive(Clone)]
pub struct Road {
    pub spec: RoadSpec,
}

#[pymethods]
impl Road {
    #[new]
    fn new(source: &Bound<'_, PyAny>) -> PyResult<Road> {
        let spec = match given(source, "road", "vbi.Road")? {
            Given::Document(file) => road::load(&file).map_err(input_error)?,
            Given::Name(name) => Resolver::default()
                .road(&argument_file(), "road", &name, &RoadSpec::default())
                .map_err(input_error)?,
        };
        Ok(Road { spec })
    }

    /// The road's seed (the crossing's seed).
    #[getter]
    fn seed(&self) -> u64 {
        self.spec.seed
    }

    /// A profile sample from `start_m` to `end_m` [m] (bridge coordinates): positions x [m] and
    /// the left and right track elevations [m], as the crossing samples it. `seed` defaults to
    /// the road's own.
    #[pyo3(signature = (start_m, end_m, seed = None))]
    #[allow(clippy::type_complexity)]
    fn profile<'py>(
        &self,
        py: Python<'py>,
        start_m: f64,
        end_m: f64,
        seed: Option<u64>,
    ) -> PyResult<(
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray1<f64>>,
    )> {
        let seed = seed.unwrap_or(self.spec.seed);
        let spec = &self.spec;
        let profile = py
            .detach(|| generate(spec, start_m, end_m, seed))
            .map_err(|e| library_error(&e))?;
        let positions: Vec<f64> = (0..profile.left.len())
            .map(|i| profile.position(i))
            .collect();
        Ok((
            positions.into_pyarray(py),
            profile.left.into_pyarray(py),
            profile.right.into_pyarray(py),
        ))
    }

    fn __repr__(&self) -> String {
        format!("vbi.Road({:?})", self.spec.roughness)
    }
}

/// The names of the vehicle presets.
#[pyfunction]
pub fn vehicle_presets() -> Vec<&'static str> {
    PRESET_NAMES.to_vec()
}
