// tests/unit/test_driver_options_more.cpp — the option table's additions for the batch drivers
// (stiffness_study, accuracy_study; issue #11): a repeatable option (a std::vector<std::string>
// member, composing the command line and --config), a one-letter alias, an option passed through
// only when given (kNoDefault + `given`), and the stored text of a repeatable option.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "error_assertions.hpp"
#include "nscd/shared/driver/options.hpp"

namespace {

namespace fs = std::filesystem;
namespace driver = nscd::driver;
using nscd::testing_support::Contains;

struct Batch {
  int jobs = 3;
  std::vector<std::string> extra;  // repeatable
  std::vector<std::string> tags;   // repeatable, stored with the run
  std::string pads;                // passed on only when given
};

const driver::OptionTable<Batch>& batch_table() {
  static const driver::OptionTable<Batch> t(
      "batch", "a toy batch driver",
      {{"jobs", &Batch::jobs, "processes at a time", driver::Kind::Free, driver::kNone, "N", 'j'},
       {"extra", &Batch::extra, "KEY=VALUE for every run (repeatable)"},
       {"tag", &Batch::tags, "a tag (repeatable)", driver::Kind::Run},
       {"pads", &Batch::pads, "passed to the preparation", driver::Kind::Free, driver::kNoDefault}});
  return t;
}

bool parse(std::vector<std::string> args, Batch& c, std::set<std::string>* given = nullptr) {
  args.insert(args.begin(), "batch");
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  return batch_table().parse(static_cast<int>(argv.size()), argv.data(), c, given);
}

TEST(DriverOptionsMore, RepeatableOptionAppendsInOrder) {
  Batch c;
  std::set<std::string> given;
  ASSERT_TRUE(parse({}, c, &given));
  EXPECT_TRUE(c.extra.empty());  // no default
  EXPECT_FALSE(given.count("extra"));
  ASSERT_TRUE(parse({"--extra", "dt=1e-4", "--tag", "x", "--extra=load-mean=-100"}, c, &given));
  EXPECT_EQ(c.extra, (std::vector<std::string>{"dt=1e-4", "load-mean=-100"}));
  EXPECT_EQ(c.tags, (std::vector<std::string>{"x"}));
  EXPECT_EQ(given, (std::set<std::string>{"extra", "tag"}));
}

TEST(DriverOptionsMore, RepeatableOptionComposesWithTheConfigFile) {
  const fs::path cfg = fs::temp_directory_path() / ("nscd_driver_more_" + std::to_string(::getpid()) + ".cfg");
  std::ofstream(cfg) << "extra = frequency=10\njobs = 5\n";
  Batch c;
  std::set<std::string> given;
  const bool ok = parse({"--extra", "dt=1e-4", "--config", cfg.string(), "-j", "2"}, c, &given);
  fs::remove(cfg);
  ASSERT_TRUE(ok);
  EXPECT_EQ(c.extra, (std::vector<std::string>{"dt=1e-4", "frequency=10"}));  // the command line's first
  EXPECT_EQ(c.jobs, 2);  // the command line wins, through its alias too
  EXPECT_TRUE(given.count("extra") && given.count("jobs"));
}

TEST(DriverOptionsMore, ShortAliasSetsTheLongOption) {
  Batch c;
  std::set<std::string> given;
  ASSERT_TRUE(parse({"-j", "7"}, c, &given));
  EXPECT_EQ(c.jobs, 7);
  EXPECT_EQ(given, (std::set<std::string>{"jobs"}));  // named by the long name
  ASSERT_TRUE(parse({"--jobs=4"}, c, &given));
  EXPECT_EQ(c.jobs, 4);
  ::testing::internal::CaptureStdout();
  EXPECT_FALSE(parse({"--help"}, c));
  const std::string help = ::testing::internal::GetCapturedStdout();
  EXPECT_TRUE(Contains(help, "-j [ --jobs ] N (=4)"));
  EXPECT_TRUE(Contains(help, "--extra arg"));
  EXPECT_FALSE(Contains(help, "--pads arg (="));  // kNoDefault: none shown
}

TEST(DriverOptionsMore, PassedThroughOnlyWhenGiven) {
  Batch c;
  std::set<std::string> given;
  ASSERT_TRUE(parse({"--jobs", "1"}, c, &given));
  EXPECT_FALSE(given.count("pads"));
  ASSERT_TRUE(parse({"--pads", "25"}, c, &given));
  ASSERT_TRUE(given.count("pads"));
  EXPECT_EQ(batch_table().value_text(c, *batch_table().find("pads")), "25");
  Batch bad;
  std::vector<std::string> args = {"batch", "--jobs"};  // a value missing: one line naming the option
  std::vector<char*> argv = {args[0].data(), args[1].data()};
  try {
    batch_table().parse(2, argv.data(), bad);
    ADD_FAILURE() << "no InputError";
  } catch (const driver::InputError& e) {
    EXPECT_TRUE(Contains(e.what(), "jobs"));
  }
}

TEST(DriverOptionsMore, RepeatableOptionIsStoredJoinedAndReadBack) {
  Batch c;
  ASSERT_TRUE(parse({"--tag", "a", "--tag", "b c", "--extra", "x=1"}, c));
  const std::map<std::string, std::string> m = batch_table().to_map(c, false);
  EXPECT_EQ(m, (std::map<std::string, std::string>{{"tag", "a,b c"}}));  // Free options are not stored
  Batch back;
  batch_table().from_map(m, back, "checkpoint");
  EXPECT_EQ(back.tags, c.tags);
  batch_table().from_map({{"tag", ""}}, back, "checkpoint");
  EXPECT_TRUE(back.tags.empty());
  std::set<std::string> given;
  ASSERT_TRUE(parse({"--tag", "a"}, back, &given));
  EXPECT_THROW(batch_table().refuse_changes(back, given, m, false, "the checkpoint"), driver::InputError);
}

}  // namespace
