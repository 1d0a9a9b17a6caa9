#pragma once
/// @file errors.hpp
/// The library's exceptions. Everything thrown for bad input derives from sonarmap::Error,
/// itself a std::runtime_error, so callers can catch one type. The library never prints.

#include <stdexcept>
#include <string>

namespace sonarmap {

/// Root of all sonarmap exceptions.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A file could not be opened, read or written, or its content does not match its format.
/// The message names the file, the field or byte offset, and what was expected.
class FileError : public Error {
 public:
  using Error::Error;
};

/// A parameter or a value read from data is out of its valid range (non-finite, negative, zero…).
class ValueError : public Error {
 public:
  using Error::Error;
};

/// A coordinate lies outside the extent a tree of the chosen depth and resolution can address.
class OutOfMapError : public Error {
 public:
  using Error::Error;
};

}  // namespace sonarmap
