// `rgbdvo calibrate`: fit A-D of paper eq. 1 from point pairs, from a file or clicked in a window,
// or from a recording's depth and colour edges (--auto).
#include <cstdlib>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "opencv_window.hpp"
#include "rgbdvo/calibrate/auto_calibrate.hpp"
#include "rgbdvo/calibrate/calibrate.hpp"
#include "rgbdvo/calibrate/calibration_clicker.hpp"
#include "rgbdvo/calibrate/pixel_pairs_file.hpp"
#include "rgbdvo/io/opencv_codecs.hpp"
#include "rgbdvo/sensor/calibration_catalog.hpp"
#include "rgbdvo/sources/frame_cache.hpp"
#include "rgbdvo/sources/open_source.hpp"
#include "rgbdvo/util/display_text.hpp"

namespace rgbdvo::cli {
namespace {

constexpr const char* kWindow = "rgbdvo calibrate";

struct CalibrateArgs {
  std::string source, pairs, out, calib, save_pairs, png;
  int start = 0;
  bool automatic = false, depth_scale_given = false;
  SourceOptions source_options;
  ClickerOptions clicker;
  AutoCalibrateOptions auto_options;
};

// The calibration whose all but A-D is kept, and a line saying where K_ir comes from.
Calibration Base(const CalibrateArgs& a) {
  if (a.calib.empty()) {
    Calibration paper;  // not const: returned by move
    std::cout << "# K_ir, depth range: the paper's (fx = fy = " << paper.fx << ", cx = " << paper.cx
              << ", cy = " << paper.cy << "); give --calib with your camera's for better results"
              << std::endl;
    return paper;
  }
  const std::string path = FindCalibration(a.calib);
  std::cout << "# K_ir, distortion, depth range: from " << path << std::endl;
  return LoadCalibration(path);
}

int FromFile(const CalibrateArgs& a) {
  const Calibration base = Base(a);
  const std::vector<PixelPair> pairs = LoadPixelPairs(a.pairs);
  const MappingFit fit = FitMapping(a.clicker.fit, pairs);
  std::cout << FitReport(fit, pairs);
  if (!fit.success) throw std::runtime_error(a.pairs + ": " + fit.reason);
  std::cout << WriteCalibrateOutputs(pairs, fit, base, a.out, a.save_pairs) << std::endl;
  return 0;
}

// --auto: the start and all but A-D from --calib, else kinect_v1_default for a fakenect (raw
// Kinect) recording and the paper's K_ir with the identity mapping otherwise (the grid search
// spans both: calibrate_auto in docs/usage.md).
int Automatic(const CalibrateArgs& a) {
  Calibration base;
  std::string base_name = a.calib;
  if (base_name.empty() && IsFakenectFolder(a.source)) base_name = "kinect_v1_default";
  if (base_name.empty()) {
    std::cout << "# start: identity A-D, the paper's K_ir (give --calib for your camera's)"
              << std::endl;
  } else {
    const std::string path = FindCalibration(base_name);
    base = LoadCalibration(path);
    std::cout << "# start and K_ir, distortion, depth range: " << path << std::endl;
  }
  SourceOptions options = a.source_options;
  if (!a.depth_scale_given && base.depth_units_per_m > 0)
    options.tum.depth_units_per_m = base.depth_units_per_m;
  std::unique_ptr<FrameSource> source = OpenRecording(a.source, options);
  std::cout << "# source: " << source->Describe() << std::endl;
  const std::vector<Frame> frames = ReadSpreadFrames(*source, a.auto_options.max_frames);
  if (frames.empty()) throw std::runtime_error(a.source + ": no frames");
  const AutoCalibration fit = AutoCalibrate(a.auto_options, frames, base);
  std::cout << fit.Brief() << std::endl;
  if (!fit.success) throw std::runtime_error(a.source + ": " + fit.reason);
  if (!fit.warning.empty()) std::cerr << "rgbdvo: warning: " << Printable(fit.warning) << std::endl;
  const Calibration calib = ApplyAutoCalibration(base, fit, a.source);
  SaveCalibration(calib, a.out);
  std::cout << "wrote " << a.out << std::endl;
  if (!a.png.empty()) {
    const Frame& frame = frames[fit.picture_frame];
    if (!ImwriteWithOpenCv(a.png, AutoCalibrationPicture(a.auto_options, frame, calib)))
      throw std::runtime_error(a.png + ": cannot write the picture");
    std::cout
        << "wrote " << a.png << " (frame " << frame.index << " " << frame.name
        << ": depth edges green, colour edges mapped by A-D magenta, depth edges on them white)"
        << std::endl;
  }
  return 0;
}

void OnMouse(int event, int x, int y, int, void* user) {
  auto* clicker = static_cast<CalibrationClicker*>(user);
  if (event == cv::EVENT_LBUTTONDOWN) clicker->Click(x, y);
  if (event == cv::EVENT_MOUSEMOVE) clicker->Hover(x, y);
}

int Interactive(const CalibrateArgs& a) {
  const Calibration base = Base(a);
  const std::string pairs_path = a.save_pairs.empty() ? DefaultPairsPath(a.out) : a.save_pairs;
  if (!std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY"))
    throw std::runtime_error(
        "no display (DISPLAY is not set) for the calibration window; "
        "use --pairs FILE without SOURCE to fit from a pairs file");
  std::unique_ptr<FrameSource> source = OpenRecording(a.source, a.source_options);
  FrameCache frames(*source);
  int index = a.start;
  if (!frames.At(index))
    throw std::runtime_error(a.source + ": no frame " + std::to_string(index) + " (" +
                             std::to_string(frames.size()) + " frames)");
  CalibrationClicker clicker(a.clicker,
                             a.pairs.empty() ? std::vector<PixelPair>{} : LoadPixelPairs(a.pairs));
  clicker.SetFrame(*frames.At(index));
  std::cout << "# source: " << source->Describe() << "\n# window '" << kWindow << "': pairs go to "
            << pairs_path << ", calibration to " << a.out << std::endl;

  window::NamedWindow(kWindow, cv::WINDOW_AUTOSIZE | cv::WINDOW_GUI_NORMAL);
  window::SetMouseCallback(kWindow, OnMouse, &clicker);
  for (;;) {
    window::Show(kWindow, clicker.Render());
    const int key = window::WaitKey(20);
    if (window::GetProperty(kWindow, cv::WND_PROP_VISIBLE) < 1) break;  // window closed
    const ClickerAction action = clicker.Key(key);
    for (const std::string& line : clicker.TakeLog()) std::cout << line << std::endl;
    if (action == ClickerAction::kQuit) break;
    if (action == ClickerAction::kSave) {
      const std::vector<PixelPair> pairs = clicker.Pairs();
      std::cout << FitReport(clicker.fit(), pairs);
      const std::string msg = WriteCalibrateOutputs(pairs, clicker.fit(), base, a.out, pairs_path);
      std::cout << msg << std::endl;
      clicker.SetMessage(msg);
      clicker.MarkSaved();
    }
    if (action == ClickerAction::kNextFrame || action == ClickerAction::kPrevFrame) {
      const int step =
          action == ClickerAction::kNextFrame ? a.clicker.frame_step : -a.clicker.frame_step;
      int target = std::max(0, index + step);
      if (!frames.At(target)) target = frames.size() - 1;  // clamp at the last frame
      if (target != index) clicker.SetFrame(*frames.At(index = target));
      const bool last = frames.ended() && index == frames.size() - 1;
      clicker.SetMessage("frame " + std::to_string(index) + (last ? " (last)" : ""));
      std::cout << "frame " << index << (last ? " (last)" : "") << std::endl;
    }
  }
  window::DestroyAll();
  if (clicker.dirty()) std::cout << "quit without saving the last changes" << std::endl;
  return 0;
}

}  // namespace

void AddCalibrateCommand(CLI::App& app) {
  auto args = std::make_shared<CalibrateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "calibrate",
      "fit the colour->IR mapping A-D (paper eq. 1): click point pairs in a window over a "
      "recorded SOURCE, fit from --pairs FILE, or fit from SOURCE's depth and colour edges with "
      "--auto");
  cmd->add_option("source", args->source,
                  "recording folder to click pairs in or to fit (--auto); omit with --pairs");
  cmd->add_flag("--auto", args->automatic,
                "fit A-D without clicks: depth edges of SOURCE against its colour edges");
  cmd->add_option("--png", args->png,
                  "auto: residual picture (depth, its edges and the mapped colour edges)");
  cmd->add_option("--max-frames", args->auto_options.max_frames,
                  "auto: frames used, spread over the recording")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--pairs", args->pairs,
                  "pairs CSV (u_vis,v_vis,u_ir,v_ir): fit from it, or with SOURCE start from it");
  cmd->add_option("--out", args->out, "calibration YAML to write")->required();
  AddCalibFlag(cmd, &args->calib,
               "base calibration YAML, all but A-D kept (K_ir, dist_ir, depth range)");
  cmd->add_option("--save-pairs", args->save_pairs,
                  "where clicked pairs are saved (default: OUT with .pairs.csv)");
  cmd->add_flag("--robust", args->clicker.fit.robust, "set aside pairs with large residuals");
  cmd->add_option("--outlier-px", args->clicker.fit.outlier_px, "robust: outlier residual, px")
      ->capture_default_str();
  cmd->add_option("--min-spread", args->clicker.fit.min_spread_px,
                  "refuse pairs whose u or v span less, px")
      ->capture_default_str();
  cmd->add_option("--scale", args->clicker.scale, "window: screen pixels per image pixel")
      ->capture_default_str();
  cmd->add_option("--step", args->clicker.frame_step, "window: frames per n/p key")
      ->capture_default_str();
  cmd->add_option("--start", args->start, "window: first frame shown")->capture_default_str();
  cmd->add_option("--depth-scale", args->source_options.tum.depth_units_per_m,
                  "TUM depth units per metre")
      ->capture_default_str()
      ->each([args](const std::string&) { args->depth_scale_given = true; });
  cmd->add_option("--max-dt", args->source_options.tum.max_time_diff_s,
                  "max rgb-depth time difference, s")
      ->capture_default_str();
  cmd->callback([args] {
    if (args->source.empty() && args->pairs.empty())
      throw CLI::ValidationError("calibrate", "give a SOURCE folder (window) or --pairs FILE");
    if (args->automatic && (args->source.empty() || !args->pairs.empty()))
      throw CLI::ValidationError("calibrate", "--auto fits a SOURCE recording, without --pairs");
    if (args->automatic)
      args->auto_options.min_frames =
          std::min(args->auto_options.min_frames, args->auto_options.max_frames);
    const int code = args->automatic        ? Automatic(*args)
                     : args->source.empty() ? FromFile(*args)
                                            : Interactive(*args);
    if (code != 0) throw CLI::RuntimeError(code);
  });
}

}  // namespace rgbdvo::cli
