#include "rgbdvo/sources/pairing.hpp"

#include <catch2/catch.hpp>
#include <stdexcept>
#include <utility>

using namespace rgbdvo;

namespace {

std::vector<std::pair<size_t, size_t>> Pairs(const StampPairs& p) {
  std::vector<std::pair<size_t, size_t>> out;
  out.reserve(p.pairs.size());
  for (const StampPairs::Pair& q : p.pairs) out.emplace_back(q.color, q.depth);
  return out;
}

using PairList = std::vector<std::pair<size_t, size_t>>;

}  // namespace

TEST_CASE("One-to-one pairing takes the closest pairs first, each image once, drops the rest") {
  // Colour 1 is 2 ms from depth 0 and takes it before colour 0 (8 ms) can; colour 0 has no
  // other depth image within 20 ms and is dropped. Colour 2 takes depth 1 (5 ms), not depth 2
  // (30 ms, outside the window).
  const std::vector<double> color = {1.000, 1.010, 1.100}, depth = {1.008, 1.095, 1.130};
  const StampPairs one = PairStamps(Pairing::kOneToOne, color, depth, 0.02);
  CHECK(Pairs(one) == PairList{{1, 0}, {2, 1}});
  CHECK(one.unpaired_color == std::vector<size_t>{0});
  // Nearest: colours 0 and 1 share depth 0.
  const StampPairs nearest = PairStamps(Pairing::kNearest, color, depth, 0.02);
  CHECK(Pairs(nearest) == PairList{{0, 0}, {1, 0}, {2, 1}});
  CHECK(nearest.unpaired_color.empty());
}

TEST_CASE("One-to-one pairing orders by time difference, not by colour order") {
  // associate.py's greedy order: colour 0 - depth 1 (1 ms) first, so colour 0 does not get its
  // own nearest-in-order partner; colour 1 then takes depth 0 (15 ms): the pairs cross.
  const std::vector<double> color = {0.010, 0.015}, depth = {0.000, 0.011};
  const StampPairs one = PairStamps(Pairing::kOneToOne, color, depth, 0.02);
  CHECK(Pairs(one) == PairList{{0, 1}, {1, 0}});
  CHECK(one.unpaired_color.empty());
}

TEST_CASE("Pairing ties: one-to-one takes the earlier depth image, nearest the later") {
  const std::vector<double> color = {0.5}, depth = {0.25, 0.75};  // exact in binary
  CHECK(Pairs(PairStamps(Pairing::kOneToOne, color, depth, 0.5)) == PairList{{0, 0}});
  CHECK(Pairs(PairStamps(Pairing::kNearest, color, depth, 0.5)) == PairList{{0, 1}});
}

TEST_CASE("Pairing keeps the window inclusive and drops colour images beyond it") {
  const std::vector<double> color = {1.0, 2.0}, depth = {1.5};
  for (Pairing p : {Pairing::kNearest, Pairing::kOneToOne}) {
    CHECK(PairStamps(p, color, depth, 0.25).pairs.empty());
    CHECK(PairStamps(p, color, depth, 0.25).unpaired_color == std::vector<size_t>{0, 1});
    CHECK(PairStamps(p, {1.0}, depth, 0.5).pairs.size() == 1);
  }
}

TEST_CASE("Pairing names parse both ways and a wrong one is refused") {
  for (Pairing p : {Pairing::kNearest, Pairing::kOneToOne})
    CHECK(ParsePairing(PairingName(p)) == p);
  CHECK_THROWS_WITH(ParsePairing("closest"), Catch::Contains("closest"));
  CHECK_THROWS_AS(PairStamps(Pairing::kNearest, {1.0}, {2.0, 1.0}, 0.1), std::invalid_argument);
}
