//! The generators' families: a named strategy of scenes, uniform or biased,
//! with the parameters a case carries beside its shapes.

use super::build::Scene;
use proptest::strategy::{SBoxedStrategy, Strategy};

/// What a generated case carries beside its shapes: `t_max` for `toi` (`None`:
/// the format's default, 1) and `restitution` for `response`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Params {
    /// End of the time interval of a `toi` case.
    pub(crate) t_max: Option<f64>,
    /// Coefficient of restitution of a `response` case.
    pub(crate) restitution: Option<f64>,
}

/// A generated scene with its case parameters.
pub(crate) type Posed = (Scene, Params);

/// How a family builds its strategy: shapes alone, or shapes with parameters.
#[derive(Clone, Copy)]
enum Build {
    Scene(fn() -> SBoxedStrategy<Scene>),
    Posed(fn() -> SBoxedStrategy<Posed>),
}

/// One named family of scenes.
pub(crate) struct Family {
    pub(super) name: &'static str,
    pub(super) biased: bool,
    build: Build,
}

impl Family {
    /// A uniform family.
    pub(crate) fn uniform(name: &'static str, build: fn() -> SBoxedStrategy<Scene>) -> Self {
        Self { name, biased: false, build: Build::Scene(build) }
    }

    /// A family biased toward where methods fail.
    pub(crate) fn biased(name: &'static str, build: fn() -> SBoxedStrategy<Scene>) -> Self {
        Self { name, biased: true, build: Build::Scene(build) }
    }

    /// A uniform family whose cases carry parameters (`toi`, `response`).
    pub(crate) fn uniform_posed(name: &'static str, build: fn() -> SBoxedStrategy<Posed>) -> Self {
        Self { name, biased: false, build: Build::Posed(build) }
    }

    /// A biased family whose cases carry parameters (`toi`, `response`).
    pub(crate) fn biased_posed(name: &'static str, build: fn() -> SBoxedStrategy<Posed>) -> Self {
        Self { name, biased: true, build: Build::Posed(build) }
    }

    /// Its strategy: scenes with their parameters.
    pub(super) fn strategy(&self) -> SBoxedStrategy<Posed> {
        match self.build {
            Build::Scene(f) => f().prop_map(|s| (s, Params::default())).sboxed(),
            Build::Posed(f) => f(),
        }
    }
}
