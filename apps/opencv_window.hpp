#pragma once
// OpenCV's window functions (highgui), loaded when the calibration window first opens. Linked,
// highgui brings Qt, OpenGL and X11 (23 more shared libraries) into every start of the program,
// about 11 ms of CPU each time, for a window that only `rgbdvo calibrate` opens. Each function
// is the cv:: function of the same name; each throws std::runtime_error when the library cannot
// be loaded.

#include <opencv2/core.hpp>
#include <opencv2/highgui.hpp>  // the constants and cv::MouseCallback only
#include <string>

namespace rgbdvo::cli::window {

void NamedWindow(const std::string& name, int flags);
void SetMouseCallback(const std::string& name, cv::MouseCallback on_mouse, void* userdata);
void Show(const std::string& name, const cv::Mat& image);
int WaitKey(int delay_ms);
double GetProperty(const std::string& name, int property);
void DestroyAll();

}  // namespace rgbdvo::cli::window
