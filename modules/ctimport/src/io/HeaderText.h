#pragma once
// Parsing helpers for the text headers of NRRD and MetaImage; errors name the file and the header line.
#include <string>
#include <string_view>
#include <vector>

namespace reamsim::ct::io {

// A header field's value and the line it was read from (for messages).
struct HeaderField {
  std::string value;
  long line = 0;
};

std::string trim(std::string_view s);
std::string lower(std::string_view s);
std::vector<std::string> splitWords(std::string_view s);

double parseNumber(const std::string& path, long line, const std::string& token, const std::string& what);
long parseInteger(const std::string& path, long line, const std::string& token, const std::string& what);
// Exactly `count` whitespace-separated numbers.
std::vector<double> parseNumbers(const std::string& path, long line, const std::string& value, std::size_t count,
                                 const std::string& what);
// The numbers of a numbered data-file pattern ("name%03d.raw min max step"): min, min + step, … up to max.
// `label` names the field in messages ("data file", "ElementDataFile"). At most 100,000 numbers; the values are
// bounded before any arithmetic, so no header can overflow it.
std::vector<long> numberedFileSequence(const std::string& path, long line, const std::string& minToken,
                                       const std::string& maxToken, const std::string& stepToken, const std::string& label);
bool parseBool(const std::string& path, long line, const std::string& value, const std::string& what);

}  // namespace reamsim::ct::io
