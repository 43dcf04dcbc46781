#include "rgbdvo/sources/frame_cache.hpp"

#include <catch2/catch.hpp>

using namespace rgbdvo;

namespace {
class CountingSource : public FrameSource {
 public:
  explicit CountingSource(int n) : n_(n) {}
  std::optional<Frame> Next() override {
    if (reads_ >= n_) return std::nullopt;
    Frame f;
    f.index = reads_++;
    return f;
  }
  std::string Describe() const override { return "counting"; }
  int reads_ = 0;

 private:
  int n_;
};
}  // namespace

TEST_CASE("FrameCache reads on demand and steps back without re-reading") {
  CountingSource source(5);
  FrameCache cache(source);
  REQUIRE(cache.At(2) != nullptr);
  CHECK(cache.At(2)->index == 2);
  CHECK(source.reads_ == 3);
  CHECK(cache.At(0)->index == 0);
  CHECK(source.reads_ == 3);
  CHECK_FALSE(cache.ended());
  CHECK(cache.At(7) == nullptr);
  CHECK(cache.ended());
  CHECK(cache.size() == 5);
  CHECK(cache.At(4)->index == 4);
  CHECK(cache.At(-1) == nullptr);
}
