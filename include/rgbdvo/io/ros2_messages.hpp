#pragma once
// The sensor_msgs messages of ROS 2 bags, decoded without ROS: CDR (XCDR1, the serialisation of
// ROS 2's DDS middlewares) as rosbag2 stores it. A 4-byte encapsulation header (0x00 0x00
// big-endian, 0x00 0x01 little-endian, then two option bytes), then the fields in declaration
// order, each primitive aligned to its own size counted from after that header; a string is a
// u32 length counting its terminating NUL, then its bytes; a sequence a u32 count, then its
// elements; a fixed array its elements only.
//
// Every length is checked against the bytes left before anything is allocated: a message that
// does not hold what its lengths say throws std::runtime_error naming the type and the field.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace rgbdvo {

struct Ros2Header {
  int32_t sec = 0;  // builtin_interfaces/Time
  uint32_t nanosec = 0;
  std::string frame_id;
  double Seconds() const { return sec + nanosec * 1e-9; }
};

struct Ros2Image {  // sensor_msgs/msg/Image
  Ros2Header header;
  uint32_t height = 0, width = 0;
  std::string encoding;  // rgb8, bgr8, mono8, 16UC1 (mm), 32FC1 (m), ...
  uint8_t is_bigendian = 0;
  uint32_t step = 0;  // bytes per row
  std::vector<uint8_t> data;
};

struct Ros2CompressedImage {  // sensor_msgs/msg/CompressedImage
  Ros2Header header;
  // "png", "jpeg", "rgb8; jpeg compressed bgr8", or image_transport's depth
  // "16UC1; compressedDepth png" (data: a 12-byte header, then a PNG).
  std::string format;
  std::vector<uint8_t> data;
};

struct Ros2CameraInfo {  // sensor_msgs/msg/CameraInfo
  Ros2Header header;
  uint32_t height = 0, width = 0;
  std::string distortion_model;  // plumb_bob, rational_polynomial, equidistant
  std::vector<double> d;
  std::array<double, 9> k{}, r{};  // row-major 3x3
  std::array<double, 12> p{};      // row-major 3x4
  uint32_t binning_x = 0, binning_y = 0;
  uint32_t roi_x_offset = 0, roi_y_offset = 0, roi_height = 0, roi_width = 0;
  bool roi_do_rectify = false;
};

struct Ros2Imu {  // sensor_msgs/msg/Imu
  Ros2Header header;
  std::array<double, 4> orientation{};  // x, y, z, w
  std::array<double, 9> orientation_covariance{};
  std::array<double, 3> angular_velocity{};  // rad/s
  std::array<double, 9> angular_velocity_covariance{};
  std::array<double, 3> linear_acceleration{};  // m/s^2
  std::array<double, 9> linear_acceleration_covariance{};
};

// The type names as ROS 2 bags give them (MCAP schema names, rosbag2 topic types).
constexpr const char* kRos2ImageType = "sensor_msgs/msg/Image";
constexpr const char* kRos2CompressedImageType = "sensor_msgs/msg/CompressedImage";
constexpr const char* kRos2CameraInfoType = "sensor_msgs/msg/CameraInfo";
constexpr const char* kRos2ImuType = "sensor_msgs/msg/Imu";

// Decode one serialised message. Throw std::runtime_error ("sensor_msgs/msg/Image: data: ...")
// when the bytes are not a message of that type.
Ros2Image DecodeRos2Image(const uint8_t* bytes, size_t size);
Ros2CompressedImage DecodeRos2CompressedImage(const uint8_t* bytes, size_t size);
Ros2CameraInfo DecodeRos2CameraInfo(const uint8_t* bytes, size_t size);
Ros2Imu DecodeRos2Imu(const uint8_t* bytes, size_t size);
// The header alone (the first field of each type above), for pairing before decoding the rest.
Ros2Header DecodeRos2Header(const uint8_t* bytes, size_t size, const std::string& type);

// Serialise, little-endian unless `big_endian` (for writing bags and for the tests).
std::vector<uint8_t> EncodeRos2Image(const Ros2Image& m, bool big_endian = false);
std::vector<uint8_t> EncodeRos2CompressedImage(const Ros2CompressedImage& m,
                                               bool big_endian = false);
std::vector<uint8_t> EncodeRos2CameraInfo(const Ros2CameraInfo& m, bool big_endian = false);
std::vector<uint8_t> EncodeRos2Imu(const Ros2Imu& m, bool big_endian = false);

}  // namespace rgbdvo
