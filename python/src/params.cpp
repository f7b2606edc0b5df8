// The params file from Python: the Python layer (gasp/__init__.py) turns dicts into the file's
// YAML text and back; reading, checking and writing are the params module's.
#include "gasp/params/params_file.h"

#include <pybind11/stl/filesystem.h>

#include <filesystem>

#include "bindings.h"

namespace gasp::python {

SlamParams paramsFromYaml(const std::string& yaml_text) {
  return yaml_text.empty() ? SlamParams{} : readParamsYaml(yaml_text, "params");
}

void bindParams(py::module_& m) {
  m.def("_default_params_yaml", [] { return paramsYaml(SlamParams{}); },
        "The params file of the defaults (YAML text).");
  m.def("_effective_params_yaml", [](const std::string& yaml_text) { return paramsYaml(paramsFromYaml(yaml_text)); },
        py::arg("yaml_text"), "Every parameter after `yaml_text` is read over the defaults (checked).");
  m.def("_read_params_file", [](const std::filesystem::path& path) { return paramsYaml(readParamsFile(path.string())); },
        py::arg("path"),
        "Every parameter after the params file at `path` is read over the defaults (checked).");
  m.def("_write_params_file",
        [](const std::string& yaml_text, const std::filesystem::path& path) {
          writeParamsFile(paramsFromYaml(yaml_text), path.string());
        },
        py::arg("yaml_text"), py::arg("path"),
        "Writes every parameter (`yaml_text` over the defaults) to `path`: a temporary file in the same folder, "
        "checked, then renamed.");
}

}  // namespace gasp::python
