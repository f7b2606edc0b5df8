#include "gasp/graphslam/ini_check.h"

#include <algorithm>
#include <fstream>
#include <set>

#include "gasp/core/error.h"

namespace gasp::graphslam {

namespace {

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

}  // namespace

IniCheck checkGraphSlamIni(const std::string& path) {
  static const std::set<std::string> kKnown = {
      "GeneralConfiguration",          "VisualizationParameters", "NodeRegistrationDeciderParameters",
      "EdgeRegistrationDeciderParameters", "OptimizerParameters", "CGaspOdometryNRD",
      "CGaspLoopClosureERD",           "CGaspPoseGraphGSO"};
  std::ifstream in(path);
  if (!in) throw Error("cannot open configuration " + path);
  IniCheck check;
  std::string line;
  bool continued = false;  // the previous line ended with '\': this one belongs to it
  for (int n = 1; std::getline(in, line); ++n) {
    const std::string t = trimmed(line);
    const bool was_continued = continued;
    continued = !t.empty() && t.back() == '\\';
    // MRPT's CConfigFile also takes "@define NAME VALUE" lines and lines continued with '\'.
    if (was_continued || t.empty() || t[0] == '#' || t[0] == ';' || t[0] == '@' || t.rfind("//", 0) == 0) continue;
    if (t.front() == '[') {
      if (t.back() != ']' || t.size() < 3) {
        if (check.error.empty()) check.error = path + ":" + std::to_string(n) + ": a section needs [NAME], got '" + t + "'";
        continue;
      }
      const std::string name = trimmed(t.substr(1, t.size() - 2));
      if (!kKnown.count(name) &&
          std::find(check.unknown_sections.begin(), check.unknown_sections.end(), name) == check.unknown_sections.end())
        check.unknown_sections.push_back(name);
      continue;
    }
    const auto eq = t.find('=');
    if ((eq == std::string::npos || trimmed(t.substr(0, eq)).empty()) && check.error.empty())
      check.error = path + ":" + std::to_string(n) + ": neither a [section] nor 'key = value': '" +
                    (t.size() > 60 ? t.substr(0, 60) + "..." : t) + "'";
  }
  return check;
}

}  // namespace gasp::graphslam
