#include "rgbdvo/features/track_options.hpp"

#include <stdexcept>

namespace rgbdvo {

void TrackOptions::Check() const {
  if (window_px < 3) throw std::invalid_argument("TrackOptions.window_px must be >= 3");
  if (levels < 0) throw std::invalid_argument("TrackOptions.levels must be >= 0");
  if (max_points < 1) throw std::invalid_argument("TrackOptions.max_points must be >= 1");
  if (!(warp_max_shift_px > 0))
    throw std::invalid_argument("TrackOptions.warp_max_shift_px must be > 0");
  if (warp_window_px < 3) throw std::invalid_argument("TrackOptions.warp_window_px must be >= 3");
  if (!(warp_min_px >= 0)) throw std::invalid_argument("TrackOptions.warp_min_px must be >= 0");
  if (!(warp_settled_px > 0))
    throw std::invalid_argument("TrackOptions.warp_settled_px must be > 0");
  if (warp_iterations < 1) throw std::invalid_argument("TrackOptions.warp_iterations must be >= 1");
}

}  // namespace rgbdvo
