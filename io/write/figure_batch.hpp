// The figures of an output directory rendered together: each figure's gnuplot script is
// written when the figure is added, and once the data the figures plot is on disk their SVGs
// are rendered by concurrent gnuplot processes, at most one per core.
#pragma once

#include <atomic>
#include <exception>
#include <string>
#include <thread>
#include <vector>

namespace pronk::io {

class FigureBatch {
 public:
  FigureBatch() = default;
  FigureBatch(const FigureBatch&) = delete;
  FigureBatch& operator=(const FigureBatch&) = delete;
  /// Waits for a started rendering (its errors dropped: an error is already on its way out).
  /// A figure added and never rendered loses the SVG of an earlier run.
  ~FigureBatch();

  /// Writes `dir/name.gp` now (the script must `set output 'NAME.svg'` when run in `dir`) and
  /// queues the figure. Without rendering (--no-figures) removes `dir/name.svg` instead: no
  /// figure rather than an earlier run's.
  void add(const std::string& dir, const std::string& name, const std::string& script);

  /// Starts rendering the queued figures in the background, at most
  /// std::thread::hardware_concurrency() gnuplot processes at once; nothing may be added
  /// after. Without gnuplot on PATH says so once per process and renders nothing.
  void start();

  /// Starts if not yet started and waits for every figure. True when every figure added was
  /// rendered; false without rendering, without gnuplot, or after one message on stderr per
  /// figure gnuplot failed on (its SVG removed). Rethrows the first error (in the order the
  /// figures were added), after every figure has ended.
  bool finish();

 private:
  struct Figure {
    std::string dir, name, script;  ///< script: its output sent to standard output
    bool rendered = false;
    std::exception_ptr error;
  };

  void render_queued();  // a worker: renders figures until none is left
  void join();

  std::vector<Figure> figures_;
  std::vector<std::thread> workers_;
  std::atomic<size_t> next_{0};
  bool all_rendered_ = true;
  bool started_ = false;
};

}  // namespace pronk::io
