//! The `[bridge]` keys that a beam and a grillage share (spans, supports count, damping,
//! damage, material), checked alike for both.

use vbi::model::{Damage, Material};
use vbi::units::GPA;

use crate::bridge::raw::{RawBridge, RawMaterial};
use crate::bridge_damage::{damage, ratio_in_range, BridgeExtent, RawDampingKeys};
use crate::source::{require_in_range, InputError, SourceFile};

/// Refuses a key of another bridge type.
pub(crate) fn forbid(
    file: &SourceFile,
    present: bool,
    key: &str,
    bridge_type: &str,
) -> Result<(), InputError> {
    if present {
        Err(file.error_at(
            &format!("bridge.{key}"),
            format!("`{key}` is not a key of a `{bridge_type}` bridge"),
        ))
    } else {
        Ok(())
    }
}

/// `span_lengths_m`: at least one, each 0.5 to 1000 m.
pub(crate) fn spans(file: &SourceFile, bridge: &RawBridge) -> Result<Vec<f64>, InputError> {
    if bridge.span_lengths_m.is_empty() {
        return Err(file.error_at(
            "bridge.span_lengths_m",
            "at least one span length is required",
        ));
    }
    bridge
        .span_lengths_m
        .iter()
        .enumerate()
        .map(|(i, &l)| {
            require_in_range(
                file,
                &format!("bridge.span_lengths_m[{i}]"),
                l,
                0.5,
                1000.0,
                "m",
            )
        })
        .collect()
}

/// `damping_ratio` (the key table's range), or `default`.
pub(crate) fn damping(
    file: &SourceFile,
    bridge: &RawBridge,
    default: f64,
) -> Result<f64, InputError> {
    match bridge.damping_ratio {
        None => Ok(default),
        Some(z) => ratio_in_range(file, "bridge.damping_ratio", z),
    }
}

/// The damage of the bridge's `[[bridge.stiffness_loss]]` and `[[bridge.support_change]]`.
pub(crate) fn bridge_damage(
    file: &SourceFile,
    bridge: &RawBridge,
    span_lengths: &[f64],
    girder_count: usize,
) -> Result<Damage, InputError> {
    let extent = BridgeExtent {
        length: span_lengths.iter().sum(),
        girder_count,
        support_count: span_lengths.len() + 1,
    };
    damage(
        file,
        &bridge.stiffness_loss,
        &bridge.support_change,
        &extent,
    )
}

/// The damping keys as given, for [`mode_damping`](crate::bridge_damage::mode_damping).
pub(crate) fn damping_keys(bridge: &RawBridge) -> RawDampingKeys<'_> {
    RawDampingKeys {
        damping_ratio_given: bridge.damping_ratio.is_some(),
        damping_ratios: bridge.damping_ratios.as_deref(),
        rayleigh_damping: bridge.rayleigh_damping.as_ref(),
    }
}

/// One support more than spans.
pub(crate) fn support_count_check(
    file: &SourceFile,
    count: usize,
    span_count: usize,
) -> Result<(), InputError> {
    if count != span_count + 1 {
        return Err(file.error_at(
            "bridge.supports",
            format!(
                "{span_count} spans need {} supports, got {count}",
                span_count + 1
            ),
        ));
    }
    Ok(())
}

/// `[bridge.material]` over the default concrete: E [GPa → Pa], ρ [kg/m³], ν.
pub(crate) fn material(
    file: &SourceFile,
    raw: Option<&RawMaterial>,
) -> Result<Material, InputError> {
    let mut m = Material::default();
    if let Some(raw) = raw {
        if let Some(e) = raw.modulus_gpa {
            m.elastic_modulus =
                require_in_range(file, "bridge.material.modulus_gpa", e, 0.1, 1000.0, "GPa")? * GPA;
        }
        if let Some(rho) = raw.density_kg_per_m3 {
            m.density = require_in_range(
                file,
                "bridge.material.density_kg_per_m3",
                rho,
                100.0,
                20000.0,
                "kg/m³",
            )?;
        }
        if let Some(nu) = raw.poisson_ratio {
            m.poisson_ratio =
                require_in_range(file, "bridge.material.poisson_ratio", nu, 0.0, 0.49, "")?;
        }
    }
    Ok(m)
}

/// A section or deck length: 1 mm to 100 m.
pub(crate) fn length(file: &SourceFile, path: &str, value: f64) -> Result<f64, InputError> {
    require_in_range(file, path, value, 1e-3, 100.0, "m")
}
