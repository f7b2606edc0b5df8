#include "gasp/core/text_file.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "gasp/core/error.h"

namespace gasp {

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return {};
  const auto last = s.find_last_not_of(" \t\r\n");
  return s.substr(first, last - first + 1);
}

void forEachDataLine(const std::string& path,
                     const std::function<void(const std::string&, int)>& fn) {
  std::ifstream in(path);
  if (!in) throw Error("cannot open '" + path + "'");
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string t = trim(line);
    if (t.empty() || t[0] == '#') continue;
    fn(t, line_no);
  }
  if (in.bad()) throw Error("read error in '" + path + "'");
}

std::vector<double> parseNumbers(const std::string& text, const std::string& path, int line_no) {
  std::istringstream ss(text);
  std::vector<double> values;
  std::string token;
  while (ss >> token) {
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(token.c_str(), &end);
    if (end == token.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
      throw Error(path + ":" + std::to_string(line_no) + ": '" + token +
                  "' is not a finite number");
    values.push_back(v);
  }
  return values;
}

}  // namespace gasp
