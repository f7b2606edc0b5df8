#pragma once
/// \file bindings.h The module's parts, each binding one area of GASP (docs/python.md).
#include <pybind11/pybind11.h>

#include <string>

#include "gasp/slam/slam_params.h"

namespace gasp::python {

namespace py = pybind11;

/// Parameters as the params file's YAML text (the Python layer turns dicts and paths into it;
/// empty: the defaults). Throws gasp::Error naming the key.
SlamParams paramsFromYaml(const std::string& yaml_text);

void bindParams(py::module_& m);     ///< params.cpp: defaults, reading and writing the params file
void bindPairs(py::module_& m);      ///< pairs.cpp: intrinsics, views (segmentation), registration, TUM folders
void bindSequences(py::module_& m);  ///< sequences.cpp: trajectories, odometry and SLAM, ATE

}  // namespace gasp::python
