// The compiled part of the Python package `sonarmap`: bindings of the C++ library, not a second
// implementation. The package's __init__.py re-exports everything defined here.
#include "bindings.hpp"

PYBIND11_MODULE(_sonarmap, m) {
  m.doc() = "sonarmap: MSIS sonar logs to probabilistic 3D occupancy octrees (C++ library bindings).";
  sonarmap::python::bindErrors(m);
  sonarmap::python::bindMap(m);
  sonarmap::python::bindSonar(m);
  sonarmap::python::bindOptions(m);
  sonarmap::python::bindMapping(m);
  sonarmap::python::bindOnline(m);
  sonarmap::python::bindSimEval(m);
  sonarmap::python::bindViews(m);
}
