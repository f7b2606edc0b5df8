#pragma once
/// \file params_file.h The params file: every parameter of GASP in one YAML file, one section per
/// stage of the pair pipeline (segment, associate, hypothesise, refine, certify, retry) and for
/// the odometry, the loop closer and the pose graph (docs/parameters.md lists every key with its
/// default; params/gasp.yaml is the file of defaults). Every program loads it with --params and
/// writes its effective values with --print-params; the MRPT matcher, aligner and map read the
/// same keys (params_io.h).
///
/// A missing section or key keeps the value it is read over. An unknown section or key, a value
/// of the wrong kind, or values that together are invalid (validate(SlamParams)) are errors naming
/// the file and the key.
#include <mrpt/containers/yaml.h>

#include <cstddef>
#include <string>
#include <vector>

#include "gasp/slam/slam_params.h"

namespace gasp {

/// The sections, in the file's order.
const std::vector<std::string>& paramsSections();

/// The keys of one section, in the file's order (empty for a name that is no section).
std::vector<std::string> paramsKeys(const std::string& section);

/// `base` with the values of the YAML text set; `source` names it in errors ("params 'FILE'").
/// Throws gasp::Error.
SlamParams readParamsYaml(const std::string& yaml_text, const std::string& source, const SlamParams& base = {});

/// The same from a YAML node already parsed (the MRPT matcher's parameters): a map of sections.
SlamParams readParamsNode(const mrpt::containers::yaml& node, const std::string& source, const SlamParams& base = {});

/// The largest params file read (the file of every key is about 5 KB).
constexpr std::size_t kMaxParamsFileBytes = 1 << 20;

/// readParamsYaml over a file's text; an unreadable file, one that is not a regular file (a device,
/// a FIFO, a folder) or one over kMaxParamsFileBytes is an error naming it.
SlamParams readParamsFile(const std::string& path, const SlamParams& base = {});

/// The YAML text of every parameter, section by section, each number written so that it reads
/// back to the same value: readParamsYaml(paramsYaml(p), ...) == p.
std::string paramsYaml(const SlamParams& params);

/// Writes paramsYaml(params) to `path` (a temporary file in the same folder, checked, then
/// renamed). Throws gasp::Error.
void writeParamsFile(const SlamParams& params, const std::string& path);

/// True when every parameter of `a` equals that of `b` (compared as paramsYaml writes them).
bool sameParams(const SlamParams& a, const SlamParams& b);

}  // namespace gasp
