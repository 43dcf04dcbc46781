#pragma once
// The body of `rgbdvo calibrate`: fitted A-D into a calibration, the outputs on disk and the
// report printed for the user.

#include <string>
#include <vector>

#include "rgbdvo/calibrate/mapping_fit.hpp"
#include "rgbdvo/sensor/calibration.hpp"

namespace rgbdvo {

// `base` with A, B, C, D replaced by the fit (which must have succeeded) and a description
// saying so; K_ir, the depth range and the base description are kept.
Calibration ApplyMappingFit(const Calibration& base, const MappingFit& fit,
                            const std::string& pairs_note);

// The fit as lines for the terminal: the Brief(), then one line per pair with its residual,
// outliers marked.
std::string FitReport(const MappingFit& fit, const std::vector<PixelPair>& pairs);

// Writes the pairs file (when pairs_path is not empty) and, when the fit succeeded, the
// calibration YAML. Returns one line saying what was written (or why the YAML was not).
// Throws std::runtime_error naming a file that cannot be written.
std::string WriteCalibrateOutputs(const std::vector<PixelPair>& pairs, const MappingFit& fit,
                                  const Calibration& base, const std::string& calib_path,
                                  const std::string& pairs_path);

// The default pairs file beside the calibration: calib.yaml -> calib.pairs.csv.
std::string DefaultPairsPath(const std::string& calib_path);

}  // namespace rgbdvo
