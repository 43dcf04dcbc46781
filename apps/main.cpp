// rgbdvo: RGB-D visual odometry after Fiala & Ufkes (CRV 2011).
#include <cerrno>
#include <cstdio>
#include <exception>
#include <iostream>
#include <opencv2/core/utils/logger.hpp>
#include <system_error>

#include "commands.hpp"
#include "rgbdvo/util/display_text.hpp"
#include "rgbdvo/util/image_heap.hpp"

namespace {

// The images' heap advised to huge pages this far: twice the heap's peak with two workers
// (fr1_xyz: 64 MiB). Address space only: a page is taken when first touched.
constexpr size_t kImageHeapBytes = size_t{128} << 20;

int Main(int argc, char** argv) {
  rgbdvo::SetUpImageHeap(kImageHeapBytes);
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
    // Messages quote input files, whose bytes must not reach the terminal as control sequences.
    std::cerr << "rgbdvo: error: " << rgbdvo::Printable(e.what()) << std::endl;
    return 1;
  } catch (...) {
    std::cerr << "rgbdvo: error: unknown exception" << std::endl;
    return 1;
  }
  return 0;
}

// Output that never reached standard output (a full disk) fails the command, as in coreutils.
int FlushStandardOutput(int code) {
  std::cout.flush();
  errno = 0;
  if (std::fflush(stdout) == 0 && !std::ferror(stdout) && std::cout.good()) return code;
  std::cerr << "rgbdvo: error: writing standard output: "
            << (errno != 0 ? std::generic_category().message(errno) : "write error") << std::endl;
  return code == 0 ? 1 : code;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return FlushStandardOutput(Main(argc, argv));
  } catch (...) {  // from the error reporting itself (a failing stream, out of memory)
    return 1;
  }
}
