// examples/scene_demo/main.cpp — the paper's ballast sample and PLPLx contact detection.
//
// What it shows
//   The 724 pentagons of Saussine et al. (2006, §3) — 361 × 1 cm, 242 × 1.5 cm, 121 × 2 cm,
//   mixed by a seeded shuffle, random orientations — are placed in a box (fixed floor and
//   walls) on a square lattice, twice:
//     * loose:  pitch 1.1 × 2 cm, no two grains closer than 2 mm, above the alert distance
//               (1.25 mm): detection must find no grain–grain contact;
//     * packed: pitch 0.8 × 2 cm, below the grain size: neighbours overlap, and detection
//               reports many contact points, some of them double (edge–edge contacts, the
//               two extremities of the contact segment).
//   For each arrangement it prints the candidate pairs of the broad phase (bounding boxes on a
//   grid of tiles), the pairs in contact after the narrow phase (shadow overlap), the contact
//   points and the double contacts; then the detection time on the packed sample, and writes
//   both arrangements (grains and contact points) as VTK files for ParaView.
//
// Build
//   cmake -S . -B build && cmake --build build --target scene_demo
// Run
//   ./build/examples/scene_demo/scene_demo                       (defaults, VTK in out/scene_demo)
//   ./build/examples/scene_demo/scene_demo --config examples/scene_demo/scene_demo.cfg
//   ./build/examples/scene_demo/scene_demo --help                (every option, units, defaults)
// Then open out/scene_demo/packed_bodies.pvd and packed_contacts.pvd in ParaView.
//
// Exit status (nscd::driver::run_main): 0 on success, 2 on bad input (unknown option, unreadable
// config file, a size or factor out of range, a sample the builder refuses), 1 on any other
// failure (e.g. the output directory not writable).
//
// It is also the model of a small driver on the toolkit (shared/driver/, docs/user-guide.md
// §4.3): an Options struct, one table of options, a check, run(), and main() = run_main.
#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "nscd/interactions/plplx.hpp"
#include "nscd/io/vtk_writer.hpp"
#include "nscd/shared/driver/options.hpp"
#include "nscd/shared/driver/run_main.hpp"
#include "nscd/shared/grading.hpp"
#include "nscd/shared/samples.hpp"

using namespace nscd;

namespace {

struct Options {
  std::string output = "out/scene_demo";
  std::string seed = std::to_string(scenes::kDefaultSeed);  ///< text: "-1" must be refused, not wrapped
  double alert = Parameters{}.alert;
  double lattice_pitch_factor = scenes::kLoosePitchFactor;
  double packed_pitch_factor = scenes::kPackedPitchFactor;
  double box_width = scenes::kPaperBoxWidth;
  bool no_vtk = false;
};

// ---- step 0: options, from the command line and an optional config file -----------------
const driver::OptionTable<Options> kOptions(
    "scene_demo", "PLPLx detection on the paper's ballast sample (loose and packed)",
    {{"output", &Options::output, "directory of the VTK files (created if needed)", driver::Kind::Free, 0, "DIR"},
     {"seed", &Options::seed, "seed of the grading shuffle and of the orientations (integer >= 0)", driver::Kind::Free, 0, "N"},
     {"alert", &Options::alert, "alert distance of the detection, m (>= 0): pairs with gap <= alert are contacts", driver::Kind::Free, 0, "M"},
     {"lattice-pitch-factor", &Options::lattice_pitch_factor,
      "loose lattice: pitch / largest diameter (2 cm), > 0; above 1 + alert/2 cm no grain touches", driver::Kind::Free, 0, "F"},
     {"packed-pitch-factor", &Options::packed_pitch_factor, "packed lattice: pitch / largest diameter (2 cm), > 0; below 1 neighbours overlap",
      driver::Kind::Free, 0, "F"},
     {"box-width", &Options::box_width, "inner width of the box, m (>= 0.024: one 2 cm grain plus 2 mm clearance each side)",
      driver::Kind::Free, 0, "M"},
     {"no-vtk", &Options::no_vtk, "do not write VTK files", driver::Kind::Free, driver::kSwitch}});

// A value as messages show it: 6 significant digits ("1.1", not "1.1000000000000001").
std::string text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

using driver::require;

std::uint64_t seed_of(const Options& o) {
  std::uint64_t seed = 0;
  const char* end = o.seed.data() + o.seed.size();
  const auto [p, ec] = std::from_chars(o.seed.data(), end, seed);
  require(ec == std::errc() && p == end, "--seed must be an integer >= 0, got '" + o.seed + "'");
  return seed;
}

// Returns false when --help was asked (the help is printed).
bool parse(int argc, char** argv, Options& o) {
  if (!kOptions.parse(argc, argv, o)) return false;
  kOptions.require_finite(o);
  seed_of(o);
  const double d_max = scenes::largest_diameter(scenes::paper_grading());
  const double min_width = d_max * (1.0 + 2.0 * scenes::kClearanceFactor);
  require(o.alert >= 0.0, "--alert must be >= 0 m, got " + text(o.alert));
  require(o.lattice_pitch_factor > 0.0, "--lattice-pitch-factor must be > 0, got " + text(o.lattice_pitch_factor));
  require(o.packed_pitch_factor > 0.0, "--packed-pitch-factor must be > 0, got " + text(o.packed_pitch_factor));
  require(o.box_width >= min_width, "--box-width must be >= " + text(min_width) + " m, got " + text(o.box_width));
  require(!o.output.empty() || o.no_vtk, "--output must not be empty");
  return true;
}

// ---- detection and its report --------------------------------------------------------
struct Report {
  DetectionStats stats;
  std::size_t grain_grain_points = 0;  ///< points between two grains (not with a wall)
  double deepest_overlap = 0.0;        ///< max of −gap over the points (m), 0 if none overlap
};

bool is_wall(const scenes::Scene& s, BodyId b) { return b == s.walls.floor || b == s.walls.left || b == s.walls.right; }

Report detect(scenes::Scene& s, PlplxDetector& det) {
  Report r;
  r.stats = detect_plplx(s.reg, det);
  const ContactTable& c = s.reg.contacts;
  for (std::size_t k = 0; k < c.size(); ++k) {
    if (!is_wall(s, c.cd_body[k]) && !is_wall(s, c.an_body[k])) ++r.grain_grain_points;
    r.deepest_overlap = std::max(r.deepest_overlap, -c.gap[k]);
  }
  return r;
}

void print_layout(const scenes::Scene& s, double factor) {
  const std::size_t cols = static_cast<std::size_t>(s.lattice.columns);
  const std::size_t rows = (s.grains.size() + cols - 1) / cols;
  std::printf("   lattice pitch %.2f cm (%.2f x 2 cm): %zu columns x %zu rows, box %.3f m x %.3f m\n",
              100.0 * s.lattice.pitch_x, factor, cols, rows, s.box_width, s.box_height);
}

void print_report(const Report& r) {
  std::printf("   candidate pairs (broad phase)    %8zu\n", r.stats.candidate_pairs);
  std::printf("   contact pairs (narrow phase)     %8zu\n", r.stats.contact_pairs);
  std::printf("   contact points                   %8zu   (grain-grain: %zu)\n", r.stats.contact_points,
              r.grain_grain_points);
  std::printf("   double contacts (edge-edge)      %8zu\n", r.stats.double_contacts);
  std::printf("   deepest overlap                  %8.3f mm\n", 1e3 * r.deepest_overlap);
}

// Median wall-clock time of `runs` detections (the workspace is warm: no allocation).
double median_detection_seconds(scenes::Scene& s, PlplxDetector& det, int runs) {
  std::vector<double> t;
  for (int k = 0; k < runs; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    detect_plplx(s.reg, det);
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::nth_element(t.begin(), t.begin() + runs / 2, t.end());
  return t[static_cast<std::size_t>(runs / 2)];
}

int run(const Options& o) {
  // ---- step 1: the grading --------------------------------------------------------------
  const scenes::Grading g = scenes::paper_grading();
  std::printf("1. Grading (Saussine et al. 2006, section 3):");
  for (const auto& c : g) std::printf(" %zu x %.1f cm", c.count, 100.0 * c.diameter);
  std::printf(" = %zu pentagons, seed %llu\n", scenes::grain_count(g), static_cast<unsigned long long>(seed_of(o)));

  scenes::SampleOptions so;
  so.seed = seed_of(o);
  so.box_width = o.box_width;

  // ---- step 2: loose lattice — no contact expected ----------------------------------------
  so.pitch_factor = o.lattice_pitch_factor;
  scenes::Scene loose = scenes::paper_sample(so);
  loose.reg.params.alert = o.alert;
  PlplxDetector det_loose;
  std::printf("2. Loose sample, alert %.3f mm\n", 1e3 * o.alert);
  print_layout(loose, o.lattice_pitch_factor);
  const Report rl = detect(loose, det_loose);
  print_report(rl);
  std::printf("   -> %s\n", rl.grain_grain_points == 0 ? "no grain-grain contact, as expected"
                                                        : "grains touch: the lattice pitch is too small to be loose");

  // ---- step 3: packed lattice — neighbours overlap ----------------------------------------
  so.pitch_factor = o.packed_pitch_factor;
  scenes::Scene packed = scenes::paper_sample(so);
  packed.reg.params.alert = o.alert;
  driver::input_accepted();  // both samples built: from here, errors are the run's (exit 1)
  PlplxDetector det;
  std::printf("3. Packed sample\n");
  print_layout(packed, o.packed_pitch_factor);
  const auto t0 = std::chrono::steady_clock::now();
  const Report rp = detect(packed, det);
  const double first = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  print_report(rp);

  // ---- step 4: detection time -------------------------------------------------------------
  const int runs = 101;
  const double median = median_detection_seconds(packed, det, runs);
  const double n = static_cast<double>(packed.reg.bodies.size());
  std::printf("4. Detection time on the packed sample (%zu bodies)\n", packed.reg.bodies.size());
  std::printf("   first call (allocates its workspace) %9.1f us\n", 1e6 * first);
  std::printf("   median of %d calls                  %9.1f us = %.0f ns per body\n", runs, 1e6 * median,
              1e9 * median / n);

  // ---- step 5: VTK output -------------------------------------------------------------------
  if (o.no_vtk) {
    std::printf("5. VTK output skipped (--no-vtk)\n");
    return 0;
  }
  detect_plplx(loose.reg, det_loose);  // reg.contacts holds the contacts of the frame written
  VtkWriter wl(o.output, "loose_");
  wl.write_frame(loose.reg);
  VtkWriter wp(o.output, "packed_");
  wp.write_frame(packed.reg);
  std::printf("5. VTK written to %s: loose_bodies.pvd, loose_contacts.pvd, packed_bodies.pvd, packed_contacts.pvd\n",
              o.output.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return driver::run_main("scene_demo", argc, argv, Options{}, parse, run); }
