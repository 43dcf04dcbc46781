#pragma once
// Figures of an evaluation (`rgbdvo eval --plot ...`), as evo draws them: every estimate against
// the ground truth in the ground truth's frame, each brought there by its own ATE alignment; the
// ATE of every matched pose over time; position and orientation over time. Drawn by gnuplot
// (see gnuplot.hpp).

#include <string>
#include <vector>

#include "rgbdvo/evaluation/evaluation.hpp"
#include "rgbdvo/evaluation/evaluation_report.hpp"
#include "rgbdvo/io/trajectory_io.hpp"

namespace rgbdvo {

struct EvaluationPlotOptions {
  std::string title;                // figure title; empty = "evaluation"
  std::string gnuplot = "gnuplot";  // the gnuplot executable (name on PATH or a path)
  void Check() const;               // throws naming the field
};

// An estimate to draw: its name in the legend, its poses (as given to ComputeAte) and its ATE
// (the alignment and the error of every matched pose). One whose ATE failed is left out of the
// figures and named in the subtitle.
struct PlottedEstimate {
  std::string name;
  std::vector<StampedPose> poses;
  AteResult ate;
};

// Times on the figures are seconds from the ground truth's first pose; an estimate's times are
// its own plus t_offset_s (as matched). Each throws as RenderGnuplot does.

// The x-y and the x-z plane of the ground truth and every aligned
// estimate, equal scale on both axes, 1300x720.
void PlotTrajectories(const std::vector<StampedPose>& groundtruth,
                      const std::vector<PlottedEstimate>& estimates, double t_offset_s,
                      const std::string& png_path, const EvaluationPlotOptions& options);

// The ATE of every matched pose against time, one line per estimate, 1300x560.
void PlotErrors(const std::vector<StampedPose>& groundtruth,
                const std::vector<PlottedEstimate>& estimates, const std::string& png_path,
                const EvaluationPlotOptions& options);

// x, y, z (m) and roll, pitch, yaw (degrees; R = Rz(yaw) Ry(pitch) Rx(roll), evo's "sxyz")
// against time, the ground truth and every aligned estimate, 1300x950.
void PlotPosesOverTime(const std::vector<StampedPose>& groundtruth,
                       const std::vector<PlottedEstimate>& estimates, double t_offset_s,
                       const std::string& png_path, const EvaluationPlotOptions& options);

// The figures of `rgbdvo eval`: PNG paths, empty = not drawn.
struct EvaluationFigures {
  std::string trajectories;  // PlotTrajectories
  std::string errors;        // PlotErrors
  std::string poses;         // PlotPosesOverTime
};

// Reads the files of the reports (one ground truth, an estimate each) and draws the figures
// asked for, with the reports' options and ATE results. Returns one line per figure written.
std::string PlotEvaluation(const std::vector<EvaluationReport>& reports,
                           const EvaluationFigures& figures, const EvaluationPlotOptions& options);

}  // namespace rgbdvo
