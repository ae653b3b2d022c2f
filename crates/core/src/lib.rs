//! # crashtest-core — what an engine needs to be judged by crashtest
//!
//! The vocabulary every part of crashtest speaks, and nothing heavy: plain `f64`
//! geometry values ([`geom`]) with their vector operations ([`vec3`]), meshes
//! ([`mesh`]), the answers and the engine trait ([`engine::Queries`]), and the
//! table of query pairs ([`pair`]). It has no dependencies by default; the
//! `serde` feature adds the derives the fixture format is read and written with.
//!
//! An engine is written against this crate alone:
//!
//! ```
//! use crashtest_core::engine::{Queries, Reply};
//! use crashtest_core::geom::{Aabb, Contact, ContactAnswer, Sphere};
//! use crashtest_core::vec3::{dist, scale, sub, add};
//!
//! struct Naive;
//! impl Queries for Naive {
//!     fn contact_sphere_sphere(&self, a: &Sphere, b: &Sphere) -> Reply<ContactAnswer> {
//!         let d = dist(a.center, b.center);
//!         let depth = a.radius + b.radius - d;
//!         if depth < 0.0 || d == 0.0 {
//!             return Ok(ContactAnswer { contact: None, degenerate: d == 0.0 });
//!         }
//!         let normal = scale(sub(a.center, b.center), 1.0 / d);
//!         let point = add(b.center, scale(normal, b.radius));
//!         Ok(ContactAnswer { contact: Some(Contact { point, normal, depth }), degenerate: false })
//!     }
//! }
//!
//! let a = Sphere { center: [0.0, 0.0, 1.5], radius: 1.0 };
//! let b = Sphere { center: [0.0, 0.0, 0.0], radius: 1.0 };
//! let c = Naive.contact_sphere_sphere(&a, &b).unwrap().contact.unwrap();
//! // From b toward a, unit, to a few rounding errors.
//! assert!(dist(c.normal, [0.0, 0.0, 1.0]) <= 4.0 * f64::EPSILON);
//! assert!((c.depth - 0.5).abs() <= 4.0 * f64::EPSILON);
//! // Everything it does not implement says so.
//! let unit = Aabb { min: [0.0; 3], max: [1.0; 3] };
//! assert!(Naive.overlap(&unit, &unit).is_err());
//! ```
#![deny(missing_docs)]

pub mod engine;
pub mod geom;
pub mod mesh;
pub mod pair;
pub mod vec3;
