// A temporary path that belongs to the running test alone.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <string_view>

namespace tyndall::test {

// ctest runs tests two at a time, each in its own process; a fixed name let one test remove the files
// another was reading. The test's full name and the process id keep two tests, or two checkouts, apart.
inline std::filesystem::path scratchPath(std::string_view what) {
  const ::testing::TestInfo& test = *::testing::UnitTest::GetInstance()->current_test_info();
  return std::filesystem::temp_directory_path() /
         (std::string("tyndall-test-") + test.test_suite_name() + "." + test.name() + "-" +
          std::to_string(::getpid()) + "-" + std::string(what));
}

}  // namespace tyndall::test
