#include "provenance/progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <cstring>

namespace hofem {

namespace {

using Clock = std::chrono::steady_clock;

double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

}  // namespace

ProgressLog::ProgressLog(std::string what, std::FILE* out, double interval_seconds)
    : what_(std::move(what)),
      out_(out),
      interval_(interval_seconds),
      start_(Clock::now()),
      last_line_(start_) {
  const char* env = std::getenv("HOFEM_PROGRESS");
  enabled_ = !(env && std::strcmp(env, "0") == 0);
  terminal_ = isatty(fileno(out_)) != 0;
  if (enabled_) thread_ = std::thread([this] { heartbeat(); });
}

ProgressLog::~ProgressLog() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

std::string ProgressLog::format_seconds(double s) {
  if (!std::isfinite(s) || s < 0) return "?";
  if (s < 60) return fmt::format("{:.0f} s", s);
  const long t = std::lround(s);
  if (t < 3600) return fmt::format("{} min {:02d} s", t / 60, t % 60);
  return fmt::format("{} h {:02d} min", t / 3600, (t % 3600) / 60);
}

// On a terminal a line is rewritten in place unless `keep` (notes, the last line).
void ProgressLog::print_locked(const std::string& text, bool keep) {
  if (!enabled_) return;
  const double elapsed = seconds(Clock::now() - start_);
  std::string line = fmt::format("{}: {} | {} elapsed", what_, text, format_seconds(elapsed));
  if (fraction_ > 0.0 && fraction_ < 1.0)
    line += fmt::format(", ~{} left ({:.0f} % done)", format_seconds(elapsed * (1.0 - fraction_) / fraction_),
                        100.0 * fraction_);
  if (terminal_) fmt::print(out_, "\r\033[K{}{}", line, keep ? "\n" : "");
  else fmt::print(out_, "{}\n", line);
  std::fflush(out_);
  last_line_ = Clock::now();
}

void ProgressLog::stage(const std::string& name, double fraction_done) {
  std::lock_guard lock(mutex_);
  stage_ = name;
  fraction_ = fraction_done;
  print_locked(name);
}

void ProgressLog::update(const std::string& name, double fraction_done) {
  std::lock_guard lock(mutex_);
  stage_ = name;
  fraction_ = fraction_done;
  if (terminal_) print_locked(name);
}

void ProgressLog::note(const std::string& text) {
  std::lock_guard lock(mutex_);
  print_locked(text, true);
}

void ProgressLog::done(const std::string& summary) {
  std::lock_guard lock(mutex_);
  fraction_ = 1.0;
  stage_.clear();
  print_locked("done: " + summary, true);
  stop_ = true;
  wake_.notify_all();
}

// Wakes once a second; prints "still in <stage>" when no line went out for
// `interval_`.
void ProgressLog::heartbeat() {
  std::unique_lock lock(mutex_);
  while (!stop_) {
    wake_.wait_for(lock, std::chrono::seconds(1));
    if (!stop_ && !stage_.empty() && Clock::now() - last_line_ >= interval_) print_locked("still in " + stage_);
  }
}

}  // namespace hofem
