#pragma once
// Parsing helpers for the text headers of NRRD and MetaImage; errors name the file and the header line.
#include <string>
#include <string_view>
#include <vector>

namespace reamsim::ct::io {

std::string trim(std::string_view s);
std::string lower(std::string_view s);
std::vector<std::string> splitWords(std::string_view s);

double parseNumber(const std::string& path, long line, const std::string& token, const std::string& what);
long parseInteger(const std::string& path, long line, const std::string& token, const std::string& what);
// Exactly `count` whitespace-separated numbers.
std::vector<double> parseNumbers(const std::string& path, long line, const std::string& value, std::size_t count,
                                 const std::string& what);
bool parseBool(const std::string& path, long line, const std::string& value, const std::string& what);

}  // namespace reamsim::ct::io
