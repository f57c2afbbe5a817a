// A TetGen client written the way FEM codes call TetGen 1.5: it fills tetgenio from a surface
// mesh, calls tetrahedralize("pq1.414a0.01nnAzQ", ...) inside try/catch(int), and reads the
// arrays back. The same file, with no #ifdef, is built against Debian's tetgen.h + libtet and
// against idmesh's compat/tetgen (tetgen_client_compare.sh compares the two). It prints, per
// case, the volume of each region (by attribute) and the area of each boundary marker, and
// checks itself that the mesh is valid: positive tetrahedra, symmetric neighbours, faces whose
// adjacent tetrahedra (adjtetlist) contain them, and every input vertex kept at its index.
//
// The domain: a 2 x 1 x 1 box cut by an internal facet at x = 1 into two regions (attributes
// 1 and 2), with a cubic cavity (a hole) in the second; quad facets, and the x = 2 side as two
// triangle facets. Markers: bottom 1, top 2, front 3, back 4, left 5, right 6, internal 7,
// cavity 8.
#include <tetgen.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

static int failures = 0;
static void check(bool ok, const char *what, int test) {
  if (!ok) {
    fprintf(stderr, "FAIL (case %d): %s\n", test, what);
    failures++;
  }
}

static void add_facet(tetgenio &in, int &f, const std::vector<std::vector<int> > &polys,
                      int marker) {
  tetgenio::facet *fa = &in.facetlist[f];
  tetgenio::init(fa);
  fa->numberofpolygons = (int)polys.size();
  fa->polygonlist = new tetgenio::polygon[polys.size()];
  for (size_t k = 0; k < polys.size(); k++) {
    tetgenio::polygon *p = &fa->polygonlist[k];
    tetgenio::init(p);
    p->numberofvertices = (int)polys[k].size();
    p->vertexlist = new int[polys[k].size()];
    for (size_t i = 0; i < polys[k].size(); i++) p->vertexlist[i] = polys[k][i] + in.firstnumber;
  }
  in.facetmarkerlist[f] = marker;
  f++;
}

static void fill(tetgenio &in, int firstnumber) {
  in.firstnumber = firstnumber;
  // Box corners: index x + 3y + 6z for x in {0,1,2}, y, z in {0,1}; cavity 12..19.
  in.numberofpoints = 20;
  in.pointlist = new REAL[3 * 20];
  in.pointmarkerlist = new int[20];
  for (int z = 0; z < 2; z++)
    for (int y = 0; y < 2; y++)
      for (int x = 0; x < 3; x++) {
        int i = x + 3 * y + 6 * z;
        in.pointlist[3 * i] = x;
        in.pointlist[3 * i + 1] = y;
        in.pointlist[3 * i + 2] = z;
      }
  for (int i = 0; i < 8; i++) {
    int p = 12 + i;
    in.pointlist[3 * p] = (i & 1) ? 1.7 : 1.3;
    in.pointlist[3 * p + 1] = (i & 2) ? 0.7 : 0.3;
    in.pointlist[3 * p + 2] = (i & 4) ? 0.7 : 0.3;
  }
  for (int i = 0; i < 20; i++) in.pointmarkerlist[i] = 100 + i;

  in.numberoffacets = 18;
  in.facetlist = new tetgenio::facet[18];
  in.facetmarkerlist = new int[18];
  int f = 0;
  auto P = [](int x, int y, int z) { return x + 3 * y + 6 * z; };
  for (int x = 0; x < 2; x++) {
    add_facet(in, f, {{P(x, 0, 0), P(x + 1, 0, 0), P(x + 1, 1, 0), P(x, 1, 0)}}, 1);
    add_facet(in, f, {{P(x, 0, 1), P(x + 1, 0, 1), P(x + 1, 1, 1), P(x, 1, 1)}}, 2);
    add_facet(in, f, {{P(x, 0, 0), P(x + 1, 0, 0), P(x + 1, 0, 1), P(x, 0, 1)}}, 3);
    add_facet(in, f, {{P(x, 1, 0), P(x + 1, 1, 0), P(x + 1, 1, 1), P(x, 1, 1)}}, 4);
  }
  add_facet(in, f, {{P(0, 0, 0), P(0, 1, 0), P(0, 1, 1), P(0, 0, 1)}}, 5);
  add_facet(in, f, {{P(2, 0, 0), P(2, 1, 0), P(2, 1, 1)}}, 6);
  add_facet(in, f, {{P(2, 0, 0), P(2, 1, 1), P(2, 0, 1)}}, 6);
  add_facet(in, f, {{P(1, 0, 0), P(1, 1, 0), P(1, 1, 1), P(1, 0, 1)}}, 7);
  auto C = [](int x, int y, int z) { return 12 + x + 2 * y + 4 * z; };
  add_facet(in, f, {{C(0, 0, 0), C(1, 0, 0), C(1, 1, 0), C(0, 1, 0)}}, 8);
  add_facet(in, f, {{C(0, 0, 1), C(1, 0, 1), C(1, 1, 1), C(0, 1, 1)}}, 8);
  add_facet(in, f, {{C(0, 0, 0), C(1, 0, 0), C(1, 0, 1), C(0, 0, 1)}}, 8);
  add_facet(in, f, {{C(0, 1, 0), C(1, 1, 0), C(1, 1, 1), C(0, 1, 1)}}, 8);
  add_facet(in, f, {{C(0, 0, 0), C(0, 1, 0), C(0, 1, 1), C(0, 0, 1)}}, 8);
  add_facet(in, f, {{C(1, 0, 0), C(1, 1, 0), C(1, 1, 1), C(1, 0, 1)}}, 8);

  in.numberofholes = 1;
  in.holelist = new REAL[3]{1.5, 0.5, 0.5};
  in.numberofregions = 2;
  in.regionlist = new REAL[10]{0.5, 0.5, 0.5, 1.0, -1.0, 1.2, 0.5, 0.5, 2.0, -1.0};
}

static double volume(const REAL *a, const REAL *b, const REAL *c, const REAL *d) {
  double u[3], v[3], w[3];
  for (int k = 0; k < 3; k++) {
    u[k] = b[k] - a[k];
    v[k] = c[k] - a[k];
    w[k] = d[k] - a[k];
  }
  return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
          u[2] * (v[0] * w[1] - v[1] * w[0])) / 6.0;
}

static double area(const REAL *a, const REAL *b, const REAL *c) {
  double u[3], v[3];
  for (int k = 0; k < 3; k++) {
    u[k] = b[k] - a[k];
    v[k] = c[k] - a[k];
  }
  double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2], z = u[0] * v[1] - u[1] * v[0];
  return 0.5 * std::sqrt(x * x + y * y + z * z);
}

static void run_case(int test, int firstnumber) {
  tetgenio in, out;
  fill(in, firstnumber);
  char switches[] = "pq1.414a0.01nnAzQ";
  try {
    tetrahedralize(switches, &in, &out);
  } catch (int code) {
    fprintf(stderr, "FAIL (case %d): tetrahedralize threw %d\n", test, code);
    failures++;
    return;
  }
  // z: indices from 0 (TetGen 1.5 leaves out.firstnumber at the input's value, idmesh sets 0).
  const int b = 0;
  check(out.numberofpoints >= in.numberofpoints, "input points kept", test);
  for (int i = 0; i < in.numberofpoints * 3; i++)
    if (out.pointlist[i] != in.pointlist[i]) {
      check(false, "an input point moved or was renumbered", test);
      break;
    }
  check(out.pointmarkerlist != NULL, "point markers are output", test);
  if (out.pointmarkerlist)
    for (int i = 0; i < in.numberofpoints; i++)
      if (out.pointmarkerlist[i] != in.pointmarkerlist[i]) {
        check(false, "an input point marker changed", test);
        break;
      }
  check(out.numberoftetrahedronattributes == 1 && out.tetrahedronattributelist != NULL,
        "A gives one attribute per tetrahedron", test);
  check(out.neighborlist != NULL && out.adjtetlist != NULL && out.trifacemarkerlist != NULL,
        "neighborlist, adjtetlist and trifacemarkerlist are output", test);
  if (failures) return;
  std::map<double, double> region_volume;
  for (int t = 0; t < out.numberoftetrahedra; t++) {
    const int *v = &out.tetrahedronlist[4 * t];
    double vol = volume(&out.pointlist[3 * (v[0] - b)], &out.pointlist[3 * (v[1] - b)],
                        &out.pointlist[3 * (v[2] - b)], &out.pointlist[3 * (v[3] - b)]);
    if (!(vol > 0) || vol > 0.01 * (1 + 1e-12)) {
      check(false, "a tetrahedron is not positive or exceeds a0.01", test);
      return;
    }
    region_volume[out.tetrahedronattributelist[t]] += vol;
    for (int i = 0; i < 4; i++) {
      int n = out.neighborlist[4 * t + i];
      if (n < 0) continue;
      bool back = false;
      for (int j = 0; j < 4; j++) back = back || out.neighborlist[4 * (n - b) + j] == t + b;
      if (!back) {
        check(false, "neighbours are not symmetric", test);
        return;
      }
    }
  }
  std::map<int, double> marker_area;
  for (int f = 0; f < out.numberoftrifaces; f++) {
    const int *v = &out.trifacelist[3 * f];
    // At least one side names a tetrahedron with the face (TetGen 1.5 may give 0 rather than
    // -1 for the outer side of a boundary face).
    int with_face = 0;
    for (int s = 0; s < 2; s++) {
      int t = out.adjtetlist[2 * f + s];
      if (t < b || t >= out.numberoftetrahedra + b) continue;
      int shared = 0;
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++) shared += out.tetrahedronlist[4 * (t - b) + j] == v[i];
      with_face += shared == 3;
    }
    if (with_face == 0) {
      check(false, "adjtetlist names no tetrahedron with the face", test);
      return;
    }
    int m = out.trifacemarkerlist[f];
    if (m != 0)
      marker_area[m] += area(&out.pointlist[3 * (v[0] - b)], &out.pointlist[3 * (v[1] - b)],
                             &out.pointlist[3 * (v[2] - b)]);
  }
  for (auto &r : region_volume) printf("case %d region %g volume %.12f\n", test, r.first, r.second);
  for (auto &m : marker_area) printf("case %d marker %d area %.12f\n", test, m.first, m.second);
}

int main() {
  run_case(1, 0);
  run_case(2, 1);
  return failures ? 1 : 0;
}
