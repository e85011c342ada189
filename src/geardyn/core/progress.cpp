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

StderrProgress::~StderrProgress() {
  if (ticker_.joinable()) {
    ticker_.request_stop();
    wake_.notify_all();
  }
}

void StderrProgress::start(const std::string& what, std::size_t total) {
  std::lock_guard<std::mutex> lock(mutex_);
  what_ = what;
  total_ = total;
  done_ = 0;
  start_ = last_ = Clock::now();
  printed_ = false;
  active_ = true;
  if (!ticker_.joinable())
    ticker_ = std::jthread([this](std::stop_token stop) { heartbeat(stop); });
}

void StderrProgress::update(std::size_t done) {
  std::lock_guard<std::mutex> lock(mutex_);
  done_ = done;
  const auto now = Clock::now();
  if (!active_ || now - start_ < delay_ || now - last_ < interval_) return;
  print_locked(now);
}

void StderrProgress::print_locked(Clock::time_point now) {
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  std::string line;
  if (total_ > 0 && done_ > 0) {
    const double fraction = static_cast<double>(done_) / static_cast<double>(total_);
    const double left = elapsed * (1.0 - fraction) / fraction;
    line = fmt::format("{}: {}/{} ({:.0f} %), {:.1f} s elapsed, ~{:.1f} s left", what_, done_,
                       total_, 100.0 * fraction, elapsed, left);
  } else if (done_ > 0) {
    line = fmt::format("{}: {} steps, {:.1f} s elapsed", what_, done_, elapsed);
  } else {
    line = fmt::format("{}: {:.1f} s elapsed", what_, elapsed);
  }
  std::lock_guard<std::mutex> lock(g_stderr_mutex);
  std::fprintf(stderr, "\r%-100s", line.c_str());
  std::fflush(stderr);
  printed_ = true;
}

void StderrProgress::heartbeat(std::stop_token stop) {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop.stop_requested()) {
    wake_.wait_for(lock, stop, interval_, [] { return false; });
    if (stop.stop_requested()) break;
    const auto now = Clock::now();
    if (active_ && now - start_ >= delay_ && now - last_ >= interval_) print_locked(now);
  }
}

void StderrProgress::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  active_ = false;
  if (!printed_) return;
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  std::lock_guard<std::mutex> out(g_stderr_mutex);
  std::fprintf(stderr, "\r%-100s\n", fmt::format("{}: done in {:.1f} s", what_, elapsed).c_str());
  printed_ = false;
}

}  // namespace geardyn
