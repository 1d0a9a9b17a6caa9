#pragma once
/// @file atomic_file.hpp
/// Writing files so that a reader never sees half of one: the content goes to a temporary file
/// beside the target, is flushed, and is renamed over the target only when complete. On any
/// failure the temporary file is removed and an existing target is left untouched.

#include <functional>
#include <ostream>
#include <span>
#include <string>

namespace sonarmap {

/// Writes `path` atomically with what `write` puts into the stream (binary mode).
/// @throws FileError when the temporary file cannot be created, written, flushed or renamed;
///         any exception thrown by `write` propagates after the temporary file is removed.
void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);

/// Writes `bytes` to `path` atomically. @throws FileError as writeFileAtomically.
void writeBytesAtomically(const std::string& path, std::span<const unsigned char> bytes);

}  // namespace sonarmap
