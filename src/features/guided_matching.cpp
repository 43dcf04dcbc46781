#include "rgbdvo/features/guided_matching.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "rgbdvo/util/simd.hpp"

namespace rgbdvo {

void GuidedMatchOptions::Check() const {
  if (!(radius_px > 0)) throw std::invalid_argument("GuidedMatchOptions.radius_px must be > 0");
  if (!(ratio > 0 && ratio <= 1))
    throw std::invalid_argument("GuidedMatchOptions.ratio must be in (0, 1]");
}

namespace {

// Squared L2 distance of two byte descriptors (vectorised where the caller is: 16-bit
// differences, 32-bit sums). cv::normL2Sqr<uint8_t, int> gives the same sums, but compiled for
// the baseline CPU only, where whole runs measured slower with it.
inline int DistanceSq(const uint8_t* a, const uint8_t* b, int n) {
  int sum = 0;
  for (int k = 0; k < n; ++k) {
    const int d = a[k] - b[k];
    sum += d * d;
  }
  return sum;
}

// The current keypoints bucketed in square cells (counting sort, one array per frame): the
// keypoints of cell c are index[start[c] .. start[c+1]), in ascending order.
struct Grid {
  float x0 = 0, y0 = 0, cell = 1;
  int nx = 0, ny = 0;
  std::vector<int> start, index;
  std::vector<float> xs, ys;  // the keypoints' positions in the same order as index

  Grid(const std::vector<cv::KeyPoint>& kps, float cell_px) : cell(cell_px) {
    float x1 = 0, y1 = 0;
    x0 = y0 = std::numeric_limits<float>::max();
    x1 = y1 = std::numeric_limits<float>::lowest();
    for (const cv::KeyPoint& k : kps) {
      x0 = std::min(x0, k.pt.x), y0 = std::min(y0, k.pt.y);
      x1 = std::max(x1, k.pt.x), y1 = std::max(y1, k.pt.y);
    }
    nx = static_cast<int>((x1 - x0) / cell) + 1;
    ny = static_cast<int>((y1 - y0) / cell) + 1;
    start.assign(static_cast<size_t>(nx) * ny + 1, 0);
    std::vector<int> cell_of(kps.size());
    for (size_t j = 0; j < kps.size(); ++j) {
      cell_of[j] = Cell(kps[j].pt.x, kps[j].pt.y);
      ++start[cell_of[j] + 1];
    }
    for (size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
    index.resize(kps.size());
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (size_t j = 0; j < kps.size(); ++j) index[fill[cell_of[j]]++] = static_cast<int>(j);
    xs.resize(kps.size());
    ys.resize(kps.size());
    for (size_t k = 0; k < kps.size(); ++k) {
      xs[k] = kps[index[k]].pt.x;
      ys[k] = kps[index[k]].pt.y;
    }
  }
  int Cell(float x, float y) const {
    return static_cast<int>((y - y0) / cell) * nx + static_cast<int>((x - x0) / cell);
  }
  // Cell range [lo, hi] along one axis covering [v - r, v + r]; empty (lo > hi) if outside.
  static void Range(double v, double r, float v0, float cell, int n, int* lo, int* hi) {
    const double a = std::floor((v - r - v0) / cell), b = std::floor((v + r - v0) / cell);
    *lo = static_cast<int>(std::clamp(a, 0.0, static_cast<double>(n)));
    *hi = static_cast<int>(std::clamp(b, -1.0, n - 1.0));
  }
};

// A reference keypoint's nearest and second nearest candidate (squared distances) and the
// nearest's index.
struct Best {
  float d1, d2;
  int j;
};

// Reference keypoint i (descriptor a, predicted at px, py) against the current keypoints of
// cells c0 .. c1 (one row of the grid) within sqrt(r2) pixels: updates i's best candidates and
// each candidate's nearest reference keypoint. Ties go to the lower index, as in cv::BFMatcher.
RGBDVO_SIMD_CLONES void CompareRow(const Grid& grid, int c0, int c1, double px, double py,
                                   double r2, const uint8_t* a, int i, const cv::Mat& descriptors,
                                   Best* b, float* cur_best, int* cur_best_ref) {
  for (int k = grid.start[c0]; k < grid.start[c1 + 1]; ++k) {
    const double dx = grid.xs[k] - px, dy = grid.ys[k] - py;
    if (dx * dx + dy * dy > r2) continue;
    const int j = grid.index[k];
    // Exact: a whole number below 2^24 (128 x 255^2), as cv::BFMatcher's distances are.
    const auto d = static_cast<float>(DistanceSq(a, descriptors.ptr<uint8_t>(j), descriptors.cols));
    if (d < b->d1 || (d == b->d1 && j < b->j)) {
      b->d2 = b->d1;
      b->d1 = d;
      b->j = j;
    } else if (d < b->d2) {
      b->d2 = d;
    }
    if (d < cur_best[j] || (d == cur_best[j] && i < cur_best_ref[j])) {
      cur_best[j] = d;
      cur_best_ref[j] = i;
    }
  }
}

}  // namespace

std::vector<cv::DMatch> MatchGuided(const GuidedMatchOptions& o, const Features& ref,
                                    const std::vector<std::optional<Eigen::Vector2d>>& predicted,
                                    const Features& cur) {
  if (predicted.size() != ref.size())
    throw std::invalid_argument("MatchGuided: one prediction per reference keypoint expected");
  std::vector<cv::DMatch> out;
  if (ref.size() == 0 || cur.size() == 0) return out;
  if (ref.descriptors.type() != CV_8U || cur.descriptors.type() != CV_8U ||
      ref.descriptors.cols != cur.descriptors.cols)
    throw std::invalid_argument("MatchGuided: CV_8U descriptors of the same length expected");
  const double r = o.radius_px, r2 = r * r;
  const Grid grid(cur.keypoints, static_cast<float>(std::clamp(r, 4.0, 1e4)));
  constexpr float kInf = std::numeric_limits<float>::infinity();

  // One pass over the candidate pairs (the relation is symmetric): squared distances to the
  // nearest and second nearest candidate of each reference keypoint, and the nearest reference
  // keypoint of each current keypoint. Ties go to the lower index, as in cv::BFMatcher.
  std::vector<float> cur_best(cur.size(), kInf);
  std::vector<int> cur_best_ref(cur.size(), -1);
  std::vector<Best> ref_best(ref.size(), Best{kInf, kInf, -1});
  for (size_t i = 0; i < ref.size(); ++i) {
    if (!predicted[i]) continue;
    const double px = predicted[i]->x(), py = predicted[i]->y();
    int cx0, cx1, cy0, cy1;
    Grid::Range(px, r, grid.x0, grid.cell, grid.nx, &cx0, &cx1);
    Grid::Range(py, r, grid.y0, grid.cell, grid.ny, &cy0, &cy1);
    for (int cy = cy0; cy <= cy1; ++cy)
      CompareRow(grid, cy * grid.nx + cx0, cy * grid.nx + cx1, px, py, r2,
                 ref.descriptors.ptr<uint8_t>(static_cast<int>(i)), static_cast<int>(i),
                 cur.descriptors, &ref_best[i], cur_best.data(), cur_best_ref.data());
  }
  for (size_t i = 0; i < ref.size(); ++i) {
    const Best& b = ref_best[i];
    if (b.j < 0) continue;
    // The ratio test on L2 distances exactly as MatchFeatures does it on cv::DMatch::distance.
    const float d1 = std::sqrt(b.d1), d2 = std::sqrt(b.d2);
    if (!(d1 < o.ratio * d2)) continue;
    if (o.mutual && cur_best_ref[b.j] != static_cast<int>(i)) continue;
    out.emplace_back(static_cast<int>(i), b.j, d1);
  }
  return out;
}

}  // namespace rgbdvo
