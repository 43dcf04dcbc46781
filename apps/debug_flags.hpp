#pragma once
// Flags for tests only. They exist in the test build of the program (rgbdvo_debug, with
// RGBDVO_DEBUG_FLAGS) and not in the installed rgbdvo, whose users never see or need them.

#include <CLI/CLI.hpp>

namespace rgbdvo::cli {

// --debug-frame-delay-ms into *ms (an odometry that much slower per frame, to test the queues
// and dropping); nothing in the installed program.
void AddFrameDelayFlag(CLI::App* cmd, int* ms);
// The sleep --debug-frame-delay-ms asks for after each frame.
void DelayFrame(int ms);

}  // namespace rgbdvo::cli
