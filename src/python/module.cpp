// The `dispcon` module: the engine for Python and for FreeCAD's Python (python.md).
#include "bindings.hpp"

PYBIND11_MODULE(dispcon, m) {
  m.doc() =
      "dispcon: mechanism assembly with displacement constraints (Gascuel & Gascuel 1994).\n"
      "load(path) or loads(text) read a .dcl file into a Model; Model() builds one in code.";
  dispcon::py::bind_vocabulary(m);
  dispcon::py::bind_results(m);
  auto model = dispcon::py::bind_model(m);
  dispcon::py::bind_solve(m, model);
  dispcon::py::bind_diagnostics(m, model);
  dispcon::py::bind_dynamics(m, model);
}
