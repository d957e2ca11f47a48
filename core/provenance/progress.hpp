#pragma once
// Progress of a long run on stderr, for logs that CI systems keep: a line when
// a stage (a family of checks, a study's run, a benchmark) starts, naming it,
// with the elapsed time and an estimate of what remains, and while a stage runs
// a "still in ..." line at least every `interval` seconds (a heartbeat thread),
// so a log never goes silent for longer. On a terminal the line is rewritten in
// place instead of scrolling. HOFEM_PROGRESS=0 in the environment silences it.
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>

namespace hofem {

class ProgressLog {
 public:
  /// `what` prefixes every line ("verify", "study drop_orders").
  explicit ProgressLog(std::string what, std::FILE* out = stderr, double interval_seconds = 20.0);
  ~ProgressLog();
  ProgressLog(const ProgressLog&) = delete;
  ProgressLog& operator=(const ProgressLog&) = delete;

  /// Stage `name` starts with `fraction_done` (0 to 1) of the run's work behind
  /// it: remaining time is estimated as elapsed (1 - f) / f.
  void stage(const std::string& name, double fraction_done);
  /// The current stage's name and fraction, without a line of its own off a
  /// terminal (the heartbeat reports it), rewritten in place on one: for
  /// per-step updates.
  void update(const std::string& name, double fraction_done);
  /// A line of its own (a result) that leaves the stage as it is.
  void note(const std::string& text);
  /// The last line: the run's name, its total time and `summary`.
  void done(const std::string& summary);

  /// "1 min 05 s" style, for the lines (and tests).
  static std::string format_seconds(double s);

 private:
  void print_locked(const std::string& text, bool keep = false);
  void heartbeat();

  std::string what_;
  std::FILE* out_;
  std::chrono::duration<double> interval_;
  bool enabled_, terminal_;
  std::chrono::steady_clock::time_point start_, last_line_;
  std::string stage_;
  double fraction_ = 0.0;
  bool stop_ = false;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread thread_;
};

}  // namespace hofem
