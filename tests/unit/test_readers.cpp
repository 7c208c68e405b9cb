// tests/unit/test_readers.cpp — the strict number parser and line reader (io/text_reader.hpp)
// and what the checkpoint reader refuses (issue #9: every reader validates, nothing read can
// crash, save never writes what load refuses). The fuzzers' crashers are kept in
// test_fuzz_regressions.cpp.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "error_assertions.hpp"
#include "nscd/bodies/rbdy2.hpp"
#include "nscd/contactors/polyg.hpp"
#include "nscd/core/error.hpp"
#include "nscd/io/checkpoint.hpp"
#include "nscd/io/text_reader.hpp"
#include "nscd/solvers/moreau_jean.hpp"

namespace {

using namespace nscd;
using nscd::testing_support::Contains;
using nscd::testing_support::error_message;
namespace fs = std::filesystem;

// ---- numbers ------------------------------------------------------------------------------

TEST(StrictNumbers, RealsAreReadWholeFiniteAndInRange) {
  EXPECT_EQ(parse_real("0.5", "x"), 0.5);
  EXPECT_EQ(parse_real("-2e-4", "x"), -2e-4);
  EXPECT_EQ(parse_real("0x1.8p+3", "x"), 12.0);  // std::hexfloat, as checkpoints write
  EXPECT_TRUE(Contains(error_message([] { parse_real("0.5x", "mu"); }), "mu: bad number '0.5x'"));
  EXPECT_TRUE(Contains(error_message([] { parse_real(" 1", "mu"); }), "bad number"));
  EXPECT_TRUE(Contains(error_message([] { parse_real("", "mu"); }), "found nothing"));
  EXPECT_TRUE(Contains(error_message([] { parse_real("inf", "rn"); }), "bad number 'inf'"));
  EXPECT_TRUE(Contains(error_message([] { parse_real("nan", "rn"); }), "bad number 'nan'"));
  EXPECT_TRUE(Contains(error_message([] { parse_real("-inf", "rn"); }), "not a finite number"));
  EXPECT_TRUE(Contains(error_message([] { parse_real("1e400", "rn"); }), "not a finite number"));
  EXPECT_TRUE(Contains(error_message([] { parse_real("2", "theta", 0.5, 1.0); }), "theta 2 is out of range [0.5, 1]"));
}

TEST(StrictNumbers, IntegersAreNotTruncated) {
  EXPECT_EQ(parse_integer("1000", "max-sweeps", 1, 1000000), 1000);
  EXPECT_EQ(parse_integer("-1", "law", -1, 3), -1);
  // the ballast resume read "1.5" and "1e9" as 1 (std::stoi)
  EXPECT_TRUE(Contains(error_message([] { parse_integer("1.5", "max-sweeps"); }), "max-sweeps: '1.5' is not an integer"));
  EXPECT_TRUE(Contains(error_message([] { parse_integer("1e9", "max-sweeps"); }), "'1e9' is not an integer"));
  EXPECT_TRUE(Contains(error_message([] { parse_integer("0", "steps-every", 1, 100); }), "steps-every 0 is out of range [1, 100]"));
  EXPECT_TRUE(Contains(error_message([] { parse_integer("99999999999999999999", "n"); }), "out of range"));
  EXPECT_TRUE(Contains(error_message([] { parse_integer("+3", "n"); }), "not an integer"));
  EXPECT_EQ(parse_unsigned("18446744073709551615", "seed"), std::numeric_limits<std::uint64_t>::max());
  EXPECT_TRUE(Contains(error_message([] { parse_unsigned("-1", "seed"); }), "not an unsigned integer"));
  EXPECT_TRUE(parse_bool("true", "b"));
  EXPECT_FALSE(parse_bool("0", "b"));
  EXPECT_TRUE(Contains(error_message([] { parse_bool("yes", "guided-sleeper"); }), "not a boolean"));
}

TEST(StrictNumbers, ExactTextReadsBackToTheSameBits) {
  EXPECT_EQ(exact(0.4999999), "0.4999999");
  EXPECT_EQ(exact(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(parse_real(exact(1.0 / 3.0), "x"), 1.0 / 3.0);
}

// ---- key = value files ---------------------------------------------------------------------

class ReaderDir : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir = fs::temp_directory_path() / ("nscd_readers_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir / name, std::ios::binary) << text;
    return dir / name;
  }
  fs::path dir;
};

TEST_F(ReaderDir, KeyValueFilesNameTheFileAndTheLine) {
  const auto ok = read_key_value_file(write("ok.cfg", "# comment\n\ndt = 2e-4\n  mu=0.5  \r\noutput =\n"));
  ASSERT_EQ(ok.size(), 3u);
  EXPECT_EQ(ok[0].key, "dt");
  EXPECT_EQ(ok[0].line, 3u);
  EXPECT_EQ(ok[1].value, "0.5");
  EXPECT_EQ(ok[2].value, "");
  const fs::path twice = write("twice.cfg", "dt = 1\n\ndt = 2\n");
  const std::string m = error_message([&] { read_key_value_file(twice); });
  EXPECT_TRUE(Contains(m, twice.string()));
  EXPECT_TRUE(Contains(m, "line 3: 'dt' is given twice (first on line 1)"));
  EXPECT_TRUE(Contains(error_message([&] { read_key_value_file(write("noeq.cfg", "dt 1\n")); }), "line 1: expected 'key = value'"));
  EXPECT_TRUE(Contains(error_message([&] { read_key_value_file(write("nokey.cfg", "a=1\n = 2\n")); }), "line 2: no key"));
  EXPECT_TRUE(Contains(error_message([&] { read_key_value_file(write("nul.cfg", std::string("a = 1\0", 6) + "\n")); }),
                       "control character"));
  EXPECT_TRUE(Contains(error_message([&] { read_key_value_file(dir / "absent.cfg"); }), "cannot open"));
}

// ---- checkpoints ---------------------------------------------------------------------------

// A block resting on a fixed floor, stepped so that the warm-start memory holds its contacts.
struct Resting {
  Registry reg;
  ContactHistory warm;
  Resting() {
    const MaterialId m = add_material(reg, "stone", 2000.0);
    set_default_contact_law(reg, LawSpec{LawKind::IQS_CLB, 0.5, 0.0, 0.0});
    const BodyId floor = add_polygon_body(reg, rectangle(1.0, 0.1), m, {0.0, -0.05}, 0.0, "floor");
    fix_body(reg, floor);
    add_polygon_body(reg, rectangle(0.1, 0.1), m, {0.0, 0.05}, 0.0, "block");
    MoreauJean mj(reg);
    for (int i = 0; i < 5; ++i) mj.step();
    warm = mj.warm_start_memory();
  }
};

class CheckpointRules : public ReaderDir {
 protected:
  void SetUp() override {
    ReaderDir::SetUp();
    save_checkpoint(dir / "good.nscd", scene.reg, scene.warm, {{"kind", "test"}});
    std::ifstream f(dir / "good.nscd", std::ios::binary);
    std::ostringstream s;
    s << f.rdbuf();
    text = s.str();
    ASSERT_FALSE(scene.warm.empty());
  }
  /// The error message of loading the text with the first line starting with `tag` replaced.
  std::string with_line(const std::string& tag, const std::string& line) {
    std::istringstream in(text);
    std::string out, l;
    bool done = false;
    while (std::getline(in, l)) {
      if (!done && l.rfind(tag, 0) == 0) {
        l = line;
        done = true;
      }
      out += l + "\n";
    }
    EXPECT_TRUE(done) << "no line starting with '" << tag << "'";
    return load_error(out);
  }
  std::string load_error(const std::string& content) {
    const fs::path p = write("bad.nscd", content);
    const std::string m = error_message([&] { load_checkpoint(p); });
    EXPECT_TRUE(Contains(m, p.string()));
    return m;
  }
  std::string line_of(const std::string& tag) const {
    std::istringstream in(text);
    std::string l;
    while (std::getline(in, l))
      if (l.rfind(tag, 0) == 0) return l;
    return {};
  }
  Resting scene;
  std::string text;
};

TEST_F(CheckpointRules, WarmStartForcesMustBeFiniteAndInRange) {
  // issue #9: an infinite `w` force made `ballast --sample` segfault, −2^1000 gave exit 0 with a
  // settlement of −1e288; both are refused now, with the line and the rule
  const std::string w = line_of("w ");
  const std::string head = w.substr(0, w.rfind(' ', w.rfind(' ') - 1));  // "w <pair> <feature>"
  const std::string inf = with_line("w ", head + " inf 0x0p+0");
  EXPECT_TRUE(Contains(inf, "w record, normal force: bad number 'inf'"));
  EXPECT_TRUE(Contains(inf, "line 2"));
  EXPECT_TRUE(Contains(with_line("w ", head + " -0x1p+1000 0x0p+0"), "normal force -1.0715086071862673e+301 is out of range"));
  EXPECT_TRUE(Contains(with_line("w ", head + " 0x1p+0 nan"), "tangential force: bad number 'nan'"));
  // its POLYGs must exist and the entries be sorted
  EXPECT_TRUE(Contains(with_line("w ", "w 42949672960 0 0x0p+0 0x0p+0"), "contactor pair (10, 0) is out of range (2 POLYGs, 0 DISKx"));
  EXPECT_TRUE(Contains(with_line("w ", "w 4294967296 0 0x0p+0 0x0p+0 7"), "unexpected '7' after its last field"));
  EXPECT_TRUE(Contains(with_line("w ", "w 4294967296 0 0x0p+0"), "expected tangential force, found the end of the line"));
}

TEST_F(CheckpointRules, StateMustBeFiniteAndInRange) {
  const std::string b = line_of("b \"block\"");
  std::istringstream f(b);
  std::vector<std::string> t;
  for (std::string w; f >> w;) t.push_back(w);
  ASSERT_EQ(t.size(), 14u);
  auto with = [&](std::size_t i, const std::string& v) {
    auto u = t;
    u[i] = v;
    std::string l;
    for (const auto& w : u) l += (l.empty() ? "" : " ") + w;
    return with_line("b \"block\"", l);
  };
  // an infinite state was a std::length_error; now a clear refusal naming the field
  EXPECT_TRUE(Contains(with(8, "inf"), "b record, x: bad number 'inf'"));
  EXPECT_TRUE(Contains(with(8, "1e10"), "b record, x 1e+10 is out of range [-1e+09, 1e+09]"));
  EXPECT_TRUE(Contains(with(11, "2e6"), "b record, vx 2e+06 is out of range"));
  EXPECT_TRUE(Contains(with(3, "-1"), "b record, mass -1 is out of range [1e-30, 1e+100]"));
  EXPECT_TRUE(Contains(with(4, "1e-40"), "b record, inertia 1e-40 is out of range [1e-30, 1e+100]"));
  EXPECT_TRUE(Contains(with(3, "0x1p+0x"), "b record, mass: bad number"));
  EXPECT_TRUE(Contains(with_line("time", "time 0x0p+0 -3"), "step -3 is out of range"));
  EXPECT_TRUE(Contains(with_line("params", "params 0x0p+0 0x1p-1 0x0p+0 -0x1.39eb851eb851fp+3 0x1.47ae147ae147bp-10"),
                       "time step dt must be finite and > 0"));
}

TEST_F(CheckpointRules, WrongCountsAndSectionsAreRefused) {
  EXPECT_TRUE(Contains(with_line("bodies", "bodies 3"), "expected 'b', found 'drives'"));
  EXPECT_TRUE(Contains(with_line("bodies", "bodies 1"), "expected 'drives', found 'b'"));
  EXPECT_TRUE(Contains(with_line("bodies", "bodies 2 2"), "unexpected '2' after its last field"));
  EXPECT_TRUE(Contains(with_line("bodies", "bodies -2"), "body count -2 is out of range"));
  EXPECT_TRUE(Contains(with_line("bodies", "bodies 1e3"), "'1e3' is not an integer"));
  EXPECT_TRUE(Contains(load_error(text + "end\n"), "data after 'end'"));
  EXPECT_TRUE(Contains(load_error(text + "bodies 0\n"), "data after 'end'"));
  EXPECT_TRUE(Contains(with_line("extra", "extra 2\nx \"kind\" \"a\"\nx \"kind\" \"b\""), "key 'kind' is given twice"));
  EXPECT_TRUE(Contains(with_line("m ", "m stone 0x1p+11"), "expected material name (a quoted string)"));
  EXPECT_TRUE(Contains(with_line("m ", "m \"stone 0x1p+11"), "unterminated string"));
}

TEST_F(CheckpointRules, SaveRefusesWhatLoadWouldRefuse) {
  // issue #9: a NaN force from a user's function was saved silently, then refused by the load
  Registry reg = scene.reg;
  reg.bodies.vx[1] = std::numeric_limits<double>::quiet_NaN();
  const fs::path p = dir / "nan.nscd";
  const std::string m = error_message([&] { save_checkpoint(p, reg, scene.warm); });
  EXPECT_TRUE(Contains(m, "refusing to write a non-finite state: 'b' record 1 holds nan"));
  EXPECT_FALSE(fs::exists(p));
  EXPECT_FALSE(fs::exists(p.string() + ".tmp"));
  ContactHistory warm = scene.warm;
  warm[0].rn = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(Contains(error_message([&] { save_checkpoint(p, scene.reg, warm); }), "'w' record 0 holds inf"));
  // finite but beyond the reader's limits
  reg = scene.reg;
  reg.bodies.x[1] = 2e9;
  EXPECT_TRUE(Contains(error_message([&] { save_checkpoint(p, reg, scene.warm); }),
                       "refusing to write a state the reader would refuse"));
  EXPECT_FALSE(fs::exists(p));
  // an earlier checkpoint stays as it was
  save_checkpoint(p, scene.reg, scene.warm);
  const auto size = fs::file_size(p);
  EXPECT_THROW(save_checkpoint(p, reg, scene.warm), Error);
  EXPECT_EQ(fs::file_size(p), size);
  EXPECT_NO_THROW(load_checkpoint(p));
}

}  // namespace
