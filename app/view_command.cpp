#include "app/view_command.hpp"

#include <cstdio>
#include <exception>

#include "io/page/html_page.hpp"
#include "io/page/page_data.hpp"

namespace pronk::app {

CLI::App* add_view_command(CLI::App& app, ViewArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "view",
      "Write the page of a directory pronk wrote, from its files: view.html (3-D playback and\n"
      "linked plots) for a run of `pronk simulate`, report.html for a study (`pronk optimize`),\n"
      "a map (`pronk map`) or a comparison (`pronk compare`). One self-contained file; open it\n"
      "in a browser, offline.");
  cmd->add_option("dir", args.dir, "Run, study, map or comparison directory")->required();
  cmd->add_flag("--quiet,-q", args.quiet, "Print nothing on success");
  return cmd;
}

int run_view(const ViewArgs& args) {
  const std::string page = io::page::write_directory_page(args.dir);
  if (page.empty()) {
    std::fprintf(stderr, "pronk view: %s\n", io::page::missing_template_hint().c_str());
    return 1;
  }
  if (!args.quiet) std::printf("%s\n", page.c_str());
  return 0;
}

void write_page_after(const std::string& dir, bool quiet) {
  // The command's own results are written; a page that cannot be made from them (a study
  // stopped before its design.json) is reported, not an error of the command.
  try {
    const std::string page = io::page::write_directory_page(dir);
    if (!quiet) print_page_line(page);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "pronk: no page for %s: %s\n", dir.c_str(), e.what());
  }
}

void print_page_line(const std::string& page) {
  if (page.empty()) {
    std::printf("  page: %s\n", io::page::missing_template_hint().c_str());
  } else {
    std::printf("  page: %s (open it in a browser)\n", page.c_str());
  }
}

}  // namespace pronk::app
