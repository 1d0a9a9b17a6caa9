// C++ exceptions become Python exceptions of the same names (core/errors.hpp):
//   sonarmap.Error(RuntimeError)                     ← sonarmap::Error (a std::runtime_error)
//   sonarmap.FileError(sonarmap.Error, OSError)      ← sonarmap::FileError
//   sonarmap.ValueError(sonarmap.Error, ValueError)  ← sonarmap::ValueError, std::invalid_argument,
//                                                      std::domain_error, std::out_of_range
//   sonarmap.OutOfMapError(sonarmap.Error, ValueError) ← sonarmap::OutOfMapError
// so `except ValueError` and `except OSError` catch what a Python user expects as well. Messages
// name the keywords a Python user gives, not the command line's flags (inPythonWords).
#include <stdexcept>

#include "bindings.hpp"
#include "sonarmap/core/errors.hpp"

namespace sonarmap::python {
namespace {

PyObject* g_error = nullptr;
PyObject* g_file_error = nullptr;
PyObject* g_value_error = nullptr;
PyObject* g_out_of_map_error = nullptr;

/// A new exception class `sonarmap.<name>` with `bases`, added to `m`.
PyObject* newException(py::module_& m, const char* name, py::tuple bases, const char* doc) {
  const std::string qualified = std::string("sonarmap.") + name;
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr);
  if (type == nullptr) throw py::error_already_set();
  m.add_object(name, py::handle(type));  // the module holds a reference; so do we (never released)
  return type;
}

}  // namespace

void bindErrors(py::module_& m) {
  const py::handle runtime_error(PyExc_RuntimeError);
  g_error = newException(m, "Error", py::make_tuple(runtime_error),
                         "Root of the exceptions of sonarmap (C++ sonarmap::Error, a std::runtime_error).");
  const py::handle error(g_error);
  g_file_error = newException(
      m, "FileError", py::make_tuple(error, py::handle(PyExc_OSError)),
      "A file could not be opened, read or written, or its content does not match its format; the message "
      "names the file, the field or byte offset, and what was expected (C++ sonarmap::FileError).");
  g_value_error = newException(
      m, "ValueError", py::make_tuple(error, py::handle(PyExc_ValueError)),
      "A parameter, an array or a value read from data is out of its valid range: wrong shape or dtype, NaN, "
      "negative, zero… (C++ sonarmap::ValueError; also std::invalid_argument and std::out_of_range).");
  g_out_of_map_error = newException(
      m, "OutOfMapError", py::make_tuple(error, py::handle(PyExc_ValueError)),
      "A coordinate lies outside the extent a depth-16 tree of the map's resolution can address "
      "(C++ sonarmap::OutOfMapError).");

  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const sonarmap::FileError& e) {
      PyErr_SetString(g_file_error, inPythonWords(e.what()).c_str());
    } catch (const sonarmap::ValueError& e) {
      PyErr_SetString(g_value_error, inPythonWords(e.what()).c_str());
    } catch (const sonarmap::OutOfMapError& e) {
      PyErr_SetString(g_out_of_map_error, inPythonWords(e.what()).c_str());
    } catch (const sonarmap::Error& e) {
      PyErr_SetString(g_error, inPythonWords(e.what()).c_str());
    } catch (const std::invalid_argument& e) {
      PyErr_SetString(g_value_error, inPythonWords(e.what()).c_str());
    } catch (const std::domain_error& e) {
      PyErr_SetString(g_value_error, inPythonWords(e.what()).c_str());
    } catch (const std::out_of_range& e) {
      PyErr_SetString(g_value_error, inPythonWords(e.what()).c_str());
    }
  });
}

}  // namespace sonarmap::python
