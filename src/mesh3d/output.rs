//! The output mesh of the 3D mesher.

use crate::error::Error;

/// A tetrahedral mesh produced by [`crate::mesh3d::tetrahedralize`] or
/// [`crate::mesh3d::delaunay3d`].
///
/// Vertex `i < num_input_vertices` is input point `i` (same coordinates, same index), even when
/// it lies outside the meshed volume (then no tetrahedron uses it). Steiner vertices follow.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TetMesh {
    /// Vertex coordinates.
    pub vertices: Vec<[f64; 3]>,
    /// One marker per vertex: the input marker for input vertices (0 when none was given), the
    /// facet's or segment's marker for Steiner vertices on one, 0 for interior Steiner vertices.
    pub vertex_markers: Vec<i32>,
    /// How many leading vertices are input points.
    pub num_input_vertices: usize,
    /// Tetrahedra as vertex indices, positively oriented as in TetGen:
    /// `det[b − a, c − a, d − a] > 0` for `[a, b, c, d]`.
    pub tets: Vec<[u32; 4]>,
    /// `neighbors[t][i]` is the tetrahedron across the face opposite `tets[t][i]`, or
    /// [`super::NONE`] on the boundary of the meshed volume.
    pub neighbors: Vec<[u32; 4]>,
    /// The regional attribute of each tetrahedron when `Options3::region_attributes` is set
    /// (0.0 for tetrahedra in no region); empty otherwise.
    pub tet_attributes: Vec<f64>,
    /// The subfaces: boundary faces and faces lying in input facets; every input facet is the
    /// union of the subfaces with its marker.
    pub faces: Vec<[u32; 3]>,
    /// One marker per subface (inherited from its facet; 0 for hull faces of a point set).
    pub face_markers: Vec<i32>,
    /// The subsegments: every input edge (segment or facet loop edge) is the union of the
    /// subsegments on it.
    pub edges: Vec<[u32; 2]>,
    /// One marker per subsegment.
    pub edge_markers: Vec<i32>,
    /// `false` when refinement stopped at the Steiner-point cap before meeting every bound.
    pub complete: bool,
    /// Number of Steiner points added (vertices beyond the input points that are in the mesh).
    pub steiner_points: usize,
    /// The mesh keeps the input surface (`Options3::keep_surface`, TetGen's `-Y`): every
    /// subface has input vertices only, and the tetrahedra next to the surface need not be
    /// Delaunay. [`TetMesh::validate`] then checks that instead of empty circumspheres.
    pub surface_kept: bool,
    /// The mesh was optimised by flips and vertex smoothing (`Options3::optimize_level`,
    /// TetGen's `-O`) and is in general no longer Delaunay. [`TetMesh::validate`] then checks
    /// structure, orientation and conformity (every subface a face and every subsegment an
    /// edge of a tetrahedron) but not empty circumspheres.
    pub optimized: bool,
}

/// Quality figures of a tetrahedral mesh, as printed by `idmesh tetgen -V`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TetStats {
    /// Total volume.
    pub volume: f64,
    /// Largest circumradius-to-shortest-edge ratio.
    pub max_radius_edge: f64,
    /// Smallest dihedral angle, degrees.
    pub min_dihedral: f64,
    /// Largest dihedral angle, degrees.
    pub max_dihedral: f64,
    /// How many tetrahedra have a dihedral angle below 5, 10 and 15 degrees.
    pub tets_below: [usize; 3],
}

/// The bins of TetGen's `-V` dihedral-angle histogram, degrees: `[0, 5)`, `[5, 10)`, ...,
/// `[175, 180]`.
pub const DIHEDRAL_BINS: [f64; 18] = [
    0.0, 5.0, 10.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0, 110.0, 120.0, 130.0, 140.0, 150.0, 160.0,
    170.0, 175.0, 180.0,
];

impl TetMesh {
    /// The corners of tetrahedron `t`.
    pub fn corners(&self, t: usize) -> [[f64; 3]; 4] {
        self.tets[t].map(|v| self.vertices[v as usize])
    }

    /// Total volume of the tetrahedra (floating point, summed per tetrahedron).
    pub fn volume(&self) -> f64 {
        (0..self.tets.len())
            .map(|t| crate::geometry::tet_volume(self.corners(t)))
            .sum()
    }

    /// Volume, radius-edge and dihedral-angle figures (zeros for an empty mesh).
    pub fn stats(&self) -> TetStats {
        let mut s = TetStats {
            volume: 0.0,
            max_radius_edge: 0.0,
            min_dihedral: if self.tets.is_empty() { 0.0 } else { 180.0 },
            max_dihedral: 0.0,
            tets_below: [0; 3],
        };
        for t in 0..self.tets.len() {
            let c = self.corners(t);
            s.volume += crate::geometry::tet_volume(c);
            s.max_radius_edge = s.max_radius_edge.max(crate::geometry::tet_radius_edge(c));
            let (lo, hi) = crate::geometry::tet_dihedral_range(c);
            s.min_dihedral = s.min_dihedral.min(lo);
            s.max_dihedral = s.max_dihedral.max(hi);
            for (k, bound) in [5.0, 10.0, 15.0].into_iter().enumerate() {
                s.tets_below[k] += usize::from(lo < bound);
            }
        }
        s
    }

    /// How many dihedral angles (six per tetrahedron) fall in each bin of [`DIHEDRAL_BINS`]
    /// (17 counts; 180 degrees counts in the last bin).
    pub fn dihedral_histogram(&self) -> [usize; 17] {
        let mut h = [0usize; 17];
        for t in 0..self.tets.len() {
            for a in crate::geometry::tet_dihedrals(self.corners(t)) {
                let bin = DIHEDRAL_BINS[1..].iter().position(|&b| a < b).unwrap_or(16);
                h[bin] += 1;
            }
        }
        h
    }

    /// Checks the mesh invariants exactly: positive orientation, neighbour symmetry, every
    /// subface a face of the mesh, and every circumsphere empty of all mesh vertices, or, for
    /// a mesh that keeps the input surface ([`TetMesh::surface_kept`]), no Steiner vertex on a
    /// subface; for an optimised mesh ([`TetMesh::optimized`]), every subsegment an edge of the
    /// mesh instead of the empty circumspheres.
    pub fn validate(&self) -> Result<(), Error> {
        // Coordinates below 2^-64 are checked scaled up by a power of two (exact), as they
        // are meshed: the exact insphere test underflows on them.
        if let Some(s) = crate::geometry::tiny_scale(self.vertices.iter()) {
            let mut m = self.clone();
            m.vertices.iter_mut().for_each(|p| *p = p.map(|x| x * s));
            return super::validate::validate_mesh(&m);
        }
        super::validate::validate_mesh(self)
    }
}
