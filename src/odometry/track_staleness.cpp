#include "rgbdvo/odometry/track_staleness.hpp"

namespace rgbdvo {

bool TrackStaleness::Stale(double pixel_noise) {
  if (least_ < 0 || pixel_noise < least_) {
    least_ = pixel_noise;
    return false;
  }
  return pixel_noise > ratio_ * least_;
}

}  // namespace rgbdvo
