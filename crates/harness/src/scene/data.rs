//! What the scene section measured: the report's types, plain data,
//! serializable, read by the rendering.

use crate::summary::Timing;
use serde::Serialize;

/// A bounding level, cheapest test first.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Level {
    /// No cheap test: every query tests every element.
    None,
    /// The lecture's bounding sphere: centroid, largest distance.
    SphereCentroid,
    /// Ritter's bounding sphere.
    SphereRitter,
    /// The minimal bounding sphere (Welzl).
    SphereMinimal,
    /// The scene's AABB.
    Aabb,
    /// The scene's oriented box, along the principal axes of its points.
    Obb,
    /// A bounding volume hierarchy (AABB tree).
    Bvh,
}

impl Level {
    /// Every level, in the order the tables show them (and ties are broken).
    pub const ALL: [Level; 7] = [
        Level::None,
        Level::SphereCentroid,
        Level::SphereRitter,
        Level::SphereMinimal,
        Level::Aabb,
        Level::Obb,
        Level::Bvh,
    ];

    /// For a bounding-sphere level, its method's index in the scenes' sphere
    /// triples (centroid 0, Ritter 1, minimal 2); 0 for the other levels.
    pub(super) fn sphere_method(self) -> usize {
        match self {
            Level::SphereRitter => 1,
            Level::SphereMinimal => 2,
            _ => 0,
        }
    }

    /// Its name in the tables.
    pub fn label(self) -> &'static str {
        match self {
            Level::None => "none (every element)",
            Level::SphereCentroid => "bounding sphere: centroid (lecture)",
            Level::SphereRitter => "bounding sphere: Ritter",
            Level::SphereMinimal => "bounding sphere: minimal (Welzl)",
            Level::Aabb => "AABB",
            Level::Obb => "oriented box (principal axes)",
            Level::Bvh => "BVH",
        }
    }
}

/// One level on one scene.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LevelStats {
    /// The level.
    pub level: Level,
    /// Queries its cheap test let through.
    pub passed: usize,
    /// Queries without contact it let through.
    pub false_positives: usize,
    /// `false_positives` over the queries without contact; `None` when every
    /// query is in contact.
    pub false_positive_rate: Option<f64>,
    /// Queries in contact whose answer at this level has none.
    pub lost: usize,
    /// Mean elements tested exactly per query.
    pub exact_tests_per_query: f64,
    /// Time per query (cheap test and exact tests), when timed.
    pub timing: Option<Timing>,
}

/// One scene's measurements.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SceneNeeds {
    /// The scene, for the reader.
    pub name: String,
    /// Its elements and queries, for the reader.
    pub description: String,
    /// Elements (faces or spheres).
    pub elements: usize,
    /// Queries.
    pub queries: usize,
    /// Queries in contact (every element tested exactly).
    pub contacts: usize,
    /// Queries timed per repetition (0: not timed).
    pub timed_queries: usize,
    /// Per level, in [`Level::ALL`] order.
    pub levels: Vec<LevelStats>,
    /// Index in `levels` of the cheapest level that loses no contact.
    pub cheapest_lossless: Option<usize>,
    /// What "cheapest" was judged by: `"time"` or `"exact tests"`.
    pub cheapest_by: String,
}

/// Tightness of one method over a set of clouds: radius over the minimal
/// radius.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TightnessStats {
    /// The method.
    pub method: String,
    /// Mean over the clouds.
    pub mean: f64,
    /// Smallest.
    pub min: f64,
    /// Largest.
    pub max: f64,
    /// Every value, in cloud order.
    pub values: Vec<f64>,
}

/// Tightness on one family of clouds at one size.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CloudTightness {
    /// The family.
    pub family: String,
    /// Points per cloud.
    pub points: usize,
    /// Per method.
    pub methods: Vec<TightnessStats>,
}

/// Everything the section measured.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SceneReport {
    /// The seed of every draw.
    pub seed: u64,
    /// The scenes (the bunny when its file loads, then the scattered spheres).
    pub scenes: Vec<SceneNeeds>,
    /// Why a scene is missing, if one is.
    pub problems: Vec<String>,
    /// Tightness on the bunny under random rotations, per method.
    pub bunny_tightness: Vec<TightnessStats>,
    /// Tightness on random clouds.
    pub cloud_tightness: Vec<CloudTightness>,
}

/// The tightness methods, in table order.
pub const METHODS: [&str; 4] = ["centroid (lecture)", "Ritter", "parry", "minimal (Welzl)"];

/// Cloud sizes of the tightness measure.
pub const CLOUD_SIZES: [usize; 5] = [4, 16, 64, 256, 1024];

/// Cloud families of the tightness measure.
pub const CLOUD_FAMILIES: [&str; 2] = ["uniform in a cube", "Gaussian"];
