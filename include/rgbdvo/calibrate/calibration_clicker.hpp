#pragma once
// The state of the interactive `rgbdvo calibrate` window, without any window: the user clicks a
// point in the colour image and its twin in the IR/depth image (either first), pairs are
// numbered, the mapping of paper eq. 1 is refitted after every change, and Render() draws the
// canvas that a thin highgui loop shows. Coordinates passed in are canvas pixels.
//
// Canvas layout (fixed, no scaling by the window): colour image at (0, 0), depth image to its
// right at (colour width * scale, 0), both scaled by `scale`; a text panel below them with the
// keys, the fit, each pair's residual and a magnifier around the mouse.

#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "rgbdvo/calibrate/mapping_fit.hpp"
#include "rgbdvo/sensor/calibration.hpp"
#include "rgbdvo/sources/frame.hpp"

namespace rgbdvo {

struct ClickerOptions {
  double scale = 1.0;         // screen pixels per image pixel (0.5 for small screens)
  int panel_height_px = 120;  // text panel below the images, pixels
  int frame_step = 10;        // frames skipped by the next/previous keys
  MappingFitOptions fit;
  void Check() const;  // throws std::invalid_argument naming the field
};

enum class ClickerAction { kNone, kSave, kQuit, kNextFrame, kPrevFrame };

// A pair with the frame it was clicked on (-1: loaded from a pairs file).
struct ClickedPair {
  PixelPair pair;
  int frame = -1;
};

class CalibrationClicker {
 public:
  // `base` gives the depth range for the colour map; `initial` pairs (e.g. from --pairs) count
  // in the fit but are drawn on no frame.
  CalibrationClicker(const ClickerOptions& options, const std::vector<PixelPair>& initial = {});

  // Shows this frame; pairs clicked from now on belong to frame.index. A pending click is dropped.
  void SetFrame(const Frame& frame);
  // A left click at canvas pixel (x, y): starts a pair or completes it. Clicks outside both
  // images are ignored; a second click in the same image moves the pending point.
  void Click(int x, int y);
  // The mouse position, for the magnifier.
  void Hover(int x, int y);
  // A key code as returned by cv::waitKey (-1: none). u/Backspace: undo the pending point or
  // the last pair; r: robust fit on/off; n/p: next/previous frame; s: save; q/Esc: quit (asks
  // again while there are unsaved pairs). Returns what the caller must do.
  ClickerAction Key(int key);
  // One line shown at the bottom (e.g. "wrote calib.yaml").
  void SetMessage(const std::string& message) { message_ = message; }
  void MarkSaved() { dirty_ = false; }
  // What happened since the last call, one line per event (a point, a pair with the new fit,
  // an undo, robust on/off), for the terminal; the window test waits for these lines.
  std::vector<std::string> TakeLog();

  cv::Mat Render() const;  // CV_8UC3 canvas of CanvasSize()
  cv::Size CanvasSize() const;
  // Canvas pixel of an image point (ir=false: colour image, true: depth image).
  cv::Point2d ToCanvas(const cv::Point2d& image_pt, bool ir) const;

  std::vector<PixelPair> Pairs() const;
  const std::vector<ClickedPair>& clicked() const { return pairs_; }
  const MappingFit& fit() const { return fit_; }
  bool dirty() const { return dirty_; }
  bool robust() const { return options_.fit.robust; }

 private:
  struct Pending {
    cv::Point2d pt;
    bool ir = false;
  };
  // Which image the canvas pixel falls in, and the image point; nullopt outside both.
  std::optional<Pending> FromCanvas(int x, int y) const;
  void Refit();
  void Log(const std::string& line);
  void DrawPanel(cv::Mat& canvas) const;
  void DrawMagnifier(cv::Mat& canvas, const cv::Mat& images) const;
  cv::Size VisSize() const;
  cv::Size IrSize() const;

  ClickerOptions options_;
  std::vector<ClickedPair> pairs_;
  std::optional<Pending> pending_;
  MappingFit fit_;
  cv::Mat vis_bgr_, depth_bgr_;  // images as shown (unscaled), depth colour-mapped
  cv::Mat depth_m_;              // the frame's depth, metres (a pair's z_ir_m)
  int frame_index_ = -1;
  double timestamp_ = 0;
  cv::Point hover_{-1, -1};
  std::string message_;
  std::vector<std::string> log_;
  bool dirty_ = false;
  bool quit_asked_ = false;
};

// The depth image (CV_32FC1 metres, 0 = no reading) as a colour image: turbo colour map over
// the 2nd..98th percentile of the valid depths, missing depth black.
cv::Mat ColorizeDepth(const cv::Mat& depth_m);

// The nearest depth (metres) among the 3x3 pixels around pt in a CV_32FC1 depth image, 0 when
// none has a reading: a pair's z_ir_m (a clicked depth edge belongs to the nearer surface).
double NearestDepth(const cv::Mat& depth_m, const cv::Point2d& pt);

}  // namespace rgbdvo
