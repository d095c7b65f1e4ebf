//! Stations: the cross-sections of the bridge where responses are recorded, and the quantities
//! read there. The FE model defines them (with the functionals that read them,
//! [`StationFunctional`](crate::fe::StationFunctional)); an imported modal basis lists its own;
//! the modal basis and the influence lines carry copies.

use serde::{Deserialize, Serialize};

/// Which part of the cross-section a station reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "kind", content = "index")]
pub enum StationTarget {
    /// One girder (deck line index, 0 = rightmost).
    Girder(usize),
    /// The whole section: mean deflection of the girders, sum of their moments.
    Section,
}

/// A cross-section of interest where responses are recorded.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Station {
    /// Name, for example `span1_mid_g2` or `support2_section`.
    pub name: String,
    /// Longitudinal position x [m] from the first support.
    pub position: f64,
    /// Girder or whole section.
    pub target: StationTarget,
    /// True over an interior support, where the moment of interest is hogging.
    pub over_support: bool,
    /// True where a support (end or interior, rigid or elastic) bears the deck at this
    /// station: the support reaction is read here, and not the shear force, which jumps there
    /// by the reaction (default false).
    #[serde(default)]
    pub support: bool,
}

impl Station {
    /// The station's distance along its girder from that girder's first support [m]: its deck
    /// position less its girder's offset `line_offsets[g]` on a skewed grillage
    /// ([`super::BridgeModel::line_offsets`]; empty or zero elsewhere).
    pub fn along_girders(&self, line_offsets: &[f64]) -> f64 {
        match self.target {
            StationTarget::Girder(g) => self.position - line_offsets.get(g).copied().unwrap_or(0.0),
            StationTarget::Section => self.position,
        }
    }

    /// Whether a load at longitudinal position `x` [m] reads this station's bending moment and
    /// shear force from the element left of the station (its `moment_left` and `shear_left`
    /// functionals and lines): a load at or right of the station, so that the element read is
    /// on the side away from the load; else the element right of it. The one rule of the FE
    /// static solve and of every reader of the two-sided influence lines.
    #[inline]
    pub fn reads_left_element(&self, x: f64) -> bool {
        x >= self.position
    }

    /// The quantities an FE model reads at this station: deflection, bending moment, and the
    /// support reaction at a support or the shear force elsewhere.
    pub fn quantities(&self) -> [Quantity; 3] {
        [
            Quantity::Deflection,
            Quantity::BendingMoment,
            self.force_quantity(),
        ]
    }

    /// The force read at this station: the support reaction at a support, the shear force
    /// elsewhere.
    pub fn force_quantity(&self) -> Quantity {
        if self.support {
            Quantity::SupportReaction
        } else {
            Quantity::ShearForce
        }
    }
}

/// Quantities recorded at stations.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    /// Vertical deflection [m], positive upwards.
    Deflection,
    /// Bending moment [N·m], positive sagging (tension at the bottom).
    BendingMoment,
    /// Vertical shear force [N], V = dM/dx: the upward force on the part of the bridge left of
    /// the section (the left support's reaction less the loads between it and the section).
    ShearForce,
    /// Vertical support reaction [N], upward positive: the force the bearings at the station
    /// (one girder's, or the whole support line's) exert on the bridge.
    SupportReaction,
}

impl Quantity {
    /// Every quantity, in the order of a station's entries.
    pub const ALL: [Quantity; 4] = [
        Quantity::Deflection,
        Quantity::BendingMoment,
        Quantity::ShearForce,
        Quantity::SupportReaction,
    ];

    /// The quantity's name in outputs (its serde name).
    pub fn name(self) -> &'static str {
        match self {
            Quantity::Deflection => "deflection",
            Quantity::BendingMoment => "bending_moment",
            Quantity::ShearForce => "shear_force",
            Quantity::SupportReaction => "support_reaction",
        }
    }

    /// Whether the paper's plain modal sum (Eqs. 15–16) of the quantity reads as a DAF: for the
    /// deflection and the bending moment it converges to the response with the modes kept; a
    /// shear force or a reaction jumps under a passing wheel, so its plain sum converges slowly,
    /// oscillating, and a reaction's overshoots even with every mode kept (1.276 against a
    /// converged 1.171 on a two-span beam; issue 46, item 5, docs/theory.md).
    pub fn plain_sum_is_a_daf(self) -> bool {
        matches!(self, Quantity::Deflection | Quantity::BendingMoment)
    }

    /// The quantity of that [`name`](Quantity::name), if any.
    pub fn from_name(name: &str) -> Option<Quantity> {
        Quantity::ALL.into_iter().find(|q| q.name() == name)
    }

    /// The SI unit of the quantity's values.
    pub fn unit(self) -> &'static str {
        match self {
            Quantity::Deflection => "m",
            Quantity::BendingMoment => "N·m",
            Quantity::ShearForce | Quantity::SupportReaction => "N",
        }
    }
}

/// Names, lookup and units of the quantities, through serde: [`Quantity::names`] reads the
/// variant names that serde's derive lists, so a variant added to [`Quantity`] is known to
/// every caller (a study's `record`, its tables) with no second list to keep up to date.
impl Quantity {
    /// Every quantity's name (its serde name, the same as [`Quantity::name`]), in declaration
    /// order.
    pub fn names() -> &'static [&'static str] {
        variant_names::<Quantity>()
    }

    /// Every quantity, in declaration order.
    pub fn all() -> Vec<Quantity> {
        Quantity::ALL.to_vec()
    }
}

/// The variant names of a serde enum, as its derived `Deserialize` lists them (the names it
/// accepts): a deserializer that only records the list that `deserialize_enum` is given.
fn variant_names<'de, T: Deserialize<'de>>() -> &'static [&'static str] {
    use serde::de::{Error, Visitor};

    struct Names<'a>(&'a mut &'static [&'static str]);

    impl<'de> serde::Deserializer<'de> for Names<'_> {
        type Error = serde::de::value::Error;

        fn deserialize_any<V: Visitor<'de>>(self, _: V) -> Result<V::Value, Self::Error> {
            Err(Self::Error::custom("only the variant names are read"))
        }

        fn deserialize_enum<V: Visitor<'de>>(
            self,
            _: &'static str,
            variants: &'static [&'static str],
            _: V,
        ) -> Result<V::Value, Self::Error> {
            *self.0 = variants;
            Err(Self::Error::custom("only the variant names are read"))
        }

        serde::forward_to_deserialize_any! {
            bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf
            option unit unit_struct newtype_struct seq tuple tuple_struct map struct identifier
            ignored_any
        }
    }

    let mut names: &'static [&'static str] = &[];
    let _ = T::deserialize(Names(&mut names));
    names
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_quantity_is_found_by_its_name_and_named_by_it() {
        let all = Quantity::all();
        assert!(all.contains(&Quantity::Deflection) && all.contains(&Quantity::BendingMoment));
        assert_eq!(all.len(), Quantity::names().len());
        for (quantity, name) in all.iter().zip(Quantity::names()) {
            assert_eq!(quantity.name(), *name);
            assert_eq!(Quantity::from_name(name), Some(*quantity));
            assert!(!quantity.unit().is_empty());
        }
        assert_eq!(Quantity::from_name("deflections"), None);
        assert_eq!(Quantity::from_name(""), None);
    }
}
