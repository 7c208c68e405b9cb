// tools/stream_probe.cpp — how fast one core streams memory in the colored sweep's pattern: 20
// cache lines read per bundle of 8 contacts (sizeof(ContactBundle), src/solvers/nlgs_lanes.hpp),
// 2 of them written back (the impulses). A system whose bundles pass stream_bytes() is swept from
// memory, so on one thread a contact update costs at least the time of its 160 bytes here; this
// tells a slow machine's memory from slow code (docs/record/benchmarks-history.md §11.5).
//   g++ -O2 tools/stream_probe.cpp -o /tmp/stream_probe && /tmp/stream_probe [MiB]
// Prints, for an array of MiB (default 512, far beyond any last-level cache), the medians of 5
// passes: GB/s read and ns per contact's 160-byte share.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

constexpr std::size_t kLinesPerBundle = 20, kContactsPerBundle = 8, kDoublesPerLine = 8;

// One pass: every bundle's 20 lines read (two doubles each), two of them dirtied. Returns seconds.
double pass(std::vector<double>& a, double& sink) {
  const std::size_t bundles = a.size() / (kLinesPerBundle * kDoublesPerLine);
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t b = 0; b < bundles; ++b) {
    double* p = a.data() + b * kLinesPerBundle * kDoublesPerLine;
    double acc = 0.0;
    for (std::size_t k = 0; k < kLinesPerBundle * kDoublesPerLine; k += kDoublesPerLine) acc += p[k] + p[k + 1];
    sink += acc;
    p[15 * kDoublesPerLine] += 1e-9;  // the impulses' two lines
    p[16 * kDoublesPerLine] += 1e-9;
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  const long mib = argc > 1 ? std::atol(argv[1]) : 512;
  if (mib < 1 || mib > 65536) {
    std::fprintf(stderr, "stream_probe: MiB must lie in [1, 65536], got %s\n", argv[1]);
    return 2;
  }
  std::vector<double> a(static_cast<std::size_t>(mib) << 17, 1.0);  // MiB × 2^20 / 8 doubles
  const std::size_t bundles = a.size() / (kLinesPerBundle * kDoublesPerLine);
  double sink = 0.0;
  pass(a, sink);  // pages touched, caches warm
  std::vector<double> t;
  for (int r = 0; r < 5; ++r) t.push_back(pass(a, sink));
  std::sort(t.begin(), t.end());
  const double s = t[t.size() / 2], bytes = static_cast<double>(bundles * kLinesPerBundle * 64);
  std::printf("stream_probe: %ld MiB, one core: %.1f GB/s read, %.2f ns per contact (160 bytes)%s\n", mib,
              bytes / s / 1e9, s / static_cast<double>(bundles * kContactsPerBundle) * 1e9, sink == 0.0 ? " " : "");
  return 0;
}
