// rgbdvo_peer_opencv: OpenCV 4.6 cv::rgbd odometries (opencv_contrib rgbd module), frame to
// frame, default settings. Benchmark only.
#include <limits>
#include <map>
#include <opencv2/imgproc.hpp>
#include <opencv2/rgbd.hpp>

#include "peer_runner.hpp"

namespace rgbdvo::bench {
namespace {

// Method name on the command line -> cv::rgbd::Odometry::create() name.
const std::map<std::string, std::string> kMethods = {{"Rgbd", "RgbdOdometry"},
                                                     {"ICP", "ICPOdometry"},
                                                     {"RgbdICP", "RgbdICPOdometry"},
                                                     {"FastICP", "FastICPOdometry"}};

class OpenCvPeer : public PeerOdometry {
 public:
  OpenCvPeer(const std::string& method, const Calibration& calib) : method_(method) {
    odometry_ = cv::rgbd::Odometry::create(kMethods.at(method));
    if (odometry_.empty()) throw std::runtime_error("OpenCV has no odometry " + method);
    const cv::Mat K =
        (cv::Mat_<double>(3, 3) << calib.fx, 0, calib.cx, 0, calib.fy, calib.cy, 0, 0, 1);
    odometry_->setCameraMatrix(K);
  }

  // Odometry::compute(src, dst, Rt) returns Rt with p_dst = Rt * p_src (opencv2/rgbd/depth.hpp),
  // so with src = current and dst = previous frame, Rt = prev_from_cur (as OpenCV's
  // samples/odometry_evaluation.cpp chains it: pose_cur = pose_prev * Rt).
  bool Track(const Frame& cur, Rigid3d* prev_from_cur) override {
    cv::Ptr<cv::rgbd::OdometryFrame> frame = cv::makePtr<cv::rgbd::OdometryFrame>();
    cv::cvtColor(cur.bgr, frame->image, cv::COLOR_BGR2GRAY);
    frame->depth = cur.depth_m.clone();  // CV_32F metres; no reading -> NaN (OpenCV samples)
    frame->depth.setTo(std::numeric_limits<float>::quiet_NaN(), cur.depth_m <= 0);
    // Prepare each frame once for both roles (source now, destination next time).
    odometry_->prepareFrameCache(frame, cv::rgbd::OdometryFrame::CACHE_ALL);
    bool ok = true;
    if (prev_) {
      cv::Mat Rt;
      ok = odometry_->compute(frame, prev_, Rt);
      if (ok) {
        Eigen::Matrix4d M;
        for (int r = 0; r < 4; ++r) {
          for (int c = 0; c < 4; ++c) M(r, c) = Rt.at<double>(r, c);
        }
        *prev_from_cur = RigidFromMatrix(M);
      }
    }
    prev_ = frame;
    return ok;
  }

  std::string Describe() const override {
    return "OpenCV " CV_VERSION " cv::rgbd::" + kMethods.at(method_) +
           ", default settings, frame to frame";
  }

 private:
  std::string method_;
  cv::Ptr<cv::rgbd::Odometry> odometry_;
  cv::Ptr<cv::rgbd::OdometryFrame> prev_;
};

}  // namespace
}  // namespace rgbdvo::bench

int main(int argc, char** argv) {
  using namespace rgbdvo::bench;
  std::vector<std::string> methods;
  for (const auto& m : kMethods) methods.push_back(m.first);
  return RunPeerMain(argc, argv, "rgbdvo_peer_opencv", methods,
                     [](const std::string& method, const rgbdvo::Calibration& calib) {
                       return std::make_unique<OpenCvPeer>(method, calib);
                     });
}
