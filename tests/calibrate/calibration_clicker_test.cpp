// The calibration window's state machine and canvas, without a window.
#include "rgbdvo/calibrate/calibration_clicker.hpp"

#include <catch2/catch.hpp>

using namespace rgbdvo;

namespace {

Frame MakeFrame(int index) {
  Frame f;
  f.index = index;
  f.bgr = cv::Mat(480, 640, CV_8UC3, cv::Scalar(100, 120, 140));
  f.depth_m = cv::Mat(480, 640, CV_32FC1, cv::Scalar(2.0f));
  f.depth_m(cv::Rect(0, 0, 320, 480)) = 1.0f;
  f.depth_m(cv::Rect(0, 0, 10, 10)) = 0.0f;
  return f;
}

void ClickVis(CalibrationClicker& c, int u, int v) { c.Click(u, v); }
void ClickIr(CalibrationClicker& c, int u, int v) { c.Click(640 + u, v); }

}  // namespace

TEST_CASE("Clicker: the canvas is both images side by side over a panel, at 1:1") {
  CalibrationClicker c({});
  c.SetFrame(MakeFrame(0));
  CHECK(c.CanvasSize() == cv::Size(1280, 600));
  const cv::Mat canvas = c.Render();
  CHECK(canvas.size() == cv::Size(1280, 600));
  CHECK(canvas.type() == CV_8UC3);
  CHECK(canvas.at<cv::Vec3b>(300, 100) == cv::Vec3b(100, 120, 140));  // colour image, unscaled
  CHECK(c.ToCanvas({10, 20}, false) == cv::Point2d(10, 20));
  CHECK(c.ToCanvas({10, 20}, true) == cv::Point2d(650, 20));
  ClickerOptions half;
  half.scale = 0.5;
  CalibrationClicker small(half);
  small.SetFrame(MakeFrame(0));
  CHECK(small.CanvasSize() == cv::Size(640, 240 + 120));
  // At scale 0.5 canvas pixel 5 covers image pixels 10 and 11: their centre is 10.5.
  small.Click(5, 5);
  small.Click(320 + 5, 5);
  REQUIRE(small.Pairs().size() == 1);
  CHECK(small.Pairs()[0].u_vis == 10.5);
  CHECK(small.Pairs()[0].u_ir == 10.5);
}

TEST_CASE("Clicker: a pair is a click in each image, in either order") {
  CalibrationClicker c({});
  c.SetFrame(MakeFrame(3));
  ClickVis(c, 100, 50);
  CHECK(c.Pairs().empty());
  ClickVis(c, 110, 60);  // a second colour click moves the pending point
  ClickIr(c, 120, 70);
  ClickIr(c, 300, 200);  // IR first
  c.Click(700, 550);     // the panel: ignored
  ClickVis(c, 310, 210);
  REQUIRE(c.Pairs().size() == 2);
  CHECK(c.Pairs()[0].u_vis == 110);
  CHECK(c.Pairs()[0].v_vis == 60);
  CHECK(c.Pairs()[0].u_ir == 120);
  CHECK(c.Pairs()[0].v_ir == 70);
  CHECK(c.Pairs()[1].u_vis == 310);
  CHECK(c.Pairs()[1].u_ir == 300);
  CHECK(c.clicked()[1].frame == 3);
  CHECK(c.dirty());
  CHECK_FALSE(c.fit().success);
  CHECK(c.fit().reason == "need at least 3 pairs, have 2");
}

TEST_CASE("Clicker: the fit follows every pair and undo") {
  CalibrationClicker c({}, {{0, 0, 20, 30}});  // one pair from a file
  c.SetFrame(MakeFrame(0));
  ClickVis(c, 100, 100), ClickIr(c, 110, 120);
  ClickVis(c, 500, 400), ClickIr(c, 470, 390);  // u_ir = 0.9 u + 20, v_ir = 0.9 v + 30
  REQUIRE(c.fit().success);
  CHECK(c.fit().A == Approx(0.9));
  CHECK(c.fit().D == Approx(30));
  ClickVis(c, 300, 300), ClickIr(c, 100, 100);  // a bad click
  CHECK(c.fit().rms_px > 10);
  CHECK(c.Key('u') == ClickerAction::kNone);
  REQUIRE(c.Pairs().size() == 3);
  CHECK(c.fit().rms_px < 1e-9);
  ClickVis(c, 200, 200);  // pending: undo drops it, not a pair
  c.Key('u');
  CHECK(c.Pairs().size() == 3);
  c.Key(8);  // Backspace undoes too
  CHECK(c.Pairs().size() == 2);
  CHECK_FALSE(c.fit().success);
  const std::vector<std::string> log = c.TakeLog();
  REQUIRE(log.size() == 10);
  CHECK(log[0] == "point in the colour image at 100.0,100.0");
  CHECK(log[1] == "pair 2: 100.0,100.0 -> 110.0,120.0; fit failed: need at least 3 pairs, have 2");
  CHECK_THAT(log[3], Catch::StartsWith("pair 3: 500.0,400.0 -> 470.0,390.0; A=0.9 B=20"));
  CHECK_THAT(log[6], Catch::StartsWith("undo: pair 4 removed; A=0.9"));
  CHECK(log[8] == "undo: pending point dropped");
  CHECK(log[9] == "undo: pair 3 removed; fit failed: need at least 3 pairs, have 2");
  CHECK(c.TakeLog().empty());
}

TEST_CASE("Clicker: r turns the robust fit on and flags the bad pair") {
  CalibrationClicker c({});
  c.SetFrame(MakeFrame(0));
  for (int u : {50, 200, 350, 500})
    for (int v : {50, 400}) ClickVis(c, u, v), ClickIr(c, u + 5, v - 5);
  ClickVis(c, 300, 250), ClickIr(c, 340, 245);  // 35 px off
  REQUIRE(c.fit().success);
  CHECK(c.fit().num_inliers == 9);
  c.Key('r');
  CHECK(c.robust());
  CHECK(c.fit().num_inliers == 8);
  CHECK(c.fit().outlier[8]);
  CHECK(c.fit().rms_px < 1e-9);
}

TEST_CASE("Clicker: keys map to actions, and quit asks again while pairs are unsaved") {
  CalibrationClicker c({});
  c.SetFrame(MakeFrame(0));
  CHECK(c.Key(-1) == ClickerAction::kNone);
  CHECK(c.Key('n') == ClickerAction::kNextFrame);
  CHECK(c.Key('p') == ClickerAction::kPrevFrame);
  CHECK(c.Key('s') == ClickerAction::kSave);
  CHECK(c.Key('q') == ClickerAction::kQuit);  // nothing to lose
  ClickVis(c, 10, 10), ClickIr(c, 10, 10);
  CHECK(c.Key('q') == ClickerAction::kNone);
  CHECK(c.Key(27) == ClickerAction::kQuit);  // the second press (Esc) quits
  CHECK(c.Key('q') == ClickerAction::kNone);
  c.MarkSaved();
  CHECK(c.Key('q') == ClickerAction::kQuit);
}

TEST_CASE("Clicker: pairs are drawn on their own frame only") {
  CalibrationClicker c({});
  c.SetFrame(MakeFrame(0));
  const cv::Mat empty = c.Render();
  ClickVis(c, 200, 200), ClickIr(c, 200, 200);
  const cv::Mat drawn = c.Render();
  const cv::Rect around(190, 190, 21, 21);
  CHECK(cv::norm(drawn(around), empty(around), cv::NORM_L1) > 0);
  c.SetFrame(MakeFrame(10));
  CHECK(cv::norm(c.Render()(around), empty(around), cv::NORM_L1) == 0);
  CHECK(c.Pairs().size() == 1);  // still counted in the fit
}

TEST_CASE("ColorizeDepth: missing depth black, near and far in different colours") {
  const cv::Mat bgr = ColorizeDepth(MakeFrame(0).depth_m);
  CHECK(bgr.type() == CV_8UC3);
  CHECK(bgr.at<cv::Vec3b>(5, 5) == cv::Vec3b(0, 0, 0));
  CHECK(cv::norm(cv::Vec3d(bgr.at<cv::Vec3b>(100, 100)) - cv::Vec3d(bgr.at<cv::Vec3b>(100, 500))) >
        60);
  CHECK(bgr.at<cv::Vec3b>(100, 500) != cv::Vec3b(0, 0, 0));
}
