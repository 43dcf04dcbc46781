// rgbdvo: RGB-D visual odometry after Fiala & Ufkes (CRV 2011).
#include <exception>
#include <iostream>

#include "commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"rgbdvo: visual odometry for Kinect-style RGB-D cameras (Fiala & Ufkes 2011)"};
  app.require_subcommand(1);
  rgbdvo::cli::AddRunCommand(app);
  rgbdvo::cli::AddCalibrateCommand(app);
  rgbdvo::cli::AddEvalCommand(app);
  rgbdvo::cli::AddPlotCommand(app);
  rgbdvo::cli::AddCaptureCommand(app);
  rgbdvo::cli::AddSynthKinectCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::cerr << "rgbdvo: error: " << e.what() << std::endl;
    return 1;
  }
  return 0;
}
