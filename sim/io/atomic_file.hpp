// Atomic file output: content goes to a temporary file in the same directory,
// is flushed and fsynced, then renamed over the target, so a crash never
// leaves a half-written result.
#pragma once

#include <string>

namespace pronk::io {

/// Writes `content` to `path` atomically. Throws std::runtime_error on I/O failure.
void write_file_atomic(const std::string& path, const std::string& content);

/// Creates a directory and its parents; throws std::runtime_error with the path on failure.
void make_directories(const std::string& path);

}  // namespace pronk::io
