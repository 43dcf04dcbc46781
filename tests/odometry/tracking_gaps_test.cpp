#include "rgbdvo/odometry/tracking_gaps.hpp"

#include <catch2/catch.hpp>

using namespace rgbdvo;

namespace {

FrameResult At(int frame, FrameStatus status) {
  FrameResult r;
  r.frame = frame;
  r.timestamp = 100 + frame / 10.0;
  r.status = status;
  if (!HasEstimate(status)) r.reason = "inliers<15";
  return r;
}

}  // namespace

TEST_CASE("A gap is announced when it starts and when it ends, with its length") {
  TrackingGaps gaps;
  CHECK_FALSE(gaps.Add(At(0, FrameStatus::kFirst)));
  CHECK_FALSE(gaps.Add(At(1, FrameStatus::kAccepted)));
  const auto start = gaps.Add(At(2, FrameStatus::kPredicted));
  REQUIRE(start);
  CHECK_THAT(*start, Catch::Contains("tracking failed at t=100.200 (frame 2): inliers<15") &&
                         Catch::Contains("predicted"));
  CHECK_FALSE(gaps.Add(At(3, FrameStatus::kPredicted)));
  CHECK_FALSE(gaps.Add(At(4, FrameStatus::kPredicted)));
  const auto end = gaps.Add(At(5, FrameStatus::kRecovered));
  REQUIRE(end);
  // Frames 1 and 5 are the feature estimates either side: 0.4 s without one.
  CHECK_THAT(*end, Catch::Contains("resumed at t=100.500 (frame 5) after 3 frames without a "
                                   "feature estimate (0.40 s between feature estimates)"));
  CHECK(gaps.longest_frames() == 3);
  CHECK(gaps.longest_seconds() == Approx(0.4));
  CHECK(gaps.gaps() == 1);
  CHECK_FALSE(gaps.Finish());
}

TEST_CASE("The longest of several gaps is kept, a lost frame is announced, an open gap too") {
  TrackingGaps gaps;
  gaps.Add(At(0, FrameStatus::kFirst));
  CHECK(gaps.Add(At(1, FrameStatus::kRejected)).value().find("holding the last pose") !=
        std::string::npos);
  gaps.Add(At(2, FrameStatus::kAccepted));
  gaps.Add(At(3, FrameStatus::kPredicted));
  gaps.Add(At(4, FrameStatus::kPredicted));
  const auto lost = gaps.Add(At(5, FrameStatus::kLost));
  REQUIRE(lost);
  CHECK_THAT(*lost, Catch::Contains("lost at t=100.500 (frame 5) after 3 frames"));
  CHECK(gaps.gaps() == 2);
  CHECK(gaps.longest_frames() == 3);
  gaps.Add(At(6, FrameStatus::kAccepted));
  gaps.Add(At(7, FrameStatus::kPredicted));
  REQUIRE(gaps.Finish());
  CHECK_THAT(*gaps.Finish(), Catch::Contains("ends in a gap of 1 frame without a feature "
                                             "estimate (0.10 s since the last one)"));
  CHECK(gaps.longest_seconds() == Approx(0.4));  // frames 2 and 6 either side of frames 3-5
}

TEST_CASE("A gap the sequence begins with is timed from the first frame") {
  TrackingGaps gaps;
  const auto start = gaps.Add(At(0, FrameStatus::kPredicted));
  REQUIRE(start);
  CHECK_THAT(*start, Catch::Contains("tracking failed at t=100.000 (frame 0)"));
  gaps.Add(At(1, FrameStatus::kPredicted));
  const auto end = gaps.Add(At(2, FrameStatus::kFirst));
  REQUIRE(end);
  CHECK_THAT(*end, Catch::Contains("after 2 frames without a feature estimate (0.20 s since the "
                                   "first frame)"));
  CHECK(gaps.longest_seconds() == Approx(0.2));
  // Later gaps are timed between feature estimates again.
  gaps.Add(At(3, FrameStatus::kPredicted));
  CHECK_THAT(gaps.Add(At(4, FrameStatus::kAccepted)).value(),
             Catch::Contains("(0.20 s between feature estimates)"));
  // A sequence without any feature estimate: its one gap, from the first frame.
  TrackingGaps none;
  none.Add(At(0, FrameStatus::kPredicted));
  none.Add(At(3, FrameStatus::kPredicted));
  REQUIRE(none.Finish());
  CHECK_THAT(*none.Finish(), Catch::Contains("(0.30 s since the first frame)"));
  CHECK(none.longest_seconds() == Approx(0.3));
}
