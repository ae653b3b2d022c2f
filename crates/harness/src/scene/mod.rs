//! What a scene needs: for mesh scenes, which bounding level — none, one
//! bounding sphere (the lecture's centroid method, Ritter's, the minimal one),
//! one AABB, one oriented box, or a BVH — is the cheapest that loses no
//! contact, measured; and how tight each bounding-sphere method is.
//!
//! Scenes at opposite ends:
//!
//! - **the bunny** (`fixtures/meshes/bunny.obj`, 3,674 faces), queried by
//!   segments whose endpoints are uniform in its box grown by its largest size
//!   on each side (so many pass beside it): the exact test is collide's robust
//!   segment–mesh first hit over every face
//!   ([`intersect_segment_mesh_brute`](collide::mesh::intersect_segment_mesh_brute)), a few hundred microseconds;
//!   and **the bunny turned** by [`BUNNY_TURN`], the same queries drawn in its
//!   new box: its AABB is looser, its oriented box (principal axes of the
//!   vertices, [`obb_of_points`]) is the same box turned;
//! - **scattered spheres** (analytic, radius [`SCATTER_RADIUS`], centres
//!   uniform in a cube of side `2·`[`SCATTER_HALF_SIDE`]), queried by spheres:
//!   the exact test is collide's sphere–sphere contact against every sphere
//!   (all contacts are wanted), a few nanoseconds each.
//!
//! For each level, each query first meets the level's **cheap test** (none;
//! the query against the one bounding sphere or box of the whole scene; the
//! tree's boxes), and only if it passes goes on to the exact test (every
//! element; the tree: the elements of the leaves it reached). Measured per
//! level, over the same seeded queries: how many pass, the **false-positive
//! rate** (of the queries without contact, the fraction the cheap test still
//! lets through), the contacts the level **loses** (queries in contact whose
//! answer at this level says none, against every element tested exactly), the
//! exact element tests per query, and the time per query (like the
//! campaign's timing loops: repetitions of a loop over the queries, the
//! median reported). The **cheapest lossless level** is the fastest one that
//! loses no contact (by exact tests per query when the run is not timed).
//!
//! Bounding-sphere **tightness** (radius over the minimal radius, the
//! referee's exact one) for the lecture's centroid method, Ritter's, parry's
//! `point_cloud_bounding_sphere` and collide's minimal sphere, on the bunny
//! under random rotations and on random clouds of several sizes.
//!
//! Decisions: the cheap tests are the ones a reader would write — segment
//! against sphere by the closest point of the segment, query box against
//! scene box — evaluated in `f64`, so a lost contact would show a cheap test
//! that is not conservative; the scattered spheres get a tree of their own
//! here ([`SphereTree`], median split on boxes), collide's trees being over
//! triangles; a sphere stays a sphere (DESIGN: model no more than a scene
//! needs).
//!
//! Split as the experiments are: `data` (the report's types), `run` (the
//! scenes built and measured) and `render` (Markdown, HTML and charts, from the
//! data alone).

mod data;
mod render;
mod run;

pub use data::{
    CLOUD_FAMILIES, CLOUD_SIZES, CloudTightness, Level, LevelStats, METHODS, SceneNeeds, SceneReport, TightnessStats,
};
pub use render::{
    SAME_RADIUS_REL, charts, markdown, scene_table, section_of, strip_chart, tightness_notes, tightness_table,
};
pub use run::{
    BUNNY_TURN, MINIMAL_TIGHTNESS_TOL, OBB_PAD_REL, Obb, Outcome, QUERY_RADIUS_MAX, SCATTER_HALF_SIDE, SCATTER_RADIUS,
    SPHERE_LEAF, SceneSettings, SphereTree, TIGHTNESS_ROUNDING, cheapest_lossless, level_stats, mesh_levels,
    obb_of_points, run, segment_meets_ball, segment_meets_obb, sphere_levels, tightness,
};

use crate::render::section::Section;

/// The section "What the scene needs" (id `scene`), measured now: [`run`],
/// then [`section_of`].
pub fn section(settings: &SceneSettings) -> Section {
    section_of(&run(settings))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scene_section_has_its_parts_without_timing() {
        let settings = SceneSettings {
            timing: false,
            bunny_queries: 24,
            bunny_timed: 0,
            spheres: 40,
            sphere_queries: 60,
            rotations: 2,
            clouds_per_size: 1,
            ..SceneSettings::default()
        };
        let s = section(&settings);
        assert_eq!(s.id, "scene");
        assert!(s.markdown.starts_with("## What the scene needs\n"), "{}", s.markdown);
        assert!(s.markdown.contains("The bunny") && s.markdown.contains("Scattered spheres"), "both scenes");
        assert!(s.markdown.contains("cheapest lossless"), "the cheapest level is marked");
        assert_eq!(s.charts.len(), 3);
        assert!(s.charts.iter().all(|c| c.svg.starts_with("<svg") && !c.svg.contains(" id=")), "inline SVG, no ids");
        assert!(!s.html.contains("<h2"), "the heading is the report's");
        // Pure apart from timings: the same settings give the same section.
        assert_eq!(section(&settings), s);
    }
}
