// TetGen's switches r, i, m, o2, X and e, and point attributes, through idmesh's TetGen
// compatibility layer, each checked for a property of the result:
//   o2  every edge node is at the midpoint of its edge (TetGen 1.5's node order) and shared
//       by every tetrahedron on that edge;
//   r   the refined mesh keeps the given points at their indices, has the given volume, and
//       every tetrahedron meets the per-tetrahedron volume bounds (tetrahedronvolumelist, a);
//   i   the addin points are vertices of the output, used by tetrahedra;
//   m   every tetrahedron's longest edge is at most the size given by pointmtrlist
//       (linear in x, so its linear interpolation is exact) at its centroid;
//   point attributes (linear in the coordinates) are reproduced at every output point;
//   e   edgelist lists every edge of the tetrahedra once;
//   X   is accepted;
//   facetconstraintlist / segmentconstraintlist: every boundary face of the bounded marker is
//       within its area bound and every piece of the bounded segment within its length bound,
//       while other faces are not forced below them; a bad bound throws 10;
//   c   an L-shaped prism is meshed to its convex hull (volume 3.5 instead of 3);
//   O, o/  optlevel is 0 unless O is given (idmesh stays Delaunay by default), O3/1o/150 is
//       parsed into optlevel, optscheme and optmaxdihedral; optlevel 3 with optmaxdihedral 140
//       set in the fields makes the cube's smallest dihedral angle larger and its largest not
//       larger, keeping the volume; a bad optscheme throws 10.
//   T   (epsilon) the cube with its top corner lowered by 1e-9: kept with TetGen's default
//       epsilon (idmesh is exact unless asked), moved onto the top with another epsilon or an
//       explicit -T; an epsilon above 0.01 throws 10.
#include <tetgen.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <utility>
#include <vector>

static int failures = 0;
static void check(bool ok, const char *what) {
  if (!ok) {
    fprintf(stderr, "FAIL: %s\n", what);
    failures++;
  }
}

// The unit cube: 8 corners (index x + 2y + 4z), 6 quad facets with markers 1..6.
static void cube(tetgenio &in) {
  in.firstnumber = 0;
  in.numberofpoints = 8;
  in.pointlist = new REAL[24];
  for (int i = 0; i < 8; i++) {
    in.pointlist[3 * i] = i & 1;
    in.pointlist[3 * i + 1] = (i >> 1) & 1;
    in.pointlist[3 * i + 2] = (i >> 2) & 1;
  }
  const int quads[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
  in.numberoffacets = 6;
  in.facetlist = new tetgenio::facet[6];
  in.facetmarkerlist = new int[6];
  for (int f = 0; f < 6; f++) {
    tetgenio::facet *fa = &in.facetlist[f];
    tetgenio::init(fa);
    fa->numberofpolygons = 1;
    fa->polygonlist = new tetgenio::polygon[1];
    tetgenio::init(&fa->polygonlist[0]);
    fa->polygonlist[0].numberofvertices = 4;
    fa->polygonlist[0].vertexlist = new int[4];
    for (int k = 0; k < 4; k++) fa->polygonlist[0].vertexlist[k] = quads[f][k];
    in.facetmarkerlist[f] = f + 1;
  }
}

static const REAL *pt(const tetgenio &io, int v) { return &io.pointlist[3 * (v - io.firstnumber)]; }

static double volume(const tetgenio &io, int t) {
  const int *c = &io.tetrahedronlist[t * io.numberofcorners];
  const REAL *a = pt(io, c[0]), *b = pt(io, c[1]), *d = pt(io, c[2]), *e = pt(io, c[3]);
  double u[3], v[3], w[3];
  for (int k = 0; k < 3; k++) {
    u[k] = b[k] - a[k];
    v[k] = d[k] - a[k];
    w[k] = e[k] - a[k];
  }
  return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
          u[2] * (v[0] * w[1] - v[1] * w[0])) /
         6.0;
}

static double total_volume(const tetgenio &io) {
  double s = 0;
  for (int t = 0; t < io.numberoftetrahedra; t++) s += volume(io, t);
  return s;
}

static double dist(const REAL *a, const REAL *b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                   (a[2] - b[2]) * (a[2] - b[2]));
}

static void test_order2() {
  tetgenio in, out;
  cube(in);
  tetrahedralize((char *)"pq1.4a0.05o2Q", &in, &out);
  check(out.numberofcorners == 10, "o2: 10 nodes per tetrahedron");
  const int order[6][2] = {{2, 3}, {0, 3}, {0, 1}, {1, 2}, {1, 3}, {0, 2}};
  std::vector<int> node_of_edge;  // checked through a map from edge to node
  std::set<std::pair<std::pair<int, int>, int> > seen;
  std::set<std::pair<int, int> > edges;
  bool mid = true;
  for (int t = 0; t < out.numberoftetrahedra; t++) {
    const int *c = &out.tetrahedronlist[10 * t];
    for (int k = 0; k < 6; k++) {
      int a = c[order[k][0]], b = c[order[k][1]], m = c[4 + k];
      for (int x = 0; x < 3; x++)
        if (pt(out, m)[x] != (pt(out, a)[x] + pt(out, b)[x]) / 2) mid = false;
      std::pair<int, int> e(std::min(a, b), std::max(a, b));
      edges.insert(e);
      seen.insert(std::make_pair(e, m));
    }
  }
  check(mid, "o2: edge nodes at the midpoints, in TetGen's order");
  check(seen.size() == edges.size(), "o2: one node per edge, shared by its tetrahedra");
  check(out.numberofpoints > 8 && (size_t)out.numberofpoints >= 8 + edges.size(),
        "o2: edge nodes are output points");
}

static void test_refine() {
  tetgenio in, first;
  cube(in);
  tetrahedralize((char *)"pq1.4a0.1Q", &in, &first);
  tetgenio again, out;
  again.firstnumber = first.firstnumber;
  again.numberofpoints = first.numberofpoints;
  again.pointlist = new REAL[3 * first.numberofpoints];
  std::copy(first.pointlist, first.pointlist + 3 * first.numberofpoints, again.pointlist);
  again.numberoftetrahedra = first.numberoftetrahedra;
  again.numberofcorners = 4;
  again.tetrahedronlist = new int[4 * first.numberoftetrahedra];
  std::copy(first.tetrahedronlist, first.tetrahedronlist + 4 * first.numberoftetrahedra,
            again.tetrahedronlist);
  // Tetrahedra on the x < 0.5 side get a bound of 0.002, the others none.
  again.tetrahedronvolumelist = new REAL[first.numberoftetrahedra];
  for (int t = 0; t < first.numberoftetrahedra; t++) {
    double cx = 0;
    for (int k = 0; k < 4; k++) cx += pt(first, first.tetrahedronlist[4 * t + k])[0] / 4;
    again.tetrahedronvolumelist[t] = cx < 0.5 ? 0.002 : -1;
  }
  tetrahedralize((char *)"raQ", &again, &out);
  check(std::fabs(total_volume(out) - 1.0) < 1e-9, "r: the refined mesh has the given volume");
  bool kept = out.numberofpoints >= first.numberofpoints;
  for (int i = 0; kept && i < 3 * first.numberofpoints; i++)
    kept = out.pointlist[i] == first.pointlist[i];
  check(kept, "r: the given points keep their indices");
  check(out.numberoftetrahedra > first.numberoftetrahedra, "r: the bound refines the mesh");
  // A refined tetrahedron lies in one given tetrahedron; with x < 0.4 at all corners it lies
  // in the bounded half (given tetrahedra of the other half reach x >= 0.5 > 0.4... only if
  // their centroid is there), so check those far from the middle.
  bool bounded = true;
  for (int t = 0; t < out.numberoftetrahedra; t++) {
    double xmax = 0;
    for (int k = 0; k < 4; k++) xmax = std::max(xmax, pt(out, out.tetrahedronlist[4 * t + k])[0]);
    if (xmax <= 0.2 && volume(out, t) > 0.002 * (1 + 1e-9)) bounded = false;
  }
  check(bounded, "r: tetrahedra in the bounded part meet the volume bound");
}

static void test_insert() {
  tetgenio in, add, out;
  cube(in);
  add.numberofpoints = 2;
  add.pointlist = new REAL[6];
  const REAL p[6] = {0.5, 0.5, 0.5, 0.25, 0.75, 0.3};
  std::copy(p, p + 6, add.pointlist);
  tetrahedralize((char *)"piQ", &in, &out, &add);
  for (int k = 0; k < 2; k++) {
    int found = -1;
    for (int v = 0; v < out.numberofpoints; v++)
      if (pt(out, v)[0] == p[3 * k] && pt(out, v)[1] == p[3 * k + 1] && pt(out, v)[2] == p[3 * k + 2])
        found = v;
    bool used = false;
    for (int i = 0; found >= 0 && i < 4 * out.numberoftetrahedra; i++)
      used = used || out.tetrahedronlist[i] == found;
    check(used, "i: each addin point is a vertex of the mesh");
  }
}

static void test_metric_and_attributes() {
  tetgenio in, out;
  cube(in);
  in.numberofpointmtrs = 1;
  in.pointmtrlist = new REAL[8];
  in.numberofpointattributes = 1;
  in.pointattributelist = new REAL[8];
  for (int i = 0; i < 8; i++) {
    const REAL *q = pt(in, i);
    in.pointmtrlist[i] = 0.1 + 0.4 * q[0];
    in.pointattributelist[i] = q[0] + 2 * q[1] + 3 * q[2];
  }
  tetrahedralize((char *)"pmXeQ", &in, &out);
  bool graded = out.numberoftetrahedra > 100;
  for (int t = 0; t < out.numberoftetrahedra; t++) {
    const int *c = &out.tetrahedronlist[4 * t];
    double cx = 0, longest = 0;
    for (int i = 0; i < 4; i++) {
      cx += pt(out, c[i])[0] / 4;
      for (int j = i + 1; j < 4; j++) longest = std::max(longest, dist(pt(out, c[i]), pt(out, c[j])));
    }
    if (longest > (0.1 + 0.4 * cx) * (1 + 1e-9)) graded = false;
  }
  check(graded, "m: every tetrahedron's longest edge is within the size at its centroid");
  bool linear = out.numberofpointattributes == 1 && out.pointattributelist != NULL;
  for (int v = 0; linear && v < out.numberofpoints; v++) {
    const REAL *q = pt(out, v);
    linear = std::fabs(out.pointattributelist[v] - (q[0] + 2 * q[1] + 3 * q[2])) < 1e-9;
  }
  check(linear, "point attributes are interpolated linearly");
  std::set<std::pair<int, int> > edges;
  const int pairs[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  for (int t = 0; t < out.numberoftetrahedra; t++)
    for (int k = 0; k < 6; k++) {
      int a = out.tetrahedronlist[4 * t + pairs[k][0]], b = out.tetrahedronlist[4 * t + pairs[k][1]];
      edges.insert(std::make_pair(std::min(a, b), std::max(a, b)));
    }
  std::set<std::pair<int, int> > listed;
  for (int e = 0; e < out.numberofedges; e++) {
    int a = out.edgelist[2 * e], b = out.edgelist[2 * e + 1];
    listed.insert(std::make_pair(std::min(a, b), std::max(a, b)));
  }
  check(out.numberofedges == (int)edges.size() && listed == edges,
        "e: every edge of the tetrahedra, once");
}

static double tri_area(const REAL *a, const REAL *b, const REAL *c) {
  double u[3], v[3];
  for (int k = 0; k < 3; k++) {
    u[k] = b[k] - a[k];
    v[k] = c[k] - a[k];
  }
  double n0 = u[1] * v[2] - u[2] * v[1], n1 = u[2] * v[0] - u[0] * v[2], n2 = u[0] * v[1] - u[1] * v[0];
  return 0.5 * std::sqrt(n0 * n0 + n1 * n1 + n2 * n2);
}

static void test_constraints(int firstnumber) {
  tetgenio in, out;
  cube(in);
  if (firstnumber == 1) {
    in.firstnumber = 1;
    for (int f = 0; f < in.numberoffacets; f++)
      for (int k = 0; k < 4; k++) in.facetlist[f].polygonlist[0].vertexlist[k] += 1;
  }
  // Marker 1 is the face z = 0; points 1 and 3 (0-based) the edge x = 1, z = 0.
  in.numberoffacetconstraints = 1;
  in.facetconstraintlist = new REAL[2];
  in.facetconstraintlist[0] = 1;
  in.facetconstraintlist[1] = 0.01;
  in.numberofsegmentconstraints = 1;
  in.segmentconstraintlist = new REAL[3];
  in.segmentconstraintlist[0] = 1 + firstnumber;
  in.segmentconstraintlist[1] = 3 + firstnumber;
  in.segmentconstraintlist[2] = 0.05;
  tetrahedralize((char *)"pqQ", &in, &out);
  double bounded = 0, other = 0, piece = 0, top_piece = 0;
  for (int f = 0; f < out.numberoftrifaces; f++) {
    const int *v = &out.trifacelist[3 * f];
    double a = tri_area(pt(out, v[0]), pt(out, v[1]), pt(out, v[2]));
    if (out.trifacemarkerlist[f] == 1)
      bounded = std::max(bounded, a);
    else
      other = std::max(other, a);
    for (int i = 0; i < 3; i++) {
      const REAL *p = pt(out, v[i]), *q = pt(out, v[(i + 1) % 3]);
      if (p[0] == 1 && q[0] == 1 && p[2] == q[2] && (p[2] == 0 || p[2] == 1)) {
        double &slot = p[2] == 0 ? piece : top_piece;
        slot = std::max(slot, dist(p, q));
      }
    }
  }
  check(bounded > 0 && bounded <= 0.01, "facetconstraintlist: faces of marker 1 within 0.01");
  check(other > 0.01, "facetconstraintlist: other markers are not forced below the bound");
  check(piece > 0 && piece <= 0.05, "segmentconstraintlist: pieces of the edge within 0.05");
  check(top_piece > 0.05, "segmentconstraintlist: other edges are not forced below it");

  tetgenio bad, out2;
  cube(bad);
  bad.numberoffacetconstraints = 1;
  bad.facetconstraintlist = new REAL[2];
  bad.facetconstraintlist[0] = 1;
  bad.facetconstraintlist[1] = -1;
  int code = 0;
  try {
    tetrahedralize((char *)"pqQ", &bad, &out2);
  } catch (int c) {
    code = c;
  }
  check(code == 10, "a negative facet area bound throws 10");
}

// An L-shaped prism (the square [0,2]^2 minus [1,2]^2, z from 0 to 1) meshed with and without c.
static void test_convex() {
  const double l[6][2] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  double vol[2];
  for (int c = 0; c < 2; c++) {
    tetgenio in, out;
    in.firstnumber = 0;
    in.numberofpoints = 12;
    in.pointlist = new REAL[36];
    for (int i = 0; i < 12; i++) {
      in.pointlist[3 * i] = l[i % 6][0];
      in.pointlist[3 * i + 1] = l[i % 6][1];
      in.pointlist[3 * i + 2] = i / 6;
    }
    in.numberoffacets = 8;
    in.facetlist = new tetgenio::facet[8];
    for (int f = 0; f < 8; f++) {
      tetgenio::facet *fa = &in.facetlist[f];
      tetgenio::init(fa);
      fa->numberofpolygons = 1;
      fa->polygonlist = new tetgenio::polygon[1];
      tetgenio::polygon *p = &fa->polygonlist[0];
      tetgenio::init(p);
      p->numberofvertices = f < 2 ? 6 : 4;
      p->vertexlist = new int[p->numberofvertices];
      if (f < 2) {
        for (int k = 0; k < 6; k++) p->vertexlist[k] = 6 * f + k;
      } else {
        int i = f - 2, j = (i + 1) % 6;
        p->vertexlist[0] = i;
        p->vertexlist[1] = j;
        p->vertexlist[2] = j + 6;
        p->vertexlist[3] = i + 6;
      }
    }
    tetrahedralize((char *)(c ? "pcQ" : "pQ"), &in, &out);
    vol[c] = total_volume(out);
  }
  check(std::fabs(vol[0] - 3) < 1e-12, "without c the L prism has volume 3");
  check(std::fabs(vol[1] - 3.5) < 1e-12, "c: the mesh fills the convex hull (volume 3.5)");
}

// The cube with corner 6 (x = 0, y = 1, z = 1) lowered by 1e-9 and its top split along 4-7.
static double lowered_corner_z(tetgenbehavior *b, const char *switches) {
  tetgenio in, out;
  cube(in);
  in.pointlist[3 * 6 + 2] -= 1e-9;
  tetgenio::facet *top = &in.facetlist[1];
  top->polygonlist[0].numberofvertices = 3;  // 4 5 7; the other half added below
  top->polygonlist[0].vertexlist[2] = 7;
  tetgenio::facet *facets = new tetgenio::facet[7];
  int *markers = new int[7];
  for (int f = 0; f < 6; f++) {
    facets[f] = in.facetlist[f];
    markers[f] = in.facetmarkerlist[f];
  }
  tetgenio::init(&facets[6]);
  facets[6].numberofpolygons = 1;
  facets[6].polygonlist = new tetgenio::polygon[1];
  tetgenio::init(&facets[6].polygonlist[0]);
  facets[6].polygonlist[0].numberofvertices = 3;
  facets[6].polygonlist[0].vertexlist = new int[3]{4, 7, 6};
  markers[6] = markers[1];
  delete[] in.facetlist;  // the polygons now belong to `facets`
  delete[] in.facetmarkerlist;
  in.facetlist = facets;
  in.facetmarkerlist = markers;
  in.numberoffacets = 7;
  if (b != nullptr)
    tetrahedralize(b, &in, &out);
  else
    tetrahedralize((char *)switches, &in, &out);
  return out.pointlist[3 * 6 + 2];
}

static void test_epsilon() {
  tetgenbehavior b;
  b.plc = 1;
  b.quiet = 1;
  check(lowered_corner_z(&b, nullptr) == 1 - 1e-9, "default epsilon: the input is kept exactly");
  b.epsilon = 1e-7;
  check(lowered_corner_z(&b, nullptr) == 1, "epsilon 1e-7: the corner is moved onto the top");
  check(lowered_corner_z(nullptr, "pQT") == 1, "-T: TetGen's default tolerance, asked for");
  b.epsilon = 0.5;
  int code = 0;
  try {
    lowered_corner_z(&b, nullptr);
  } catch (int c) {
    code = c;
  }
  check(code == 10, "epsilon 0.5 throws 10");
}

// Smallest and largest dihedral angle of the output, degrees.
static void dihedral_range(const tetgenio &io, double *lo, double *hi) {
  *lo = 180;
  *hi = 0;
  for (int t = 0; t < io.numberoftetrahedra; t++) {
    const int *c = &io.tetrahedronlist[t * io.numberofcorners];
    const REAL *p[4];
    for (int k = 0; k < 4; k++) p[k] = pt(io, c[k]);
    double n[4][3];
    for (int i = 0; i < 4; i++) {
      const REAL *a = p[(i + 1) % 4], *b = p[(i + 2) % 4], *d = p[(i + 3) % 4];
      double u[3], v[3], w[3];
      for (int k = 0; k < 3; k++) {
        u[k] = b[k] - a[k];
        v[k] = d[k] - a[k];
        w[k] = p[i][k] - a[k];
      }
      double m[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
      double len = std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
      double side = m[0] * w[0] + m[1] * w[1] + m[2] * w[2] > 0 ? -1 : 1;
      for (int k = 0; k < 3; k++) n[i][k] = side * m[k] / len;
    }
    for (int i = 0; i < 4; i++)
      for (int j = i + 1; j < 4; j++) {
        double d = -(n[i][0] * n[j][0] + n[i][1] * n[j][1] + n[i][2] * n[j][2]);
        double a = std::acos(std::max(-1.0, std::min(1.0, d))) * 180 / M_PI;
        *lo = std::min(*lo, a);
        *hi = std::max(*hi, a);
      }
  }
}

static void test_optimize() {
  tetgenbehavior b;
  check(b.optlevel == 0, "idmesh's tetgenbehavior does not optimise by default");
  check(b.parse_commandline((char *)"pO3/1o/150Q") && b.optlevel == 3 && b.optscheme == 1 &&
            b.optmaxdihedral == 150.0,
        "O3/1o/150 sets optlevel, optscheme, optmaxdihedral");
  double lo[2], hi[2], vol[2];
  for (int o = 0; o < 2; o++) {
    tetgenbehavior bb;
    check(bb.parse_commandline((char *)"pq1.414a0.001Q"), "parse pq1.414a0.001Q");
    check(bb.optlevel == 0, "no O: optlevel 0");
    if (o) {
      bb.optlevel = 3;
      bb.optmaxdihedral = 140;
    }
    tetgenio in, out;
    cube(in);
    tetrahedralize(&bb, &in, &out);
    dihedral_range(out, &lo[o], &hi[o]);
    vol[o] = total_volume(out);
  }
  check(lo[1] > lo[0] && hi[1] <= hi[0], "optlevel 3 improves the dihedral angles");
  check(std::fabs(vol[0] - 1) < 1e-12 && std::fabs(vol[1] - 1) < 1e-12,
        "the optimised cube keeps its volume");
  tetgenbehavior bad;
  bad.parse_commandline((char *)"pqQ");
  bad.optlevel = 2;
  bad.optscheme = 9;
  int code = 0;
  try {
    tetgenio in, out;
    cube(in);
    tetrahedralize(&bad, &in, &out);
  } catch (int c) {
    code = c;
  }
  check(code == 10, "optscheme 9 throws 10");
}

int main() {
  try {
    test_optimize();
    test_epsilon();
    test_constraints(0);
    test_constraints(1);
    test_convex();
    test_order2();
    test_refine();
    test_insert();
    test_metric_and_attributes();
  } catch (int code) {
    fprintf(stderr, "FAIL: tetrahedralize threw %d\n", code);
    return 1;
  }
  if (failures == 0) printf("tetgen_switches: all checks passed\n");
  return failures == 0 ? 0 : 1;
}
