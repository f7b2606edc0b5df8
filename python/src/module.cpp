// The extension module gasp._gasp; the package gasp (python/gasp/__init__.py) is its public face.
#include <pybind11/pybind11.h>

#include "bindings.h"
#include "gasp/core/error.h"

PYBIND11_MODULE(_gasp, m) {
  namespace py = pybind11;
  m.doc() = "GASP: appearance-free data association and registration between depth views (C++ core)";
  static py::exception<gasp::Error> error(m, "Error", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const gasp::Error& e) {
      PyErr_SetString(error.ptr(), gasp::exceptionMessage(e).c_str());
    }
  });
  gasp::python::bindParams(m);
  gasp::python::bindPairs(m);
  gasp::python::bindSequences(m);
}
