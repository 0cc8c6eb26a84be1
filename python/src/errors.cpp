// pronk.InputError: bad input (a ValueError) carrying what the CLI prints on exit 2:
// the file, the JSON Pointer, what was expected and what was found.
#include "io/load/input_error.hpp"
#include "python/src/bindings.hpp"

namespace pronk::python {

void bind_errors(py::module_& m) {
  // Never destroyed: the type must outlive the interpreter's finalization.
  static auto* input_error = new py::exception<io::InputError>(m, "InputError", PyExc_ValueError);
  input_error->doc() =
      "Bad input: attributes file, pointer (JSON Pointer), expected and found; str() is the "
      "one line the pronk CLI prints.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const io::InputError& e) {
      py::object err = py::reinterpret_borrow<py::object>(input_error->ptr())(e.what());
      err.attr("file") = e.file();
      err.attr("pointer") = e.pointer();
      err.attr("expected") = e.expected();
      err.attr("found") = e.found();
      PyErr_SetObject(input_error->ptr(), err.ptr());
    }
  });
}

}  // namespace pronk::python
