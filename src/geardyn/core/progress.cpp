#include "geardyn/core/progress.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <mutex>

namespace geardyn {
namespace {
std::mutex g_stderr_mutex;  // serialises progress lines from threads of a study
}

Progress& null_progress() {
  static NullProgress instance;
  return instance;
}

StderrProgress::StderrProgress(std::chrono::milliseconds delay, std::chrono::milliseconds interval)
    : delay_(delay), interval_(interval) {}

void StderrProgress::start(const std::string& what, std::size_t total) {
  what_ = what;
  total_ = total;
  start_ = last_ = Clock::now();
  printed_ = false;
}

void StderrProgress::update(std::size_t done) {
  const auto now = Clock::now();
  if (now - start_ < delay_ || now - last_ < interval_) return;
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  std::string line;
  if (total_ > 0 && done > 0) {
    const double fraction = static_cast<double>(done) / static_cast<double>(total_);
    const double left = elapsed * (1.0 - fraction) / fraction;
    line = fmt::format("{}: {}/{} ({:.0f} %), {:.1f} s elapsed, ~{:.1f} s left", what_, done,
                       total_, 100.0 * fraction, elapsed, left);
  } else {
    line = fmt::format("{}: {} steps, {:.1f} s elapsed", what_, done, elapsed);
  }
  std::lock_guard<std::mutex> lock(g_stderr_mutex);
  std::fprintf(stderr, "\r%-100s", line.c_str());
  std::fflush(stderr);
  printed_ = true;
}

void StderrProgress::finish() {
  if (!printed_) return;
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  std::lock_guard<std::mutex> lock(g_stderr_mutex);
  std::fprintf(stderr, "\r%-100s\n", fmt::format("{}: done in {:.1f} s", what_, elapsed).c_str());
  printed_ = false;
}

}  // namespace geardyn
