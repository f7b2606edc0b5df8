#pragma once
/// \file baseline_method.h The baselines by name, as gasp-pairs --method takes them.
#include <string>
#include <vector>

namespace gasp::baselines {

enum class BaselineMethod { kFpfh, kShot, kColourShot, kSift, kDenseSift };

/// "fpfh", "shot", "cshot", "sift", "dsift".
std::string methodName(BaselineMethod method);

/// The inverse of methodName(); throws gasp::Error for an unknown name.
BaselineMethod parseMethod(const std::string& name);

/// All five, in the order above.
std::vector<BaselineMethod> allMethods();

/// Whether the method reads the colour image (colour SHOT, SIFT, dense SIFT).
bool needsColour(BaselineMethod method);

}  // namespace gasp::baselines
