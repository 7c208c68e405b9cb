// tests/unit/test_checkpoint_files.cpp — unit tests of src/io/checkpoint's files: written
// atomically, a scene it cannot save refused, and bad files refused with an nscd::Error naming
// the file. The scene saved: checkpoint_fixtures.hpp; the round trip: test_checkpoint.cpp.
//
// Suites: CheckpointFiles, CheckpointBadFiles.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "nscd/core/error.hpp"
#include "nscd/io/checkpoint.hpp"
#include "nscd/solvers/moreau_jean.hpp"
#include "error_assertions.hpp"
#include "checkpoint_fixtures.hpp"

namespace {

using nscd::testing_support::error_message;
using nscd::testing_support::Contains;

using namespace nscd;
namespace fs = std::filesystem;
using namespace nscd::checkpoint_fixtures;

// ---- files ------------------------------------------------------------------------------------

using CheckpointFiles = CheckpointDir;

TEST_F(CheckpointFiles, WritesAtomically) {
  CheckpointScene s = make_scene();
  const fs::path file = dir / "run.nscd", tmp = dir / "run.nscd.tmp";
  save_checkpoint(file, s.reg, {}, {{"version", "first"}});
  EXPECT_TRUE(fs::exists(file));
  EXPECT_FALSE(fs::exists(tmp));
  const std::string first = read_bytes(file);

  // a failed write into a directory that does not exist: an error naming it, nothing touched
  const fs::path nowhere = dir / "no such dir" / "run.nscd";
  EXPECT_TRUE(Contains(error_message([&] { save_checkpoint(nowhere, s.reg); }), (dir / "no such dir").string()));
  EXPECT_FALSE(fs::exists(dir / "no such dir"));
  EXPECT_EQ(read_bytes(file), first);

  // a write that fails next to an existing checkpoint (its .tmp cannot be created): the
  // previous checkpoint survives whole
  fs::create_directory(tmp);
  EXPECT_TRUE(Contains(error_message([&] { save_checkpoint(file, s.reg, {}, {{"version", "second"}}); }), tmp.string()));
  EXPECT_EQ(read_bytes(file), first);
  EXPECT_EQ(load_checkpoint(file).extra.at("version"), "first");
  fs::remove(tmp);

  // overwriting works and leaves no .tmp
  save_checkpoint(file, s.reg, {}, {{"version", "second"}});
  EXPECT_EQ(load_checkpoint(file).extra.at("version"), "second");
  EXPECT_FALSE(fs::exists(tmp));
}

TEST_F(CheckpointFiles, LambdaDriveIsRefusedNamingTheBody) {
  CheckpointScene s = make_scene();
  impose_velocity(s.reg, s.sleeper, Dof::X, TimeFunction::lambda([](double t) { return 0.01 * t; }));
  const fs::path file = dir / "lambda.nscd";
  const std::string msg = error_message([&] { save_checkpoint(file, s.reg); });
  EXPECT_TRUE(Contains(msg, "body " + std::to_string(s.sleeper.index()) + " 'sleeper'"));
  EXPECT_TRUE(Contains(msg, "lambda"));
  EXPECT_FALSE(fs::exists(file));
  EXPECT_FALSE(fs::exists(dir / "lambda.nscd.tmp"));
}

// ---- bad files --------------------------------------------------------------------------------

class CheckpointBadFiles : public CheckpointDir {
 protected:
  void SetUp() override {
    CheckpointDir::SetUp();
    CheckpointScene s = make_scene();
    MoreauJean mj(s.reg);
    for (int n = 0; n < 20; ++n) mj.step();
    good = dir / "good.nscd";
    save_checkpoint(good, s.reg, mj.warm_start_memory(), kExtra);
    text = read_bytes(good);
  }
  /// Loads `content` from a file and returns the error message (the test fails if none).
  std::string load_error(const std::string& content, const std::string& name = "bad.nscd") {
    const fs::path p = dir / name;
    write_text(p, content);
    const std::string msg = error_message([&] { load_checkpoint(p); });
    EXPECT_TRUE(Contains(msg, p.string()));
    return msg;
  }
  /// The text with the first occurrence of `from` replaced (the test fails if absent).
  std::string edited(const std::string& from, const std::string& to) const {
    std::string t = text;
    const auto at = t.find(from);
    EXPECT_NE(at, std::string::npos) << "'" << from << "' not in the checkpoint";
    if (at != std::string::npos) t.replace(at, from.size(), to);
    return t;
  }
  fs::path good;
  std::string text;
};

TEST_F(CheckpointBadFiles, MissingEmptyForeignAndWrongVersion) {
  EXPECT_TRUE(Contains(error_message([&] { load_checkpoint(dir / "absent.nscd"); }), (dir / "absent.nscd").string()));
  EXPECT_TRUE(Contains(load_error(""), "not an nscd checkpoint"));
  EXPECT_TRUE(Contains(load_error("hello world\n"), "not an nscd checkpoint"));
  EXPECT_TRUE(Contains(load_error(edited("nscd-checkpoint 3", "nscd-checkpoint 99")), "version 99 is not supported"));
  EXPECT_TRUE(Contains(load_error(edited("nscd-checkpoint 3", "nscd-checkpoint 1")), "version 1 is not supported"));
  EXPECT_TRUE(Contains(load_error(edited("nscd-checkpoint 3", "nscd-checkpoint x")), "no version number"));
  EXPECT_NO_THROW(load_checkpoint(good));
}

TEST_F(CheckpointBadFiles, TruncatedAnywhere) {
  // Every cut before the final "end" is refused (cutting only the last newline is harmless).
  ASSERT_GT(text.size(), 1000u);
  int refused = 0;
  for (std::size_t cut = 0; cut + 1 < text.size(); cut += 37) {
    const fs::path p = dir / "cut.nscd";
    write_text(p, text.substr(0, cut));
    const std::string msg = error_message([&] { load_checkpoint(p); });
    ASSERT_TRUE(Contains(msg, p.string())) << "cut at " << cut;
    ++refused;
  }
  EXPECT_GT(refused, 25);
  EXPECT_TRUE(Contains(load_error(text.substr(0, text.size() - 2)), "expected 'end'"));
  write_text(dir / "no_newline.nscd", text.substr(0, text.size() - 1));
  EXPECT_NO_THROW(load_checkpoint(dir / "no_newline.nscd"));
}

TEST_F(CheckpointBadFiles, CorruptValuesNameTheFileAndTheLine) {
  // the line of the fault: "time" is on line 2
  const std::string bad_time = load_error(edited("\ntime ", "\ntime 0xZZ "));
  EXPECT_TRUE(Contains(bad_time, "bad number '0xZZ'"));
  EXPECT_TRUE(Contains(bad_time, "line 2"));
  EXPECT_TRUE(Contains(load_error(edited("\nbodies ", "\nbodys ")), "expected 'bodies'"));
  // out-of-range codes and counts, refused before they are used
  EXPECT_TRUE(Contains(load_error(edited("\nd 0 0 1", "\nd 0 9 1")), "degree of freedom 9"));
  EXPECT_TRUE(Contains(load_error(edited("\nd 0 0 1", "\nd 0 0 7")), "drive 7"));
  EXPECT_TRUE(Contains(load_error(edited("\np 1 0 4 ", "\np 1 0 4000000000 ")), "vertex count 4000000000"));
  EXPECT_TRUE(Contains(load_error(edited("\nl 0 ", "\nl 3 ")), "contact law kind 3"));  // VOIGT_ROD
  EXPECT_TRUE(Contains(load_error(edited("\npairs 4 -1 ", "\npairs 4 5 ")), "pair law index 5"));
  EXPECT_TRUE(Contains(load_error(edited("\nlaws 3 0", "\nlaws 3 3")), "default law index 3"));
  // data the registry refuses while the scene is rebuilt, also named with the file
  EXPECT_TRUE(Contains(load_error(edited("\"pad 0\" 1 ", "\"pad 0\" 77 ")), "unknown material id"));
  EXPECT_TRUE(Contains(load_error(edited("\nlk 0 1 ", "\nlk 0 99 ")), "unknown PT2Dx point id"));
  EXPECT_TRUE(Contains(load_error(edited("\npt 1 ", "\npt 42 ")), "unknown body id"));
  EXPECT_TRUE(Contains(load_error(edited("\nm \"grain\" ", "\nm \"pad\" ")), "defined twice"));
  EXPECT_TRUE(Contains(load_error(edited("\nd 0 0 1", "\nd 99 0 1")), "unknown body id"));
}

}  // namespace
