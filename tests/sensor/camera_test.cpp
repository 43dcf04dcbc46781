#include "rgbdvo/sensor/camera.hpp"

#include <catch2/catch.hpp>
#include <vector>

#include "rgbdvo/sensor/calibration_catalog.hpp"

using namespace rgbdvo;

namespace {

Calibration PaperLike() {
  Calibration c;  // K_ir of the paper (eq. 3)
  c.A = 0.91;
  c.B = 28.0;
  c.C = 0.92;
  c.D = 19.0;
  return c;
}

}  // namespace

TEST_CASE("ColorToIr applies eq. 1 per axis") {
  const Calibration c = PaperLike();
  const Eigen::Vector2d ir = ColorToIr(c, {100, 200});
  CHECK(ir.x() == Approx(0.91 * 100 + 28));
  CHECK(ir.y() == Approx(0.92 * 200 + 19));
}

TEST_CASE("IrToColor inverts ColorToIr") {
  const Calibration c = PaperLike();
  for (double u : {0.0, 123.4, 639.0})
    for (double v : {0.0, 240.0, 479.0}) {
      const Eigen::Vector2d back = IrToColor(c, ColorToIr(c, {u, v}));
      CHECK(back.x() == Approx(u).margin(1e-9));
      CHECK(back.y() == Approx(v).margin(1e-9));
    }
  CHECK(IrToColor(c, {0.91 * 100 + 28, 0.92 * 200 + 19}).y() == Approx(200));
}

TEST_CASE("BackProject and ProjectIr round-trip and keep Z = depth") {
  const Calibration c = PaperLike();
  for (double u : {0.0, 123.4, 639.0})
    for (double v : {0.0, 240.0, 479.0})
      for (double d : {0.5, 2.0, 7.9}) {
        const Eigen::Vector3d X = BackProject(c, {u, v}, d);
        CHECK(X.z() == Approx(d));
        const Eigen::Vector2d uv = ProjectIr(c, X);
        CHECK(uv.x() == Approx(u).margin(1e-9));
        CHECK(uv.y() == Approx(v).margin(1e-9));
      }
  // The principal point looks straight ahead.
  CHECK(BackProject(c, {c.cx, c.cy}, 3.0).head<2>().norm() == Approx(0).margin(1e-12));
}

TEST_CASE("LiftColorPixel maps through eq. 1 and samples the depth there") {
  const Calibration c = PaperLike();
  cv::Mat depth(480, 640, CV_32F, cv::Scalar(0));
  const Eigen::Vector2d uv_vis(300, 200);
  const Eigen::Vector2d uv_ir = ColorToIr(c, uv_vis);  // (301, 203)
  depth.at<float>(static_cast<int>(std::round(uv_ir.y())),
                  static_cast<int>(std::round(uv_ir.x()))) = 2.5f;
  const auto X = LiftColorPixel(c, depth, uv_vis);
  REQUIRE(X);
  CHECK(X->z() == Approx(2.5));
  CHECK(X->x() == Approx((uv_ir.x() - c.cx) / c.fx * 2.5));
  // The same colour pixel with the depth reading cleared: excluded.
  depth.setTo(0);
  CHECK_FALSE(LiftColorPixel(c, depth, uv_vis));
}

TEST_CASE("Depth 0, out-of-range depth and out-of-image pixels are excluded") {
  Calibration c;
  cv::Mat depth(480, 640, CV_32F, cv::Scalar(2.0f));
  depth.at<float>(10, 10) = 0.0f;
  depth.at<float>(20, 20) = static_cast<float>(c.max_depth_m + 1);
  depth.at<float>(30, 30) = static_cast<float>(c.min_depth_m / 2);
  CHECK_FALSE(SampleDepth(c, depth, {10, 10}));
  CHECK_FALSE(SampleDepth(c, depth, {20, 20}));
  CHECK_FALSE(SampleDepth(c, depth, {30, 30}));
  CHECK(SampleDepth(c, depth, {11, 10}));
  for (const Eigen::Vector2d& uv :
       {Eigen::Vector2d(-0.6, 5), Eigen::Vector2d(5, -0.6), Eigen::Vector2d(639.6, 5),
        Eigen::Vector2d(5, 479.6), Eigen::Vector2d(1e9, 1e9), Eigen::Vector2d(NAN, 5)})
    CHECK_FALSE(SampleDepth(c, depth, uv));
  CHECK(SampleDepth(c, depth, {639.4, 479.4}));
  // A colour pixel whose mapped IR pixel leaves the image is excluded too.
  c.B = 50;
  CHECK_FALSE(LiftColorPixel(c, depth, {630, 100}));
}

TEST_CASE("BackProject removes lens distortion and ProjectIr puts it back") {
  Calibration c;  // TUM fr1 colour camera (Sturm et al. 2012)
  c.fx = 517.3;
  c.fy = 516.5;
  c.cx = 318.6;
  c.cy = 255.3;
  c.dist_ir = {0.2624, -0.9531, -0.0054, 0.0026, 1.1633};
  for (double u : {5.0, 200.0, 318.6, 500.0, 635.0})
    for (double v : {5.0, 255.3, 470.0}) {
      const Eigen::Vector3d X = BackProject(c, {u, v}, 2.0);
      CHECK(X.z() == 2.0);
      const Eigen::Vector2d uv = ProjectIr(c, X);
      CHECK(uv.x() == Approx(u).margin(1e-9));
      CHECK(uv.y() == Approx(v).margin(1e-9));
    }
  // Off-centre, distortion matters: the undistorted ray differs from the pinhole one by pixels.
  Calibration pinhole = c;
  pinhole.dist_ir = {0, 0, 0, 0, 0};
  const Eigen::Vector3d corner = BackProject(c, {5, 5}, 2.0),
                        plain = BackProject(pinhole, {5, 5}, 2.0);
  CHECK((corner - plain).norm() * c.fx / 2.0 > 3.0);
}

TEST_CASE("Bilinear depth interpolates a slope and refuses a depth edge") {
  Calibration c;
  cv::Mat depth(10, 10, CV_32F);
  for (int v = 0; v < 10; ++v)
    for (int u = 0; u < 10; ++u) depth.at<float>(v, u) = static_cast<float>(2.0 + 0.01 * u);
  const auto d = SampleDepthBilinear(c, depth, {3.25, 4.5}, 0.03);
  REQUIRE(d);
  CHECK(*d == Approx(2.0325));
  CHECK(SampleDepthBilinear(c, depth, {9.0, 9.0}, 0.03));  // the last pixel is inside
  CHECK_FALSE(SampleDepthBilinear(c, depth, {9.01, 3.0}, 0.03));
  depth.at<float>(5, 4) = 3.0f;  // a foreground/background edge next to (3.5, 4.5)
  CHECK_FALSE(SampleDepthBilinear(c, depth, {3.5, 4.5}, 0.03));
  depth.at<float>(5, 4) = 0.0f;  // a hole
  CHECK_FALSE(SampleDepthBilinear(c, depth, {3.5, 4.5}, 0.03));
  CHECK(SampleDepthBilinear(c, depth, {1.5, 1.5}, 0.03));
}

TEST_CASE("The disparity term moves the IR pixel by s / z and IrToColor inverts it") {
  Calibration c = PaperLike();
  c.s_u = -14.5;
  c.s_v = 2.0;
  const Eigen::Vector2d uv(250, 130);
  CHECK((ColorToIr(c, uv, 2.0) - ColorToIr(c, uv) - Eigen::Vector2d(-7.25, 1.0)).norm() < 1e-12);
  for (double z : {0.5, 1.0, 4.0}) CHECK((IrToColor(c, ColorToIr(c, uv, z), z) - uv).norm() < 1e-9);
  // The colour ray's point at depth z has Z = z and maps back to the colour pixel.
  const Eigen::Vector3d p = ColorRayPoint(c, uv, 1.5);
  CHECK(p.z() == Approx(1.5));
  CHECK((IrToColor(c, ProjectIr(c, p), p.z()) - uv).norm() < 1e-9);
}

TEST_CASE("FindIrPixel takes the nearest surface on the colour ray that the IR camera sees") {
  // A wall at 3 m with a box at 1 m in front of IR columns 300-339; A = C = 1, B = D = 0,
  // s_u = -15 px m: the colour ray of column u meets the IR image at u - 15 / z.
  Calibration c;
  c.s_u = -15.0;
  cv::Mat depth(480, 640, CV_32FC1, cv::Scalar(3.0f));
  depth(cv::Rect(300, 0, 40, 480)).setTo(1.0f);
  // On the box: colour columns 315-354 see it (u - 15 in 300-339).
  const auto box = FindIrPixel(c, depth, {330, 200});
  REQUIRE(box);
  CHECK(box->x() == Approx(315));
  // The wall left of the box: colour column 200 sees the wall at IR column 195.
  const auto wall = FindIrPixel(c, depth, {200, 200});
  REQUIRE(wall);
  CHECK(wall->x() == Approx(195));
  // Colour column 348 sees the box (IR 333), though the wall point on its ray (IR 343) is also
  // in view of the IR camera: the nearer surface hides it.
  const auto front = FindIrPixel(c, depth, {348, 200});
  REQUIRE(front);
  CHECK(front->x() == Approx(333));
  // Colour column 360 sees the wall at IR 355, just right of the box.
  const auto behind = FindIrPixel(c, depth, {360, 200});
  REQUIRE(behind);
  CHECK(behind->x() == Approx(355));
  // Lifted: the point on the colour ray at the box's depth.
  const auto lifted = LiftColorPixel(c, depth, {330, 200});
  REQUIRE(lifted);
  CHECK(lifted->z() == Approx(1.0));
  CHECK((IrToColor(c, ProjectIr(c, *lifted), lifted->z()) - Eigen::Vector2d(330, 200)).norm() <
        1e-9);
  // No depth at all: nothing.
  CHECK_FALSE(FindIrPixel(c, cv::Mat::zeros(480, 640, CV_32FC1), {330, 200}));
  // Without the term the depth image is not consulted: eq. 1.
  c.s_u = 0;
  CHECK(FindIrPixel(c, depth, {330, 200})->x() == 330);
}

TEST_CASE("ColorCenterInIr is the disparity term's baseline, zero without it") {
  Calibration c = PaperLike();
  CHECK(ColorCenterInIr(c).isZero());  // eq. 1 alone: one centre
  c.fx = 585;
  c.fy = 580;
  c.s_u = -585 * 0.025;  // the IR camera 2.5 cm to the colour camera's right (+x)
  c.s_v = 580 * 0.01;    // and 1 cm above it (-y)
  const Eigen::Vector3d centre = ColorCenterInIr(c);
  CHECK(centre.x() == Approx(-0.025));
  CHECK(centre.y() == Approx(0.01));
  CHECK(centre.z() == 0);
}

TEST_CASE("NormalizeIrRow gives each pixel of a row NormalizeIr's ray", "[camera]") {
  // TUM fr1's IR camera (strong radial distortion), and the same without distortion; 13 pixels:
  // a whole group of interleaved pixels and a remainder done one at a time.
  Calibration distorted = LoadCalibration(FindCalibration("tum_fr1"));
  Calibration pinhole = distorted;
  pinhole.dist_ir = {0, 0, 0, 0, 0};
  for (const Calibration& c : {distorted, pinhole}) {
    for (int v : {0, 17, 479}) {
      const int u0 = 600, n = 13;  // pixels 600 .. 612 (the row's own u goes from 0)
      std::vector<Eigen::Vector2d> start(u0 + n), out(u0 + n);
      for (int u = 0; u < u0 + n; ++u)  // a start a few pixels off the root, and one far off
        start[u] = NormalizeIr(c, {u + (u % 2 ? 3.0 : -40.0), v - 2.0});
      NormalizeIrRow(c, v, u0 + n, start.data(), out.data());
      double worst = 0, moved = 0;
      for (int u = 0; u < u0 + n; ++u) {
        const Eigen::Vector2d expected = NormalizeIr(c, {u, v}, start[u]);
        worst = std::max(worst, (out[u] - expected).cwiseAbs().maxCoeff());
        moved = std::max(moved, (out[u] - start[u]).norm());
      }
      CHECK(worst < 1e-14);
      CHECK(moved > 1e-3);  // the starts were not the answers
    }
  }
}
