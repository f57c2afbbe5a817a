/*
 * A C client of compat/triangle/triangle.h written as Triangle's users write one: REAL, VOID
 * and ANSI_DECLARATORS defined before the include, a triangulateio zeroed by hand, outputs
 * freed with trifree. It meshes a square with a hole, an internal segment and two regions in
 * 1-based and 0-based numbering, with two point attributes linear in x and y (which must come
 * out linear at every vertex, Steiner points included, as Triangle interpolates them), remeshes a mesh with -r (T lines: the given triangles, their
 * attribute and area bound), and prints each input and mesh (read by
 * triangle_compare.py, which meshes the same input with Triangle itself and compares), then
 * feeds bad input and checks that each call returns with empty outputs and a message, and that
 * the next input still meshes. Exit status 0 when every check here passed.
 */
#define REAL double
#define VOID void
#define ANSI_DECLARATORS
#include "triangle.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures = 0;

#define CHECK(cond, ...)                                  \
  do {                                                    \
    if (!(cond)) {                                        \
      fprintf(stderr, "FAIL %s:%d: ", __FILE__, __LINE__); \
      fprintf(stderr, __VA_ARGS__);                       \
      fprintf(stderr, "\n");                              \
      failures++;                                         \
    }                                                     \
  } while (0)

static void clear(struct triangulateio *io) { memset(io, 0, sizeof *io); }

static void free_out(struct triangulateio *out) {
  trifree((VOID *)out->pointlist);
  trifree((VOID *)out->pointattributelist);
  trifree((VOID *)out->pointmarkerlist);
  trifree((VOID *)out->trianglelist);
  trifree((VOID *)out->triangleattributelist);
  trifree((VOID *)out->neighborlist);
  trifree((VOID *)out->segmentlist);
  trifree((VOID *)out->segmentmarkerlist);
  trifree((VOID *)out->edgelist);
  trifree((VOID *)out->edgemarkerlist);
  /* holelist and regionlist are in's arrays, as in Triangle: not freed here. */
  clear(out);
}

/* The square [0,4]^2 with a square hole [1.5,2.5]^2 and a vertical internal segment x = 1
 * splitting it into two regions; `first` is the number of the first point. */
static REAL points[] = {0, 0, 4, 0, 4, 4, 0, 4, 1.5, 1.5, 2.5, 1.5, 2.5, 2.5, 1.5, 2.5, 1, 0, 1, 4};
static int point_markers[] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
static int segments0[] = {0, 8, 8, 1, 1, 2, 2, 9, 9, 3, 3, 0, 4, 5, 5, 6, 6, 7, 7, 4, 8, 9};
static int segment_markers[] = {2, 2, 3, 4, 4, 5, 6, 6, 6, 6, 7};
static REAL holes[] = {2, 2};
/* Two point attributes, linear in x and y: Triangle interpolates them linearly at new vertices,
 * so every output vertex must carry these functions of its coordinates (to rounding). */
#define ATTR0(x, y) (2.0 * (x) - 3.0 * (y) + 1.0)
#define ATTR1(x, y) (0.5 * (y) - 7.0)

/* Counts the output vertices whose attributes are not the linear functions above (relative
 * error above 1e-12), or all of them when there are not 2 per vertex. */
static int bad_attributes(const struct triangulateio *out) {
  int i, bad = 0;
  if (out->numberofpointattributes != 2 || out->pointattributelist == NULL)
    return out->numberofpoints > 0 ? out->numberofpoints : 1;
  for (i = 0; i < out->numberofpoints; i++) {
    double x = out->pointlist[2 * i], y = out->pointlist[2 * i + 1];
    double want[2], *got = &out->pointattributelist[2 * i];
    int k;
    want[0] = ATTR0(x, y);
    want[1] = ATTR1(x, y);
    for (k = 0; k < 2; k++)
      if (fabs(got[k] - want[k]) > 1e-12 * (1.0 + fabs(want[k]))) {
        bad++;
        break;
      }
  }
  return bad;
}

/* Gives `in`'s points the two linear attributes. */
static void add_attributes(struct triangulateio *in) {
  static REAL values[64];
  int i;
  for (i = 0; i < in->numberofpoints && i < 32; i++) {
    values[2 * i] = ATTR0(in->pointlist[2 * i], in->pointlist[2 * i + 1]);
    values[2 * i + 1] = ATTR1(in->pointlist[2 * i], in->pointlist[2 * i + 1]);
  }
  in->numberofpointattributes = 2;
  in->pointattributelist = values;
}
static REAL regions[] = {0.5, 2, 1.0, 0.05, 3, 3.5, 2.0, -1};

static void fill_domain(struct triangulateio *in, int first, int *segments) {
  int i;
  clear(in);
  in->numberofpoints = 10;
  in->pointlist = points;
  in->pointmarkerlist = point_markers;
  in->numberofsegments = 11;
  for (i = 0; i < 22; i++) segments[i] = segments0[i] + first;
  in->segmentlist = segments;
  in->segmentmarkerlist = segment_markers;
  in->numberofholes = 1;
  in->holelist = holes;
  in->numberofregions = 2;
  in->regionlist = regions;
}

/* Prints the input and the output for triangle_compare.py (all indices 0-based). */
static void dump(const char *sw, const struct triangulateio *in, const struct triangulateio *out,
                 int first) {
  int i;
  printf("case %s\n", sw);
  for (i = 0; i < in->numberofpoints; i++)
    printf("P %.17g %.17g %d\n", in->pointlist[2 * i], in->pointlist[2 * i + 1],
           in->pointmarkerlist[i]);
  for (i = 0; i < in->numberofpoints && in->numberofpointattributes == 2; i++)
    printf("A %.17g %.17g\n", in->pointattributelist[2 * i], in->pointattributelist[2 * i + 1]);
  for (i = 0; i < out->numberofpoints && out->numberofpointattributes == 2; i++)
    printf("a %.17g %.17g\n", out->pointattributelist[2 * i], out->pointattributelist[2 * i + 1]);
  for (i = 0; i < in->numberofsegments; i++)
    printf("G %d %d %d\n", in->segmentlist[2 * i] - first, in->segmentlist[2 * i + 1] - first,
           in->segmentmarkerlist[i]);
  for (i = 0; i < in->numberofholes; i++)
    printf("H %.17g %.17g\n", in->holelist[2 * i], in->holelist[2 * i + 1]);
  for (i = 0; i < in->numberofregions; i++)
    printf("R %.17g %.17g %.17g %.17g\n", in->regionlist[4 * i], in->regionlist[4 * i + 1],
           in->regionlist[4 * i + 2], in->regionlist[4 * i + 3]);
  for (i = 0; in->trianglelist != NULL && i < in->numberoftriangles; i++)
    printf("T %d %d %d %.17g %.17g\n", in->trianglelist[3 * i] - first,
           in->trianglelist[3 * i + 1] - first, in->trianglelist[3 * i + 2] - first,
           in->triangleattributelist[i], in->trianglearealist[i]);
  for (i = 0; i < out->numberofpoints; i++)
    printf("p %.17g %.17g %d\n", out->pointlist[2 * i], out->pointlist[2 * i + 1],
           out->pointmarkerlist[i]);
  for (i = 0; i < out->numberoftriangles; i++)
    printf("t %d %d %d %.17g\n", out->trianglelist[3 * i] - first,
           out->trianglelist[3 * i + 1] - first, out->trianglelist[3 * i + 2] - first,
           out->triangleattributelist[i]);
  for (i = 0; i < out->numberoftriangles; i++) {
    int k;
    printf("n");
    for (k = 0; k < 3; k++) {
      int n = out->neighborlist[3 * i + k];
      printf(" %d", n < 0 ? -1 : n - first);
    }
    printf("\n");
  }
  for (i = 0; i < out->numberofsegments; i++)
    printf("s %d %d %d\n", out->segmentlist[2 * i] - first, out->segmentlist[2 * i + 1] - first,
           out->segmentmarkerlist[i]);
  for (i = 0; i < out->numberofedges; i++)
    printf("e %d %d %d\n", out->edgelist[2 * i] - first, out->edgelist[2 * i + 1] - first,
           out->edgemarkerlist[i]);
  printf("end\n");
}

/* Meshes the domain with `sw` (Triangle's library switches) and dumps the result. */
static void mesh_domain(const char *sw, int first) {
  struct triangulateio in, out, vor;
  int segments[22];
  char switches[64];
  fill_domain(&in, first, segments);
  add_attributes(&in);
  clear(&out);
  clear(&vor);
  snprintf(switches, sizeof switches, "%s", sw);
  triangulate(switches, &in, &out, &vor);
  CHECK(strcmp(idm_last_error(), "") == 0, "%s: %s", sw, idm_last_error());
  CHECK(out.numberofpoints > 10 && out.numberoftriangles > 50, "%s: %d points %d triangles", sw,
        out.numberofpoints, out.numberoftriangles);
  CHECK(out.numberofcorners == 3 && out.numberoftriangleattributes == 1, "%s: corners %d", sw,
        out.numberofcorners);
  CHECK(out.holelist == in.holelist && out.numberofholes == 1, "%s: holelist not shared", sw);
  CHECK(out.regionlist == in.regionlist && out.numberofregions == 2, "%s: regionlist", sw);
  CHECK(bad_attributes(&out) == 0, "%s: %d vertices with attributes not linear", sw,
        bad_attributes(&out));
  if (out.numberofpoints > 0) dump(sw, &in, &out, first);
  free_out(&out);
}

/* Calls triangulate on bad input: it must return, with empty outputs and a message. */
static void expect_failure(const char *sw, struct triangulateio *in, const char *needle) {
  struct triangulateio out;
  char switches[64];
  clear(&out);
  snprintf(switches, sizeof switches, "%s", sw);
  triangulate(switches, in, &out, NULL);
  CHECK(out.numberofpoints == 0 && out.numberoftriangles == 0 && out.pointlist == NULL &&
            out.trianglelist == NULL && out.segmentlist == NULL,
        "%s: outputs not empty after an error", sw);
  CHECK(strstr(idm_last_error(), needle) != NULL, "%s: message '%s' lacks '%s'", sw,
        idm_last_error(), needle);
  free_out(&out);
}

static void bad_inputs(void) {
  struct triangulateio in;
  int segments[22];
  fill_domain(&in, 1, segments);
  expect_failure("prQ", &in, "no triangles"); /* -r without a mesh to refine */
  expect_failure("pwQ", &in, "-w");    /* refused by name */
  expect_failure("pkQ", &in, "-k");    /* unknown to Triangle */
  expect_failure("pq30a-1Q", &in, "'-'");
  segments[5] = 99;                    /* a segment to a missing point */
  expect_failure("pQ", &in, "segment");
  segments[5] = 0;                     /* below the first number (1) */
  expect_failure("pQ", &in, "first number");
  fill_domain(&in, 1, segments);
  in.numberofpointattributes = 1; /* attributes announced, none given */
  expect_failure("pQ", &in, "pointattributelist");
  fill_domain(&in, 1, segments);
  in.numberofpoints = 2;               /* too few points */
  in.numberofsegments = 0;
  expect_failure("pQ", &in, "point");
  expect_failure("pQ", NULL, "NULL");
  fill_domain(&in, 1, segments);
  expect_failure("pvQ", &in, "vorout"); /* -v needs vorout */
  /* -u without triunsuitable() defined in this program. */
  fill_domain(&in, 1, segments);
  expect_failure("puQ", &in, "triunsuitable");
}

/* -v: one Voronoi vertex per triangle, its circumcentre; one Voronoi edge per mesh edge, a
 * ray (second end -1, direction in normlist) for each hull edge. */
static void voronoi(struct triangulateio *in) {
  struct triangulateio out, vor;
  char sw[] = "vezQ";
  int i, k, rays = 0;
  clear(&out);
  clear(&vor);
  triangulate(sw, in, &out, &vor);
  CHECK(vor.numberofpoints == out.numberoftriangles && vor.numberofpoints > 0,
        "-v: %d Voronoi vertices for %d triangles (%s)", vor.numberofpoints,
        out.numberoftriangles, idm_last_error());
  CHECK(vor.numberofedges == out.numberofedges, "-v: %d Voronoi edges for %d edges",
        vor.numberofedges, out.numberofedges);
  for (i = 0; i < vor.numberofpoints; i++) {
    double d[3];
    for (k = 0; k < 3; k++) {
      const double *p = &out.pointlist[2 * out.trianglelist[3 * i + k]];
      d[k] = hypot(p[0] - vor.pointlist[2 * i], p[1] - vor.pointlist[2 * i + 1]);
    }
    CHECK(fabs(d[0] - d[1]) < 1e-12 && fabs(d[0] - d[2]) < 1e-12, "-v: circumcentre %d", i);
  }
  for (i = 0; i < vor.numberofedges; i++) {
    int ray = vor.edgelist[2 * i + 1] == -1;
    rays += ray;
    CHECK(vor.edgelist[2 * i] >= 0 && vor.edgelist[2 * i] < vor.numberofpoints,
          "-v: edge %d starts at %d", i, vor.edgelist[2 * i]);
    CHECK(ray == (vor.normlist[2 * i] != 0 || vor.normlist[2 * i + 1] != 0),
          "-v: normlist only on rays (edge %d)", i);
  }
  CHECK(rays == 4, "-v: %d rays, 4 hull edges", rays);
  free_out(&out);
  trifree(vor.pointlist);
  trifree(vor.edgelist);
  trifree(vor.normlist);
}

/* -o2: 6 nodes per triangle, the last three the midpoints of the edges opposite the first
 * three, each midpoint one new vertex shared by the triangles of its edge. */
static void second_order(struct triangulateio *in) {
  struct triangulateio plain, out;
  char sw1[] = "czQ", sw2[] = "co2zQ";
  int t, k;
  clear(&plain);
  clear(&out);
  triangulate(sw1, in, &plain, NULL);
  add_attributes(in);
  triangulate(sw2, in, &out, NULL);
  in->numberofpointattributes = 0;
  in->pointattributelist = NULL;
  CHECK(bad_attributes(&out) == 0, "-o2: %d nodes with attributes not linear",
        bad_attributes(&out));
  CHECK(out.numberofcorners == 6 && out.numberoftriangles == plain.numberoftriangles,
        "-o2: %d corners (%s)", out.numberofcorners, idm_last_error());
  /* Euler: edges = vertices + triangles - 1 for a disc; one midpoint per edge. */
  CHECK(out.numberofpoints == 2 * plain.numberofpoints + plain.numberoftriangles - 1,
        "-o2: %d points from %d vertices and %d triangles", out.numberofpoints,
        plain.numberofpoints, plain.numberoftriangles);
  for (t = 0; t < out.numberoftriangles; t++)
    for (k = 0; k < 3; k++) {
      const int *n = &out.trianglelist[6 * t];
      const double *a = &out.pointlist[2 * n[(k + 1) % 3]], *b = &out.pointlist[2 * n[(k + 2) % 3]];
      const double *mid = &out.pointlist[2 * n[3 + k]];
      CHECK(n[k] == plain.trianglelist[3 * t + k], "-o2: corner %d of triangle %d", k, t);
      CHECK(n[3 + k] >= plain.numberofpoints && mid[0] == 0.5 * (a[0] + b[0]) &&
                mid[1] == 0.5 * (a[1] + b[1]),
            "-o2: node %d of triangle %d is not the midpoint opposite corner %d", 3 + k, t, k);
    }
  free_out(&plain);
  free_out(&out);
}

/* -j: a point outside the square's segments is in no triangle: kept at its index without -j,
 * left out with -j. */
static void jettison(void) {
  struct triangulateio in, out;
  REAL pts[] = {0, 0, 1, 0, 5, 5, 1, 1, 0, 1};
  int segs[] = {0, 1, 1, 3, 3, 4, 4, 0};
  char keep[] = "pq30zQ", drop[] = "pq30jzQ";
  int i, with = 0;
  clear(&in);
  clear(&out);
  in.numberofpoints = 5;
  in.pointlist = pts;
  in.numberofsegments = 4;
  in.segmentlist = segs;
  triangulate(keep, &in, &out, NULL);
  with = out.numberofpoints;
  CHECK(with >= 5 && out.pointlist[4] == 5 && out.pointlist[5] == 5, "without -j: %s",
        idm_last_error());
  free_out(&out);
  add_attributes(&in);
  triangulate(drop, &in, &out, NULL);
  CHECK(bad_attributes(&out) == 0, "-j: %d vertices with attributes not linear",
        bad_attributes(&out));
  CHECK(out.numberofpoints == with - 1, "-j: %d points, %d without -j", out.numberofpoints, with);
  for (i = 0; i < out.numberofpoints; i++)
    CHECK(out.pointlist[2 * i] <= 1 && out.pointlist[2 * i + 1] <= 1, "-j kept point %d", i);
  for (i = 0; i < 3 * out.numberoftriangles; i++)
    CHECK(out.trianglelist[i] >= 0 && out.trianglelist[i] < out.numberofpoints, "-j: corner %d", i);
  for (i = 0; i < 2 * out.numberofsegments; i++)
    CHECK(out.segmentlist[i] >= 0 && out.segmentlist[i] < out.numberofpoints, "-j: segment end");
  free_out(&out);
}

/* A point set (no -p): the convex hull is meshed; with -c its edges are output as segments
 * with marker 1, and -B leaves the markers out; -N -E leave vertices and triangles out. */
static void point_set(void) {
  struct triangulateio in, out;
  REAL pts[] = {0, 0, 2, 0, 2, 1, 0, 1, 1, 0.5, 0.3, 0.2};
  char sw[] = "czQ";
  char sw2[] = "cBNEzQ";
  int i;
  clear(&in);
  clear(&out);
  in.numberofpoints = 6;
  in.pointlist = pts;
  triangulate(sw, &in, &out, NULL);
  CHECK(out.numberofpoints == 6 && out.numberoftriangles == 6, "point set: %d points %d tris",
        out.numberofpoints, out.numberoftriangles);
  CHECK(out.numberofsegments == 4, "point set -c: %d hull segments", out.numberofsegments);
  for (i = 0; i < out.numberofsegments; i++)
    CHECK(out.segmentmarkerlist[i] == 1 && out.segmentlist[2 * i] < 4, "hull segment %d", i);
  CHECK(out.holelist == NULL && out.numberofholes == 0, "no holes without -p");
  free_out(&out);
  voronoi(&in);
  second_order(&in);
  triangulate(sw2, &in, &out, NULL);
  CHECK(out.pointlist == NULL && out.trianglelist == NULL && out.segmentmarkerlist == NULL &&
            out.segmentlist != NULL && out.numberoftriangles == 6,
        "-B -N -E");
  free_out(&out);
}

static double tri_area(const double *p, const int *t) {
  const double *a = p + 2 * t[0], *b = p + 2 * t[1], *c = p + 2 * t[2];
  return 0.5 * fabs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
}

/* -r: a mesh of the domain is remeshed with per-triangle area bounds (trianglearealist) small
 * in the strip x < 1 (attribute 1) only: its points stay at their indices, each attribute's
 * area is kept, and only the strip gets triangles below its bound. Then bad given meshes. */
static void refine_given(void) {
  struct triangulateio in, out, given, again;
  int segments[22], i, small = 0;
  double *bounds, area[3] = {0, 0, 0}, coarse = 0;
  char sw1[] = "pq30a0.05AzQ", sw2[] = "rq30aenzQ", sw3[] = "rzQ";
  fill_domain(&in, 0, segments);
  clear(&out);
  triangulate(sw1, &in, &out, NULL);
  CHECK(out.numberoftriangles > 0, "-r: first mesh: %s", idm_last_error());
  bounds = (double *)malloc((size_t)out.numberoftriangles * sizeof *bounds);
  for (i = 0; i < out.numberoftriangles; i++)
    bounds[i] = out.triangleattributelist[i] == 1.0 ? 0.005 : -1;
  clear(&given);
  given.numberofpoints = out.numberofpoints;
  given.pointlist = out.pointlist;
  given.pointmarkerlist = out.pointmarkerlist;
  given.numberoftriangles = out.numberoftriangles;
  given.numberofcorners = 3;
  given.trianglelist = out.trianglelist;
  given.numberoftriangleattributes = 1;
  given.triangleattributelist = out.triangleattributelist;
  given.trianglearealist = bounds;
  clear(&again);
  triangulate(sw2, &given, &again, NULL);
  CHECK(strcmp(idm_last_error(), "") == 0, "-ra: %s", idm_last_error());
  CHECK(again.numberofpoints > out.numberofpoints && again.numberoftriangleattributes == 1,
        "-ra: %d points from %d", again.numberofpoints, out.numberofpoints);
  for (i = 0; i < out.numberofpoints && i < again.numberofpoints; i++)
    CHECK(again.pointlist[2 * i] == out.pointlist[2 * i] &&
              again.pointlist[2 * i + 1] == out.pointlist[2 * i + 1] &&
              again.pointmarkerlist[i] == out.pointmarkerlist[i],
          "-ra: point %d moved", i);
  for (i = 0; i < again.numberoftriangles; i++) {
    double a = tri_area(again.pointlist, again.trianglelist + 3 * i), at;
    at = again.triangleattributelist[i];
    CHECK(at == 1.0 || at == 2.0, "-ra: attribute %g", at);
    area[at == 1.0 ? 1 : 2] += a;
    if (at == 1.0) {
      CHECK(a <= 0.005, "-ra: triangle %d of the strip has area %g", i, a);
      small++;
    } else if (a > coarse) {
      coarse = a;
    }
  }
  CHECK(fabs(area[1] - 4) < 1e-12 && fabs(area[2] - 11) < 1e-12, "-ra: areas %g %g", area[1],
        area[2]);
  CHECK(small >= 4 / 0.005 && coarse > 0.01, "-ra: %d small triangles, largest other %g", small,
        coarse);
  if (again.numberoftriangles > 0) dump(sw2, &given, &again, 0);
  free_out(&again);
  /* Bad given meshes: an error naming the item, empty outputs, never a crash. */
  given.trianglelist[4] = out.numberofpoints + 3;
  triangulate(sw3, &given, &again, NULL);
  CHECK(again.numberoftriangles == 0 && again.trianglelist == NULL &&
            strstr(idm_last_error(), "triangle 1 has corner") != NULL,
        "-r bad corner: %s", idm_last_error());
  given.trianglelist = NULL;
  triangulate(sw3, &given, &again, NULL);
  CHECK(again.numberoftriangles == 0 && strstr(idm_last_error(), "no triangles") != NULL,
        "-r without triangles: %s", idm_last_error());
  given.trianglelist = out.trianglelist;
  given.trianglearealist = NULL;
  triangulate(sw2, &given, &again, NULL);
  CHECK(again.numberoftriangles == 0 && strstr(idm_last_error(), "trianglearealist") != NULL,
        "-ra without trianglearealist: %s", idm_last_error());
  free(bounds);
  free_out(&out);
}

/* -YY: no Steiner point on any segment, the internal one (x = 1) included. */
static void no_segment_steiner(void) {
  struct triangulateio in, out;
  int segments[22], i;
  char sw[] = "pq30a0.05YYzQ";
  fill_domain(&in, 0, segments);
  clear(&out);
  triangulate(sw, &in, &out, NULL);
  CHECK(strcmp(idm_last_error(), "") == 0 && out.numberoftriangles > 0, "-YY: %s",
        idm_last_error());
  CHECK(out.numberofsegments == 11, "-YY: %d segments, 11 given", out.numberofsegments);
  for (i = 0; i < 2 * out.numberofsegments; i++)
    CHECK(out.segmentlist[i] < 10, "-YY: segment end %d is a Steiner point", out.segmentlist[i]);
  free_out(&out);
}

int main(void) {
  bad_inputs();
  mesh_domain("pq30a0.02AenQ", 1);
  mesh_domain("pq30aAenzQ", 0);
  bad_inputs(); /* errors after successes, and successes after errors */
  mesh_domain("pq25a0.05AenzQiFlsX", 0);
  point_set();
  jettison();
  refine_given();
  no_segment_steiner();
  if (failures) fprintf(stderr, "%d checks failed\n", failures);
  return failures ? 1 : 0;
}
