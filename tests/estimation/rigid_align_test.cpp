#include "rgbdvo/estimation/rigid_align.hpp"

#include <catch2/catch.hpp>

#include "test_support.hpp"

using namespace rgbdvo;
using namespace rgbdvo::test;

TEST_CASE("AlignRigid recovers random rigid motions exactly from noise-free pairs") {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> angle(0, M_PI), trans(0, 2);
  for (int i = 0; i < 200; ++i) {
    const double t = trans(rng);  // one draw per statement, last first: the same on every compiler
    const double a = angle(rng);
    const Rigid3d truth = RandomRigid(rng, a, t);
    const auto pairs = SynthesizePairs(rng, truth, 4 + i % 20, 0, 0);
    const auto est = AlignRigid(pairs);
    REQUIRE(est);
    CHECK(RotationErrorDeg(*est, truth) < 1e-7);
    CHECK(TranslationError(*est, truth) < 1e-9);
    CHECK(est->linear().determinant() == Approx(1.0).epsilon(1e-12));
  }
}

TEST_CASE("AlignRigid handles rotations near 0 and near pi") {
  std::mt19937 rng(2);
  for (double angle : {0.0, 1e-9, 1e-5, M_PI - 1e-5, M_PI - 1e-9, M_PI}) {
    const Rigid3d truth = RandomRigid(rng, angle, 0.3);
    const auto est = AlignRigid(SynthesizePairs(rng, truth, 10, 0, 0));
    REQUIRE(est);
    INFO("angle " << angle);
    CHECK(RotationErrorDeg(*est, truth) < 1e-6);
    CHECK(TranslationError(*est, truth) < 1e-9);
  }
}

TEST_CASE("AlignRigid never returns a reflection") {
  // Points mirrored through a plane: the least-squares orthogonal map is a reflection; the
  // result must still be a proper rotation.
  std::mt19937 rng(3);
  for (int i = 0; i < 50; ++i) {
    auto pairs = SynthesizePairs(rng, Rigid3d::Identity(), 8, 0, 0);
    for (auto& p : pairs) p.p_prev.x() = -p.p_prev.x();
    const auto est = AlignRigid(pairs);
    REQUIRE(est);
    CHECK(est->linear().determinant() == Approx(1.0).epsilon(1e-12));
    CHECK((est->linear() * est->linear().transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-12);
  }
}

TEST_CASE("AlignRigid refuses too few and collinear pairs") {
  std::mt19937 rng(4);
  auto pairs = SynthesizePairs(rng, Rigid3d::Identity(), 2, 0, 0);
  CHECK_FALSE(AlignRigid(pairs));
  std::vector<PointPair> line;
  for (int k = 0; k < 5; ++k) {
    const Eigen::Vector3d p(0.1 * k, 0.2 * k, 1 + 0.3 * k);
    line.push_back({p, p});
  }
  CHECK_FALSE(AlignRigid(line));
}

TEST_CASE("AlignRigid uses only the pairs named by indices") {
  std::mt19937 rng(5);
  const Rigid3d truth = RandomRigid(rng, 0.4, 0.2);
  auto pairs = SynthesizePairs(rng, truth, 30, 0, 0.5);  // first 15 are outliers
  std::vector<int> good;
  for (int k = 15; k < 30; ++k) good.push_back(k);
  const auto est = AlignRigid(pairs, good);
  REQUIRE(est);
  CHECK(RigidNear(*est, truth, 1e-7, 1e-9));
  CHECK_FALSE(RigidNear(*AlignRigid(pairs), truth, 0.1, 0.01));
}
