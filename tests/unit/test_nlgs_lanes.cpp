// tests/unit/test_nlgs_lanes.cpp — the colored order's SIMD lanes (src/solvers/nlgs_lanes.hpp)
// give the scalar colored sweep's numbers, bit for bit:
//   - on a made-up system that reaches every branch of the local solve (open, stick, both
//     slides, the cone's edge, degenerate blocks with no stick or no slide, the frictionless
//     closure), with kinematic bodies shared by the lanes and idle lanes at the end of a colour:
//     impulses, velocities, statuses and convergence sums, for the AVX2 and the SSE2 kernels;
//   - the deal: every contact in one lane once, each block closed once, longest blocks first;
//   - on a running scene (a compressed field of pentagons under gravity, 12 steps, relaxed):
//     the same state hash and sweeps with lanes 0, 2 and 4, on 1 and 2 threads.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "nscd/core/error.hpp"
#include "nscd/shared/samples.hpp"
#include "nscd/solvers/moreau_jean.hpp"
#include "nscd/solvers/nlgs_colored.hpp"
#include "nscd/solvers/nlgs_lanes.hpp"
#include "threads.hpp"

namespace {

using namespace nscd;

bool same_double_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// `blocks` groups of 256 consecutive contacts, each among its own 6 dynamic bodies and two
/// kinematic bodies shared by all groups (a moving floor and a fixed wall); random frames,
/// lever arms, shifts and warm starts, and some blocks made degenerate on purpose.
ContactSystem made_up_system(int blocks, int last_block_size, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ContactSystem sys;
  SolverBody floor;  // kinematic: moving, never written
  floor.vx = 0.3, floor.vy = -0.2, floor.w = 0.1;
  sys.bodies.push_back(floor);
  sys.bodies.push_back(SolverBody{});  // kinematic, at rest
  constexpr int kBodies = 6;
  for (int b = 0; b < blocks; ++b)
    for (int i = 0; i < kBodies; ++i) {
      SolverBody s;
      s.vx = u(rng), s.vy = u(rng), s.w = 5.0 * u(rng);
      s.inv_mx = s.inv_my = 1.0 + 0.5 * u(rng);
      s.inv_i = 200.0 * (1.0 + 0.5 * u(rng));
      if (i == 0) s.inv_mx = 0.0;  // a body with a driven dof: dynamic, but not along x
      sys.bodies.push_back(s);
    }
  for (int b = 0; b < blocks; ++b) {
    const int size = b + 1 == blocks ? last_block_size : 256;
    for (int k = 0; k < size; ++k) {
      SolverContact c;
      const auto first = static_cast<std::uint32_t>(2 + b * kBodies);
      c.cd = first + static_cast<std::uint32_t>(rng() % kBodies);
      const int pick = static_cast<int>(rng() % 8);
      c.an = pick == 0 ? 0u : pick == 1 ? 1u : first + static_cast<std::uint32_t>(rng() % kBodies);
      if (c.an == c.cd) c.an = 0;
      if (pick == 2) c.an = c.cd, c.cd = 1;  // a kinematic candidate, a dynamic antagonist
      const double a = 3.14159 * u(rng);
      c.nx = std::cos(a), c.ny = std::sin(a);
      c.cd_rn = 0.01 * u(rng), c.cd_rt = 0.01 * u(rng), c.an_rn = 0.01 * u(rng), c.an_rt = 0.01 * u(rng);
      c.cd_dynamic = c.cd >= 2;
      c.an_dynamic = c.an >= 2;
      c.mu = (rng() % 5 == 0) ? 0.0 : 0.5 * (1.0 + u(rng));
      c.W = delassus_block(c, sys.bodies[c.cd], sys.bodies[c.an]);
      c.f = coulomb_factors(c.W, c.mu);
      switch (rng() % 10) {  // degenerate blocks: a case that does not exist
        case 0: c.f.inv_det = 0.0; break;
        case 1: c.f.inv_den_fwd = 0.0; break;
        case 2: c.f.inv_den_bwd = 0.0; break;
        case 3: c.f.inv_det = c.f.inv_den_fwd = c.f.inv_den_bwd = 0.0; break;  // closure
        default: break;
      }
      c.sn = 0.5 * u(rng), c.st = 0.5 * u(rng);
      if (rng() % 4 == 0) {  // warm start
        c.pn = 0.1 * (1.0 + u(rng));
        c.pt = 0.5 * c.mu * c.pn * u(rng);
      }
      sys.contacts.push_back(c);
    }
  }
  sys.rows.resize(sys.contacts.size());
  for (std::size_t i = 0; i < sys.rows.size(); ++i) sys.rows[i] = static_cast<std::uint32_t>(i);
  sys.status.assign(sys.contacts.size(), ContactStatus::Open);
  return sys;
}

struct Solved {
  ContactSystem sys;
  NlgsResult res;
};

Solved solve_with(const ContactSystem& start, int lanes) {
  Solved s{start, {}};
  NlgsOptions o;
  o.order = SweepOrder::Colored;
  o.relaxation = 1.3;
  o.check_every = 3;
  o.min_sweeps = o.max_sweeps = 17;  // checked and unchecked sweeps, the last one checked
  o.lanes = lanes;
  NlgsColoredWorkspace ws;
  s.res = nlgs_iterate_colored(s.sys, o, ws);
  return s;
}

void expect_same_bits(const Solved& a, const Solved& b, const char* what) {
  ASSERT_EQ(a.sys.contacts.size(), b.sys.contacts.size());
  for (std::size_t i = 0; i < a.sys.contacts.size(); ++i) {
    ASSERT_TRUE(same_double_bits(a.sys.contacts[i].pn, b.sys.contacts[i].pn)) << what << ", contact " << i;
    ASSERT_TRUE(same_double_bits(a.sys.contacts[i].pt, b.sys.contacts[i].pt)) << what << ", contact " << i;
    ASSERT_EQ(a.sys.status[i], b.sys.status[i]) << what << ", contact " << i;
  }
  for (std::size_t i = 0; i < a.sys.bodies.size(); ++i) {
    ASSERT_TRUE(same_double_bits(a.sys.bodies[i].vx, b.sys.bodies[i].vx)) << what << ", body " << i;
    ASSERT_TRUE(same_double_bits(a.sys.bodies[i].vy, b.sys.bodies[i].vy)) << what << ", body " << i;
    ASSERT_TRUE(same_double_bits(a.sys.bodies[i].w, b.sys.bodies[i].w)) << what << ", body " << i;
  }
  const Criteria& x = a.res.criteria;
  const Criteria& y = b.res.criteria;
  EXPECT_EQ(x.n_active, y.n_active) << what;
  EXPECT_TRUE(same_double_bits(x.mean_dvor, y.mean_dvor)) << what;
  EXPECT_TRUE(same_double_bits(x.quad_dv, y.quad_dv)) << what;
  EXPECT_TRUE(same_double_bits(x.maxm_dv, y.maxm_dv)) << what;
  EXPECT_TRUE(same_double_bits(x.quad_dvr, y.quad_dvr)) << what;
  EXPECT_TRUE(same_double_bits(x.maxm_dvr, y.maxm_dvr)) << what;
  EXPECT_EQ(a.res.sweeps, b.res.sweeps) << what;
}

TEST(NlgsLanes, EveryCaseOfTheLocalSolveGivesTheScalarBits) {
  if (!lanes_available()) GTEST_SKIP() << "no SIMD lane kernel on this architecture";
  // 11 blocks in one colour (no shared dynamic body): more blocks than a bundle's 8 lanes, the
  // last block shorter than the others, so lanes idle at the end
  const ContactSystem start = made_up_system(11, 131, 7);
  const Solved scalar = solve_with(start, 0);
  // every branch reached, in the final statuses and through the degenerate blocks
  std::size_t per_status[4] = {};
  for (ContactStatus s : scalar.sys.status) ++per_status[static_cast<int>(s)];
  for (int k = 0; k < 4; ++k) EXPECT_GT(per_status[k], 20u) << "status " << k;
  EXPECT_GT(scalar.res.criteria.n_active, 200u);
  EXPECT_TRUE(std::isfinite(scalar.res.criteria.quad_dv));
  expect_same_bits(scalar, solve_with(start, 2), "SSE2 kernel");
  expect_same_bits(scalar, solve_with(start, 4), "AVX2 kernel (SSE2 without AVX2)");
  // the floor and the wall are kinematic: read by every lane, written by none
  std::size_t kinematic_candidates = 0;
  for (const SolverContact& c : start.contacts) kinematic_candidates += !c.cd_dynamic;
  EXPECT_GT(kinematic_candidates, 100u);
  EXPECT_EQ(scalar.sys.bodies[0].vx, 0.3);
  EXPECT_EQ(solve_with(start, 4).sys.bodies[0].vx, 0.3);
}

TEST(NlgsLanes, BundlesDealEveryContactOnceAndEndEachBlock) {
  const ContactSystem sys = made_up_system(6, 40, 3);
  std::vector<std::uint32_t> block_start;
  for (std::uint32_t b = 0; b <= 6; ++b) block_start.push_back(std::min<std::uint32_t>(b * 256, 5 * 256 + 40));
  block_start.insert(block_start.begin() + 2, 256);  // an empty block (1) is skipped
  std::vector<ContactBundle> bundles;
  std::vector<std::uint32_t> order;
  append_bundles(sys.contacts, sys.bodies.data(), block_start.data(), 0, 7, bundles, order);
  std::vector<int> seen(sys.contacts.size(), 0);
  std::vector<int> ends(7, 0);
  for (const ContactBundle& b : bundles)
    for (int j = 0; j < ContactBundle::kLanes; ++j) {
      if (b.id[j] == ContactBundle::kIdleLane) {
        EXPECT_FALSE(b.write_cd[j] || b.write_an[j] || b.block_ends[j]);
        continue;
      }
      ++seen[b.id[j]];
      EXPECT_GE(b.id[j], block_start[b.block[j]]);
      EXPECT_LT(b.id[j], block_start[b.block[j] + 1]);
      ends[b.block[j]] += b.block_ends[j];
      if (b.block_ends[j]) {
        EXPECT_EQ(b.id[j] + 1, block_start[b.block[j] + 1]);
      }
      EXPECT_EQ(b.pn[j], sys.contacts[b.id[j]].pn);
      // each body by its place in words, which body_at turns back into the body
      const SolverContact& c = sys.contacts[b.id[j]];
      EXPECT_EQ(&body_at(sys.bodies.data(), b.cd_word[j]), &sys.bodies[c.cd]);
      EXPECT_EQ(&body_at(sys.bodies.data(), b.an_word[j]), &sys.bodies[c.an]);
    }
  for (std::size_t i = 0; i < seen.size(); ++i) EXPECT_EQ(seen[i], 1) << "contact " << i;
  for (std::uint32_t b = 0; b < 7; ++b) EXPECT_EQ(ends[b], block_start[b + 1] > block_start[b] ? 1 : 0) << "block " << b;
  // 6 non-empty blocks on 8 lanes: as many bundles as the longest block has contacts
  EXPECT_EQ(bundles.size(), 256u);
  // a half of four lanes writes all its rows (the AVX2 sweep's untested stores) exactly where
  // each lane is live between two dynamic bodies; both kinds of half occur here
  int all_written = 0, some_not = 0;
  for (const ContactBundle& b : bundles)
    for (int h = 0; h < ContactBundle::kLanes; h += 4) {
      bool all = true;
      for (int j = h; j < h + 4; ++j) all = all && b.write_cd[j] && b.write_an[j];
      EXPECT_EQ(b.writes_all[h / 4], all ? 1 : 0);
      ++(all ? all_written : some_not);
    }
  EXPECT_GT(all_written, 10);
  EXPECT_GT(some_not, 10);
}

TEST(NlgsLanes, StreamedBundlesGiveTheSameBits) {
  if (!lanes_available()) GTEST_SKIP() << "no SIMD lane kernel on this architecture";
  // Bundles larger than the L3 (a system of ~90,000 contacts and more) are streamed: built
  // without the inverse masses (ContactBundle), which the sweep reads from the bodies, and
  // prefetched ahead. The same sweeps on MassBundles and on ContactBundles, relaxed and
  // checked, in both kernels, give the same bits (impulses, velocities, sums, statuses).
  const ContactSystem sys = made_up_system(11, 131, 11);
  std::vector<std::uint32_t> block_start;
  for (std::uint32_t b = 0; b <= 11; ++b) block_start.push_back(std::min<std::uint32_t>(b * 256, 10 * 256 + 131));
  std::vector<std::uint32_t> order;
  std::vector<MassBundle> cached;
  std::vector<ContactBundle> streamed;
  append_bundles(sys.contacts, sys.bodies.data(), block_start.data(), 0, 11, cached, order);
  append_bundles(sys.contacts, sys.bodies.data(), block_start.data(), 0, 11, streamed, order);
  ASSERT_GT(cached.size(), 3u);  // more bundles than the prefetch distance
  ASSERT_EQ(cached.size(), streamed.size());
  EXPECT_LT(sizeof(ContactBundle), sizeof(MassBundle));
  for (int width : {2, 4}) {
    struct Run {
      std::vector<SolverBody> bodies;
      std::vector<CriteriaAccumulator> sums;
      std::vector<ContactStatus> status;
      std::vector<double> pn, pt;
    } run[2];
    auto sweep = [&](Run& r, auto bundles) {
      r.bodies = sys.bodies;
      r.sums.assign(11, CriteriaAccumulator{});
      r.status = sys.status;
      for (int sweep = 1; sweep <= 7; ++sweep)
        sweep_bundles(bundles.data(), bundles.data() + bundles.size(), r.bodies.data(), 1.3, sweep % 3 == 0,
                      r.sums.data(), width);
      std::vector<SolverContact> contacts = sys.contacts;
      bundle_results_to_contacts(bundles.data(), bundles.data() + bundles.size(), contacts.data(), r.status.data());
      for (const auto& b : bundles)
        for (int j = 0; j < ContactBundle::kLanes; ++j) r.pn.push_back(b.pn[j]), r.pt.push_back(b.pt[j]);
    };
    sweep(run[0], cached);
    sweep(run[1], streamed);
    for (std::size_t k = 0; k < run[0].pn.size(); ++k) {
      ASSERT_TRUE(same_double_bits(run[0].pn[k], run[1].pn[k])) << "width " << width << ", lane " << k;
      ASSERT_TRUE(same_double_bits(run[0].pt[k], run[1].pt[k])) << "width " << width << ", lane " << k;
    }
    for (std::size_t i = 0; i < sys.bodies.size(); ++i) {
      ASSERT_TRUE(same_double_bits(run[0].bodies[i].vx, run[1].bodies[i].vx)) << "width " << width << ", body " << i;
      ASSERT_TRUE(same_double_bits(run[0].bodies[i].vy, run[1].bodies[i].vy)) << "width " << width << ", body " << i;
      ASSERT_TRUE(same_double_bits(run[0].bodies[i].w, run[1].bodies[i].w)) << "width " << width << ", body " << i;
    }
    EXPECT_NE(run[0].bodies[3].vx, sys.bodies[3].vx);  // the sweeps did something
    for (std::size_t b = 0; b < 11; ++b) {
      EXPECT_TRUE(same_double_bits(run[0].sums[b].sum_dv2, run[1].sums[b].sum_dv2)) << "block " << b;
      EXPECT_EQ(run[0].sums[b].n_active, run[1].sums[b].n_active) << "block " << b;
    }
    EXPECT_EQ(run[0].status, run[1].status);
    EXPECT_LT(std::count(run[0].status.begin(), run[0].status.end(), ContactStatus::Open),
              static_cast<std::ptrdiff_t>(run[0].status.size()));  // the checked sweeps wrote them
  }
  // the threshold: half an L3 of at least a MiB
  EXPECT_GE(stream_bytes(), std::size_t{512} << 10);
}

TEST(NlgsLanes, TheLongestBlocksAreDealtFirst) {
  // 12 blocks of 1, 2, …, 12 contacts on 8 lanes: longest first, the 12-contact block sets the
  // length (12 bundles); in index order the lanes would end unevenly (16 bundles)
  const ContactSystem sys = made_up_system(1, 78, 5);
  std::vector<std::uint32_t> block_start{0};
  for (std::uint32_t len = 1; len <= 12; ++len) block_start.push_back(block_start.back() + len);
  std::vector<ContactBundle> bundles;
  std::vector<std::uint32_t> order;
  append_bundles(sys.contacts, sys.bodies.data(), block_start.data(), 0, 12, bundles, order);
  EXPECT_EQ(bundles.size(), 12u);
  std::size_t live = 0;
  for (const ContactBundle& b : bundles)
    for (int j = 0; j < ContactBundle::kLanes; ++j) live += b.id[j] != ContactBundle::kIdleLane;
  EXPECT_EQ(live, 78u);
}

TEST(NlgsLanes, TheDealImprovesOnLongestFirst) {
  // Graham's worst case for longest-first on 8 lanes: blocks of 15, 15, 14, 14, …, 9, 9, 8, 8, 8
  // contacts (192). Longest first ends the last lane at 31 bundles; 24 (= 192 / 8) is the best
  // deal (three blocks a lane). Moving and swapping blocks off the longest lane must come below
  // 31, every contact still dealt once.
  std::vector<std::uint32_t> block_start{0};
  for (std::uint32_t len = 15; len >= 9; --len) {
    block_start.push_back(block_start.back() + len);
    block_start.push_back(block_start.back() + len);
  }
  for (int k = 0; k < 3; ++k) block_start.push_back(block_start.back() + 8);
  ASSERT_EQ(block_start.back(), 192u);
  const ContactSystem sys = made_up_system(1, 192, 9);
  std::vector<ContactBundle> bundles;
  std::vector<std::uint32_t> order;
  const auto blocks = static_cast<std::uint32_t>(block_start.size() - 1);
  append_bundles(sys.contacts, sys.bodies.data(), block_start.data(), 0, blocks, bundles, order);
  EXPECT_LE(bundles.size(), 26u);
  EXPECT_GE(bundles.size(), 24u);
  std::vector<int> seen(192, 0);
  for (const ContactBundle& b : bundles)
    for (int j = 0; j < ContactBundle::kLanes; ++j)
      if (b.id[j] != ContactBundle::kIdleLane) ++seen[b.id[j]];
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), 192);
}

TEST(NlgsLanes, ARunningSceneHasTheSameHashWithAndWithoutLanesOnOneAndTwoThreads) {
  // the compressed field of bench_nlgs under gravity: strips (colored) and cells (colored-rows),
  // relaxed sweeps, contacts appearing
  scenes::Scene s = scenes::pentagon_field(300, 0.01, 0.009);
  scenes::converge_to_centroid(s.reg, 0.1);
  struct Run {
    std::vector<double> rn, rt, vx, spin, x;
    std::vector<ContactStatus> status;
    int sweeps = 0;
  };
  auto run = [&](SweepOrder order, int lanes, int threads) {
    Registry reg = s.reg;
    StepperOptions o;
    o.nlgs.order = order;
    o.nlgs.relaxation = 1.3;
    o.nlgs.lanes = lanes;
    o.nlgs.threads = threads;
    o.threads = o.solve_threads = threads;
    MoreauJean mj(reg, o);
    Run r;
    for (int k = 0; k < 12; ++k) {
      mj.step();
      r.sweeps += mj.report().sweeps;
    }
    r.rn = reg.contacts.rn, r.rt = reg.contacts.rt, r.status = reg.contacts.status;
    r.vx = reg.bodies.vx, r.spin = reg.bodies.spin, r.x = reg.bodies.x;
    return r;
  };
  for (SweepOrder order : {SweepOrder::Colored, SweepOrder::ColoredRows, SweepOrder::ColoredCells}) {
    SCOPED_TRACE(std::string(name_of(order)));
    const Run scalar = run(order, 0, 1);
    ASSERT_GT(scalar.rn.size(), 256u);  // strips or cells
    EXPECT_GT(scalar.sweeps, 12 * 10);
    for (int lanes : {2, 4})
      for (int threads : {1, 2}) {
        if (threads > 1 && !testing_support::threads_run_in_parallel()) continue;  // (skipped below)
        const Run r = run(order, lanes, threads);
        EXPECT_EQ(r.sweeps, scalar.sweeps) << lanes << " lanes, " << threads << " threads";
        EXPECT_EQ(r.rn, scalar.rn) << lanes << " lanes, " << threads << " threads";
        EXPECT_EQ(r.rt, scalar.rt) << lanes << " lanes, " << threads << " threads";
        EXPECT_EQ(r.status, scalar.status) << lanes << " lanes, " << threads << " threads";
        EXPECT_EQ(r.vx, scalar.vx) << lanes << " lanes, " << threads << " threads";
        EXPECT_EQ(r.spin, scalar.spin) << lanes << " lanes, " << threads << " threads";
        EXPECT_EQ(r.x, scalar.x) << lanes << " lanes, " << threads << " threads";
      }
  }
  NSCD_SKIP_WITHOUT_THREADS();  // the lanes were compared; say that the threads were not
}

TEST(NlgsLanes, LaneOptionIsChecked) {
  NlgsOptions o;
  o.lanes = 3;
  EXPECT_THROW(validate(o), Error);
  o.lanes = 8;
  EXPECT_THROW(validate(o), Error);
  for (int ok : {0, 2, 4}) {
    o.lanes = ok;
    EXPECT_NO_THROW(validate(o));
  }
}

}  // namespace
