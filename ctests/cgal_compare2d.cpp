// Compares idmesh's 2D meshes with CGAL's 2D meshers on PSLGs built here, and checks both
// results independently with CGAL's exact predicates.
//
// For each PSLG:
//  (a) conforming Delaunay, no quality bound: idmesh with default options vs
//      CGAL::make_conforming_Delaunay_2 on a Constrained_Delaunay_triangulation_2 (and, for
//      information, CGAL::make_conforming_Gabriel_2, which splits every encroached segment as
//      Delaunay refinement does);
//  (b) quality meshes at minimum angles 20.7 and 30 degrees with an edge-length bound S, and
//      at 30 degrees without a size bound:
//      idmesh (min_angle + a sizing callback "longest edge > S") vs CGAL::Delaunay_mesher_2
//      with Delaunay_mesh_size_criteria_2(sin^2(theta), S). CGAL's shape bound is on sin^2 of the
//      smallest angle and its size bound is on the longest EDGE, which is exactly what the
//      callback asks of idmesh, so both sides refine against the same criteria.
//
// Checks (exact predicates of Exact_predicates_inexact_constructions_kernel):
//  - idmesh: status OK, idm_mesher2d_validate OK, every triangle counter-clockwise, every
//    circumcircle empty of all mesh vertices, the angle bound except at input corners below
//    60 degrees, the edge bound, total area equal to the domain's area (1e-9 relative);
//  - CGAL: in-domain faces counter-clockwise, their total area equal to the domain's area;
//  - for the quality runs, idmesh's triangle count at most 1.5 times CGAL's at the same bounds.
//    The conforming runs have no bound to compare at and tiny meshes (a handful of Steiner
//    points decides the ratio), so there the ratio is printed but not enforced.
// A table of both counts, their ratio and both minimum angles is always printed.
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_conformer_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "idmesh.h"

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_2;

using MeshVb = CGAL::Delaunay_mesh_vertex_base_2<K>;
using MeshFb = CGAL::Delaunay_mesh_face_base_2<K>;
using MeshTds = CGAL::Triangulation_data_structure_2<MeshVb, MeshFb>;
using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, MeshTds, CGAL::Exact_predicates_tag>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<CDT>;
using Mesher = CGAL::Delaunay_mesher_2<CDT, Criteria>;

using InfoVb = CGAL::Triangulation_vertex_base_with_info_2<uint32_t, K>;
using InfoTds = CGAL::Triangulation_data_structure_2<InfoVb>;
using DT = CGAL::Delaunay_triangulation_2<K, InfoTds>;

constexpr double kPi = 3.14159265358979323846;
constexpr double kRelAreaTol = 1e-9;
// Angles are measured with atan2 in floating point while the mesher decides with its own
// rounding: a violation smaller than this many degrees is measurement noise, not a bug.
constexpr double kAngleSlackDeg = 1e-7;
constexpr double kMaxRatio = 1.5;

// ------------------------------------------------------------------------------------------
// Test PSLGs.

struct Pslg {
  std::string name;
  std::vector<std::array<double, 2>> pts;
  std::vector<std::array<uint32_t, 2>> segs;
  std::vector<std::array<double, 2>> holes;
  double area = 0.0;         // area of the meshed domain
  double size_bound = 0.0;   // edge-length bound S for the quality runs
};

// Appends a closed polygon (points and segments) and returns its unsigned area.
double add_loop(Pslg& g, const std::vector<std::array<double, 2>>& loop) {
  const auto base = static_cast<uint32_t>(g.pts.size());
  const auto n = static_cast<uint32_t>(loop.size());
  double twice = 0.0;
  for (uint32_t i = 0; i < n; ++i) {
    const auto& p = loop[i];
    const auto& q = loop[(i + 1) % n];
    twice += p[0] * q[1] - p[1] * q[0];
    g.pts.push_back(p);
    g.segs.push_back({base + i, base + (i + 1) % n});
  }
  return std::fabs(0.5 * twice);
}

Pslg square_circle_hole() {
  Pslg g;
  g.name = "square+circle64";
  double outer = add_loop(g, {{{-1, -1}}, {{1, -1}}, {{1, 1}}, {{-1, 1}}});
  std::vector<std::array<double, 2>> circle;
  for (int k = 0; k < 64; ++k) {
    double t = 2.0 * kPi * k / 64.0;
    circle.push_back({{0.5 * std::cos(t), 0.5 * std::sin(t)}});
  }
  double hole = add_loop(g, circle);
  g.holes.push_back({{0.0, 0.0}});
  g.area = outer - hole;
  g.size_bound = 0.04;
  return g;
}

Pslg l_shape_interior_segment() {
  Pslg g;
  g.name = "L+interior segment";
  g.area = add_loop(g, {{{0, 0}}, {{2, 0}}, {{2, 1}}, {{1, 1}}, {{1, 2}}, {{0, 2}}});
  // A free-standing segment inside the domain: it splits no area but must be conformed to.
  auto a = static_cast<uint32_t>(g.pts.size());
  g.pts.push_back({{0.3, 0.3}});
  g.pts.push_back({{1.7, 0.6}});
  g.segs.push_back({a, a + 1});
  g.size_bound = 0.05;
  return g;
}

Pslg ten_degree_corner() {
  Pslg g;
  g.name = "10-degree corner";
  const double t = 10.0 * kPi / 180.0;
  g.area = add_loop(g, {{{0, 0}}, {{6, 0}}, {{6, 3}}, {{3, 3}},
                        {{4.0 * std::cos(t), 4.0 * std::sin(t)}}});
  g.size_bound = 0.12;
  return g;
}

Pslg letter_p_with_hole() {
  Pslg g;
  g.name = "letter P with hole";
  double outer = add_loop(g, {{{0, 0}}, {{1, 0}}, {{1, 2}}, {{2.2, 2}}, {{2.8, 2.5}},
                              {{2.8, 3.5}}, {{2.2, 4}}, {{0, 4}}});
  double hole = add_loop(g, {{{1, 2.6}}, {{1.9, 2.6}}, {{2.3, 3}}, {{1.9, 3.4}}, {{1, 3.4}}});
  g.holes.push_back({{1.5, 3.0}});
  g.area = outer - hole;
  g.size_bound = 0.06;
  return g;
}

// ------------------------------------------------------------------------------------------
// Small geometry helpers.

double dist2(const double* a, const double* b) {
  double dx = a[0] - b[0], dy = a[1] - b[1];
  return dx * dx + dy * dy;
}

double max_edge2(const double* a, const double* b, const double* c) {
  return std::max({dist2(a, b), dist2(b, c), dist2(c, a)});
}

// The angle at p between p->q and p->r in degrees; atan2 stays accurate for tiny angles.
double angle_deg(const double* p, const double* q, const double* r) {
  double ux = q[0] - p[0], uy = q[1] - p[1], vx = r[0] - p[0], vy = r[1] - p[1];
  return std::atan2(std::fabs(ux * vy - uy * vx), ux * vx + uy * vy) * (180.0 / kPi);
}

double tri_area(const double* a, const double* b, const double* c) {
  return 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
}

Point pt(const double* p) { return Point(p[0], p[1]); }

// ------------------------------------------------------------------------------------------
// One row of the result table.

struct Row {
  std::string pslg, mode;
  size_t id_tris = 0, cgal_tris = 0, cgal_gabriel_tris = 0;
  double id_min = 180.0, cgal_min = 180.0;
  double id_sec = 0.0, cgal_sec = 0.0;
  size_t exempt = 0;
  bool cgal_capped = false;
  std::vector<std::string> failures;
};

void fail(Row& row, std::string msg) { row.failures.push_back(std::move(msg)); }

template <typename... Args>
std::string fmt(const char* f, Args... args) {
  char buf[512];
  std::snprintf(buf, sizeof buf, f, args...);
  return buf;
}

// ------------------------------------------------------------------------------------------
// idmesh side.

// The idmesh twin of CGAL's size criterion: too large when the longest edge exceeds S.
extern "C" int32_t longest_edge_rule(void* user, const double* a, const double* b,
                                     const double* c, double /*area*/) {
  const double s2 = *static_cast<const double*>(user);
  return max_edge2(a, b, c) > s2 ? 1 : 0;
}

struct IdMesh {
  std::vector<double> xy;
  std::vector<uint32_t> tri;
  std::vector<uint32_t> seg;
  std::vector<int32_t> seg_marker;
};

// Meshes `g` with idmesh. theta <= 0: conforming Delaunay only. Returns false (with failures
// recorded) when no mesh could be read.
bool run_idmesh(const Pslg& g, double theta, double size_bound, Row& row, IdMesh& out) {
  idm_mesher2d* m = nullptr;
  if (idm_mesher2d_new(&m) != IDM_OK || !m) {
    fail(row, std::string("idm_mesher2d_new: ") + idm_last_error());
    return false;
  }
  std::vector<double> xy;
  for (const auto& p : g.pts) xy.insert(xy.end(), {p[0], p[1]});
  std::vector<uint32_t> ab;
  std::vector<int32_t> markers;  // segment i has marker i + 1, so subsegments map back
  for (size_t i = 0; i < g.segs.size(); ++i) {
    ab.insert(ab.end(), {g.segs[i][0], g.segs[i][1]});
    markers.push_back(static_cast<int32_t>(i + 1));
  }
  std::vector<double> holes;
  for (const auto& h : g.holes) holes.insert(holes.end(), {h[0], h[1]});

  idm_options2d o;
  idm_options2d_default(&o);
  o.min_angle = theta > 0 ? theta : 0.0;
  const double s2 = size_bound * size_bound;
  bool ok = idm_mesher2d_add_points(m, xy.data(), g.pts.size(), nullptr) == IDM_OK &&
            idm_mesher2d_add_segments(m, ab.data(), g.segs.size(), markers.data()) == IDM_OK &&
            idm_mesher2d_add_holes(m, holes.data(), g.holes.size()) == IDM_OK &&
            idm_mesher2d_set_options(m, &o) == IDM_OK &&
            (size_bound <= 0 ||
             idm_mesher2d_set_sizing(m, longest_edge_rule, const_cast<double*>(&s2)) == IDM_OK);
  if (!ok) {
    fail(row, std::string("idmesh input rejected: ") + idm_last_error());
    idm_mesher2d_free(m);
    return false;
  }
  auto t0 = std::chrono::steady_clock::now();
  idm_status st = idm_mesher2d_refine(m);
  row.id_sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (st != IDM_OK) {
    fail(row, fmt("idm_mesher2d_refine returned %d: %s", static_cast<int>(st), idm_last_error()));
    idm_mesher2d_free(m);
    return false;
  }
  if (idm_mesher2d_validate(m) != IDM_OK) {
    fail(row, std::string("idm_mesher2d_validate: ") + idm_last_error());
  }
  const double* vxy = nullptr;
  const uint32_t* tri = nullptr;
  const uint32_t* seg = nullptr;
  const int32_t* smark = nullptr;
  size_t nv = 0, nt = 0, ns = 0;
  if (idm_mesher2d_vertices(m, &vxy, &nv) != IDM_OK ||
      idm_mesher2d_triangles(m, &tri, &nt) != IDM_OK ||
      idm_mesher2d_segments(m, &seg, &smark, &ns) != IDM_OK) {
    fail(row, std::string("idmesh getters: ") + idm_last_error());
    idm_mesher2d_free(m);
    return false;
  }
  out.xy.assign(vxy, vxy + 2 * nv);
  out.tri.assign(tri, tri + 3 * nt);
  out.seg.assign(seg, seg + 2 * ns);
  out.seg_marker.assign(smark, smark + ns);
  idm_mesher2d_free(m);
  return true;
}

// Exact check that every triangle's circumcircle is empty of the mesh's vertices.
//
// Lemma used: if a circle C through vertex a has a vertex strictly inside, then some Delaunay
// neighbour of a is strictly inside C. (Shrink C towards a while keeping it tangent at a; the
// last circle before it becomes empty passes through a and has an empty interior, so the points
// on it form a Delaunay cell, whose two boundary neighbours of a are edges of EVERY Delaunay
// triangulation and lie strictly inside C.) So testing a's neighbours in CGAL's Delaunay
// triangulation is exact and costs O(degree) per triangle, and cocircular ties cannot cause
// false alarms.
size_t count_nonempty_circumcircles(const IdMesh& m, Row& row) {
  const size_t nv = m.xy.size() / 2;
  std::vector<char> used(nv, 0);
  for (uint32_t v : m.tri) used[v] = 1;
  std::vector<std::pair<Point, uint32_t>> pts;
  for (size_t v = 0; v < nv; ++v)
    if (used[v]) pts.emplace_back(pt(&m.xy[2 * v]), static_cast<uint32_t>(v));
  DT dt;
  dt.insert(pts.begin(), pts.end());
  if (dt.number_of_vertices() != pts.size()) {
    fail(row, fmt("%zu mesh vertices share coordinates", pts.size() - dt.number_of_vertices()));
    return 0;
  }
  std::vector<DT::Vertex_handle> handle(nv);
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v)
    handle[v->info()] = v;
  auto side = K().side_of_oriented_circle_2_object();
  size_t bad = 0;
  for (size_t t = 0; t + 2 < m.tri.size(); t += 3) {
    const Point a = pt(&m.xy[2 * m.tri[t]]), b = pt(&m.xy[2 * m.tri[t + 1]]),
                c = pt(&m.xy[2 * m.tri[t + 2]]);
    if (CGAL::orientation(a, b, c) != CGAL::LEFT_TURN) continue;  // reported separately
    auto circ = dt.incident_vertices(handle[m.tri[t]]), done = circ;
    do {
      if (!dt.is_infinite(circ) && side(a, b, c, circ->point()) == CGAL::ON_POSITIVE_SIDE) {
        ++bad;
        break;
      }
    } while (++circ != done);
  }
  return bad;
}

// Which input segments each output vertex lies on (from the subsegments' markers), and the
// smallest angle between input segments at each input vertex.
struct SegmentInfo {
  std::vector<std::vector<uint32_t>> on;  // per output vertex: input segment ids
  std::vector<double> corner;             // per input vertex: smallest angle between segments
};

SegmentInfo segment_info(const Pslg& g, const IdMesh& m) {
  SegmentInfo si;
  si.on.resize(m.xy.size() / 2);
  si.corner.assign(g.pts.size(), 360.0);
  for (size_t s = 0; s < m.seg_marker.size(); ++s) {
    int32_t id = m.seg_marker[s] - 1;
    if (id < 0 || static_cast<size_t>(id) >= g.segs.size()) continue;
    for (int e = 0; e < 2; ++e) {
      auto& list = si.on[m.seg[2 * s + e]];
      if (std::find(list.begin(), list.end(), static_cast<uint32_t>(id)) == list.end())
        list.push_back(static_cast<uint32_t>(id));
    }
  }
  for (size_t i = 0; i < g.segs.size(); ++i) {
    for (size_t j = i + 1; j < g.segs.size(); ++j) {
      for (int ei = 0; ei < 2; ++ei) {
        for (int ej = 0; ej < 2; ++ej) {
          uint32_t c = g.segs[i][ei];
          if (c != g.segs[j][ej]) continue;
          const double* pc = g.pts[c].data();
          double ang = angle_deg(pc, g.pts[g.segs[i][1 - ei]].data(),
                                 g.pts[g.segs[j][1 - ej]].data());
          si.corner[c] = std::min(si.corner[c], ang);
        }
      }
    }
  }
  return si;
}

// Whether input segments s1 and s2 share an endpoint where they meet at less than 60 degrees.
bool small_corner_between(const Pslg& g, const SegmentInfo& si, uint32_t s1, uint32_t s2) {
  if (s1 == s2) return false;
  for (uint32_t c1 : g.segs[s1])
    for (uint32_t c2 : g.segs[s2])
      if (c1 == c2 && si.corner[c1] < 60.0) return true;
  return false;
}

// An angle below the bound is exempt when it sits at an input corner below 60 degrees, or is
// opposite an edge joining two segments that meet at such a corner (the shells around it).
bool exempt_angle(const Pslg& g, const SegmentInfo& si, uint32_t apex, uint32_t x, uint32_t y) {
  if (apex < g.pts.size() && si.corner[apex] < 60.0) return true;
  for (uint32_t s1 : si.on[x])
    for (uint32_t s2 : si.on[y])
      if (small_corner_between(g, si, s1, s2)) return true;
  return false;
}

void check_idmesh(const Pslg& g, const IdMesh& m, double theta, double size_bound, Row& row) {
  const size_t nv = m.xy.size() / 2, nt = m.tri.size() / 3;
  row.id_tris = nt;
  for (uint32_t v : m.tri) {
    if (v >= nv) {
      fail(row, fmt("idmesh triangle refers to vertex %u of %zu", v, nv));
      return;
    }
  }
  SegmentInfo si = segment_info(g, m);
  size_t not_ccw = 0, bad_angle = 0, too_long = 0;
  double area = 0.0, worst = 180.0;
  const double s2 = size_bound * size_bound;
  for (size_t t = 0; t < nt; ++t) {
    const uint32_t* v = &m.tri[3 * t];
    const double *a = &m.xy[2 * v[0]], *b = &m.xy[2 * v[1]], *c = &m.xy[2 * v[2]];
    if (CGAL::orientation(pt(a), pt(b), pt(c)) != CGAL::LEFT_TURN) ++not_ccw;
    area += tri_area(a, b, c);
    if (size_bound > 0 && max_edge2(a, b, c) > s2) ++too_long;
    const double ang[3] = {angle_deg(a, b, c), angle_deg(b, c, a), angle_deg(c, a, b)};
    for (int k = 0; k < 3; ++k) {
      row.id_min = std::min(row.id_min, ang[k]);
      if (theta > 0 && ang[k] < theta - kAngleSlackDeg) {
        if (exempt_angle(g, si, v[k], v[(k + 1) % 3], v[(k + 2) % 3])) {
          ++row.exempt;
        } else {
          ++bad_angle;
          worst = std::min(worst, ang[k]);
        }
      }
    }
  }
  if (not_ccw) fail(row, fmt("idmesh: %zu triangles not counter-clockwise", not_ccw));
  if (bad_angle)
    fail(row, fmt("idmesh: %zu angles below %.2f deg away from small input corners (worst %.4f)",
                  bad_angle, theta, worst));
  if (too_long) fail(row, fmt("idmesh: %zu triangles with an edge longer than %g", too_long,
                              size_bound));
  if (!(std::fabs(area - g.area) <= kRelAreaTol * g.area))
    fail(row, fmt("idmesh: total area %.15g, domain area %.15g", area, g.area));
  size_t nonempty = count_nonempty_circumcircles(m, row);
  if (nonempty) fail(row, fmt("idmesh: %zu triangles with a vertex inside their circumcircle",
                              nonempty));
}

// ------------------------------------------------------------------------------------------
// Self-test of the checks: deliberately broken copies of a real idmesh mesh must be caught,
// or a passing table would mean nothing.

bool mentions(const Row& r, const char* what) {
  for (const auto& f : r.failures)
    if (f.find(what) != std::string::npos) return true;
  return false;
}

// Flips one interior edge whose two triangles form a strictly convex quadrilateral with the
// fourth vertex strictly outside the first triangle's circumcircle: the flipped pair then has
// a vertex strictly inside a circumcircle. Returns false if no such edge exists.
bool flip_a_delaunay_edge(IdMesh& m) {
  std::vector<std::array<uint32_t, 4>> he;  // (lo, hi, triangle, corner opposite the edge)
  const size_t nt = m.tri.size() / 3;
  for (uint32_t t = 0; t < nt; ++t)
    for (uint32_t k = 0; k < 3; ++k) {
      uint32_t u = m.tri[3 * t + (k + 1) % 3], v = m.tri[3 * t + (k + 2) % 3];
      he.push_back({std::min(u, v), std::max(u, v), t, k});
    }
  std::sort(he.begin(), he.end());
  auto side = K().side_of_oriented_circle_2_object();
  for (size_t i = 0; i + 1 < he.size(); ++i) {
    if (he[i][0] != he[i + 1][0] || he[i][1] != he[i + 1][1]) continue;
    uint32_t t1 = he[i][2], t2 = he[i + 1][2];
    uint32_t a = m.tri[3 * t1 + he[i][3]], b = m.tri[3 * t1 + (he[i][3] + 1) % 3],
             c = m.tri[3 * t1 + (he[i][3] + 2) % 3], d = m.tri[3 * t2 + he[i + 1][3]];
    Point pa = pt(&m.xy[2 * a]), pb = pt(&m.xy[2 * b]), pc = pt(&m.xy[2 * c]),
          pd = pt(&m.xy[2 * d]);
    if (CGAL::orientation(pa, pb, pd) != CGAL::LEFT_TURN ||
        CGAL::orientation(pa, pd, pc) != CGAL::LEFT_TURN ||
        side(pa, pb, pc, pd) != CGAL::ON_NEGATIVE_SIDE)
      continue;
    const uint32_t n1[3] = {a, b, d}, n2[3] = {a, d, c};
    std::copy(n1, n1 + 3, &m.tri[3 * t1]);
    std::copy(n2, n2 + 3, &m.tri[3 * t2]);
    return true;
  }
  return false;
}

// Returns the number of broken meshes the checks failed to catch (0 when all is well).
int self_test(const Pslg& g) {
  const double theta = 25.0, size = 2.0 * g.size_bound;
  Row base;
  IdMesh m;
  if (!run_idmesh(g, theta, size, base, m)) {
    std::printf("self-test skipped: idmesh failed on %s\n", g.name.c_str());
    return 0;  // the comparison rows report this failure
  }
  check_idmesh(g, m, theta, size, base);
  if (!base.failures.empty()) {
    std::printf("self-test skipped: the unbroken mesh already fails (%s)\n",
                base.failures[0].c_str());
    return 0;
  }
  int missed = 0;
  auto expect = [&](const char* what, const IdMesh& broken, double th, double sz,
                    const char* needle) {
    Row r;
    check_idmesh(g, broken, th, sz, r);
    bool caught = mentions(r, needle);
    std::printf("self-test: %-36s %s\n", what, caught ? "caught" : "MISSED");
    if (!caught) ++missed;
  };
  IdMesh cw = m;
  std::swap(cw.tri[1], cw.tri[2]);
  expect("one clockwise triangle", cw, theta, size, "counter-clockwise");
  IdMesh flipped = m;
  if (flip_a_delaunay_edge(flipped)) {
    expect("one non-Delaunay edge flip", flipped, theta, size, "circumcircle");
  } else {
    std::printf("self-test: no flippable edge found: MISSED\n");
    ++missed;
  }
  IdMesh dropped = m;
  dropped.tri.resize(dropped.tri.size() - 3);
  expect("one triangle missing", dropped, theta, size, "total area");
  expect("angle bound above the mesh's", m, base.id_min + 0.5, size, "angles below");
  expect("edge bound below the mesh's", m, theta, 0.5 * size, "longer than");
  return missed;
}

// ------------------------------------------------------------------------------------------
// CGAL side.

void insert_pslg(const Pslg& g, CDT& cdt) {
  std::vector<CDT::Vertex_handle> vh;
  vh.reserve(g.pts.size());
  for (const auto& p : g.pts) vh.push_back(cdt.insert(Point(p[0], p[1])));
  for (const auto& s : g.segs) cdt.insert_constraint(vh[s[0]], vh[s[1]]);
}

// Counts, checks and measures CGAL's in-domain faces.
void check_cgal(const Pslg& g, const CDT& cdt, Row& row) {
  size_t n = 0, not_ccw = 0;
  double area = 0.0;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (!f->is_in_domain()) continue;
    ++n;
    const Point &a = f->vertex(0)->point(), &b = f->vertex(1)->point(),
                &c = f->vertex(2)->point();
    if (CGAL::orientation(a, b, c) != CGAL::LEFT_TURN) ++not_ccw;
    const double pa[2] = {a.x(), a.y()}, pb[2] = {b.x(), b.y()}, pc[2] = {c.x(), c.y()};
    area += tri_area(pa, pb, pc);
    row.cgal_min = std::min({row.cgal_min, angle_deg(pa, pb, pc), angle_deg(pb, pc, pa),
                             angle_deg(pc, pa, pb)});
  }
  row.cgal_tris = n;
  if (not_ccw) fail(row, fmt("CGAL: %zu faces not counter-clockwise", not_ccw));
  if (!(std::fabs(area - g.area) <= kRelAreaTol * g.area))
    fail(row, fmt("CGAL: domain area %.15g, expected %.15g", area, g.area));
}

std::vector<Point> hole_seeds(const Pslg& g) {
  std::vector<Point> seeds;
  for (const auto& h : g.holes) seeds.emplace_back(h[0], h[1]);
  return seeds;
}

void run_cgal_conforming(const Pslg& g, Row& row) {
  auto seeds = hole_seeds(g);
  {
    CDT cdt;
    insert_pslg(g, cdt);
    auto t0 = std::chrono::steady_clock::now();
    CGAL::make_conforming_Delaunay_2(cdt);
    row.cgal_sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    Mesher::mark_facets(cdt, seeds.begin(), seeds.end(), false);
    check_cgal(g, cdt, row);
  }
  // Gabriel conformity, for information only (checked all the same).
  CDT cdt;
  insert_pslg(g, cdt);
  CGAL::make_conforming_Gabriel_2(cdt);
  Mesher::mark_facets(cdt, seeds.begin(), seeds.end(), false);
  Row scratch;
  scratch.pslg = g.name;
  check_cgal(g, cdt, scratch);
  for (auto& f : scratch.failures) fail(row, "Gabriel " + f);
  row.cgal_gabriel_tris = scratch.cgal_tris;
}

void run_cgal_quality(const Pslg& g, double theta, double size_bound, size_t vertex_cap,
                      Row& row) {
  CDT cdt;
  insert_pslg(g, cdt);
  const double s = std::sin(theta * kPi / 180.0);
  Mesher mesher(cdt, Criteria(s * s, size_bound));
  auto seeds = hole_seeds(g);
  mesher.set_seeds(seeds.begin(), seeds.end(), false);
  auto t0 = std::chrono::steady_clock::now();
  mesher.init();
  // Step by step so a non-terminating run (CGAL guarantees termination only up to about
  // 20.7 degrees) is capped instead of hanging the test.
  while (mesher.step_by_step_refine_mesh()) {
    if (cdt.number_of_vertices() > vertex_cap) {
      row.cgal_capped = true;
      break;
    }
  }
  row.cgal_sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  check_cgal(g, cdt, row);
}

// ------------------------------------------------------------------------------------------

// theta <= 0: conforming Delaunay; otherwise a quality run, with the edge bound when
// size_bound > 0.
Row run_case(const Pslg& g, double theta, double size_bound) {
  Row row;
  row.pslg = g.name;
  row.mode = theta <= 0         ? std::string("conforming")
             : size_bound > 0 ? fmt("q%.1f S=%g", theta, size_bound)
                              : fmt("q%.1f", theta);
  IdMesh m;
  if (run_idmesh(g, theta, size_bound, row, m)) check_idmesh(g, m, theta, size_bound, row);
  if (theta > 0) {
    // Far beyond what either mesher needs: only a run-away refinement reaches it.
    size_t cap = std::max<size_t>(200000, 20 * (m.xy.size() / 2));
    run_cgal_quality(g, theta, size_bound, cap, row);
  } else {
    run_cgal_conforming(g, row);
  }
  if (row.cgal_capped) fail(row, "CGAL did not finish (vertex cap reached)");
  if (theta > 0 && row.id_tris > 0 && row.cgal_tris > 0 &&
      static_cast<double>(row.id_tris) > kMaxRatio * static_cast<double>(row.cgal_tris))
    fail(row, fmt("idmesh has %.2fx CGAL's triangles (limit %.1fx)",
                  static_cast<double>(row.id_tris) / static_cast<double>(row.cgal_tris),
                  kMaxRatio));
  return row;
}

}  // namespace

int main() {
  std::printf("idmesh %s vs CGAL %s\n", idm_version(), CGAL_VERSION_STR);
  const std::vector<Pslg> cases = {square_circle_hole(), l_shape_interior_segment(),
                                   ten_degree_corner(), letter_p_with_hole()};
  int missed = self_test(cases[0]);
  std::vector<Row> rows;
  for (const auto& g : cases) {
    rows.push_back(run_case(g, 0.0, 0.0));
    rows.push_back(run_case(g, 20.7, g.size_bound));
    rows.push_back(run_case(g, 30.0, g.size_bound));
    rows.push_back(run_case(g, 30.0, 0.0));
  }

  std::printf("\n%-20s %-16s %9s %9s %6s %9s %9s %8s %8s %s\n", "case", "mode", "idmesh", "CGAL",
              "ratio", "id min", "CGAL min", "id s", "CGAL s", "result");
  int failed = 0;
  for (const auto& r : rows) {
    double ratio = r.cgal_tris ? static_cast<double>(r.id_tris) / r.cgal_tris : 0.0;
    std::printf("%-20s %-16s %9zu %9zu %6.3f %9.3f %9.3f %8.3f %8.3f %s\n", r.pslg.c_str(),
                r.mode.c_str(), r.id_tris, r.cgal_tris, ratio, r.id_min, r.cgal_min, r.id_sec,
                r.cgal_sec, r.failures.empty() ? "ok" : "FAIL");
    if (r.cgal_gabriel_tris)
      std::printf("%-20s   (CGAL conforming Gabriel: %zu triangles; ratio not enforced)\n", "",
                  r.cgal_gabriel_tris);
    if (r.exempt) std::printf("%-20s   (%zu idmesh angles exempt at input corners < 60 deg)\n",
                              "", r.exempt);
    for (const auto& f : r.failures) std::printf("%-20s   FAIL: %s\n", "", f.c_str());
    if (!r.failures.empty()) ++failed;
  }
  if (missed) std::printf("\nself-test: %d deliberately broken meshes were NOT caught\n", missed);
  if (failed) std::printf("\n%d of %zu comparisons FAILED\n", failed, rows.size());
  if (failed || missed) return 1;
  std::printf("\nall %zu comparisons passed\n", rows.size());
  return 0;
}
