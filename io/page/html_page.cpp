#include "io/page/html_page.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#ifndef PRONK_WEB_DIST
#define PRONK_WEB_DIST "web/dist"
#endif

namespace pronk::io::page {

namespace {
constexpr const char* kPlaceholder = "@PRONK_DATA@";
}

std::string template_dir() {
  const char* env = std::getenv("PRONK_WEB_DIR");
  return env != nullptr && *env != '\0' ? std::string(env) : std::string(PRONK_WEB_DIST);
}

std::optional<std::string> read_template(const std::string& name) {
  std::ifstream in(template_dir() + "/" + name + ".html", std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string missing_template_hint() {
  return "no page templates in " + template_dir() +
         ": `PRONK_WITH_WEB=1 bash scripts/setup.sh` installs Node, npm and Chromium and builds "
         "them (then `pronk view DIR` writes the pages of runs already on disk)";
}

std::string fill_template(const std::string& html, const nlohmann::json& data) {
  const size_t at = html.find(kPlaceholder);
  if (at == std::string::npos) throw std::logic_error("page template without @PRONK_DATA@");
  // Compact, invalid UTF-8 replaced (text fields of a damaged CSV must not abort the page).
  const std::string text = data.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string out;
  out.reserve(html.size() + text.size() + text.size() / 64);
  out.append(html, 0, at);
  for (size_t from = 0; from < text.size();) {
    const size_t lt = std::min(text.find('<', from), text.size());
    out.append(text, from, lt - from);
    if (lt == text.size()) break;
    out += "\\u003c";  // only inside JSON strings: the same string, and no "</script>"
    from = lt + 1;
  }
  out.append(html, at + std::char_traits<char>::length(kPlaceholder), std::string::npos);
  return out;
}

}  // namespace pronk::io::page
