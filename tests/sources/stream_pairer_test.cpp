#include "rgbdvo/sources/stream_pairer.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <random>
#include <tuple>

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

TEST_CASE("One-to-one StreamPairer uses each depth frame once and drops the colour frame left") {
  // d100 is 8 ms from r1 and 2 ms from r2: r2 takes it; r1 has nothing else within 20 ms.
  Pairer p(20000, Pairing::kOneToOne);
  const auto pairs = RunStream(
      p,
      {{'r', 0, 1}, {'d', 8, 100}, {'r', 10, 2}, {'r', 100, 3}, {'d', 95, 101}, {'d', 130, 102}});
  CHECK(pairs == std::vector<std::pair<int, int>>{{2, 100}, {3, 101}});
  CHECK(p.unpaired() == 1);
}

TEST_CASE("One-to-one StreamPairer decides a pair once no later frame can be closer") {
  Pairer p(20000, Pairing::kOneToOne);
  CHECK(p.AddDepth({0, 100}).empty());
  CHECK(p.AddColor({5000, 1}).empty());  // a depth frame to come could be nearer r1
  // Now a colour frame to come is over 5 ms from d100 and a depth frame over 28 ms from r1.
  const auto done = p.AddDepth({33000, 101});
  REQUIRE(done.size() == 1);
  CHECK(done[0].color.value == 1);
  CHECK(done[0].depth.value == 100);
  CHECK(
      p.AddColor({38000, 2}).empty());  // d101 is 5 ms away; a depth frame to come could be nearer
  const auto last = p.Finish();
  REQUIRE(last.size() == 1);
  CHECK(last[0].color.value == 2);
  CHECK(last[0].depth.value == 101);
}

TEST_CASE("One-to-one StreamPairer gives associate.py's pairs over jittered 30 Hz streams") {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    // Colour and depth at 30 Hz with an offset, jitter and dropped frames; merged in time order.
    std::uniform_int_distribution<int> jitter(-6000, 6000), offset(-16000, 16000), drop(0, 9);
    const int shift = offset(rng);
    std::vector<std::tuple<int64_t, char, int>> events;
    for (int i = 0; i < 60; ++i) {
      if (drop(rng) > 0) events.emplace_back(i * 33333 + jitter(rng), 'r', i);
      if (drop(rng) > 0) events.emplace_back(i * 33333 + shift + jitter(rng), 'd', 1000 + i);
    }
    std::sort(events.begin(), events.end());
    std::vector<double> color_s, depth_s;
    std::vector<int> color_id, depth_id;
    StreamPairer<int> p(20000, Pairing::kOneToOne);
    std::vector<std::pair<int, int>> streamed;
    auto take = [&](const std::vector<StampedPair<int>>& done) {
      for (const auto& d : done) streamed.emplace_back(d.color.value, d.depth.value);
    };
    for (const auto& [t, type, id] : events) {
      (type == 'r' ? color_s : depth_s).push_back(static_cast<double>(t) * 1e-6);
      (type == 'r' ? color_id : depth_id).push_back(id);
      take(type == 'r' ? p.AddColor({t, id}) : p.AddDepth({t, id}));
    }
    take(p.Finish());
    const StampPairs whole = PairStamps(Pairing::kOneToOne, color_s, depth_s, 0.02);
    std::vector<std::pair<int, int>> expected;
    expected.reserve(whole.pairs.size());
    for (const StampPairs::Pair& q : whole.pairs)
      expected.emplace_back(color_id[q.color], depth_id[q.depth]);
    INFO("trial " << trial);
    CHECK(streamed == expected);
    CHECK(p.unpaired() == static_cast<int>(whole.unpaired_color.size()));
  }
}
