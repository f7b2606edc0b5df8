#pragma once
/// \file params_io.h GASP's parameters in MRPT's configuration formats: ini sections
/// (mrpt::config::CConfigFileBase, as CMultiMetricMap and CGaspAligner read them) and YAML
/// (mrpt::containers::yaml, as ObservationMatcher_GASP reads them). One key table per struct, so
/// every format uses the same names, those of the params file (params_file.h; docs/parameters.md
/// lists every key with its default).
///
/// Reading: missing keys keep the value passed in; unknown keys and invalid values throw an MRPT
/// exception (std::exception) naming the section and the key.
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/containers/yaml.h>

#include <set>
#include <string>

#include "gasp/odometry/odometry_params.h"
#include "gasp/pipeline/pair_registration.h"
#include "gasp/slam/slam_params.h"
#include "gasp/superpixels/superpixel_params.h"

namespace gasp {

/// Segmentation: every field of SuperpixelParams, under its C++ name.
void readSuperpixelParams(const mrpt::config::CConfigFileBase& source, const std::string& section,
                          SuperpixelParams& params, const std::set<std::string>& other_allowed_keys = {});
void writeSuperpixelParams(const SuperpixelParams& params, mrpt::config::CConfigFileBase& target,
                           const std::string& section);

/// The pair pipeline: every field of PairParams, its segmentation under the keys above and the
/// rest under the keys of sections associate to retry of docs/parameters.md. Enumerations by name
/// (candidate_key: quantiles | mean; refinement_loss: none | huber | cauchy), dense_gates_m as a
/// comma-separated list (or a YAML sequence), cost_replace and cost_transpose may be inf.
void readPairParams(const mrpt::config::CConfigFileBase& source, const std::string& section, PairParams& params,
                    const std::set<std::string>& other_allowed_keys = {});
/// The YAML form takes either the flat keys or the params file's form: its sections (segment to
/// retry used, the others checked) and `params_file: PATH`, a params file loaded first.
/// `lidar` (when given): the params file form's section `lidar` goes there too (unchanged by the
/// flat keys).
void readPairParams(const mrpt::containers::yaml& source, const std::string& who, PairParams& params,
                    LidarParams* lidar = nullptr);
void writePairParams(const PairParams& params, mrpt::config::CConfigFileBase& target, const std::string& section);

/// A rotating LiDAR's values (LidarParams): the keys of the params file's section lidar.
void readLidarParams(const mrpt::config::CConfigFileBase& source, const std::string& section, LidarParams& params,
                     const std::set<std::string>& other_allowed_keys = {});
void writeLidarParams(const LidarParams& params, mrpt::config::CConfigFileBase& target, const std::string& section);

/// The keys each table reads, for a section that holds several (as other_allowed_keys).
std::set<std::string> superpixelKeys();
std::set<std::string> pairKeys();
std::set<std::string> lidarKeys();

/// The odometry (a decider's section): PairParams' keys and those of the params file's section
/// odometry.
void readOdometryParams(const mrpt::config::CConfigFileBase& source, const std::string& section,
                        OdometryParams& params, const std::set<std::string>& other_allowed_keys = {});
void writeOdometryParams(const OdometryParams& params, mrpt::config::CConfigFileBase& target,
                         const std::string& section);

/// The loop closer (a decider's section): PairParams' keys and those of section loop_closure.
void readLoopClosureParams(const mrpt::config::CConfigFileBase& source, const std::string& section, PairParams& pair,
                           LoopClosureParams& loop, const std::set<std::string>& other_allowed_keys = {});
void writeLoopClosureParams(const PairParams& pair, const LoopClosureParams& loop, mrpt::config::CConfigFileBase& target,
                            const std::string& section);

/// The pose-graph optimiser: the keys of section pose_graph.
void readPoseGraphSettings(const mrpt::config::CConfigFileBase& source, const std::string& section,
                           PoseGraphSettings& settings, const std::set<std::string>& other_allowed_keys = {});
void writePoseGraphSettings(const PoseGraphSettings& settings, mrpt::config::CConfigFileBase& target,
                            const std::string& section);

/// One value, strictly parsed; a missing key leaves it unchanged. Throws naming section and key.
void readValue(const mrpt::config::CConfigFileBase& source, const std::string& section, const std::string& key,
               double& value);
void readValue(const mrpt::config::CConfigFileBase& source, const std::string& section, const std::string& key,
               int& value);
/// A flag: true/false, 1/0, yes/no, on/off (as the pair keys read them).
void readValue(const mrpt::config::CConfigFileBase& source, const std::string& section, const std::string& key,
               bool& value);
/// Writes a number so that it reads back exactly (%.17g; MRPT's write(double) keeps 6 decimals).
void writeValue(mrpt::config::CConfigFileBase& target, const std::string& section, const std::string& key,
                double value);
/// Throws when the section holds a key not in `known`.
void checkKeys(const mrpt::config::CConfigFileBase& source, const std::string& section,
               const std::set<std::string>& known);

}  // namespace gasp
