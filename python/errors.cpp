// The library's exceptions as the package's (python/stengmc/errors.py): InputError is a
// ValueError (bad input: a study, file, key or array), ModelError a RuntimeError (the model
// left its domain of validity), any other stengmc::Error a stengmc.Error. Messages pass
// through unchanged: they name the file, the key and what was expected.
#include "bindings.hpp"
#include "core/error.hpp"

namespace py = pybind11;

namespace stengmc::python {

namespace {

//! Sets the Python error (a translator sets it and returns; pybind11 raises it).
void set_error(const char* name, const std::exception& e) {
  // Looked up when raised, not at import: stengmc.errors imports nothing from _core.
  const py::object type = py::module_::import("stengmc.errors").attr(name);
  PyErr_SetString(type.ptr(), e.what());
}

}  // namespace

void bind_errors(py::module_&) {
  py::register_exception_translator([](std::exception_ptr failure) {
    if (!failure) return;
    try {
      std::rethrow_exception(failure);
    } catch (const InputError& e) {
      set_error("InputError", e);
    } catch (const ModelError& e) {
      set_error("ModelError", e);
    } catch (const Error& e) {
      set_error("Error", e);
    }
  });
}

}  // namespace stengmc::python
