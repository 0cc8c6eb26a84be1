// Writes a self-contained HTML page (view.html, report.html): the page template built
// from web/ (three.js, uPlot and the page script inlined; see web/build.mjs) with the
// page's JSON data put in its placeholder. The file is written atomically.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace pronk::io::page {

/// Where the templates are: $PRONK_WEB_DIR if set, else the source tree's web/dist.
std::string template_dir();

/// The text of template `name` ("view" or "report"), or nothing when it is absent.
std::optional<std::string> read_template(const std::string& name);

/// One line telling how to get the pages when the templates are absent.
std::string missing_template_hint();

/// The template with `data` in its placeholder ('<' escaped, so no text in the data can
/// end the script element). std::logic_error if the template has no placeholder.
std::string fill_template(const std::string& html, const nlohmann::json& data);

}  // namespace pronk::io::page
