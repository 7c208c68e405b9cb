// tests/unit/test_sample_file.cpp — the sample-file reader (shared/sample_file.hpp, issue #8):
// a good file gives the grains exactly as written, every defect is refused with the file, the
// line and the rule; LMGC90's exported sample (tests/data/lmgc90/deposit_700.txt) reads back
// as the 700 pentagons of the LMGC90 run.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "error_assertions.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/core/error.hpp"
#include "nscd/shared/sample_file.hpp"

namespace {

using namespace nscd;
using nscd::testing_support::Contains;
using nscd::testing_support::error_message;

// A line of the format for a regular pentagon (vertex k at theta + 2 pi k / 5).
std::string pentagon_line(int index, double x, double y, double r, double theta) {
  char buf[64];
  std::string s = std::to_string(index);
  for (double v : {x, y, r, theta}) {
    std::snprintf(buf, sizeof buf, " %.17g", v);
    s += buf;
  }
  for (const Vec2& v : transformed(regular_polygon(5, 2.0 * r), {x, y}, theta)) {
    std::snprintf(buf, sizeof buf, " %.17g %.17g", v.x, v.y);
    s += buf;
  }
  return s + "\n";
}

std::string parse_error(const std::string& text) {
  return error_message([&] { scenes::parse_sample_text(text, "bad.txt"); });
}

TEST(SampleFile, ReadsGrainsAndPlacesTheirVerticesExactly) {
  const std::string text = "# two pentagons\n\n" + pentagon_line(0, 0.1, 0.2, 0.02, 0.3) + "  # a comment line\n" +
                           pentagon_line(1, 0.3, 0.2, 0.0125, 1.1);
  const std::vector<scenes::SampleGrain> g = scenes::parse_sample_text(text, "good.txt");
  ASSERT_EQ(g.size(), 2u);
  EXPECT_EQ(g[0].line, 3u);
  EXPECT_EQ(g[1].line, 5u);
  EXPECT_DOUBLE_EQ(g[1].radius, 0.0125);
  EXPECT_DOUBLE_EQ(g[1].theta, 1.1);
  EXPECT_EQ(g[0].vertices.size(), 5u);
  Registry reg;
  const MaterialId m = add_material(reg, "grain", 2700.0);
  const std::vector<BodyId> b = scenes::add_sample_grains(reg, m, g);
  ASSERT_EQ(b.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(reg.bodies.x[b[i].index()], g[i].centre.x, 1e-15);
    EXPECT_NEAR(reg.bodies.y[b[i].index()], g[i].centre.y, 1e-15);
    EXPECT_DOUBLE_EQ(reg.bodies.angle[b[i].index()], g[i].theta);
    const Polygon w = world_polygon(reg, PolygId(static_cast<std::uint32_t>(i)));
    ASSERT_EQ(w.size(), 5u);
    for (std::size_t k = 0; k < 5; ++k) {
      EXPECT_NEAR(w[k].x, g[i].vertices[k].x, 1e-15);
      EXPECT_NEAR(w[k].y, g[i].vertices[k].y, 1e-15);
    }
  }
}

TEST(SampleFile, RefusesAWrongFieldCount) {
  const std::string m = parse_error(pentagon_line(0, 0.1, 0.2, 0.02, 0.3) + "1 0.3 0.2 0.02 0.1 0.3 0.2\n");
  EXPECT_TRUE(Contains(m, "sample file 'bad.txt', line 2:"));
  EXPECT_TRUE(Contains(m, "5 + 2n fields with n >= 3, got 7 fields"));
  EXPECT_TRUE(Contains(parse_error("0 0.1 0.2 0.02 0.3 0 0 1 0 1 1 0\n"), "got 12 fields"));
}

TEST(SampleFile, RefusesIndicesOutOfOrder) {
  const std::string m = parse_error(pentagon_line(0, 0.1, 0.2, 0.02, 0.3) + pentagon_line(2, 0.3, 0.2, 0.02, 0.3));
  EXPECT_TRUE(Contains(m, "line 2: grain index 2 out of order"));
  EXPECT_TRUE(Contains(m, "must be 1"));
}

TEST(SampleFile, RefusesBadNumbers) {
  std::string line = pentagon_line(0, 0.1, 0.2, 0.02, 0.3);
  line.replace(line.find(" 0.20000"), 4, " abc");  // y -> "abc..."
  const std::string m = parse_error(line);
  EXPECT_TRUE(Contains(m, "sample file 'bad.txt', line 1:"));
  EXPECT_TRUE(Contains(m, "y"));
  std::string nan_line = pentagon_line(0, 0.1, 0.2, 0.02, 0.3);
  nan_line.replace(nan_line.find(" 0.02"), 5, " nan ");
  EXPECT_TRUE(Contains(parse_error(nan_line), "line 1:"));
  EXPECT_TRUE(Contains(parse_error("0.5" + pentagon_line(0, 0.1, 0.2, 0.02, 0.3).substr(1)), "index"));
}

TEST(SampleFile, RefusesANonPositiveRadius) {
  std::string line = pentagon_line(0, 0.1, 0.2, 0.02, 0.3);
  line.replace(line.find(" 0.02"), 1, " -");
  EXPECT_TRUE(Contains(parse_error(line), "line 1: radius must be > 0"));
}

TEST(SampleFile, RefusesAClockwisePolygon) {
  // the same pentagon, its vertices listed clockwise
  std::string s = "0 0 0 1 0";
  for (int k = 4; k >= 0; --k) s += " " + std::to_string(std::cos(2 * kPi * k / 5)) + " " + std::to_string(std::sin(2 * kPi * k / 5));
  const std::string m = parse_error(s + "\n");
  EXPECT_TRUE(Contains(m, "line 1:"));
  EXPECT_TRUE(Contains(m, "grain 0"));
}

TEST(SampleFile, RefusesAVertexBeyondTheRadius) {
  // radius 0.019 while the vertices lie 0.02 from the centre
  std::string line = pentagon_line(0, 0.1, 0.2, 0.02, 0.3);
  line.replace(line.find(" 0.02"), 5, " 0.019");
  EXPECT_TRUE(Contains(parse_error(line), "line 1: vertex 0 lies"));
}

TEST(SampleFile, RefusesACentreThatIsNotTheCentroid) {
  // the vertices of a pentagon centred at (0.1, 0.2) given with the centre (0.1, 0.201)
  const std::string line = pentagon_line(0, 0.1, 0.2, 0.02, 0.3);
  std::size_t at = 0;
  for (int field = 0; field < 5; ++field) at = line.find(' ', at + 1);  // after "index x y radius theta"
  EXPECT_TRUE(Contains(parse_error("0 0.1 0.201 0.0215 0.3" + line.substr(at)), "line 1: the vertices' centroid"));
}

TEST(SampleFile, RefusesAnEmptyFileAndAMissingOne) {
  EXPECT_TRUE(Contains(parse_error("# nothing\n\n"), "no grain"));
  EXPECT_TRUE(Contains(parse_error(pentagon_line(0, 0.1, 0.2, 0.02, 0.3) + "\x01\n"), "line 2: control character"));
  EXPECT_TRUE(Contains(error_message([] { scenes::read_sample_file("/nonexistent/sample.txt"); }), "/nonexistent/sample.txt"));
}

// LMGC90's sample, exported by contrib/lmgc90/deposit_700.py: 700 pentagons of circumradius
// in [12.5, 25] mm on the 28 x 25 lattice of pitch 55 mm whose first row is 52.5 mm above the
// floor, file order = lattice order (rows left to right, bottom to top).
TEST(SampleFile, ReadsLmgc90sDeposit) {
  const std::vector<scenes::SampleGrain> g = scenes::read_sample_file(std::string(NSCD_TEST_DATA_DIR) + "/lmgc90/deposit_700.txt");
  ASSERT_EQ(g.size(), 700u);
  for (std::size_t i = 0; i < g.size(); ++i) {
    ASSERT_EQ(g[i].vertices.size(), 5u);
    EXPECT_GE(g[i].radius, 0.0125);
    EXPECT_LE(g[i].radius, 0.025);
    EXPECT_NEAR(g[i].centre.x, 0.0275 + 0.055 * double(i % 28), 1e-12) << "grain " << i;
    EXPECT_NEAR(g[i].centre.y, 0.0525 + 0.055 * double(i / 28), 1e-12) << "grain " << i;
  }
}

}  // namespace
