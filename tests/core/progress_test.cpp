// Progress on the terminal: a phase that reports no steps still shows that it is running.
#include "geardyn/core/progress.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>

namespace geardyn {
namespace {

using namespace std::chrono_literals;

TEST(StderrProgress, APhaseWithoutStepsShowsItIsRunning) {
  ::testing::internal::CaptureStderr();
  {
    StderrProgress progress(0ms, 20ms);
    progress.start("full-wheel expansion", 0);
    std::this_thread::sleep_for(150ms);  // no update() at all, as a factorisation
    progress.finish();
  }
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("full-wheel expansion: "), std::string::npos) << err;
  EXPECT_NE(err.find(" s elapsed"), std::string::npos) << err;
  EXPECT_NE(err.find("full-wheel expansion: done in"), std::string::npos) << err;
}

TEST(StderrProgress, ShortTasksStayQuiet) {
  ::testing::internal::CaptureStderr();
  {
    StderrProgress progress(10s, 20ms);
    progress.start("quick", 10);
    for (std::size_t i = 1; i <= 10; ++i) progress.update(i);
    progress.finish();
  }
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

TEST(StderrProgress, StepsShowTheirFraction) {
  ::testing::internal::CaptureStderr();
  {
    StderrProgress progress(0ms, 0ms);
    progress.start("speeds", 4);
    progress.update(2);
    progress.finish();
  }
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("speeds: 2/4 (50 %)"), std::string::npos) << err;
}

}  // namespace
}  // namespace geardyn
