// Atomic file output: content goes to a temporary file in the same directory,
// is flushed and fsynced, then renamed over the target, so a crash never
// leaves a half-written result.
#pragma once

#include <string>

namespace pronk::io {

/// Writes `content` to `path` atomically. Throws std::runtime_error on I/O failure.
void write_file_atomic(const std::string& path, const std::string& content);

/// Creates a directory and its parents. InputError when the path cannot be a directory (a
/// part of it is a file, it is not writable, or the file system refuses: /proc, read-only);
/// std::runtime_error on other failures (a full disk, an I/O error).
void make_directories(const std::string& path);

/// Throws InputError (file `origin`, e.g. "--out") unless `path` is a directory or one can be
/// created there: its nearest existing ancestor is a directory in which an entry can be
/// created (tried with a probe directory, removed at once). Leaves nothing behind.
void check_output_directory(const std::string& path, const std::string& origin);

}  // namespace pronk::io
