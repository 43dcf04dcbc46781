#pragma once
// Live frames from a Kinect v1 through libfreenect's asynchronous C API (or from a recording
// replayed by Debian's `fakenect`, which stands in for the same library).
//
// A thread runs freenect_process_events; the video (RGB 640x480) and depth (raw 11-bit)
// callbacks copy each frame, optionally record it (fakenect layout), and pair colour with the
// nearest depth frame (stream_pairer.hpp). Pairs go through a bounded queue to Next(), which
// converts them (RGB -> BGR, raw disparity -> metres, kinect_depth.hpp). A second thread writes
// the recording, fed through a small queue that waits rather than drops. When the consumer is
// slower than the camera, the queue drops the oldest pair ("newest wins") and counts it, so
// the odometry stays near real time and memory stays bounded; the recording keeps every frame.

#include <Eigen/Core>
#include <atomic>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "rgbdvo/capture/fakenect_recorder.hpp"
#include "rgbdvo/sources/frame_source.hpp"
#include "rgbdvo/sources/stream_pairer.hpp"
#include "rgbdvo/util/bounded_queue.hpp"

// libfreenect's own (reserved) struct names, declared here to keep its header out of ours.
struct _freenect_context;  // NOLINT(bugprone-reserved-identifier)
struct _freenect_device;   // NOLINT(bugprone-reserved-identifier)

namespace rgbdvo {

struct KinectSourceOptions {
  int device = 0;                       // libfreenect device index
  int max_frames = 0;                   // stop after this many colour-depth pairs, 0 = no limit
  double max_seconds = 0;               // stop after this long, s, 0 = no limit
  int queue_capacity = 4;               // pairs waiting for the consumer (1.5 MB each)
  bool drop_when_behind = true;         // false: wait for the consumer instead of dropping (for
                                        // replays; a live Kinect would lose USB packets meanwhile)
  double max_time_diff_s = 0.034;       // colour-depth pairing window, s (as FakenectSourceOptions)
  Pairing pairing = Pairing::kNearest;  // stream_pairer.hpp; kOneToOne uses each depth frame once
  std::string record_folder;            // "" = do not record
  bool record_accel = true;             // also record accelerometer entries (a-*.dump)
  // Give each frame the accelerometer's latest reading (Frame::gravity_in_cam), read after each
  // depth frame.
  bool read_accel = false;
  double stall_timeout_s = 5.0;             // no frame for this long: treat the device as lost, s
  const std::atomic<bool>* stop = nullptr;  // stop when it becomes true (e.g. set on SIGINT)
  void Check() const;
};

enum class CaptureEnd {
  kRunning,
  kFrameLimit,
  kTimeLimit,
  kStopRequested,
  kEndOfData,
  kDeviceLost,
  kError
};

struct CaptureStats {
  int color_frames = 0, depth_frames = 0;  // received from the device
  int pairs = 0;                           // colour-depth pairs formed
  int delivered = 0;                       // pairs handed to the consumer
  int dropped = 0;                         // pairs dropped because the consumer was behind
  int unpaired = 0;                        // colour frames without a depth frame in the window
  int recorded = 0;                        // entries written to the recording
  CaptureEnd end = CaptureEnd::kRunning;
  std::string end_reason;  // one phrase: "end of the fakenect recording", "device lost (...)"
  std::string Brief() const;
};

class KinectSource : public FrameSource {
 public:
  // Opens the device and starts streaming. Throws std::runtime_error with a clear message
  // when libfreenect cannot start, there is no Kinect (or not that index), the device cannot
  // be opened (permissions), the modes are refused, or the recording folder is not new.
  explicit KinectSource(const KinectSourceOptions& options);
  ~KinectSource() override;  // stops streaming, closes the device and the recording
  KinectSource(const KinectSource&) = delete;
  KinectSource& operator=(const KinectSource&) = delete;

  // The next pair; nullopt once the stream has ended (limit, stop, end of data, device lost)
  // and every queued pair was delivered. Rethrows a recording failure.
  std::optional<Frame> Next() override;
  std::string Describe() const override;
  CaptureStats stats() const;

 private:
  struct LiveFrame {
    int64_t host_us = 0;  // the device time on the host's clock (KinectClock::OnHost)
    cv::Mat data;
  };
  struct RawPair {
    int64_t color_us = 0, depth_us = 0;             // capture times (DeviceTimeOnHostClock)
    cv::Mat rgb;                                    // CV_8UC3, RGB order
    cv::Mat raw;                                    // CV_16UC1 raw disparity
    std::optional<Eigen::Vector3d> gravity_in_cam;  // with read_accel
  };
  static void OnVideo(_freenect_device* dev, void* data, uint32_t timestamp);
  static void OnDepth(_freenect_device* dev, void* data, uint32_t timestamp);
  // A file for the recording thread (so slow disks do not delay the callbacks' timestamps).
  struct RecordJob {
    char type = 0;
    int64_t t_us = 0;
    uint32_t device_ts = 0;
    cv::Mat data;  // image, or the accelerometer state's bytes as one row
  };
  void HandleFrame(bool is_depth, const void* data, uint32_t timestamp);
  // After events with a depth frame: records the accelerometer state and keeps its reading.
  void ReadAccelerometer();
  void Record(const RecordJob& job);
  void RecordLoop();
  void SetError(std::exception_ptr error);
  void Deliver(std::vector<StampedPair<LiveFrame>> pairs);
  void Loop();
  void End(CaptureEnd end, const std::string& reason);

  KinectSourceOptions options_;
  _freenect_context* ctx_ = nullptr;
  _freenect_device* dev_ = nullptr;
  int width_ = 640, height_ = 480;
  std::unique_ptr<FakenectRecorder> recorder_;
  StreamPairer<LiveFrame> pairer_;
  KinectClock clock_;
  BoundedQueue<RawPair> queue_;
  BoundedQueue<RecordJob> record_queue_;
  std::thread thread_, record_thread_;
  std::atomic<bool> quit_{false};
  bool depth_this_call_ = false;
  uint32_t last_depth_ts_ = 0;
  int64_t last_frame_us_ = 0;
  bool accel_ok_ = true;
  std::optional<Eigen::Vector3d> gravity_in_cam_;  // the latest reading (device thread)
  std::vector<StampedPair<LiveFrame>> pending_;    // pairs of the events being processed
  mutable std::mutex mutex_;                       // guards stats_ and error_
  CaptureStats stats_;
  std::exception_ptr error_;
};

// Host wall-clock time in microseconds (the time stamped on live frames and recordings).
int64_t WallClockMicros();

}  // namespace rgbdvo
