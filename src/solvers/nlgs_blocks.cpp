// nscd/solvers/nlgs_blocks.cpp — the colored sweep's strips and cells (nlgs_blocks.hpp), and
// two_ranks (nlgs_colored.hpp).
#include "nscd/solvers/nlgs_blocks.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "nscd/solvers/thread_range.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace nscd::colored {
namespace {

// A system whose bodies have positions is cut into strips (two colours) or a grid of cells (two
// colours a row), below, at any size. Without positions: blocks of consecutive contacts, swept
// on several threads from kParallelMin (nlgs_colored.hpp) contacts on, below that on one thread,
// which gives the same numbers (the blocks of a colour are independent).
/// Strips and cells: at least this many contacts (a smaller sweep is shorter than the barriers
/// it needs). Strips (SweepOrder::Colored): at least kMinCells strips as wide as cell_span
/// (below), at most kMaxColumns. Cells (SweepOrder::ColoredRows): at least kMinCells cells; a
/// column as wide as cell_span along x, a row kRowSpans times cell_span along y; at most
/// kMaxColumns columns and kMaxRows rows (two colours a row: the rows' colours must fit the 63
/// parallel colours). Rows two spans tall needed the fewest sweeps on the LMGC90 deposit
/// (docs/theory.md §9.5).
constexpr std::size_t kCellContactsMin = 256;
constexpr std::size_t kMinCells = 4, kMaxColumns = 256, kMaxRows = 31;
constexpr double kRowSpans = 2.0;

/// Spans are the distances between the two bodies of the contacts that join two dynamic
/// bodies: of every contact up to this many contacts, of every k-th contact in a larger system
/// (k = 1 + n / kSpanSample), whose median and 95th percentile they estimate.
constexpr std::size_t kSpanSample = 16384;

/// The distances along x (spans[0]) and y (spans[1]) between the two bodies of each contact
/// that joins two dynamic bodies, in contact order (every k-th contact of a large system).
void sample_spans(const ContactSystem& sys, const std::vector<Ends>& ends, std::vector<double>* spans) {
  const double* x = sys.body_x.data();
  const double* y = sys.body_y.data();
  spans[0].clear(), spans[1].clear();
  const std::size_t every = 1 + ends.size() / kSpanSample;
  for (std::size_t a = 0; a < ends.size(); a += every) {
    const Ends e = ends[a];
    if (e.cd != kNoBody && e.an != kNoBody) {
      spans[0].push_back(std::abs(x[e.cd] - x[e.an]));
      spans[1].push_back(std::abs(y[e.cd] - y[e.an]));
    }
  }
}

/// The box around the dynamic bodies in contact. False when the system cannot be cut by
/// position: too few contacts, bodies without positions, or a position there not finite. Also
/// the contacts' spans (sample_spans).
bool contact_box(const ContactSystem& sys, const std::vector<Ends>& ends, double lo[2], double hi[2],
                 std::vector<double>* spans, int threads, std::vector<double>& ws_box_parts) {
  if (sys.contacts.size() < kCellContactsMin || sys.body_x.size() != sys.bodies.size() ||
      sys.body_y.size() != sys.bodies.size())
    return false;
  constexpr double inf = std::numeric_limits<double>::infinity();
  const double* x = sys.body_x.data();
  const double* y = sys.body_y.data();
  // the box of contacts a0 … a1−1, and a check that is 0 if all their positions are finite (x − x
  // is 0 for a finite x and NaN for an infinite or NaN one)
  struct Box {
    double lo[2] = {inf, inf}, hi[2] = {-inf, -inf}, check = 0.0;
  };
  auto box_of = [&](std::size_t a0, std::size_t a1) {
    Box b;
    auto widen = [&](std::uint32_t i) {
      b.check += (x[i] - x[i]) + (y[i] - y[i]);
      b.lo[0] = std::min(b.lo[0], x[i]);
      b.hi[0] = std::max(b.hi[0], x[i]);
      b.lo[1] = std::min(b.lo[1], y[i]);
      b.hi[1] = std::max(b.hi[1], y[i]);
    };
    for (std::size_t a = a0; a < a1; ++a) {
      const Ends e = ends[a];
      if (e.cd != kNoBody) widen(e.cd);
      if (e.an != kNoBody) widen(e.an);
    }
    return b;
  };
  // on the threads for a large system: each thread its range, the boxes joined (min and max are
  // exact, so the box does not depend on the threads)
  Box box;
  if (threads > 1 && ends.size() >= kParallelMin) {
    // thread t's box in part[5t … 5t+4]: lo x, lo y, hi x, hi y, check; the empty box where
    // OpenMP starts fewer threads (scratch: no allocation once warm)
    std::vector<double>& part = ws_box_parts;
    part.clear();
    for (int t = 0; t < threads; ++t) part.insert(part.end(), {inf, inf, -inf, -inf, 0.0});
#pragma omp parallel num_threads(threads)
    {
#ifdef _OPENMP
      const auto t = static_cast<std::size_t>(omp_get_thread_num()),
                 team = static_cast<std::size_t>(omp_get_num_threads());
#else
      const std::size_t t = 0, team = 1;
#endif
      const Box b = box_of(ends.size() * t / team, ends.size() * (t + 1) / team);
      double* mine = part.data() + 5 * t;
      mine[0] = b.lo[0], mine[1] = b.lo[1], mine[2] = b.hi[0], mine[3] = b.hi[1], mine[4] = b.check;
    }
    for (std::size_t i = 0; i < part.size(); i += 5) {
      for (int k = 0; k < 2; ++k) {
        box.lo[k] = std::min(box.lo[k], part[i + k]);
        box.hi[k] = std::max(box.hi[k], part[i + 2 + k]);
      }
      box.check += part[i + 4];
    }
  } else {
    box = box_of(0, ends.size());
  }
  for (int k = 0; k < 2; ++k) lo[k] = box.lo[k], hi[k] = box.hi[k];
  if (!(box.check == 0.0 && std::isfinite(lo[0]) && std::isfinite(lo[1]) && std::isfinite(hi[0]) &&
        std::isfinite(hi[1])))
    return false;
  sample_spans(sys, ends, spans);
  return true;
}

/// The span along one axis that a cell's side must not be under: twice the median distance
/// along it between the two dynamic bodies of a contact (`spans`, reordered here), and at least
/// the distance that 95 % of them do not exceed (a lattice whose rows run along the axis has a
/// median near 0 across it: its cells would miss most contacts); 0 if no contact joins two
/// dynamic bodies. (The median is the value of rank n/2, the 95th percentile that of rank
/// (n − 1)·95/100, 0-based.)
double cell_span(std::vector<double>& spans, std::vector<double>& scratch) {
  if (spans.empty()) return 0.0;
  double median = 0.0, q95 = 0.0;
  // (below 3 spans the 95th percentile's rank lies below the median's, and twice the median wins
  // either way)
  two_ranks(spans, spans.size() / 2, std::max(spans.size() / 2, (spans.size() - 1) * 95 / 100), median, q95, scratch);
  return std::max(2.0 * median, q95);
}

}  // namespace

void fill_ends(const std::vector<SolverContact>& c, std::vector<Ends>& ends, int threads) {
  ends.resize(c.size());
  each_index(c.size(), c.size() >= kParallelMin ? threads : 1, [&](std::size_t a) {
    const SolverContact& s = c[a];
    ends[a] = {s.cd_dynamic ? s.cd : kNoBody, s.an_dynamic ? s.an : kNoBody};
  });
}

/// Strips across the longer side of the bodies in contact: body i lies in strip
/// floor((x_i − lo) / width); a contact between two dynamic bodies of the same or neighbouring
/// strips belongs to the lower strip, one with a single dynamic body to that body's strip; a
/// contact whose bodies lie further apart (a body wider than a strip, as a sleeper) spills to
/// the overflow. Strips two apart share no body: coloured greedily, two colours. `key` gets each
/// strip's index. False (nothing decided) when the system has no positions or is too small or
/// too narrow for kMinCells strips.
bool strip_blocks(const ContactSystem& sys, NlgsColoredWorkspace& ws, std::vector<std::uint32_t>& block_of,
                  std::size_t& nblocks, std::vector<std::uint32_t>& key, std::size_t& nkeys, int threads) {
  const std::vector<Ends>& ends = ws.scratch.ends;
  double lo[2], hi[2];
  std::vector<double>* spans = ws.scratch.axis_spans;  // the contacts' spans along x and y
  if (!contact_box(sys, ends, lo, hi, spans, threads, ws.scratch.box_parts)) return false;
  const int axis = hi[0] - lo[0] >= hi[1] - lo[1] ? 0 : 1;
  const double* pos = axis == 0 ? sys.body_x.data() : sys.body_y.data();
  const double extent = hi[axis] - lo[axis];
  if (!(extent > 0.0) || !std::isfinite(extent)) return false;
  const double least = cell_span(spans[axis], ws.scratch.span_bin);
  const double most = least > 0.0 ? std::floor(extent / least) : static_cast<double>(kMaxColumns);
  const std::size_t strips = static_cast<std::size_t>(std::min(most, static_cast<double>(kMaxColumns)));
  if (strips < kMinCells) return false;
  const double width = extent / static_cast<double>(strips);
  auto strip = [&](std::uint32_t i) {
    const double k = std::floor((pos[i] - lo[axis]) / width);
    return static_cast<std::uint32_t>(std::clamp(k, 0.0, static_cast<double>(strips - 1)));
  };
  block_of.resize(ends.size());
  // each contact's own strip: on the threads from kLoopParallelMin contacts on
  each_index(ends.size(), loop_threads(ends.size(), threads), [&](std::size_t a) {
    const Ends e = ends[a];
    if (e.cd != kNoBody && e.an != kNoBody) {
      const std::uint32_t p = strip(e.cd), q = strip(e.an);
      block_of[a] = (p > q ? p - q : q - p) > 1 ? kSpill : std::min(p, q);
    } else if (e.cd != kNoBody || e.an != kNoBody) {
      block_of[a] = strip(e.cd != kNoBody ? e.cd : e.an);
    } else {
      block_of[a] = 0;  // writes no body: any block will do
    }
  });
  nblocks = nkeys = strips;
  key.resize(nblocks);
  std::iota(key.begin(), key.end(), 0u);
  return true;
}

/// A grid of cells over the dynamic bodies in contact: body i lies in column
/// floor((x_i − x_lo) / width) and row floor((y_i − y_lo) / height). A contact between two
/// dynamic bodies of the same or neighbouring columns and rows belongs to the cell of the lower
/// column and the lower row, one with a single dynamic body to that body's cell; a contact whose
/// bodies lie further apart (a body wider than a cell, as a sleeper) spills to the overflow. So
/// a cell's contacts touch bodies of the cell and of its neighbours to the right and above only.
/// The cells are numbered row by row from the bottom (from the top if `from_top`), in each row
/// the even columns, then the odd ones (blocks of one row and one parity share no body); `key`
/// gets each cell's column (the threads' shares are ranges of columns). False (nothing decided)
/// when the system has no positions or is too small for kMinCells.
bool cell_blocks(const ContactSystem& sys, NlgsColoredWorkspace& ws, std::vector<std::uint32_t>& block_of,
                 std::size_t& nblocks, std::vector<std::uint32_t>& key, std::size_t& nkeys,
                 std::vector<std::uint32_t>& body_cell, bool from_top, int threads) {
  const std::vector<Ends>& ends = ws.scratch.ends;
  // a. the box around the dynamic bodies in contact
  double lo[2], hi[2];
  std::vector<double>* spans = ws.scratch.axis_spans;  // and the contacts' spans along x and y
  if (!contact_box(sys, ends, lo, hi, spans, threads, ws.scratch.box_parts)) return false;
  const double* pos[2] = {sys.body_x.data(), sys.body_y.data()};
  // b. columns and rows: as many as fit (one where the bodies have no extent along an axis)
  std::size_t cells[2] = {1, 1};
  double side[2] = {1.0, 1.0};
  const double most_cells[2] = {static_cast<double>(kMaxColumns), static_cast<double>(kMaxRows)};
  for (int axis = 0; axis < 2; ++axis) {
    const double extent = hi[axis] - lo[axis];
    if (!(extent > 0.0) || !std::isfinite(extent)) continue;
    const double least = cell_span(spans[axis], ws.scratch.span_bin) * (axis == 1 ? kRowSpans : 1.0);
    const double fit = least > 0.0 ? std::floor(extent / least) : most_cells[axis];
    cells[axis] = static_cast<std::size_t>(std::clamp(fit, 1.0, most_cells[axis]));
    side[axis] = extent / static_cast<double>(cells[axis]);
  }
  if (cells[0] * cells[1] < kMinCells) return false;
  auto along = [&](int axis, std::uint32_t i) {
    const double k = std::floor((pos[axis][i] - lo[axis]) / side[axis]);
    return static_cast<std::uint32_t>(std::clamp(k, 0.0, static_cast<double>(cells[axis] - 1)));
  };
  // a body's row and column (row << 16 | column), worked out once per body in contact
  constexpr std::uint32_t kUnset = std::numeric_limits<std::uint32_t>::max();
  body_cell.assign(sys.bodies.size(), kUnset);
  auto cell = [&](std::uint32_t i) {
    if (body_cell[i] == kUnset) body_cell[i] = along(1, i) << 16 | along(0, i);
    return body_cell[i];
  };
  // c. numbering: row by row, the even columns of a row before its odd ones
  const auto columns = static_cast<std::uint32_t>(cells[0]), evens = (columns + 1) / 2;
  const auto rows = static_cast<std::uint32_t>(cells[1]);
  auto id = [&](std::uint32_t row, std::uint32_t column) {
    return (from_top ? rows - 1 - row : row) * columns + (column % 2 == 0 ? column / 2 : evens + column / 2);
  };
  nblocks = cells[0] * cells[1];
  nkeys = columns;
  key.resize(nblocks);
  for (std::uint32_t r = 0; r < rows; ++r)
    for (std::uint32_t k = 0; k < columns; ++k) key[id(r, k)] = k;
  // d. each contact's cell
  block_of.resize(ends.size());
  for (std::size_t a = 0; a < ends.size(); ++a) {
    const Ends e = ends[a];
    if (e.cd != kNoBody && e.an != kNoBody) {
      const std::uint32_t p = cell(e.cd), q = cell(e.an);
      const std::uint32_t px = p & 0xffffu, qx = q & 0xffffu, py = p >> 16, qy = q >> 16;
      const bool near = (px > qx ? px - qx : qx - px) <= 1 && (py > qy ? py - qy : qy - py) <= 1;
      block_of[a] = near ? id(std::min(py, qy), std::min(px, qx)) : kSpill;
    } else if (e.cd != kNoBody || e.an != kNoBody) {
      const std::uint32_t p = cell(e.cd != kNoBody ? e.cd : e.an);
      block_of[a] = id(p >> 16, p & 0xffffu);
    } else {
      block_of[a] = 0;  // writes no body: any block will do
    }
  }
  return true;
}

// Two cells of neighbouring rows share bodies only along the line between the rows. Numbered
// from the top, the upper row is swept first and, its contacts going upward, begins at that
// line; the lower row is swept second and ends there. So the lower cell's contacts on the
// shared bodies come last in it, after the upper cell's first ones, and the plan
// (nlgs_plan.hpp) starts every row at once: a sweep on many threads lasts about one cell, where
// rows numbered from the bottom, each ending where the next begins, follow one another.
void sort_cells_upward(const ContactSystem& sys, NlgsColoredWorkspace& ws, std::size_t nblocks, int threads) {
  NlgsColoredWorkspace::ColorScratch& x = ws.scratch;
  const double* y = sys.body_y.data();
  // a contact's height: the mean of its dynamic bodies' (a contact has one at least, or any
  // place will do)
  auto height = [&](std::uint32_t a) {
    const Ends e = x.ends[a];
    if (e.cd != kNoBody && e.an != kNoBody) return 0.5 * (y[e.cd] + y[e.an]);
    return e.cd != kNoBody ? y[e.cd] : e.an != kNoBody ? y[e.an] : 0.0;
  };
  each_index(nblocks, loop_threads(x.members.size(), threads), [&](std::size_t b) {
    std::sort(x.members.begin() + x.first[b], x.members.begin() + x.first[b + 1],
              [&](std::uint32_t p, std::uint32_t q) {
                const double hp = height(p), hq = height(q);
                return hp != hq ? hp < hq : p < q;  // (ties in contact order: the same on any threads)
              });
  });
}

}  // namespace nscd::colored

namespace nscd {

// two_ranks, exactly: a histogram of 256 bins over [min, max] — the bin is a non-decreasing
// function of the value, so the values of lower bins are no larger — then nth_element within the
// one or two bins that hold those ranks. Three passes with few branches, where nth_element over all of v mispredicts
// at every comparison (docs/benchmarks.md §8). `bin` is scratch.
void two_ranks(std::vector<double>& v, std::size_t k1, std::size_t k2, double& r1, double& r2,
               std::vector<double>& bin) {
  double lo = v[0], hi = v[0];
  for (const double x : v) {
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  if (!(hi > lo)) {
    r1 = r2 = lo;
    return;
  }
  constexpr std::uint32_t kBins = 256;
  const double scale = kBins / (hi - lo);
  auto bin_of = [&](double x) {
    return std::min<std::uint32_t>(kBins - 1, static_cast<std::uint32_t>((x - lo) * scale));
  };
  std::uint32_t count[kBins] = {};
  for (const double x : v) ++count[bin_of(x)];
  auto find = [&](std::size_t k, std::size_t& below) {  // the bin holding rank k, and the values below it
    std::uint32_t b = 0;
    for (below = 0; below + count[b] <= k; ++b) below += count[b];
    return b;
  };
  std::size_t below1 = 0, below2 = 0;
  const std::uint32_t b1 = find(k1, below1), b2 = find(k2, below2);
  auto select = [&](std::uint32_t b, std::size_t k) {
    bin.clear();
    for (const double x : v)
      if (bin_of(x) == b) bin.push_back(x);
    std::nth_element(bin.begin(), bin.begin() + static_cast<std::ptrdiff_t>(k), bin.end());
    return bin[k];
  };
  r1 = select(b1, k1 - below1);
  if (b2 != b1) {
    r2 = select(b2, k2 - below2);
    return;
  }
  // the same bin: already gathered
  std::nth_element(bin.begin(), bin.begin() + static_cast<std::ptrdiff_t>(k2 - below1), bin.end());
  r2 = bin[k2 - below1];
}

}  // namespace nscd
