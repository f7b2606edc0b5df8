#include "gasp/params/params_file.h"

#include <charconv>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>

#include "gasp/core/error.h"
#include "gasp/core/output_file.h"
#include "param_keys.h"

namespace gasp {

namespace {

using namespace detail;

/// Calls f(key, field) for every field of one section of `p`.
template <class P, class F>
void sectionFields(const std::string& section, P& p, F&& f) {
  auto& pair = p.odometry.pair;
  if (section == "segment") superpixelFields(pair.segment, f);
  else if (section == "associate") associateFields(pair, f);
  else if (section == "hypothesise") hypothesiseFields(pair, f);
  else if (section == "refine") refineFields(pair, f);
  else if (section == "certify") certifyFields(pair, f);
  else if (section == "retry") retryFields(pair, f);
  else if (section == "odometry") odometryFields(p.odometry, f);
  else if (section == "loop_closure") loopClosureFields(p.loop, f);
  else if (section == "pose_graph") poseGraphFields(p.graph, f);
  else if (section == "lidar") lidarFields(p.lidar, f);
}

/// The shortest text of `v` that reads back to the same double (a file people read: 0.1, not
/// 0.10000000000000001).
std::string shortestText(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return r.ec == std::errc() ? std::string(buf, r.ptr) : toText(v);
}

std::string yamlText(double v) { return shortestText(v); }
template <class D>
std::string yamlText(const MayBeInfinite<D>& w) {
  return std::isinf(w.value) ? "inf" : shortestText(static_cast<double>(w.value));
}
std::string yamlText(const std::vector<double>& v) {
  std::string s;
  for (const double x : v) s += (s.empty() ? "" : ", ") + shortestText(x);
  return "[" + s + "]";
}
template <class T>
std::string yamlText(const T& v) {
  return toText(v);
}

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

/// One value of the file: its text (a list's items joined by commas), the line it is on and
/// whether it was a list.
struct Value {
  std::string text;
  int line = 0;
  bool list = false;
};
using Sections = std::map<std::string, std::map<std::string, Value>>;

/// `line` without a trailing comment ('#' at the start or after a blank, outside quotes).
std::string withoutComment(const std::string& line) {
  char quote = 0;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quote) {
      if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '#' && (i == 0 || line[i - 1] == ' ' || line[i - 1] == '\t')) {
      return line.substr(0, i);
    }
  }
  return line;
}

/// A scalar as written: plain, or in single or double quotes (no escapes: no key needs them).
std::string scalar(const std::string& text, const std::function<void(const std::string&)>& fail) {
  const std::string t = trimmed(text);
  if (t.size() >= 2 && (t.front() == '"' || t.front() == '\'') && t.back() == t.front()) return t.substr(1, t.size() - 2);
  if (!t.empty() && (t.front() == '"' || t.front() == '\'')) fail("a quoted value without its closing quote");
  if (!t.empty() && (t.front() == '{' || t.front() == '&' || t.front() == '*' || t.front() == '!' || t.front() == '|' ||
                     t.front() == '>'))
    fail("'" + t + "' is not a plain value (the params file holds numbers, flags, names and [lists])");
  return t;
}

/// The params file's YAML: sections at column 0 ("name:"), each holding "key: value" lines
/// indented below it; a value is a plain or quoted scalar, a flow list "[a, b]" or a block list
/// of "- item" lines. Comments, blank lines, a "%YAML" directive and "---" are allowed. Anything
/// else, a key twice, or a section twice is an error naming the line: a file cut short or
/// mistyped must not load as something else.
Sections parseSections(const std::string& text, const std::string& source) {
  Sections out;
  std::istringstream in(text);
  std::string raw;
  int line_no = 0;
  std::string section;
  Value* open_list = nullptr;  // a key whose value is a block list being read
  std::size_t key_indent = 0;
  auto fail = [&](const std::string& what) {
    throw Error(source + " line " + std::to_string(line_no) + ": " + what);
  };
  bool content_seen = false;
  while (std::getline(in, raw)) {
    ++line_no;
    if (!raw.empty() && raw.back() == '\r') raw.pop_back();
    const std::string line = withoutComment(raw);
    const std::string t = trimmed(line);
    if (t.empty()) continue;
    if (line.find('\t') < line.find_first_not_of(" \t")) fail("a tab in the indentation (YAML indents with spaces)");
    const std::size_t indent = line.find_first_not_of(' ');
    if (indent == 0 && (t.rfind("%YAML", 0) == 0 || t == "---")) {
      if (content_seen) fail("'" + t + "' after the first section (one document per file)");
      continue;
    }
    content_seen = true;
    if (t == "...") break;  // the end of the document
    if (open_list && indent >= key_indent && t.rfind("- ", 0) == 0) {
      const std::string item = scalar(t.substr(2), fail);
      open_list->text += (open_list->list ? "," : "") + item;
      open_list->list = true;
      continue;
    }
    if (open_list && !open_list->list) fail("no value for the key above (a key needs a value or a list below it)");
    open_list = nullptr;
    const std::size_t colon = t.find(':');
    if (colon == std::string::npos || colon == 0 || (colon + 1 < t.size() && t[colon + 1] != ' '))
      fail("'" + t + "' is not 'key: value' (the params file is sections of 'key: value' lines)");
    const std::string name = scalar(t.substr(0, colon), fail);
    const std::string rest = trimmed(t.substr(colon + 1));
    if (indent == 0) {
      if (!rest.empty() && rest != "{}")
        fail("section '" + name + "' holds keys on the lines below it, not a value ('" + rest + "')");
      if (paramsKeys(name).empty())
        fail("unknown section '" + name + "' (sections: " + joined(paramsSections()) + ")");
      if (out.count(name)) fail("section '" + name + "' a second time");
      section = name;
      out[section];
      continue;
    }
    if (section.empty()) fail("key '" + name + "' before any section");
    const std::vector<std::string> keys = paramsKeys(section);
    if (std::find(keys.begin(), keys.end(), name) == keys.end())
      fail("unknown key '" + name + "' in section '" + section + "' (its keys: " + joined(keys) + ")");
    auto& values = out[section];
    if (values.count(name)) fail("key '" + section + "." + name + "' a second time");
    Value& v = values[name];
    v.line = line_no;
    if (rest.empty()) {  // a block list follows
      open_list = &v;
      key_indent = indent;
      continue;
    }
    if (rest.front() == '[') {
      if (rest.back() != ']') fail("a list without its closing ']'");
      std::string items;
      std::stringstream list(rest.substr(1, rest.size() - 2));
      std::string item;
      while (std::getline(list, item, ',')) items += (items.empty() ? "" : ",") + scalar(item, fail);
      v.text = items;
      v.list = true;
      continue;
    }
    v.text = scalar(rest, fail);
  }
  if (open_list && !open_list->list) {
    line_no = open_list->line;
    fail("no value for this key (a key needs a value or a list below it)");
  }
  return out;
}

/// Sets one value on `p`; false when the text is not a value of the field's kind (`kind` says
/// what it must be).
bool setValue(SlamParams& p, const std::string& section, const std::string& key, const Value& v, std::string& kind) {
  bool ok = false;
  sectionFields(section, p, [&](const char* k, auto&& field) {
    if (key != k) return;
    kind = typeName(field);
    using V = std::decay_t<decltype(field)>;
    if (v.list && !std::is_same_v<V, std::vector<double>>) return;  // a list where one value belongs
    ok = parse(v.text, std::forward<decltype(field)>(field));
  });
  return ok;
}

}  // namespace

const std::vector<std::string>& paramsSections() {
  static const std::vector<std::string> sections{"segment", "associate",    "hypothesise", "refine",    "certify",
                                                 "retry",   "odometry",     "loop_closure", "pose_graph", "lidar"};
  return sections;
}

std::vector<std::string> paramsKeys(const std::string& section) {
  std::vector<std::string> keys;
  SlamParams p;
  sectionFields(section, p, [&](const char* key, auto&&) { keys.emplace_back(key); });
  return keys;
}

namespace {

/// " line N" for a value read from a file's text, "" for one from a YAML node (no lines).
std::string lineOf(int line) { return line > 0 ? " line " + std::to_string(line) : ""; }

/// `base` with the values of `sections` set, then validated.
SlamParams applySections(const Sections& sections, const std::string& source, const SlamParams& base) {
  SlamParams p = base;
  for (const auto& [section, values] : sections)
    for (const auto& [key, value] : values) {
      std::string kind;
      if (!setValue(p, section, key, value, kind))
        throw Error(source + lineOf(value.line) + ": " + section + "." + key + " = '" +
                    (value.list ? "[" + value.text + "]" : value.text) + "': expected " + kind);
    }
  try {
    validate(p);
  } catch (const Error& e) {
    // Name the keys that are invalid on their own: validate's messages name the C++ fields.
    std::string culprits;
    for (const auto& [section, values] : sections)
      for (const auto& [key, value] : values) {
        SlamParams trial = base;
        std::string kind;
        setValue(trial, section, key, value, kind);
        try {
          validate(trial);
        } catch (const Error&) {
          culprits += (culprits.empty() ? " (" : ", ") + section + "." + key +
                      (value.line > 0 ? " on line " + std::to_string(value.line) : "");
        }
      }
    throw Error(source + ": invalid parameters" + (culprits.empty() ? "" : culprits + ")") + ": " + e.what());
  }
  return p;
}

/// A scalar of a YAML node as text; a double exactly (MRPT's own text may round it).
std::string scalarText(const mrpt::containers::yaml& v) {
  if (v.scalarType() == typeid(double)) return shortestText(v.as<double>());
  if (v.scalarType() == typeid(float)) return shortestText(static_cast<double>(v.as<float>()));
  return trimmed(v.as<std::string>());
}

}  // namespace

SlamParams readParamsYaml(const std::string& yaml_text, const std::string& source, const SlamParams& base) {
  return applySections(parseSections(yaml_text, source), source, base);
}

SlamParams readParamsNode(const mrpt::containers::yaml& node, const std::string& source, const SlamParams& base) {
  Sections sections;
  if (node.isNullNode() || node.empty()) return applySections(sections, source, base);
  if (!node.isMap()) throw Error(source + ": parameters must be a map of sections (docs/parameters.md)");
  for (const auto& [section_key, section_node] : node.asMap()) {
    const std::string section = section_key.as<std::string>();
    if (paramsKeys(section).empty())
      throw Error(source + ": unknown section '" + section + "' (sections: " + joined(paramsSections()) + ")");
    const mrpt::containers::yaml values(section_node);
    auto& out = sections[section];
    if (values.isNullNode() || values.empty()) continue;
    if (!values.isMap()) throw Error(source + ": section '" + section + "' must hold 'key: value' pairs");
    const std::vector<std::string> keys = paramsKeys(section);
    for (const auto& [key_node, value_node] : values.asMap()) {
      const std::string key = key_node.as<std::string>();
      if (std::find(keys.begin(), keys.end(), key) == keys.end())
        throw Error(source + ": unknown key '" + key + "' in section '" + section + "' (its keys: " + joined(keys) + ")");
      const mrpt::containers::yaml v(value_node);
      Value value;
      if (v.isSequence()) {
        value.list = true;
        for (const auto& item : v.asSequence()) {
          const mrpt::containers::yaml e(item);
          if (!e.isScalar()) throw Error(source + ": " + section + "." + key + ": a list of plain values expected");
          value.text += (value.text.empty() ? "" : ",") + scalarText(e);
        }
      } else if (v.isScalar()) {
        value.text = scalarText(v);
      } else {
        throw Error(source + ": " + section + "." + key + ": a plain value or a list expected");
      }
      out[key] = value;
    }
  }
  return applySections(sections, source, base);
}

SlamParams readParamsFile(const std::string& path, const SlamParams& base) {
  // A params file is a regular file of a few kilobytes: a device or a FIFO (/dev/zero) would be
  // read without end, a huge file is no params file.
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) throw Error("params '" + path + "': cannot open the file");
  if (!std::filesystem::is_regular_file(status))
    throw Error("params '" + path + "': not a regular file (a params file is a YAML text file)");
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw Error("params '" + path + "': cannot read the file: " + ec.message());
  if (size > kMaxParamsFileBytes)
    throw Error("params '" + path + "': " + std::to_string(size) + " bytes, more than a params file holds (at most " +
                std::to_string(kMaxParamsFileBytes) + ")");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("params '" + path + "': cannot open the file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw Error("params '" + path + "': cannot read the file");
  return readParamsYaml(text.str(), "params '" + path + "'", base);
}

std::string paramsYaml(const SlamParams& params) {
  std::string out;
  for (const auto& section : paramsSections()) {
    out += section + ":\n";
    sectionFields(section, params, [&](const char* key, const auto& v) { out += std::string("  ") + key + ": " + yamlText(v) + "\n"; });
  }
  return out;
}

void writeParamsFile(const SlamParams& params, const std::string& path) {
  OutputFile file(path, "params file");
  file.write("# GASP parameters (docs/parameters.md): load with --params FILE\n");
  file.write(paramsYaml(params));
  file.commit();
}

bool sameParams(const SlamParams& a, const SlamParams& b) { return paramsYaml(a) == paramsYaml(b); }

}  // namespace gasp
