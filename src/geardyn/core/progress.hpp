#pragma once
// Progress of long work. The library never prints: an analysis reports through a Progress it is
// given (a null Progress is silent). The program's Progress writes to stderr with an ETA.
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <stop_token>
#include <string>
#include <thread>

namespace geardyn {

class Progress {
 public:
  virtual ~Progress() = default;
  /// Starts a task of `total` steps (0 if unknown) named `what`.
  virtual void start(const std::string& what, std::size_t total) = 0;
  /// `done` steps of the current task are complete. Must be cheap; callers may call it often.
  virtual void update(std::size_t done) = 0;
  virtual void finish() = 0;
};

/// Does nothing; the default for library calls.
class NullProgress final : public Progress {
 public:
  void start(const std::string&, std::size_t) override {}
  void update(std::size_t) override {}
  void finish() override {}
};

/// Returns a reference to a shared NullProgress (stateless, safe from any thread).
Progress& null_progress();

/// Writes "what: done/total (pct), elapsed, ~left" to stderr at most every `interval`, and only
/// once the task has run for more than `delay` (short tasks stay quiet). A phase that reports no
/// steps (a factorisation, a full-wheel expansion) still shows "what: 25.0 s elapsed": a
/// heartbeat thread prints it when no update came for an interval. Thread-safe.
class StderrProgress final : public Progress {
 public:
  explicit StderrProgress(std::chrono::milliseconds delay = std::chrono::milliseconds(1500),
                          std::chrono::milliseconds interval = std::chrono::milliseconds(500));
  ~StderrProgress() override;
  StderrProgress(const StderrProgress&) = delete;
  StderrProgress& operator=(const StderrProgress&) = delete;
  void start(const std::string& what, std::size_t total) override;
  void update(std::size_t done) override;
  void finish() override;

 private:
  using Clock = std::chrono::steady_clock;
  void print_locked(Clock::time_point now);  // with mutex_ held
  void heartbeat(std::stop_token stop);

  std::mutex mutex_;
  std::condition_variable_any wake_;
  std::string what_;
  std::size_t total_ = 0, done_ = 0;
  Clock::time_point start_{}, last_{};
  std::chrono::milliseconds delay_, interval_;
  bool active_ = false;
  bool printed_ = false;
  std::jthread ticker_;  // last: stopped and joined first on destruction
};

}  // namespace geardyn
