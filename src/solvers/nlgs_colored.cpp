// nscd/solvers/nlgs_colored.cpp — see nlgs_colored.hpp.
#include "nscd/solvers/nlgs_colored.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
#include <thread>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "nscd/solvers/nlgs_lanes.hpp"
#include "nscd/solvers/scene_backend.hpp"

namespace nscd {
namespace {

constexpr unsigned kOverflow = 63;  ///< colours 0 … 62 run in parallel, 63 on one thread
constexpr std::uint32_t kSpill = std::numeric_limits<std::uint32_t>::max();  ///< a contact of no block: the overflow

/// Contacts per block of consecutive contacts (a system without positions): n/64 within
/// [256, 8192] — a function of the system only, never of the threads. Blocks of consecutive
/// contacts keep the detection order's cache locality; where that order follows the layers of a
/// packing, a block large enough to span a row meets only its neighbours and two or three
/// colours do, and fewer colours sweep faster (docs/benchmarks.md §8). Where it does not, a block touches bodies all over the field and the colours are many and small
/// (a 7,000-grain deposit: 9–10 colours of 1–11 blocks): hence strips and cells wherever the
/// bodies have positions.
std::size_t block_size(std::size_t n) { return std::clamp<std::size_t>(n / 64, 256, 8192); }

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
/// Anderson mixing (anderson.hpp): every kMixPeriod sweeps. After kStallChecks checks in a row
/// that do not bring the policy's ratio 10 % below its best since the phase began, the solve
/// goes over from mixed sweeps to relaxed ones, and from relaxed ones back to mixed ones, from a
/// fresh history (theory §9.5b, from the LMGC90 case).
constexpr int kMixPeriod = 4, kStallChecks = 5;

/// f(i) for i = 0 … count−1, each on its own: on `threads` threads (static ranges) when
/// `threads` > 1, else in order. The colouring's loops over a large system's contacts, whose
/// results do not depend on the threads.
template <class F>
void each_index(std::size_t count, int threads, const F& f) {
  const auto m = static_cast<std::ptrdiff_t>(count);
  if (threads > 1) {
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::ptrdiff_t i = 0; i < m; ++i) f(static_cast<std::size_t>(i));
  } else {
    for (std::ptrdiff_t i = 0; i < m; ++i) f(static_cast<std::size_t>(i));
  }
}

/// Each contact's dynamic bodies, 8 bytes a contact (kNoBody for a kinematic end): what the
/// blocks and the colours need, without streaming the 152-byte records again and again (each
/// pass over the records costs milliseconds in a large system: docs/benchmarks.md §8).
constexpr std::uint32_t kNoBody = std::numeric_limits<std::uint32_t>::max();
using Ends = NlgsColoredWorkspace::ColorScratch::Ends;
void fill_ends(const std::vector<SolverContact>& c, std::vector<Ends>& ends, int threads) {
  ends.resize(c.size());
  each_index(c.size(), c.size() >= kParallelMin ? threads : 1, [&](std::size_t a) {
    const SolverContact& s = c[a];
    ends[a] = {s.cd_dynamic ? s.cd : kNoBody, s.an_dynamic ? s.an : kNoBody};
  });
}

/// Spans are the distances between the two bodies of the contacts that join two dynamic
/// bodies: of every contact up to this many contacts, of every k-th contact in a larger system
/// (k = 1 + n / kSpanSample), whose median and 95th percentile they estimate.
constexpr std::size_t kSpanSample = 16384;

/// The box around the dynamic bodies in contact. False when the system cannot be cut by
/// position: too few contacts, bodies without positions, or a position there not finite. With
/// `spans`, also the distances along x (spans[0]) and y (spans[1]) between the two bodies of each
/// contact that joins two dynamic bodies, in contact order (every k-th contact of a large system,
/// above).
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
      const auto t = static_cast<std::size_t>(omp_get_thread_num()), team = static_cast<std::size_t>(omp_get_num_threads());
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
  if (!(box.check == 0.0 && std::isfinite(lo[0]) && std::isfinite(lo[1]) && std::isfinite(hi[0]) && std::isfinite(hi[1])))
    return false;
  spans[0].clear(), spans[1].clear();
  const std::size_t every = 1 + ends.size() / kSpanSample;
  for (std::size_t a = 0; a < ends.size(); a += every) {
    const Ends e = ends[a];
    if (e.cd != kNoBody && e.an != kNoBody) {
      spans[0].push_back(std::abs(x[e.cd] - x[e.an]));
      spans[1].push_back(std::abs(y[e.cd] - y[e.an]));
    }
  }
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
  // each contact's own strip: on the threads for a large system
  each_index(ends.size(), ends.size() >= kParallelMin ? threads : 1, [&](std::size_t a) {
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
/// The cells are numbered row by row from the bottom, in each row the even columns, then the
/// odd ones (blocks of one row and one parity share no body); `key` gets each cell's column
/// (the threads' shares are ranges of columns). False (nothing decided) when the system has no
/// positions or is too small for kMinCells.
bool cell_blocks(const ContactSystem& sys, NlgsColoredWorkspace& ws, std::vector<std::uint32_t>& block_of,
                 std::size_t& nblocks, std::vector<std::uint32_t>& key, std::size_t& nkeys,
                 std::vector<std::uint32_t>& body_cell, int threads) {
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
  auto id = [&](std::uint32_t row, std::uint32_t column) { return row * columns + (column % 2 == 0 ? column / 2 : evens + column / 2); };
  nblocks = cells[0] * cells[1];
  nkeys = columns;
  key.resize(nblocks);
  for (std::uint32_t r = 0; r < cells[1]; ++r)
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

/// A barrier that spins: the colours of a small system are a microsecond apart, and OpenMP's
/// barrier costs several times more than this one (docs/benchmarks.md §8) (sense reversal: the last thread to arrive resets the count and flips the flag). After a
/// few thousand spins a waiting thread yields, in case it shares its core with another.
class SpinBarrier {
 public:
  void reset(unsigned team) {
    team_ = team;
    count_.store(0, std::memory_order_relaxed);
    flag_.store(0, std::memory_order_relaxed);
  }
  /// `sense`: the calling thread's own, 0 before its first wait.
  void wait(unsigned& sense) {
    sense ^= 1u;
    if (count_.fetch_add(1, std::memory_order_acq_rel) + 1 == team_) {
      count_.store(0, std::memory_order_relaxed);
      flag_.store(sense, std::memory_order_release);
      return;
    }
    for (unsigned spins = 0; flag_.load(std::memory_order_acquire) != sense; ++spins) {
      if (spins < 4096) {
#if defined(__x86_64__) || defined(__i386__)
        __builtin_ia32_pause();
#endif
      } else {
        std::this_thread::yield();
      }
    }
  }

 private:
  alignas(64) std::atomic<unsigned> count_{0};
  alignas(64) std::atomic<unsigned> flag_{0};
  unsigned team_ = 1;
};

}  // namespace

// two_ranks, exactly: a histogram of 256 bins over [min, max] — the bin is a non-decreasing
// function of the value, so the values of lower bins are no larger — then nth_element within the
// one or two bins that hold those ranks. Three passes with few branches, where nth_element over all of v mispredicts
// at every comparison (docs/benchmarks.md §8). `bin` is scratch.
void two_ranks(std::vector<double>& v, std::size_t k1, std::size_t k2, double& r1, double& r2, std::vector<double>& bin) {
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
  auto bin_of = [&](double x) { return std::min<std::uint32_t>(kBins - 1, static_cast<std::uint32_t>((x - lo) * scale)); };
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

std::size_t color_contacts(ContactSystem& sys, NlgsColoredWorkspace& ws, SweepOrder order, int threads) {
  const std::vector<SolverContact>& c = sys.contacts;
  const std::size_t n = c.size();
  // 1. Blocks: strips or cells of the field (systems with positions) or consecutive contacts.
  NlgsColoredWorkspace::ColorScratch& x = ws.scratch;
  fill_ends(c, x.ends, threads);
  const std::vector<Ends>& ends = x.ends;
  std::vector<std::uint32_t>& block_of = x.block_of;
  std::size_t nblocks = 0, nkeys = 0;
  const bool rows = order == SweepOrder::ColoredRows;
  ws.cells = rows && cell_blocks(sys, ws, block_of, nblocks, x.key, nkeys, x.body_cell, threads);
  ws.strips = !rows && strip_blocks(sys, ws, block_of, nblocks, x.key, nkeys, threads);
  if (!ws.cells && !ws.strips) {
    // consecutive in detection order: by rank of the registry row when the rows say it (an
    // arranged system then gives back its own blocks), else by index
    const std::size_t kBlock = block_size(n);
    nblocks = (n + kBlock - 1) / kBlock;
    block_of.resize(n);
    const bool by_rank = sys.rows.size() == n && !std::is_sorted(sys.rows.begin(), sys.rows.end());
    if (by_rank) {
      x.rank.resize(n);
      std::iota(x.rank.begin(), x.rank.end(), 0u);
      std::sort(x.rank.begin(), x.rank.end(), [&](std::uint32_t p, std::uint32_t q) { return sys.rows[p] < sys.rows[q]; });
      for (std::size_t r = 0; r < n; ++r) block_of[x.rank[r]] = static_cast<std::uint32_t>(r / kBlock);
    } else {
      for (std::size_t a = 0; a < n; ++a) block_of[a] = static_cast<std::uint32_t>(a / kBlock);
    }
    nkeys = nblocks;  // the threads' shares: ranges of blocks
    x.key.resize(nblocks);
    std::iota(x.key.begin(), x.key.end(), 0u);
  }
  // 2. Each block's contacts, in contact order (a counting sort; the spilled ones last).
  std::vector<std::uint32_t>& first = x.first;
  first.assign(nblocks + 2, 0);
  for (std::size_t a = 0; a < n; ++a) ++first[(block_of[a] == kSpill ? nblocks : block_of[a]) + 1];
  for (std::size_t b = 0; b <= nblocks; ++b) first[b + 1] += first[b];
  std::vector<std::uint32_t>& members = x.members;
  members.resize(n);
  x.next.assign(first.begin(), first.end() - 1);
  for (std::size_t a = 0; a < n; ++a) members[x.next[block_of[a] == kSpill ? nblocks : block_of[a]]++] = static_cast<std::uint32_t>(a);
  // 3. Colours, block by block, marked at every dynamic body of the block. Strips and
  //    consecutive blocks: greedy, the lowest colour not taken at any of its dynamic bodies
  //    (two or three colours).
  //    Cells: levels, the lowest colour above every colour taken at its dynamic bodies, so that
  //    two blocks sharing a dynamic body are swept in block order: the sweep is that of the
  //    cells one after the other, row by row from the bottom (theory §9.5), two colours a row.
  //    No colour left: the overflow.
  ws.body_colors.assign(sys.bodies.size(), 0);
  std::vector<std::uint32_t>& col = x.col;
  col.assign(nblocks + 1, 0);
  std::uint32_t count[kOverflow + 2] = {};
  for (std::size_t b = 0; b < nblocks; ++b) {
    std::uint64_t taken = 0;
    for (std::uint32_t i = first[b]; i < first[b + 1]; ++i) {
      const Ends e = ends[members[i]];
      taken |= (e.cd != kNoBody ? ws.body_colors[e.cd] : 0) | (e.an != kNoBody ? ws.body_colors[e.an] : 0);
    }
    std::uint64_t free_colors = ~taken & ((std::uint64_t{1} << kOverflow) - 1);
    if (ws.cells && taken != 0) free_colors &= ~std::uint64_t{0} << (64 - std::countl_zero(taken));  // above the highest taken
    const unsigned k = free_colors ? static_cast<unsigned>(std::countr_zero(free_colors)) : kOverflow;
    if (k != kOverflow)
      for (std::uint32_t i = first[b]; i < first[b + 1]; ++i) {
        const Ends e = ends[members[i]];
        if (e.cd != kNoBody) ws.body_colors[e.cd] |= std::uint64_t{1} << k;
        if (e.an != kNoBody) ws.body_colors[e.an] |= std::uint64_t{1} << k;
      }
    col[b] = k;
    ++count[k + 1];
  }
  const bool spilled = first[nblocks + 1] > first[nblocks];
  col[nblocks] = kOverflow;  // the spilled contacts: one more block of the overflow, the last
  if (spilled) ++count[kOverflow + 1];
  // 4. Layout: blocks colour by colour (by key inside a colour: block order, or column then
  //    row), and the system's contacts put in that order, so that a block, a colour and a
  //    thread's share are each one range of consecutive records (records are written at every
  //    visit: records of two threads sharing a cache line would bounce between the cores).
  ws.color_start.assign(kOverflow + 2, 0);
  for (unsigned k = 0; k <= kOverflow; ++k) ws.color_start[k + 1] = ws.color_start[k] + count[k + 1];
  x.next.assign(ws.color_start.begin(), ws.color_start.end() - 1);
  std::vector<std::uint32_t>& placed = x.placed;
  placed.resize(nblocks + 1);
  {
    std::vector<std::uint32_t>& by_key = x.by_key;  // the blocks by key (a counting sort, stable)
    by_key.resize(nblocks);
    x.key_first.assign(nkeys + 1, 0);
    for (std::size_t b = 0; b < nblocks; ++b) ++x.key_first[x.key[b] + 1];
    for (std::size_t k = 0; k < nkeys; ++k) x.key_first[k + 1] += x.key_first[k];
    for (std::size_t b = 0; b < nblocks; ++b) by_key[x.key_first[x.key[b]]++] = static_cast<std::uint32_t>(b);
    for (const std::uint32_t b : by_key) placed[x.next[col[b]]++] = b;
    if (spilled) placed[x.next[kOverflow]++] = static_cast<std::uint32_t>(nblocks);
  }
  const std::size_t laid = ws.color_start.back();
  ws.block_start.resize(laid + 1);
  ws.block_id.assign(placed.begin(), placed.begin() + static_cast<std::ptrdiff_t>(laid));
  ws.block_key.resize(laid);
  for (std::size_t i = 0; i < laid; ++i) ws.block_key[i] = placed[i] < nblocks ? x.key[placed[i]] : static_cast<std::uint32_t>(nkeys);
  ws.keys = nkeys;
  const bool with_rows = sys.rows.size() == n, with_status = sys.status.size() == n;
  x.contacts.resize(n);
  if (with_rows) x.rows.resize(n);
  if (with_status) x.status.resize(n);
  std::uint32_t at = 0;
  for (std::size_t i = 0; i < laid; ++i) {
    ws.block_start[i] = at;
    at += first[placed[i] + 1] - first[placed[i]];
  }
  ws.block_start[laid] = at;
  // the records into their places, block by block: each block's own range (on the threads for
  // a large system: a copy of every record)
  auto copy_block = [&](std::size_t i) {
    const std::uint32_t b = placed[i];
    std::uint32_t to = ws.block_start[i];
    for (std::uint32_t j = first[b]; j < first[b + 1]; ++j, ++to) {
      const std::uint32_t a = members[j];
      x.contacts[to] = c[a];
      if (with_rows) x.rows[to] = sys.rows[a];
      if (with_status) x.status[to] = sys.status[a];
    }
  };
  each_index(laid, n >= kParallelMin ? threads : 1, copy_block);
  sys.contacts.swap(x.contacts);  // the old arrays stay in the scratch, for the next step
  if (with_rows) sys.rows.swap(x.rows);
  if (with_status) sys.status.swap(x.status);
  ws.arranged = &sys;
  ws.arranged_order = order;
  ws.arranged_contacts = n;
  std::size_t used = 0;
  for (unsigned k = 0; k <= kOverflow; ++k) used += ws.color_start[k + 1] > ws.color_start[k];
  return used;
}

NlgsResult nlgs_iterate_colored(ContactSystem& sys, const NlgsOptions& opt, NlgsColoredWorkspace& ws) {
  NlgsResult res;
  const std::size_t n = sys.contacts.size();
  if (n == 0 && sys.links.empty()) {
    res.converged = true;
    return res;
  }
  if (ws.arranged != &sys || ws.arranged_contacts != n || ws.arranged_order != opt.order) color_contacts(sys, ws, opt.order, opt.threads);
  if (opt.skip_zero) {
    ws.vanish.assign(n, 0u);
    ws.level.assign(n, 1u);
  }
  ws.block_sums.assign(ws.block_start.size(), CriteriaAccumulator{});  // an empty block adds nothing
  if (sys.status.size() != n) sys.status.resize(n, ContactStatus::Open);  // written on checked sweeps
  SceneBackend be(sys);
  // Anderson mixing: the sweeps it mixes are plain Gauss–Seidel (ω = 1); the relaxation takes
  // over if it stalls, and the mixing again if the relaxed sweeps stall
  bool mixing = opt.anderson > 0;
  double omega = mixing ? 1.0 : opt.relaxation;
  double best_ratio = HUGE_VAL;
  int stalled = 0;
  AndersonMixer& mixer = ws.mixer;
  if (mixing) {
    mixer.start(n, sys.links.size(), 3 * sys.bodies.size(), opt.anderson);
    double* x = mixer.x();
    ws.mix_mu.resize(n);
    for (std::size_t a = 0; a < n; ++a) {
      x[2 * a] = sys.contacts[a].pn;
      x[2 * a + 1] = sys.contacts[a].pt;
      ws.mix_mu[a] = sys.contacts[a].mu;
    }
    for (std::size_t l = 0; l < sys.links.size(); ++l) x[2 * n + l] = sys.links[l].p;
    mixer.begin();
  }
  const std::uint32_t* block_start = ws.block_start.data();
  const std::vector<std::uint32_t>& start = ws.color_start;
  unsigned colours = 0;  // colours 0 … colours−1 are used (greedy: the lowest free colour first)
  while (colours < kOverflow && start[colours + 1] > start[colours]) ++colours;
  const bool parallel = opt.threads > 1 && (ws.cells || ws.strips || n >= kParallelMin);
  const int threads = parallel ? opt.threads : 1;
  // each thread's share: one range of keys (blocks, or columns of cells) for all colours, about
  // as many contacts each, so that a body is written by one thread only, but at the ranges'
  // borders
  const auto T = static_cast<std::size_t>(threads);
  std::vector<std::uint32_t>& border = ws.scratch.border;
  border.assign(T + 1, 0);
  {
    std::vector<std::uint64_t>& upto = ws.scratch.upto;  // contacts in blocks of keys before k
    upto.assign(ws.keys + 2, 0);
    for (std::size_t i = 0; i < start[kOverflow]; ++i) upto[ws.block_key[i] + 1] += block_start[i + 1] - block_start[i];
    for (std::size_t b = 0; b + 1 < upto.size(); ++b) upto[b + 1] += upto[b];
    const std::uint64_t total = upto.back();
    for (std::size_t t = 1; t < T; ++t)
      border[t] = static_cast<std::uint32_t>(std::lower_bound(upto.begin(), upto.end(), total * t / T) - upto.begin());
    border[T] = std::numeric_limits<std::uint32_t>::max();
  }
  ws.split.resize(colours * (T + 1));
  for (unsigned k = 0; k < colours; ++k) {
    std::uint32_t* s = ws.split.data() + k * (T + 1);
    const auto b0 = ws.block_key.begin() + start[k], b1 = ws.block_key.begin() + start[k + 1];
    for (std::size_t t = 0; t <= T; ++t) s[t] = static_cast<std::uint32_t>(std::lower_bound(b0, b1, border[t]) - ws.block_key.begin());
  }
  // SIMD lanes: the blocks of each thread share, colour by colour, dealt to the lanes of the
  // share's bundles (built, swept and read back by the thread that sweeps the share)
  const bool lanes = opt.lanes != 0 && !opt.skip_zero && lanes_available();
  const std::size_t per_share = colours + 1;
  // bundles larger than the last-level cache are streamed: without the inverse masses, which the
  // sweeps read from the bodies, and prefetched (nlgs_lanes.hpp)
  const bool stream = lanes && n * (sizeof(MassBundle) / MassBundle::kLanes) > stream_bytes();
  if (lanes) {
    ws.share_bundles.resize(stream ? 0 : T);
    ws.share_streamed.resize(stream ? T : 0);
    ws.share_order.resize(T);
    ws.bundle_split.assign(T * per_share, 0);
  }
  auto build_share = [&](std::size_t u) {
    auto build = [&](auto& v) {
      v.clear();
      // One thread on the cells or strips of a small system (below kParallelMin: a colour's
      // blocks are few, its last bundles half idle): the colours' blocks in one run of bundles, a
      // colour's idle lanes taking the next colours' blocks. A larger system's colours have many
      // blocks and fill their lanes anyway (blocks of consecutive contacts: no fewer bundles at
      // 7,000 or 70,000 grains): colour by colour, in the layout's order.
      if (T == 1 && (ws.cells || ws.strips) && n < kParallelMin) {
        ws.bundle_split[0] = 0;
        append_bundles_scheduled(sys.contacts, sys.bodies.data(), sys.bodies.size(), block_start, start.data(), colours,
                                 v, ws.lane_schedule);
        for (unsigned k = 1; k <= colours; ++k) ws.bundle_split[k] = static_cast<std::uint32_t>(v.size());
        return;
      }
      for (unsigned k = 0; k < colours; ++k) {
        const std::uint32_t* s = ws.split.data() + k * (T + 1);
        ws.bundle_split[u * per_share + k] = static_cast<std::uint32_t>(v.size());
        append_bundles(sys.contacts, sys.bodies.data(), block_start, s[u], s[u + 1], v, ws.share_order[u]);
      }
      ws.bundle_split[u * per_share + colours] = static_cast<std::uint32_t>(v.size());
    };
    stream ? build(ws.share_streamed[u]) : build(ws.share_bundles[u]);
  };
  auto finish_share = [&](std::size_t u) {
    auto finish = [&](const auto& v) {
      bundle_results_to_contacts(v.data(), v.data() + v.size(), sys.contacts.data(), sys.status.data());
    };
    stream ? finish(ws.share_streamed[u]) : finish(ws.share_bundles[u]);
  };
  // blocks b0 … b1−1: consecutive contacts, Gauss–Seidel; on a checked sweep each block adds
  // up its own convergence terms (a thread reads no other thread's contacts)
  auto sweep_blocks = [&](std::uint32_t b0, std::uint32_t b1, bool check) {
    for (std::uint32_t b = b0; b < b1; ++b) {
      CriteriaAccumulator acc;
      SequentialSums sums{acc};
      for (std::uint32_t a = block_start[b]; a < block_start[b + 1]; ++a) nlgs_visit(be, a, opt, ws, check, omega, sums);
      if (check) ws.block_sums[b] = acc;
    }
  };
  // colour k, thread share u: in lanes, or scalar
  auto sweep_share = [&](unsigned k, std::size_t u, bool check) {
    if (!lanes) {
      const std::uint32_t* s = ws.split.data() + k * (T + 1);
      return sweep_blocks(s[u], s[u + 1], check);
    }
    auto sweep = [&](auto* base) {
      sweep_bundles(base + ws.bundle_split[u * per_share + k], base + ws.bundle_split[u * per_share + k + 1],
                    sys.bodies.data(), omega, check, ws.block_sums.data(), opt.lanes);
    };
    stream ? sweep(ws.share_streamed[u].data()) : sweep(ws.share_bundles[u].data());
  };
  // 2.–4. after the colours: the overflow colour on one thread, the blocks' sums added in the
  // layout's order (fixed, whatever the threads), the links, the convergence test. True: converged.
  auto end_of_sweep = [&](int sweep, bool check) {
    sweep_blocks(start[kOverflow], start[kOverflow + 1], check);
    CriteriaAccumulator acc;
    if (check)
      for (std::uint32_t b = 0; b < start[kOverflow + 1]; ++b) acc.merge(ws.block_sums[b]);
    be.sweep_extra(check, acc, check ? 1.0 : omega);
    res.sweeps = sweep;
    if (!check) return false;
    res.criteria = acc.finish(opt.tol);
    res.converged = sweep >= opt.min_sweeps && converged(res.criteria, opt.policy);
    if (opt.anderson > 0 && !res.converged) {
      const double ratio = policy_ratio(res.criteria, opt.policy);
      if (ratio < 0.9 * best_ratio) {
        best_ratio = ratio;
        stalled = 0;
      } else if (++stalled >= kStallChecks) {
        // the phase stalls: mixed sweeps give way to relaxed ones (the mixing stalls where the
        // statuses keep changing), relaxed ones to mixed ones from a fresh history (relaxed
        // sweeps can settle into a cycle that repeats the same changes)
        mixing = !mixing;
        omega = mixing ? 1.0 : opt.relaxation;
        if (mixing) {
          mixer.restart_at_next();
          ++res.mix_returns;
        }
        best_ratio = HUGE_VAL;
        stalled = 0;
      }
    }
    return res.converged;
  };
  // 5. Anderson mixing, every kMixPeriod sweeps: the impulses (from the bundles, or the
  //    contacts; the overflow colour's are always in the contacts) and the velocities out, the
  //    mixed ones back, the projection's changes propagated. One thread; every sum in a fixed
  //    order.
  auto mix_step = [&](int sweep) {
    if (!mixing || sweep % kMixPeriod != 0) return;
    double* x = mixer.x();
    double* v = mixer.v();
    const std::size_t scalar_from = lanes ? block_start[start[kOverflow]] : 0;
    auto out = [&](const auto& shares) {
      for (const auto& b : shares) bundle_impulses_to(b.data(), b.data() + b.size(), x);
    };
    auto in = [&](auto& shares) {
      for (auto& b : shares) bundle_impulses_from(b.data(), b.data() + b.size(), x);
    };
    if (lanes) stream ? out(ws.share_streamed) : out(ws.share_bundles);
    for (std::size_t a = scalar_from; a < n; ++a) {
      x[2 * a] = sys.contacts[a].pn;
      x[2 * a + 1] = sys.contacts[a].pt;
    }
    for (std::size_t l = 0; l < sys.links.size(); ++l) x[2 * n + l] = sys.links[l].p;
    for (std::size_t i = 0; i < sys.bodies.size(); ++i) {
      v[3 * i] = sys.bodies[i].vx;
      v[3 * i + 1] = sys.bodies[i].vy;
      v[3 * i + 2] = sys.bodies[i].w;
    }
    if (!mixer.mix(ws.mix_mu.data())) return;
    if (lanes) stream ? in(ws.share_streamed) : in(ws.share_bundles);
    for (std::size_t a = scalar_from; a < n; ++a) {
      sys.contacts[a].pn = x[2 * a];
      sys.contacts[a].pt = x[2 * a + 1];
    }
    for (std::size_t l = 0; l < sys.links.size(); ++l) sys.links[l].p = x[2 * n + l];
    for (std::size_t i = 0; i < sys.bodies.size(); ++i) {
      sys.bodies[i].vx = v[3 * i];
      sys.bodies[i].vy = v[3 * i + 1];
      sys.bodies[i].w = v[3 * i + 2];
    }
    for (const AndersonMixer::Move& m : mixer.moved()) {
      const SolverContact& c = sys.contacts[m.contact];
      apply_impulse(c, sys.bodies[c.cd], sys.bodies[c.an], m.dpn, m.dpt);
    }
  };
  if (!parallel) {
    if (lanes) build_share(0);
    for (int sweep = 1; sweep <= opt.max_sweeps; ++sweep) {
      const bool check = sweep % opt.check_every == 0 || sweep == opt.max_sweeps;
      // 1. Colours 0 … 62, one after the other.
      for (unsigned k = 0; k < colours; ++k) sweep_share(k, 0, check);
      if (end_of_sweep(sweep, check)) break;
      mix_step(sweep);
    }
    if (lanes) finish_share(0);
  } else {
    // One parallel region for the whole solve: a region per sweep costs more than a small sweep.
    bool done = false;
    SpinBarrier barrier;
#pragma omp parallel num_threads(threads)
    {
#ifdef _OPENMP
      const auto t = static_cast<std::size_t>(omp_get_thread_num());
      const auto team = static_cast<std::size_t>(omp_get_num_threads());  // fewer than asked if OpenMP says so
#else
      const std::size_t t = 0, team = 1;
#endif
#pragma omp single
      barrier.reset(static_cast<unsigned>(team));  // (the single's own barrier follows)
      unsigned sense = 0;
      if (lanes) {  // the same on every thread
        for (std::size_t u = t; u < T; u += team) build_share(u);
        // the bundles are built from the bodies' inverse masses, which no sweep writes, but the
        // sweeps write the rows around them: all built before any sweep
#pragma omp barrier
      }
      for (int sweep = 1; sweep <= opt.max_sweeps; ++sweep) {
        const bool check = sweep % opt.check_every == 0 || sweep == opt.max_sweeps;
        // 1. Colours 0 … 62: the blocks of a colour share no dynamic body; each thread sweeps
        //    its share, and a barrier separates the colours.
        for (unsigned k = 0; k < colours; ++k) {
          for (std::size_t u = t; u < T; u += team) sweep_share(k, u, check);
          barrier.wait(sense);
        }
        // 2.–4. on thread 0, always the same (the overflow's bodies stay in its cache); the
        //    barrier after it shows every thread the verdict.
        if (t == 0 && !(done = end_of_sweep(sweep, check))) mix_step(sweep);
        barrier.wait(sense);
        if (done) break;
      }
      if (lanes)
        for (std::size_t u = t; u < T; u += team) finish_share(u);
    }
  }
  res.mixes = static_cast<int>(opt.anderson > 0 ? mixer.mixes() : 0);
  return res;
}

}  // namespace nscd
