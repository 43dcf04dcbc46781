#pragma once
// The TUM tools' association file (associate.py's output, as ORB-SLAM and other RGB-D programs
// read it): one colour-depth pair a line, `t_rgb rgb/x.png t_depth depth/y.png`, paths relative
// to the file's folder, '#' comments. The pairing is the file's: TumSource reads the pairs as
// given (in the file's order) instead of pairing rgb.txt with depth.txt.

#include <string>
#include <vector>

#include "rgbdvo/sources/tum_source.hpp"

namespace rgbdvo {

// Reads the pairs. Throws std::runtime_error naming the file and line for an unreadable file, a
// line not of the four fields, or a file without any pair.
std::vector<TumPair> ReadAssociations(const std::string& path);

// True when `path` is a regular file whose first line that is not blank or a comment has the
// four fields of an association line.
bool IsAssociationFile(const std::string& path);

}  // namespace rgbdvo
