// tests/ballast/test_ballast_run.cpp — the ballast study end to end on the tiny sample: the
// outputs of a short run (settlement, one cycles.csv row per cycle, bounded overlaps), the
// sleeper load F(t) as the stepper sees it, and the refusal of bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "ballast_test_support.hpp"
#include "nscd/bodies/rbdy2.hpp"
#include "nscd/core/math.hpp"
#include "nscd/io/checkpoint.hpp"
#include "nscd/shared/ballast.hpp"

using namespace ballast_test;

namespace {

// 1. A short run: 5 cycles of the tiny sample.
TEST(BallastRun, ShortRunSettlesWithBoundedOverlaps) {
  TempDir dir("short");
  const ballast::Config c = tiny_config(dir.path(), 5);
  ASSERT_EQ(ballast::run(c), 0);

  // summary.txt: the settlement at the smallest load of the last cycle. The load pushes the
  // sleeper down (A + B < A − B < 0), so it is positive; it stays below the layer's thickness
  // (36 grains of 1–2 cm over a 0.2 m box: about 4 rows, ≈ 5 cm), else the sleeper went through.
  const auto sum = read_summary(dir / "summary.txt");
  ASSERT_TRUE(sum.count("final_settlement"));
  const double settlement = std::stod(sum.at("final_settlement"));
  EXPECT_TRUE(std::isfinite(settlement));
  EXPECT_GT(settlement, 0.0);
  EXPECT_LT(settlement, 0.05);
  EXPECT_EQ(sum.at("cycles"), "5");
  EXPECT_EQ(sum.at("steps_per_cycle"), "250");  // 1 / (20 Hz · 2e-4 s)
  EXPECT_EQ(sum.at("grains"), "36");            // round(0.05 · 361) + round(0.05 · 242) + round(0.05 · 121) = 18 + 12 + 6
  EXPECT_EQ(sum.at("pads"), "10");

  // cycles.csv: one row per cycle, numbered 1..5, one period (1/f = 0.05 s) apart.
  const Csv cy = read_csv(dir / "cycles.csv");
  ASSERT_EQ(cy.rows.size(), 5u);
  for (std::size_t i = 0; i < cy.rows.size(); ++i) {
    EXPECT_EQ(cy.rows[i][cy.column("cycle")], std::to_string(i + 1));
    EXPECT_TRUE(std::isfinite(cy.value(i, "settlement_min_load")));
    EXPECT_TRUE(std::isfinite(cy.value(i, "settlement_max_load")));
    if (i > 0) {
      EXPECT_NEAR(cy.value(i, "time") - cy.value(i - 1, "time"), 0.05, 1e-9);
    }
  }
  const double last = cy.value(4, "settlement_min_load");
  EXPECT_GT(last, 0.0);
  EXPECT_NEAR(last, settlement, 1e-9 * settlement);  // summary.txt has 10 significant digits

  // steps.csv (steps_every = 1): one row per step; the last step of the last cycle is where the
  // cycle's settlement at the smallest load is read, so the two files hold the same double.
  const Csv st = read_csv(dir / "steps.csv");
  ASSERT_EQ(st.rows.size(), 5u * 250u);
  EXPECT_EQ(st.rows.back()[st.column("settlement")], cy.rows.back()[cy.column("settlement_min_load")]);

  // Overlaps. With IQS_CLB a contact's end-of-step gap g_f = g_m + θ h U_N is kept >= 0 by the
  // solver up to its tolerance, so an overlap only builds up over one step in which a contact
  // closes faster than the linearised gap foresees: at most v·dt. The fastest grains of the
  // tiny sample fall from the top of the start lattice, ≈ 0.1 m above the pads:
  // v = √(2 · 9.81 · 0.1) ≈ 1.4 m/s, v·dt ≈ 2.8e-4 m. We ask for less, 2e-4 m = d_min / 50 =
  // 0.16 × the alert distance 1.25e-3 m: more means contacts are missed or the solver is far
  // from converged. (Observed: ≈ 5e-5 m, left from the deposit.)
  const double bound = 2e-4;
  double max_row = 0.0;
  for (std::size_t i = 0; i < cy.rows.size(); ++i) {
    EXPECT_LT(cy.value(i, "max_overlap"), bound) << "cycle " << i + 1;
    EXPECT_LE(cy.value(i, "mean_overlap"), cy.value(i, "max_overlap"));
    max_row = std::max(max_row, cy.value(i, "max_overlap"));
  }
  const double max_overlap = std::stod(sum.at("max_overlap"));
  EXPECT_LT(max_overlap, bound);
  // The cumulated overlap (issue #10): each step's total over its overlapping points is at least
  // their mean, so the cycle means keep that order; the summary's is the mean over the steps,
  // here the mean of the five cycles' (every cycle has 250 steps).
  double total_sum = 0.0;
  for (std::size_t i = 0; i < cy.rows.size(); ++i) {
    EXPECT_GE(cy.value(i, "total_overlap"), cy.value(i, "mean_overlap")) << "cycle " << i + 1;
    total_sum += cy.value(i, "total_overlap");
  }
  EXPECT_GT(total_sum, 0.0);
  const double cumulated = std::stod(sum.at("cumulated_overlap"));
  EXPECT_NEAR(cumulated, total_sum / 5.0, 1e-9 * cumulated);
  EXPECT_GE(std::stod(sum.at("cpu_time_per_cycle")), 0.0);
  EXPECT_NEAR(max_overlap, max_row, 1e-9 * max_row);  // the summary's is the max over the cycles
  // max_sweeps (issue #10): the most iterations in one step, i.e. the largest `sweeps` of
  // steps.csv (every step is there), and at least the mean.
  double most = 0.0;
  for (std::size_t i = 0; i < st.rows.size(); ++i) most = std::max(most, st.value(i, "sweeps"));
  EXPECT_EQ(std::stod(sum.at("max_sweeps")), most);
  EXPECT_GE(most, std::stod(sum.at("mean_sweeps")));
}

// 3. The sleeper load with the paper's values: A = −1000 N, B = −500 N, f = 20 Hz, φ = −π,
// ramp-in over one cycle, inclined β = 10° toward +x.
TEST(BallastRun, SleeperLoadFollowsTheCosineAndTheInclination) {
  TempDir dir("load");
  ballast::Config c = tiny_config(dir.path(), 1);
  c.load_mean = -1000.0;
  c.load_amplitude = -500.0;
  c.frequency = 20.0;
  c.phase = -nscd::kPi;
  c.ramp_cycles = 1.0;
  c.inclination = 10.0;
  ASSERT_EQ(ballast::run(c), 0);

  nscd::Checkpoint cp = nscd::load_checkpoint(dir / "checkpoint.nscd");
  const double t0 = std::strtod(cp.extra.at("state.t0").c_str(), nullptr);
  nscd::scenes::BallastScene s = nscd::scenes::recognise_ballast(std::move(cp.reg));
  const nscd::Registry& reg = s.scene.reg;
  ASSERT_TRUE(s.sleeper.valid());
  const double m = reg.bodies.mass[s.sleeper.index()];
  const nscd::Vec2 g = reg.params.gravity;
  // the imposed force alone: external_force − m g
  auto imposed = [&](double t) {
    const nscd::BodyForce f = nscd::external_force(reg, s.sleeper, t);
    return nscd::Vec2{f.fx - m * g.x, f.fy - m * g.y};
  };
  const double beta = 10.0 * nscd::kPi / 180.0, cb = std::cos(beta), sb = std::sin(beta);
  // F(s) = ramp(s) (A + B cos(2π f s − φ)), ramp(s) = min(1, s / 0.05 s); with φ = −π,
  // cos(2π f s + π) = −cos(2π f s). By hand:
  //   s = 0        ramp 0                              F = 0
  //   s = 0.0125   ramp 1/4, cos(π/2 + π) = 0          F = ¼ (−1000)          = −250
  //   s = 0.025    ramp 1/2, cos(π + π)   = 1          F = ½ (−1000 − 500)    = −750
  //   s = 0.05     ramp 1,   cos(2π + π)  = −1         F = −1000 + 500        = −500
  //   s = 0.075    ramp 1,   cos(3π + π)  = 1          F = −1000 − 500        = −1500
  // and F_y = F cos β (F_y(0.025) = −738.6058…), F_x = −F sin β (F_x(0.025) = +130.2361…).
  const double cases[][2] = {{0.0, 0.0}, {0.0125, -250.0}, {0.025, -750.0}, {0.05, -500.0}, {0.075, -1500.0}};
  for (const auto& [sec, F] : cases) {
    const nscd::Vec2 f = imposed(t0 + sec);
    EXPECT_NEAR(f.y, F * cb, 1e-9) << "s = " << sec;
    EXPECT_NEAR(f.x, -F * sb, 1e-9) << "s = " << sec;
  }
  EXPECT_NEAR(imposed(t0 + 0.025).y, -738.6058147591, 1e-9);
  EXPECT_NEAR(imposed(t0 + 0.025).x, 130.2361332501977, 1e-9);
  // nothing before t0 (the preparation ran without load)
  for (const double sec : {-1e-9, -0.01, -t0}) {
    EXPECT_EQ(imposed(t0 + sec).x, 0.0) << "s = " << sec;
    EXPECT_EQ(imposed(t0 + sec).y, 0.0) << "s = " << sec;
  }

  // The driver's own read-back in steps.csv (column load = F_y at the end of each step) over
  // the cycle: F_y(t) = ramp(s) (A + B cos(2π f s − φ)) cos β, s = t − t0.
  const Csv st = read_csv(dir / "steps.csv");
  ASSERT_EQ(st.rows.size(), 250u);
  for (std::size_t i = 0; i < st.rows.size(); ++i) {
    const double sec = st.value(i, "time") - t0;
    const double F = std::min(1.0, sec / 0.05) * (-1000.0 - 500.0 * std::cos(2.0 * nscd::kPi * 20.0 * sec + nscd::kPi));
    EXPECT_NEAR(st.value(i, "load"), F * cb, 1e-9) << "row " << i;
  }
  EXPECT_NEAR(st.value(0, "time") - t0, 2e-4, 1e-12);  // the first row is after one step
}

// 4. Bad input.
bool parse_run_args(std::vector<std::string> args, ballast::Config& c) {
  args.insert(args.begin(), "ballast");
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  return ballast::parse(static_cast<int>(argv.size()), argv.data(), c);
}

std::string run_parse_error(const std::vector<std::string>& args) {
  ballast::Config c;
  try {
    parse_run_args(args, c);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no std::invalid_argument thrown)";
}

TEST(BallastInput, ParseAcceptsGoodOptions) {
  ballast::Config c;
  // 1 / (20 Hz · 2.5e-4 s) = 200 steps per cycle: an integer
  ASSERT_TRUE(parse_run_args({"--dt", "2.5e-4", "--cycles", "7", "--inclination", "-15"}, c));
  EXPECT_EQ(c.dt, 2.5e-4);
  EXPECT_EQ(c.cycles, 7);
  EXPECT_EQ(c.inclination, -15.0);
}

TEST(BallastInput, ParseRejectsBadOptions) {
  // 1 / (20 Hz · 3e-4 s) = 166.67 steps per cycle: not an integer
  EXPECT_NE(run_parse_error({"--dt", "3e-4"}).find("steps per cycle"), std::string::npos) << run_parse_error({"--dt", "3e-4"});
  // 1 / (30 Hz · 2e-4 s) = 166.67 as well, with the default dt
  EXPECT_NE(run_parse_error({"--frequency", "30"}).find("steps per cycle"), std::string::npos);
  EXPECT_NE(run_parse_error({"--cycles", "-3"}).find("--cycles"), std::string::npos) << run_parse_error({"--cycles", "-3"});
  EXPECT_NE(run_parse_error({"--no-such-option", "1"}).find("no-such-option"), std::string::npos)
      << run_parse_error({"--no-such-option", "1"});
  EXPECT_NE(run_parse_error({"--dt", "fast"}).find("dt"), std::string::npos) << run_parse_error({"--dt", "fast"});
  EXPECT_NE(run_parse_error({"--k-factor", "0"}).find("--k-factor"), std::string::npos);
  EXPECT_NE(run_parse_error({"--inclination", "95"}).find("--inclination"), std::string::npos);
  ballast::Config c;
  EXPECT_THROW(parse_run_args({"--cycles", "-1"}, c), std::invalid_argument);
}

TEST(BallastInput, ResumeWithoutCheckpointNamesTheFile) {
  TempDir dir("nocheckpoint");
  ballast::Config c;
  c.resume = dir.path().string();
  c.progress_every = 1e9;
  const std::string file = (dir.path() / "checkpoint.nscd").string();
  try {
    ballast::run(c);
    FAIL() << "resuming a directory without checkpoint did not throw";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
  }
  // nothing was written into the directory
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

}  // namespace
