#include <pybind11/pybind11.h>

#include "app/provenance.h"
#include "app/subcommand.h"
#include "python/bindings.h"

namespace allanlab::python {

void Raise(int exit_code, const std::string& message) {
  if (exit_code == app::kExitUsageError) throw pybind11::value_error(message);
  throw std::runtime_error(message);
}

}  // namespace allanlab::python

PYBIND11_MODULE(_allanlab, m) {
  m.doc() = "allanlab's commands on records in memory (use the allanlab package, not this module)";
  m.attr("version") = allanlab::app::VersionLine();
  allanlab::python::AddRecordFunctions(m);
  allanlab::python::AddCurveFunctions(m);
}
