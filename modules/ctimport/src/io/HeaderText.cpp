#include "HeaderText.h"

#include <cctype>
#include <charconv>
#include <cmath>

#include "reamsim/mesh/MeshError.h"

namespace reamsim::ct::io {

std::string trim(std::string_view s) {
  std::size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return std::string(s.substr(b, e - b));
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::vector<std::string> splitWords(std::string_view s) {
  std::vector<std::string> words;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    std::size_t j = i;
    while (j < s.size() && !std::isspace(static_cast<unsigned char>(s[j]))) ++j;
    if (j > i) words.emplace_back(s.substr(i, j - i));
    i = j;
  }
  return words;
}

double parseNumber(const std::string& path, long line, const std::string& token, const std::string& what) {
  double v = 0;
  const char* first = token.data();
  const char* last = token.data() + token.size();
  if (first != last && *first == '+') ++first;
  const auto r = std::from_chars(first, last, v);
  if (token.empty() || r.ec != std::errc() || r.ptr != last) {
    // NRRD writes "nan" for non-spatial axes; from_chars accepts it, so anything failing here is garbage.
    throw InputError(path, line, what + ": '" + token + "' is not a number");
  }
  return v;
}

long parseInteger(const std::string& path, long line, const std::string& token, const std::string& what) {
  long v = 0;
  const char* first = token.data();
  const char* last = token.data() + token.size();
  if (first != last && *first == '+') ++first;
  const auto r = std::from_chars(first, last, v);
  if (token.empty() || r.ec != std::errc() || r.ptr != last)
    throw InputError(path, line, what + ": '" + token + "' is not an integer");
  return v;
}

std::vector<long> numberedFileSequence(const std::string& path, long line, const std::string& minToken,
                                       const std::string& maxToken, const std::string& stepToken, const std::string& label) {
  constexpr long kLimit = 1000000000;  // file numbers beyond ±1e9 are not a volume's slices
  const long first = parseInteger(path, line, minToken, label + " min");
  const long last = parseInteger(path, line, maxToken, label + " max");
  const long step = parseInteger(path, line, stepToken, label + " step");
  auto outside = [&](long v) { return v < -kLimit || v > kLimit; };  // not std::abs: it overflows on LONG_MIN
  if (outside(first) || outside(last) || outside(step))
    throw InputError(path, line, label + ": min, max and step must lie within ±" + std::to_string(kLimit));
  if (step == 0 || (last - first) / step < 0)
    throw InputError(path, line, label + ": min, max and step do not describe a sequence");
  const long count = (last - first) / step + 1;
  if (count > 100000) throw InputError(path, line, label + ": more than 100000 files");
  std::vector<long> numbers;
  for (long i = 0; i < count; ++i) numbers.push_back(first + i * step);
  return numbers;
}

std::vector<double> parseNumbers(const std::string& path, long line, const std::string& value, std::size_t count,
                                 const std::string& what) {
  const std::vector<std::string> words = splitWords(value);
  if (words.size() != count)
    throw InputError(path, line, what + ": expected " + std::to_string(count) + " numbers, found " +
                                     std::to_string(words.size()));
  std::vector<double> out;
  for (const std::string& w : words) out.push_back(parseNumber(path, line, w, what));
  return out;
}

bool parseBool(const std::string& path, long line, const std::string& value, const std::string& what) {
  const std::string v = lower(trim(value));
  if (v == "true" || v == "1" || v == "yes") return true;
  if (v == "false" || v == "0" || v == "no") return false;
  throw InputError(path, line, what + ": expected True or False, found '" + value + "'");
}

}  // namespace reamsim::ct::io
