#include "debug_flags.hpp"

#include <chrono>
#include <thread>

namespace rgbdvo::cli {

#ifdef RGBDVO_DEBUG_FLAGS
void AddFrameDelayFlag(CLI::App* cmd, int* ms) {
  cmd->add_option("--debug-frame-delay-ms", *ms,
                  "for tests: sleep this long after each frame, as an odometry that much slower")
      ->check(CLI::NonNegativeNumber)
      ->group("");  // hidden from --help
}
#else
void AddFrameDelayFlag(CLI::App* /*cmd*/, int* /*ms*/) {}
#endif

void DelayFrame(int ms) {
  if (ms > 0) std::this_thread::sleep_for(std::chrono::milliseconds(ms));
}

}  // namespace rgbdvo::cli
