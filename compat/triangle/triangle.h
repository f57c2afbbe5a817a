/*
 * triangle.h: source compatibility with Triangle 1.6's library interface, over idmesh.
 *
 * Code written for Triangle's `triangulate()` compiles unchanged against this header and links
 * with idmesh instead (CMake: idmesh::triangle; pkg-config: idmesh-triangle). The structure,
 * the functions and the switch string are Triangle's; the meshes are idmesh's (quality
 * conforming Delaunay, exact arithmetic). Differences a caller will notice (see README.md,
 * "Switching from Triangle"):
 *   - Errors never exit: where Triangle prints a message and calls exit(1), triangulate()
 *     prints the message on stderr (unless -Q), leaves every output empty (counts 0, no array
 *     allocated) and returns; idm_last_error() (declared in idmesh.h) gives the message.
 *   - Switches idmesh cannot honour (w W) are refused by name as above, never ignored. r is
 *     honoured differently: the given triangles (trianglelist, their first attribute,
 *     trianglearealist with a) are remeshed, not refined in place; points keep their indices.
 *     i F l s X (algorithm and arithmetic choices of Triangle) are accepted and do nothing;
 *     g and I, which only affect Triangle's files, are accepted and do nothing (as in
 *     Triangle's library).
 *   - Point attributes (numberofpointattributes > 0) are copied at input points and
 *     interpolated linearly at Steiner points (along the input segment for a point on one,
 *     else in the input points' Delaunay triangle containing it; o2 nodes: the mean of the
 *     edge's ends): equal to Triangle's for attributes linear in x and y, otherwise another
 *     linear interpolation. Duplicate input points are an error (Triangle drops them).
 *   - REAL must be double (a compile-time check fails otherwise); ANSI_DECLARATORS and VOID
 *     may be defined or not: the declarations below are always ANSI prototypes.
 */
#ifndef IDMESH_COMPAT_TRIANGLE_H
#define IDMESH_COMPAT_TRIANGLE_H

#include "idmesh.h"

#ifdef REAL
/* Triangle may be compiled with REAL float; idmesh computes in double only. */
typedef char idmesh_triangle_REAL_must_be_double[sizeof(REAL) == sizeof(double) ? 1 : -1];
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Triangle 1.6's structure: same members, same order, same types (REAL is double). Counts and
 * the meaning of each array are as documented in Triangle's triangle.h. */
struct triangulateio {
  double *pointlist;               /* In / out: 2 per point. */
  double *pointattributelist;      /* In / out: numberofpointattributes per point. */
  int *pointmarkerlist;            /* In / out: 1 per point. */
  int numberofpoints;              /* In / out. */
  int numberofpointattributes;     /* In / out. */

  int *trianglelist;               /* In / out: numberofcorners per triangle. */
  double *triangleattributelist;   /* In / out: numberoftriangleattributes per triangle. */
  double *trianglearealist;        /* In only (-r with -a): 1 per triangle, <= 0 none. */
  int *neighborlist;               /* Out only (-n): 3 per triangle, -1 on the boundary. */
  int numberoftriangles;           /* In / out. */
  int numberofcorners;             /* In / out. */
  int numberoftriangleattributes;  /* In / out. */

  int *segmentlist;                /* In / out: 2 per segment. */
  int *segmentmarkerlist;          /* In / out: 1 per segment. */
  int numberofsegments;            /* In / out. */

  double *holelist;                /* In: 2 per hole; the pointer is copied to out (-p). */
  int numberofholes;               /* In / copied out. */

  double *regionlist;              /* In: x, y, attribute, max area; pointer copied to out. */
  int numberofregions;             /* In / copied out. */

  int *edgelist;                   /* Out only (-e): 2 per edge. */
  int *edgemarkerlist;             /* Out only (-e, not -B): 1 per edge. */
  double *normlist;                /* Out only, Voronoi diagram (-v): ray directions. */
  int numberofedges;               /* Out only. */
};

/* Meshes `in` as the switch string says (Triangle's letters, no leading dash needed) and fills
 * `out`, and with -v `vorout` (Voronoi vertices = circumcentres, one per triangle; one Voronoi
 * edge per mesh edge, second index -1 and normlist the outward direction for rays). Output arrays whose pointer is
 * NULL are allocated with malloc (free them with trifree or free); a pointer the caller set
 * before the call is written through as Triangle does, so it must point to enough memory. */
void triangulate(char *triswitches, struct triangulateio *in, struct triangulateio *out,
                 struct triangulateio *vorout);

/* Frees memory allocated by triangulate (free()). */
void trifree(void *memptr);

/* The user's sizing test for -u, as in Triangle built with EXTERNAL_TEST: nonzero when the
 * triangle with corners triorg, tridest, triapex (counter-clockwise; x at [0], y at [1]) and
 * area `area` must be split. Define it in the program (in C++ it gets C linkage from this
 * declaration); -u without a definition is an error. It must not throw or longjmp. */
int triunsuitable(double *triorg, double *tridest, double *triapex, double area);

#ifdef __cplusplus
}
#endif

#endif /* IDMESH_COMPAT_TRIANGLE_H */
