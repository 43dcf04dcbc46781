#include "rgbdvo/tracking_gaps.hpp"

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

}  // namespace

std::optional<std::string> TrackingGaps::Add(const FrameResult& r) {
  if (!HasEstimate(r.status)) {
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
      return "tracking failed at " + At(r) + ": " + r.reason + "; " +
             (r.status == FrameStatus::kRejected ? "holding the last pose"
                                                 : "reporting predicted poses");
    if (r.status == FrameStatus::kLost)
      return "tracking lost at " + At(r) + " after " + std::to_string(run_frames_) +
             " frames without an estimate: restarting from this frame";
    return std::nullopt;
  }
  if (!open_) return std::nullopt;
  open_ = false;
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(2);
  s << "tracking resumed at " << At(r) << " after " << run_frames_ << " frames ("
    << last_time_ - run_start_time_ << " s) without an estimate";
  return s.str();
}

std::optional<std::string> TrackingGaps::Finish() const {
  if (!open_) return std::nullopt;
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(2);
  s << "the sequence ends in a gap of " << run_frames_ << " frames ("
    << last_time_ - run_start_time_ << " s) without an estimate";
  return s.str();
}

}  // namespace rgbdvo
