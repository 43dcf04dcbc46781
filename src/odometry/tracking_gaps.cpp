#include "rgbdvo/odometry/tracking_gaps.hpp"

#include <algorithm>
#include <sstream>

namespace rgbdvo {
namespace {

std::string At(const FrameResult& r) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(3);
  s << "t=" << r.timestamp << " (frame " << r.frame << ")";
  return s.str();
}

std::string Fallback(FrameStatus status) {
  switch (status) {
    case FrameStatus::kDepth:
      return "aligning depth images instead";
    case FrameStatus::kRejected:
      return "holding the last pose";
    case FrameStatus::kLost:
      return "restarting from this frame";
    default:
      return "reporting predicted poses";
  }
}

std::string Frames(int n) { return std::to_string(n) + (n == 1 ? " frame" : " frames"); }

std::string Seconds(double s) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(2);
  out << s << " s";
  return out.str();
}

}  // namespace

std::optional<std::string> TrackingGaps::Add(const FrameResult& r) {
  if (HasFeatureEstimate(r.status)) {
    const std::optional<double> before = estimate_time_;
    estimate_time_ = r.timestamp;
    if (!open_) return std::nullopt;
    open_ = false;
    const double seconds = r.timestamp - *before;
    const std::string timed =
        gap_at_start_ ? " since the first frame)" : " between feature estimates)";
    gap_at_start_ = false;
    longest_seconds_ = std::max(longest_seconds_, seconds);
    return "tracking resumed at " + At(r) + " after " + Frames(run_frames_) +
           " without a feature estimate (" + Seconds(seconds) + timed;
  }
  if (!open_) {
    open_ = true;
    run_frames_ = 0;
    ++gaps_;
  }
  if (!estimate_time_) {  // a gap at the start: timed from its first frame
    estimate_time_ = r.timestamp;
    gap_at_start_ = true;
  }
  ++run_frames_;
  last_time_ = r.timestamp;
  longest_frames_ = std::max(longest_frames_, run_frames_);
  longest_seconds_ = std::max(longest_seconds_, last_time_ - *estimate_time_);
  if (run_frames_ == 1)
    return "tracking failed at " + At(r) + ": " + r.reason + "; " + Fallback(r.status);
  if (r.status == FrameStatus::kLost)
    return "tracking lost at " + At(r) + " after " + Frames(run_frames_) +
           " without a feature estimate: restarting from this frame";
  return std::nullopt;
}

std::optional<std::string> TrackingGaps::Finish() const {
  if (!open_) return std::nullopt;
  return "the sequence ends in a gap of " + Frames(run_frames_) + " without a feature estimate (" +
         Seconds(last_time_ - *estimate_time_) +
         (gap_at_start_ ? " since the first frame)" : " since the last one)");
}

}  // namespace rgbdvo
