#include "rgbdvo/io/ros2_messages.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace rgbdvo {
namespace {

constexpr bool kHostLittle = __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__;

std::string Hex(uint8_t b) {
  const char* digits = "0123456789abcdef";
  return std::string("0x") + digits[b >> 4] + digits[b & 15];
}

// Reads the fields of one message; a field that does not fit in what is left throws, naming it.
class CdrIn {
 public:
  CdrIn(const uint8_t* bytes, size_t size, const std::string& type) : type_(type) {
    if (size < 4)
      Fail("encapsulation header", "the message has " + std::to_string(size) + " bytes");
    if (bytes[0] != 0 || bytes[1] > 1)
      Fail("encapsulation header",
           Hex(bytes[0]) + " " + Hex(bytes[1]) + " is not plain CDR (XCDR1, little or big endian)");
    swap_ = (bytes[1] == 1) != kHostLittle;
    data_ = bytes + 4;
    size_ = size - 4;
  }
  template <class T>
  void Num(T& v, const char* field) {
    Align(sizeof(T), field);
    std::array<uint8_t, sizeof(T)> b{};
    std::memcpy(b.data(), Take(sizeof(T), field), sizeof(T));
    if (swap_) std::reverse(b.begin(), b.end());
    std::memcpy(&v, b.data(), sizeof(T));
  }
  void Num(bool& v, const char* field) {
    uint8_t b = 0;
    Num(b, field);
    v = b != 0;
  }
  void Str(std::string& s, const char* field) {
    uint32_t n = 0;
    Num(n, field);
    const uint8_t* p = Take(n, field);
    // The length counts the terminating NUL; a string written without one is taken whole.
    s.assign(reinterpret_cast<const char*>(p), n > 0 && p[n - 1] == 0 ? n - 1 : n);
  }
  void Seq(std::vector<uint8_t>& v, const char* field) {
    uint32_t n = 0;
    Num(n, field);
    const uint8_t* p = Take(n, field);
    v.assign(p, p + n);
  }
  void Seq(std::vector<double>& v, const char* field) {
    uint32_t n = 0;
    Num(n, field);
    v.clear();
    if (n == 0) return;
    Align(8, field);
    if (n > Left() / 8)
      Fail(field,
           std::to_string(n) + " doubles declared, " + std::to_string(Left()) + " bytes left");
    v.resize(n);
    for (double& x : v) Num(x, field);
  }
  template <size_t N>
  void Arr(std::array<double, N>& a, const char* field) {
    for (double& x : a) Num(x, field);
  }

 private:
  size_t Left() const { return size_ - pos_; }
  void Align(size_t a, const char* field) { Take((a - pos_ % a) % a, field); }
  const uint8_t* Take(size_t n, const char* field) {
    if (n > Left())
      Fail(field, std::to_string(n) + " bytes needed, " + std::to_string(Left()) + " left");
    const uint8_t* p = data_ + pos_;
    pos_ += n;
    return p;
  }
  [[noreturn]] void Fail(const char* field, const std::string& what) const {
    throw std::runtime_error(type_ + ": " + field + ": " + what);
  }

  std::string type_;
  const uint8_t* data_ = nullptr;
  size_t size_ = 0, pos_ = 0;
  bool swap_ = false;
};

// Writes the fields as CdrIn reads them, with the encapsulation header first.
class CdrOut {
 public:
  explicit CdrOut(bool big_endian) : swap_(big_endian == kHostLittle) {
    out_ = {0, static_cast<uint8_t>(big_endian ? 0 : 1), 0, 0};
  }
  template <class T>
  void Num(const T& v, const char* /*field*/) {
    Align(sizeof(T));
    std::array<uint8_t, sizeof(T)> b{};
    std::memcpy(b.data(), &v, sizeof(T));
    if (swap_) std::reverse(b.begin(), b.end());
    out_.insert(out_.end(), b.begin(), b.end());
  }
  void Num(const bool& v, const char* field) { Num(static_cast<uint8_t>(v ? 1 : 0), field); }
  void Str(const std::string& s, const char* field) {
    Num(static_cast<uint32_t>(s.size() + 1), field);
    out_.insert(out_.end(), s.begin(), s.end());
    out_.push_back(0);
  }
  void Seq(const std::vector<uint8_t>& v, const char* field) {
    Num(static_cast<uint32_t>(v.size()), field);
    out_.insert(out_.end(), v.begin(), v.end());
  }
  void Seq(const std::vector<double>& v, const char* field) {
    Num(static_cast<uint32_t>(v.size()), field);
    for (const double x : v) Num(x, field);
  }
  template <size_t N>
  void Arr(const std::array<double, N>& a, const char* field) {
    for (const double x : a) Num(x, field);
  }
  std::vector<uint8_t> Take() { return std::move(out_); }

 private:
  void Align(size_t a) { out_.resize(out_.size() + (a - (out_.size() - 4) % a) % a, 0); }
  std::vector<uint8_t> out_;
  bool swap_;
};

// The fields of each type in declaration order, for CdrIn and CdrOut alike.
template <class S, class H>
void HeaderFields(S& s, H& h) {
  s.Num(h.sec, "header.stamp.sec");
  s.Num(h.nanosec, "header.stamp.nanosec");
  s.Str(h.frame_id, "header.frame_id");
}

template <class S, class M>
void ImageFields(S& s, M& m) {
  HeaderFields(s, m.header);
  s.Num(m.height, "height");
  s.Num(m.width, "width");
  s.Str(m.encoding, "encoding");
  s.Num(m.is_bigendian, "is_bigendian");
  s.Num(m.step, "step");
  s.Seq(m.data, "data");
}

template <class S, class M>
void CompressedImageFields(S& s, M& m) {
  HeaderFields(s, m.header);
  s.Str(m.format, "format");
  s.Seq(m.data, "data");
}

template <class S, class M>
void CameraInfoFields(S& s, M& m) {
  HeaderFields(s, m.header);
  s.Num(m.height, "height");
  s.Num(m.width, "width");
  s.Str(m.distortion_model, "distortion_model");
  s.Seq(m.d, "d");
  s.Arr(m.k, "k");
  s.Arr(m.r, "r");
  s.Arr(m.p, "p");
  s.Num(m.binning_x, "binning_x");
  s.Num(m.binning_y, "binning_y");
  s.Num(m.roi_x_offset, "roi.x_offset");
  s.Num(m.roi_y_offset, "roi.y_offset");
  s.Num(m.roi_height, "roi.height");
  s.Num(m.roi_width, "roi.width");
  s.Num(m.roi_do_rectify, "roi.do_rectify");
}

template <class S, class M>
void ImuFields(S& s, M& m) {
  HeaderFields(s, m.header);
  s.Arr(m.orientation, "orientation");
  s.Arr(m.orientation_covariance, "orientation_covariance");
  s.Arr(m.angular_velocity, "angular_velocity");
  s.Arr(m.angular_velocity_covariance, "angular_velocity_covariance");
  s.Arr(m.linear_acceleration, "linear_acceleration");
  s.Arr(m.linear_acceleration_covariance, "linear_acceleration_covariance");
}

}  // namespace

Ros2Image DecodeRos2Image(const uint8_t* bytes, size_t size) {
  CdrIn in(bytes, size, kRos2ImageType);
  Ros2Image m;
  ImageFields(in, m);
  return m;
}

Ros2CompressedImage DecodeRos2CompressedImage(const uint8_t* bytes, size_t size) {
  CdrIn in(bytes, size, kRos2CompressedImageType);
  Ros2CompressedImage m;
  CompressedImageFields(in, m);
  return m;
}

Ros2CameraInfo DecodeRos2CameraInfo(const uint8_t* bytes, size_t size) {
  CdrIn in(bytes, size, kRos2CameraInfoType);
  Ros2CameraInfo m;
  CameraInfoFields(in, m);
  return m;
}

Ros2Imu DecodeRos2Imu(const uint8_t* bytes, size_t size) {
  CdrIn in(bytes, size, kRos2ImuType);
  Ros2Imu m;
  ImuFields(in, m);
  return m;
}

Ros2Header DecodeRos2Header(const uint8_t* bytes, size_t size, const std::string& type) {
  CdrIn in(bytes, size, type);
  Ros2Header h;
  HeaderFields(in, h);
  return h;
}

std::vector<uint8_t> EncodeRos2Image(const Ros2Image& m, bool big_endian) {
  CdrOut out(big_endian);
  ImageFields(out, m);
  return out.Take();
}

std::vector<uint8_t> EncodeRos2CompressedImage(const Ros2CompressedImage& m, bool big_endian) {
  CdrOut out(big_endian);
  CompressedImageFields(out, m);
  return out.Take();
}

std::vector<uint8_t> EncodeRos2CameraInfo(const Ros2CameraInfo& m, bool big_endian) {
  CdrOut out(big_endian);
  CameraInfoFields(out, m);
  return out.Take();
}

std::vector<uint8_t> EncodeRos2Imu(const Ros2Imu& m, bool big_endian) {
  CdrOut out(big_endian);
  ImuFields(out, m);
  return out.Take();
}

}  // namespace rgbdvo
