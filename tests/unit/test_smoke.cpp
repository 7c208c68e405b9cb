#include <gtest/gtest.h>

#include "nscd/core/names.hpp"

TEST(Names, ResolveKnownAndRejectUnknown) {
  EXPECT_EQ(nscd::parse_law_kind("IQS_CLB"), nscd::LawKind::IQS_CLB);
  EXPECT_THROW(nscd::parse_law_kind("FOO"), std::exception);
}
