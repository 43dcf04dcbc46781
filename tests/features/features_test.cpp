#include "rgbdvo/features/features.hpp"

#include <catch2/catch.hpp>
#include <thread>

#include "rgbdvo/synthetic/synthetic.hpp"

using namespace rgbdvo;

namespace {

// Fraction of `a`'s keypoints with a keypoint of `b` within `px` pixels and a size within 25%.
double FractionFound(const Features& a, const Features& b, double px) {
  int found = 0;
  for (const cv::KeyPoint& k : a.keypoints)
    for (const cv::KeyPoint& m : b.keypoints)
      if (cv::norm(k.pt - m.pt) <= px && std::abs(k.size - m.size) <= 0.25 * k.size) {
        ++found;
        break;
      }
  return a.size() ? static_cast<double>(found) / a.size() : 0.0;
}

}  // namespace

TEST_CASE("OpenCV SIFT on the half image finds the full image's keypoints in image pixels") {
  const SyntheticScene scene;
  const cv::Mat image = scene.RenderColor(PinholeCamera{}, Rigid3d::Identity());
  FeatureOptions full_options = FeatureOptions::Lowe(), half_options = FeatureOptions::Lowe();
  full_options.implementation = half_options.implementation = SiftImplementation::kOpenCv;
  half_options.upsample_first_octave = false;
  const Features full = SiftExtractor(full_options).Extract(image);
  const Features half = SiftExtractor(half_options).Extract(image);
  INFO("full " << full.size() << " half " << half.size() << " found "
               << FractionFound(half, full, 1.5));
  REQUIRE(half.size() > 100);
  CHECK(half.size() < full.size());  // no features below 1.6 px of blur
  CHECK(half.descriptors.rows == static_cast<int>(half.size()));
  // Keypoints come back in image pixels: most coincide with a full-image keypoint.
  CHECK(FractionFound(half, full, 1.5) > 0.7);
  // Not coincidences: the same keypoints unscaled (half-image pixels) are mostly not found.
  Features unscaled = half;
  for (cv::KeyPoint& k : unscaled.keypoints) k.pt *= 0.5f, k.size *= 0.5f;
  CHECK(FractionFound(unscaled, full, 1.5) < 0.3);
}

TEST_CASE("rgbdvo SIFT without the upsampled octave keeps the larger keypoints") {
  const SyntheticScene scene;
  const cv::Mat image = scene.RenderColor(PinholeCamera{}, Rigid3d::Identity());
  FeatureOptions full_options = FeatureOptions::Lowe(), native_options = FeatureOptions::Lowe();
  native_options.upsample_first_octave = false;
  const Features full = SiftExtractor(full_options).Extract(image);
  const Features native = SiftExtractor(native_options).Extract(image);
  INFO("full " << full.size() << " native " << native.size());
  REQUIRE(native.size() > 100);
  CHECK(native.size() < 0.8 * full.size());
  for (const cv::KeyPoint& k : native.keypoints) CHECK(k.size >= 2 * 1.6f * 0.99f);
  CHECK(FractionFound(native, full, 0.5) > 0.7);
}

TEST_CASE("SiftExtractor gives the same features from several threads at once") {
  const SyntheticScene scene;
  const cv::Mat image = scene.RenderColor(PinholeCamera{}, Rigid3d::Identity());
  const SiftExtractor extractor{FeatureOptions{}};
  const Features alone = extractor.Extract(image);
  std::vector<Features> results(4);
  std::vector<std::thread> threads;
  threads.reserve(results.size());
  for (Features& r : results) threads.emplace_back([&] { r = extractor.Extract(image); });
  for (std::thread& t : threads) t.join();
  for (const Features& r : results) {
    REQUIRE(r.size() == alone.size());
    CHECK(cv::norm(r.descriptors, alone.descriptors, cv::NORM_INF) == 0);
  }
}

TEST_CASE("FeatureOptions::Check names the field") {
  FeatureOptions o;
  o.octave_layers = 0;
  CHECK_THROWS_WITH(o.Check(), Catch::Contains("octave_layers"));
}
