// tests/unit/test_fuzz_regressions.cpp — hostile files for the readers (issue #9):
//   * mutations of a real ballast sample (tests/data/ballast/mini_sample.nscd, 7 grains on 4
//     pads): every deleted, duplicated or cut line is refused, and byte flips and bad numbers
//     either load or throw nscd::Error, never anything else; what loads steps without a crash;
//   * every input the fuzzers (tools/fuzz) found to crash a reader, and crafted hostile files,
//     kept under tests/data/fuzz/<reader>/: each must now load or throw nscd::Error (a DATBOX
//     folder is one file there, its files each after a line "#FILE <name>", as fuzz_datbox
//     takes it).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "nscd/core/error.hpp"
#include "nscd/io/checkpoint.hpp"
#include "nscd/io/datbox.hpp"
#include "nscd/shared/ballast.hpp"
#include "nscd/solvers/local_problem.hpp"
#include "nscd/solvers/moreau_jean.hpp"
#include "temp_path.hpp"

namespace {

using namespace nscd;
namespace fs = std::filesystem;

const fs::path kFuzzData = NSCD_TEST_DATA_DIR;

std::string read_input(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> v;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) v.push_back(l);
  return v;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const auto& l : lines) s += l + "\n";
  return s;
}

enum class LoadOutcome { loaded, refused, other };

/// Loads the text as a ballast sample and, if it loads, steps it as `ballast --sample` would
/// (recognise the scene, the warm start, a stiffer sublayer, 3 steps). `why` gets the message.
LoadOutcome load_and_step(const std::string& text, std::string& why) {
  try {
    Checkpoint cp = load_checkpoint_text(text, "mutated.nscd");
    scenes::BallastScene s = scenes::recognise_ballast(std::move(cp.reg));
    if (!s.sleeper.valid()) return LoadOutcome::loaded;
    scenes::scale_sublayer_stiffness(s, 2.0);
    MoreauJean mj(s.scene.reg);
    mj.set_warm_start_memory(cp.warm_start);
    for (int i = 0; i < 3; ++i) mj.step();
    return LoadOutcome::loaded;
  } catch (const Error& e) {
    why = e.what();
    return LoadOutcome::refused;
  } catch (const std::exception& e) {
    why = e.what();
    return LoadOutcome::other;
  }
}

class MutatedSample : public ::testing::Test {
 protected:
  void SetUp() override {
    text = read_input(kFuzzData / "ballast" / "mini_sample.nscd");
    lines = lines_of(text);
    ASSERT_GT(lines.size(), 50u);
    std::string why;
    ASSERT_EQ(load_and_step(text, why), LoadOutcome::loaded) << why;
  }
  std::string text;
  std::vector<std::string> lines;
};

TEST_F(MutatedSample, EveryDeletedDuplicatedOrCutLineIsRefused) {
  // (the 120 mutated samples: 5 were accepted, among them deleted and duplicated lines)
  for (std::size_t i = 0; i < lines.size(); ++i) {
    std::string why;
    auto deleted = lines;
    deleted.erase(deleted.begin() + static_cast<std::ptrdiff_t>(i));
    EXPECT_EQ(load_and_step(joined(deleted), why), LoadOutcome::refused) << "line " << i + 1 << " deleted: " << lines[i];
    EXPECT_NE(why.find("mutated.nscd', line "), std::string::npos) << why;
    auto twice = lines;
    twice.insert(twice.begin() + static_cast<std::ptrdiff_t>(i), lines[i]);
    EXPECT_EQ(load_and_step(joined(twice), why), LoadOutcome::refused) << "line " << i + 1 << " duplicated: " << lines[i];
    const std::vector<std::string> cut(lines.begin(), lines.begin() + static_cast<std::ptrdiff_t>(i));
    EXPECT_EQ(load_and_step(joined(cut), why), LoadOutcome::refused) << "cut before line " << i + 1;
  }
}

TEST_F(MutatedSample, BadNumbersAndWrongCountsAreRefused) {
  // every number of every record in turn replaced by a hostile value
  const char* hostile[] = {"inf", "-inf", "nan", "-0x1p+1000", "1e309", "0x", "1.5.2", "", "99999999999999999999999", "-1"};
  int refused = 0, loaded = 0;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    std::istringstream ls(lines[i]);
    std::vector<std::string> t;
    for (std::string w; ls >> w;) t.push_back(w);
    for (std::size_t k = 1; k < t.size() && k < 8; ++k) {
      if (t[k].front() == '"' || t[k].back() == '"') continue;  // names
      for (const char* h : hostile) {
        auto u = t;
        u[k] = h;
        auto m = lines;
        m[i].clear();
        for (const auto& w : u) m[i] += (m[i].empty() ? "" : " ") + w;
        std::string why;
        const LoadOutcome o = load_and_step(joined(m), why);
        ASSERT_NE(o, LoadOutcome::other) << "line " << i + 1 << " field " << k << " = '" << h << "': " << why;
        if (o == LoadOutcome::refused) ++refused;
        else ++loaded;
        // non-finite values are never accepted
        const std::string hs(h);
        if (hs == "inf" || hs == "nan" || hs == "-0x1p+1000" || hs == "1e309") {
          EXPECT_EQ(o, LoadOutcome::refused) << "line " << i + 1 << " field " << k << " = '" << h << "'";
        }
      }
    }
    // a record with one field more
    auto m = lines;
    m[i] += " 0";
    std::string why;
    EXPECT_EQ(load_and_step(joined(m), why), LoadOutcome::refused) << "line " << i + 1 << " with an extra field";
  }
  EXPECT_GT(refused, 1000);
  // "-1" is a valid value for a few fields (a signed coordinate, a law index): the rest is refused
  EXPECT_LT(loaded, refused / 5);
}

TEST_F(MutatedSample, ByteFlipsNeverCrash) {
  std::mt19937_64 rng(9);
  for (int n = 0; n < 400; ++n) {
    std::string m = text;
    const int flips = 1 + static_cast<int>(rng() % 3);
    for (int f = 0; f < flips; ++f) m[rng() % m.size()] ^= static_cast<char>(1u << (rng() % 8));
    std::string why;
    ASSERT_NE(load_and_step(m, why), LoadOutcome::other) << "mutation " << n << ": " << why;
  }
}

// ---- the fuzzers' crashers ----------------------------------------------------------------

std::vector<fs::path> crashers(const char* reader) {
  std::vector<fs::path> v;
  const fs::path dir = kFuzzData / "fuzz" / reader;
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir)) v.push_back(e.path());
  return v;
}

// tests/data/fuzz/checkpoint and tests/data/fuzz/sample: crafted files (a run checkpoint and the
// mini ballast sample, each valid and then truncated, of another version, with a NaN or an
// infinity, with a count far beyond the file) and whatever the fuzzers find. A file named
// valid_* must load and step, bad_* must be refused; any other (a fuzzer's crash-*) may do
// either, but never throw anything else. An empty or missing folder fails: nothing was tested.
TEST(FuzzRegressions, CheckpointAndSampleCrashersLoadOrAreRefused) {
  for (const char* reader : {"checkpoint", "sample"}) {
    const std::vector<fs::path> files = crashers(reader);
    ASSERT_FALSE(files.empty()) << (kFuzzData / "fuzz" / reader) << " is missing or empty";
    int valid = 0, bad = 0;
    for (const fs::path& f : files) {
      std::string why;
      const LoadOutcome o = load_and_step(read_input(f), why);
      EXPECT_NE(o, LoadOutcome::other) << f << ": " << why;
      const std::string name = f.filename().string();
      if (name.starts_with("valid_")) {
        ++valid;
        EXPECT_EQ(o, LoadOutcome::loaded) << f << ": " << why;
      } else if (name.starts_with("bad_")) {
        ++bad;
        EXPECT_EQ(o, LoadOutcome::refused) << f;
        EXPECT_NE(why.find("mutated.nscd"), std::string::npos) << f << ": the message names the file: " << why;
      }
    }
    EXPECT_GE(valid, 1) << reader << ": no valid_* file, so nothing shows that a good one loads";
    EXPECT_GE(bad, 5) << reader << ": the crafted bad_* files are gone";
  }
}

/// Reads `f` with `read`; "" if it reads or throws nscd::Error, the message of anything else.
template <class Read>
std::string other_exception(const fs::path& f, Read read) {
  try {
    read(f);
  } catch (const Error&) {
  } catch (const std::exception& e) {
    return std::string("threw a std::exception that is not nscd::Error: ") + e.what();
  }
  return {};
}

// The problem readers (src/solvers/local_problem.cpp) let std::invalid_argument ("stoul"),
// std::length_error / std::bad_alloc (a contact count of 2^63, or beyond the file) escape and
// read a block row of 2^31 as row 0; they now refuse those files with nscd::Error.
TEST(FuzzRegressions, ProblemDumpCrashersAreRefused) {
  ASSERT_FALSE(crashers("problem").empty());
  for (const fs::path& f : crashers("problem")) {
    EXPECT_EQ(other_exception(f, [](const fs::path& p) { read_problem(p); }), "") << f;
    EXPECT_THROW(read_problem(f), Error) << f;
  }
}

TEST(FuzzRegressions, SiconosCrashersAreRefused) {
  ASSERT_FALSE(crashers("siconos").empty());
  for (const fs::path& f : crashers("siconos")) {
    EXPECT_EQ(other_exception(f, [](const fs::path& p) { read_siconos_fc2d(p); }), "") << f;
    EXPECT_THROW(read_siconos_fc2d(f), Error) << f;
  }
}

/// Writes a fuzz_datbox input (files each after "#FILE <name>") as a folder under `dir`.
void unpack_datbox(const std::string& text, const fs::path& dir) {
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::istringstream in(text);
  std::ofstream out;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("#FILE ", 0) == 0) {
      out.close();
      out.open(dir / line.substr(6), std::ios::binary | std::ios::trunc);
    } else if (out.is_open()) {
      out << line << '\n';
    }
  }
}

// tests/data/fuzz/datbox: the two folders of tests/data/datbox and a driven xKSID drum (valid_*),
// broken in ways the reader must name (bad_*: a 3D body, a DISKb, a NaN radius, a cut
// BODIES.DAT, no BODIES.DAT, a cohesive law, a huge vertex count, an unknown body in
// Vloc_Rloc.INI, an evolution file going back in time, a GAP_SGR_CLB contact without its internal
// variable line, a drum of mass 0 whose spin is free), and what fuzz_datbox found. A folder that
// reads must step.
TEST(FuzzRegressions, DatboxFoldersReadOrAreRefusedByName) {
  const std::vector<fs::path> files = crashers("datbox");
  ASSERT_FALSE(files.empty()) << (kFuzzData / "fuzz" / "datbox") << " is missing or empty";
  const fs::path dir = testing_support::unique_temp_path("fuzz_datbox");
  int valid = 0, bad = 0;
  for (const fs::path& f : files) {
    unpack_datbox(read_input(f), dir);
    std::string why;
    bool read = false;
    EXPECT_EQ(other_exception(dir, [&](const fs::path& p) {
                try {
                  Datbox d = read_datbox(p);
                  read = true;
                  MoreauJean mj(d.reg);
                  for (int i = 0; i < 3; ++i) mj.step();
                } catch (const Error& e) {
                  why = e.what();
                  throw;
                }
              }),
              "")
        << f;
    const std::string name = f.filename().string();
    if (name.starts_with("valid_")) {
      ++valid;
      EXPECT_TRUE(read && why.empty()) << f << ": " << why;
    } else if (name.starts_with("bad_")) {
      ++bad;
      EXPECT_FALSE(read) << f << " was read";
      EXPECT_NE(why.find("DATBOX file '"), std::string::npos) << f << ": the message names the file: " << why;
    }
  }
  fs::remove_all(dir);
  EXPECT_GE(valid, 2);
  EXPECT_GE(bad, 11) << "the crafted bad_* folders are gone";
}

}  // namespace
