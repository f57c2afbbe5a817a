// CGAL side of bench/bench2d.py. Times only the meshing call and prints one JSON line.
//
//   cgal_bench2d dt   POINTS.bin                 Delaunay_triangulation_2, range insert
//                                                (CGAL spatially sorts the range itself)
//   cgal_bench2d mesh PSLG.poly MIN_ANGLE EDGE   Constrained_Delaunay_triangulation_2 of the
//                                                PSLG, then refine_Delaunay_mesh_2 with
//                                                Delaunay_mesh_size_criteria_2(sin^2(angle), EDGE)
//
// POINTS.bin: raw little-endian doubles x0 y0 x1 y1 ... (written by bench2d.py).
// PSLG.poly: Triangle's .poly format as written by bench2d.py (0-based, no attributes).
// Kernel: Exact_predicates_inexact_constructions_kernel, the kernel CGAL recommends for
// triangulations and 2D meshing.
//
// input_hash is the same order-sensitive hash as examples/bench2d.rs, so the script can check
// that every tool meshed bit-identical input.

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_2 Point;
typedef CGAL::Delaunay_triangulation_2<K> DT;

typedef CGAL::Delaunay_mesh_vertex_base_2<K> MVb;
typedef CGAL::Delaunay_mesh_face_base_2<K> MFb;
typedef CGAL::Triangulation_data_structure_2<MVb, MFb> MTds;
typedef CGAL::Constrained_Delaunay_triangulation_2<K, MTds> CDT;
typedef CGAL::Delaunay_mesh_size_criteria_2<CDT> Criteria;

namespace {

struct Status {
  long rss_kb = 0;
  long hwm_kb = 0;
};

Status proc_status() {
  Status s;
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line)) {
    if (line.rfind("VmRSS:", 0) == 0) s.rss_kb = std::atol(line.c_str() + 6);
    if (line.rfind("VmHWM:", 0) == 0) s.hwm_kb = std::atol(line.c_str() + 6);
  }
  return s;
}

// Resets VmHWM so that the peak read after meshing covers the meshing call only.
bool reset_hwm() {
  FILE* f = std::fopen("/proc/self/clear_refs", "w");
  if (!f) return false;
  bool ok = std::fputs("5", f) >= 0;
  return std::fclose(f) == 0 && ok;
}

uint64_t mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

uint64_t input_hash(const std::vector<double>& xy, const std::vector<uint64_t>& segwords) {
  uint64_t h = 0, i = 0;
  auto add = [&](uint64_t w) {
    h += mix64(w ^ (i * 0x9E3779B97F4A7C15ULL));
    ++i;
  };
  for (double d : xy) {
    uint64_t w;
    std::memcpy(&w, &d, 8);
    add(w);
  }
  for (uint64_t w : segwords) add(w);
  return h;
}

double min_angle_deg(const Point& a, const Point& b, const Point& c) {
  auto ang = [](const Point& p, const Point& q, const Point& r) {
    double ux = q.x() - p.x(), uy = q.y() - p.y();
    double vx = r.x() - p.x(), vy = r.y() - p.y();
    return std::atan2(std::fabs(ux * vy - uy * vx), ux * vx + uy * vy) * 180.0 / M_PI;
  };
  return std::min(ang(a, b, c), std::min(ang(b, c, a), ang(c, a, b)));
}

void print_result(const char* mode, double secs, size_t nv, size_t nt, double min_ang,
                  uint64_t hash, size_t npts, const Status& before, const Status& after,
                  bool hwm_reset, const std::string& extra) {
  std::printf(
      "{\"tool\":\"cgal\",\"case\":\"%s\",\"time_s\":%.6f,\"vertices\":%zu,\"triangles\":%zu,"
      "\"min_angle\":%.6f,\"input_hash\":\"%016llx\",\"input_points\":%zu,"
      "\"rss_before_kb\":%ld,\"hwm_before_kb\":%ld,\"hwm_after_kb\":%ld,\"rss_after_kb\":%ld,\"hwm_reset\":%s%s}\n",
      mode, secs, nv, nt, min_ang, (unsigned long long)hash, npts, before.rss_kb, before.hwm_kb, after.hwm_kb,
      after.rss_kb, hwm_reset ? "true" : "false", extra.c_str());
}

int fail(const std::string& msg) {
  std::printf("{\"tool\":\"cgal\",\"error\":\"%s\"}\n", msg.c_str());
  std::fprintf(stderr, "cgal_bench2d: %s\n", msg.c_str());
  return 1;
}

int run_dt(const char* path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return fail(std::string("cannot read ") + path);
  std::vector<char> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (bytes.size() % 16 != 0) return fail(std::string(path) + ": size is not a multiple of 16");
  std::vector<double> xy(bytes.size() / 8);
  std::memcpy(xy.data(), bytes.data(), bytes.size());
  std::vector<char>().swap(bytes);
  std::vector<Point> pts;
  pts.reserve(xy.size() / 2);
  for (size_t i = 0; i + 1 < xy.size(); i += 2) pts.emplace_back(xy[i], xy[i + 1]);
  uint64_t hash = input_hash(xy, {});

  Status before = proc_status();
  bool hwm = reset_hwm();
  auto t0 = std::chrono::steady_clock::now();
  DT dt;
  dt.insert(pts.begin(), pts.end());
  auto t1 = std::chrono::steady_clock::now();
  Status after = proc_status();

  double min_ang = 180.0;
  for (auto fit = dt.finite_faces_begin(); fit != dt.finite_faces_end(); ++fit)
    min_ang = std::min(min_ang, min_angle_deg(fit->vertex(0)->point(), fit->vertex(1)->point(),
                                              fit->vertex(2)->point()));
  print_result("dt", std::chrono::duration<double>(t1 - t0).count(), dt.number_of_vertices(),
               dt.number_of_faces(), min_ang, hash, pts.size(), before, after, hwm, "");
  return 0;
}

// Reads the next non-comment line's tokens.
bool next_tokens(std::istream& in, std::vector<std::string>& toks) {
  std::string line;
  while (std::getline(in, line)) {
    auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream ss(line);
    toks.clear();
    std::string t;
    while (ss >> t) toks.push_back(t);
    if (!toks.empty()) return true;
  }
  return false;
}

int run_mesh(const char* path, double angle, double edge) {
  std::ifstream in(path);
  if (!in) return fail(std::string("cannot read ") + path);
  std::vector<std::string> t;
  std::vector<double> xy;
  std::vector<std::pair<size_t, size_t>> segs;
  std::vector<uint64_t> segwords;
  std::vector<Point> holes;
  try {
    if (!next_tokens(in, t)) return fail("empty .poly");
    size_t n = std::stoul(t.at(0));
    long base = 0;
    for (size_t i = 0; i < n; ++i) {
      if (!next_tokens(in, t)) return fail("file ends inside the vertex list");
      if (i == 0) base = std::stol(t.at(0));
      xy.push_back(std::strtod(t.at(1).c_str(), nullptr));
      xy.push_back(std::strtod(t.at(2).c_str(), nullptr));
    }
    if (!next_tokens(in, t)) return fail("missing segment header");
    size_t ns = std::stoul(t.at(0));
    for (size_t i = 0; i < ns; ++i) {
      if (!next_tokens(in, t)) return fail("file ends inside the segment list");
      size_t a = std::stol(t.at(1)) - base, b = std::stol(t.at(2)) - base;
      if (a >= n || b >= n) return fail("segment " + std::to_string(i) + " index out of range");
      segs.emplace_back(a, b);
      segwords.push_back((uint64_t(a) << 32) | uint64_t(b));
    }
    if (next_tokens(in, t)) {
      size_t nh = std::stoul(t.at(0));
      for (size_t i = 0; i < nh; ++i) {
        if (!next_tokens(in, t)) return fail("file ends inside the hole list");
        holes.emplace_back(std::strtod(t.at(1).c_str(), nullptr),
                           std::strtod(t.at(2).c_str(), nullptr));
      }
    }
  } catch (const std::exception& e) {
    return fail(std::string(path) + ": malformed .poly (" + e.what() + ")");
  }
  uint64_t hash = input_hash(xy, segwords);
  double s = std::sin(angle * M_PI / 180.0);

  Status before = proc_status();
  bool hwm = reset_hwm();
  auto t0 = std::chrono::steady_clock::now();
  CDT cdt;
  std::vector<CDT::Vertex_handle> vh;
  vh.reserve(xy.size() / 2);
  for (size_t i = 0; i + 1 < xy.size(); i += 2) vh.push_back(cdt.insert(Point(xy[i], xy[i + 1])));
  for (auto& sg : segs) cdt.insert_constraint(vh[sg.first], vh[sg.second]);
  // Seeds mark holes (seeds_are_in_domain defaults to false).
  CGAL::refine_Delaunay_mesh_2(cdt, holes.begin(), holes.end(), Criteria(s * s, edge));
  auto t1 = std::chrono::steady_clock::now();
  Status after = proc_status();

  size_t nt = 0;
  double min_ang = 180.0;
  for (auto fit = cdt.finite_faces_begin(); fit != cdt.finite_faces_end(); ++fit) {
    if (!fit->is_in_domain()) continue;
    ++nt;
    min_ang = std::min(min_ang, min_angle_deg(fit->vertex(0)->point(), fit->vertex(1)->point(),
                                              fit->vertex(2)->point()));
  }
  char extra[128];
  std::snprintf(extra, sizeof extra, ",\"shape_bound_sin2\":%.9f,\"edge_bound\":%.9g", s * s, edge);
  print_result("mesh", std::chrono::duration<double>(t1 - t0).count(), cdt.number_of_vertices(),
               nt, min_ang, hash, xy.size() / 2, before, after, hwm, extra);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 3 && std::strcmp(argv[1], "dt") == 0) return run_dt(argv[2]);
  if (argc == 5 && std::strcmp(argv[1], "mesh") == 0)
    return run_mesh(argv[2], std::strtod(argv[3], nullptr), std::strtod(argv[4], nullptr));
  return fail("usage: cgal_bench2d dt POINTS.bin | mesh PSLG.poly MIN_ANGLE EDGE_BOUND");
}
