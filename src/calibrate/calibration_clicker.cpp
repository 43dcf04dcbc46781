#include "rgbdvo/calibrate/calibration_clicker.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <stdexcept>
#include <utility>

#include "rgbdvo/calibrate/calibrate.hpp"
#include "rgbdvo/sensor/camera.hpp"

namespace rgbdvo {
namespace {

const cv::Scalar kGood(60, 220, 60), kBad(40, 40, 255), kPending(0, 230, 255),
    kPredicted(255, 80, 255), kText(235, 235, 235), kDim(170, 170, 170), kMessage(255, 220, 120);
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kFontScale = 0.45;
constexpr int kMagnifierHalf = 7;  // image pixels each side of the mouse
constexpr int kMagnifierZoom = 7;  // screen pixels per pixel

void Text(cv::Mat& img, const std::string& s, cv::Point at, const cv::Scalar& colour) {
  cv::putText(img, s, at, kFont, kFontScale, cv::Scalar(0, 0, 0), 3, cv::LINE_AA);
  cv::putText(img, s, at, kFont, kFontScale, colour, 1, cv::LINE_AA);
}

int TextWidth(const std::string& s) {
  int baseline = 0;
  return cv::getTextSize(s, kFont, kFontScale, 1, &baseline).width;
}

std::string Format(const char* fmt, double a) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, a);
  return buf;
}

void Marker(cv::Mat& img, cv::Point2d c, const cv::Scalar& colour, const std::string& label) {
  const cv::Point p(cvRound(c.x), cvRound(c.y));
  cv::circle(img, p, 6, cv::Scalar(0, 0, 0), 3, cv::LINE_AA);
  cv::circle(img, p, 6, colour, 1, cv::LINE_AA);
  cv::line(img, p, p, colour, 1);
  if (!label.empty()) Text(img, label, p + cv::Point(8, -7), colour);
}

void Cross(cv::Mat& img, cv::Point2d c, const cv::Scalar& colour) {
  const cv::Point p(cvRound(c.x), cvRound(c.y));
  cv::drawMarker(img, p, colour, cv::MARKER_TILTED_CROSS, 9, 1, cv::LINE_AA);
}

}  // namespace

cv::Mat ColorizeDepth(const cv::Mat& depth_m) {
  CV_Assert(depth_m.type() == CV_32FC1);
  std::vector<float> valid;
  for (int r = 0; r < depth_m.rows; r += 2)
    for (int c = 0; c < depth_m.cols; c += 2)
      if (depth_m.at<float>(r, c) > 0) valid.push_back(depth_m.at<float>(r, c));
  float lo = 0.5f, hi = 5.0f;
  if (valid.size() > 10) {
    std::sort(valid.begin(), valid.end());
    lo = valid[valid.size() * 2 / 100];
    hi = valid[valid.size() * 98 / 100];
    if (hi <= lo) hi = lo + 0.01f;
  }
  cv::Mat grey;
  depth_m.convertTo(grey, CV_8U, 255.0 / (hi - lo), -255.0 * lo / (hi - lo));  // saturates
  cv::Mat bgr;
  cv::applyColorMap(grey, bgr, cv::COLORMAP_TURBO);
  bgr.setTo(cv::Scalar(0, 0, 0), depth_m <= 0);
  return bgr;
}

void ClickerOptions::Check() const {
  if (!(scale >= 0.25 && scale <= 4))
    throw std::invalid_argument("ClickerOptions.scale must be in [0.25, 4]");
  if (panel_height_px < 100)
    throw std::invalid_argument("ClickerOptions.panel_height_px must be >= 100");
  if (frame_step < 1) throw std::invalid_argument("ClickerOptions.frame_step must be >= 1");
  fit.Check();
}

CalibrationClicker::CalibrationClicker(const ClickerOptions& options,
                                       const std::vector<PixelPair>& initial)
    : options_(options) {
  options_.Check();
  for (const PixelPair& p : initial) pairs_.push_back({p, -1});
  Refit();
}

double NearestDepth(const cv::Mat& depth_m, const cv::Point2d& pt) {
  if (depth_m.empty()) return 0;
  const int u = static_cast<int>(std::lround(pt.x)), v = static_cast<int>(std::lround(pt.y));
  float nearest = 0;
  for (int r = std::max(0, v - 1); r <= std::min(depth_m.rows - 1, v + 1); ++r)
    for (int c = std::max(0, u - 1); c <= std::min(depth_m.cols - 1, u + 1); ++c) {
      const float d = depth_m.at<float>(r, c);
      if (d > 0 && (nearest == 0 || d < nearest)) nearest = d;
    }
  return nearest;
}

void CalibrationClicker::SetFrame(const Frame& frame) {
  vis_bgr_ = frame.bgr.clone();
  depth_bgr_ = ColorizeDepth(frame.depth_m);
  depth_m_ = frame.depth_m.clone();
  frame_index_ = frame.index;
  timestamp_ = frame.timestamp;
  pending_.reset();
}

cv::Size CalibrationClicker::VisSize() const {
  return vis_bgr_.empty() ? cv::Size(640, 480) : vis_bgr_.size();
}
cv::Size CalibrationClicker::IrSize() const {
  return depth_bgr_.empty() ? cv::Size(640, 480) : depth_bgr_.size();
}

cv::Size CalibrationClicker::CanvasSize() const {
  const double s = options_.scale;
  const int w = cvRound(VisSize().width * s) + cvRound(IrSize().width * s);
  const int h = cvRound(std::max(VisSize().height, IrSize().height) * s);
  return {w, h + options_.panel_height_px};
}

cv::Point2d CalibrationClicker::ToCanvas(const cv::Point2d& pt, bool ir) const {
  const double s = options_.scale;
  const double x0 = ir ? cvRound(VisSize().width * s) : 0;
  // Pixel centres: image pixel i covers canvas [i*s, (i+1)*s).
  return {x0 + (pt.x + 0.5) * s - 0.5, (pt.y + 0.5) * s - 0.5};
}

std::optional<CalibrationClicker::Pending> CalibrationClicker::FromCanvas(int x, int y) const {
  const double s = options_.scale;
  const int vis_w = cvRound(VisSize().width * s);
  const bool ir = x >= vis_w;
  const cv::Size size = ir ? IrSize() : VisSize();
  const cv::Point2d pt(((ir ? x - vis_w : x) + 0.5) / s - 0.5, (y + 0.5) / s - 0.5);
  if (x < 0 || y < 0 || pt.x < -0.5 || pt.y < -0.5 || pt.x > size.width - 0.5 ||
      pt.y > size.height - 0.5)
    return std::nullopt;
  return Pending{pt, ir};
}

void CalibrationClicker::Click(int x, int y) {
  const std::optional<Pending> at = FromCanvas(x, y);
  if (!at) return;
  quit_asked_ = false;
  if (!pending_ || pending_->ir == at->ir) {
    pending_ = at;  // first point, or a corrected one in the same image
    Log(std::string("point in the ") + (at->ir ? "depth" : "colour") + " image at " +
        Format("%.1f", at->pt.x) + "," + Format("%.1f", at->pt.y));
    return;
  }
  const Pending& vis = at->ir ? *pending_ : *at;
  const Pending& ir = at->ir ? *at : *pending_;
  pairs_.push_back(
      {{vis.pt.x, vis.pt.y, ir.pt.x, ir.pt.y, NearestDepth(depth_m_, ir.pt)}, frame_index_});
  pending_.reset();
  dirty_ = true;
  Refit();
  const PixelPair& p = pairs_.back().pair;
  Log("pair " + std::to_string(pairs_.size()) + ": " + Format("%.1f", p.u_vis) + "," +
      Format("%.1f", p.v_vis) + " -> " + Format("%.1f", p.u_ir) + "," + Format("%.1f", p.v_ir) +
      "; " + fit_.Brief());
}

void CalibrationClicker::Hover(int x, int y) { hover_ = {x, y}; }

void CalibrationClicker::Log(const std::string& line) { log_.push_back(line); }

std::vector<std::string> CalibrationClicker::TakeLog() { return std::exchange(log_, {}); }

ClickerAction CalibrationClicker::Key(int key) {
  if (key < 0) return ClickerAction::kNone;
  const int k = key & 0xFFFF;
  const bool quit = k == 'q' || k == 'Q' || k == 27;
  if (!quit) quit_asked_ = false;
  switch (k) {
    case 'u':
    case 'U':
    case 8:
    case 127:
      if (pending_) {
        pending_.reset();
        Log("undo: pending point dropped");
      } else if (!pairs_.empty()) {
        pairs_.pop_back();
        dirty_ = true;
        Refit();
        Log("undo: pair " + std::to_string(pairs_.size() + 1) + " removed; " + fit_.Brief());
      } else {
        Log("undo: nothing to undo");
      }
      return ClickerAction::kNone;
    case 'r':
    case 'R':
      options_.fit.robust = !options_.fit.robust;
      Refit();
      Log(std::string("robust fit ") + (options_.fit.robust ? "on" : "off") + "; " + fit_.Brief());
      return ClickerAction::kNone;
    case 'n':
    case 'N':
      return ClickerAction::kNextFrame;
    case 'p':
    case 'P':
      return ClickerAction::kPrevFrame;
    case 's':
    case 'S':
      return ClickerAction::kSave;
    default:
      break;
  }
  if (!quit) return ClickerAction::kNone;
  if (!dirty_ || quit_asked_) {
    quit_asked_ = false;
    return ClickerAction::kQuit;
  }
  quit_asked_ = true;
  message_ = "unsaved pairs: press s to save, or q again to quit without saving";
  Log(message_);
  return ClickerAction::kNone;
}

std::vector<PixelPair> CalibrationClicker::Pairs() const {
  std::vector<PixelPair> out;
  out.reserve(pairs_.size());
  for (const ClickedPair& p : pairs_) out.push_back(p.pair);
  return out;
}

void CalibrationClicker::Refit() { fit_ = FitMapping(options_.fit, Pairs()); }

cv::Mat CalibrationClicker::Render() const {
  const cv::Size size = CanvasSize();
  const double s = options_.scale;
  cv::Mat canvas(size, CV_8UC3, cv::Scalar(40, 40, 40));
  const auto place = [&](const cv::Mat& img, bool ir, const char* label) {
    const cv::Point2d origin = ToCanvas({-0.5, -0.5}, ir) + cv::Point2d(0.5, 0.5);
    const cv::Size sz = ir ? IrSize() : VisSize();
    const cv::Rect roi(cvRound(origin.x), 0, cvRound(sz.width * s), cvRound(sz.height * s));
    if (!img.empty())
      cv::resize(img, canvas(roi), roi.size(), 0, 0, s < 1 ? cv::INTER_AREA : cv::INTER_NEAREST);
    Text(canvas, label, {roi.x + 6, 16}, kText);
  };
  place(vis_bgr_, false, vis_bgr_.empty() ? "colour (no frame)" : "colour");
  place(depth_bgr_, true, "depth (colour-mapped)");
  const int image_h = size.height - options_.panel_height_px;
  const cv::Mat images = canvas(cv::Rect(0, 0, size.width, image_h)).clone();  // for the magnifier
  cv::line(canvas, cv::Point(cvRound(VisSize().width * s), 0),
           cv::Point(cvRound(VisSize().width * s), image_h - 1), cv::Scalar(255, 255, 255), 1);

  // The fitted mapping (A-D and the disparity term) as a calibration, for the camera model.
  std::optional<Calibration> mapping;
  if (fit_.success) mapping = ApplyMappingFit(Calibration{}, fit_, "");
  for (size_t i = 0; i < pairs_.size(); ++i) {
    if (pairs_[i].frame != frame_index_ || frame_index_ < 0) continue;
    const PixelPair& p = pairs_[i].pair;
    const bool bad =
        fit_.success && (fit_.outlier[i] || fit_.residual_px[i] > options_.fit.outlier_px);
    const cv::Scalar colour = bad ? kBad : kGood;
    const std::string label = std::to_string(i + 1);
    Marker(canvas, ToCanvas({p.u_vis, p.v_vis}, false), colour, label);
    const cv::Point2d ir = ToCanvas({p.u_ir, p.v_ir}, true);
    Marker(canvas, ir, colour, label);
    if (mapping) {  // where the fit puts the twin, and the residual as a line
      const Eigen::Vector2d at =
          ColorToIr(*mapping, {p.u_vis, p.v_vis}, p.z_ir_m > 0 ? p.z_ir_m : kInfiniteDepth);
      const cv::Point2d pred = ToCanvas({at.x(), at.y()}, true);
      cv::line(canvas, ir, pred, kPredicted, 1, cv::LINE_AA);
      Cross(canvas, pred, kPredicted);
    }
  }
  if (pending_) {
    Marker(canvas, ToCanvas(pending_->pt, pending_->ir), kPending, "?");
    if (mapping) {
      // The twin through the fitted mapping, at the depth the depth image gives.
      const Eigen::Vector2d q(pending_->pt.x, pending_->pt.y);
      std::optional<Eigen::Vector2d> twin;
      if (pending_->ir) {
        const double z = NearestDepth(depth_m_, pending_->pt);
        twin = IrToColor(*mapping, q, z > 0 ? z : kInfiniteDepth);
      } else {
        twin = depth_m_.empty() ? ColorToIr(*mapping, q) : FindIrPixel(*mapping, depth_m_, q);
      }
      if (twin) Cross(canvas, ToCanvas({twin->x(), twin->y()}, !pending_->ir), kPending);
    }
  }
  DrawPanel(canvas);
  DrawMagnifier(canvas, images);
  return canvas;
}

void CalibrationClicker::DrawPanel(cv::Mat& canvas) const {
  const int y0 = canvas.rows - options_.panel_height_px;
  const int text_right = canvas.cols - (2 * kMagnifierHalf + 1) * kMagnifierZoom - 16;
  const int line_h = 19;
  int y = y0 + 17;
  const std::string step = std::to_string(options_.frame_step);
  // The long wording where it fits (1280 px canvas), a short one on narrow canvases.
  const auto pick = [&](const std::string& full, const std::string& brief) {
    return TextWidth(full) <= text_right - 8 ? full : brief;
  };
  const std::string robust = options_.fit.robust ? "(on)" : "(off)";
  Text(canvas,
       pick("keys: u undo | n/p frame +/-" + step + " | r robust fit " + robust +
                " | s save | q quit    (magenta x: where the fit puts the twin)",
            "u undo | n/p frame +/-" + step + " | r robust " + robust + " | s save | q quit"),
       {8, y}, kText);
  y += line_h;
  const std::string frame = frame_index_ < 0 ? std::string("-") : std::to_string(frame_index_);
  const std::string count = std::to_string(pairs_.size());
  std::string state;
  if (!pending_) {
    state = pick("frame " + frame + "  pairs " + count +
                     "  click a sharp point (a corner ~3 m away) in either image",
                 "frame " + frame + ", " + count + " pairs: click a corner in either image");
  } else {
    const std::string other = pending_->ir ? "colour" : "depth";
    state =
        pick("frame " + frame + "  pairs " + count + "  now click the same point in the " + other +
                 " image (u: cancel)",
             "frame " + frame + ", " + count + " pairs: now click it in the " + other + " image");
  }
  Text(canvas, state, {8, y}, pending_ ? kPending : kText);
  y += line_h;
  if (fit_.success) {
    const std::string abcd = "A=" + Format("%.4f", fit_.A) + " B=" + Format("%.2f", fit_.B) +
                             " C=" + Format("%.4f", fit_.C) + " D=" + Format("%.2f", fit_.D);
    const std::string rms = Format("%.2f", fit_.rms_px);
    const int outliers = fit_.num_pairs - fit_.num_inliers;
    const std::string f =
        outliers == 0
            ? pick("fit: " + abcd + "  RMS " + rms + " px", abcd + " RMS " + rms)
            : pick("fit: " + abcd + "  RMS " + rms + " px  (robust: " + std::to_string(outliers) +
                       " outlier(s) set aside)",
                   abcd + " RMS " + rms + ", " + std::to_string(outliers) + " out");
    Text(canvas, f, {8, y}, kGood);
  } else {
    Text(canvas, "fit: " + fit_.reason, {8, y}, kBad);
  }
  y += line_h;
  // Residuals, newest last; as many lines as fit above the message line.
  std::vector<std::string> tokens;
  tokens.reserve(pairs_.size());
  for (size_t i = 0; i < pairs_.size(); ++i)
    tokens.push_back("#" + std::to_string(i + 1) + " " +
                     (fit_.success ? Format("%.1f", fit_.residual_px[i]) : std::string("-")) +
                     (fit_.success && fit_.outlier[i] ? "!" : ""));
  const int max_lines = std::max(1, (canvas.rows - 6 - line_h - y) / line_h + 1);
  std::vector<std::vector<size_t>> lines(1);
  int x = 0;
  for (size_t i = 0; i < tokens.size(); ++i) {
    const int w = TextWidth(tokens[i]) + 12;
    if (x + w > text_right - 8 - 90 && !lines.back().empty()) lines.emplace_back(), x = 0;
    lines.back().push_back(i);
    x += w;
  }
  const size_t first = lines.size() > static_cast<size_t>(max_lines) ? lines.size() - max_lines : 0;
  for (size_t l = first; l < lines.size(); ++l) {
    int xx = 8;
    Text(canvas, l == 0 ? "residual px:" : (l == first ? "... " : ""), {xx, y}, kDim);
    xx += 90;
    for (size_t i : lines[l]) {
      const bool bad =
          fit_.success && (fit_.outlier[i] || fit_.residual_px[i] > options_.fit.outlier_px);
      Text(canvas, tokens[i], {xx, y}, bad ? kBad : (fit_.success ? kGood : kDim));
      xx += TextWidth(tokens[i]) + 12;
    }
    y += line_h;
  }
  if (!message_.empty()) Text(canvas, message_, {8, canvas.rows - 8}, kMessage);
}

void CalibrationClicker::DrawMagnifier(cv::Mat& canvas, const cv::Mat& images) const {
  const int side = (2 * kMagnifierHalf + 1) * kMagnifierZoom;
  const cv::Rect box(canvas.cols - side - 8,
                     canvas.rows - options_.panel_height_px + (options_.panel_height_px - side) / 2,
                     side, side);
  cv::rectangle(canvas, box, cv::Scalar(90, 90, 90), 1);
  if (hover_.x < 0 || hover_.y < 0 || hover_.x >= images.cols || hover_.y >= images.rows) {
    Text(canvas, "zoom", {box.x + side / 2 - 18, box.y + side / 2 + 5}, kDim);
    return;
  }
  cv::Mat patch(2 * kMagnifierHalf + 1, 2 * kMagnifierHalf + 1, CV_8UC3, cv::Scalar(0, 0, 0));
  for (int r = 0; r < patch.rows; ++r)
    for (int c = 0; c < patch.cols; ++c) {
      const cv::Point q(hover_.x + c - kMagnifierHalf, hover_.y + r - kMagnifierHalf);
      if (q.x >= 0 && q.y >= 0 && q.x < images.cols && q.y < images.rows)
        patch.at<cv::Vec3b>(r, c) = images.at<cv::Vec3b>(q);
    }
  cv::resize(patch, canvas(box), box.size(), 0, 0, cv::INTER_NEAREST);
  const int c0 = box.x + kMagnifierHalf * kMagnifierZoom,
            r0 = box.y + kMagnifierHalf * kMagnifierZoom;
  cv::rectangle(canvas, cv::Rect(c0, r0, kMagnifierZoom, kMagnifierZoom), kPending, 1);
}

}  // namespace rgbdvo
