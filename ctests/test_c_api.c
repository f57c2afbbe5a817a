/* Tests of the idmesh C ABI using nothing but idmesh.h.
 *
 * Every mesh the library hands back is checked here independently of the library's own
 * validator: index ranges, counter-clockwise triangles (a sound filtered orientation test),
 * neighbour symmetry, that every subsegment is a triangle edge and that the subsegments of each
 * input segment form a chain between its endpoints, Euler's formula, the total area, and the
 * angle / area bounds that were asked for. Error paths must return the documented status, leave
 * out-parameters untouched and set a non-empty idm_last_error().
 *
 * Exit status 0 when every check passes; each failed check prints its line and reason. */
#define _POSIX_C_SOURCE 200809L

#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "idmesh.h"

static int g_failures = 0;
static int g_checks = 0;

#define CHECK(cond, ...)                                                  \
  do {                                                                    \
    ++g_checks;                                                           \
    if (!(cond)) {                                                        \
      ++g_failures;                                                       \
      fprintf(stderr, "FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);     \
      fprintf(stderr, __VA_ARGS__);                                       \
      fprintf(stderr, "\n");                                              \
    }                                                                     \
  } while (0)

/* Checks a status and, for failures, that a message explains it; for successes, that the
 * thread's message was cleared. */
#define CHECK_STATUS(call, expected)                                                         \
  do {                                                                                     \
    idm_status got_ = (call);                                                              \
    CHECK(got_ == (expected), "%s returned %d, expected %d (last error: \"%s\")", #call,  \
          (int)got_, (int)(expected), idm_last_error());                                   \
    if ((expected) != IDM_OK && (expected) != IDM_INCOMPLETE) {                            \
      CHECK(idm_last_error() != NULL && idm_last_error()[0] != '\0',                       \
            "%s failed without a message", #call);                                         \
    } else if ((expected) == IDM_OK) {                                                     \
      CHECK(idm_last_error() != NULL && idm_last_error()[0] == '\0',                       \
            "%s succeeded but left the message \"%s\"", #call, idm_last_error());          \
    }                                                                                      \
  } while (0)

/* ------------------------------------------------------------------------------------------ */
/* Geometry helpers.                                                                           */

/* Sign of the orientation determinant of (a, b, c), or 0 when floating point cannot certify
 * it. The error bound is the classical first-stage bound of adaptive orientation tests, so a
 * nonzero answer is always the exact sign. Meshes under test are quality meshes whose triangles
 * are far from degenerate, so "uncertain" is treated as a failure by the callers. */
static int orient_certified(const double *a, const double *b, const double *c) {
  const double eps = DBL_EPSILON * 0.5;
  const double bound = (3.0 + 16.0 * eps) * eps;
  double detleft = (a[0] - c[0]) * (b[1] - c[1]);
  double detright = (a[1] - c[1]) * (b[0] - c[0]);
  double det = detleft - detright;
  double detsum = fabs(detleft) + fabs(detright);
  if (det > bound * detsum) return 1;
  if (-det > bound * detsum) return -1;
  return 0;
}

static double tri_area(const double *a, const double *b, const double *c) {
  return 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
}

/* The angle at p between rays p->q and p->r, in degrees (atan2 is accurate for tiny angles). */
static double angle_deg(const double *p, const double *q, const double *r) {
  double ux = q[0] - p[0], uy = q[1] - p[1], vx = r[0] - p[0], vy = r[1] - p[1];
  return atan2(fabs(ux * vy - uy * vx), ux * vx + uy * vy) * (180.0 / 3.14159265358979323846);
}

static double dist(const double *a, const double *b) { return hypot(a[0] - b[0], a[1] - b[1]); }

static uint64_t edge_key(uint32_t a, uint32_t b) {
  return a < b ? ((uint64_t)a << 32) | b : ((uint64_t)b << 32) | a;
}

static int cmp_u64(const void *x, const void *y) {
  uint64_t a = *(const uint64_t *)x, b = *(const uint64_t *)y;
  return (a > b) - (a < b);
}

/* ------------------------------------------------------------------------------------------ */
/* A PSLG as the tests build it, plus what the mesh must satisfy.                               */

typedef struct {
  const double *xy;            /* 2 * np */
  size_t np;
  const int32_t *pmarkers;     /* np or NULL */
  const uint32_t *seg;         /* 2 * ns */
  size_t ns;
  const int32_t *smarkers;     /* ns; each distinct, so subsegments can be traced back */
  const double *holes;         /* 2 * nh */
  size_t nh;
  double domain_area;          /* exact area of the domain (input polygons with holes removed) */
  int genus;                   /* number of holes in the domain, for Euler's formula */
  double min_angle;            /* angle bound to check, 0 for none */
  double max_area;             /* area bound to check, 0 for none */
  int segments_are_boundary;   /* every segment bounds the domain (for Euler's formula) */
} case2d;

static void add_case_input(idm_mesher2d *m, const case2d *c) {
  CHECK_STATUS(idm_mesher2d_add_points(m, c->xy, c->np, c->pmarkers), IDM_OK);
  CHECK_STATUS(idm_mesher2d_add_segments(m, c->seg, c->ns, c->smarkers), IDM_OK);
  CHECK_STATUS(idm_mesher2d_add_holes(m, c->holes, c->nh), IDM_OK);
}

/* Everything the output must satisfy, checked from the getters alone. Returns the number of
 * triangles (0 when the mesh could not be read). */
static size_t check_mesh(const idm_mesher2d *m, const case2d *c, const char *name) {
  size_t nv = 0, nt = 0, ns = 0;
  CHECK_STATUS(idm_mesher2d_counts(m, &nv, &nt, &ns), IDM_OK);
  const double *xy = NULL;
  const uint32_t *tri = NULL, *nbr = NULL, *seg = NULL;
  const int32_t *vmark = NULL, *smark = NULL;
  size_t cnt = (size_t)-1;
  CHECK_STATUS(idm_mesher2d_vertices(m, &xy, &cnt), IDM_OK);
  CHECK(cnt == nv, "%s: vertices count %zu != counts() %zu", name, cnt, nv);
  cnt = (size_t)-1;
  CHECK_STATUS(idm_mesher2d_vertex_markers(m, &vmark, &cnt), IDM_OK);
  CHECK(cnt == nv, "%s: vertex markers count %zu != %zu", name, cnt, nv);
  cnt = (size_t)-1;
  CHECK_STATUS(idm_mesher2d_triangles(m, &tri, &cnt), IDM_OK);
  CHECK(cnt == nt, "%s: triangles count %zu != %zu", name, cnt, nt);
  cnt = (size_t)-1;
  CHECK_STATUS(idm_mesher2d_neighbors(m, &nbr, &cnt), IDM_OK);
  CHECK(cnt == nt, "%s: neighbors count %zu != %zu", name, cnt, nt);
  cnt = (size_t)-1;
  CHECK_STATUS(idm_mesher2d_segments(m, &seg, &smark, &cnt), IDM_OK);
  CHECK(cnt == ns, "%s: segments count %zu != %zu", name, cnt, ns);
  CHECK_STATUS(idm_mesher2d_validate(m), IDM_OK);
  if (g_failures) {
    /* Without consistent arrays the checks below would read out of bounds. */
    if (!xy || !tri || !nbr || !vmark || (ns && (!seg || !smark))) return 0;
  }
  CHECK(nv >= c->np, "%s: %zu vertices, fewer than the %zu input points", name, nv, c->np);
  CHECK(nt > 0, "%s: empty mesh", name);

  /* Input points keep their index and coordinates. */
  for (size_t i = 0; i < c->np && i < nv; ++i) {
    CHECK(xy[2 * i] == c->xy[2 * i] && xy[2 * i + 1] == c->xy[2 * i + 1],
          "%s: vertex %zu moved to (%.17g, %.17g)", name, i, xy[2 * i], xy[2 * i + 1]);
  }
  /* Input points keep a nonzero marker; as in Triangle, one whose marker is 0 (or not given)
   * takes the marker of a subsegment it ends, and stays 0 off segments. */
  for (size_t i = 0; i < c->np && i < nv; ++i) {
    int32_t given = c->pmarkers ? c->pmarkers[i] : 0;
    if (given != 0) {
      CHECK(vmark[i] == given, "%s: vertex %zu marker %d, given %d", name, i, vmark[i], given);
      continue;
    }
    int on_any = 0, matches = 0;
    for (size_t s = 0; s < ns; ++s) {
      if (seg[2 * s] != i && seg[2 * s + 1] != i) continue;
      on_any = 1;
      if (smark[s] == vmark[i]) matches = 1;
    }
    CHECK(on_any ? matches : vmark[i] == 0,
          "%s: vertex %zu (no marker given) has marker %d, not %s", name, i, vmark[i],
          on_any ? "one of its subsegments' markers" : "0");
  }

  /* Triangles: index range, certified CCW, area and angle bounds. */
  uint64_t *edges = malloc(sizeof(uint64_t) * 3 * (nt ? nt : 1));
  unsigned char *used = calloc(nv ? nv : 1, 1);
  if (!edges || !used) {
    fprintf(stderr, "out of memory\n");
    exit(2);
  }
  double area = 0.0, min_ang = 180.0, max_tri_area = 0.0;
  size_t bad_index = 0, not_ccw = 0, bad_angle = 0, bad_area = 0;
  for (size_t t = 0; t < nt; ++t) {
    const uint32_t *v = tri + 3 * t;
    if (v[0] >= nv || v[1] >= nv || v[2] >= nv) {
      ++bad_index;
      continue;
    }
    const double *a = xy + 2 * v[0], *b = xy + 2 * v[1], *p = xy + 2 * v[2];
    used[v[0]] = used[v[1]] = used[v[2]] = 1;
    if (orient_certified(a, b, p) != 1) ++not_ccw;
    double ar = tri_area(a, b, p);
    area += ar;
    if (ar > max_tri_area) max_tri_area = ar;
    /* The mesher decides "too large" with its own rounding; allow 1e-9 relative. */
    if (c->max_area > 0 && ar > c->max_area * (1.0 + 1e-9)) ++bad_area;
    double angs[3] = {angle_deg(a, b, p), angle_deg(b, p, a), angle_deg(p, a, b)};
    for (int k = 0; k < 3; ++k) {
      if (angs[k] < min_ang) min_ang = angs[k];
      /* The bound is given in degrees and turned into a trigonometric test inside the mesher:
       * allow a 1e-7 degree measurement slack (far below any real violation). */
      if (c->min_angle > 0 && angs[k] < c->min_angle - 1e-7) ++bad_angle;
    }
    for (int k = 0; k < 3; ++k) edges[3 * t + k] = edge_key(v[(k + 1) % 3], v[(k + 2) % 3]);
  }
  CHECK(bad_index == 0, "%s: %zu triangles with a vertex index >= %zu", name, bad_index, nv);
  CHECK(not_ccw == 0, "%s: %zu triangles not certified counter-clockwise", name, not_ccw);
  CHECK(bad_angle == 0, "%s: %zu angles below %.3f (min %.6f)", name, bad_angle, c->min_angle,
        min_ang);
  CHECK(bad_area == 0, "%s: %zu triangles above area %g (max %g)", name, bad_area, c->max_area,
        max_tri_area);
  CHECK(fabs(area - c->domain_area) <= 1e-9 * c->domain_area,
        "%s: total area %.17g, domain area %.17g", name, area, c->domain_area);

  /* Neighbours: symmetric, across the shared edge, and NONE exactly on unshared edges. */
  size_t bad_nbr = 0;
  for (size_t t = 0; t < nt && !bad_index; ++t) {
    for (int k = 0; k < 3; ++k) {
      uint32_t n = nbr[3 * t + k];
      if (n == UINT32_MAX) continue;
      if (n >= nt) {
        ++bad_nbr;
        continue;
      }
      uint64_t e = edges[3 * t + k];
      int back = 0;
      for (int j = 0; j < 3; ++j)
        if (nbr[3 * n + j] == t && edges[3 * n + j] == e) back = 1;
      if (!back) ++bad_nbr;
    }
  }
  CHECK(bad_nbr == 0, "%s: %zu neighbour entries not symmetric across their edge", name, bad_nbr);

  /* Edge set (each mesh edge once) to find subsegments in. */
  qsort(edges, 3 * nt, sizeof(uint64_t), cmp_u64);
  size_t n_boundary_edges = 0;
  for (size_t i = 0; i < 3 * nt;) {
    size_t j = i;
    while (j < 3 * nt && edges[j] == edges[i]) ++j;
    CHECK(j - i <= 2, "%s: edge shared by %zu triangles", name, j - i);
    if (j - i == 1) ++n_boundary_edges;
    i = j;
  }
  size_t missing = 0;
  for (size_t s = 0; s < ns; ++s) {
    uint64_t e = edge_key(seg[2 * s], seg[2 * s + 1]);
    if (!bsearch(&e, edges, 3 * nt, sizeof(uint64_t), cmp_u64)) ++missing;
  }
  CHECK(missing == 0, "%s: %zu subsegments are not edges of any triangle", name, missing);

  /* Each input segment is the union of the subsegments carrying its (distinct) marker: they
   * form a chain from one endpoint to the other with the same total length, and the Steiner
   * vertices on it inherit the marker. */
  unsigned *deg = calloc(nv ? nv : 1, sizeof(unsigned));
  unsigned char *on_seg = calloc(nv ? nv : 1, 1);
  if (!deg || !on_seg) exit(2);
  for (size_t k = 0; k < c->ns; ++k) {
    double len = 0.0;
    size_t pieces = 0;
    memset(deg, 0, sizeof(unsigned) * nv);
    for (size_t s = 0; s < ns; ++s) {
      if (smark[s] != c->smarkers[k]) continue;
      uint32_t a = seg[2 * s], b = seg[2 * s + 1];
      if (a >= nv || b >= nv) {
        CHECK(0, "%s: subsegment %zu has an index out of range", name, s);
        continue;
      }
      ++pieces;
      len += dist(xy + 2 * a, xy + 2 * b);
      ++deg[a];
      ++deg[b];
      on_seg[a] = on_seg[b] = 1;
      if (a >= c->np) CHECK(vmark[a] == c->smarkers[k], "%s: Steiner vertex %u marker", name, a);
      if (b >= c->np) CHECK(vmark[b] == c->smarkers[k], "%s: Steiner vertex %u marker", name, b);
    }
    uint32_t ea = c->seg[2 * k], eb = c->seg[2 * k + 1];
    double want = dist(c->xy + 2 * ea, c->xy + 2 * eb);
    CHECK(pieces > 0, "%s: input segment %zu has no subsegments", name, k);
    CHECK(fabs(len - want) <= 1e-12 * want, "%s: subsegments of segment %zu have length %.17g, "
          "expected %.17g", name, k, len, want);
    CHECK(deg[ea] == 1 && deg[eb] == 1, "%s: segment %zu's chain does not end at its endpoints",
          name, k);
    size_t odd = 0;
    for (size_t v = 0; v < nv; ++v)
      if (deg[v] > 2 || (deg[v] == 1 && v != ea && v != eb)) ++odd;
    CHECK(odd == 0, "%s: subsegments of segment %zu do not form a simple chain", name, k);
  }
  size_t stray = 0;
  for (size_t s = 0; s < ns; ++s) {
    int known = 0;
    for (size_t k = 0; k < c->ns; ++k)
      if (smark[s] == c->smarkers[k]) known = 1;
    if (!known) ++stray;
  }
  CHECK(stray == 0, "%s: %zu subsegments carry a marker no input segment has", name, stray);

  /* Euler's formula for a triangulated polygon with h holes, when every segment is on the
   * boundary: T = 2 Vi + Vb + 2h - 2, and the boundary edges are exactly the subsegments. */
  if (c->segments_are_boundary && !bad_index) {
    size_t vi = 0, vb = 0;
    for (size_t v = 0; v < nv; ++v) {
      if (!used[v]) continue;
      if (on_seg[v]) ++vb; else ++vi;
    }
    CHECK(nt == 2 * vi + vb + 2 * (size_t)c->genus - 2,
          "%s: Euler: %zu triangles, %zu interior and %zu boundary vertices, %d holes", name, nt,
          vi, vb, c->genus);
    CHECK(n_boundary_edges == ns, "%s: %zu boundary edges but %zu subsegments", name,
          n_boundary_edges, ns);
  }

  /* No triangle inside a hole: the hole seeds are not covered. */
  for (size_t h = 0; h < c->nh && !bad_index; ++h) {
    const double *q = c->holes + 2 * h;
    size_t covering = 0;
    for (size_t t = 0; t < nt; ++t) {
      const uint32_t *v = tri + 3 * t;
      const double *a = xy + 2 * v[0], *b = xy + 2 * v[1], *p = xy + 2 * v[2];
      if (orient_certified(a, b, q) >= 0 && orient_certified(b, p, q) >= 0 &&
          orient_certified(p, a, q) >= 0)
        ++covering;
    }
    CHECK(covering == 0, "%s: hole seed %zu is covered by %zu triangles", name, h, covering);
  }

  printf("  %-28s %6zu vertices %6zu triangles %5zu subsegments, min angle %7.3f, max area %.3g\n",
         name, nv, nt, ns, min_ang, max_tri_area);
  free(edges);
  free(used);
  free(deg);
  free(on_seg);
  return nt;
}

/* ------------------------------------------------------------------------------------------ */
/* The main test domain: a pentagon (corners of 90 and ~127 degrees) with a square hole.       */

static const double k_pent_xy[] = {0, 0, 4, 0, 4, 3, 2, 4, 0, 3, /* outer */
                                   1.5, 1, 2.5, 1, 2.5, 2, 1.5, 2 /* hole */};
static const int32_t k_pent_pmark[] = {100, 101, 102, 103, 104, 105, 106, 107, 108};
static const uint32_t k_pent_seg[] = {0, 1, 1, 2, 2, 3, 3, 4, 4, 0, 5, 6, 6, 7, 7, 8, 8, 5};
static const int32_t k_pent_smark[] = {10, 11, 12, 13, 14, 20, 21, 22, 23};
static const double k_pent_hole[] = {2.0, 1.5};

static case2d pentagon_case(double min_angle, double max_area) {
  case2d c = {k_pent_xy, 9, k_pent_pmark, k_pent_seg, 9, k_pent_smark, k_pent_hole, 1,
              14.0 - 1.0, 1, min_angle, max_area, 1};
  return c;
}

static void test_version_and_defaults(void) {
  const char *v = idm_version();
  CHECK(v != NULL && v[0] != '\0', "idm_version() is empty");
#ifdef IDMESH_EXPECTED_VERSION
  CHECK(v != NULL && strstr(v, IDMESH_EXPECTED_VERSION) != NULL, "idm_version() \"%s\" lacks %s",
        v ? v : "(null)", IDMESH_EXPECTED_VERSION);
#endif
  idm_options2d o;
  memset(&o, 0x5a, sizeof o);
  idm_options2d_default(&o);
  CHECK(o.min_angle == 0.0 && o.max_area == 0.0, "default angle/area %g %g", o.min_angle,
        o.max_area);
  CHECK(o.region_max_area == 0 && o.region_attributes == 0 && o.convex_hull == 0,
        "default region/hull flags");
  CHECK(o.off_centers == 1 && o.split_crossings == 0 && o.no_boundary_steiner == 0,
        "default off_centers %d split %d Y %d", o.off_centers, o.split_crossings,
        o.no_boundary_steiner);
  CHECK(o.max_steiner == -1, "default max_steiner %lld", (long long)o.max_steiner);
  idm_options2d_default(NULL); /* must be a no-op */
  idm_mesher2d_free(NULL);     /* must be a no-op */
  CHECK(idm_last_error() != NULL, "idm_last_error() returned NULL");
}

/* Conforming Delaunay without quality bounds, then the same domain with angle and area
 * bounds on one handle (set_options + refine again). */
static void test_pentagon_with_hole(void) {
  idm_mesher2d *m = NULL;
  CHECK_STATUS(idm_mesher2d_new(&m), IDM_OK);
  if (!m) return;
  case2d c = pentagon_case(0, 0);
  add_case_input(m, &c);
  idm_status st = idm_mesher2d_refine(m);
  CHECK(st == IDM_OK, "refine (conforming) returned %d: %s", (int)st, idm_last_error());
  if (st == IDM_OK) check_mesh(m, &c, "pentagon conforming");

  idm_options2d o;
  idm_options2d_default(&o);
  o.min_angle = 28.0;
  o.max_area = 0.05;
  CHECK_STATUS(idm_mesher2d_set_options(m, &o), IDM_OK);
  st = idm_mesher2d_refine(m);
  CHECK(st == IDM_OK, "refine (quality) returned %d: %s", (int)st, idm_last_error());
  if (st == IDM_OK) {
    c = pentagon_case(28.0, 0.05);
    size_t nt = check_mesh(m, &c, "pentagon q28 a0.05");
    CHECK((double)nt * 0.05 >= c.domain_area, "too few triangles (%zu) for the area bound", nt);
  }

  /* Circumcenters instead of off-centers must honour the same bounds. */
  o.off_centers = 0;
  o.min_angle = 33.0;
  o.max_area = 0;
  CHECK_STATUS(idm_mesher2d_set_options(m, &o), IDM_OK);
  st = idm_mesher2d_refine(m);
  CHECK(st == IDM_OK, "refine (q33, circumcenters) returned %d: %s", (int)st, idm_last_error());
  if (st == IDM_OK) {
    c = pentagon_case(33.0, 0);
    check_mesh(m, &c, "pentagon q33 circumcenters");
  }
  idm_mesher2d_free(m);
}

/* A unit square cut in two by an interior segment, with a region seed on each side: region
 * attributes and a regional area bound on the left half only. */
static void test_regions(void) {
  static const double xy[] = {0, 0, 0.5, 0, 1, 0, 1, 1, 0.5, 1, 0, 1};
  static const uint32_t seg[] = {0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 0, 1, 4};
  static const int32_t smark[] = {1, 2, 3, 4, 5, 6, 7};
  static const double rxy[] = {0.25, 0.5, 0.75, 0.5};
  static const double rattr[] = {1.5, 2.5};
  static const double rarea[] = {0.002, 0.0};
  idm_mesher2d *m = NULL;
  CHECK_STATUS(idm_mesher2d_new(&m), IDM_OK);
  if (!m) return;
  CHECK_STATUS(idm_mesher2d_add_points(m, xy, 6, NULL), IDM_OK);
  CHECK_STATUS(idm_mesher2d_add_segments(m, seg, 7, smark), IDM_OK);
  CHECK_STATUS(idm_mesher2d_add_regions(m, rxy, rattr, rarea, 2), IDM_OK);
  idm_options2d o;
  idm_options2d_default(&o);
  o.min_angle = 25.0;
  o.region_attributes = 1;
  o.region_max_area = 1;
  CHECK_STATUS(idm_mesher2d_set_options(m, &o), IDM_OK);
  idm_status st = idm_mesher2d_refine(m);
  CHECK(st == IDM_OK, "refine (regions) returned %d: %s", (int)st, idm_last_error());
  if (st == IDM_OK) {
    /* Not "segments_are_boundary": segment 6 is interior, so no Euler check. */
    case2d c = {xy, 6, NULL, seg, 7, smark, NULL, 0, 1.0, 0, 25.0, 0, 0};
    size_t nt = check_mesh(m, &c, "square with two regions");
    const double *attr = NULL, *vxy = NULL;
    const uint32_t *tri = NULL;
    size_t na = 0, nv = 0, nt2 = 0;
    CHECK_STATUS(idm_mesher2d_triangle_attributes(m, &attr, &na), IDM_OK);
    CHECK_STATUS(idm_mesher2d_vertices(m, &vxy, &nv), IDM_OK);
    CHECK_STATUS(idm_mesher2d_triangles(m, &tri, &nt2), IDM_OK);
    CHECK(na == nt && nt2 == nt, "attributes count %zu, triangles %zu", na, nt);
    size_t left = 0, right = 0, wrong = 0, big = 0;
    double right_max = 0.0;
    for (size_t t = 0; attr && tri && vxy && t < na && t < nt2; ++t) {
      const double *a = vxy + 2 * tri[3 * t], *b = vxy + 2 * tri[3 * t + 1],
                   *p = vxy + 2 * tri[3 * t + 2];
      double cx = (a[0] + b[0] + p[0]) / 3.0;
      if (cx < 0.5) {
        ++left;
        if (attr[t] != 1.5) ++wrong;
        if (tri_area(a, b, p) > 0.002 * (1 + 1e-9)) ++big;
      } else {
        ++right;
        if (attr[t] != 2.5) ++wrong;
        if (tri_area(a, b, p) > right_max) right_max = tri_area(a, b, p);
      }
    }
    CHECK(wrong == 0, "%zu triangles carry the other region's attribute", wrong);
    CHECK(big == 0, "%zu left triangles exceed the regional area bound", big);
    CHECK(left >= 0.5 / 0.002, "left half has %zu triangles, needs >= 250", left);
    CHECK(left > right, "regional bound did not refine the left half (%zu vs %zu)", left, right);
    CHECK(right_max > 0.002, "the left region's area bound leaked into the right region (largest "
          "right triangle %g)", right_max);
  }

  /* Without region_attributes the attribute array is empty. */
  o.region_attributes = 0;
  CHECK_STATUS(idm_mesher2d_set_options(m, &o), IDM_OK);
  st = idm_mesher2d_refine(m);
  CHECK(st == IDM_OK, "refine (regions, no attributes) returned %d", (int)st);
  if (st == IDM_OK) {
    const double *attr = NULL;
    size_t na = 99;
    CHECK_STATUS(idm_mesher2d_triangle_attributes(m, &attr, &na), IDM_OK);
    CHECK(na == 0, "attributes count %zu without region_attributes", na);
  }
  idm_mesher2d_free(m);
}

/* ------------------------------------------------------------------------------------------ */
/* The user sizing callback.                                                                   */

typedef struct {
  uint32_t magic;
  size_t calls;
  size_t not_ccw;
  size_t bad_area_arg;
} sizing_state;

/* "Too large" left of x = 0.5 above a small area; computed from the corners only so the test
 * can re-evaluate it on the output with the very same arithmetic. */
static int sizing_rule(const double *a, const double *b, const double *c) {
  double cx = (a[0] + b[0] + c[0]) / 3.0;
  return cx < 0.5 && fabs(tri_area(a, b, c)) > 0.001;
}

static int32_t sizing_cb(void *user, const double *a, const double *b, const double *c,
                         double area) {
  sizing_state *s = (sizing_state *)user;
  if (!s || s->magic != 0xC0FFEEu) return 0; /* the test fails on calls == 0 below */
  ++s->calls;
  if (orient_certified(a, b, c) != 1) ++s->not_ccw;
  double mine = tri_area(a, b, c);
  if (!(fabs(area - mine) <= 1e-9 * fabs(mine))) ++s->bad_area_arg;
  return sizing_rule(a, b, c);
}

static void test_sizing_callback(void) {
  static const double xy[] = {0, 0, 1, 0, 1, 1, 0, 1};
  static const uint32_t seg[] = {0, 1, 1, 2, 2, 3, 3, 0};
  static const int32_t smark[] = {1, 2, 3, 4};
  sizing_state s = {0xC0FFEEu, 0, 0, 0};
  idm_mesher2d *m = NULL;
  CHECK_STATUS(idm_mesher2d_new(&m), IDM_OK);
  if (!m) return;
  CHECK_STATUS(idm_mesher2d_add_points(m, xy, 4, NULL), IDM_OK);
  CHECK_STATUS(idm_mesher2d_add_segments(m, seg, 4, smark), IDM_OK);
  CHECK_STATUS(idm_mesher2d_set_sizing(m, sizing_cb, &s), IDM_OK);
  idm_options2d o;
  idm_options2d_default(&o);
  o.min_angle = 20.0;
  CHECK_STATUS(idm_mesher2d_set_options(m, &o), IDM_OK);
  idm_status st = idm_mesher2d_refine(m);
  CHECK(st == IDM_OK, "refine (sizing) returned %d: %s", (int)st, idm_last_error());
  CHECK(s.calls > 0, "the sizing callback was never called");
  CHECK(s.not_ccw == 0, "%zu callback triangles not counter-clockwise", s.not_ccw);
  CHECK(s.bad_area_arg == 0, "%zu callback calls with a wrong area", s.bad_area_arg);
  if (st == IDM_OK) {
    case2d c = {xy, 4, NULL, seg, 4, smark, NULL, 0, 1.0, 0, 20.0, 0, 1};
    check_mesh(m, &c, "square with sizing callback");
    const double *vxy = NULL;
    const uint32_t *tri = NULL;
    size_t nv = 0, nt = 0, unsuitable = 0, left = 0;
    CHECK_STATUS(idm_mesher2d_vertices(m, &vxy, &nv), IDM_OK);
    CHECK_STATUS(idm_mesher2d_triangles(m, &tri, &nt), IDM_OK);
    for (size_t t = 0; vxy && tri && t < nt; ++t) {
      const double *a = vxy + 2 * tri[3 * t], *b = vxy + 2 * tri[3 * t + 1],
                   *p = vxy + 2 * tri[3 * t + 2];
      if (sizing_rule(a, b, p)) ++unsuitable;
      if ((a[0] + b[0] + p[0]) / 3.0 < 0.5) ++left;
    }
    CHECK(unsuitable == 0, "%zu output triangles still fail the sizing rule", unsuitable);
    CHECK(left > nt - left, "the callback did not refine the left half (%zu of %zu)", left, nt);
  }

  /* Clearing the callback: the coarse mesh comes back and the callback is not called again. */
  size_t before = s.calls;
  CHECK_STATUS(idm_mesher2d_set_sizing(m, NULL, NULL), IDM_OK);
  st = idm_mesher2d_refine(m);
  CHECK(st == IDM_OK, "refine (sizing cleared) returned %d", (int)st);
  CHECK(s.calls == before, "cleared callback was called %zu more times", s.calls - before);
  size_t nv = 0, nt = 0, ns = 0;
  if (st == IDM_OK) {
    CHECK_STATUS(idm_mesher2d_counts(m, &nv, &nt, &ns), IDM_OK);
    CHECK(nt < 100, "without the callback a 20-degree unit square needs few triangles, got %zu",
          nt);
  }
  idm_mesher2d_free(m);
}

/* The Steiner cap stops refinement early with IDM_INCOMPLETE and a readable, valid mesh. */
static void test_steiner_cap(void) {
  idm_mesher2d *m = NULL;
  CHECK_STATUS(idm_mesher2d_new(&m), IDM_OK);
  if (!m) return;
  case2d c = pentagon_case(0, 0);
  add_case_input(m, &c);
  idm_options2d o;
  idm_options2d_default(&o);
  o.min_angle = 30.0;
  o.max_area = 1e-4;
  o.max_steiner = 10;
  CHECK_STATUS(idm_mesher2d_set_options(m, &o), IDM_OK);
  idm_status st = idm_mesher2d_refine(m);
  CHECK(st == IDM_INCOMPLETE, "refine with max_steiner=10 returned %d (%s), expected "
        "IDM_INCOMPLETE", (int)st, idm_last_error());
  if (st == IDM_INCOMPLETE) {
    const uint32_t *tri = NULL;
    size_t nt = 0, nv = 0, steiner = 0;
    const double *xy = NULL;
    CHECK_STATUS(idm_mesher2d_vertices(m, &xy, &nv), IDM_OK);
    CHECK_STATUS(idm_mesher2d_triangles(m, &tri, &nt), IDM_OK);
    unsigned char *seen = calloc(nv + 1, 1);
    if (!seen) exit(2);
    for (size_t i = 0; tri && i < 3 * nt; ++i) {
      if (tri[i] < nv && tri[i] >= c.np && !seen[tri[i]]) ++steiner;
      if (tri[i] < nv) seen[tri[i]] = 1;
    }
    free(seen);
    /* The cap is checked before each triangle split; the segment splits one triangle split
     * triggers always finish, so a few points beyond the cap are allowed. */
    CHECK(steiner >= 10 && steiner <= 100, "%zu Steiner vertices in the mesh with a cap of 10",
          steiner);
    check_mesh(m, &c, "pentagon capped at 10 Steiner");
  }
  idm_mesher2d_free(m);
}

/* ------------------------------------------------------------------------------------------ */
/* Error paths.                                                                                */

static void expect_message_mentions(const char *what, const char *needle) {
  const char *msg = idm_last_error();
  CHECK(msg && strstr(msg, needle) != NULL, "%s: message \"%s\" does not mention \"%s\"", what,
        msg ? msg : "(null)", needle);
}

/* Meshes a small PSLG that must be rejected with `expected`; returns after checking that the
 * getters still report no mesh and leave out-parameters alone. */
static void expect_refine_error(const char *what, const double *xy, size_t np,
                                const uint32_t *seg, size_t ns, const double *holes, size_t nh,
                                idm_status expected, const char *needle) {
  idm_mesher2d *m = NULL;
  CHECK_STATUS(idm_mesher2d_new(&m), IDM_OK);
  if (!m) return;
  /* The library may reject an item when it is added or only at refine: the first failure
   * must be the expected one. */
  idm_status st = idm_mesher2d_add_points(m, xy, np, NULL);
  if (st == IDM_OK) st = idm_mesher2d_add_segments(m, seg, ns, NULL);
  if (st == IDM_OK) st = idm_mesher2d_add_holes(m, holes, nh);
  if (st == IDM_OK) st = idm_mesher2d_refine(m);
  CHECK(st == expected, "%s: got status %d, expected %d (%s)", what, (int)st, (int)expected,
        idm_last_error());
  CHECK(idm_last_error()[0] != '\0', "%s: no message", what);
  if (needle) expect_message_mentions(what, needle);
  size_t sentinel = 12345;
  CHECK_STATUS(idm_mesher2d_counts(m, &sentinel, &sentinel, &sentinel), IDM_ERR_NO_MESH);
  CHECK(sentinel == 12345, "%s: counts wrote an out-parameter on failure", what);
  idm_mesher2d_free(m);
}

static void test_errors(void) {
  /* NULL handles and NULL required pointers. */
  CHECK_STATUS(idm_mesher2d_new(NULL), IDM_ERR_NULL_POINTER);
  static const double xy[] = {0, 0, 1, 0, 1, 1, 0, 1};
  static const uint32_t seg[] = {0, 1, 1, 2, 2, 3, 3, 0};
  CHECK_STATUS(idm_mesher2d_add_points(NULL, xy, 4, NULL), IDM_ERR_NULL_POINTER);
  CHECK_STATUS(idm_mesher2d_refine(NULL), IDM_ERR_NULL_POINTER);
  CHECK_STATUS(idm_mesher2d_validate(NULL), IDM_ERR_NULL_POINTER);
  size_t a = 7, b = 7, c = 7;
  CHECK_STATUS(idm_mesher2d_counts(NULL, &a, &b, &c), IDM_ERR_NULL_POINTER);
  CHECK(a == 7 && b == 7 && c == 7, "counts(NULL) wrote out-parameters");

  idm_mesher2d *m = NULL;
  CHECK_STATUS(idm_mesher2d_new(&m), IDM_OK);
  if (!m) return;
  CHECK_STATUS(idm_mesher2d_add_points(m, NULL, 4, NULL), IDM_ERR_NULL_POINTER);
  CHECK_STATUS(idm_mesher2d_add_segments(m, NULL, 4, NULL), IDM_ERR_NULL_POINTER);
  CHECK_STATUS(idm_mesher2d_add_holes(m, NULL, 1), IDM_ERR_NULL_POINTER);
  CHECK_STATUS(idm_mesher2d_add_regions(m, NULL, NULL, NULL, 1), IDM_ERR_NULL_POINTER);
  CHECK_STATUS(idm_mesher2d_add_regions(m, xy, NULL, NULL, 1), IDM_ERR_NULL_POINTER);
  CHECK_STATUS(idm_mesher2d_set_options(m, NULL), IDM_ERR_NULL_POINTER);
  CHECK_STATUS(idm_mesher2d_counts(m, NULL, NULL, NULL), IDM_ERR_NO_MESH);
  /* The message survives reads: idm_last_error() itself is not an idm_ call that resets it. */
  const char *first = idm_last_error();
  CHECK(first[0] != '\0' && strcmp(first, idm_last_error()) == 0, "message changed on re-read");

  /* A count whose byte size overflows size_t is rejected before anything is read. */
  CHECK_STATUS(idm_mesher2d_add_points(m, xy, SIZE_MAX / 2 + 1, NULL), IDM_ERR_INVALID_ARGUMENT);
  CHECK_STATUS(idm_mesher2d_add_segments(m, seg, SIZE_MAX / 2 + 1, NULL),
               IDM_ERR_INVALID_ARGUMENT);
  CHECK_STATUS(idm_mesher2d_add_holes(m, xy, SIZE_MAX / 2 + 1), IDM_ERR_INVALID_ARGUMENT);

  /* Getters before any refine: IDM_ERR_NO_MESH and untouched out-parameters. */
  const double *vp = (const double *)xy;
  const uint32_t *tp = seg;
  size_t n = 4242;
  CHECK_STATUS(idm_mesher2d_vertices(m, &vp, &n), IDM_ERR_NO_MESH);
  CHECK(vp == xy && n == 4242, "vertices() wrote out-parameters on failure");
  CHECK_STATUS(idm_mesher2d_triangles(m, &tp, &n), IDM_ERR_NO_MESH);
  CHECK(tp == seg && n == 4242, "triangles() wrote out-parameters on failure");
  CHECK_STATUS(idm_mesher2d_validate(m), IDM_ERR_NO_MESH);

  /* NULL with count 0 is an empty array, not an error. */
  CHECK_STATUS(idm_mesher2d_add_points(m, NULL, 0, NULL), IDM_OK);
  CHECK_STATUS(idm_mesher2d_add_holes(m, NULL, 0), IDM_OK);
  CHECK_STATUS(idm_mesher2d_add_points(m, xy, 4, NULL), IDM_OK);
  CHECK_STATUS(idm_mesher2d_add_segments(m, seg, 4, NULL), IDM_OK);
  CHECK_STATUS(idm_mesher2d_set_sizing(m, NULL, NULL), IDM_OK);

  /* An out-of-range option value is rejected (at set_options or at refine) with a message. */
  idm_options2d o;
  idm_options2d_default(&o);
  o.min_angle = 60.0;
  idm_status st = idm_mesher2d_set_options(m, &o);
  if (st == IDM_OK) st = idm_mesher2d_refine(m);
  CHECK(st == IDM_ERR_INVALID_ARGUMENT, "min_angle=60 gave %d, expected IDM_ERR_INVALID_ARGUMENT",
        (int)st);
  CHECK(idm_last_error()[0] != '\0', "min_angle=60: no message");
  expect_message_mentions("min_angle=60", "angle");

  /* The handle recovers: valid options mesh the square, and the message is cleared. */
  idm_options2d_default(&o);
  CHECK_STATUS(idm_mesher2d_set_options(m, &o), IDM_OK);
  CHECK_STATUS(idm_mesher2d_refine(m), IDM_OK);
  size_t nv = 0, nt = 0, ns = 0;
  CHECK_STATUS(idm_mesher2d_counts(m, &nv, &nt, &ns), IDM_OK);
  CHECK(nv == 4 && nt == 2 && ns == 4, "unit square: %zu vertices %zu triangles %zu segments", nv,
        nt, ns);
  /* Unwanted counts may be NULL. */
  size_t only_t = 0;
  CHECK_STATUS(idm_mesher2d_counts(m, NULL, &only_t, NULL), IDM_OK);
  CHECK(only_t == nt, "counts with NULL out-pointers gave %zu triangles", only_t);
  CHECK_STATUS(idm_mesher2d_validate(m), IDM_OK);
  idm_mesher2d_free(m);

  /* Invalid PSLGs: each names the offending item. */
  static const uint32_t seg_oob[] = {0, 1, 1, 2, 2, 17};
  expect_refine_error("segment out of range", xy, 4, seg_oob, 3, NULL, 0,
                      IDM_ERR_INVALID_INPUT, "17");
  static const double dup_xy[] = {0, 0, 1, 0, 1, 1, 1, 0};
  expect_refine_error("duplicate point", dup_xy, 4, NULL, 0, NULL, 0, IDM_ERR_INVALID_INPUT,
                      "3");
  static const uint32_t seg_cross[] = {0, 2, 1, 3};
  expect_refine_error("crossing segments", xy, 4, seg_cross, 2, NULL, 0, IDM_ERR_INVALID_INPUT,
                      "segment");
  expect_refine_error("too few points", xy, 2, NULL, 0, NULL, 0, IDM_ERR_INVALID_INPUT, "2");
  static const double line_xy[] = {0, 0, 1, 1, 2, 2, 3, 3};
  expect_refine_error("collinear points", line_xy, 4, NULL, 0, NULL, 0, IDM_ERR_INVALID_INPUT,
                      NULL);
  static const double nan_xy[] = {0, 0, 1, 0, NAN, 1, 0, 1};
  expect_refine_error("NaN point", nan_xy, 4, NULL, 0, NULL, 0, IDM_ERR_INVALID_INPUT, "2");
  static const uint32_t seg_zero[] = {0, 1, 1, 1};
  expect_refine_error("zero-length segment", xy, 4, seg_zero, 2, NULL, 0, IDM_ERR_INVALID_INPUT,
                      "1");
  static const double hole_out[] = {5.0, 5.0};
  expect_refine_error("hole outside", xy, 4, seg, 4, hole_out, 1, IDM_ERR_INVALID_INPUT,
                      "hole");
}

/* ------------------------------------------------------------------------------------------ */
/* Threads: distinct handles on distinct threads, and a per-thread error message.              */

typedef struct {
  double scale;
  size_t triangles;
  int ok;
  int saw_clean_error;
} thread_job;

static void *thread_main(void *arg) {
  thread_job *job = (thread_job *)arg;
  /* The main thread's pending error must not be visible here. */
  job->saw_clean_error = idm_last_error() != NULL && idm_last_error()[0] == '\0';
  double s = job->scale;
  double xy[] = {0, 0, s, 0, s, s, 0, s};
  static const uint32_t seg[] = {0, 1, 1, 2, 2, 3, 3, 0};
  idm_mesher2d *m = NULL;
  if (idm_mesher2d_new(&m) != IDM_OK) return NULL;
  idm_options2d o;
  idm_options2d_default(&o);
  o.min_angle = 30.0;
  o.max_area = s * s / 400.0;
  size_t nv = 0, ns = 0;
  job->ok = idm_mesher2d_add_points(m, xy, 4, NULL) == IDM_OK &&
            idm_mesher2d_add_segments(m, seg, 4, NULL) == IDM_OK &&
            idm_mesher2d_set_options(m, &o) == IDM_OK && idm_mesher2d_refine(m) == IDM_OK &&
            idm_mesher2d_validate(m) == IDM_OK &&
            idm_mesher2d_counts(m, &nv, &job->triangles, &ns) == IDM_OK;
  idm_mesher2d_free(m);
  return NULL;
}

static void test_threads(void) {
  CHECK_STATUS(idm_mesher2d_new(NULL), IDM_ERR_NULL_POINTER); /* leave an error pending here */
  char before[512];
  snprintf(before, sizeof before, "%s", idm_last_error());
  thread_job jobs[2] = {{1.0, 0, 0, 0}, {1024.0, 0, 0, 0}};
  pthread_t th[2];
  int started[2] = {0, 0};
  for (int i = 0; i < 2; ++i) started[i] = pthread_create(&th[i], NULL, thread_main, &jobs[i]) == 0;
  for (int i = 0; i < 2; ++i)
    if (started[i]) pthread_join(th[i], NULL);
  for (int i = 0; i < 2; ++i) {
    CHECK(started[i], "thread %d did not start", i);
    CHECK(jobs[i].ok, "thread %d: meshing failed", i);
    CHECK(jobs[i].saw_clean_error, "thread %d saw another thread's error message", i);
    CHECK(jobs[i].triangles >= 400, "thread %d: %zu triangles for area bound 1/400", i,
          jobs[i].triangles);
  }
  /* Same shape scaled by a power of two, so every floating-point operation scales exactly:
   * a deterministic mesher must produce the same triangle count. */
  CHECK(jobs[0].triangles == jobs[1].triangles, "scaled squares: %zu vs %zu triangles",
        jobs[0].triangles, jobs[1].triangles);
  CHECK(strcmp(before, idm_last_error()) == 0, "this thread's message changed to \"%s\"",
        idm_last_error());
}

int main(void) {
  printf("idmesh C API test, library version %s\n", idm_version());
  test_version_and_defaults();
  test_errors();
  test_pentagon_with_hole();
  test_regions();
  test_sizing_callback();
  test_steiner_cap();
  test_threads();
  if (g_failures) {
    printf("FAILED: %d of %d checks\n", g_failures, g_checks);
    return 1;
  }
  printf("OK: %d checks passed\n", g_checks);
  return 0;
}
