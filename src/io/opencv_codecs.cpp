#include "rgbdvo/io/opencv_codecs.hpp"

#include <dlfcn.h>

#include <stdexcept>
#include <vector>

namespace rgbdvo {
namespace {

// The library CMake found (RGBDVO_IMGCODECS_SONAME, e.g. "libopencv_imgcodecs.so.406"), opened
// once; the functions are looked up by their C++ names, which the same OpenCV headers and
// compiler give them here.
using Imread = cv::Mat (*)(const cv::String&, int);
using Imwrite = bool (*)(const cv::String&, const cv::_InputArray&, const std::vector<int>&);
using Imdecode = cv::Mat (*)(const cv::_InputArray&, int);

struct Codecs {
  Imread imread = nullptr;
  Imwrite imwrite = nullptr;
  Imdecode imdecode = nullptr;
  std::string error;  // why they could not be loaded
};

const Codecs& LoadCodecs() {
  static const Codecs codecs = [] {
    Codecs c;
    void* library = dlopen(RGBDVO_IMGCODECS_SONAME, RTLD_NOW | RTLD_LOCAL);
    if (library == nullptr) {
      const char* why = dlerror();
      c.error = why != nullptr ? why : RGBDVO_IMGCODECS_SONAME;
      return c;
    }
    c.imread = reinterpret_cast<Imread>(
        dlsym(library, "_ZN2cv6imreadERKNSt7__cxx1112basic_stringIcSt11char_traitsIcESaIcEEEi"));
    c.imwrite = reinterpret_cast<Imwrite>(
        dlsym(library,
              "_ZN2cv7imwriteERKNSt7__cxx1112basic_stringIcSt11char_traitsIcESaIcEEERKNS_"
              "11_InputArrayERKSt6vectorIiSaIiEE"));
    c.imdecode = reinterpret_cast<Imdecode>(dlsym(library, "_ZN2cv8imdecodeERKNS_11_InputArrayEi"));
    if (c.imread == nullptr || c.imwrite == nullptr || c.imdecode == nullptr)
      c.error = std::string(RGBDVO_IMGCODECS_SONAME) + " has no cv::imread, imwrite or imdecode";
    return c;
  }();
  return codecs;
}

const Codecs& CodecsFor(const std::string& path) {
  const Codecs& codecs = LoadCodecs();
  if (!codecs.error.empty())
    throw std::runtime_error(path + ": OpenCV's image codecs could not be loaded (" + codecs.error +
                             ")");
  return codecs;
}

}  // namespace

cv::Mat ImreadWithOpenCv(const std::string& path, int imread_flags) {
  return CodecsFor(path).imread(path, imread_flags);
}

bool ImwriteWithOpenCv(const std::string& path, const cv::Mat& image) {
  return CodecsFor(path).imwrite(path, image, std::vector<int>());
}

cv::Mat ImdecodeWithOpenCv(const std::vector<uint8_t>& bytes, int imread_flags,
                           const std::string& what) {
  return CodecsFor(what).imdecode(bytes, imread_flags);
}

}  // namespace rgbdvo
