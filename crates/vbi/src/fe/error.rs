//! The errors of the FE stage.

use super::Direction;
use crate::model::ModelError;

/// Errors of the FE stage.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FeError {
    /// The bridge model is invalid.
    #[error("invalid bridge model: {0}")]
    Model(#[from] ModelError),
    /// The supports leave a rigid-body motion free.
    #[error("the model is a mechanism: {direction:?} is unrestrained ({explanation})")]
    Mechanism {
        /// The free direction.
        direction: Direction,
        /// Why, and how to fix it.
        explanation: String,
    },
    /// A non-positive target element length.
    #[error("element length must be a positive finite number of metres, got {element_length}")]
    ElementLength {
        /// The value given [m].
        element_length: f64,
    },
    /// Zero elements per span.
    #[error("elements per span must be at least 1, got {elements_per_span}")]
    ElementsPerSpan {
        /// The value given.
        elements_per_span: usize,
    },
    /// The mesh would be too large.
    #[error("the mesh would have about {node_count} nodes, more than the {limit} allowed")]
    TooManyNodes {
        /// Estimated node count.
        node_count: usize,
        /// [`MAX_NODE_COUNT`](super::MAX_NODE_COUNT).
        limit: usize,
    },
    /// More elements in a span than double precision resolves.
    #[error(
        "the mesh would have {elements} elements in a {span_length} m span, more than the \
         {limit} allowed: the stiffness's condition number grows as (span / element length)⁴, \
         and a finer mesh loses more to round-off than it gains (a first mode indistinguishable \
         from a rigid-body motion); use longer elements"
    )]
    TooFine {
        /// Elements the longest span would have.
        elements: usize,
        /// That span's length [m].
        span_length: f64,
        /// [`MAX_ELEMENTS_PER_SPAN`](super::MAX_ELEMENTS_PER_SPAN).
        limit: usize,
    },
    /// A station off the deck.
    #[error("station `{name}` at x = {position} m is off the deck (0 to {length} m)")]
    StationOffDeck {
        /// The station's name.
        name: String,
        /// Its position [m].
        position: f64,
        /// The deck length [m].
        length: f64,
    },
    /// A station reading the whole section of a skewed grillage.
    #[error(
        "station `{name}` reads the whole section, which a skewed grillage does not have at one \
         place (its girders' supports are offset); give it a girder"
    )]
    SkewedSection {
        /// The station's name.
        name: String,
    },
    /// A station on a girder that does not exist.
    #[error("station `{name}` reads girder {girder}, but the model has {girder_count} (0-based)")]
    NoSuchGirder {
        /// The station's name.
        name: String,
        /// The girder index given.
        girder: usize,
        /// Number of girders.
        girder_count: usize,
    },
    /// A damage region too short to hold a mesh element.
    #[error(
        "damage region {index} from x = {start} m to {end} m is too short to hold a mesh element"
    )]
    DamageRegionTooShort {
        /// Index of the stiffness loss (0-based).
        index: usize,
        /// Its start [m].
        start: f64,
        /// Its end [m].
        end: f64,
    },
    /// A displacement vector of the wrong length.
    #[error("expected {expected} displacements (one per free DOF), got {got}")]
    DisplacementCount {
        /// Free DOF count.
        expected: usize,
        /// Length given.
        got: usize,
    },
}
