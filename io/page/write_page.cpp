#include <optional>

#include "io/write/atomic_file.hpp"
#include "io/page/html_page.hpp"
#include "io/page/page_data.hpp"

namespace pronk::io::page {

std::string write_directory_page(const std::string& dir) {
  const DirKind kind = classify_directory(dir);
  const std::string name = page_name(kind);
  const std::optional<std::string> html = read_template(name);
  if (!html) return "";
  const std::string path = dir + "/" + name + ".html";
  write_file_atomic(path, fill_template(*html, page_data(dir, kind)));
  return path;
}

}  // namespace pronk::io::page
