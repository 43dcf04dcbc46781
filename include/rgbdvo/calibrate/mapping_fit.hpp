#pragma once
// Least-squares fit of the colour -> IR pixel mapping of paper section 2.1, eq. 1:
// u_ir = A * u_vis + B and v_ir = C * v_vis + D, from pixels identified in both images; when
// the pairs' depths span enough, with the disparity term eq. 1 leaves out (+ s_u / z, + s_v / z;
// Calibration::s_u).

#include <string>
#include <vector>

namespace rgbdvo {

// One world point seen at (u_vis, v_vis) in the colour image and (u_ir, v_ir) in the IR/depth
// image, pixels.
struct PixelPair {
  double u_vis = 0, v_vis = 0, u_ir = 0, v_ir = 0;
  double z_ir_m = 0;  // depth at (u_ir, v_ir), metres; 0 = not known
};

struct MappingFitOptions {
  int min_pairs = 3;            // fewer pairs are refused (2 unknowns per axis + 1 to check)
  double min_spread_px = 10.0;  // u_vis (and v_vis) must span at least this, pixels
  bool robust = false;          // flag outlier pairs and fit without them
  double outlier_px = 4.0;      // robust: a pair whose residual exceeds this is an outlier, px
  // Fit s_u, s_v too when there are more than min_pairs pairs, every pair has a depth and
  // their inverse depths 1/z span at least this, 1/m (1.5 m to 3 m spans 0.33; the Kinect's
  // 2.5 cm baseline then moves a point by 580 * 0.025 * 0.33 = 4.8 px between the two ends).
  // Below it the term is not observable.
  double min_inverse_depth_spread = 0.2;
  bool fit_disparity = true;  // false: eq. 1 only, whatever the depths
  void Check() const;         // throws std::invalid_argument naming the field
};

struct MappingFit {
  bool success = false;
  std::string reason;  // why the fit failed (empty on success)
  double A = 1, B = 0, C = 1, D = 0;
  bool depth_aware = false;  // s_u, s_v were fitted (else 0: eq. 1)
  double s_u = 0, s_v = 0;   // pixels * metres
  int num_pairs = 0;         // pairs given
  int num_inliers = 0;       // pairs used by the final fit (all unless robust)
  double rms_px = 0;         // RMS of the inliers' residuals, pixels
  // Per given pair: |(A u_vis + B + s_u / z, C v_vis + D + s_v / z) - (u_ir, v_ir)|, pixels
  // (s = 0 unless depth_aware), and whether the robust
  // fit set it aside. Filled on success only.
  std::vector<double> residual_px;
  std::vector<bool> outlier;
  std::string Brief() const;  // one line: A-D, pairs, outliers, RMS (or the reason)
};

// Fits (A, B) to the (u_vis, u_ir) and (C, D) to the (v_vis, v_ir) by linear least squares,
// (A, B, s_u) and (C, D, s_v) with the depths when they span min_inverse_depth_spread.
// Fails (success = false, reason says why) with fewer than options.min_pairs pairs, when the
// u_vis or v_vis span less than min_spread_px (all equal: the scale is undetermined), or when
// A or C comes out zero. Robust mode removes the worst pair while its residual exceeds
// outlier_px and min_pairs would remain, refitting each time.
MappingFit FitMapping(const MappingFitOptions& options, const std::vector<PixelPair>& pairs);

}  // namespace rgbdvo
