#include "rgbdvo/features/sift/sift.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <stdexcept>

#include "rgbdvo/features/sift/sift_descriptor.hpp"
#include "rgbdvo/util/simd.hpp"

namespace rgbdvo {
namespace {

constexpr int kBorder = 5;              // no extrema this close to an octave's edge (OpenCV)
constexpr int kMaxSteps = 5;            // sub-pixel refinement steps (OpenCV)
constexpr float kOriSigma = 1.5f;       // orientation window: Gaussian of 1.5 x scale (Lowe)
constexpr float kOriRadius = 3 * 1.5f;  // ... cut at 3 of its sigmas
constexpr float kOriPeak = 0.8f;        // extra orientations for peaks above 80% (Lowe)
constexpr float kToUnit = 1.0f / 255;   // DoG values are grey levels; thresholds are for 0..1

// Written as comparisons so that the compiler vectorises them into max/min instructions.
inline float Max(float a, float b) { return a > b ? a : b; }
inline float Min(float a, float b) { return a < b ? a : b; }

// Marks flags[x] = 1 for x in [begin, end) where row[x] is the maximum (minimum) of its 3x3
// neighbourhood (rows above, row, below) and above `threshold` (below -threshold). Returns how
// many. vmax and vmin are scratch rows of the row's length. Branch-free, vectorised.
RGBDVO_SIMD_CLONES int PlanarExtrema(const float* above, const float* row, const float* below,
                                     int begin, int end, float threshold, float* vmax, float* vmin,
                                     uint8_t* flags) {
  for (int x = begin - 1; x <= end; ++x) {
    vmax[x] = Max(Max(above[x], row[x]), below[x]);
    vmin[x] = Min(Min(above[x], row[x]), below[x]);
  }
  int found = 0;
  for (int x = begin; x < end; ++x) {
    const float v = row[x];
    const bool is_max = (v > threshold) & (v >= Max(Max(vmax[x - 1], vmax[x]), vmax[x + 1]));
    const bool is_min = (v < -threshold) & (v <= Min(Min(vmin[x - 1], vmin[x]), vmin[x + 1]));
    flags[x] = is_max | is_min;
    found += flags[x];
  }
  return found;
}

// Whether v (at x, y of the layer between `below` and `above`, already an extremum within its
// own layer) is also >= (if positive; <= if negative) its 18 neighbours in the two other layers:
// then it is an extremum of all 26 (Lowe section 3.1; ties allowed, as in OpenCV). Branch-free:
// the maximum and minimum of the 3 x 3 patches, 4 columns at a time (x - 1 .. x + 2; the
// fourth, x + 2, is inside the octave and left out at the end).
bool ExtremumAcrossLayers(const cv::Mat& below, const cv::Mat& above, int x, int y, float v) {
  typedef float v4f __attribute__((vector_size(16)));
  const auto load = [x](const cv::Mat& m, int yy) {
    v4f r;
    std::memcpy(&r, m.ptr<float>(yy) + x - 1, sizeof r);
    return r;
  };
  v4f hi = load(below, y - 1), lo = hi;
  for (const cv::Mat* m : {&below, &above})
    for (int dy = -1; dy <= 1; ++dy) {
      const v4f r = load(*m, y + dy);
      hi = hi > r ? hi : r;
      lo = lo < r ? lo : r;
    }
  return v > 0 ? v >= Max(Max(hi[0], hi[1]), hi[2]) : v <= Min(Min(lo[0], lo[1]), lo[2]);
}

// Lowe section 4: fits a 3D quadratic to the DoG around (x, y, layer), moving to the
// neighbouring sample while the offset exceeds 0.5; rejects low contrast and edge responses.
bool Refine(const Octave& o, int S, float contrast_threshold, float edge_threshold, int layer,
            int x, int y, Extremum* out) {
  const int rows = o.dog[0].rows, cols = o.dog[0].cols;
  const float d1 = 0.5f * kToUnit, d2 = kToUnit, dc = 0.25f * kToUnit;
  Eigen::Vector3f g, X;
  for (int step = 0;; ++step) {
    if (step == kMaxSteps) return false;
    const cv::Mat &prev = o.dog[layer - 1], &img = o.dog[layer], &next = o.dog[layer + 1];
    const auto at = [](const cv::Mat& m, int yy, int xx) { return m.ptr<float>(yy)[xx]; };
    const float v2 = 2 * at(img, y, x);
    g << (at(img, y, x + 1) - at(img, y, x - 1)) * d1, (at(img, y + 1, x) - at(img, y - 1, x)) * d1,
        (at(next, y, x) - at(prev, y, x)) * d1;
    const float dxx = (at(img, y, x + 1) + at(img, y, x - 1) - v2) * d2;
    const float dyy = (at(img, y + 1, x) + at(img, y - 1, x) - v2) * d2;
    const float dss = (at(next, y, x) + at(prev, y, x) - v2) * d2;
    const float dxy = (at(img, y + 1, x + 1) - at(img, y + 1, x - 1) - at(img, y - 1, x + 1) +
                       at(img, y - 1, x - 1)) *
                      dc;
    const float dxs =
        (at(next, y, x + 1) - at(next, y, x - 1) - at(prev, y, x + 1) + at(prev, y, x - 1)) * dc;
    const float dys =
        (at(next, y + 1, x) - at(next, y - 1, x) - at(prev, y + 1, x) + at(prev, y - 1, x)) * dc;
    Eigen::Matrix3f H;
    H << dxx, dxy, dxs, dxy, dyy, dys, dxs, dys, dss;
    X = -H.partialPivLu().solve(g);  // offset (x, y, s) of the quadratic's extremum
    if (!X.allFinite() || X.cwiseAbs().maxCoeff() > 1e6f) return false;
    if (X.cwiseAbs().maxCoeff() < 0.5f) {
      // Contrast at the interpolated extremum: D + g.X / 2 (Lowe eq. 3).
      const float contrast = at(img, y, x) * kToUnit + 0.5f * g.dot(X);
      if (std::abs(contrast) * S < contrast_threshold) return false;
      // Edges: ratio of principal curvatures of the 2D Hessian (Lowe section 4.1).
      const float tr = dxx + dyy, det = dxx * dyy - dxy * dxy;
      const float r = edge_threshold;
      if (det <= 0 || tr * tr * r >= (r + 1) * (r + 1) * det) return false;
      *out = {layer, x, y, X[0], X[1], X[2], std::abs(contrast)};
      return true;
    }
    x += static_cast<int>(std::lround(X[0]));
    y += static_cast<int>(std::lround(X[1]));
    layer += static_cast<int>(std::lround(X[2]));
    if (layer < 1 || layer > S || x < kBorder || x >= cols - kBorder || y < kBorder ||
        y >= rows - kBorder)
      return false;
  }
}

}  // namespace

void SiftOptions::Check() const {
  scale_space.Check();
  if (!(contrast_threshold > 0))
    throw std::invalid_argument("SiftOptions.contrast_threshold must be > 0");
  if (!(edge_threshold > 0)) throw std::invalid_argument("SiftOptions.edge_threshold must be > 0");
  if (max_features < 0)
    throw std::invalid_argument("SiftOptions.max_features must be >= 0 (0 = all)");
}

Sift::Sift(const SiftOptions& options) : options_(options), scale_space_(options.scale_space) {
  options_.Check();
}

void Sift::DetectAndDescribe(const cv::Mat& gray, std::vector<cv::KeyPoint>* keypoints,
                             cv::Mat* descriptors) {
  keypoints->clear();
  found_.clear();
  extrema_.clear();
  for (bool more = scale_space_.Begin(gray); more; more = scale_space_.Next())
    SearchOctave(static_cast<int>(scale_space_.octaves().size()) - 1);
  if (options_.max_features > 0) {
    OrientStrongest(keypoints);
  } else {
    for (const auto& [octave, e] : extrema_) Orient(octave, e, keypoints);
  }
  descriptors->create(static_cast<int>(keypoints->size()), kSiftDescriptorSize, CV_8U);
  for (size_t i = 0; i < found_.size(); ++i) {
    const Found& f = found_[i];
    SiftDescriptor(scale_space_.octaves()[f.octave].gauss[f.layer], f.x, f.y, f.scale,
                   (*keypoints)[i].angle, descriptors->ptr<uint8_t>(static_cast<int>(i)));
  }
}

void Sift::OrientStrongest(std::vector<cv::KeyPoint>* keypoints) {
  // Extrema from the strongest, ties in detection order, until max_features keypoints: the
  // strongest keypoints of all (an extremum's keypoints share its response), but only those
  // oriented. Then back to detection order (by extremum, then orientation).
  const size_t limit = static_cast<size_t>(options_.max_features);
  std::vector<size_t> order(extrema_.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return extrema_[a].second.response > extrema_[b].second.response;
  });
  std::vector<size_t> source;  // the extremum of each keypoint
  for (size_t i : order) {
    if (keypoints->size() >= limit) break;
    Orient(extrema_[i].first, extrema_[i].second, keypoints);
    source.resize(keypoints->size(), i);
  }
  const size_t n = std::min(limit, keypoints->size());
  std::vector<size_t> kept(n);
  std::iota(kept.begin(), kept.end(), 0);
  std::stable_sort(kept.begin(), kept.end(),
                   [&](size_t a, size_t b) { return source[a] < source[b]; });
  std::vector<cv::KeyPoint> kps;
  std::vector<Found> found;
  kps.reserve(n);
  found.reserve(n);
  for (size_t k : kept) {
    kps.push_back((*keypoints)[k]);
    found.push_back(found_[k]);
  }
  keypoints->swap(kps);
  found_.swap(found);
}

void Sift::SearchOctave(int index) {
  const Octave& o = scale_space_.octaves()[index];
  const int S = options_.scale_space.octave_layers;
  const int rows = o.dog[0].rows, cols = o.dog[0].cols;
  if (rows <= 2 * kBorder || cols <= 2 * kBorder) return;
  // Candidates need |DoG| above half the contrast threshold (Lowe). Not rounded down to whole
  // grey levels as OpenCV does: at contrast 0.015 that makes it 0, and every planar extremum
  // (45000 a frame on fr1/xyz, against 22000 unrounded, for the same keypoints) goes on
  // to the 26-neighbour test and the refinement.
  const float threshold = 0.5f * static_cast<float>(options_.contrast_threshold) / S * 255;
  row_buffers_.resize(2 * static_cast<size_t>(cols));
  refined_.clear();
  flags_.assign(cols + 8, 0);  // whole 8-byte words, 0 outside [kBorder, cols - kBorder)
  uint8_t* flags = flags_.data();

  for (int y = kBorder; y < rows - kBorder; ++y)
    for (int layer = 1; layer <= S; ++layer) {
      const cv::Mat& dog = o.dog[layer];
      const float* v = dog.ptr<float>(y);
      int found =
          PlanarExtrema(dog.ptr<float>(y - 1), v, dog.ptr<float>(y + 1), kBorder, cols - kBorder,
                        threshold, row_buffers_.data(), row_buffers_.data() + cols, flags);
      // Visit the flagged columns, skipping 8 unflagged ones at a time.
      for (int x8 = 0; found > 0 && x8 < cols; x8 += 8) {
        uint64_t word;
        std::memcpy(&word, flags + x8, 8);
        for (; word != 0; word &= word - 1) {
          const int x = x8 + __builtin_ctzll(word) / 8;
          --found;
          // An extremum of its 8 neighbours in the layer: now the 18 in the layers around it.
          if (!ExtremumAcrossLayers(o.dog[layer - 1], o.dog[layer + 1], x, y, v[x])) continue;
          Extremum e;
          if (!Refine(o, S, static_cast<float>(options_.contrast_threshold),
                      static_cast<float>(options_.edge_threshold), layer, x, y, &e))
            continue;
          // Several samples can converge on the same extremum: keep it once (OpenCV removes
          // such duplicates too; a duplicate would fail every ratio test it takes part in).
          if (!refined_.insert((static_cast<int64_t>(e.layer) * rows + e.y) * cols + e.x).second)
            continue;
          extrema_.emplace_back(index, e);
        }
      }
    }
}

void Sift::Orient(int index, const Extremum& e, std::vector<cv::KeyPoint>* keypoints) {
  // Scale in octave pixels, and the orientations (Lowe section 5).
  const Octave& o = scale_space_.octaves()[index];
  const int S = options_.scale_space.octave_layers;
  const float scale =
      static_cast<float>(options_.scale_space.sigma) * std::exp2((e.layer + e.ds) / S);
  const cv::Mat& level = o.gauss[e.layer];
  float hist[36];
  const float best = OrientationHistogram(
      level, e.x, e.y, static_cast<int>(std::lround(kOriRadius * scale)), kOriSigma * scale, hist);
  const float px = e.x + e.dx, py = e.y + e.dy;
  cv::KeyPoint k;
  k.pt = cv::Point2f(static_cast<float>(o.ToImage(px)), static_cast<float>(o.ToImage(py)));
  k.size = static_cast<float>(std::ldexp(2.0 * scale, o.index));
  k.response = e.response;
  k.octave =
      (o.index & 255) | (e.layer << 8) | (static_cast<int>(std::lround((e.ds + 0.5f) * 255)) << 16);
  // One keypoint per histogram peak within 80% of the highest (Lowe section 5).
  for (int i = 0; i < 36; ++i) {
    const float l = hist[(i + 35) % 36], c = hist[i], r = hist[(i + 1) % 36];
    if (!(c > l && c > r && c >= kOriPeak * best)) continue;
    // Parabola through the peak and its neighbours.
    float bin = i + 0.5f * (l - r) / (l - 2 * c + r);
    bin = bin < 0 ? bin + 36 : (bin >= 36 ? bin - 36 : bin);
    k.angle = 360.0f - 10.0f * bin;
    if (std::abs(k.angle - 360.0f) < 1e-4f) k.angle = 0;
    keypoints->push_back(k);
    found_.push_back({index, e.layer, px, py, scale});
  }
}

}  // namespace rgbdvo
