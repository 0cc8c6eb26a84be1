// A full disk: pronk ends with exit 1 and one line giving the reason, and every file it
// leaves is whole (the figures too, which gnuplot renders) or absent, with no temporary
// left behind. Runs on small tmpfs mounts (root only: skipped with a warning elsewhere).
#include <sys/mount.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/cli/cli_support.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
namespace fs = std::filesystem;

namespace {

using namespace cli_support;  // NOLINT(google-build-using-namespace): test helpers

/// A tmpfs of `size` mounted on `path` (created) while the object lives.
class SmallDisk {
 public:
  SmallDisk(const std::string& path, const std::string& size) : path_(path) {
    fs::create_directories(path);
    mounted_ = ::mount("tmpfs", path.c_str(), "tmpfs", 0, ("size=" + size).c_str()) == 0;
  }
  ~SmallDisk() {
    if (mounted_) ::umount2(path_.c_str(), MNT_DETACH);
  }
  SmallDisk(const SmallDisk&) = delete;
  SmallDisk& operator=(const SmallDisk&) = delete;
  bool mounted() const { return mounted_; }

 private:
  std::string path_;
  bool mounted_ = false;
};

/// Every regular file under `dir` (relative path -> bytes).
std::map<std::string, std::string> files_under(const std::string& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.is_regular_file()) out[fs::relative(e.path(), dir).string()] = slurp(e.path());
  }
  return out;
}

bool ends_with(std::string text, const std::string& tail) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text.size() >= tail.size() &&
         text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
}

/// True when `file` (as left on the full disk) is whole: the reference run's bytes, or for
/// the files that hold a wall time (summary.json, the page), a complete document.
bool whole(const std::string& name, const std::string& bytes, const std::string& reference) {
  if (bytes == reference) return true;
  const std::string ext = fs::path(name).extension().string();
  if (ext == ".json") return nlohmann::json::accept(bytes);
  if (ext == ".html") return ends_with(bytes, "</html>");
  return false;
}

}  // namespace

TEST_CASE("a full disk is exit 1 with the reason, and every file left is whole or absent",
          "[cli][full_disk]") {
  TempDir d("full_disk");
  {
    SmallDisk probe(d / "probe", "64k");
    if (!probe.mounted()) {
      WARN("skipped: cannot mount a tmpfs here (needs root): the full-disk test did not run");
      return;
    }
  }
  const std::string scene = std::string(PRONK_SOURCE_DIR) + "/studies/mechanisms/pendulum.json";
  const Run ref = pronk(d, {"simulate", scene, "--out", "ref", "-q"});
  REQUIRE(ref.code == 0);
  const std::map<std::string, std::string> reference = files_under(d / "ref");
  std::size_t total = 0;
  for (const auto& [name, bytes] : reference) total += bytes.size();
  // Disks from an eighth of the outputs to a little less than all of them, in 32nds: the disk
  // fills while a CSV is written, while a figure is rendered and (with the page templates
  // built) while view.html, more than half the outputs, is written.
  long figure_failures = 0;
  for (int k = 4; k <= 31; ++k) {
    const std::size_t size_k = total * k / 32 / 1024;
    INFO("tmpfs of " << size_k << " KiB (outputs " << total / 1024 << " KiB)");
    SmallDisk disk(d / "disk", std::to_string(size_k) + "k");
    REQUIRE(disk.mounted());
    const Run r = pronk(d, {"simulate", scene, "--out", "disk/o", "-q"});
    CHECK(r.code == 1);
    CHECK_THAT(r.err,
               StartsWith("pronk: failed: cannot write ") && Contains(": No space left on device"));
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    if (r.err.find(".svg") != std::string::npos) ++figure_failures;
    for (const auto& [name, bytes] : files_under(d / "disk/o")) {
      INFO(name << ": " << bytes.size() << " bytes");
      REQUIRE(reference.count(name) == 1);  // no temporary left behind
      CHECK(whole(name, bytes, reference.at(name)));
    }
  }
  CHECK(figure_failures > 0);  // the disk filled during a figure at least once
}
