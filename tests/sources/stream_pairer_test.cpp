#include "rgbdvo/sources/stream_pairer.hpp"

#include <catch2/catch.hpp>

using namespace rgbdvo;

namespace {

using Pairer = StreamPairer<int>;

// Runs a stream ("r" or "d", time in ms, id) and returns (colour id, depth id) pairs.
std::vector<std::pair<int, int>> RunStream(Pairer& p,
                                           const std::vector<std::tuple<char, int, int>>& s) {
  std::vector<std::pair<int, int>> out;
  auto take = [&](const std::vector<StampedPair<int>>& done) {
    for (const auto& d : done) out.emplace_back(d.color.value, d.depth.value);
  };
  for (auto [type, ms, id] : s)
    take(type == 'r' ? p.AddColor({ms * 1000, id}) : p.AddDepth({ms * 1000, id}));
  take(p.Finish());
  return out;
}

}  // namespace

TEST_CASE("StreamPairer takes the nearer of the depth frames before and after") {
  Pairer p(25000);
  const auto pairs = RunStream(p, {{'d', 0, 100},
                                   {'r', 5, 1},  // 5 ms after d100, 28 ms before d101
                                   {'d', 33, 101},
                                   {'r', 60, 2},  // 27 ms after d101, 6 ms before d102
                                   {'d', 66, 102}});
  REQUIRE(pairs.size() == 2);
  CHECK(pairs[0] == std::make_pair(1, 100));
  CHECK(pairs[1] == std::make_pair(2, 102));
  CHECK(p.unpaired() == 0);
}

TEST_CASE("StreamPairer prefers the earlier depth frame on a tie") {
  Pairer p(25000);
  const auto pairs = RunStream(p, {{'d', 0, 100}, {'r', 10, 1}, {'d', 20, 101}});
  REQUIRE(pairs.size() == 1);
  CHECK(pairs[0] == std::make_pair(1, 100));
}

TEST_CASE("StreamPairer drops colour frames with no depth frame within the window") {
  Pairer p(10000);
  const auto pairs = RunStream(p, {
                                      {'r', 0, 1},  // no depth before, next 50 ms later
                                      {'d', 50, 100},
                                      {'r', 55, 2},  // 5 ms after d100
                                      {'r', 90, 3},  // decided at end: 40 ms from d100
                                  });
  REQUIRE(pairs.size() == 1);
  CHECK(pairs[0] == std::make_pair(2, 100));
  CHECK(p.unpaired() == 2);
}

TEST_CASE("StreamPairer decides a waiting colour frame when the next one arrives") {
  Pairer p(25000);
  CHECK(p.AddDepth({0, 100}).empty());
  CHECK(p.AddColor({3000, 1}).empty());      // waits for the next depth frame
  const auto done = p.AddColor({36000, 2});  // the depth stream skipped a frame
  REQUIRE(done.size() == 1);
  CHECK(done[0].color.value == 1);
  CHECK(done[0].depth.value == 100);
  CHECK(done[0].color.t_us == 3000);
  const auto last = p.AddDepth({37000, 101});
  REQUIRE(last.size() == 1);
  CHECK(last[0].depth.value == 101);
  CHECK(p.Finish().empty());
}

TEST_CASE("KinectClock turns 60 MHz frame stamps into microseconds across the 32-bit wrap") {
  KinectClock clock;
  const uint32_t start = 0xffffffffu - 1000000;  // 16.7 ms before the counter wraps
  CHECK(clock.Micros(start) == 0);
  CHECK(clock.Micros(start + 2000000u) == 33333);  // wrapped: 2e6 ticks = 33.3 ms later
  CHECK(clock.Micros(start + 1000u) == 17);        // the other stream, slightly earlier
  CHECK(clock.Micros(start + 4000000u) == 66667);
}
