//! The engines crashtest runs, each behind [`crate::engine::Queries`].

pub mod collide;
pub mod parry;
pub mod referee;

use crate::engine::Engine;
use collide::{CollideQueries, Method};
use oracle::parry::{Parry32, Parry64};

/// The engine whose answers decide `crashtest check`'s exit code.
pub const DEFAULT_ENGINE: &str = "collide/robust";

/// The referee's name in reports.
pub const REFEREE: &str = "referee";

/// Every engine judged, in report order: collide's methods and precisions, then
/// parry in both precisions.
pub fn judged() -> Vec<Engine> {
    vec![
        Engine::new("collide/robust", Some(53), CollideQueries::<f64>::new(Method::Robust)),
        Engine::new("collide/lecture", Some(53), CollideQueries::<f64>::new(Method::Lecture)),
        Engine::new("collide-f32/robust", Some(24), CollideQueries::<f32>::new(Method::Robust)),
        Engine::new("collide-f32/lecture", Some(24), CollideQueries::<f32>::new(Method::Lecture)),
        Engine::new(Parry64::NAME, Some(53), parry::ParryQueries(Parry64)),
        Engine::new(Parry32::NAME, Some(24), parry::ParryQueries(Parry32)),
    ]
}

/// The referee as an engine.
pub fn referee() -> Engine {
    Engine::new(REFEREE, None, referee::RefereeQueries)
}
