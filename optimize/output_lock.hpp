// One writer per output directory: a study, a staged study or a map holds an exclusive
// flock(2) on DIR/pronk.lock while it writes there, so two runs on one --out cannot
// interleave their journals. The lock file holds the holder's pid; a second run is bad
// input naming that pid. The kernel drops the lock when the holder exits, however it
// exits (kill -9 included), so a stale lock file never blocks anyone.
#pragma once

#include <string>

namespace pronk::optimize {

class OutputLock {
 public:
  /// Takes the lock of directory `dir` (which must exist) for `what` ("pronk optimize", ...).
  /// Throws io::InputError (file DIR/pronk.lock) naming the holder's pid when another
  /// process holds it; std::runtime_error when the lock file cannot be created.
  OutputLock(const std::string& dir, const std::string& what);
  /// Releases the lock and removes the lock file.
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

  /// The lock file's path.
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
};

/// Removes the temporaries a killed writer left in `dir` and its subdirectories down to
/// `depth` levels: files named NAME.tmp.PID (io::write_file_atomic's) whose process PID is
/// gone. Call it while holding the directory's OutputLock. Returns how many.
long remove_stale_temporaries(const std::string& dir, int depth);

}  // namespace pronk::optimize
