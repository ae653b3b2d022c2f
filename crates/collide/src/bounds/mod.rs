//! Bounding volumes: AABBs by expansion and their overlap test, bounding spheres.
