#pragma once
/// @file mat_size_check.hpp
/// Private to src/formats: checks the sizes a MAT-file v5 declares before libmatio allocates from
/// them. libmatio trusts an array's dimensions: a hostile or corrupt file that declares 2^48
/// elements in 1 KB makes it request petabytes. This walk over the file's data elements (format:
/// MathWorks, "MAT-File Format", version 5, chapter 1) rejects such files first.

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace sonarmap::detail {

/// True when `file` starts with a MATLAB 5 (or 7.3) 128-byte header: at least 128 bytes, with the
/// endian indicator "IM" (little-endian) or "MI" (big-endian) at bytes 126–127. libmatio takes
/// any other file for a MATLAB 4 file, whose headers it trusts just as blindly.
bool hasMat5Header(std::span<const unsigned char> file);

/// Largest inflated size of one compressed (miCOMPRESSED) variable the check accepts: 1 GiB.
inline constexpr std::size_t kMaxInflatedMatBytes = std::size_t{1} << 30;

/// The top-level element a file cut short ends in (a full disk, a pulled cable).
struct MatCut {
  std::size_t at = 0;         ///< its tag's byte
  bool swap = false;          ///< the file is big-endian
  bool compressed = false;    ///< an miCOMPRESSED element
  /// Its bytes that the file holds, from its tag on; for a compressed one, what inflates from them
  /// (the variable's miMATRIX element, from its tag on, up to where the stream was cut).
  std::vector<unsigned char> element;
  std::string what;  ///< "PATH: byte N: data element declares N bytes, M left"
};

/// Files without a level-5 header (shorter than 128 bytes, no "IM"/"MI" endian indicator, or a
/// version other than 0x0100, e.g. 7.3 files, which are HDF5) are not walked: the caller decides
/// what to do with them. Otherwise, walks every top-level data element of a MAT-file v5 (inflating
/// compressed ones with zlib, up to kMaxInflatedMatBytes each) and checks every array (miMATRIX,
/// nested ones included, at most 32 levels deep): its size is a multiple of 8 and a struct's field
/// names a whole number of names (so the walk steps through the file exactly as libmatio will),
/// its array flags and dimensions subelements are present, every data subelement fits inside the
/// array, no dimension is negative, and the number of elements fits in the bytes the array
/// occupies — at least 1 byte per element of a numeric, character or logical array, 8 bytes (one
/// tag) per element of a cell array and per element and field of a struct or object array, 4
/// bytes per stored value of a sparse one. Every allocation libmatio then makes is thereby bounded
/// by a small multiple of the (inflated) file size.
/// A top-level element that runs past the end of the file (a file cut short) ends the walk: it is
/// returned, the elements before it checked; libmatio must not read it.
/// @param file          the whole file.
/// @param path          the file's name, for messages.
/// @param uncompressed  when not null and the file is walked whole with at least one compressed
///                      element: the same file with each miCOMPRESSED element replaced by the
///                      element(s) it inflates to (MAT-File Format, "Compressed Data Elements");
///                      otherwise left empty. libmatio reads a compressed struct array's fields
///                      by copying zlib's state, its 32 KB window, once per field of every element
///                      (inflateCopy): the CRAS log's 5,604 × 4 fields cost a third of `map`'s
///                      instructions, which the uncompressed copy does not.
/// @return              the element the file ends in, or nothing when the file ends after a whole one.
/// @throws FileError naming `path`, the byte offset (inside the inflated variable, with the
///         variable's own offset, for compressed ones) and what was expected, when an element
///         runs past its container (but the file), a compressed variable does not inflate or
///         inflates beyond the limit, or an array's sizes do not fit.
std::optional<MatCut> checkMatSizes(std::span<const unsigned char> file, const std::string& path,
                                    std::vector<unsigned char>* uncompressed = nullptr);

}  // namespace sonarmap::detail
