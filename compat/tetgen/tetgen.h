/*
 * tetgen.h -- TetGen's library interface (tetgenio, tetgenbehavior, tetrahedralize) on top of
 * idmesh. Code written for TetGen 1.5.0 or 1.6.0 compiles unchanged against this header and
 * links against idmesh::tetgen (CMake) instead of -ltet. Written for idmesh from TetGen's
 * public interface (names, types and order of the public members); it contains no TetGen code.
 *
 * Layout: tetgenio and tetgenbehavior have TetGen 1.5.0's members in 1.5.0's order and types.
 * 1.6.0's additions (point2tetlist, tet2facelist, tet2edgelist, face2edgelist) come after them,
 * except when IDMESH_TETGEN_LAYOUT_1_5 is defined (the libtet.so.1.5 build, which must match
 * Debian's libtet1.5 byte for byte). face2tetlist and edge2tetlist (1.6) share the storage of
 * adjtetlist and edgeadjtetlist (1.5).
 *
 * Switches (one parser, shared with `idmesh tetgen`; README "Switching from TetGen" has the
 * details of each):
 *   honoured:  p q[ratio][/angle] a[volume] a A S[n] Y M z f e n nn N E F B I d C Q V k g c T
 *              O[level][/scheme] (opt-in; scheme bit 4, sliver splitting, is idmesh's
 *              Delaunay sliver removal) o/<angle>; D, J, X accepted (idmesh output is always conforming
 *              Delaunay, keeps all vertices, is always exact);
 *              r (tetrahedronlist, tetrahedronattributelist, tetrahedronvolumelist with a,
 *              trifacelist + trifacemarkerlist: the given mesh's boundary and region faces are
 *              remeshed with its points kept, not refined in place); i (addin's points);
 *              m (pointmtrlist of bgmin with its tetrahedra, else of in: 1 size per point,
 *              interpolated linearly); o2 (10-node tetrahedra, TetGen 1.5's node order).
 *   refused:   every other letter (w R s l L b v G K j, p<tolerance>): tetrahedralize throws
 *              10 and the message (printed unless Q, and in idm_last_error()) names the switch.
 * Input honoured: facetconstraintlist and segmentconstraintlist (when refining), tetunsuitable.
 * Input refused (throw 10, message says which): anisotropic metrics (numberofpointmtrs other
 *   than 1).
 * Input edges (edgelist + edgemarkerlist, e.g. from load_edge) are segments of the PLC, as in
 *   TetGen. load_vtk reads legacy ASCII VTK surfaces; load_pbc returns false (TetGen 1.5/1.6
 *   implement it nowhere: tetgenio has no periodic-boundary fields).
 * Output: pointlist (with o2 the edge nodes after the vertices), pointmarkerlist (unless B),
 *   pointattributelist (input attributes, linearly interpolated at Steiner points),
 *   tetrahedronlist (4 or 10 corners), tetrahedronattributelist (A, or r with attributes),
 *   neighborlist (n), trifacelist + trifacemarkerlist (boundary
 *   and facet faces; every face with f) + adjtetlist (nn), edgelist + edgemarkerlist (e: every
 *   mesh edge, marker of the subsegment it lies on, else 0), and with the 1.6 layout
 *   point2tetlist (always), tet2facelist (f), tet2edgelist and face2edgelist (e).
 * Errors are thrown as int, TetGen's codes: 1 out of memory, 2 internal error, 3
 *   self-intersecting input, 10 input error (also unsupported switches and input). The
 *   message is printed to stderr unless Q and stays in idm_last_error() (see idmesh.h).
 *   Nothing exits or aborts.
 * Differences a user notices: `p` output is conforming Delaunay (input edges and facets are
 *   split by Steiner points where TetGen's constrained output would not split them), unless Y.
 */
#ifndef tetgenH
#define tetgenH

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <stdint.h>

#ifndef REAL
#define REAL double
#endif
#define FILENAMESIZE 1024
#define INPUTLINESIZE 2048

class tetgenio {
public:
  typedef struct {
    int *vertexlist;
    int numberofvertices;
  } polygon;

  typedef struct {
    polygon *polygonlist;
    int numberofpolygons;
    REAL *holelist;
    int numberofholes;
  } facet;

  typedef struct {
    int v1, v2;
    REAL vnormal[3];
  } voroedge;

  typedef struct {
    int c1, c2;
    int *elist;
  } vorofacet;

  typedef struct {
    REAL uv[2];
    int tag;
    int type;
  } pointparam;

  typedef REAL (*GetVertexParamOnEdge)(void *, int, int);
  typedef void (*GetSteinerOnEdge)(void *, int, REAL, REAL *);
  typedef void (*GetVertexParamOnFace)(void *, int, int, REAL *);
  typedef void (*GetEdgeSteinerParamOnFace)(void *, int, REAL, int, REAL *);
  typedef void (*GetSteinerOnFace)(void *, int, REAL *, REAL *);
  typedef bool (*TetSizeFunc)(REAL *, REAL *, REAL *, REAL *, REAL *, REAL);

  int firstnumber;
  int mesh_dim;
  int useindex;

  REAL *pointlist;
  REAL *pointattributelist;
  REAL *pointmtrlist;
  int *pointmarkerlist;
  pointparam *pointparamlist;
  int numberofpoints;
  int numberofpointattributes;
  int numberofpointmtrs;

  int *tetrahedronlist;
  REAL *tetrahedronattributelist;
  REAL *tetrahedronvolumelist;
  int *neighborlist;
  int numberoftetrahedra;
  int numberofcorners;
  int numberoftetrahedronattributes;

  facet *facetlist;
  int *facetmarkerlist;
  int numberoffacets;

  REAL *holelist;
  int numberofholes;

  REAL *regionlist;
  int numberofregions;

  REAL *facetconstraintlist;
  int numberoffacetconstraints;

  REAL *segmentconstraintlist;
  int numberofsegmentconstraints;

  int *trifacelist;
  int *trifacemarkerlist;
  int *o2facelist;
  union {
    int *adjtetlist;   /* TetGen 1.5 */
    int *face2tetlist; /* TetGen 1.6: the same array */
  };
  int numberoftrifaces;

  int *edgelist;
  int *edgemarkerlist;
  int *o2edgelist;
  union {
    int *edgeadjtetlist; /* TetGen 1.5 */
    int *edge2tetlist;   /* TetGen 1.6: the same array */
  };
  int numberofedges;

  REAL *vpointlist;
  voroedge *vedgelist;
  vorofacet *vfacetlist;
  int **vcelllist;
  int numberofvpoints;
  int numberofvedges;
  int numberofvfacets;
  int numberofvcells;

  void *geomhandle;
  GetVertexParamOnEdge getvertexparamonedge;
  GetSteinerOnEdge getsteineronedge;
  GetVertexParamOnFace getvertexparamonface;
  GetEdgeSteinerParamOnFace getedgesteinerparamonface;
  GetSteinerOnFace getsteineronface;

  /* Called during quality refinement as tetunsuitable(pa, pb, pc, pd, elen, vol) with the
   * corners, their 6 squared edge lengths (ab, bc, ca, ad, bd, cd) and the volume; true splits
   * the tetrahedron. A C++ exception it throws is rethrown by tetrahedralize. */
  TetSizeFunc tetunsuitable;

#ifndef IDMESH_TETGEN_LAYOUT_1_5
  /* TetGen 1.6.0's connectivity outputs (not in 1.5.0's layout). */
  int *point2tetlist; /* one tetrahedron per point (firstnumber - 1 when none) */
  int *tet2facelist;  /* 4 per tetrahedron: its faces in trifacelist (with f) */
  int *tet2edgelist;  /* 6 per tetrahedron: its edges in edgelist (with e) */
  int *face2edgelist; /* 3 per face: its edges in edgelist (with e) */
#endif

  /* Input and output through idmesh's readers (node, poly, smesh, off, ply, stl, medit). The
   * name may carry the extension or not. They return false and print why on failure. */
  bool load_node_call(FILE *infile, int markers, int uvflag, char *infilename);
  bool load_node(char *);
  bool load_edge(char *);
  bool load_face(char *);
  bool load_tet(char *);
  bool load_vol(char *);
  bool load_var(char *);
  bool load_mtr(char *);
  bool load_pbc(char *);
  bool load_poly(char *);
  bool load_off(char *);
  bool load_ply(char *);
  bool load_stl(char *);
  bool load_vtk(char *);
  bool load_medit(char *, int);
  bool load_plc(char *, int);
  bool load_tetmesh(char *, int);
  void save_nodes(char *);
  void save_elements(char *);
  void save_faces(char *);
  void save_edges(char *);
  void save_neighbors(char *);
  void save_poly(char *);
  void save_faces2smesh(char *);

  /* TetGen's line helpers (as in TetGen 1.5): readline returns the next line that is not
   * blank (at its first non-blank character; comments are not skipped), NULL at the end of
   * the file, counting lines in *linenumber when not NULL; findnextfield skips the current
   * field and the separators after it (blanks, ',', ';'); readnumberline returns the next
   * line with a number before any '#', at that number (the file name is unused);
   * findnextnumber skips the current number and whatever follows up to the next number,
   * returning the end of the string at a '#' (which it overwrites with '\0'). */
  char *readline(char *string, FILE *infile, int *linenumber);
  char *findnextfield(char *string);
  char *readnumberline(char *string, FILE *infile, char *infilename);
  char *findnextnumber(char *string);

  static void init(polygon *p) {
    p->vertexlist = NULL;
    p->numberofvertices = 0;
  }
  static void init(facet *f) {
    f->polygonlist = NULL;
    f->numberofpolygons = 0;
    f->holelist = NULL;
    f->numberofholes = 0;
  }

  void initialize() {
    firstnumber = 0;
    mesh_dim = 3;
    useindex = 1;
    pointlist = pointattributelist = pointmtrlist = NULL;
    pointmarkerlist = NULL;
    pointparamlist = NULL;
    numberofpoints = numberofpointattributes = numberofpointmtrs = 0;
    tetrahedronlist = NULL;
    tetrahedronattributelist = tetrahedronvolumelist = NULL;
    neighborlist = NULL;
    numberoftetrahedra = 0;
    numberofcorners = 4;
    numberoftetrahedronattributes = 0;
    facetlist = NULL;
    facetmarkerlist = NULL;
    numberoffacets = 0;
    holelist = NULL;
    numberofholes = 0;
    regionlist = NULL;
    numberofregions = 0;
    facetconstraintlist = NULL;
    numberoffacetconstraints = 0;
    segmentconstraintlist = NULL;
    numberofsegmentconstraints = 0;
    trifacelist = trifacemarkerlist = o2facelist = adjtetlist = NULL;
    numberoftrifaces = 0;
    edgelist = edgemarkerlist = o2edgelist = edgeadjtetlist = NULL;
    numberofedges = 0;
    vpointlist = NULL;
    vedgelist = NULL;
    vfacetlist = NULL;
    vcelllist = NULL;
    numberofvpoints = numberofvedges = numberofvfacets = numberofvcells = 0;
    geomhandle = NULL;
    getvertexparamonedge = NULL;
    getsteineronedge = NULL;
    getvertexparamonface = NULL;
    getedgesteinerparamonface = NULL;
    getsteineronface = NULL;
    tetunsuitable = NULL;
#ifndef IDMESH_TETGEN_LAYOUT_1_5
    point2tetlist = tet2facelist = tet2edgelist = face2edgelist = NULL;
#endif
  }

  /* Frees every array (all were allocated with new[]) and leaves the object initialized. */
  void clean_memory() {
    delete[] pointlist;
    delete[] pointattributelist;
    delete[] pointmtrlist;
    delete[] pointmarkerlist;
    delete[] pointparamlist;
    delete[] tetrahedronlist;
    delete[] tetrahedronattributelist;
    delete[] tetrahedronvolumelist;
    delete[] neighborlist;
    delete[] trifacelist;
    delete[] trifacemarkerlist;
    delete[] o2facelist;
    delete[] adjtetlist;
    delete[] edgelist;
    delete[] edgemarkerlist;
    delete[] o2edgelist;
    delete[] edgeadjtetlist;
    if (facetlist != NULL) {
      for (int i = 0; i < numberoffacets; i++) {
        facet *f = &facetlist[i];
        if (f->polygonlist != NULL) {
          for (int j = 0; j < f->numberofpolygons; j++) {
            delete[] f->polygonlist[j].vertexlist;
          }
        }
        delete[] f->polygonlist;
        delete[] f->holelist;
      }
      delete[] facetlist;
    }
    delete[] facetmarkerlist;
    delete[] holelist;
    delete[] regionlist;
    delete[] facetconstraintlist;
    delete[] segmentconstraintlist;
    delete[] vpointlist;
    delete[] vedgelist;
    if (vfacetlist != NULL) {
      for (int i = 0; i < numberofvfacets; i++) {
        delete[] vfacetlist[i].elist;
      }
      delete[] vfacetlist;
    }
    if (vcelllist != NULL) {
      for (int i = 0; i < numberofvcells; i++) {
        delete[] vcelllist[i];
      }
      delete[] vcelllist;
    }
#ifndef IDMESH_TETGEN_LAYOUT_1_5
    delete[] point2tetlist;
    delete[] tet2facelist;
    delete[] tet2edgelist;
    delete[] face2edgelist;
#endif
    initialize();
  }

  void deinitialize() { clean_memory(); }

  tetgenio() { initialize(); }
  ~tetgenio() { deinitialize(); }
};

class tetgenbehavior {
public:
  int plc;
  int psc;
  int refine;
  int quality;
  int nobisect;
  int coarsen;
  int weighted;
  int brio_hilbert;
  int incrflip;
  int flipinsert;
  int metric;
  int varvolume;
  int fixedvolume;
  int regionattrib;
  int conforming;
  int insertaddpoints;
  int diagnose;
  int convex;
  int nomergefacet;
  int nomergevertex;
  int noexact;
  int nostaticfilter;
  int zeroindex;
  int facesout;
  int edgesout;
  int neighout;
  int voroout;
  int meditview;
  int vtkview;
  int nobound;
  int nonodewritten;
  int noelewritten;
  int nofacewritten;
  int noiterationnum;
  int nojettison;
  int reversetetori;
  int docheck;
  int quiet;
  int verbose;

  int vertexperblock;
  int tetrahedraperblock;
  int shellfaceperblock;
  int nobisect_param;
  int addsteiner_algo;
  int coarsen_param;
  int weighted_param;
  int fliplinklevel;
  int flipstarsize;
  int fliplinklevelinc;
  int reflevel;
  int optlevel;
  int optscheme;
  int delmaxfliplevel;
  int order;
  int steinerleft;
  int no_sort;
  int hilbert_order;
  int hilbert_limit;
  int brio_threshold;
  REAL brio_ratio;
  REAL facet_ang_tol;
  REAL maxvolume;
  REAL minratio;
  REAL mindihedral;
  REAL optmaxdihedral;
  REAL optminsmtdihed;
  REAL optminslidihed;
  REAL epsilon;
  REAL minedgelength;
  REAL coarsen_percent;

  char commandline[1024];
  char infilename[1024];
  char outfilename[1024];
  char addinfilename[1024];
  char bgmeshfilename[1024];

  enum objecttype { NODES, POLY, OFF, PLY, STL, MEDIT, VTK, MESH } object;

  void syntax();
  void usage();

  /* Parses TetGen's command line (argv[0] is the program name; one argument not starting
   * with '-' is the input file) with idmesh's switch parser. With argc == 0, argv[0] is a
   * switch string without '-' (what parse_commandline(char*) passes). Returns false, after
   * printing why unless Q, on a bad or unsupported switch. */
  bool parse_commandline(int argc, char **argv);
  bool parse_commandline(char *switches) { return parse_commandline(0, &switches); }

  tetgenbehavior();
};

#ifdef IDMESH_TETGEN_LAYOUT_1_5
/* Only for binary compatibility with programs built against TetGen 1.5's header, whose
 * inline terminatetetgen() names these destructors; idmesh never creates these objects. */
class tetgenmesh {
public:
  class arraypool {
  public:
    ~arraypool();
  };
  class memorypool {
  public:
    ~memorypool();
  };
};
#endif

void tetrahedralize(tetgenbehavior *b, tetgenio *in, tetgenio *out, tetgenio *addin = NULL,
                    tetgenio *bgmin = NULL);
void tetrahedralize(char *switches, tetgenio *in, tetgenio *out, tetgenio *addin = NULL,
                    tetgenio *bgmin = NULL);

#endif /* tetgenH */
