#include "rgbdvo/run.hpp"

#include <chrono>
#include <sstream>

namespace rgbdvo {
namespace {

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

std::string RunSummary::Brief() const {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(1);
  s << frames << " frames, " << accepted << " accepted, " << rejected << " rejected, mean inliers "
    << mean_inliers << ", " << (seconds > 0 ? frames / seconds : 0.0) << " fps";
  return s.str();
}

RunSummary RunOdometry(FrameSource& source, Odometry& odometry,
                       const std::vector<TrajectoryWriter*>& writers,
                       const std::function<void(const FrameResult&)>& on_frame) {
  RunSummary summary;
  const Clock::time_point start = Clock::now();
  double inlier_sum = 0;
  for (;;) {
    Clock::time_point t0 = Clock::now();
    std::optional<Frame> frame = source.Next();
    summary.decode_seconds += Since(t0);
    if (!frame) break;
    const FrameResult result = odometry.Process(*frame);
    t0 = Clock::now();
    for (TrajectoryWriter* w : writers) w->Write(result);
    summary.write_seconds += Since(t0);

    ++summary.frames;
    if (result.status == FrameStatus::kFirst || result.status == FrameStatus::kAccepted)
      ++summary.accepted;
    else
      ++summary.rejected;
    if (result.status != FrameStatus::kFirst) inlier_sum += result.inliers;
    summary.stage_seconds.features += result.times.features;
    summary.stage_seconds.matching += result.times.matching;
    summary.stage_seconds.lifting += result.times.lifting;
    summary.stage_seconds.ransac += result.times.ransac;
    summary.seconds = Since(start);
    if (on_frame) on_frame(result);
  }
  summary.mean_inliers = summary.frames > 1 ? inlier_sum / (summary.frames - 1) : 0.0;
  summary.seconds = Since(start);
  return summary;
}

}  // namespace rgbdvo
