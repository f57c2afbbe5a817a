// A C++ client of compat/triangle/triangle.h written as FEM codes call Triangle: no REAL or VOID
// defined, inputs in std::vectors, a user sizing test (-u) defined in C++, outputs read into
// the program's own structures and freed with trifree. It meshes an L-shaped domain and
// prints it for triangle_compare.py, checks that the sizing test was honoured, then feeds a
// bad input and checks that the program goes on and meshes the next one.
#include "triangle.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace {

int failures = 0;
long calls = 0;

void check(bool ok, const std::string &what) {
  if (!ok) {
    std::fprintf(stderr, "FAIL: %s\n", what.c_str());
    ++failures;
  }
}

// Smaller triangles near the re-entrant corner (1, 1).
double wanted_area(double x, double y) {
  double d = std::hypot(x - 1.0, y - 1.0);
  return 0.002 + 0.05 * d * d;
}

struct Mesh {
  std::vector<double> xy;
  std::vector<int> markers, tris, nbrs, segs, segmarks, edges, edgemarks;
  std::vector<double> attrs;
};

void free_out(triangulateio &out) {
  void *arrays[] = {out.pointlist, out.pointattributelist, out.pointmarkerlist,
                    out.trianglelist, out.triangleattributelist, out.neighborlist,
                    out.segmentlist, out.segmentmarkerlist, out.edgelist, out.edgemarkerlist};
  for (void *p : arrays) trifree(p);
  out = triangulateio();
}

}  // namespace

extern "C" int triunsuitable(double *org, double *dest, double *apex, double area) {
  ++calls;
  double cx = (org[0] + dest[0] + apex[0]) / 3, cy = (org[1] + dest[1] + apex[1]) / 3;
  return area > wanted_area(cx, cy) ? 1 : 0;
}

namespace {

bool mesh_l(const char *switches, Mesh &m) {
  std::vector<double> pts = {0, 0, 2, 0, 2, 1, 1, 1, 1, 2, 0, 2};
  std::vector<int> pmarks(6, 0);
  std::vector<int> segs = {0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 0};
  std::vector<int> smarks = {1, 2, 3, 3, 4, 5};
  std::vector<double> regions = {0.5, 0.5, 7.0, 0.0};
  triangulateio in = triangulateio(), out = triangulateio();
  in.numberofpoints = 6;
  in.pointlist = pts.data();
  in.pointmarkerlist = pmarks.data();
  in.numberofsegments = 6;
  in.segmentlist = segs.data();
  in.segmentmarkerlist = smarks.data();
  in.numberofregions = 1;
  in.regionlist = regions.data();
  std::string sw = switches;
  triangulate(&sw[0], &in, &out, nullptr);
  bool ok = out.numberoftriangles > 0;
  if (ok) {
    m.xy.assign(out.pointlist, out.pointlist + 2 * out.numberofpoints);
    m.markers.assign(out.pointmarkerlist, out.pointmarkerlist + out.numberofpoints);
    m.tris.assign(out.trianglelist, out.trianglelist + 3 * out.numberoftriangles);
    m.attrs.assign(out.triangleattributelist,
                   out.triangleattributelist + out.numberoftriangles);
    m.nbrs.assign(out.neighborlist, out.neighborlist + 3 * out.numberoftriangles);
    m.segs.assign(out.segmentlist, out.segmentlist + 2 * out.numberofsegments);
    m.segmarks.assign(out.segmentmarkerlist, out.segmentmarkerlist + out.numberofsegments);
    m.edges.assign(out.edgelist, out.edgelist + 2 * out.numberofedges);
    m.edgemarks.assign(out.edgemarkerlist, out.edgemarkerlist + out.numberofedges);
    std::printf("case %s\n", switches);
    for (int i = 0; i < in.numberofpoints; ++i)
      std::printf("P %.17g %.17g %d\n", pts[2 * i], pts[2 * i + 1], pmarks[i]);
    for (int i = 0; i < in.numberofsegments; ++i)
      std::printf("G %d %d %d\n", segs[2 * i], segs[2 * i + 1], smarks[i]);
    std::printf("R %.17g %.17g %.17g %.17g\n", regions[0], regions[1], regions[2], regions[3]);
    for (size_t i = 0; i < m.markers.size(); ++i)
      std::printf("p %.17g %.17g %d\n", m.xy[2 * i], m.xy[2 * i + 1], m.markers[i]);
    for (size_t i = 0; i < m.attrs.size(); ++i)
      std::printf("t %d %d %d %.17g\n", m.tris[3 * i], m.tris[3 * i + 1], m.tris[3 * i + 2],
                  m.attrs[i]);
    for (size_t i = 0; i < m.attrs.size(); ++i)
      std::printf("n %d %d %d\n", m.nbrs[3 * i], m.nbrs[3 * i + 1], m.nbrs[3 * i + 2]);
    for (size_t i = 0; i < m.segmarks.size(); ++i)
      std::printf("s %d %d %d\n", m.segs[2 * i], m.segs[2 * i + 1], m.segmarks[i]);
    for (size_t i = 0; i < m.edgemarks.size(); ++i)
      std::printf("e %d %d %d\n", m.edges[2 * i], m.edges[2 * i + 1], m.edgemarks[i]);
    std::printf("end\n");
  }
  check(out.regionlist == in.regionlist || !ok, "regionlist is shared with in");
  free_out(out);
  return ok;
}

}  // namespace

int main() {
  Mesh m;
  check(mesh_l("pq28uzAenQ", m), std::string("pq28uzAenQ: ") + idm_last_error());
  check(calls > 0, "triunsuitable was called");
  for (size_t t = 0; t < m.attrs.size(); ++t) {
    const double *a = &m.xy[2 * m.tris[3 * t]], *b = &m.xy[2 * m.tris[3 * t + 1]],
                 *c = &m.xy[2 * m.tris[3 * t + 2]];
    double area = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
    double ca[2] = {a[0], a[1]}, cb[2] = {b[0], b[1]}, cc[2] = {c[0], c[1]};
    check(area > 0, "triangle " + std::to_string(t) + " is counter-clockwise");
    check(triunsuitable(ca, cb, cc, area) == 0,
          "triangle " + std::to_string(t) + " meets the user's sizing test");
    check(m.attrs[t] == 7.0, "regional attribute 7");
  }
  Mesh bad;
  check(!mesh_l("pq28zAenrQ", bad), "-r is refused");
  check(std::strstr(idm_last_error(), "-r") != nullptr, "the message names -r");
  Mesh again;
  check(mesh_l("pq30a0.01zAenQ", again), "the host goes on meshing after an error");
  if (failures) std::fprintf(stderr, "%d checks failed\n", failures);
  return failures ? 1 : 0;
}
