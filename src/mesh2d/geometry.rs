//! The geometry the 2D kernel ([`super::store::Cdt`]) is generic over: the exact predicates
//! every decision of the incremental Bowyer–Watson kernel is made with (paper §2: orientation
//! and in-circle; §3: the diametral circle of a segment).
//!
//! The kernel is monomorphised over a [`Geometry`]: the predicates are static calls in its hot
//! loops (point location, the cavity search, segment recovery, flips), never virtual ones.
//! [`Plane`] is the plane of the 2D mesher and of the 3D input checks (a facet's vertices
//! projected along its dominant normal axis, an exact, sign-preserving map). A facet mesh of
//! the 3D mesher is the same kind of mesh in the facet's plane (paper §4.2, §6): [`InPlane`]
//! answers the same questions exactly on the 3D coordinates (orientation of the projection,
//! the 3D in-circle test), so the trait takes points of any representation.
//!
//! Infinity is handled once, by the kernel: one ghost vertex closes the convex hull, and a
//! ghost triangle's circle is the open half-plane beyond its hull edge plus the open edge
//! itself (`orient > 0`, or `orient == 0` and [`Geometry::strictly_between`]), the limit of
//! the circles through the hull edge and a point running off to infinity on the far side. A
//! geometry therefore only ever sees finite points, and its predicates stay exact without any
//! symbolic coordinate; [`Geometry::infinite`] only fills the ghost's coordinate slot and is
//! never handed to a predicate.

use crate::predicates::{
    encroaches, in_diametral_ball_seg3, incircle, incircle3d, incircle_fast, orient2d,
    orient2d_proj, proj, strictly_between,
};

/// Exact predicates on the points of one plane. Signs follow Shewchuk's conventions; every
/// answer is exact (no epsilon), so the kernel's decisions are consistent.
pub trait Geometry {
    /// A point of the plane (possibly stored in higher-dimensional coordinates).
    type Point: Copy + PartialEq;

    /// The coordinates stored for the ghost vertex (never passed to a predicate).
    fn infinite(&self) -> Self::Point;

    /// Positive when `a, b, c` turn counter-clockwise, negative clockwise, zero when collinear.
    fn orient(&self, a: Self::Point, b: Self::Point, c: Self::Point) -> f64;

    /// Positive when `d` lies strictly inside the circle through `a, b, c` (counter-clockwise),
    /// negative outside, zero on it.
    fn incircle(&self, a: Self::Point, b: Self::Point, c: Self::Point, d: Self::Point) -> f64;

    /// [`Geometry::incircle`] with the same sign, for the bulk insertion (a geometry may use a
    /// cheaper filter first).
    #[inline(always)]
    fn incircle_bulk(&self, a: Self::Point, b: Self::Point, c: Self::Point, d: Self::Point) -> f64 {
        self.incircle(a, b, c, d)
    }

    /// Whether `p`, collinear with `a` and `b`, lies strictly between them.
    fn strictly_between(&self, a: Self::Point, b: Self::Point, p: Self::Point) -> bool;

    /// Whether `p` lies strictly inside the diametral circle of segment `a b`.
    fn encroaches(&self, a: Self::Point, b: Self::Point, p: Self::Point) -> bool;
}

/// The Euclidean plane with `f64` coordinates: the 2D mesher's geometry.
#[derive(Clone, Copy, Debug, Default)]
pub struct Plane;

impl Geometry for Plane {
    type Point = [f64; 2];

    #[inline(always)]
    fn infinite(&self) -> [f64; 2] {
        [f64::INFINITY, f64::INFINITY]
    }

    #[inline(always)]
    fn orient(&self, a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
        orient2d(a, b, c)
    }

    #[inline(always)]
    fn incircle(&self, a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> f64 {
        incircle(a, b, c, d)
    }

    #[inline(always)]
    fn incircle_bulk(&self, a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> f64 {
        incircle_fast(a, b, c, d)
    }

    #[inline(always)]
    fn strictly_between(&self, a: [f64; 2], b: [f64; 2], p: [f64; 2]) -> bool {
        strictly_between(a, b, p)
    }

    #[inline(always)]
    fn encroaches(&self, a: [f64; 2], b: [f64; 2], p: [f64; 2]) -> bool {
        encroaches(a, b, p)
    }
}

/// The plane of a facet of a 3D input, seen along `axis`, its dominant normal axis (paper
/// §4.2, §6). Points keep their 3D coordinates: orientation is `orient2d` of the projection
/// that drops `axis` (an affine map: exact and sign-preserving for points of the plane), and
/// the in-circle test is the 3D one ([`incircle3d`]), so a facet mesh and the 3D mesh see the
/// same circles; no point is ever rounded into the plane.
#[derive(Clone, Copy, Debug)]
pub struct InPlane {
    /// The coordinate the projection drops.
    pub axis: usize,
}

impl InPlane {
    /// The projection of `p` (see [`proj`]).
    #[inline(always)]
    pub fn proj(&self, p: [f64; 3]) -> [f64; 2] {
        proj(p, self.axis)
    }
}

impl Geometry for InPlane {
    type Point = [f64; 3];

    #[inline(always)]
    fn infinite(&self) -> [f64; 3] {
        [f64::INFINITY; 3]
    }

    #[inline(always)]
    fn orient(&self, a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
        orient2d_proj(a, b, c, self.axis)
    }

    #[inline(always)]
    fn incircle(&self, a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> f64 {
        incircle3d(a, b, c, d)
    }

    #[inline(always)]
    fn strictly_between(&self, a: [f64; 3], b: [f64; 3], p: [f64; 3]) -> bool {
        strictly_between(self.proj(a), self.proj(b), self.proj(p))
    }

    #[inline(always)]
    fn encroaches(&self, a: [f64; 3], b: [f64; 3], p: [f64; 3]) -> bool {
        in_diametral_ball_seg3(a, b, p)
    }
}
