//! Fatigue details: `[[fatigue_detail]]` tables beside `[scenario]` (docs/input-format.md,
//! "Fatigue details"; docs/fatigue.md).
//!
//! ```toml
//! [[fatigue_detail]]
//! name = "bottom_flange_mid"     # optional; default <station>_<fibre>
//! station = "span1_mid_section"  # a station of the bridge (automatic or [[station]])
//! quantity = "bending_moment"    # default; or "shear_force"
//! category_mpa = 71              # EN 1993-1-9 Δσ_C (Δτ_C for shear); or aashto_category = "C"
//! partial_factor = 1.0           # γ_Ff γ_Mf (EN 1993-1-9 Table 3.1), default 1
//! stress_concentration = 1.0     # k_f, default 1
//! distribution_factor = 1.0      # the share of the station's effect the member carries
//! section_modulus_m3 = 0.0157    # σ = M/W; or web_area_m2 (τ = V/A_w); or [fatigue_detail.girder]
//!
//! [fatigue_detail.girder]        # the girder's shape, to derive (ȳ − y)/I or Q/(I t_w)
//! bottom_flange_mm = [400, 30]   # width, thickness
//! web_mm = [1200, 12]            # depth, thickness
//! top_flange_mm = [300, 20]
//! slab_mm = [2000, 250]          # optional: effective width, thickness
//! haunch_mm = 50                 # optional (default 0)
//! modular_ratio = 6.5            # with slab_mm: E_steel/E_concrete
//! ```

use vbi::crossing::Scenario;
use vbi::fatigue::{
    AashtoCategory, ConcreteSlab, FatigueDetail, Fibre, GirderSection, Plate, SnCurve, StressKind,
};
use vbi::model::station::Quantity;
use vbi::units::{MM, MPA};

use crate::source::{InputError, SourceFile};

/// Every key of a `[[fatigue_detail]]` table.
const DETAIL_KEYS: [&str; 13] = [
    "name",
    "station",
    "quantity",
    "category_mpa",
    "aashto_category",
    "partial_factor",
    "stress_concentration",
    "distribution_factor",
    "section_modulus_m3",
    "web_area_m2",
    "girder",
    "fibre",
    "fibre_height_mm",
];
/// Every key of a `[fatigue_detail.girder]` table.
const GIRDER_KEYS: [&str; 6] = [
    "bottom_flange_mm",
    "web_mm",
    "top_flange_mm",
    "slab_mm",
    "haunch_mm",
    "modular_ratio",
];

/// Reads `[[fatigue_detail]]` (if any) into the scenario's fatigue details.
pub fn load(
    file: &SourceFile,
    table: &toml::Table,
    scenario: &mut Scenario,
) -> Result<(), InputError> {
    scenario.fatigue_details = read(file, table)?;
    Ok(())
}

/// The `[[fatigue_detail]]` tables of a file (a scenario's or a lifetime's), in order.
pub fn read(file: &SourceFile, table: &toml::Table) -> Result<Vec<FatigueDetail>, InputError> {
    let Some(value) = table.get("fatigue_detail") else {
        return Ok(Vec::new());
    };
    let toml::Value::Array(entries) = value else {
        return Err(file.error_at(
            "fatigue_detail",
            "expected [[fatigue_detail]] tables, one per detail",
        ));
    };
    let mut details: Vec<FatigueDetail> = Vec::with_capacity(entries.len());
    for (i, entry) in entries.iter().enumerate() {
        let at = format!("fatigue_detail[{i}]");
        let toml::Value::Table(entry) = entry else {
            return Err(file.error_at(&at, "expected a [[fatigue_detail]] table"));
        };
        let detail = Reader {
            file,
            at: &at,
            entry,
        }
        .detail()?;
        if let Some(first) = details.iter().position(|other| other.name == detail.name) {
            return Err(file.error_at(
                &format!("{at}.name"),
                format!(
                    "detail `{}` is already defined by fatigue_detail[{first}]; expected a name \
                     of its own",
                    detail.name
                ),
            ));
        }
        details.push(detail);
    }
    Ok(details)
}

/// Each detail of a lifetime on the effect it reads: the effect of its station and quantity
/// among the analysis's (a lifetime tracks its `quantities` at its stations).
pub fn lifetime_details(
    file: &SourceFile,
    details: &[FatigueDetail],
    analysis: &vbi::lifetime::StaticLifetime,
) -> Result<Vec<vbi::lifetime::fatigue::LifetimeDetail>, InputError> {
    details
        .iter()
        .enumerate()
        .map(|(i, detail)| {
            let effect = (analysis.effects.iter())
                .position(|e| e.station == detail.station && e.quantity == detail.quantity)
                .ok_or_else(|| {
                    let known: Vec<String> = (analysis.effects.iter())
                        .map(|e| format!("{} {}", e.station, e.quantity.name()))
                        .collect();
                    file.error_at(
                        &format!("fatigue_detail[{i}].station"),
                        format!(
                            "the lifetime tracks no {} at `{}`; expected one of its effects: {} \
                             (its `quantities` at its stations)",
                            detail.quantity.name(),
                            detail.station,
                            known.join(", ")
                        ),
                    )
                })?;
            Ok(vbi::lifetime::fatigue::LifetimeDetail {
                detail: detail.clone(),
                effect,
            })
        })
        .collect()
}

/// Checks each detail's station and effect against the stations of the bridge: what `vbi check`
/// and `vbi run` refuse before any crossing.
pub fn check(
    file: &SourceFile,
    scenario: &Scenario,
    stations: &[vbi::model::station::Station],
) -> Result<(), InputError> {
    vbi::crossing::check_fatigue_details(stations, &scenario.fatigue_details).map_err(
        |(i, error)| file.error_at(&format!("fatigue_detail[{i}].station"), error.to_string()),
    )
}

/// One `[[fatigue_detail]]` table being read.
struct Reader<'a> {
    file: &'a SourceFile,
    at: &'a str,
    entry: &'a toml::Table,
}

impl Reader<'_> {
    fn error(&self, key: &str, message: impl Into<String>) -> InputError {
        self.file.error_at(&format!("{}.{key}", self.at), message)
    }

    fn number(&self, key: &str) -> Result<Option<f64>, InputError> {
        number_in(
            self.file,
            &format!("{}.{key}", self.at),
            self.entry.get(key),
        )
    }

    fn positive(&self, key: &str, default: Option<f64>) -> Result<Option<f64>, InputError> {
        match self.number(key)?.or(default) {
            Some(x) if !(x > 0.0 && x.is_finite()) => Err(self.error(
                key,
                format!("{x} is not allowed; expected a positive number"),
            )),
            value => Ok(value),
        }
    }

    fn text(&self, key: &str) -> Result<Option<&str>, InputError> {
        match self.entry.get(key) {
            None => Ok(None),
            Some(toml::Value::String(s)) => Ok(Some(s)),
            Some(other) => Err(self.error(key, format!("{other} is not allowed; expected a name"))),
        }
    }

    fn detail(&self) -> Result<FatigueDetail, InputError> {
        if let Some(unknown) = self
            .entry
            .keys()
            .find(|k| !DETAIL_KEYS.contains(&k.as_str()))
        {
            return Err(self.error(
                unknown,
                format!(
                    "unknown key `{unknown}` in [[fatigue_detail]]; expected one of {}",
                    DETAIL_KEYS.join(", ")
                ),
            ));
        }
        let Some(station) = self.text("station")? else {
            return Err(self.file.error_at(
                self.at,
                "a fatigue detail needs `station`: the station whose effect stresses it",
            ));
        };
        let quantity = match self.text("quantity")? {
            None | Some("bending_moment") => Quantity::BendingMoment,
            Some("shear_force") => Quantity::ShearForce,
            Some(other) => {
                return Err(self.error(
                    "quantity",
                    format!("`{other}` is not allowed; expected bending_moment or shear_force"),
                ))
            }
        };
        let curve = self.curve(quantity)?;
        let (stress_per_section, fibre) = self.section(quantity)?;
        // The share of the station's effect that the detail's member carries (a lateral
        // distribution factor), default 1.
        let share = self
            .positive("distribution_factor", Some(1.0))?
            .unwrap_or(1.0);
        let stress_per_effect = share * stress_per_section;
        let stress_concentration = self
            .positive("stress_concentration", Some(1.0))?
            .unwrap_or(1.0);
        let name = match self.text("name")? {
            Some(name) => name.to_string(),
            None => format!("{station}_{fibre}"),
        };
        Ok(FatigueDetail {
            name,
            station: station.to_string(),
            quantity,
            stress_per_effect,
            stress_concentration,
            fibre,
            curve,
        })
    }

    fn curve(&self, quantity: Quantity) -> Result<SnCurve, InputError> {
        let stress = match quantity {
            Quantity::ShearForce => StressKind::Shear,
            _ => StressKind::Direct,
        };
        match (
            self.positive("category_mpa", None)?,
            self.text("aashto_category")?,
        ) {
            (Some(category), None) => {
                if category > 300.0 {
                    return Err(self.error(
                        "category_mpa",
                        format!(
                            "{category} MPa is not a detail category; expected Δσ_C in MPa, \
                             36 to 160 in EN 1993-1-9's tables (Δτ_C 80 or 100)"
                        ),
                    ));
                }
                let partial_factor = self.positive("partial_factor", Some(1.0))?.unwrap_or(1.0);
                Ok(SnCurve::Eurocode {
                    category: category * MPA,
                    stress,
                    partial_factor,
                })
            }
            (None, Some(name)) => {
                if stress == StressKind::Shear {
                    return Err(self.error(
                        "aashto_category",
                        "AASHTO LRFD's categories A to E' are for normal stress ranges; expected \
                         category_mpa (EN 1993-1-9 Δτ_C) for a shear detail",
                    ));
                }
                if self.entry.contains_key("partial_factor") {
                    return Err(self.error(
                        "partial_factor",
                        "γ_Ff γ_Mf is EN 1993-1-9's; expected none with aashto_category",
                    ));
                }
                let category = AashtoCategory::of_name(name).ok_or_else(|| {
                    self.error(
                        "aashto_category",
                        format!(
                            "`{name}` is not allowed; expected one of {}",
                            AashtoCategory::ALL.map(|c| c.name()).join(", ")
                        ),
                    )
                })?;
                Ok(SnCurve::Aashto { category })
            }
            _ => Err(self.file.error_at(
                self.at,
                "a fatigue detail needs one curve: category_mpa (EN 1993-1-9 Δσ_C or Δτ_C, MPa) \
                 or aashto_category (A, B, B', C, C', D, E, E')",
            )),
        }
    }

    /// The stress per unit effect and the fibre in words.
    fn section(&self, quantity: Quantity) -> Result<(f64, String), InputError> {
        let bending = quantity == Quantity::BendingMoment;
        let given = [
            (
                "section_modulus_m3",
                self.entry.contains_key("section_modulus_m3"),
            ),
            ("web_area_m2", self.entry.contains_key("web_area_m2")),
            ("girder", self.entry.contains_key("girder")),
        ];
        let named: Vec<&str> = given.iter().filter(|g| g.1).map(|g| g.0).collect();
        if named.len() != 1 {
            return Err(self.file.error_at(
                self.at,
                format!(
                    "a fatigue detail needs one section: section_modulus_m3 (bending), \
                     web_area_m2 (shear) or a [fatigue_detail.girder] table{}",
                    if named.is_empty() {
                        String::new()
                    } else {
                        format!("; it has {}", named.join(" and "))
                    }
                ),
            ));
        }
        let no_fibre = |what: &str| -> Result<(), InputError> {
            match ["fibre", "fibre_height_mm"]
                .iter()
                .find(|k| self.entry.contains_key(**k))
            {
                Some(key) => Err(self.error(
                    key,
                    format!(
                        "{what} gives the stress itself; expected no `{key}` (it is for a girder)"
                    ),
                )),
                None => Ok(()),
            }
        };
        match named[0] {
            "section_modulus_m3" => {
                if !bending {
                    return Err(self.error(
                        "section_modulus_m3",
                        "a section modulus gives a direct stress; expected web_area_m2 or a \
                         girder for a shear_force detail",
                    ));
                }
                no_fibre("a section modulus")?;
                let modulus = self.positive("section_modulus_m3", None)?.unwrap_or(1.0);
                Ok((1.0 / modulus, "section_modulus".into()))
            }
            "web_area_m2" => {
                if bending {
                    return Err(self.error(
                        "web_area_m2",
                        "a web area gives the mean shear stress V/A_w; expected \
                         section_modulus_m3 or a girder for a bending_moment detail",
                    ));
                }
                no_fibre("a web area")?;
                let area = self.positive("web_area_m2", None)?.unwrap_or(1.0);
                Ok((1.0 / area, "web_area".into()))
            }
            _ => self.girder(bending),
        }
    }

    fn girder(&self, bending: bool) -> Result<(f64, String), InputError> {
        let at = format!("{}.girder", self.at);
        let Some(toml::Value::Table(girder)) = self.entry.get("girder") else {
            return Err(self
                .file
                .error_at(&at, "expected a [fatigue_detail.girder] table"));
        };
        if let Some(unknown) = girder.keys().find(|k| !GIRDER_KEYS.contains(&k.as_str())) {
            return Err(self.file.error_at(
                &format!("{at}.{unknown}"),
                format!(
                    "unknown key `{unknown}` in [fatigue_detail.girder]; expected one of {}",
                    GIRDER_KEYS.join(", ")
                ),
            ));
        }
        let plate = |key: &str| -> Result<Option<Plate>, InputError> {
            let path = format!("{at}.{key}");
            let Some(value) = girder.get(key) else {
                return Ok(None);
            };
            let pair = match value {
                toml::Value::Array(items) if items.len() == 2 => [
                    number_in(self.file, &path, Some(&items[0]))?,
                    number_in(self.file, &path, Some(&items[1]))?,
                ],
                _ => [None, None],
            };
            match pair {
                [Some(width), Some(thickness)] if width > 0.0 && thickness > 0.0 => {
                    Ok(Some(Plate {
                        width: width * MM,
                        thickness: thickness * MM,
                    }))
                }
                _ => Err(self.file.error_at(
                    &path,
                    format!(
                        "{value} is not allowed; expected [width, thickness] in mm, both positive"
                    ),
                )),
            }
        };
        let required = |key: &str| -> Result<Plate, InputError> {
            plate(key)?.ok_or_else(|| {
                self.file.error_at(
                    &at,
                    format!("a girder needs `{key}` = [width, thickness] in mm"),
                )
            })
        };
        let (bottom_flange, web, top_flange) = (
            required("bottom_flange_mm")?,
            required("web_mm")?,
            required("top_flange_mm")?,
        );
        let slab = match plate("slab_mm")? {
            None => {
                if let Some(key) = ["haunch_mm", "modular_ratio"]
                    .into_iter()
                    .find(|k| girder.contains_key(*k))
                {
                    return Err(self.file.error_at(
                        &format!("{at}.{key}"),
                        "belongs to a composite slab; expected slab_mm = [width, thickness] with it",
                    ));
                }
                None
            }
            Some(plate) => {
                let haunch = number_in(
                    self.file,
                    &format!("{at}.haunch_mm"),
                    girder.get("haunch_mm"),
                )?
                .unwrap_or(0.0);
                let Some(modular_ratio) = number_in(
                    self.file,
                    &format!("{at}.modular_ratio"),
                    girder.get("modular_ratio"),
                )?
                else {
                    return Err(self.file.error_at(
                        &at,
                        "a composite slab needs `modular_ratio` = E_steel/E_concrete (about 6 \
                         for traffic: EN 1994-2 §5.4.2.2, n₀)",
                    ));
                };
                Some(ConcreteSlab {
                    plate,
                    haunch: haunch * MM,
                    modular_ratio,
                })
            }
        };
        let section = GirderSection {
            bottom_flange,
            web,
            top_flange,
            slab,
        };
        let (fibre, words) = match (self.text("fibre")?, self.number("fibre_height_mm")?) {
            (Some(_), Some(_)) => {
                return Err(self.error(
                    "fibre_height_mm",
                    "give `fibre` or `fibre_height_mm`, not both",
                ))
            }
            (None, Some(height)) => (Fibre::Height(height * MM), format!("{height}_mm")),
            (Some(name), None) => {
                let fibre = match name {
                    "bottom_flange" => Fibre::BottomFlange,
                    "weld_toe" => Fibre::WeldToe,
                    "top_flange" => Fibre::TopFlange,
                    "neutral_axis" => Fibre::NeutralAxis,
                    other => {
                        return Err(self.error(
                            "fibre",
                            format!(
                                "`{other}` is not allowed; expected bottom_flange, weld_toe, \
                                 top_flange, neutral_axis, or fibre_height_mm"
                            ),
                        ))
                    }
                };
                (fibre, name.to_string())
            }
            (None, None) if bending => (Fibre::BottomFlange, "bottom_flange".into()),
            (None, None) => (Fibre::NeutralAxis, "neutral_axis".into()),
        };
        let stress = match bending {
            true => section.direct_stress_per_moment(fibre),
            false => section.shear_stress_per_force(fibre),
        };
        let key = if self.entry.contains_key("fibre_height_mm") {
            "fibre_height_mm"
        } else if self.entry.contains_key("fibre") {
            "fibre"
        } else {
            "girder"
        };
        stress
            .map(|s| (s, words))
            .map_err(|e| self.error(key, e.to_string()))
    }
}

/// A number at `path` (an integer or a float), or None where absent.
fn number_in(
    file: &SourceFile,
    path: &str,
    value: Option<&toml::Value>,
) -> Result<Option<f64>, InputError> {
    match value {
        None => Ok(None),
        Some(toml::Value::Integer(i)) => Ok(Some(*i as f64)),
        Some(toml::Value::Float(x)) if x.is_finite() => Ok(Some(*x)),
        Some(other) => {
            Err(file.error_at(path, format!("{other} is not allowed; expected a number")))
        }
    }
}
