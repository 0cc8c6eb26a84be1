#include "optimize/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <utility>

namespace pronk::optimize {

namespace {

constexpr double kTerminalPeriod = 0.2;  ///< [s] between rewrites of a terminal line
constexpr double kLogPeriod = 30.0;      ///< [s] between plain lines in a log

}  // namespace

double monotonic_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

ProgressStyle progress_style(bool quiet) {
  if (quiet) return ProgressStyle::kOff;
  return ::isatty(STDERR_FILENO) ? ProgressStyle::kTerminal : ProgressStyle::kLog;
}

std::string format_duration(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char buf[48];
  if (s < 60) {
    std::snprintf(buf, sizeof buf, "%ld s", s);
  } else if (s < 3600) {
    std::snprintf(buf, sizeof buf, "%ld min %02ld s", s / 60, s % 60);
  } else {
    std::snprintf(buf, sizeof buf, "%ld h %02ld min", s / 3600, (s % 3600) / 60);
  }
  return buf;
}

Progress::Progress(ProgressStyle style, std::string label, long total, long already)
    : style_(style),
      label_(std::move(label)),
      total_(total),
      already_(already),
      t0_(monotonic_seconds()) {}

double Progress::elapsed() const { return monotonic_seconds() - t0_; }

std::string Progress::line(long done, const std::string& detail) const {
  const double t = elapsed();
  std::string out = label_ + " " + std::to_string(done) + "/" + std::to_string(total_) + ", " +
                    format_duration(t) + " elapsed, ";
  const long fresh = done - already_;
  if (done >= total_) {
    out += "done";
  } else if (fresh <= 0) {
    out += "time left unknown yet";
  } else {
    // The rate of the items this run computed (replayed ones cost next to nothing).
    out += "about " +
           format_duration(t / static_cast<double>(fresh) * static_cast<double>(total_ - done)) +
           " left";
  }
  if (!detail.empty()) out += ", " + detail;
  return out;
}

void Progress::update(long done, const std::string& detail) {
  if (style_ == ProgressStyle::kOff) return;
  const double t = elapsed();
  const bool last = done >= total_;
  if (style_ == ProgressStyle::kTerminal) {
    if (!last && last_print_ >= 0.0 && t - last_print_ < kTerminalPeriod) return;
    last_print_ = t;
    std::fprintf(stderr, "\r  %s   ", line(done, detail).c_str());
    open_line_ = true;
  } else {
    if (!last && last_print_ >= 0.0 && t - last_print_ < kLogPeriod) return;
    last_print_ = t;
    std::fprintf(stderr, "  %s\n", line(done, detail).c_str());
  }
  std::fflush(stderr);
}

void progress_note(ProgressStyle style, const std::string& line) {
  if (style == ProgressStyle::kOff) return;
  std::fprintf(stderr, "%s\n", line.c_str());
  std::fflush(stderr);
}

void Progress::finish() {
  if (style_ == ProgressStyle::kTerminal && open_line_) std::fprintf(stderr, "\n");
  open_line_ = false;
}

}  // namespace pronk::optimize
