#include "rgbdvo/calibrate/calibrate.hpp"

#include <filesystem>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "rgbdvo/calibrate/pixel_pairs_file.hpp"

namespace rgbdvo {

Calibration ApplyMappingFit(const Calibration& base, const MappingFit& fit,
                            const std::string& pairs_note) {
  if (!fit.success) throw std::invalid_argument("ApplyMappingFit: the fit failed: " + fit.reason);
  Calibration c = base;
  c.A = fit.A, c.B = fit.B, c.C = fit.C, c.D = fit.D;
  c.s_u = fit.s_u, c.s_v = fit.s_v;
  std::ostringstream d;
  d << (fit.depth_aware ? "A-D and s_u, s_v" : "A-D") << " fitted by rgbdvo calibrate from "
    << fit.num_inliers << " pairs";
  if (!pairs_note.empty()) d << " (" << pairs_note << ")";
  d << ", RMS " << std::setprecision(3) << fit.rms_px << " px.";
  if (!base.description.empty()) d << " Other fields: " << base.description;
  c.description = d.str();
  c.Check();
  return c;
}

std::string FitReport(const MappingFit& fit, const std::vector<PixelPair>& pairs) {
  std::ostringstream s;
  s << fit.Brief() << "\n";
  if (!fit.success) return s.str();
  bool depths = false;
  for (const PixelPair& p : pairs) depths = depths || p.z_ir_m > 0;
  s << "pair  u_vis   v_vis   u_ir    v_ir  " << (depths ? "  z_ir_m" : "") << "  residual_px\n";
  for (size_t i = 0; i < pairs.size(); ++i) {
    const PixelPair& p = pairs[i];
    s << std::setw(4) << i + 1 << std::fixed << std::setprecision(1) << std::setw(8) << p.u_vis
      << std::setw(8) << p.v_vis << std::setw(8) << p.u_ir << std::setw(8) << p.v_ir;
    if (depths) s << std::setprecision(3) << std::setw(8) << p.z_ir_m;
    s << std::setprecision(2) << std::setw(10) << fit.residual_px[i]
      << (fit.outlier[i] ? "  outlier (not used)" : "") << "\n";
    s.unsetf(std::ios::fixed);
  }
  return s.str();
}

std::string WriteCalibrateOutputs(const std::vector<PixelPair>& pairs, const MappingFit& fit,
                                  const Calibration& base, const std::string& calib_path,
                                  const std::string& pairs_path) {
  std::string msg;
  if (!pairs_path.empty()) {
    SavePixelPairs(pairs, pairs_path);
    msg = "wrote " + std::to_string(pairs.size()) + " pairs to " + pairs_path;
  }
  if (!msg.empty()) msg += "; ";
  if (!fit.success) return msg + "calibration not written: " + fit.reason;
  const std::string note =
      pairs_path.empty() ? "" : std::filesystem::path(pairs_path).filename().string();
  SaveCalibration(ApplyMappingFit(base, fit, note), calib_path);
  return msg + "wrote " + calib_path;
}

std::string DefaultPairsPath(const std::string& calib_path) {
  std::filesystem::path p(calib_path);
  p.replace_extension(".pairs.csv");
  return p.string();
}

}  // namespace rgbdvo
