// TetGen's library interface over idmesh's C ABI (see tetgen.h for what is supported).
//
// This file translates only: tetgenio arrays to idm_mesher3d calls and back, tetgenbehavior
// fields to idmesh's switch parser (the one behind `idmesh tetgen`) and back, and idmesh's
// errors to TetGen's thrown int codes. The meshing, the switch parsing, the file reading and
// the writing of output files are idmesh's. Every exception is thrown from C++ frames only:
// idmesh calls return a status, and a C++ exception from the user's tetunsuitable is caught in
// the callback and rethrown after idmesh has returned.
#include "tetgen.h"

#include <idmesh.h>

#include <cmath>
#include <exception>
#include <new>
#include <string>
#include <unordered_map>
#include <vector>

#ifdef IDMESH_TETGEN_LAYOUT_1_5
// Programs built against Debian's libtet1.5-dev allocate these objects themselves (tetgenio
// on the stack, tetgenbehavior too): the sizes must be TetGen 1.5.0's on x86-64.
#if defined(__x86_64__) && defined(__LP64__)
static_assert(sizeof(tetgenio) == 392, "tetgenio must have TetGen 1.5.0's layout");
static_assert(sizeof(tetgenbehavior) == 5456, "tetgenbehavior must have TetGen 1.5.0's layout");
#endif

// Named by TetGen 1.5's inline terminatetetgen(), which programs compile into themselves;
// idmesh creates no such objects, so there is nothing to release.
tetgenmesh::arraypool::~arraypool() {}
tetgenmesh::memorypool::~memorypool() {}
#endif

namespace {

// Owners of the C ABI's handles, so that a throw frees them.
struct Mesher {
  idm_mesher3d *m = nullptr;
  Mesher() {
    if (idm_mesher3d_new(&m) != IDM_OK) throw 1;
  }
  ~Mesher() { idm_mesher3d_free(m); }
  Mesher(const Mesher &) = delete;
  Mesher &operator=(const Mesher &) = delete;
};

struct Extra {
  idm_tetgen_extra *e = nullptr;
  Extra() {
    if (idm_tetgen_extra_new(&e) != IDM_OK) throw 1;
  }
  ~Extra() { idm_tetgen_extra_free(e); }
  Extra(const Extra &) = delete;
  Extra &operator=(const Extra &) = delete;
};

struct Plc {
  idm_plc3d *p = nullptr;
  ~Plc() { idm_plc3d_free(p); }
};

// Prints the message unless quiet and throws TetGen's code.
[[noreturn]] void fail(int code, bool quiet) {
  if (!quiet) fprintf(stderr, "Error:  %s\n", idm_last_error());
  throw code;
}

// TetGen's code for a failed status whose cause is not known more precisely.
int code_of(idm_status s) {
  switch (s) {
  case IDM_ERR_INTERNAL:
    return 2;
  default:
    return 10;
  }
}

bool has_suffix(const std::string &s, const char *suffix) {
  size_t n = strlen(suffix);
  return s.size() >= n && s.compare(s.size() - n, n, suffix) == 0;
}

template <class T> T *new_array(size_t n) { return n == 0 ? nullptr : new T[n]; }

// Fills `io` (its arrays are replaced) with what `read` (idm_tetgen_read or
// idm_tetgen_parse_node) gives.
template <class Read> bool read_with_reader(tetgenio *io, Read read) {
  Plc plc;
  idm_plc3d_view v;
  if (read(&plc.p) != IDM_OK || idm_plc3d_arrays(plc.p, &v) != IDM_OK) {
    fprintf(stderr, "Error:  %s\n", idm_last_error());
    return false;
  }
  io->clean_memory();
  const int b = (int)v.base;
  io->firstnumber = b;
  io->numberofpoints = (int)v.num_points;
  io->pointlist = new_array<REAL>(3 * v.num_points);
  for (size_t i = 0; i < 3 * v.num_points; i++) io->pointlist[i] = v.points[i];
  if (v.point_markers != nullptr) {
    io->pointmarkerlist = new_array<int>(v.num_points);
    for (size_t i = 0; i < v.num_points; i++) io->pointmarkerlist[i] = v.point_markers[i];
  }
  if (v.num_point_attributes > 0) {
    size_t n = v.num_point_attributes * v.num_points;
    io->numberofpointattributes = (int)v.num_point_attributes;
    io->pointattributelist = new_array<REAL>(n);
    for (size_t i = 0; i < n; i++) io->pointattributelist[i] = v.point_attributes[i];
  }
  io->numberoffacets = (int)v.num_facets;
  io->facetlist = new_array<tetgenio::facet>(v.num_facets);
  io->facetmarkerlist = new_array<int>(v.num_facets);
  for (size_t f = 0; f < v.num_facets; f++) {
    tetgenio::facet *fa = &io->facetlist[f];
    tetgenio::init(fa);
    io->facetmarkerlist[f] = v.facet_markers[f];
    size_t p0 = v.facet_polygon_offsets[f], p1 = v.facet_polygon_offsets[f + 1];
    fa->numberofpolygons = (int)(p1 - p0);
    fa->polygonlist = new_array<tetgenio::polygon>(p1 - p0);
    for (size_t k = p0; k < p1; k++) {
      tetgenio::polygon *p = &fa->polygonlist[k - p0];
      tetgenio::init(p);
      size_t i0 = v.polygon_offsets[k], i1 = v.polygon_offsets[k + 1];
      p->numberofvertices = (int)(i1 - i0);
      p->vertexlist = new_array<int>(i1 - i0);
      for (size_t i = i0; i < i1; i++) p->vertexlist[i - i0] = (int)v.polygon_indices[i] + b;
    }
    size_t h0 = v.facet_hole_offsets[f], h1 = v.facet_hole_offsets[f + 1];
    fa->numberofholes = (int)(h1 - h0);
    fa->holelist = new_array<REAL>(3 * (h1 - h0));
    for (size_t i = 3 * h0; i < 3 * h1; i++) fa->holelist[i - 3 * h0] = v.facet_holes[i];
  }
  io->numberofholes = (int)v.num_holes;
  io->holelist = new_array<REAL>(3 * v.num_holes);
  for (size_t i = 0; i < 3 * v.num_holes; i++) io->holelist[i] = v.holes[i];
  io->numberofregions = (int)v.num_regions;
  io->regionlist = new_array<REAL>(5 * v.num_regions);
  for (size_t i = 0; i < 5 * v.num_regions; i++) io->regionlist[i] = v.regions[i];
  return true;
}

// Reads `path` with idmesh's readers into `io` (its arrays are replaced).
bool read_into(tetgenio *io, const std::string &path) {
  return read_with_reader(io, [&](idm_plc3d **p) { return idm_tetgen_read(path.c_str(), p); });
}

// Reads `name`, adding `ext` when it does not end with it already.
bool read_with(tetgenio *io, const char *name, const char *ext) {
  std::string path = name;
  if (!has_suffix(path, ext)) path += ext;
  return read_into(io, path);
}


// The switch string equivalent to the fields of `b`, for idmesh's parser: every field that
// differs from what the switches would set is spelled as its switch, so that a field idmesh
// does not implement is refused by name rather than ignored.
std::string switch_string(const tetgenbehavior *b) {
  std::string s;
  char num[64];
  auto flag = [&s](int on, const char *letters) {
    if (on) s += letters;
  };
  flag(b->plc, "p");
  if (b->facet_ang_tol != 179.9) {
    snprintf(num, sizeof num, " p%.17g ", b->facet_ang_tol);
    s += num;
  }
  flag(b->psc, "s");
  flag(b->refine, "r");
  if (b->quality) {
    snprintf(num, sizeof num, " q%.17g", b->minratio);
    s += num;
    if (b->mindihedral != 0.0) {
      snprintf(num, sizeof num, "/%.17g", b->mindihedral);
      s += num;
    }
    s += ' ';
  }
  flag(b->nobisect, "Y");
  flag(b->coarsen || b->reversetetori, "R");
  flag(b->weighted, "w");
  flag(b->incrflip, "l");
  flag(b->flipinsert, "L");
  flag(b->metric, "m");
  flag(b->varvolume, "a");
  if (b->fixedvolume) {
    snprintf(num, sizeof num, " a%.17g ", b->maxvolume);
    s += num;
  }
  flag(b->regionattrib, "A");
  flag(b->insertaddpoints, "i");
  flag(b->diagnose, "d");
  flag(b->convex, "c");
  flag(b->nomergefacet || b->nomergevertex, "M");
  flag(b->noexact || b->nostaticfilter, "X");
  flag(b->zeroindex, "z");
  flag(b->facesout, "f");
  flag(b->edgesout, "e");
  for (int i = 0; i < b->neighout && i < 2; i++) s += "n";
  flag(b->voroout, "v");
  flag(b->meditview, "g");
  flag(b->vtkview, "k");
  flag(b->nobound, "B");
  flag(b->nonodewritten, "N");
  flag(b->noelewritten, "E");
  flag(b->nofacewritten, "F");
  flag(b->noiterationnum, "I");
  flag(b->docheck, "C");
  flag(b->quiet, "Q");
  flag(b->verbose, "V");
  if (b->order != 1) {
    snprintf(num, sizeof num, " o%d ", b->order);
    s += num;
  }
  // Mesh optimisation (O, o/): idmesh's default is none (optlevel 0, see the constructor);
  // the level is spelled whenever a field differs, so that o/ alone does not imply O here.
  if (b->optlevel != 0 || b->optscheme != 7 || b->optmaxdihedral != 165.0) {
    snprintf(num, sizeof num, " O%d/%d ", b->optlevel, b->optscheme);
    s += num;
  }
  if (b->optmaxdihedral != 165.0) {
    snprintf(num, sizeof num, " o/%.17f ", b->optmaxdihedral);
    s += num;
  }
  // TetGen's default epsilon stands for "no -T": idmesh decides coplanarity exactly unless a
  // tolerance is asked for (see `apply` for an explicit -T1e-8).
  if (b->epsilon != 1.0e-8) {
    snprintf(num, sizeof num, " T%.17g ", b->epsilon);
    s += num;
  }
  if (b->steinerleft >= 0) {
    snprintf(num, sizeof num, " S%d ", b->steinerleft);
    s += num;
  }
  return s;
}

// Sets the fields of `b` that the parsed switches describe.
void apply(tetgenbehavior *b, const idm_tetgen_switches &w) {
  b->plc = w.plc;
  b->quality = w.radius_edge > 0;
  if (w.radius_edge > 0) b->minratio = w.radius_edge;
  b->varvolume = w.region_volume;
  b->fixedvolume = w.max_volume > 0;
  if (w.max_volume > 0) b->maxvolume = w.max_volume;
  b->regionattrib = w.region_attributes;
  b->steinerleft = w.max_steiner < 0 ? -1 : (int)(w.max_steiner > 2147483647 ? 2147483647 : w.max_steiner);
  b->nobisect = w.keep_surface;
  b->nomergefacet = w.no_merge;
  b->zeroindex = w.zero_based;
  b->facesout = w.all_faces;
  b->edgesout = w.edges;
  b->neighout = w.neighbors;
  b->nonodewritten = w.no_node;
  b->noelewritten = w.no_ele;
  b->nofacewritten = w.no_face;
  b->nobound = w.no_markers;
  b->noiterationnum = w.no_iteration;
  b->diagnose = w.detect;
  b->docheck = w.check;
  b->quiet = w.quiet;
  b->verbose = w.verbose;
  b->vtkview = w.vtk;
  b->meditview = w.medit;
  b->refine = w.refine;
  b->insertaddpoints = w.insert_points;
  b->metric = w.metric;
  b->order = w.order2 ? 2 : 1;
  b->convex = w.convex_hull;
  // An explicit -T (or -T1e-8) is kept one ulp above TetGen's default, which stands for "not
  // given" in `switch_string`: the same tolerance, not lost on the way back.
  if (w.coplanar_tolerance > 0)
    b->epsilon = w.coplanar_tolerance == 1.0e-8 ? std::nextafter(1.0e-8, 1.0) : w.coplanar_tolerance;
  b->optlevel = w.optimize_level;
  b->optscheme = w.optimize_scheme;
  b->optmaxdihedral = w.optimize_max_dihedral;
  b->mindihedral = w.min_dihedral > 0 ? w.min_dihedral : 0.0;
}

// The user's tetunsuitable as idmesh's sizing callback. A C++ exception it throws must not
// cross idmesh's frames: it is kept, the callback answers "suitable" from then on, and the
// exception is rethrown once idmesh has returned.
struct Sizing {
  tetgenio::TetSizeFunc f;
  std::exception_ptr error;
};

extern "C" int32_t call_tetunsuitable(void *user, const double *a, const double *b,
                                      const double *c, const double *d, double volume) {
  Sizing *s = static_cast<Sizing *>(user);
  if (s->error) return 0;
  try {
    REAL p[4][3];
    const double *q[4] = {a, b, c, d};
    for (int i = 0; i < 4; i++)
      for (int k = 0; k < 3; k++) p[i][k] = q[i][k];
    REAL elen[6];
    const int e[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
    for (int i = 0; i < 6; i++) {
      REAL s2 = 0;
      for (int k = 0; k < 3; k++) {
        REAL t = p[e[i][0]][k] - p[e[i][1]][k];
        s2 += t * t;
      }
      elen[i] = s2;
    }
    return s->f(p[0], p[1], p[2], p[3], elen, volume) ? 1 : 0;
  } catch (...) {
    s->error = std::current_exception();
    return 0;
  }
}

// Loads `in` into the mesher (indices shifted from in->firstnumber to 0).
void load_input(Mesher &mh, const tetgenio *in, bool quiet) {
  idm_mesher3d *m = mh.m;
  auto check = [quiet](idm_status s) {
    if (s != IDM_OK) fail(code_of(s), quiet);
  };
  if (in->numberofpoints < 0) {
    idm_tetgen_report("numberofpoints is negative");
    fail(10, quiet);
  }
  check(idm_mesher3d_add_points(m, in->pointlist, (size_t)in->numberofpoints,
                                in->pointmarkerlist));
  const int b = in->firstnumber;
  std::vector<uint32_t> idx;
  std::vector<size_t> offsets;
  for (int f = 0; f < in->numberoffacets; f++) {
    const tetgenio::facet &fa = in->facetlist[f];
    idx.clear();
    offsets.assign(1, 0);
    for (int k = 0; k < fa.numberofpolygons; k++) {
      const tetgenio::polygon &p = fa.polygonlist[k];
      for (int i = 0; i < p.numberofvertices; i++) idx.push_back((uint32_t)(p.vertexlist[i] - b));
      offsets.push_back(idx.size());
    }
    int marker = in->facetmarkerlist ? in->facetmarkerlist[f] : 0;
    check(idm_mesher3d_add_facet(m, idx.data(), offsets.data(), (size_t)fa.numberofpolygons,
                                 fa.holelist, (size_t)(fa.numberofholes > 0 ? fa.numberofholes : 0),
                                 marker));
  }
  // As TetGen: input edges (edgelist, e.g. from load_edge) are segments of the PLC.
  if (in->numberofedges > 0 && in->edgelist != nullptr) {
    idx.clear();
    for (int i = 0; i < 2 * in->numberofedges; i++) idx.push_back((uint32_t)(in->edgelist[i] - b));
    check(idm_mesher3d_add_segments(m, idx.data(), (size_t)in->numberofedges,
                                    in->edgemarkerlist));
  }
  for (int h = 0; h < in->numberofholes; h++) check(idm_mesher3d_add_hole(m, &in->holelist[3 * h]));
  for (int r = 0; r < in->numberofregions; r++) {
    const REAL *q = &in->regionlist[5 * r];
    check(idm_mesher3d_add_region(m, q, q[3], q[4]));
  }
}

// Gives idmesh what r, i, m and point attributes take from `in`, `addin` and `bgmin`.
void load_extra(idm_tetgen_extra *e, const idm_tetgen_switches &w, const tetgenio *in,
                const tetgenio *addin, const tetgenio *bgmin) {
  const bool quiet = w.quiet != 0;
  auto check = [quiet](idm_status s) {
    if (s != IDM_OK) fail(code_of(s), quiet);
  };
  auto count = [](int n) { return (size_t)(n > 0 ? n : 0); };
  const uint32_t b = in->firstnumber == 1 ? 1 : 0;
  if (w.refine) {
    if (in->tetrahedronlist == nullptr || in->numberoftetrahedra <= 0) {
      idm_tetgen_report("-r: the input has no tetrahedra (tetrahedronlist) to refine");
      fail(10, quiet);
    }
    check(idm_tetgen_extra_set_mesh(
        e, in->tetrahedronlist, count(in->numberoftetrahedra), count(in->numberofcorners),
        in->tetrahedronattributelist, count(in->numberoftetrahedronattributes),
        in->tetrahedronvolumelist, in->trifacelist, in->trifacemarkerlist,
        in->trifacelist != nullptr ? count(in->numberoftrifaces) : 0, b));
  }
  if (w.insert_points && addin != nullptr && addin->pointlist != nullptr)
    check(idm_tetgen_extra_set_addin(e, addin->pointlist, count(addin->numberofpoints)));
  if (w.metric) {
    const tetgenio *src = bgmin != nullptr && bgmin->pointmtrlist != nullptr ? bgmin : in;
    if (src->pointmtrlist == nullptr) {
      idm_tetgen_report("-m: no sizes given (pointmtrlist of the input or of bgmin)");
      fail(10, quiet);
    }
    // The input's own tetrahedra are its background mesh only with r.
    const bool tets = src != in || w.refine;
    check(idm_tetgen_extra_set_metric(
        e, src->pointlist, count(src->numberofpoints), src->pointmtrlist,
        count(src->numberofpointmtrs), tets ? src->tetrahedronlist : nullptr,
        tets && src->tetrahedronlist != nullptr ? count(src->numberoftetrahedra) : 0,
        count(src->numberofcorners), src->firstnumber == 1 ? 1 : 0));
  }
  if (in->numberoffacetconstraints > 0 || in->numberofsegmentconstraints > 0)
    check(idm_tetgen_extra_set_constraints(
        e, in->facetconstraintlist,
        in->facetconstraintlist != nullptr ? count(in->numberoffacetconstraints) : 0,
        in->segmentconstraintlist,
        in->segmentconstraintlist != nullptr ? count(in->numberofsegmentconstraints) : 0, b));
  if (in->numberofpointattributes > 0 && in->pointattributelist != nullptr)
    check(idm_tetgen_extra_set_point_attributes(e, in->pointattributelist,
                                                count(in->numberofpoints),
                                                count(in->numberofpointattributes)));
}

uint64_t edge_key(uint32_t a, uint32_t b) {
  if (a > b) std::swap(a, b);
  return ((uint64_t)a << 32) | b;
}

struct FaceKey {
  uint32_t v[3];
  bool operator==(const FaceKey &o) const {
    return v[0] == o.v[0] && v[1] == o.v[1] && v[2] == o.v[2];
  }
};
struct FaceHash {
  size_t operator()(const FaceKey &k) const {
    return (size_t)k.v[0] * 0x9E3779B97F4A7C15ULL ^ (size_t)k.v[1] * 0xC2B2AE3D27D4EB4FULL ^
           (size_t)k.v[2];
  }
};
FaceKey face_key(uint32_t a, uint32_t b, uint32_t c) {
  if (a > b) std::swap(a, b);
  if (b > c) std::swap(b, c);
  if (a > b) std::swap(a, b);
  return FaceKey{{a, b, c}};
}

// Corners of the face opposite corner i, and the 6 edges, of a tetrahedron.
const int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
const int kEdge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};

// Fills `out` from the mesh as TetGen fills it for the switches `w`.
void fill_output(idm_mesher3d *m, idm_tetgen_extra *ex, const idm_tetgen_switches &w,
                 const tetgenio *in, tetgenio *out) {
  auto check = [&w](idm_status s) {
    if (s != IDM_OK) fail(code_of(s), w.quiet != 0);
  };
  const double *xyz;
  const int32_t *vmark;
  const uint32_t *tets, *nbr, *faces, *edges;
  const int32_t *fmark, *emark;
  const double *attr;
  size_t nv, nt, nf, ne, na;
  check(idm_mesher3d_vertices(m, &xyz, &nv));
  check(idm_mesher3d_vertex_markers(m, &vmark, &nv));
  check(idm_mesher3d_tets(m, &tets, &nt));
  check(idm_mesher3d_neighbors(m, &nbr, &nt));
  check(idm_mesher3d_faces(m, &faces, &fmark, &nf));
  check(idm_mesher3d_edges(m, &edges, &emark, &ne));
  check(idm_mesher3d_tet_attributes(m, &attr, &na));
  idm_tetgen_extra_view xv;
  check(idm_tetgen_extra_output(ex, &xv));

  // With o2 the edge nodes follow the vertices, and each tetrahedron lists 10 nodes.
  const size_t np = nv + xv.num_order2_nodes;
  const int b = w.zero_based ? 0 : in->firstnumber;
  out->firstnumber = b;
  out->mesh_dim = 3;
  out->numberofpoints = (int)np;
  out->pointlist = new_array<REAL>(3 * np);
  for (size_t i = 0; i < 3 * nv; i++) out->pointlist[i] = xyz[i];
  for (size_t i = 0; i < 3 * xv.num_order2_nodes; i++)
    out->pointlist[3 * nv + i] = xv.order2_nodes[i];
  if (!w.no_markers) {
    out->pointmarkerlist = new_array<int>(np);
    for (size_t i = 0; i < np; i++) out->pointmarkerlist[i] = i < nv ? vmark[i] : 0;
  }
  if (xv.num_point_attributes > 0) {
    size_t k = xv.num_point_attributes;
    out->numberofpointattributes = (int)k;
    out->pointattributelist = new_array<REAL>(k * np);
    for (size_t i = 0; i < k * np; i++) out->pointattributelist[i] = xv.point_attributes[i];
  }
  out->numberoftetrahedra = (int)nt;
  const size_t nc = xv.tets10 != nullptr ? 10 : 4;
  const uint32_t *tnodes = xv.tets10 != nullptr ? xv.tets10 : tets;
  out->numberofcorners = (int)nc;
  out->tetrahedronlist = new_array<int>(nc * nt);
  for (size_t i = 0; i < nc * nt; i++) out->tetrahedronlist[i] = (int)tnodes[i] + b;
  if (w.region_attributes && na == nt && nt > 0) {
    out->numberoftetrahedronattributes = 1;
    out->tetrahedronattributelist = new_array<REAL>(nt);
    for (size_t i = 0; i < nt; i++) out->tetrahedronattributelist[i] = attr[i];
  }
  if (w.neighbors) {
    out->neighborlist = new_array<int>(4 * nt);
    for (size_t i = 0; i < 4 * nt; i++)
      out->neighborlist[i] = nbr[i] == IDM_NONE ? -1 : (int)nbr[i] + b;
  }

  // Faces: the subfaces, or every face with f; each with its marker and adjacent tets.
  std::unordered_map<FaceKey, int32_t, FaceHash> subface_marker;
  subface_marker.reserve(nf);
  for (size_t i = 0; i < nf; i++)
    subface_marker[face_key(faces[3 * i], faces[3 * i + 1], faces[3 * i + 2])] = fmark[i];
  std::vector<uint32_t> flist;   // 3 per output face
  std::vector<int32_t> fmarks;   // 1 per output face
  std::vector<int> fadj;         // 2 per output face: tets, -1 for none
  std::vector<int> tet2face;     // 4 per tet (with f)
  if (w.all_faces) {
    tet2face.assign(4 * nt, -1);
    for (size_t t = 0; t < nt; t++) {
      for (int i = 0; i < 4; i++) {
        uint32_t n = nbr[4 * t + i];
        if (n != IDM_NONE && n < t) continue;  // listed from the smaller tet
        int id = (int)fmarks.size();
        uint32_t a = tets[4 * t + kFace[i][0]], bb = tets[4 * t + kFace[i][1]],
                 c = tets[4 * t + kFace[i][2]];
        flist.insert(flist.end(), {a, bb, c});
        auto it = subface_marker.find(face_key(a, bb, c));
        fmarks.push_back(it == subface_marker.end() ? 0 : it->second);
        fadj.push_back((int)t + b);
        fadj.push_back(n == IDM_NONE ? -1 : (int)n + b);
        tet2face[4 * t + i] = id;
        if (n != IDM_NONE)
          for (int j = 0; j < 4; j++)
            if (nbr[4 * n + j] == t) tet2face[4 * n + j] = id;
      }
    }
  } else {
    flist.assign(faces, faces + 3 * nf);
    fmarks.assign(fmark, fmark + nf);
    if (w.neighbors > 1) {
      std::unordered_map<FaceKey, size_t, FaceHash> at;
      at.reserve(nf);
      for (size_t i = 0; i < nf; i++) at[face_key(faces[3 * i], faces[3 * i + 1], faces[3 * i + 2])] = i;
      fadj.assign(2 * nf, -1);
      for (size_t t = 0; t < nt; t++)
        for (int i = 0; i < 4; i++) {
          auto it = at.find(face_key(tets[4 * t + kFace[i][0]], tets[4 * t + kFace[i][1]],
                                     tets[4 * t + kFace[i][2]]));
          if (it == at.end()) continue;
          int *slot = &fadj[2 * it->second];
          if (slot[0] < 0) slot[0] = (int)t + b;
          else slot[1] = (int)t + b;
        }
    }
  }
  size_t nout = fmarks.size();
  out->numberoftrifaces = (int)nout;
  out->trifacelist = new_array<int>(3 * nout);
  for (size_t i = 0; i < 3 * nout; i++) out->trifacelist[i] = (int)flist[i] + b;
  if (!w.no_markers) {
    out->trifacemarkerlist = new_array<int>(nout);
    for (size_t i = 0; i < nout; i++) out->trifacemarkerlist[i] = fmarks[i];
  }
  if (w.neighbors > 1) {
    out->adjtetlist = new_array<int>(2 * nout);
    for (size_t i = 0; i < 2 * nout; i++) out->adjtetlist[i] = fadj[i];
  }

  // Edges with e: every mesh edge, marked with its subsegment's marker (0 inside).
  std::vector<int> tet2edge;
  std::unordered_map<uint64_t, int> edge_id;
  if (w.edges) {
    std::unordered_map<uint64_t, int32_t> seg_marker;
    seg_marker.reserve(ne);
    for (size_t i = 0; i < ne; i++) seg_marker[edge_key(edges[2 * i], edges[2 * i + 1])] = emark[i];
    std::vector<uint32_t> elist;
    std::vector<int32_t> emarks;
    std::vector<int> etet;
    tet2edge.assign(6 * nt, -1);
    edge_id.reserve(nv * 7);
    for (size_t t = 0; t < nt; t++)
      for (int i = 0; i < 6; i++) {
        uint32_t a = tets[4 * t + kEdge[i][0]], c = tets[4 * t + kEdge[i][1]];
        auto ins = edge_id.emplace(edge_key(a, c), (int)emarks.size());
        if (ins.second) {
          elist.insert(elist.end(), {a, c});
          auto it = seg_marker.find(edge_key(a, c));
          emarks.push_back(it == seg_marker.end() ? 0 : it->second);
          etet.push_back((int)t + b);
        }
        tet2edge[6 * t + i] = ins.first->second;
      }
    size_t n = emarks.size();
    out->numberofedges = (int)n;
    out->edgelist = new_array<int>(2 * n);
    for (size_t i = 0; i < 2 * n; i++) out->edgelist[i] = (int)elist[i] + b;
    if (!w.no_markers) {
      out->edgemarkerlist = new_array<int>(n);
      for (size_t i = 0; i < n; i++) out->edgemarkerlist[i] = emarks[i];
    }
    out->edgeadjtetlist = new_array<int>(n);
    for (size_t i = 0; i < n; i++) out->edgeadjtetlist[i] = etet[i];
  }

#ifndef IDMESH_TETGEN_LAYOUT_1_5
  out->point2tetlist = new_array<int>(nv);
  for (size_t i = 0; i < nv; i++) out->point2tetlist[i] = b - 1;
  for (size_t t = 0; t < nt; t++)
    for (int i = 0; i < 4; i++) out->point2tetlist[tets[4 * t + i]] = (int)t + b;
  if (w.all_faces) {
    out->tet2facelist = new_array<int>(4 * nt);
    for (size_t i = 0; i < 4 * nt; i++) out->tet2facelist[i] = tet2face[i] + b;
  }
  if (w.edges) {
    out->tet2edgelist = new_array<int>(6 * nt);
    for (size_t i = 0; i < 6 * nt; i++) out->tet2edgelist[i] = tet2edge[i] + b;
    out->face2edgelist = new_array<int>(3 * nout);
    for (size_t f = 0; f < nout; f++)
      for (int k = 0; k < 3; k++) {
        auto it = edge_id.find(edge_key(flist[3 * f + k], flist[3 * f + (k + 1) % 3]));
        out->face2edgelist[3 * f + k] = it == edge_id.end() ? b - 1 : it->second + b;
      }
  }
#endif
}

}  // namespace

tetgenbehavior::tetgenbehavior() {
  plc = psc = refine = quality = nobisect = coarsen = weighted = 0;
  brio_hilbert = 1;
  incrflip = flipinsert = metric = varvolume = fixedvolume = regionattrib = 0;
  conforming = insertaddpoints = diagnose = convex = nomergefacet = nomergevertex = 0;
  noexact = nostaticfilter = zeroindex = facesout = edgesout = neighout = voroout = 0;
  meditview = vtkview = nobound = nonodewritten = noelewritten = nofacewritten = 0;
  noiterationnum = nojettison = reversetetori = docheck = quiet = verbose = 0;
  vertexperblock = 4092;
  tetrahedraperblock = 8188;
  shellfaceperblock = 4092;
  nobisect_param = 2;
  addsteiner_algo = 1;
  coarsen_param = weighted_param = 0;
  fliplinklevel = flipstarsize = -1;
  fliplinklevelinc = 1;
  reflevel = 3;
  // TetGen optimises by default (-O2/7), giving up the Delaunay property; idmesh only when
  // asked: O in the switches or optlevel set above 0.
  optlevel = 0;
  optscheme = 7;
  delmaxfliplevel = 1;
  order = 1;
  steinerleft = -1;
  no_sort = 0;
  hilbert_order = 52;
  hilbert_limit = 8;
  brio_threshold = 64;
  brio_ratio = 0.125;
  facet_ang_tol = 179.9;
  maxvolume = -1.0;
  minratio = 2.0;
  mindihedral = 0.0;
  optmaxdihedral = 165.0;
  optminsmtdihed = optminslidihed = 179.0;
  epsilon = 1.0e-8;
  minedgelength = 0.0;
  coarsen_percent = 1.0;
  object = NODES;
  commandline[0] = infilename[0] = outfilename[0] = addinfilename[0] = bgmeshfilename[0] = '\0';
}

void tetgenbehavior::syntax() {
  printf("tetgen [-pq__a__AYSzfennNEFBIdCQVMDJ] input_file\n"
         "(idmesh: run `idmesh tetgen --help` for what each switch does)\n");
}

void tetgenbehavior::usage() {
  printf("TetGen's interface on idmesh, a quality conforming Delaunay mesher.\n");
  syntax();
}

bool tetgenbehavior::parse_commandline(int argc, char **argv) {
  std::string text, file, line;
  if (argc == 0) {
    text = argv[0] ? argv[0] : "";
    line = text;
  } else {
    line = argv[0] ? argv[0] : "";
    for (int i = 1; i < argc; i++) {
      line += ' ';
      line += argv[i];
      if (argv[i][0] == '-') {
        if (!strcmp(argv[i], "-h") || !strcmp(argv[i], "-help") || !strcmp(argv[i], "--help")) {
          usage();
          return false;
        }
        text += ' ';
        text += argv[i];
      } else {
        file = argv[i];
      }
    }
  }
  snprintf(commandline, sizeof commandline, "%s", line.c_str());
  idm_tetgen_switches w;
  if (idm_tetgen_parse_switches(text.c_str(), &w) != IDM_OK) {
    // Q takes no number, so any Q in the switches asked for quiet.
    if (text.find('Q') == std::string::npos) fprintf(stderr, "Error:  %s\n", idm_last_error());
    return false;
  }
  apply(this, w);
  if (argc > 0) {
    if (file.empty()) {
      syntax();
      return false;
    }
    int32_t is_plc = 0;
    if (idm_tetgen_resolve(file.c_str(), &w, infilename, outfilename, sizeof infilename,
                           &is_plc) != IDM_OK) {
      fprintf(stderr, "Error:  %s\n", idm_last_error());
      return false;
    }
    plc = plc || is_plc;
    std::string in = infilename;
    object = has_suffix(in, ".poly") || has_suffix(in, ".smesh") ? POLY
             : has_suffix(in, ".off")                            ? OFF
             : has_suffix(in, ".ply")                            ? PLY
             : has_suffix(in, ".stl")                            ? STL
             : has_suffix(in, ".mesh")                           ? MEDIT
             : has_suffix(in, ".vtk")                            ? VTK
                                                                 : NODES;
  }
  return true;
}

bool tetgenio::load_node(char *name) { return read_with(this, name, ".node"); }
bool tetgenio::load_off(char *name) { return read_with(this, name, ".off"); }
bool tetgenio::load_ply(char *name) { return read_with(this, name, ".ply"); }
bool tetgenio::load_stl(char *name) { return read_with(this, name, ".stl"); }
bool tetgenio::load_medit(char *name, int) { return read_with(this, name, ".mesh"); }
bool tetgenio::load_vtk(char *name) { return read_with(this, name, ".vtk"); }

namespace {
struct Items {
  idm_tetgen_items *p = nullptr;
  idm_tetgen_items_view v;
  ~Items() { idm_tetgen_items_free(p); }
};

// Reads `name` + `ext` (kind as idm_tetgen_read_items) for `io`'s points and tetrahedra.
bool read_items(const tetgenio *io, const char *name, const char *ext, int kind, Items &it) {
  std::string path = name;
  if (!has_suffix(path, ext)) path += ext;
  if (idm_tetgen_read_items(path.c_str(), kind, (size_t)(io->numberofpoints > 0 ? io->numberofpoints : 0),
                            (size_t)(io->numberoftetrahedra > 0 ? io->numberoftetrahedra : 0),
                            io->firstnumber == 1 ? 1 : 0, &it.p) != IDM_OK ||
      idm_tetgen_items_arrays(it.p, &it.v) != IDM_OK) {
    fprintf(stderr, "Error:  %s\n", idm_last_error());
    return false;
  }
  return true;
}

bool exists(const char *name, const char *ext) {
  std::string path = name;
  if (!has_suffix(path, ext)) path += ext;
  FILE *f = fopen(path.c_str(), "r");
  if (f != nullptr) fclose(f);
  return f != nullptr;
}
}  // namespace

// The .poly (else .smesh) file, and as TetGen the constraints of a .var file beside it.
bool tetgenio::load_poly(char *name) {
  std::string p = name;
  std::string stem = p;
  bool ok;
  if (has_suffix(p, ".poly") || has_suffix(p, ".smesh")) {
    stem.resize(p.rfind('.'));
    ok = read_into(this, p);
  } else {
    ok = read_into(this, exists(name, ".poly") ? p + ".poly" : p + ".smesh");
  }
  if (!ok || !exists(stem.c_str(), ".var")) return ok;
  std::vector<char> buf(stem.begin(), stem.end());
  buf.push_back('\0');
  return load_var(buf.data());
}

// Facet constraints (marker, maximum area) and segment constraints (two points numbered from
// firstnumber, maximum length), read by idmesh's .var reader.
bool tetgenio::load_var(char *name) {
  Items f, g;
  if (!read_items(this, name, ".var", 4, f) || !read_items(this, name, ".var", 5, g)) return false;
  delete[] facetconstraintlist;
  delete[] segmentconstraintlist;
  numberoffacetconstraints = (int)f.v.count;
  facetconstraintlist = new_array<REAL>(2 * f.v.count);
  for (size_t i = 0; i < f.v.count; i++) {
    facetconstraintlist[2 * i] = f.v.markers[i];
    facetconstraintlist[2 * i + 1] = f.v.values[i];
  }
  numberofsegmentconstraints = (int)g.v.count;
  segmentconstraintlist = new_array<REAL>(3 * g.v.count);
  for (size_t i = 0; i < g.v.count; i++) {
    segmentconstraintlist[3 * i] = g.v.indices[2 * i];
    segmentconstraintlist[3 * i + 1] = g.v.indices[2 * i + 1];
    segmentconstraintlist[3 * i + 2] = g.v.values[i];
  }
  return true;
}

bool tetgenio::load_tet(char *name) {
  Items it;
  if (!read_items(this, name, ".ele", 0, it)) return false;
  delete[] tetrahedronlist;
  delete[] tetrahedronattributelist;
  tetrahedronattributelist = nullptr;
  numberoftetrahedra = (int)it.v.count;
  numberofcorners = 4;
  tetrahedronlist = new_array<int>(4 * it.v.count);
  for (size_t i = 0; i < 4 * it.v.count; i++) tetrahedronlist[i] = it.v.indices[i];
  numberoftetrahedronattributes = (int)it.v.num_attributes;
  if (it.v.num_attributes > 0) {
    size_t n = it.v.num_attributes * it.v.count;
    tetrahedronattributelist = new_array<REAL>(n);
    for (size_t i = 0; i < n; i++) tetrahedronattributelist[i] = it.v.attributes[i];
  }
  return true;
}

namespace {
// Replaces `list`/`markers`/`count` with the items read (markers NULL when the file has none).
void take_items(const Items &it, int *&list, int *&markers, int &count) {
  delete[] list;
  delete[] markers;
  markers = nullptr;
  count = (int)it.v.count;
  list = new_array<int>(it.v.per_item * it.v.count);
  for (size_t i = 0; i < it.v.per_item * it.v.count; i++) list[i] = it.v.indices[i];
  if (it.v.markers != nullptr) {
    markers = new_array<int>(it.v.count);
    for (size_t i = 0; i < it.v.count; i++) markers[i] = it.v.markers[i];
  }
}
}  // namespace

bool tetgenio::load_face(char *name) {
  Items it;
  if (!read_items(this, name, ".face", 1, it)) return false;
  take_items(it, trifacelist, trifacemarkerlist, numberoftrifaces);
  return true;
}

// As TetGen: the edges (and markers) of FILE.edge, which tetrahedralize takes as segments.
bool tetgenio::load_edge(char *name) {
  Items it;
  if (!read_items(this, name, ".edge", 6, it)) return false;
  take_items(it, edgelist, edgemarkerlist, numberofedges);
  return true;
}

bool tetgenio::load_vol(char *name) {
  Items it;
  if (!read_items(this, name, ".vol", 2, it)) return false;
  delete[] tetrahedronvolumelist;
  tetrahedronvolumelist = new_array<REAL>(it.v.count);
  for (size_t i = 0; i < it.v.count; i++) tetrahedronvolumelist[i] = it.v.values[i];
  return true;
}

bool tetgenio::load_mtr(char *name) {
  Items it;
  if (!read_items(this, name, ".mtr", 3, it)) return false;
  delete[] pointmtrlist;
  numberofpointmtrs = 1;
  pointmtrlist = new_array<REAL>(it.v.count);
  for (size_t i = 0; i < it.v.count; i++) pointmtrlist[i] = it.v.values[i];
  return true;
}
// TetGen's line helpers, for programs that parse their own files with them. A number starts
// with a digit, '.', '+' or '-'; '#' starts a comment.
namespace {
bool number_start(char c) { return (c >= '0' && c <= '9') || c == '.' || c == '+' || c == '-'; }

// Skips to the next number-like character; stops (and ends the string) at a comment.
char *skip_to_number(char *s) {
  while (*s != '\0' && *s != '#' && !number_start(*s)) s++;
  if (*s == '#') *s = '\0';
  return s;
}
}  // namespace

// The points of a .node section whose header line the caller has read into numberofpoints,
// mesh_dim and numberofpointattributes (as TetGen's load_node_call): the next numberofpoints
// number lines of `infile`, parsed by idmesh's .node reader (errors name the point).
bool tetgenio::load_node_call(FILE *infile, int markers, int uvflag, char *infilename) {
  const char *name = infilename != NULL ? infilename : "(node section)";
  if (uvflag) {
    fprintf(stderr, "Error:  load_node_call: point parameters (uvflag) are not supported (%s).\n",
            name);
    return false;
  }
  if (infile == NULL || numberofpoints < 0) {
    fprintf(stderr, "Error:  load_node_call: no file or a negative point count (%s).\n", name);
    return false;
  }
  std::string text = std::to_string(numberofpoints) + " " + std::to_string(mesh_dim) + " " +
                     std::to_string(numberofpointattributes) + (markers ? " 1\n" : " 0\n");
  char line[INPUTLINESIZE];
  for (int i = 0; i < numberofpoints; i++) {
    char *s = readnumberline(line, infile, infilename);
    if (s == NULL) break;  // The reader reports the missing points.
    text += s;
    if (text.back() != '\n') text += '\n';
  }
  return read_with_reader(
      this, [&](idm_plc3d **p) { return idm_tetgen_parse_node(text.c_str(), name, p); });
}

char *tetgenio::readline(char *string, FILE *infile, int *linenumber) {
  for (;;) {
    if (fgets(string, INPUTLINESIZE - 1, infile) == NULL) return NULL;
    if (linenumber != NULL) (*linenumber)++;
    char *s = string;
    while (*s == ' ' || *s == '\t') s++;
    if (*s != '\0' && *s != '\r' && *s != '\n') return s;
  }
}

char *tetgenio::findnextfield(char *string) {
  char *s = string;
  while (*s != '\0' && *s != ' ' && *s != '\t' && *s != ',' && *s != ';') s++;
  while (*s == ' ' || *s == '\t' || *s == ',' || *s == ';') s++;
  return s;
}

char *tetgenio::readnumberline(char *string, FILE *infile, char *) {
  for (;;) {
    if (fgets(string, INPUTLINESIZE, infile) == NULL) return NULL;
    char *s = string;
    while (*s != '\0' && *s != '#' && !number_start(*s)) s++;
    if (*s != '\0' && *s != '#') return s;
  }
}

char *tetgenio::findnextnumber(char *string) {
  char *s = string;
  while (*s != '\0' && *s != '#' && *s != ' ' && *s != '\t' && *s != ',') s++;
  return skip_to_number(s);
}

// TetGen 1.5 and 1.6 declare load_pbc but define it nowhere (Debian's libtet exports no such
// symbol) and tetgenio has no periodic-boundary fields to load into: refused.
bool tetgenio::load_pbc(char *name) {
  fprintf(stderr,
          "Error:  load_pbc: periodic boundary conditions are not supported (TetGen 1.5 and "
          "1.6 do not implement them either; %s not read).\n",
          name);
  return false;
}

bool tetgenio::load_plc(char *name, int object) {
  std::string p = name;
  if (has_suffix(p, ".poly") || has_suffix(p, ".smesh")) return load_poly(name);
  for (const char *ext : {".node", ".off", ".ply", ".stl", ".mesh", ".vtk"})
    if (has_suffix(p, ext)) return read_into(this, p);
  switch (object) {
  case tetgenbehavior::NODES:
    return load_node(name);
  case tetgenbehavior::POLY:
    return load_poly(name);
  case tetgenbehavior::OFF:
    return load_off(name);
  case tetgenbehavior::PLY:
    return load_ply(name);
  case tetgenbehavior::STL:
    return load_stl(name);
  case tetgenbehavior::MEDIT:
    return load_medit(name, 0);
  case tetgenbehavior::VTK:
    return load_vtk(name);
  default:
    return load_poly(name);
  }
}

// The points, the tetrahedra (.ele), and when present the faces, volume bounds and sizes
// (.face, .vol, .mtr), as TetGen's load_tetmesh reads them for -r.
bool tetgenio::load_tetmesh(char *name, int object) {
  if (object == tetgenbehavior::MEDIT) return load_medit(name, 1);
  // The file name may carry the .node extension (parse_commandline resolves it so).
  std::string stem = name;
  if (has_suffix(stem, ".node")) stem.resize(stem.size() - 5);
  std::vector<char> buf(stem.begin(), stem.end());
  buf.push_back('\0');
  name = buf.data();
  if (!load_node(name) || !load_tet(name)) return false;
  if (exists(name, ".face") && !load_face(name)) return false;
  if (exists(name, ".vol") && !load_vol(name)) return false;
  if (exists(name, ".mtr") && !load_mtr(name)) return false;
  return true;
}

namespace {
FILE *open_out(const char *name, const char *ext) {
  std::string p = std::string(name) + ext;
  FILE *f = fopen(p.c_str(), "w");
  if (f == nullptr) fprintf(stderr, "Error:  cannot create %s.\n", p.c_str());
  return f;
}
}  // namespace

void tetgenio::save_nodes(char *name) {
  FILE *f = open_out(name, ".node");
  if (f == nullptr) return;
  fprintf(f, "%d  %d  %d  %d\n", numberofpoints, mesh_dim, numberofpointattributes,
          pointmarkerlist != NULL ? 1 : 0);
  for (int i = 0; i < numberofpoints; i++) {
    fprintf(f, "%d  %.17g  %.17g  %.17g", i + firstnumber, pointlist[3 * i], pointlist[3 * i + 1],
            pointlist[3 * i + 2]);
    for (int k = 0; k < numberofpointattributes; k++)
      fprintf(f, "  %.17g", pointattributelist[i * numberofpointattributes + k]);
    if (pointmarkerlist != NULL) fprintf(f, "  %d", pointmarkerlist[i]);
    fprintf(f, "\n");
  }
  fclose(f);
}

void tetgenio::save_elements(char *name) {
  FILE *f = open_out(name, ".ele");
  if (f == nullptr) return;
  fprintf(f, "%d  %d  %d\n", numberoftetrahedra, numberofcorners, numberoftetrahedronattributes);
  for (int i = 0; i < numberoftetrahedra; i++) {
    fprintf(f, "%d", i + firstnumber);
    for (int k = 0; k < numberofcorners; k++)
      fprintf(f, "  %d", tetrahedronlist[i * numberofcorners + k]);
    for (int k = 0; k < numberoftetrahedronattributes; k++)
      fprintf(f, "  %.17g", tetrahedronattributelist[i * numberoftetrahedronattributes + k]);
    fprintf(f, "\n");
  }
  fclose(f);
}

void tetgenio::save_faces(char *name) {
  FILE *f = open_out(name, ".face");
  if (f == nullptr) return;
  fprintf(f, "%d  %d\n", numberoftrifaces, trifacemarkerlist != NULL ? 1 : 0);
  for (int i = 0; i < numberoftrifaces; i++) {
    fprintf(f, "%d  %d  %d  %d", i + firstnumber, trifacelist[3 * i], trifacelist[3 * i + 1],
            trifacelist[3 * i + 2]);
    if (trifacemarkerlist != NULL) fprintf(f, "  %d", trifacemarkerlist[i]);
    fprintf(f, "\n");
  }
  fclose(f);
}

void tetgenio::save_edges(char *name) {
  FILE *f = open_out(name, ".edge");
  if (f == nullptr) return;
  fprintf(f, "%d  %d\n", numberofedges, edgemarkerlist != NULL ? 1 : 0);
  for (int i = 0; i < numberofedges; i++) {
    fprintf(f, "%d  %d  %d", i + firstnumber, edgelist[2 * i], edgelist[2 * i + 1]);
    if (edgemarkerlist != NULL) fprintf(f, "  %d", edgemarkerlist[i]);
    fprintf(f, "\n");
  }
  fclose(f);
}

void tetgenio::save_neighbors(char *name) {
  FILE *f = open_out(name, ".neigh");
  if (f == nullptr) return;
  fprintf(f, "%d  4\n", numberoftetrahedra);
  for (int i = 0; i < numberoftetrahedra; i++)
    fprintf(f, "%d  %d  %d  %d  %d\n", i + firstnumber, neighborlist[4 * i], neighborlist[4 * i + 1],
            neighborlist[4 * i + 2], neighborlist[4 * i + 3]);
  fclose(f);
}

void tetgenio::save_poly(char *name) {
  FILE *f = open_out(name, ".poly");
  if (f == nullptr) return;
  fprintf(f, "0  3  0  0\n%d  %d\n", numberoffacets, facetmarkerlist != NULL ? 1 : 0);
  for (int i = 0; i < numberoffacets; i++) {
    const facet &fa = facetlist[i];
    fprintf(f, "%d  %d", fa.numberofpolygons, fa.numberofholes);
    if (facetmarkerlist != NULL) fprintf(f, "  %d", facetmarkerlist[i]);
    fprintf(f, "\n");
    for (int k = 0; k < fa.numberofpolygons; k++) {
      const polygon &p = fa.polygonlist[k];
      fprintf(f, "%d", p.numberofvertices);
      for (int j = 0; j < p.numberofvertices; j++) fprintf(f, "  %d", p.vertexlist[j]);
      fprintf(f, "\n");
    }
    for (int h = 0; h < fa.numberofholes; h++)
      fprintf(f, "%d  %.17g  %.17g  %.17g\n", h + firstnumber, fa.holelist[3 * h],
              fa.holelist[3 * h + 1], fa.holelist[3 * h + 2]);
  }
  fprintf(f, "%d\n", numberofholes);
  for (int h = 0; h < numberofholes; h++)
    fprintf(f, "%d  %.17g  %.17g  %.17g\n", h + firstnumber, holelist[3 * h], holelist[3 * h + 1],
            holelist[3 * h + 2]);
  fprintf(f, "%d\n", numberofregions);
  for (int r = 0; r < numberofregions; r++)
    fprintf(f, "%d  %.17g  %.17g  %.17g  %.17g  %.17g\n", r + firstnumber, regionlist[5 * r],
            regionlist[5 * r + 1], regionlist[5 * r + 2], regionlist[5 * r + 3], regionlist[5 * r + 4]);
  fclose(f);
}

void tetgenio::save_faces2smesh(char *name) {
  FILE *f = open_out(name, ".smesh");
  if (f == nullptr) return;
  fprintf(f, "0  3  0  0\n%d  %d\n", numberoftrifaces, trifacemarkerlist != NULL ? 1 : 0);
  for (int i = 0; i < numberoftrifaces; i++) {
    fprintf(f, "3  %d  %d  %d", trifacelist[3 * i], trifacelist[3 * i + 1], trifacelist[3 * i + 2]);
    if (trifacemarkerlist != NULL) fprintf(f, "  %d", trifacemarkerlist[i]);
    fprintf(f, "\n");
  }
  fprintf(f, "0\n0\n");
  fclose(f);
}

void tetrahedralize(tetgenbehavior *b, tetgenio *in, tetgenio *out, tetgenio *addin,
                    tetgenio *bgmin) {
  const bool quiet0 = b != nullptr && b->quiet;
  if (b == nullptr || in == nullptr) {
    idm_tetgen_report("tetrahedralize: the tetgenbehavior or the input is NULL");
    fail(10, quiet0);
  }
  std::string text = switch_string(b);
  idm_tetgen_switches w;
  if (idm_tetgen_parse_switches(text.c_str(), &w) != IDM_OK) fail(10, quiet0);
  const bool quiet = w.quiet != 0;
  try {
    Mesher mh;
    load_input(mh, in, quiet);
    Extra ex;
    load_extra(ex.e, w, in, addin, bgmin);
    Sizing sizing{in->tetunsuitable, nullptr};
    if (in->tetunsuitable != nullptr &&
        idm_mesher3d_set_sizing(mh.m, call_tetunsuitable, &sizing) != IDM_OK)
      fail(2, quiet);
    int32_t code = 0;
    idm_status s = idm_mesher3d_tetgen(mh.m, &w, (uint32_t)(in->firstnumber == 1 ? 1 : 0), ex.e, &code);
    if (sizing.error) std::rethrow_exception(sizing.error);
    if (s == IDM_INCOMPLETE) {
      if (!quiet) fprintf(stderr, "Warning:  %s\n", idm_last_error());
    } else if (s != IDM_OK) {
      fail(code, quiet);
    }
    if (w.detect) return;
    if (out == nullptr) {
      const char *stem = b->outfilename[0] != '\0' ? b->outfilename : "tetgen-tmp";
      int base = w.zero_based ? 0 : in->firstnumber;
      if (idm_mesher3d_write_tetgen(mh.m, stem, &w, w.plc, in->pointmarkerlist != nullptr,
                                    (uint32_t)(base == 1 ? 1 : 0), ex.e) != IDM_OK)
        fail(10, quiet);
      return;
    }
    fill_output(mh.m, ex.e, w, in, out);
  } catch (const std::bad_alloc &) {
    idm_tetgen_report("out of memory");
    fail(1, quiet);
  }
}

void tetrahedralize(char *switches, tetgenio *in, tetgenio *out, tetgenio *addin,
                    tetgenio *bgmin) {
  tetgenbehavior b;
  if (!b.parse_commandline(switches)) throw 10;
  tetrahedralize(&b, in, out, addin, bgmin);
}
