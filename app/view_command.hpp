// `pronk view DIR`: writes the page of a directory pronk wrote: view.html (3-D playback and
// linked plots) for a robot or mechanism run, report.html for a study, a staged study, a map
// or a comparison of designs.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace pronk::app {

struct ViewArgs {
  std::string dir;
  bool quiet = false;
};

CLI::App* add_view_command(CLI::App& app, ViewArgs& args);

/// 0 the page was written; 1 the page templates are absent. Throws io::InputError (exit 2)
/// when `dir` is not a run, study, map or comparison, or one of its files is missing or damaged.
int run_view(const ViewArgs& args);

/// One line: where the page is, or (empty `page`) how to get pages.
void print_page_line(const std::string& page);

/// After a command that wrote `dir`: writes its page and prints where it is (or how to get
/// pages) unless `quiet`; a page that cannot be made is one line on stderr, not an error.
void write_page_after(const std::string& dir, bool quiet);

}  // namespace pronk::app
