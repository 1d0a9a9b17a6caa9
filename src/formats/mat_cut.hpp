#pragma once
/// @file mat_cut.hpp
/// Private to src/formats: the whole elements of a struct array that a MAT-file cut short ends in
/// (mat_size_check.hpp's MatCut). MATLAB writes a struct array element by element, each field an
/// array of its own (MathWorks, "MAT-File Format", version 5): the elements before the cut are
/// whole, in the file or, for a compressed variable, in what inflates from the bytes there.

#include <cstddef>

#include "mat_size_check.hpp"

struct matvar_t;

namespace sonarmap::detail {

/// What the cut element holds of the struct array `name`.
struct CutStruct {
  bool is_variable = false;  ///< the cut element is the struct array `name` (its header whole)
  std::size_t declared = 0;  ///< elements its dimensions declare
  /// A 1×k struct array of its k whole elements, made with libmatio (the caller frees it with
  /// Mat_VarFree); null when no element is whole. An element is whole when each of its fields is a
  /// whole numeric array (real, of a numeric class, its data filling its dimensions).
  matvar_t* whole = nullptr;
};

/// @throws nothing: anything that is not whole ends the elements read.
CutStruct wholeStructElements(const MatCut& cut, const char* name);

}  // namespace sonarmap::detail
