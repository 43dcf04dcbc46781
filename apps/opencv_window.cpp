#include "opencv_window.hpp"

#include <dlfcn.h>

#include <stdexcept>

namespace rgbdvo::cli::window {
namespace {

// The library CMake found (RGBDVO_HIGHGUI_SONAME, e.g. "libopencv_highgui.so.406"), opened once;
// the functions are looked up by their C++ names, which the same OpenCV headers and compiler give
// them here.
struct Highgui {
  void (*named_window)(const cv::String&, int) = nullptr;
  void (*set_mouse_callback)(const cv::String&, cv::MouseCallback, void*) = nullptr;
  void (*imshow)(const cv::String&, const cv::_InputArray&) = nullptr;
  int (*wait_key)(int) = nullptr;
  double (*get_window_property)(const cv::String&, int) = nullptr;
  void (*destroy_all_windows)() = nullptr;
};

template <typename F>
void Find(void* library, const char* name, F* f) {
  *f = reinterpret_cast<F>(dlsym(library, name));
  if (*f == nullptr)
    throw std::runtime_error(std::string("OpenCV's window library ") + RGBDVO_HIGHGUI_SONAME +
                             " has no " + name);
}

const Highgui& Load() {
  static const Highgui highgui = [] {
    void* library = dlopen(RGBDVO_HIGHGUI_SONAME, RTLD_NOW | RTLD_LOCAL);
    if (library == nullptr) {
      const char* why = dlerror();
      throw std::runtime_error(std::string("OpenCV's window library could not be loaded (") +
                               (why != nullptr ? why : RGBDVO_HIGHGUI_SONAME) + ")");
    }
    Highgui h;
    Find(library, "_ZN2cv11namedWindowERKNSt7__cxx1112basic_stringIcSt11char_traitsIcESaIcEEEi",
         &h.named_window);
    Find(library,
         "_ZN2cv16setMouseCallbackERKNSt7__cxx1112basic_stringIcSt11char_traitsIcESaIcEEEPFviiiiPv"
         "ES8_",
         &h.set_mouse_callback);
    Find(library,
         "_ZN2cv6imshowERKNSt7__cxx1112basic_stringIcSt11char_traitsIcESaIcEEERKNS_11_InputArrayE",
         &h.imshow);
    Find(library, "_ZN2cv7waitKeyEi", &h.wait_key);
    Find(library,
         "_ZN2cv17getWindowPropertyERKNSt7__cxx1112basic_stringIcSt11char_traitsIcESaIcEEEi",
         &h.get_window_property);
    Find(library, "_ZN2cv17destroyAllWindowsEv", &h.destroy_all_windows);
    return h;
  }();
  return highgui;
}

}  // namespace

void NamedWindow(const std::string& name, int flags) { Load().named_window(name, flags); }

void SetMouseCallback(const std::string& name, cv::MouseCallback on_mouse, void* userdata) {
  Load().set_mouse_callback(name, on_mouse, userdata);
}

void Show(const std::string& name, const cv::Mat& image) { Load().imshow(name, image); }

int WaitKey(int delay_ms) { return Load().wait_key(delay_ms); }

double GetProperty(const std::string& name, int property) {
  return Load().get_window_property(name, property);
}

void DestroyAll() { Load().destroy_all_windows(); }

}  // namespace rgbdvo::cli::window
