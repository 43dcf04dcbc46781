#pragma once
// Reading numbers from the text files others make (trajectories, pixel pairs, lists): one rule
// for every parser, so each refuses the same things with the same message.

#include <string>
#include <vector>

namespace rgbdvo {

// s without leading and trailing spaces, tabs, CR and LF.
std::string Trim(const std::string& s);

// The number in field (surrounding whitespace ignored), or std::runtime_error "<where>: '<field>'
// is not a number" (empty, trailing characters: "4px") or "... is not finite" (inf, nan, out of
// double's range). `where` names the place, e.g. "file.csv:3" or "file.txt:3: tx".
double ParseNumber(const std::string& field, const std::string& where);

// One line of a list file, without its trailing CR, and its 1-based number (for messages).
struct ListLine {
  int number = 0;
  std::string text;
};
// The content lines of a list file (TUM's rgb.txt and accelerometer.txt, association files):
// blank lines and '#' comments skipped, a UTF-8 byte order mark at the start ignored. Throws
// ReadTextFile's errors ("<path>: cannot open <what> (<reason>)", not a regular file, above
// kMaxListFileBytes).
std::vector<ListLine> ReadListLines(const std::string& path, const std::string& what);

}  // namespace rgbdvo
