#include "io/write/figure_batch.hpp"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <stdexcept>

#include "io/write/atomic_file.hpp"
#include "io/write/plot.hpp"

namespace pronk::io {

FigureBatch::~FigureBatch() {
  if (started_) {
    join();
    return;
  }
  for (const Figure& f : figures_) std::remove((f.dir + "/" + f.name + ".svg").c_str());
}

void FigureBatch::add(const std::string& dir, const std::string& name, const std::string& script) {
  if (started_) throw std::logic_error("FigureBatch::add after start: " + name);
  write_file_atomic(dir + "/" + name + ".gp", script);
  if (!render_figures()) {
    std::remove((dir + "/" + name + ".svg").c_str());  // no figure rather than an earlier run's
    all_rendered_ = false;
    return;
  }
  figures_.push_back({dir, name, script_to_stdout(name, script), false, nullptr});
}

void FigureBatch::start() {
  if (started_) return;
  started_ = true;
  if (figures_.empty()) return;
  if (!gnuplot_available()) {
    report_missing_gnuplot();
    all_rendered_ = false;
    figures_.clear();  // nothing rendered, nothing removed: as without a batch
    return;
  }
  const size_t cores = std::max(1u, std::thread::hardware_concurrency());
  const size_t n = std::min(cores, figures_.size());
  workers_.reserve(n);
  for (size_t i = 0; i < n; ++i) workers_.emplace_back([this] { render_queued(); });
}

void FigureBatch::render_queued() {
  for (size_t i = next_++; i < figures_.size(); i = next_++) {
    Figure& f = figures_[i];
    try {
      f.rendered = render_svg(f.dir, f.name, f.script);
    } catch (...) {
      f.error = std::current_exception();
    }
  }
}

void FigureBatch::join() {
  for (std::thread& t : workers_) t.join();
  workers_.clear();
}

bool FigureBatch::finish() {
  start();
  join();
  std::exception_ptr first;
  for (const Figure& f : figures_) {
    if (f.error) {
      if (!first) first = f.error;
      all_rendered_ = false;
    } else if (!f.rendered) {
      std::cerr << "pronk: gnuplot failed on " + f.dir + "/" + f.name + ".gp\n";
      all_rendered_ = false;
    }
  }
  figures_.clear();
  if (first) std::rethrow_exception(first);
  return all_rendered_;
}

}  // namespace pronk::io
