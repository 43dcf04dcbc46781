#pragma once
// The pairs file of `rgbdvo calibrate`: CSV with the header `u_vis,v_vis,u_ir,v_ir` and one
// pair per line (pixels; colour image first, IR/depth image second), or with the header
// `u_vis,v_vis,u_ir,v_ir,z_ir_m` and the depth at the IR pixel (metres, 0 = unknown) as a fifth
// column (written when any pair has a depth; it lets the fit find the disparity term). Blank lines
// and lines starting with '#' are ignored.

#include <string>
#include <vector>

#include "rgbdvo/calibrate/mapping_fit.hpp"

namespace rgbdvo {

// Throws std::runtime_error "FILE:LINE: ..." for a missing file, a wrong header, a line without
// exactly 4 (5) numbers or a non-finite number.
std::vector<PixelPair> LoadPixelPairs(const std::string& path);

// Writes the header and the pairs (full precision). Throws std::runtime_error naming the file
// if it cannot be written.
void SavePixelPairs(const std::vector<PixelPair>& pairs, const std::string& path);

}  // namespace rgbdvo
