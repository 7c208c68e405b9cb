// tests/unit/test_anderson.cpp — Anderson mixing of the NLGS sweeps (src/solvers/anderson.hpp):
//   - the mixer alone: on a linear fixed-point map it reaches the fixed point in far fewer
//     iterations than the plain iteration, and the velocities it mixes with the same weights
//     stay the affine image of the mixed impulses; depth 1 on a scalar linear map lands on the
//     fixed point, which the cones then cut back (the move is listed); against a textbook
//     Anderson step written plainly (chronological history, ΔFᵀΔF recomputed, Eigen's solve),
//     every mixed iterate, velocity and listed move agree, for sizes that are no multiple of the
//     vector width, every depth, a wrapped history, restarts and cone cuts;
//   - its phases: a restart_at_next is a fresh start, and the phases in any split, with chunks
//     side by side or with slots between them, give the bits of one mix();
//   - options: a depth of 1 … 8; its arrays begin on lines, skewed apart within their pages.
// The mixing in a scene: test_anderson_pile.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "nscd/core/error.hpp"
#include "nscd/solvers/anderson.hpp"

namespace {

using namespace nscd;

// x ← G(x) = x + (b − A x) / 2.2 for the 1D Laplacian A = tridiag(−1, 2, −1) of size n: a
// slow contraction (factor 1 − O(1/n²)), as Gauss–Seidel in a deep pile.
std::vector<double> laplace_step(const std::vector<double>& x, const std::vector<double>& b) {
  const std::size_t n = x.size();
  std::vector<double> g(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double ax = 2.0 * x[i] - (i > 0 ? x[i - 1] : 0.0) - (i + 1 < n ? x[i + 1] : 0.0);
    g[i] = x[i] + (b[i] - ax) / 2.2;
  }
  return g;
}

double residual_norm(const std::vector<double>& x, const std::vector<double>& b) {
  const std::vector<double> g = laplace_step(x, b);
  double s = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) s += (g[i] - x[i]) * (g[i] - x[i]);
  return std::sqrt(s);
}

TEST(AndersonMixer, ReachesTheFixedPointOfALinearMapInFarFewerIterations) {
  const std::size_t n = 30;
  std::vector<double> b(n);
  for (std::size_t i = 0; i < n; ++i) b[i] = std::sin(0.3 * static_cast<double>(i)) + 0.5;
  // velocities: an affine image of the impulses, v = C x + d (3 components)
  auto image = [&](const std::vector<double>& x) {
    std::vector<double> v = {1.0, -2.0, 0.5};
    for (std::size_t i = 0; i < n; ++i) {
      v[0] += 0.1 * x[i];
      v[1] += std::cos(static_cast<double>(i)) * x[i];
      v[2] -= 0.01 * static_cast<double>(i) * x[i];
    }
    return v;
  };
  const double tol = 1e-9;
  int plain = 0;
  for (std::vector<double> x(n, 0.0); residual_norm(x, b) > tol && plain < 100000; ++plain) x = laplace_step(x, b);
  // mixed every 4 iterations, as the solver does (the links' slots: no cone)
  AndersonMixer m;
  m.start(0, n, 3, 5);
  std::vector<double> x(n, 0.0);
  std::copy(x.begin(), x.end(), m.x());
  m.begin();
  int mixed = 0;
  while (residual_norm(x, b) > tol && mixed < 100000) {
    for (int k = 0; k < 4; ++k) x = laplace_step(x, b);
    mixed += 4;
    const std::vector<double> v = image(x);
    std::copy(x.begin(), x.end(), m.x());
    std::copy(v.begin(), v.end(), m.v());
    if (m.mix(nullptr)) {
      x.assign(m.x(), m.x() + n);
      const std::vector<double> expect = image(x);
      for (int k = 0; k < 3; ++k) ASSERT_NEAR(m.v()[k], expect[k], 1e-9 * (1.0 + std::abs(expect[k]))) << "iteration " << mixed;
    }
  }
  EXPECT_GT(plain, 1000);
  EXPECT_LT(mixed, plain / 5) << "plain " << plain << ", mixed " << mixed;
  EXPECT_GT(m.mixes(), 0u);
}

TEST(AndersonMixer, DepthOneLandsOnTheFixedPointAndTheConeCutsItBack) {
  // one contact; both components follow x ← x/2 + c, fixed point (−0.4, 0.1): depth 1 finds it
  // exactly from two results, and the cone of μ = 0.5 at P_N = 0 sends it to (0, 0)
  AndersonMixer m;
  m.start(1, 0, 1, 1);
  const double c[2] = {-0.2, 0.05}, mu = 0.5;
  double x[2] = {1.0, 0.0};
  m.x()[0] = x[0];
  m.x()[1] = x[1];
  m.begin();
  auto step = [&] {
    for (int k = 0; k < 2; ++k) x[k] = 0.5 * x[k] + c[k];
    m.x()[0] = x[0];
    m.x()[1] = x[1];
    m.v()[0] = 3.0 * x[0] - x[1];  // a velocity, affine in the impulses
  };
  step();
  EXPECT_FALSE(m.mix(&mu));  // no difference yet
  step();
  ASSERT_TRUE(m.mix(&mu));
  EXPECT_EQ(m.x()[0], 0.0);
  EXPECT_EQ(m.x()[1], 0.0);
  ASSERT_EQ(m.moved().size(), 1u);
  EXPECT_EQ(m.moved()[0].contact, 0u);
  // (up to the 1e-10 Tikhonov term of the least squares)
  EXPECT_NEAR(m.moved()[0].dpn, 0.4, 1e-9);
  EXPECT_NEAR(m.moved()[0].dpt, -0.1, 1e-9);
  // the velocity is that of the mixed impulses before the cut (the caller propagates the move)
  EXPECT_NEAR(m.v()[0], 3.0 * -0.4 - 0.1, 1e-9);
}

// The textbook step the mixer implements (anderson.hpp), written plainly: the history as a
// chronological list of (f, g) pairs, ΔFᵀΔF recomputed, the least squares by Eigen.
struct PlainAnderson {
  std::size_t nc, nx, nv;
  int depth;
  std::vector<double> x0;
  std::vector<std::vector<double>> f, g;  ///< residuals (nx) and results (nx + nv), oldest first
  double last_norm = 0.0;
  /// x: the results (nx + nv, overwritten by the mixed iterate); returns whether it mixed.
  bool mix(std::vector<double>& x, const std::vector<double>& mu, std::vector<AndersonMixer::Move>& moved) {
    moved.clear();
    std::vector<double> fk(nx);
    double norm = 0.0;
    for (std::size_t i = 0; i < nx; ++i) norm += (fk[i] = x[i] - x0[i]) * fk[i];
    if (f.empty() || norm > 4.0 * last_norm) f.clear(), g.clear();
    f.push_back(fk);
    g.push_back(x);
    if (f.size() > static_cast<std::size_t>(depth) + 1) f.erase(f.begin()), g.erase(g.begin());
    last_norm = norm;
    const int k = static_cast<int>(f.size()) - 1;
    if (k == 0 || norm == 0.0) {
      std::copy(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(nx), x0.begin());
      return false;
    }
    Eigen::MatrixXd dF(nx, k), dG(nx + nv, k);
    for (int j = 0; j < k; ++j) {
      for (std::size_t i = 0; i < nx; ++i) dF(static_cast<Eigen::Index>(i), j) = f[j + 1][i] - f[j][i];
      for (std::size_t i = 0; i < nx + nv; ++i) dG(static_cast<Eigen::Index>(i), j) = g[j + 1][i] - g[j][i];
    }
    const Eigen::Map<const Eigen::VectorXd> fv(fk.data(), static_cast<Eigen::Index>(nx));
    Eigen::MatrixXd A = dF.transpose() * dF;
    A.diagonal().array() += 1e-10 * A.trace();
    const Eigen::VectorXd gamma = A.partialPivLu().solve(dF.transpose() * fv);
    Eigen::Map<Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(nx + nv)) -= dG * gamma;
    for (std::size_t c = 0; c < nc; ++c) {
      const double pn = x[2 * c], pt = x[2 * c + 1];
      const double n = std::max(pn, 0.0), t = std::clamp(pt, -mu[c] * n, mu[c] * n);
      if (n != pn || t != pt) moved.push_back({static_cast<std::uint32_t>(c), n - pn, t - pt});
      x[2 * c] = n;
      x[2 * c + 1] = t;
    }
    std::copy(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(nx), x0.begin());
    return true;
  }
};

TEST(AndersonMixer, AgreesWithThePlainTextbookStep) {
  // 13 contacts and 3 links (29 impulses), 6 velocities (35 in all): no multiple of the 4 or 8 the loops
  // work by. The map: x ← A x + b, a random contraction, with a jump in b now and then (the
  // residual more than doubles: a restart), velocities affine in the impulses; μ = 0.3, and b
  // pulls some P_N below 0 and some P_T out of the cone (moves)
  const std::size_t nc = 13, nl = 3, nx = 2 * nc + nl, nv = 6;
  std::uint64_t seed = 12345;
  auto uniform = [&seed] {  // in [−1, 1)
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(seed >> 11) * 0x1.0p-52 - 1.0;
  };
  Eigen::MatrixXd A(nx, nx), C(nv, nx);
  for (Eigen::Index i = 0; i < A.size(); ++i) A.data()[i] = uniform();
  for (Eigen::Index i = 0; i < C.size(); ++i) C.data()[i] = uniform();
  // ‖A‖₂ by power iteration on AᵀA (it agrees to the last bits): Eigen's operatorNorm() would
  // instantiate a self-adjoint eigensolver, the costliest template of the unit tests' build.
  Eigen::VectorXd w = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(nx));
  for (int it = 0; it < 300; ++it) w = (A.transpose() * (A * w)).normalized();
  A *= 0.9 / (A * w).norm();
  Eigen::VectorXd b(nx), e(nv);
  for (auto& v : b) v = 0.5 * uniform();
  for (auto& v : e) v = uniform();
  const std::vector<double> mu(nc, 0.3);
  // one chunk (the sequential orders' sums), and chunks as a colored layout's blocks (one empty)
  for (const std::vector<std::size_t>& chunks :
       {std::vector<std::size_t>{0, nx}, std::vector<std::size_t>{0, 6, 6, 14, 20, 26, nx}})
    for (int depth = 1; depth <= AndersonMixer::kMaxDepth; ++depth) {
      AndersonMixer m;
      m.start(nc, nl, nv, depth);
      m.set_chunks(chunks);
      Eigen::VectorXd x = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(nx));
      std::copy(x.data(), x.data() + nx, m.x());
      m.begin();
      PlainAnderson plain{nc, nx, nv, depth, std::vector<double>(x.data(), x.data() + nx), {}, {}};
      int mixes = 0, with_moves = 0;
      for (int call = 0; call < 40; ++call) {
        if (call % 13 == 12) b *= (call / 13) % 2 ? -0.25 : -4.0;  // a jump: the residual grows
        const Eigen::VectorXd gx = A * x + b, gv = C * gx + e;
        std::copy(gx.data(), gx.data() + nx, m.x());
        std::copy(gv.data(), gv.data() + nv, m.v());
        std::vector<double> ref(gx.data(), gx.data() + nx);
        ref.insert(ref.end(), gv.data(), gv.data() + nv);
        std::vector<AndersonMixer::Move> ref_moved;
        const bool mixed = m.mix(mu.data());
        ASSERT_EQ(mixed, plain.mix(ref, mu, ref_moved)) << "depth " << depth << " call " << call;
        double scale = 1.0;
        for (double v : ref) scale = std::max(scale, std::abs(v));
        for (std::size_t i = 0; i < nx; ++i)
          ASSERT_NEAR(m.x()[i], ref[i], 1e-6 * scale) << "depth " << depth << " call " << call << " x " << i;
        for (std::size_t i = 0; i < nv; ++i)
          ASSERT_NEAR(m.v()[i], ref[nx + i], 1e-6 * scale) << "depth " << depth << " call " << call << " v " << i;
        ASSERT_EQ(m.moved().size(), ref_moved.size()) << "depth " << depth << " call " << call;
        for (std::size_t j = 0; j < ref_moved.size(); ++j) {
          EXPECT_EQ(m.moved()[j].contact, ref_moved[j].contact);
          EXPECT_NEAR(m.moved()[j].dpn, ref_moved[j].dpn, 1e-6 * scale);
          EXPECT_NEAR(m.moved()[j].dpt, ref_moved[j].dpt, 1e-6 * scale);
        }
        mixes += mixed;
        with_moves += !ref_moved.empty();
        // the next period starts from the (mixed, projected) impulses
        for (std::size_t i = 0; i < nx; ++i) x[static_cast<Eigen::Index>(i)] = m.x()[i];
      }
      EXPECT_GT(m.restarts(), 0u) << "depth " << depth;
      EXPECT_GT(mixes, 20) << "depth " << depth;
      EXPECT_GT(with_moves, 5) << "depth " << depth;
    }
}

TEST(AndersonMixer, RestartAtNextIsAFreshStart) {
  // a mixer with a history, told to restart, then fed what a new mixer begun at that point is
  // fed: the same mixed iterates, bit for bit (nothing of the old history is left)
  const std::size_t nc = 5, nx = 2 * nc, nv = 4;
  auto feed = [&](AndersonMixer& m, int call) {
    for (std::size_t i = 0; i < nx; ++i) m.x()[i] = 0.3 * m.x()[i] + 0.1 * std::sin(1.0 + call + 0.7 * i) + (i % 2 ? 0.0 : 0.5);
    for (std::size_t i = 0; i < nv; ++i) m.v()[i] = 2.0 * m.x()[i] - m.x()[i + 1];
  };
  const std::vector<double> mu(nc, 0.4);
  AndersonMixer old_one, fresh;
  old_one.start(nc, 0, nv, 3);
  for (std::size_t i = 0; i < nx; ++i) old_one.x()[i] = 1.0;
  old_one.begin();
  for (int call = 0; call < 6; ++call) {
    feed(old_one, call);
    old_one.mix(mu.data());
  }
  EXPECT_GT(old_one.mixes(), 0u);
  old_one.restart_at_next();
  feed(old_one, 6);
  EXPECT_FALSE(old_one.mix(mu.data()));  // only records where the new history starts
  fresh.start(nc, 0, nv, 3);
  std::copy(old_one.x(), old_one.x() + nx, fresh.x());
  fresh.begin();
  const std::size_t before = old_one.mixes();
  for (int call = 7; call < 14; ++call) {
    feed(old_one, call);
    std::copy(old_one.x(), old_one.x() + nx + nv, fresh.x());
    const bool a = old_one.mix(mu.data()), b = fresh.mix(mu.data());
    ASSERT_EQ(a, b) << "call " << call;
    for (std::size_t i = 0; i < nx + nv; ++i) ASSERT_EQ(old_one.x()[i], fresh.x()[i]) << "call " << call << " entry " << i;
  }
  EXPECT_EQ(old_one.mixes() - before, fresh.mixes());
  EXPECT_GT(fresh.mixes(), 0u);
}

// The phases of a mixing, as threads that each own some chunks, contacts and velocities run
// them: the sums in two calls over the chunks taken backwards, the impulses and velocities in
// uneven pieces, the moves of two lists merged by contact. Against mix() with the same chunks:
// the same bits, the same moves, through mixings, restarts and a restart_at_next.
TEST(AndersonMixer, ItsPhasesInAnySplitGiveTheBitsOfMix) {
  const std::size_t nc = 13, nl = 3, nx = 2 * nc + nl, nv = 7;
  const std::vector<std::size_t> chunks{0, 6, 6, 14, 20, 26, 29};  // an empty one, the links'
  auto feed = [&](AndersonMixer& m, int call) {
    const double jump = call % 9 == 8 ? 5.0 : 1.0;  // the residual grows: a restart
    for (std::size_t i = 0; i < nx; ++i)
      m.x()[i] = 0.6 * m.x()[i] + jump * (0.2 * std::sin(1.0 + call + 0.7 * i) + (i % 2 ? 0.05 : 0.3));
    for (std::size_t i = 0; i < nv; ++i) m.v()[i] = 2.0 * m.x()[i] - m.x()[i + 3];
  };
  const std::vector<double> mu(nc, 0.2);
  AndersonMixer whole, parts;
  for (AndersonMixer* m : {&whole, &parts}) {
    m->start(nc, nl, nv, 3);
    m->set_chunks(chunks);
    for (std::size_t i = 0; i < nx; ++i) m->x()[i] = 0.1 * static_cast<double>(i);
    m->begin();
  }
  std::vector<AndersonMixer::Move> a, b, merged;
  std::size_t moves = 0;
  for (int call = 0; call < 40; ++call) {
    if (call == 23) whole.restart_at_next(), parts.restart_at_next();
    feed(whole, call);
    std::copy(whole.x(), whole.x() + nx + nv, parts.x());
    const bool mixed = whole.mix(mu.data());
    if (!parts.restarting()) parts.sums(4, 6), parts.sums(0, 4);
    const AndersonMixer::Verdict v = parts.decide(mu.data());
    a.clear(), b.clear();
    parts.apply_x(18, nx, b);  // contacts 9 … 12 and the links
    parts.apply_x(0, 18, a);
    parts.apply_v(5, nv), parts.apply_v(0, 5);
    merged = a;
    merged.insert(merged.end(), b.begin(), b.end());
    ASSERT_EQ(mixed, v == AndersonMixer::Verdict::Mixed) << "call " << call;
    for (std::size_t i = 0; i < nx + nv; ++i)
      ASSERT_EQ(parts.x()[i], whole.x()[i]) << "call " << call << " entry " << i;
    ASSERT_EQ(merged.size(), whole.moved().size()) << "call " << call;
    for (std::size_t j = 0; j < merged.size(); ++j) {
      EXPECT_EQ(merged[j].contact, whole.moved()[j].contact);
      EXPECT_EQ(merged[j].dpn, whole.moved()[j].dpn);
      EXPECT_EQ(merged[j].dpt, whole.moved()[j].dpt);
    }
    moves += merged.size();
  }
  EXPECT_EQ(parts.mixes(), whole.mixes());
  EXPECT_GT(whole.mixes(), 20u);
  EXPECT_GT(whole.restarts(), 0u);
  EXPECT_GT(moves, 0u);
  AndersonMixer bad;
  bad.start(nc, nl, nv, 3);
  EXPECT_THROW(bad.set_chunks({0, 10}), Error);  // short of the impulses' end
  EXPECT_THROW(bad.set_chunks({0, 12, 8, nx}), Error);  // not increasing
}

// A caller on threads puts its runs of contacts and velocities in regions of their own, out of
// the contacts' order, with unused slots between them (MixSlots): the same mixing as the
// contacts side by side, the same bits in every used entry, zero in the others, and the same
// moves once the shifts are taken off. Chunks as in the test above, each inside a run; then
// one chunk, away from entry 0.
TEST(AndersonMixer, ChunksWithSlotsBetweenThemGiveTheBitsOfTheContiguousLayout) {
  const std::size_t nc = 13, nl = 3, nx = 2 * nc + nl, nv = 7;
  struct Run {
    std::size_t first, end;
    std::ptrdiff_t shift;  // contacts first … end − 1 in slots from first + shift
  };
  const std::vector<Run> runs{{0, 3, 13}, {3, 7, -3}, {7, 13, 9}};  // slots 13 …, 0 …, 16 …
  const std::size_t slots = 24, gx = 2 * slots + nl, gv = 11;  // velocities 4 … 6 in 8 … 10
  auto slot_of = [&](std::size_t i) {  // x() entry i of the contiguous layout in the other
    if (i >= 2 * nc) return i - 2 * nc + 2 * slots;
    for (const Run& r : runs)
      if (i < 2 * r.end) return static_cast<std::size_t>(static_cast<std::ptrdiff_t>(i) + 2 * r.shift);
    return gx;
  };
  auto v_slot_of = [](std::size_t i) { return i < 4 ? i : i + 4; };
  const std::vector<double> mu(nc, 0.2);
  std::vector<double> gapped_mu(slots, 0.0);
  for (const Run& r : runs)
    for (std::size_t a = r.first; a < r.end; ++a) gapped_mu[slot_of(2 * a) / 2] = mu[a];
  for (const bool one_chunk : {false, true}) {
    AndersonMixer whole, gapped;
    whole.start(nc, nl, nv, 3);
    gapped.start(slots, nl, gv, 3);
    std::fill(gapped.x(), gapped.x() + gx, 0.0);
    std::fill(gapped.v(), gapped.v() + gv, 0.0);
    if (one_chunk) {  // contacts 3 … 6 alone, as a run of a system of 4 contacts
      whole.start(4, 0, nv, 3);
      gapped.set_chunks({0}, {8});
    } else {
      whole.set_chunks({0, 6, 6, 14, 20, 26, 29});
      gapped.set_chunks({26, 0, 0, 32, 38, 48}, {32, 0, 8, 38, 44, 51});
    }
    const std::size_t used = one_chunk ? 8 : nx, from = one_chunk ? 6 : 0;  // whole's entries, as entries from..
    auto feed = [&](int call) {
      const double jump = call % 9 == 8 ? 5.0 : 1.0;
      for (std::size_t i = 0; i < used; ++i)
        whole.x()[i] = 0.6 * whole.x()[i] + jump * (0.2 * std::sin(1.0 + call + 0.7 * i) + (i % 2 ? 0.05 : 0.3));
      for (std::size_t i = 0; i < nv; ++i) whole.v()[i] = 2.0 * whole.x()[i] - whole.x()[(i + 3) % used];
      for (std::size_t i = 0; i < used; ++i) gapped.x()[slot_of(i + from)] = whole.x()[i];
      for (std::size_t i = 0; i < nv; ++i) gapped.v()[v_slot_of(i)] = whole.v()[i];
    };
    for (std::size_t i = 0; i < used; ++i) whole.x()[i] = 0.1 * static_cast<double>(i);
    feed(-1);
    whole.begin();
    gapped.begin();
    std::vector<AndersonMixer::Move> moves;
    for (int call = 0; call < 40; ++call) {
      feed(call);
      const bool mixed = whole.mix(mu.data() + from / 2);
      if (!gapped.restarting()) gapped.sums(0, gapped.chunks());
      const AndersonMixer::Verdict v = gapped.decide(gapped_mu.data());
      moves.clear();
      if (one_chunk) {
        gapped.apply_x(0, 8, moves, 0);  // (slots 0 … 3 as whole's contacts 0 … 3)
      } else {
        for (const Run& r : runs) gapped.apply_x(slot_of(2 * r.first), slot_of(2 * r.end - 1) + 1, moves, r.shift);
        gapped.apply_x(2 * slots, gx, moves);
      }
      gapped.apply_v(0, 4), gapped.apply_v(8, 11);
      ASSERT_EQ(mixed, v == AndersonMixer::Verdict::Mixed) << "call " << call;
      std::vector<double> expect_x(gx, 0.0), expect_v(gv, 0.0);
      for (std::size_t i = 0; i < used; ++i) expect_x[slot_of(i + from)] = whole.x()[i];
      for (std::size_t i = 0; i < nv; ++i) expect_v[v_slot_of(i)] = whole.v()[i];
      ASSERT_EQ(std::vector<double>(gapped.x(), gapped.x() + gx), expect_x) << "call " << call;
      ASSERT_EQ(std::vector<double>(gapped.v(), gapped.v() + gv), expect_v) << "call " << call;
      ASSERT_EQ(moves.size(), whole.moved().size()) << "call " << call;
      for (std::size_t j = 0; j < moves.size(); ++j) {
        EXPECT_EQ(moves[j].contact, whole.moved()[j].contact);
        EXPECT_EQ(moves[j].dpn, whole.moved()[j].dpn);
        EXPECT_EQ(moves[j].dpt, whole.moved()[j].dpt);
      }
    }
    EXPECT_EQ(gapped.mixes(), whole.mixes());
    EXPECT_GT(whole.mixes(), 20u);
  }
  AndersonMixer bad;
  bad.start(nc, nl, nv, 3);
  EXPECT_THROW(bad.set_chunks({0, 8}, {6}), Error);          // not one end a chunk
  EXPECT_THROW(bad.set_chunks({0, 8}, {10, 20}), Error);     // the first ends after the second begins
  EXPECT_THROW(bad.set_chunks({0, 8}, {6, nx + 1}), Error);  // past the impulses
}

// The arrays' entries begin the lines asked into a page (the mixer skews its arrays apart so that
// no two of them begin at one place of a page), and keep their values as they grow.
TEST(SkewedPages, EntriesBeginTheLinesAskedIntoAPage) {
  for (const std::size_t lines : {std::size_t{0}, std::size_t{2}, std::size_t{56}}) {
    SkewedPages<double> a;
    a.resize(100, lines);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(a.data()) % kPage, lines * kCacheLine);
    a.data()[99] = 3.0;
    a.resize(5000, lines);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(a.data()) % kPage, lines * kCacheLine);
    EXPECT_EQ(a.data()[99], 3.0);
    EXPECT_EQ(a.data()[4999], 0.0);
  }
  AndersonMixer m;
  m.start(700, 3, 2100, 8);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(m.x()) % kCacheLine, 0u);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(m.v()) % kCacheLine, 0u);
}

TEST(AndersonMixer, RefusesADepthOutsideOneToEight) {
  AndersonMixer m;
  EXPECT_THROW(m.start(1, 0, 3, 0), Error);
  EXPECT_THROW(m.start(1, 0, 3, AndersonMixer::kMaxDepth + 1), Error);
}

}  // namespace
