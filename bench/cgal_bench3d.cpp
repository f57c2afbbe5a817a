// CGAL side of bench/bench3d.py. Times only the Delaunay construction and prints one JSON line.
//
//   cgal_bench3d POINTS.bin
//
// POINTS.bin: raw little-endian doubles x0 y0 z0 x1 y1 z1 ... (written by bench3d.py).
// Kernel: Exact_predicates_inexact_constructions_kernel (Epick), the kernel CGAL recommends for
// triangulations. Delaunay_triangulation_3::insert(begin, end) spatially sorts the range first
// (CGAL's spatial_sort: BRIO + Hilbert), as CGAL users do; the sort is inside the timed call.
//
// input_hash is the same order-sensitive hash as examples/bench3d_points.rs, so the script can
// check that every tool triangulated bit-identical input.

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point;
typedef CGAL::Delaunay_triangulation_3<K> DT;

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

// Resets VmHWM so that the peak read after the call covers the call only.
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

uint64_t input_hash(const std::vector<double>& xyz) {
  uint64_t h = 0;
  for (size_t i = 0; i < xyz.size(); ++i) {
    uint64_t w;
    std::memcpy(&w, &xyz[i], 8);
    h += mix64(w ^ (i * 0x9E3779B97F4A7C15ULL));
  }
  return h;
}

int fail(const std::string& msg) {
  std::printf("{\"tool\":\"cgal\",\"error\":\"%s\"}\n", msg.c_str());
  std::fprintf(stderr, "cgal_bench3d: %s\n", msg.c_str());
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) return fail("usage: cgal_bench3d POINTS.bin");
  std::ifstream f(argv[1], std::ios::binary);
  if (!f) return fail(std::string("cannot read ") + argv[1]);
  std::vector<char> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (bytes.size() % 24 != 0) return fail(std::string(argv[1]) + ": size is not a multiple of 24");
  std::vector<double> xyz(bytes.size() / 8);
  std::memcpy(xyz.data(), bytes.data(), bytes.size());
  std::vector<char>().swap(bytes);
  std::vector<Point> pts;
  pts.reserve(xyz.size() / 3);
  for (size_t i = 0; i + 2 < xyz.size(); i += 3) pts.emplace_back(xyz[i], xyz[i + 1], xyz[i + 2]);
  uint64_t hash = input_hash(xyz);
  std::vector<double>().swap(xyz);

  Status before = proc_status();
  bool hwm = reset_hwm();
  auto t0 = std::chrono::steady_clock::now();
  DT dt;
  dt.insert(pts.begin(), pts.end());
  auto t1 = std::chrono::steady_clock::now();
  Status after = proc_status();

  std::printf(
      "{\"tool\":\"cgal\",\"time_s\":%.6f,\"vertices\":%zu,\"tets\":%zu,\"hull_faces\":%zu,"
      "\"input_hash\":\"%016llx\",\"input_points\":%zu,\"rss_before_kb\":%ld,"
      "\"hwm_before_kb\":%ld,\"hwm_after_kb\":%ld,\"rss_after_kb\":%ld,\"hwm_reset\":%s}\n",
      std::chrono::duration<double>(t1 - t0).count(), dt.number_of_vertices(),
      dt.number_of_finite_cells(), dt.number_of_cells() - dt.number_of_finite_cells(),
      (unsigned long long)hash, pts.size(), before.rss_kb, before.hwm_kb, after.hwm_kb,
      after.rss_kb, hwm ? "true" : "false");
  return 0;
}
