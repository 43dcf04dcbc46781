#include "rgbdvo/features/sift/scale_space.hpp"

#include <catch2/catch.hpp>
#include <cmath>

using namespace rgbdvo;

namespace {

// Variance along x of the image's mass around column cx (a blurred impulse's blur squared).
double VarianceX(const cv::Mat& m, double cx) {
  double sum = 0, moment = 0;
  for (int y = 0; y < m.rows; ++y)
    for (int x = 0; x < m.cols; ++x) {
      sum += m.at<float>(y, x);
      moment += m.at<float>(y, x) * (x - cx) * (x - cx);
    }
  return moment / sum;
}

}  // namespace

TEST_CASE("ScaleSpace levels have blur sigma * 2^(i/S) and the DoG is their difference") {
  // An impulse: each level is the Gaussian itself, whose variance is the level's blur squared
  // minus the 0.5-pixel blur the camera image is assumed to have.
  cv::Mat impulse = cv::Mat::zeros(81, 81, CV_8U);
  impulse.at<uint8_t>(40, 40) = 255;
  ScaleSpaceOptions o;
  o.upsample = false;
  ScaleSpace space(o);
  REQUIRE(space.Begin(impulse));
  const Octave& oct = space.octave();
  REQUIRE(oct.gauss.size() == 6);
  REQUIRE(oct.dog.size() == 5);
  for (int i = 0; i < 6; ++i) {
    const double blur = o.sigma * std::pow(2.0, i / 3.0);
    INFO("level " << i);
    CHECK(std::sqrt(VarianceX(oct.gauss[i], 40)) ==
          Approx(std::sqrt(blur * blur - 0.25)).epsilon(0.02));
  }
  for (int i = 0; i < 5; ++i)
    CHECK(cv::norm(oct.dog[i], oct.gauss[i + 1] - oct.gauss[i], cv::NORM_INF) < 1e-4);
}

TEST_CASE("ScaleSpace octaves halve until they are too small, with their pixel positions") {
  const cv::Mat image(480, 640, CV_8U, cv::Scalar(128));
  ScaleSpace up({});  // default: upsampled first octave
  REQUIRE(up.Begin(image));
  std::vector<cv::Size> sizes;
  std::vector<int> indices;
  do {
    sizes.push_back(up.octave().gauss[0].size());
    indices.push_back(up.octave().index);
  } while (up.Next());
  REQUIRE(sizes.size() == 7);  // 1280x960 ... 20x15
  CHECK(sizes.front() == cv::Size(1280, 960));
  CHECK(sizes.back() == cv::Size(20, 15));
  CHECK(indices.front() == -1);
  CHECK(indices.back() == 5);
  // Upsampled pixel 2x shows image pixel x - 1/4 (OpenCV's resize convention); octave 2
  // pixel x is image pixel 4x - 1/4.
  ScaleSpace again({});
  again.Begin(image);
  CHECK(again.octave().ToImage(100) == Approx(49.75));
  again.Next();
  again.Next();
  again.Next();
  CHECK(again.octave().index == 2);
  CHECK(again.octave().ToImage(10) == Approx(39.75));

  ScaleSpaceOptions native;
  native.upsample = false;
  ScaleSpace plain(native);
  REQUIRE(plain.Begin(image));
  CHECK(plain.octave().gauss[0].size() == cv::Size(640, 480));
  CHECK(plain.octave().ToImage(100) == Approx(100));
  CHECK_FALSE(ScaleSpace(native).Begin(cv::Mat(8, 100, CV_8U, cv::Scalar(0))));
}

TEST_CASE("ScaleSpace keeps every octave of an image until the next image") {
  cv::Mat image(120, 160, CV_8U);
  cv::RNG(5).fill(image, cv::RNG::UNIFORM, 0, 256);
  ScaleSpaceOptions native;
  native.upsample = false;
  ScaleSpace space(native);
  REQUIRE(space.Begin(image));
  std::vector<cv::Mat> first;  // each octave's levels as built
  do {
    for (const cv::Mat& m : space.octave().gauss) first.push_back(m.clone());
    for (const cv::Mat& m : space.octave().dog) first.push_back(m.clone());
  } while (space.Next());
  REQUIRE(space.octaves().size() == 4);  // 160x120, 80x60, 40x30, 20x15
  size_t k = 0;
  for (const Octave& o : space.octaves()) {
    for (const cv::Mat& m : o.gauss) CHECK(cv::norm(m, first[k++], cv::NORM_INF) == 0);
    for (const cv::Mat& m : o.dog) CHECK(cv::norm(m, first[k++], cv::NORM_INF) == 0);
  }
  REQUIRE(space.Begin(image));  // a new image starts over
  CHECK(space.octaves().size() == 1);
}

TEST_CASE("ScaleSpace checks its input and options") {
  ScaleSpace space({});
  CHECK_THROWS_WITH(space.Begin(cv::Mat(100, 100, CV_32F)), Catch::Contains("CV_8UC1"));
  ScaleSpaceOptions o;
  o.sigma = 0.4;
  CHECK_THROWS_WITH(o.Check(), Catch::Contains("sigma"));
  o = {};
  o.octave_layers = 0;
  CHECK_THROWS_WITH(o.Check(), Catch::Contains("octave_layers"));
}
