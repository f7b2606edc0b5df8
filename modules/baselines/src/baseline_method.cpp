#include "gasp/baselines/baseline_method.h"

#include "gasp/core/error.h"

namespace gasp::baselines {

std::string methodName(BaselineMethod method) {
  switch (method) {
    case BaselineMethod::kFpfh: return "fpfh";
    case BaselineMethod::kShot: return "shot";
    case BaselineMethod::kColourShot: return "cshot";
    case BaselineMethod::kSift: return "sift";
    case BaselineMethod::kDenseSift: return "dsift";
  }
  return "?";
}

BaselineMethod parseMethod(const std::string& name) {
  for (auto m : allMethods())
    if (methodName(m) == name) return m;
  throw Error("unknown baseline '" + name + "' (fpfh, shot, cshot, sift, dsift)");
}

std::vector<BaselineMethod> allMethods() {
  return {BaselineMethod::kFpfh, BaselineMethod::kShot, BaselineMethod::kColourShot, BaselineMethod::kSift,
          BaselineMethod::kDenseSift};
}

bool needsColour(BaselineMethod method) {
  return method == BaselineMethod::kColourShot || method == BaselineMethod::kSift ||
         method == BaselineMethod::kDenseSift;
}

}  // namespace gasp::baselines
