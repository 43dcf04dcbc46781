#include "rgbdvo/odometry/track_staleness.hpp"

#include <catch2/catch.hpp>

using namespace rgbdvo;

TEST_CASE("Tracks are stale when their noise exceeds the ratio times the least so far") {
  TrackStaleness s(1.5);
  CHECK_FALSE(s.Stale(1.0));  // the first tracked frame sets the bar
  CHECK_FALSE(s.Stale(1.4));
  CHECK_FALSE(s.Stale(1.5));  // at the ratio: not above it
  CHECK(s.Stale(1.6));
}

TEST_CASE("A blurred first tracked frame does not raise the bar for the frames after it") {
  // fr1/xyz every 3rd frame, seed 9: 1.50 on the first tracked frame, 1.00 on the next, 1.69.
  TrackStaleness s(1.5);
  CHECK_FALSE(s.Stale(1.50));
  CHECK_FALSE(s.Stale(1.00));
  CHECK(s.Stale(1.69));  // against the first's 1.50 it would pass (bar 2.25)
  CHECK(s.Stale(1.51));  // the least stays 1.00
}
