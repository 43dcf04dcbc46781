// rgbdvo: RGB-D visual odometry after Fiala & Ufkes (CRV 2011).
#include <exception>
#include <iostream>
#include <opencv2/core/utils/logger.hpp>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "commands.hpp"

namespace {

// Every frame allocates and frees images of about a megabyte (the decoded colour and depth, the
// depth the odometry keeps, the scale space). By default glibc maps large blocks afresh and
// returns them on free (and trims the heaps' free tops), so every frame pays the page faults again.
// Kept in the heap (docs/benchmarks.md, "Memory handed back to the kernel"): CPU x0.83-0.92 with
// two workers, x0.96-0.99 with one; peak memory 5-10 MiB more, and bounded over long replays as
// before (24000 frames: 137 MiB against 130).
void KeepFreedImagesInHeap() {
#if defined(__GLIBC__)
  // mallopt is not thread-safe: this runs first in main, before any thread is started.
  constexpr int kMiB = 1 << 20;
  // The largest mmap threshold glibc accepts on 64-bit systems.
  mallopt(M_MMAP_THRESHOLD, 32 * kMiB);   // NOLINT(concurrency-mt-unsafe)
  mallopt(M_TRIM_THRESHOLD, 256 * kMiB);  // NOLINT(concurrency-mt-unsafe)
  // One heap for all threads: each thread's own arena (glibc's default for a second thread) is
  // trimmed by its own rules, and the feature workers' decoded images faulted in again
  // (fast90, 2 workers: 20900 -> 18500 page faults, system time 218 -> 171 ms a run). The
  // threads allocate a few large images per frame, so they hardly wait on the shared heap's lock.
  mallopt(M_ARENA_MAX, 1);  // NOLINT(concurrency-mt-unsafe)
#endif
}

int Main(int argc, char** argv) {
  KeepFreedImagesInHeap();
  // OpenCV's own log lines ([ WARN:0@...] ...) would interleave with ours; errors we report.
  cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_ERROR);
  CLI::App app{"rgbdvo: visual odometry for Kinect-style RGB-D cameras (Fiala & Ufkes 2011)"};
  try {
    app.set_version_flag("--version", "rgbdvo " RGBDVO_VERSION);
    app.require_subcommand(1);
    rgbdvo::cli::AddRunCommand(app);
    rgbdvo::cli::AddCalibrateCommand(app);
    rgbdvo::cli::AddEvalCommand(app);
    rgbdvo::cli::AddPlotCommand(app);
    rgbdvo::cli::AddCaptureCommand(app);
    rgbdvo::cli::AddSynthKinectCommand(app);
    rgbdvo::cli::AddCalibrationsCommand(app);
    rgbdvo::cli::AddInfoCommand(app);
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {
    // A subcommand's own exit code (its message is already printed): 3 = Kinect lost,
    // 128 + N = stopped by signal N.
    return e.get_exit_code();
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; a bad command line exits 2, as getopt-based tools do.
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const std::exception& e) {
    std::cerr << "rgbdvo: error: " << e.what() << std::endl;
    return 1;
  } catch (...) {
    std::cerr << "rgbdvo: error: unknown exception" << std::endl;
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Main(argc, argv);
  } catch (...) {  // from the error reporting itself (a failing stream, out of memory)
    return 1;
  }
}
