#pragma once
/// @file text_input.hpp
/// Opening a text file that may be gzip-compressed (RFC 1952): users keep large CSVs (point
/// scans, navigation, beams) as `.csv.gz`. The file is decompressed as it is read, with zlib's
/// inflate (Debian zlib1g), in chunks, so a large file is never held whole. A file that does not
/// start with gzip's magic bytes (1f 8b) is read as it is; several gzip members one after the
/// other (`cat a.gz b.gz`, as gzip(1) reads them) read as one text.

#include <istream>
#include <memory>
#include <string>

namespace sonarmap {

/// Opens `path` for reading as text, decompressing it when it is gzip. The stream rethrows the
/// errors of decompression from the read that meets them (its exceptions mask holds badbit), so a
/// reader fails on the broken bytes instead of taking them for the end of the file.
/// @throws FileError when the file cannot be opened, when it is named `*.gz` but does not start
///         with gzip's magic bytes ("not gzip-compressed"), and (from the stream's reads) when its
///         compressed data is corrupt ("not valid gzip data ... at compressed byte N") or ends
///         before its gzip member does ("truncated gzip data").
std::unique_ptr<std::istream> openTextInput(const std::string& path);

}  // namespace sonarmap
