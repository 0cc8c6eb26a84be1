// Atomic file output: content goes to a temporary file in the same directory,
// is flushed and fsynced, then renamed over the target, so a crash never
// leaves a half-written result.
#pragma once

#include <string>

namespace pronk::io {

/// Writes `content` to `path` atomically. Throws std::runtime_error on I/O failure.
void write_file_atomic(const std::string& path, const std::string& content);

/// Creates a directory and its parents. InputError when the path cannot be a directory
/// (a part of it is a file, or it is not writable); std::runtime_error on other failures.
void make_directories(const std::string& path);

/// Throws InputError (file `origin`, e.g. "--out") unless `path` is a directory or one can be
/// created there: its nearest existing ancestor is a writable directory. Creates nothing.
void check_output_directory(const std::string& path, const std::string& origin);

}  // namespace pronk::io
