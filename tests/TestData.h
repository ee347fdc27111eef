#pragma once
#include <gtest/gtest.h>

#include <string>

namespace baker::test {

// The project's own files (data/ and the like).
std::string sourcePath(const std::string& relative);
// ../shared/data beside the checkout, or "" when this clone has none (a user's clone).
std::string sharedDataPath(const std::string& relative);
// A fresh empty directory for one test's files.
std::string makeTempDir(const std::string& name);

}  // namespace baker::test

// Skips the test with a visible reason when ../shared/data is absent.
#define REQUIRE_SHARED_DATA()                                                                     \
  do {                                                                                            \
    if (::baker::test::sharedDataPath("").empty())                                                \
      GTEST_SKIP() << "../shared/data is not next to this checkout: skipping a shared-data check"; \
  } while (0)
