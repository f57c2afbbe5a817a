//! The output mesh of the 2D mesher.

use super::NONE;

/// A triangle mesh produced by [`crate::triangulate`].
///
/// Vertex `i < num_input_vertices` is input point `i` (same coordinates, same index), even when
/// it lies outside the meshed domain (then no triangle uses it). Steiner vertices follow.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TriMesh {
    /// Vertex coordinates.
    pub vertices: Vec<[f64; 2]>,
    /// One marker per vertex: the input marker for input vertices (0 when none was given), the
    /// segment's marker for Steiner vertices on a segment, 0 for interior Steiner vertices; as in
    /// Triangle, a vertex whose marker would be 0 but which lies on a subsegment takes the
    /// subsegment's marker.
    pub vertex_markers: Vec<i32>,
    /// How many leading vertices are input points.
    pub num_input_vertices: usize,
    /// Triangles as vertex indices in counter-clockwise order.
    pub triangles: Vec<[u32; 3]>,
    /// `neighbors[t][i]` is the triangle across the edge opposite `triangles[t][i]`, or [`NONE`]
    /// on the domain boundary.
    pub neighbors: Vec<[u32; 3]>,
    /// The regional attribute of each triangle when `Options::region_attributes` is set
    /// (0.0 for triangles in no region); empty otherwise.
    pub triangle_attributes: Vec<f64>,
    /// The subsegments: every input segment is the union of the subsegments with its marker.
    pub segments: Vec<[u32; 2]>,
    /// One marker per subsegment (inherited from its input segment).
    pub segment_markers: Vec<i32>,
    /// `false` when refinement stopped at the Steiner-point cap (or a work budget) before
    /// meeting every bound; the mesh is then constrained Delaunay, not necessarily
    /// conforming (see [`TriMesh::validate`]).
    pub complete: bool,
    /// Number of Steiner points added (vertices beyond the input points that are in the mesh).
    pub steiner_points: usize,
}

impl TriMesh {
    /// All edges of the mesh, each once, with a boundary marker: the segment marker for edges
    /// on a segment, otherwise 0. Order: by first triangle, then by edge index.
    pub fn edges(&self) -> Vec<([u32; 2], i32)> {
        let mut seg_marker = std::collections::HashMap::with_capacity(self.segments.len());
        for (s, m) in self.segments.iter().zip(&self.segment_markers) {
            seg_marker.insert(edge_key(s[0], s[1]), *m);
        }
        let mut out = Vec::with_capacity(self.triangles.len() * 3 / 2 + 16);
        for (t, tri) in self.triangles.iter().enumerate() {
            for i in 0..3 {
                let n = self.neighbors[t][i];
                if n == NONE || (n as usize) > t {
                    let a = tri[(i + 1) % 3];
                    let b = tri[(i + 2) % 3];
                    let m = seg_marker.get(&edge_key(a, b)).copied().unwrap_or(0);
                    out.push(([a, b], m));
                }
            }
        }
        out
    }

    /// Total area of the triangles.
    pub fn area(&self) -> f64 {
        let mut sum = 0.0;
        for t in &self.triangles {
            let [a, b, c] = t.map(|i| self.vertices[i as usize]);
            sum += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
        }
        sum
    }

    /// The smallest and largest triangle angles, in degrees (`(180, 0)` for an empty mesh).
    pub fn angle_range(&self) -> (f64, f64) {
        let mut lo: f64 = 180.0;
        let mut hi: f64 = 0.0;
        for t in &self.triangles {
            let p = t.map(|i| self.vertices[i as usize]);
            for ang in crate::geometry::triangle_angles_deg(p[0], p[1], p[2]) {
                lo = lo.min(ang);
                hi = hi.max(ang);
            }
        }
        (lo, hi)
    }

    /// Checks the mesh invariants exactly: index ranges, counter-clockwise orientation,
    /// neighbour symmetry, empty circumcircles (against every vertex), and that every
    /// subsegment is a mesh edge. Returns a message naming the first violation.
    ///
    /// This is the conforming Delaunay rule of the default options. An incomplete mesh
    /// (`complete == false`: the Steiner budget stopped refinement, possibly before every
    /// encroached segment was split) is checked with the constrained rule of
    /// [`TriMesh::validate_constrained`], its guarantee. A mesh made with
    /// `Options::no_boundary_steiner` is only constrained Delaunay: check it with
    /// [`TriMesh::validate_constrained`].
    pub fn validate(&self) -> Result<(), String> {
        super::validate::validate(self)
    }

    /// As [`TriMesh::validate`], but with the constrained empty-circle rule (the guarantee of
    /// meshes made with `Options::no_boundary_steiner`): a vertex inside a triangle's
    /// circumcircle is a violation only when it is visible from the triangle's interior, not
    /// hidden behind a subsegment. Checked exactly in its equivalent local form: every edge
    /// that is not a subsegment is locally Delaunay.
    pub fn validate_constrained(&self) -> Result<(), String> {
        super::validate::validate_constrained(self, crate::threads::count().unwrap_or(1))
    }
}

fn edge_key(a: u32, b: u32) -> u64 {
    let (lo, hi) = if a < b { (a, b) } else { (b, a) };
    ((lo as u64) << 32) | hi as u64
}
