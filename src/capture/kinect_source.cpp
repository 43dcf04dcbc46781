#include "rgbdvo/capture/kinect_source.hpp"

#include <libfreenect.h>
#include <sys/time.h>

#include <cmath>
#include <cstdlib>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "rgbdvo/sensor/kinect_accelerometer.hpp"
#include "rgbdvo/sensor/kinect_depth.hpp"

namespace rgbdvo {
namespace {

constexpr int kLibusbErrorInterrupted = -10;  // LIBUSB_ERROR_INTERRUPTED: a signal, not an error

bool UnderFakenect() { return std::getenv("FAKENECT_PATH") != nullptr; }

const char* kPermissionHint =
    "on Debian the libfreenect package's udev rules give the 'plugdev' group access: add "
    "yourself (sudo adduser $USER plugdev), log in again and replug the Kinect";

}  // namespace

int64_t WallClockMicros() {
  timeval tv;
  gettimeofday(&tv, nullptr);
  return static_cast<int64_t>(tv.tv_sec) * 1000000 + tv.tv_usec;
}

void KinectSourceOptions::Check() const {
  if (device < 0) throw std::invalid_argument("KinectSourceOptions.device must be >= 0");
  if (max_frames < 0) throw std::invalid_argument("KinectSourceOptions.max_frames must be >= 0");
  if (!(max_seconds >= 0))
    throw std::invalid_argument("KinectSourceOptions.max_seconds must be >= 0");
  if (queue_capacity < 1)
    throw std::invalid_argument("KinectSourceOptions.queue_capacity must be >= 1");
  if (!(max_time_diff_s > 0))
    throw std::invalid_argument("KinectSourceOptions.max_time_diff_s must be > 0");
  if (!(stall_timeout_s > 0))
    throw std::invalid_argument("KinectSourceOptions.stall_timeout_s must be > 0");
}

std::string CaptureStats::Brief() const {
  std::ostringstream s;
  s << color_frames << " colour and " << depth_frames << " depth frames received, " << pairs
    << " pairs, " << delivered << " processed, " << dropped << " dropped (odometry behind), "
    << unpaired << " colour frames without depth";
  if (recorded > 0) s << ", " << recorded << " entries recorded";
  if (!end_reason.empty()) s << "; stopped: " << end_reason;
  return s.str();
}

KinectSource::KinectSource(const KinectSourceOptions& options)
    : options_(options),
      pairer_(std::llround(options.max_time_diff_s * 1e6), options.pairing),
      queue_(static_cast<size_t>(std::max(1, options.queue_capacity))),
      record_queue_(8) {
  options_.Check();
  if (freenect_init(&ctx_, nullptr) < 0) {
    ctx_ = nullptr;
    throw std::runtime_error(
        "libfreenect: cannot initialise (no USB access?); no Kinect can be opened");
  }
  // Everything below tears the context down on failure.
  auto fail = [this](const std::string& message) {
    if (dev_) freenect_close_device(dev_);
    freenect_shutdown(ctx_);
    dev_ = nullptr;
    ctx_ = nullptr;
    throw std::runtime_error(message);
  };
  freenect_set_log_level(ctx_, FREENECT_LOG_FATAL);
  freenect_select_subdevices(
      ctx_, static_cast<freenect_device_flags>(
                FREENECT_DEVICE_CAMERA |
                (options_.record_accel || options_.read_accel ? FREENECT_DEVICE_MOTOR : 0)));
  const int devices = freenect_num_devices(ctx_);
  if (devices <= 0)
    fail(
        "no Kinect v1 found (libfreenect sees no device): check that it is plugged in and "
        "powered by its own supply; " +
        std::string(kPermissionHint));
  if (options_.device >= devices)
    fail("no Kinect with index " + std::to_string(options_.device) + " (" +
         std::to_string(devices) + " found, indices start at 0)");
  if (freenect_open_device(ctx_, &dev_, options_.device) < 0) {
    dev_ = nullptr;
    fail("cannot open Kinect " + std::to_string(options_.device) +
         " (in use, or no permission: " + kPermissionHint + ")");
  }
  const freenect_frame_mode video =
      freenect_find_video_mode(FREENECT_RESOLUTION_MEDIUM, FREENECT_VIDEO_RGB);
  const freenect_frame_mode depth =
      freenect_find_depth_mode(FREENECT_RESOLUTION_MEDIUM, FREENECT_DEPTH_11BIT);
  if (!video.is_valid || freenect_set_video_mode(dev_, video) < 0)
    fail("Kinect " + std::to_string(options_.device) + ": RGB 640x480 video mode refused");
  if (!depth.is_valid || freenect_set_depth_mode(dev_, depth) < 0)
    fail("Kinect " + std::to_string(options_.device) + ": 11-bit depth mode refused");
  width_ = video.width;
  height_ = video.height;
  if (depth.width != width_ || depth.height != height_)
    fail("Kinect: depth mode size differs from the video mode size");
  // Only now, so that a missing device leaves no empty recording folder behind.
  if (!options_.record_folder.empty()) {
    try {
      recorder_ = std::make_unique<FakenectRecorder>(options_.record_folder);
    } catch (const std::exception& e) {
      fail(e.what());
    }
  }
  freenect_set_user(dev_, this);
  freenect_set_video_callback(dev_, &KinectSource::OnVideo);
  freenect_set_depth_callback(dev_, &KinectSource::OnDepth);
  if (freenect_start_depth(dev_) < 0 || freenect_start_video(dev_) < 0)
    fail("Kinect " + std::to_string(options_.device) + ": cannot start streaming");
  if (recorder_) record_thread_ = std::thread(&KinectSource::RecordLoop, this);
  thread_ = std::thread(&KinectSource::Loop, this);
}

KinectSource::~KinectSource() {
  quit_ = true;
  queue_.Close();
  if (thread_.joinable()) thread_.join();
}

void KinectSource::OnVideo(_freenect_device* dev, void* data, uint32_t timestamp) {
  static_cast<KinectSource*>(freenect_get_user(dev))->HandleFrame(false, data, timestamp);
}

void KinectSource::OnDepth(_freenect_device* dev, void* data, uint32_t timestamp) {
  static_cast<KinectSource*>(freenect_get_user(dev))->HandleFrame(true, data, timestamp);
}

void KinectSource::HandleFrame(bool is_depth, const void* data, uint32_t timestamp) {
  if (quit_) return;
  const int64_t t = WallClockMicros();
  last_frame_us_ = t;
  try {
    const int64_t device_us = clock_.Micros(timestamp);
    Stamped<LiveFrame> frame{device_us, {clock_.OnHost(device_us, t), {}}};
    cv::Mat& image = frame.value.data;
    if (is_depth) {
      image = cv::Mat(height_, width_, CV_16UC1, const_cast<void*>(data)).clone();
      depth_this_call_ = true;
      last_depth_ts_ = timestamp;
    } else {
      image = cv::Mat(height_, width_, CV_8UC3, const_cast<void*>(data)).clone();
    }
    std::vector<StampedPair<LiveFrame>> pairs =
        is_depth ? pairer_.AddDepth(frame) : pairer_.AddColor(frame);
    int pairs_before;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ++(is_depth ? stats_.depth_frames : stats_.color_frames);
      pairs_before = stats_.pairs;
    }
    // With a frame limit, pairs beyond it are not delivered, and a colour frame arriving once
    // the limit is reached is not recorded, so the recording replays into exactly these pairs.
    if (options_.max_frames > 0 &&
        pairs_before + static_cast<int>(pairs.size()) > options_.max_frames)
      pairs.resize(options_.max_frames - pairs_before);
    const bool limit = options_.max_frames > 0 &&
                       pairs_before + static_cast<int>(pairs.size()) >= options_.max_frames;
    if (recorder_ && !(limit && !is_depth)) Record({is_depth ? 'd' : 'r', t, timestamp, image});
    // Delivered by Loop once the events are processed, with the accelerometer read after them.
    for (StampedPair<LiveFrame>& p : pairs) pending_.push_back(std::move(p));
    if (limit) End(CaptureEnd::kFrameLimit, std::to_string(options_.max_frames) + " frames");
  } catch (...) {
    SetError(std::current_exception());
  }
}

void KinectSource::SetError(std::exception_ptr error) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!error_) error_ = std::move(error);
  quit_ = true;
}

void KinectSource::Record(const RecordJob& job) {
  while (!record_queue_.PushWait(job, std::chrono::milliseconds(100)))
    if (record_queue_.closed()) return;
}

void KinectSource::RecordLoop() {
  bool failed = false;
  while (!record_queue_.closed_and_empty()) {
    std::optional<RecordJob> job = record_queue_.Pop(std::chrono::milliseconds(100));
    if (!job || failed) continue;  // after a failure, drain without writing
    try {
      if (job->type == 'r')
        recorder_->AddColor(job->t_us, job->device_ts, job->data.ptr<uint8_t>(), width_, height_);
      else if (job->type == 'd')
        recorder_->AddDepth(job->t_us, job->device_ts, job->data.ptr<uint16_t>(), width_, height_);
      else
        recorder_->AddAccel(job->t_us, job->device_ts, job->data.ptr(), job->data.total());
    } catch (...) {
      failed = true;
      SetError(std::current_exception());
    }
  }
}

void KinectSource::Deliver(std::vector<StampedPair<LiveFrame>> pairs) {
  for (StampedPair<LiveFrame>& p : pairs) {
    RawPair item{p.color.value.host_us, p.depth.value.host_us, std::move(p.color.value.data),
                 p.depth.value.data, gravity_in_cam_};
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ++stats_.pairs;
    }
    if (options_.drop_when_behind) {
      if (queue_.Push(std::move(item))) {
        std::lock_guard<std::mutex> lock(mutex_);
        ++stats_.dropped;
      }
    } else {
      // Wait for the consumer, even after a stop request, so that every recorded pair is
      // also processed; only a closed queue (the consumer has gone) abandons the pair.
      while (!queue_.PushWait(item, std::chrono::milliseconds(100)))
        if (queue_.closed()) return;
    }
  }
}

void KinectSource::End(CaptureEnd end, const std::string& reason) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (stats_.end == CaptureEnd::kRunning) {
    stats_.end = end;
    stats_.end_reason = reason;
  }
  quit_ = true;
}

void KinectSource::ReadAccelerometer() {
  const bool record_accel = recorder_ && options_.record_accel;
  if (!depth_this_call_ || !(record_accel || options_.read_accel) || !accel_ok_ || quit_) return;
  // The accelerometer state after each depth frame, as fakenect-record does per event.
  if (freenect_update_tilt_state(dev_) < 0) {
    accel_ok_ = false;
  } else if (const freenect_raw_tilt_state* s = freenect_get_tilt_state(dev_)) {
    const cv::Mat bytes(1, sizeof(*s), CV_8UC1, const_cast<freenect_raw_tilt_state*>(s));
    if (record_accel) Record({'a', WallClockMicros(), last_depth_ts_, bytes.clone()});
    const Eigen::Vector3d reading =
        KinectAccelFromCounts(s->accelerometer_x, s->accelerometer_y, s->accelerometer_z);
    // All zero: no state yet (a replay before its first entry).
    if (options_.read_accel && reading.norm() > 0)
      gravity_in_cam_ = ApparentGravityFromKinectAccel(reading);
  }
}

void KinectSource::Loop() {
  const int64_t start = WallClockMicros();
  last_frame_us_ = start;
  while (!quit_) {
    if (options_.stop && *options_.stop) {
      End(CaptureEnd::kStopRequested, "stop requested (Ctrl-C)");
      break;
    }
    const int64_t now = WallClockMicros();
    if (options_.max_seconds > 0 && now - start >= options_.max_seconds * 1e6) {
      End(CaptureEnd::kTimeLimit, std::to_string(options_.max_seconds) + " s");
      break;
    }
    if (now - last_frame_us_ > options_.stall_timeout_s * 1e6) {
      End(CaptureEnd::kDeviceLost,
          "device lost (no frame for " + std::to_string(options_.stall_timeout_s) + " s)");
      break;
    }
    depth_this_call_ = false;
    timeval timeout{0, 100000};
    const int rc = freenect_process_events_timeout(ctx_, &timeout);
    if (rc >= 0) ReadAccelerometer();
    if (!pending_.empty()) {
      Deliver(std::exchange(pending_, {}));
      last_frame_us_ = WallClockMicros();  // waiting for the consumer is not a stalled device
    }
    if (rc == kLibusbErrorInterrupted) continue;
    if (rc < 0) {
      if (UnderFakenect())
        End(CaptureEnd::kEndOfData, "end of the fakenect recording");
      else
        End(CaptureEnd::kDeviceLost,
            "device lost (freenect_process_events returned " + std::to_string(rc) + ")");
      break;
    }
  }
  bool limit_or_error;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    limit_or_error = stats_.end == CaptureEnd::kFrameLimit || error_;
    if (error_ && stats_.end == CaptureEnd::kRunning) {
      stats_.end = CaptureEnd::kError;
      stats_.end_reason = "error";
    }
  }
  // A colour frame still waiting for its next depth frame is decided with the one before,
  // exactly as a replay of the recording ends.
  if (!limit_or_error) Deliver(pairer_.Finish());
  freenect_stop_video(dev_);
  freenect_stop_depth(dev_);
  freenect_close_device(dev_);
  freenect_shutdown(ctx_);
  dev_ = nullptr;
  ctx_ = nullptr;
  record_queue_.Close();  // the recording thread writes what is queued, then ends
  if (record_thread_.joinable()) record_thread_.join();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stats_.unpaired = pairer_.unpaired();
    stats_.recorded = recorder_ ? recorder_->entries() : 0;
  }
  recorder_.reset();  // closes INDEX.txt
  queue_.Close();
}

std::optional<Frame> KinectSource::Next() {
  for (;;) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (error_) std::rethrow_exception(error_);
    }
    std::optional<RawPair> item = queue_.Pop(std::chrono::milliseconds(100));
    if (item) {
      Frame f;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        f.index = stats_.delivered++;
      }
      f.timestamp = static_cast<double>(item->depth_us) * 1e-6;  // the pose's time
      f.color_timestamp = static_cast<double>(item->color_us) * 1e-6;
      f.name = "kinect frame " + std::to_string(f.index);
      f.gravity_in_cam = item->gravity_in_cam;
      cv::cvtColor(item->rgb, f.bgr, cv::COLOR_RGB2BGR);
      f.depth_m = DepthFromKinectRaw(item->raw);
      return f;
    }
    if (queue_.closed_and_empty()) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (error_) std::rethrow_exception(error_);
      return std::nullopt;
    }
  }
}

std::string KinectSource::Describe() const {
  std::ostringstream s;
  s << (UnderFakenect() ? "fakenect replay of " + std::string(std::getenv("FAKENECT_PATH"))
                        : "Kinect v1 #" + std::to_string(options_.device))
    << " via libfreenect: RGB " << width_ << "x" << height_
    << " + raw 11-bit depth, pairing window " << options_.max_time_diff_s
    << " s of the device clock" << (options_.pairing == Pairing::kOneToOne ? " (one to one)" : "")
    << ", queue " << options_.queue_capacity
    << (options_.drop_when_behind ? " (drops the oldest pair when the odometry is behind)"
                                  : " (waits for the odometry, no drops)");
  if (!options_.record_folder.empty()) s << ", recording to " << options_.record_folder;
  return s.str();
}

CaptureStats KinectSource::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stats_;
}

}  // namespace rgbdvo
