/*
 * Triangle 1.6's triangulate()/trifree() over idmesh's C ABI: converts struct triangulateio
 * to idm_mesher2d calls and the mesh back, following Triangle's output conventions. No meshing
 * happens here; switches are parsed by the library (idm_triangle_parse_switches).
 */
#include "triangle.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* -u: the program's triunsuitable, if it defines one. */
#pragma weak triunsuitable

/* Everything triangulate() computes before it touches `out`, so a failure leaves `out` as the
 * caller passed it (apart from the counts, which are zeroed). */
struct result {
  double *points;
  double *point_attributes; /* num_attributes per point, or NULL */
  int *point_markers;
  int *triangles;
  double *triangle_attributes;
  int *neighbors;
  int *segments;
  int *segment_markers;
  int *edges;
  int *edge_markers;
  double *voronoi_points;
  int *voronoi_edges;
  double *voronoi_norms;
  int num_attributes;
  int num_points, num_triangles, num_segments, num_edges, num_voronoi_points,
      num_voronoi_edges;
};

static void free_result(struct result *r) {
  free(r->points);
  free(r->point_attributes);
  free(r->point_markers);
  free(r->triangles);
  free(r->triangle_attributes);
  free(r->neighbors);
  free(r->segments);
  free(r->segment_markers);
  free(r->edges);
  free(r->edge_markers);
  free(r->voronoi_points);
  free(r->voronoi_edges);
  free(r->voronoi_norms);
  memset(r, 0, sizeof *r);
}

/* malloc for n items of `size` bytes (at least one byte, so NULL always means failure). */
static void *alloc(size_t n, size_t size) {
  if (n != 0 && size > SIZE_MAX / n) return NULL;
  return malloc(n * size == 0 ? 1 : n * size);
}

static int32_t user_test(void *user, const double *a, const double *b, const double *c,
                         double area) {
  double org[2], dest[2], apex[2];
  (void)user;
  org[0] = a[0];
  org[1] = a[1];
  dest[0] = b[0];
  dest[1] = b[1];
  apex[0] = c[0];
  apex[1] = c[1];
  return triunsuitable(org, dest, apex, area) != 0;
}

/* Records and (unless quiet) prints a failure found here, before the library was called. */
static idm_status fail(idm_status status, const char *message) {
  return idm_triangle_fail(status, message);
}

/* Converts a lent array of `n` uint32_t indices to Triangle's numbering (from `first`). */
static int *renumbered(const uint32_t *v, size_t n, int first) {
  int *out = (int *)alloc(n, sizeof *out);
  size_t i;
  if (out == NULL) return NULL;
  for (i = 0; i < n; i++) out[i] = v[i] == IDM_NONE ? -1 : (int)v[i] + first;
  return out;
}

/* Feeds `in` to the mesher `m` as the switches say. */
static idm_status add_input(idm_mesher2d *m, const idm_triangle_switches *sw,
                            const struct triangulateio *in, int first) {
  idm_status st;
  size_t i, n;
  if (in->numberofpoints < 0) return fail(IDM_ERR_INVALID_ARGUMENT, "in->numberofpoints is negative");
  if (in->numberofpointattributes < 0)
    return fail(IDM_ERR_INVALID_ARGUMENT, "in->numberofpointattributes is negative");
  if (in->numberofpointattributes > 0 && in->numberofpoints > 0 && in->pointattributelist == NULL)
    return fail(IDM_ERR_NULL_POINTER, "in->pointattributelist is NULL");
  st = idm_mesher2d_add_points(m, in->pointlist, (size_t)in->numberofpoints,
                               in->pointmarkerlist);
  if (st != IDM_OK || !sw->poly) return st;

  if (in->numberofsegments < 0 || in->numberofholes < 0 || in->numberofregions < 0)
    return fail(IDM_ERR_INVALID_ARGUMENT, "a segment, hole or region count is negative");
  n = (size_t)in->numberofsegments;
  if (n > 0) {
    uint32_t *ab;
    if (in->segmentlist == NULL) return fail(IDM_ERR_NULL_POINTER, "in->segmentlist is NULL");
    ab = (uint32_t *)alloc(2 * n, sizeof *ab);
    if (ab == NULL) return fail(IDM_ERR_INVALID_ARGUMENT, "out of memory copying the segments");
    for (i = 0; i < 2 * n; i++) {
      if (in->segmentlist[i] < first) {
        char msg[160];
        snprintf(msg, sizeof msg, "segment %zu has vertex %d, below the first number %d",
                 i / 2 + (size_t)first, in->segmentlist[i], first);
        free(ab);
        return fail(IDM_ERR_INVALID_INPUT, msg);
      }
      ab[i] = (uint32_t)(in->segmentlist[i] - first);
    }
    st = idm_mesher2d_add_segments(m, ab, n, in->segmentmarkerlist);
    free(ab);
    if (st != IDM_OK) return st;
  }
  /* With -r, as in Triangle, the holes and regions play no part: the given mesh has them. */
  if (sw->refine) return IDM_OK;
  if (!sw->ignore_holes) {
    st = idm_mesher2d_add_holes(m, in->holelist, (size_t)in->numberofholes);
    if (st != IDM_OK) return st;
  }
  n = (size_t)in->numberofregions;
  if (n > 0) {
    double *xy, *attr, *area;
    if (in->regionlist == NULL) return fail(IDM_ERR_NULL_POINTER, "in->regionlist is NULL");
    xy = (double *)alloc(2 * n, sizeof *xy);
    attr = (double *)alloc(n, sizeof *attr);
    area = (double *)alloc(n, sizeof *area);
    if (xy == NULL || attr == NULL || area == NULL) {
      st = fail(IDM_ERR_INVALID_ARGUMENT, "out of memory copying the regions");
    } else {
      for (i = 0; i < n; i++) {
        xy[2 * i] = in->regionlist[4 * i];
        xy[2 * i + 1] = in->regionlist[4 * i + 1];
        attr[i] = in->regionlist[4 * i + 2];
        area[i] = in->regionlist[4 * i + 3];
      }
      st = idm_mesher2d_add_regions(m, xy, attr, area, n);
    }
    free(xy);
    free(attr);
    free(area);
  }
  return st;
}

/* -r: hands the given triangles (in->trianglelist, their first attribute and, with -a without
 * a number, in->trianglearealist) to the library, which remeshes them (see
 * idm_triangle_set_given_mesh). */
static idm_status add_given_mesh(idm_mesher2d *m, const idm_triangle_switches *sw,
                                 const struct triangulateio *in, int first) {
  size_t n, i, k, corners;
  uint32_t *tri;
  const double *areas = NULL;
  idm_status st;
  if (in->numberoftriangles < 0 || in->numberofcorners < 0 || in->numberoftriangleattributes < 0)
    return fail(IDM_ERR_INVALID_ARGUMENT, "-r: a triangle, corner or attribute count is negative");
  if (in->numberoftriangles == 0 || in->trianglelist == NULL)
    return fail(IDM_ERR_INVALID_INPUT, "-r: no triangles given (in->trianglelist)");
  if (in->numberofcorners != 3 && in->numberofcorners != 6)
    return fail(IDM_ERR_INVALID_INPUT, "-r: in->numberofcorners must be 3 or 6");
  if (in->numberoftriangleattributes > 1)
    return fail(IDM_ERR_UNSUPPORTED,
                "-r: in->numberoftriangleattributes is above 1: idmesh carries one attribute");
  if (in->numberoftriangleattributes == 1 && in->triangleattributelist == NULL)
    return fail(IDM_ERR_NULL_POINTER, "-r: in->triangleattributelist is NULL");
  if (sw->options.region_max_area) {
    if (in->trianglearealist == NULL)
      return fail(IDM_ERR_NULL_POINTER, "-ra: in->trianglearealist is NULL");
    areas = in->trianglearealist;
  }
  n = (size_t)in->numberoftriangles;
  corners = (size_t)in->numberofcorners;
  tri = (uint32_t *)alloc(3 * n, sizeof *tri);
  if (tri == NULL) return fail(IDM_ERR_INVALID_ARGUMENT, "out of memory copying the triangles");
  for (i = 0; i < n; i++) {
    for (k = 0; k < 3; k++) {
      int v = in->trianglelist[corners * i + k];
      if (v < first) {
        char msg[160];
        snprintf(msg, sizeof msg, "-r: triangle %zu has corner %d, below the first number %d",
                 i + (size_t)first, v, first);
        free(tri);
        return fail(IDM_ERR_INVALID_INPUT, msg);
      }
      tri[3 * i + k] = (uint32_t)(v - first);
    }
  }
  st = idm_triangle_set_given_mesh(m, tri, n,
                                   in->numberoftriangleattributes == 1 ? in->triangleattributelist
                                                                       : NULL,
                                   areas, (uint32_t)first);
  free(tri);
  return st;
}

/* Reads edges or segments (idm_triangle_edges / idm_triangle_segments) in Triangle's form. */
static idm_status read_pairs(idm_status (*get)(const idm_mesher2d *, uint32_t *, int32_t *,
                                               size_t, size_t *),
                             const idm_mesher2d *m, int first, int **pairs, int **markers,
                             int *count) {
  size_t n = 0, i;
  uint32_t *ab;
  int32_t *mk;
  idm_status st = get(m, NULL, NULL, 0, &n);
  if (st != IDM_OK) return st;
  if (n > INT32_MAX / 2) return fail(IDM_ERR_INVALID_ARGUMENT, "too many edges for int indices");
  ab = (uint32_t *)alloc(2 * n, sizeof *ab);
  mk = (int32_t *)alloc(n, sizeof *mk);
  *markers = (int *)alloc(n, sizeof **markers);
  if (ab == NULL || mk == NULL || *markers == NULL) {
    st = fail(IDM_ERR_INVALID_ARGUMENT, "out of memory reading edges");
  } else if ((st = get(m, ab, mk, n, &n)) == IDM_OK) {
    *pairs = renumbered(ab, 2 * n, first);
    if (*pairs == NULL) st = fail(IDM_ERR_INVALID_ARGUMENT, "out of memory reading edges");
    for (i = 0; i < n; i++) (*markers)[i] = mk[i];
    *count = (int)n;
  }
  free(ab);
  free(mk);
  return st;
}

/* Reads the mesh from `m` into `r` as Triangle would output it. */
static idm_status read_mesh(const idm_mesher2d *m, const idm_triangle_switches *sw, int first,
                            const struct triangulateio *in, struct result *r) {
  const double *xy = NULL, *attr = NULL;
  const int32_t *vm = NULL;
  const uint32_t *tri = NULL, *nbr = NULL;
  size_t nv = 0, nt = 0, na = 0, nn = 0, i;
  idm_status st;
  if ((st = idm_mesher2d_vertices(m, &xy, &nv)) != IDM_OK) return st;
  if ((st = idm_mesher2d_vertex_markers(m, &vm, &nv)) != IDM_OK) return st;
  if ((st = idm_mesher2d_triangles(m, &tri, &nt)) != IDM_OK) return st;
  if (sw->second_order) {
    st = idm_triangle_second_order(m, NULL, NULL, 0, NULL, 0, &nn);
    if (st != IDM_OK) return st;
  }
  if (nv + nn > INT32_MAX / 2 || nt > INT32_MAX / 6)
    return fail(IDM_ERR_INVALID_ARGUMENT, "the mesh is too large for int indices");
  r->num_points = (int)(nv + nn);
  r->num_triangles = (int)nt;
  r->points = (double *)alloc(2 * (nv + nn), sizeof *r->points);
  r->point_markers = (int *)alloc(nv + nn, sizeof *r->point_markers);
  if (r->points == NULL || r->point_markers == NULL)
    return fail(IDM_ERR_INVALID_ARGUMENT, "out of memory copying the mesh");
  if (sw->second_order) {
    /* Triangle's 6-node triangles: the corners, then the midpoints opposite them. */
    uint32_t *mid = (uint32_t *)alloc(3 * nt, sizeof *mid);
    r->triangles = (int *)alloc(6 * nt, sizeof *r->triangles);
    if (mid == NULL || r->triangles == NULL) {
      free(mid);
      return fail(IDM_ERR_INVALID_ARGUMENT, "out of memory for second-order nodes");
    }
    st = idm_triangle_second_order(m, r->points + 2 * nv, (int32_t *)(r->point_markers + nv),
                                   nn, mid, nt, &nn);
    for (i = 0; st == IDM_OK && i < nt; i++) {
      size_t k;
      for (k = 0; k < 3; k++) {
        r->triangles[6 * i + k] = (int)tri[3 * i + k] + first;
        r->triangles[6 * i + 3 + k] = (int)mid[3 * i + k] + first;
      }
    }
    free(mid);
    if (st != IDM_OK) return st;
  } else {
    r->triangles = renumbered(tri, 3 * nt, first);
    if (r->triangles == NULL) return fail(IDM_ERR_INVALID_ARGUMENT, "out of memory copying the mesh");
  }
  if (nv > 0) memcpy(r->points, xy, 2 * nv * sizeof *xy);
  for (i = 0; i < nv; i++) r->point_markers[i] = vm[i];
  if (in->numberofpointattributes > 0) {
    /* Kept at input points, interpolated linearly at Steiner points (by the library), and
     * at -o2 nodes the mean of the edge's ends, as Triangle does. */
    size_t na = (size_t)in->numberofpointattributes, k;
    r->num_attributes = in->numberofpointattributes;
    r->point_attributes = (double *)alloc((nv + nn) * na, sizeof *r->point_attributes);
    if (r->point_attributes == NULL)
      return fail(IDM_ERR_INVALID_ARGUMENT, "out of memory for the point attributes");
    st = idm_triangle_point_attributes(m, in->pointattributelist, na, r->point_attributes, nv);
    if (st != IDM_OK) return st;
    for (i = 0; sw->second_order && i < nt; i++) {
      for (k = 0; k < 3; k++) {
        size_t node = (size_t)(r->triangles[6 * i + 3 + k] - first), a;
        size_t p = (size_t)(r->triangles[6 * i + (k + 1) % 3] - first);
        size_t q = (size_t)(r->triangles[6 * i + (k + 2) % 3] - first);
        for (a = 0; a < na; a++)
          r->point_attributes[node * na + a] =
              0.5 * (r->point_attributes[p * na + a] + r->point_attributes[q * na + a]);
      }
    }
  }
  if (sw->region_attributes) {
    if ((st = idm_mesher2d_triangle_attributes(m, &attr, &na)) != IDM_OK) return st;
    r->triangle_attributes = (double *)alloc(nt, sizeof *r->triangle_attributes);
    if (r->triangle_attributes == NULL)
      return fail(IDM_ERR_INVALID_ARGUMENT, "out of memory copying the attributes");
    for (i = 0; i < nt; i++) r->triangle_attributes[i] = i < na ? attr[i] : 0.0;
  }
  if (sw->neighbors) {
    if ((st = idm_mesher2d_neighbors(m, &nbr, &nt)) != IDM_OK) return st;
    r->neighbors = renumbered(nbr, 3 * nt, first);
    if (r->neighbors == NULL) return fail(IDM_ERR_INVALID_ARGUMENT, "out of memory copying neighbours");
  }
  if ((sw->poly || sw->convex_hull) && !sw->no_poly) {
    st = read_pairs(idm_triangle_segments, m, first, &r->segments, &r->segment_markers,
                    &r->num_segments);
    if (st != IDM_OK) return st;
  }
  if (sw->edges) {
    st = read_pairs(idm_triangle_edges, m, first, &r->edges, &r->edge_markers, &r->num_edges);
    if (st != IDM_OK) return st;
  }
  if (sw->voronoi) {
    size_t np = 0, ne = 0;
    st = idm_triangle_voronoi(m, NULL, NULL, NULL, 0, 0, &np, &ne);
    if (st != IDM_OK) return st;
    if (ne > INT32_MAX / 2) return fail(IDM_ERR_INVALID_ARGUMENT, "too many Voronoi edges");
    r->voronoi_points = (double *)alloc(2 * np, sizeof *r->voronoi_points);
    r->voronoi_edges = (int *)alloc(2 * ne, sizeof *r->voronoi_edges);
    r->voronoi_norms = (double *)alloc(2 * ne, sizeof *r->voronoi_norms);
    if (r->voronoi_points == NULL || r->voronoi_edges == NULL || r->voronoi_norms == NULL)
      return fail(IDM_ERR_INVALID_ARGUMENT, "out of memory for the Voronoi diagram");
    st = idm_triangle_voronoi(m, r->voronoi_points, (int32_t *)r->voronoi_edges,
                              r->voronoi_norms, np, ne, &np, &ne);
    if (st != IDM_OK) return st;
    for (i = 0; i < 2 * ne; i++)
      if (r->voronoi_edges[i] >= 0) r->voronoi_edges[i] += first;
    r->num_voronoi_points = (int)np;
    r->num_voronoi_edges = (int)ne;
  }
  return IDM_OK;
}

/* -j: drops the vertices no triangle uses (inside holes, outside the domain) and renumbers the
 * rest in order; triangles, segments and edges refer only to used vertices. */
static idm_status jettison(struct result *r, int corners, int first) {
  int *map = (int *)alloc((size_t)r->num_points, sizeof *map);
  int i, kept = 0;
  if (map == NULL) return fail(IDM_ERR_INVALID_ARGUMENT, "out of memory for -j");
  for (i = 0; i < r->num_points; i++) map[i] = -1;
  for (i = 0; i < corners * r->num_triangles; i++) map[r->triangles[i] - first] = 0;
  for (i = 0; i < r->num_points; i++) {
    if (map[i] < 0) continue;
    map[i] = kept;
    r->points[2 * kept] = r->points[2 * i];
    r->points[2 * kept + 1] = r->points[2 * i + 1];
    r->point_markers[kept] = r->point_markers[i];
    if (r->point_attributes != NULL)
      memmove(r->point_attributes + (size_t)kept * (size_t)r->num_attributes,
              r->point_attributes + (size_t)i * (size_t)r->num_attributes,
              (size_t)r->num_attributes * sizeof *r->point_attributes);
    kept++;
  }
  for (i = 0; i < corners * r->num_triangles; i++)
    r->triangles[i] = map[r->triangles[i] - first] + first;
  for (i = 0; r->segments != NULL && i < 2 * r->num_segments; i++)
    r->segments[i] = map[r->segments[i] - first] + first;
  for (i = 0; r->edges != NULL && i < 2 * r->num_edges; i++)
    r->edges[i] = map[r->edges[i] - first] + first;
  r->num_points = kept;
  free(map);
  return IDM_OK;
}

/* Hands an array to `out`: into the caller's array when it set one (Triangle writes through
 * such pointers), else the malloc'ed array itself, which `out` then owns. */
#define GIVE_TO(io, field, mine, n)                                             \
  do {                                                                          \
    if ((io)->field != NULL) {                                                  \
      if ((n) > 0) memcpy((io)->field, (mine), (size_t)(n) * sizeof *(mine));   \
    } else {                                                                    \
      (io)->field = (mine);                                                     \
      (mine) = NULL;                                                            \
    }                                                                           \
  } while (0)
#define GIVE(field, mine, n) GIVE_TO(out, field, mine, n)

static void commit(const idm_triangle_switches *sw, struct triangulateio *in,
                   struct triangulateio *out, struct triangulateio *vorout, struct result *r) {
  out->numberofpoints = r->num_points;
  out->numberofpointattributes = r->num_attributes;
  if (!sw->no_node) {
    GIVE(pointlist, r->points, 2 * r->num_points);
    if (r->num_attributes > 0)
      GIVE(pointattributelist, r->point_attributes, r->num_attributes * r->num_points);
    if (!sw->no_boundary_markers) GIVE(pointmarkerlist, r->point_markers, r->num_points);
  }
  out->numberoftriangles = r->num_triangles;
  out->numberofcorners = sw->second_order ? 6 : 3;
  out->numberoftriangleattributes = sw->region_attributes ? 1 : 0;
  if (!sw->no_ele) {
    GIVE(trianglelist, r->triangles, out->numberofcorners * r->num_triangles);
    if (sw->region_attributes)
      GIVE(triangleattributelist, r->triangle_attributes, r->num_triangles);
  }
  if (sw->neighbors) GIVE(neighborlist, r->neighbors, 3 * r->num_triangles);
  if ((sw->poly || sw->convex_hull) && !sw->no_poly) {
    out->numberofsegments = r->num_segments;
    GIVE(segmentlist, r->segments, 2 * r->num_segments);
    if (!sw->no_boundary_markers) GIVE(segmentmarkerlist, r->segment_markers, r->num_segments);
    /* As Triangle: the hole and region arrays are shared with `in`, not copied. */
    out->holelist = sw->poly ? in->holelist : NULL;
    out->numberofholes = sw->poly ? in->numberofholes : 0;
    out->regionlist = sw->poly ? in->regionlist : NULL;
    out->numberofregions = sw->poly ? in->numberofregions : 0;
  }
  if (sw->edges) {
    out->numberofedges = r->num_edges;
    GIVE(edgelist, r->edges, 2 * r->num_edges);
    if (!sw->no_boundary_markers) GIVE(edgemarkerlist, r->edge_markers, r->num_edges);
  }
  if (sw->voronoi) {
    vorout->numberofpoints = r->num_voronoi_points;
    vorout->numberofpointattributes = 0;
    GIVE_TO(vorout, pointlist, r->voronoi_points, 2 * r->num_voronoi_points);
    vorout->numberofedges = r->num_voronoi_edges;
    GIVE_TO(vorout, edgelist, r->voronoi_edges, 2 * r->num_voronoi_edges);
    GIVE_TO(vorout, normlist, r->voronoi_norms, 2 * r->num_voronoi_edges);
  }
}

static idm_status run(char *triswitches, struct triangulateio *in, struct triangulateio *out,
                      struct triangulateio *vorout, idm_triangle_switches *sw, int *quiet) {
  idm_mesher2d *m = NULL;
  struct result r;
  idm_status st;
  int first;
  memset(&r, 0, sizeof r);
  *quiet = triswitches != NULL && strchr(triswitches, 'Q') != NULL;
  if (triswitches == NULL) return fail(IDM_ERR_NULL_POINTER, "triswitches is NULL");
  if ((st = idm_triangle_parse_switches(triswitches, sw)) != IDM_OK) return st;
  *quiet = sw->quiet != 0;
  if (in == NULL || out == NULL) return fail(IDM_ERR_NULL_POINTER, "in or out is NULL");
  if (sw->voronoi && vorout == NULL) return fail(IDM_ERR_NULL_POINTER, "-v with vorout NULL");
  if (sw->user_test && &triunsuitable == NULL)
    return fail(IDM_ERR_INVALID_ARGUMENT, "-u needs the program to define triunsuitable()");
  first = sw->zero_based ? 0 : 1;
  /* Triangle splits crossing segments at their intersection. */
  sw->options.split_crossings = 1;
  if ((st = idm_mesher2d_new(&m)) != IDM_OK) return st;
  if (sw->refine) {
    /* The given triangles' attributes are carried over (as Triangle does, A or not); c has
     * no effect, the domain being the given triangles. */
    int attributes = in != NULL && in->numberoftriangleattributes > 0;
    sw->region_attributes = sw->options.region_attributes = attributes;
    sw->convex_hull = sw->options.convex_hull = 0;
  }
  st = add_input(m, sw, in, first);
  if (st == IDM_OK && sw->refine) st = add_given_mesh(m, sw, in, first);
  if (st == IDM_OK) st = idm_mesher2d_set_options(m, &sw->options);
  if (st == IDM_OK && sw->user_test) st = idm_mesher2d_set_sizing(m, user_test, NULL);
  if (st == IDM_OK) {
    st = idm_mesher2d_refine(m);
    if (st == IDM_INCOMPLETE) {
      if (!sw->quiet) fprintf(stderr, "triangle (idmesh): warning: %s\n", idm_last_error());
      st = IDM_OK;
    }
  }
  if (st == IDM_OK && sw->check) st = idm_mesher2d_validate(m);
  if (st == IDM_OK) st = read_mesh(m, sw, first, in, &r);
  if (st == IDM_OK && sw->jettison) st = jettison(&r, sw->second_order ? 6 : 3, first);
  if (st == IDM_OK) {
    commit(sw, in, out, vorout, &r);
    if (sw->verbose && !sw->quiet)
      printf("triangle (idmesh): %d vertices, %d triangles, %d segments, %d edges\n",
             r.num_points, r.num_triangles, r.num_segments, r.num_edges);
  }
  free_result(&r);
  idm_mesher2d_free(m);
  return st;
}

void triangulate(char *triswitches, struct triangulateio *in, struct triangulateio *out,
                 struct triangulateio *vorout) {
  idm_triangle_switches sw;
  int quiet = 0;
  if (run(triswitches, in, out, vorout, &sw, &quiet) == IDM_OK) return;
  /* Where Triangle would exit(1): empty outputs, the message, and return. */
  if (out != NULL) {
    out->numberofpoints = 0;
    out->numberofpointattributes = 0;
    out->numberoftriangles = 0;
    out->numberoftriangleattributes = 0;
    out->numberofsegments = 0;
    out->numberofholes = 0;
    out->numberofregions = 0;
    out->numberofedges = 0;
  }
  if (vorout != NULL) {
    vorout->numberofpoints = 0;
    vorout->numberofedges = 0;
  }
  if (!quiet) fprintf(stderr, "triangle (idmesh): error: %s\n", idm_last_error());
}

void trifree(void *memptr) { free(memptr); }
