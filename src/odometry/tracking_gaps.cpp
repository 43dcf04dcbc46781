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

}  // namespace

std::optional<std::string> TrackingGaps::Add(const FrameResult& r) {
  if (!HasFeatureEstimate(r.status)) {
    if (!open_) {
      open_ = true;
      run_frames_ = 0;
      run_start_time_ = r.timestamp;
      ++gaps_;
    }
    ++run_frames_;
    last_time_ = r.timestamp;
    longest_frames_ = std::max(longest_frames_, run_frames_);
    longest_seconds_ = std::max(longest_seconds_, last_time_ - run_start_time_);
    if (run_frames_ == 1)
      return "tracking failed at " + At(r) + ": " + r.reason + "; " + Fallback(r.status);
    if (r.status == FrameStatus::kLost)
      return "tracking lost at " + At(r) + " after " + std::to_string(run_frames_) +
             " frames without a feature estimate: restarting from this frame";
    return std::nullopt;
  }
  if (!open_) return std::nullopt;
  open_ = false;
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(2);
  s << "tracking resumed at " << At(r) << " after " << run_frames_ << " frames ("
    << last_time_ - run_start_time_ << " s) without a feature estimate";
  return s.str();
}

std::optional<std::string> TrackingGaps::Finish() const {
  if (!open_) return std::nullopt;
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(2);
  s << "the sequence ends in a gap of " << run_frames_ << " frames ("
    << last_time_ - run_start_time_ << " s) without a feature estimate";
  return s.str();
}

}  // namespace rgbdvo
