#pragma once
/// \file text_file.h Line-oriented parsing of the project's text formats, with file:line errors.
#include <functional>
#include <string>
#include <vector>

namespace gasp {

/// Whitespace trimmed from both ends.
std::string trim(const std::string& s);

/// Calls fn(line, line_number) for each line of a text file that is neither empty nor a
/// '#' comment (line numbers start at 1). Throws gasp::Error if the file cannot be opened.
void forEachDataLine(const std::string& path,
                     const std::function<void(const std::string&, int)>& fn);

/// All whitespace-separated numbers of `text`; throws gasp::Error naming path:line for a token
/// that is not a finite number.
std::vector<double> parseNumbers(const std::string& text, const std::string& path, int line_no);

}  // namespace gasp
