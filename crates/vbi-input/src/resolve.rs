//! The one resolver of names that input files give for a bridge, a vehicle or a road: a preset
//! (or road class), or a `.toml` file relative to the naming file. Scenarios and study axes both
//! use it, so a name that one accepts the other accepts too. Files are read once and their texts
//! kept in the order they were first read, for the input hash.

use std::collections::BTreeMap;

use vbi::crossing::keys;
use vbi::model::{bridge_preset, paper_bridge, BridgeModel};
use vbi::road::{RoadSpec, Roughness};
use vbi::vehicle::{preset, VehicleSpec, PRESET_NAMES};

use crate::kind::kind_of;
pub use crate::source::relative;
use crate::source::{InputError, SourceFile};
use crate::{bridge, road, vehicle};

/// Resolves names to bridges, vehicles and roads; caches the files it reads.
#[derive(Default)]
pub struct Resolver {
    bridges: BTreeMap<String, BridgeModel>,
    vehicles: BTreeMap<String, VehicleSpec>,
    roads: BTreeMap<String, RoadSpec>,
    /// Every file read, by the name it was given, with its text, in the order first read.
    pub files: Vec<(String, String)>,
}

/// A resolved bridge and how it was named, for reports.
pub struct NamedBridge {
    /// The model.
    pub model: BridgeModel,
    /// `paper-3x30 (preset)` or the file's path.
    pub label: String,
}

impl Resolver {
    /// The file `name` that `file` names at `at`, which must be a file of `kind`: a file of
    /// another kind is refused at `at`, and a stray or misspelt top-level table in it
    /// (`[vehicle]` in a bridge file, `[brdige]`) where it stands, as `vbi check` refuses it in
    /// a file given alone, instead of its keys being dropped.
    fn read(
        &mut self,
        file: &SourceFile,
        at: &str,
        name: &str,
        kind: &str,
    ) -> Result<SourceFile, InputError> {
        let path = relative(file, name);
        let source = SourceFile::read(&path).map_err(|e| file.error_at(at, e.to_string()))?;
        let found = kind_of(&source)?;
        if found != kind {
            return Err(file.error_at(
                at,
                format!("`{name}` is a [{found}] file; expected a [{kind}] file"),
            ));
        }
        self.files.push((name.to_string(), source.text.clone()));
        Ok(source)
    }

    /// A bridge preset `paper-NxL` or a `[bridge]` file; `at` is where the name stands.
    pub fn bridge(
        &mut self,
        file: &SourceFile,
        at: &str,
        name: &str,
    ) -> Result<NamedBridge, InputError> {
        if let Some((spans, length)) = bridge_preset(name) {
            return Ok(NamedBridge {
                model: paper_bridge(spans, length),
                label: format!("{name} (preset)"),
            });
        }
        if !name.ends_with(".toml") {
            return Err(file.error_at(
                at,
                format!(
                    "`{name}` is neither a preset nor a .toml file; expected {}",
                    keys::key("bridge")
                        .map(|k| k.expected())
                        .unwrap_or_default()
                ),
            ));
        }
        if !self.bridges.contains_key(name) {
            let source = self.read(file, at, name, "bridge")?;
            self.bridges
                .insert(name.to_string(), bridge::load(&source)?);
        }
        Ok(NamedBridge {
            model: self.bridges[name].clone(),
            label: relative(file, name).display().to_string(),
        })
    }

    /// A vehicle preset or a `[vehicle]` file; `at` is where the name stands.
    pub fn vehicle(
        &mut self,
        file: &SourceFile,
        at: &str,
        name: &str,
    ) -> Result<VehicleSpec, InputError> {
        if let Some(spec) = preset(name) {
            return Ok(spec);
        }
        if !name.ends_with(".toml") {
            return Err(file.error_at(
                at,
                format!(
                    "`{name}` is neither a preset nor a .toml file; expected a [vehicle] file or \
                     one of: {}",
                    PRESET_NAMES.join(", ")
                ),
            ));
        }
        if !self.vehicles.contains_key(name) {
            let source = self.read(file, at, name, "vehicle")?;
            self.vehicles
                .insert(name.to_string(), vehicle::load(&source)?);
        }
        Ok(self.vehicles[name].clone())
    }

    /// A road class (which sets the roughness of `base`) or a `[road]` file (which replaces
    /// it); `at` is where the name stands.
    pub fn road(
        &mut self,
        file: &SourceFile,
        at: &str,
        name: &str,
        base: &RoadSpec,
    ) -> Result<RoadSpec, InputError> {
        if !name.ends_with(".toml") {
            let class = road::parse_class(name).map_err(|m| file.error_at(at, m))?;
            return Ok(RoadSpec {
                roughness: Roughness::Class(class),
                ..base.clone()
            });
        }
        if !self.roads.contains_key(name) {
            let source = self.read(file, at, name, "road")?;
            let (spec, sources) = road::load_with_sources(&source)?;
            self.files.extend(sources);
            self.roads.insert(name.to_string(), spec);
        }
        Ok(self.roads[name].clone())
    }
}
