// A long run's progress on stderr, for studies, stages, validation and maps: on a terminal
// one line rewritten in place (at most every 0.2 s); in a log (stderr redirected) plain lines,
// the first, then one every 30 s, then the last. Each says how many of how many are done,
// the time elapsed and an estimate of the time left.
#pragma once

#include <string>

namespace pronk::optimize {

enum class ProgressStyle { kOff, kTerminal, kLog };

/// Off when quiet; otherwise a terminal line when stderr is a terminal, else log lines.
ProgressStyle progress_style(bool quiet);

/// The monotonic clock progress, timings and wall times read [s] (steady_clock).
double monotonic_seconds();

/// "8 s", "3 min 05 s", "2 h 04 min".
std::string format_duration(double seconds);

/// One plain line on stderr unless `style` is off: a phase starts or ends.
void progress_note(ProgressStyle style, const std::string& line);

class Progress {
 public:
  /// `label` names what is counted ("evaluation", "cells"); `total` of them; `already` of
  /// them were done before this run (replayed from a journal: they do not count in the rate).
  Progress(ProgressStyle style, std::string label, long total, long already = 0);
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// `done` of `total` are done (including `already`); `detail` ends the line.
  void update(long done, const std::string& detail = "");
  /// Ends a terminal's line (the last update stays on screen).
  void finish();

  double elapsed() const;

 private:
  std::string line(long done, const std::string& detail) const;

  ProgressStyle style_;
  std::string label_;
  long total_, already_;
  double t0_;
  double last_print_ = -1.0;
  bool open_line_ = false;  ///< a terminal line not yet ended
};

}  // namespace pronk::optimize
