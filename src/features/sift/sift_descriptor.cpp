#include "rgbdvo/features/sift/sift_descriptor.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "rgbdvo/util/simd.hpp"

namespace rgbdvo {
namespace {

constexpr float kPi = 3.14159265358979f;
// 8 floats / ints, GCC/Clang vector extension: one AVX register where the CPU has them. The
// 8-lane vectors are never passed by value between functions: the AVX2 clone and the baseline
// would pass them in different registers (clang refuses such calls), so helpers take and give
// them by address.
typedef float v8f __attribute__((vector_size(32)));
typedef float v8f_unaligned __attribute__((vector_size(32), aligned(4), may_alias));
typedef int v8i __attribute__((vector_size(32)));
typedef float v4f __attribute__((vector_size(16)));
typedef int v4i __attribute__((vector_size(16)));
typedef int64_t v2l __attribute__((vector_size(16)));
constexpr int kWidth = 4;          // spatial bins per side (Lowe: 4)
constexpr int kBins = 8;           // orientation bins (Lowe: 8)
constexpr float kBinWidth = 3.0f;  // a spatial bin is 3 sigma wide (OpenCV SIFT_DESCR_SCL_FCTR)
constexpr float kClip = 0.2f;      // clip normalised entries at 0.2 (Lowe section 6.1)
constexpr float kToByte = 512.0f;  // scale of the stored entries (OpenCV SIFT_INT_DESCR_FCTR)
constexpr int kPerBin = 4;         // grid samples per bin and side
// The grid covers bin coordinates (-1, kWidth): a sample in the outer ring still contributes
// by interpolation to the edge bins, as every pixel there does in OpenCV.
constexpr int kGrid = (kWidth + 1) * kPerBin;
constexpr int kSamples = kGrid * kGrid;

// Each spatial bin takes the samples of a square of kSpan x kSpan grid points (those within one
// bin of its centre): bin (br, bc) takes rows kPerBin * br .. + kSpan - 1 and the same columns.
constexpr int kSpan = 2 * kPerBin;

// The fixed sampling grid: where each sample lies (rotated bin units, relative to the
// keypoint), its Gaussian weight, and the bilinear weights with which it enters its bins.
struct Grid {
  // Each sample's row and column: bin coordinate - (kWidth - 1) / 2.
  std::array<float, kSamples> row_offset, col_offset;
  std::array<float, kSamples> weight;
  // Per spatial bin (row * kWidth + col), the bilinear weight of each sample of its square,
  // row by row (entry i: grid row kPerBin * br + i / kSpan, column kPerBin * bc + i % kSpan).
  std::array<std::array<float, kSpan * kSpan>, kWidth * kWidth> splat;
};

const Grid& TheGrid() {
  static const Grid grid = [] {
    Grid g;
    int bin0[kGrid];
    float offset[kGrid], frac[kGrid];
    for (int i = 0; i < kGrid; ++i) {
      const float b = -1.0f + (i + 0.5f) / kPerBin;  // bin centres at 0 .. kWidth - 1
      offset[i] = b - 0.5f * (kWidth - 1);
      bin0[i] = static_cast<int>(std::floor(b));
      frac[i] = b - bin0[i];
    }
    // Gaussian window of sigma = half the descriptor width (Lowe section 6.1).
    const float scale = -1.0f / (0.5f * kWidth * kWidth);
    for (int r = 0; r < kGrid; ++r)
      for (int c = 0; c < kGrid; ++c) {
        const int s = r * kGrid + c;
        g.row_offset[s] = offset[r];
        g.col_offset[s] = offset[c];
        g.weight[s] = std::exp((offset[r] * offset[r] + offset[c] * offset[c]) * scale);
        // Grid line i lies between bins bin0[i] and bin0[i] + 1 = i / kPerBin (never on one).
        for (int a = 0; a < 2; ++a)
          for (int b = 0; b < 2; ++b) {
            const int br = bin0[r] + a, bc = bin0[c] + b;
            if (br < 0 || br >= kWidth || bc < 0 || bc >= kWidth) continue;
            const float w = (a ? frac[r] : 1 - frac[r]) * (b ? frac[c] : 1 - frac[c]);
            g.splat[br * kWidth + bc][(r - kPerBin * br) * kSpan + (c - kPerBin * bc)] = w;
          }
      }
    return g;
  }();
  return grid;
}

// The 8 floats at p, read as `*At(p)`.
inline const v8f_unaligned* At(const float* p) { return reinterpret_cast<const v8f_unaligned*>(p); }

// p[0] in lanes 0-3, p[1] in lanes 4-7.
// (The pair is loaded as one 64-bit value: one load into a register, where GCC builds a short
// vector through the stack.)
inline void Spread(const void* p, v8i* out) {
  int64_t pair;
  std::memcpy(&pair, p, sizeof pair);
  const v4i two = (v4i)v2l{pair, 0};
  *out = __builtin_shufflevector(two, two, 0, 0, 0, 0, 1, 1, 1, 1);
}

// Four floats from p in lanes 0-3 and four from q in lanes 4-7.
inline void Pair(const float* p, const float* q, v8f* out) {
  v4f lo, hi;
  std::memcpy(&lo, p, sizeof lo);
  std::memcpy(&hi, q, sizeof hi);
  *out = __builtin_shufflevector(lo, hi, 0, 1, 2, 3, 4, 5, 6, 7);
}

// For TwoLanes, per lane o: with GCC, where each lane of (a, b, 0, ...) goes (a to lane o, b to
// lane o + 1 mod 8, 0 elsewhere); elsewhere, the mask of lane o.
#if defined(__GNUC__) && !defined(__clang__)
const std::array<v8i, kBins> kRoute = [] {
  std::array<v8i, kBins> r;
  for (int o = 0; o < kBins; ++o)
    for (int lane = 0; lane < kBins; ++lane)
      r[o][lane] = lane == o ? 0 : lane == ((o + 1) & (kBins - 1)) ? 1 : 2;
  return r;
}();
#else
const std::array<v8i, kBins> kLaneMask = [] {
  std::array<v8i, kBins> m;
  for (int o = 0; o < kBins; ++o) m[o] = v8i{0, 1, 2, 3, 4, 5, 6, 7} == o;
  return m;
}();
#endif

// An 8-lane vector with a in lane o, b in lane o + 1 (mod 8) and 0 elsewhere: with GCC one
// permutation of (a, b, 0, ...) (vpermps where the CPU has AVX2); elsewhere (a shuffle by a
// variable mask is GCC's) the two lanes' masks, two ands and an addition. The same values.
inline void TwoLanes(int o, float a, float b, v8f* out) {
#if defined(__GNUC__) && !defined(__clang__)
  *out = __builtin_shuffle(v8f{a, b, 0, 0, 0, 0, 0, 0}, kRoute[o]);
#else
  *out = (v8f)(kLaneMask[o] & (v8i)(v8f{} + a)) +
         (v8f)(kLaneMask[(o + 1) & (kBins - 1)] & (v8i)(v8f{} + b));
#endif
}

// Normalise, clip large gradients, renormalise (Lowe section 6.1); stored as 0..255. The
// squared norms are summed in 8 lanes (a single running sum would be a chain of 128 dependent
// additions).
inline void NormaliseToBytes(float* hist, uint8_t* out) {
  const auto norm_sq = [hist] {
    v8f sum = {};
    for (int k = 0; k < kSiftDescriptorSize; k += kBins) {
      const v8f v = *At(hist + k);
      sum += v * v;
    }
    return ((sum[0] + sum[4]) + (sum[1] + sum[5])) + ((sum[2] + sum[6]) + (sum[3] + sum[7]));
  };
  const float clip = kClip * std::sqrt(norm_sq());
  for (int k = 0; k < kSiftDescriptorSize; ++k) hist[k] = std::min(hist[k], clip);
  const float scale = kToByte / std::max(std::sqrt(norm_sq()), 1e-7f);
  for (int k = 0; k < kSiftDescriptorSize; ++k)
    out[k] = static_cast<uint8_t>(std::min(255.0f, std::floor(hist[k] * scale + 0.5f)));
}

}  // namespace

RGBDVO_SIMD_CLONES float OrientationHistogram(const cv::Mat& level, int x, int y, int radius,
                                              float sigma, float hist[36]) {
  constexpr int n = 36;
  constexpr int kMaxRadius = 64;
  radius = std::min(radius, kMaxRadius);
  float raw[n + 4] = {};  // two wrap-around entries on each side for the smoothing
  float* h = raw + 2;
  // exp(-(i^2 + j^2) / (2 sigma^2)) = w[i] * w[j].
  float w[2 * kMaxRadius + 1];
  const float scale = -1.0f / (2.0f * sigma * sigma);
  for (int i = -radius; i <= radius; ++i) w[i + radius] = std::exp(i * i * scale);
  float mag[2 * kMaxRadius + 1], bin[2 * kMaxRadius + 1];
  const float to_bin = n / (2 * kPi);
  const ptrdiff_t step = static_cast<ptrdiff_t>(level.step1());
  // Ask for the window's rows (and the one above and below it) up front: the loop below waits
  // on the first read of each new row otherwise.
  {
    const int r0 = std::max(y - radius - 1, 0), r1 = std::min(y + radius + 1, level.rows - 1);
    const int c0 = std::max(x - radius - 1, 0), c1 = std::min(x + radius + 1, level.cols - 1);
    for (int yy = r0; yy <= r1; ++yy) {
      const float* row = level.ptr<float>(yy);
      for (int c = c0; c <= c1; c += 16) __builtin_prefetch(row + c);
      __builtin_prefetch(row + c1);
    }
  }
  for (int i = -radius; i <= radius; ++i) {
    const int yy = y + i;
    if (yy <= 0 || yy >= level.rows - 1) continue;
    const int j0 = std::max(-radius, 1 - x), j1 = std::min(radius, level.cols - 2 - x);
    const int len = j1 - j0 + 1;
    const float* row = level.ptr<float>(yy) + x + j0;
    const float* wj = w + (j0 + radius);
    const float wi = w[i + radius];
    // Gradients of the row's samples, vectorisable; then the histogram, scalar.
    for (int j = 0; j < len; ++j) {
      const float dx = row[j + 1] - row[j - 1], dy = row[j - step] - row[j + step];
      mag[j] = wi * wj[j] * std::sqrt(dx * dx + dy * dy);
      bin[j] = FastAtan2(dy, dx) * to_bin + 0.5f;
    }
    for (int j = 0; j < len; ++j) {
      int b = static_cast<int>(bin[j]);
      b = b >= n ? b - n : b;
      h[b] += mag[j];
    }
  }
  h[-1] = h[n - 1];
  h[-2] = h[n - 2];
  h[n] = h[0];
  h[n + 1] = h[1];
  float best = 0;
  for (int i = 0; i < n; ++i) {
    hist[i] = (h[i - 2] + h[i + 2]) * (1.0f / 16) + (h[i - 1] + h[i + 1]) * (4.0f / 16) +
              h[i] * (6.0f / 16);
    best = std::max(best, hist[i]);
  }
  return best;
}

RGBDVO_SIMD_CLONES void SiftDescriptor(const cv::Mat& level, float x, float y, float sigma,
                                       float angle_deg, uint8_t* out) {
  // The window is centred on the pixel nearest the keypoint, as OpenCV centres it: centred on
  // the sub-pixel position the odometry was less accurate on fr1/xyz
  // (docs/decisions/0001-own-sift-guided-matching-workers.md).
  x = std::round(x);
  y = std::round(y);
  const Grid& grid = TheGrid();
  // OpenCV's descriptor angle: 360 - KeyPoint::angle, the gradient angle with y up.
  const float angle = (360.0f - angle_deg) * (kPi / 180.0f);
  const float bin_px = kBinWidth * sigma;
  const float cos_a = std::cos(angle) * bin_px, sin_a = std::sin(angle) * bin_px;
  const float* data = level.ptr<float>(0);
  const int step = static_cast<int>(level.step1()), cols = level.cols, rows = level.rows;

  // 1. The gradient at every grid sample: central differences at the 4 pixels around it,
  //    interpolated bilinearly; 0 where the sample is too close to the image edge.
  //    a) Where each sample lies, branch-free over all samples (so that it vectorises): samples
  //       too close to the edge are read at a clamped position and zeroed (mask 0).
  int at[kSamples], mask[kSamples];
  float fxs[kSamples], fys[kSamples];
  for (int s = 0; s < kSamples; ++s) {
    const float r = grid.row_offset[s], c = grid.col_offset[s];
    // Rotated bin units -> image pixels (the inverse of OpenCV's rotation of pixel offsets).
    const float px = x + cos_a * c + sin_a * r, py = y - sin_a * c + cos_a * r;
    const float fpx = std::floor(px), fpy = std::floor(py);
    const bool inside = fpx >= 1 && fpy >= 1 && fpx + 2 < cols && fpy + 2 < rows;
    const int x0 = inside ? static_cast<int>(fpx) : 1, y0 = inside ? static_cast<int>(fpy) : 1;
    at[s] = y0 * step + x0;
    fxs[s] = px - fpx;
    fys[s] = py - fpy;
    mask[s] = inside ? -1 : 0;
  }
  //    b) Per sample, the 4 x 4 pixels around it (rows y0 - 1 .. y0 + 2, columns x0 - 1 ..
  //       x0 + 2) as 4 vector loads; the 8 central differences and the bilinear interpolation
  //       by lane shuffles, each value by the same operations as one at a time. Two samples at
  //       once, one in each half of an 8-lane vector (the shuffles stay within their half).
  float dx[kSamples], dy[kSamples];
  static_assert(kSamples % 2 == 0, "samples are taken in pairs");
  for (int s = 0; s < kSamples; s += 2) {
    const float* p = data + at[s] - 1;
    const float* q = data + at[s + 1] - 1;
    v8f m, a, b, c;
    Pair(p - step, q - step, &m);
    Pair(p, q, &a);
    Pair(p + step, q + step, &b);
    Pair(p + 2 * step, q + 2 * step, &c);
    // (gx00, gx01, gx10, gx11): I(x + 1) - I(x - 1) on rows y0 and y0 + 1.
    const v8f gx = __builtin_shufflevector(a, b, 2, 3, 10, 11, 6, 7, 14, 15) -
                   __builtin_shufflevector(a, b, 0, 1, 8, 9, 4, 5, 12, 13);
    // (gy00, gy01, gy10, gy11): I(y - 1) - I(y + 1) at columns x0 and x0 + 1.
    const v8f gy = __builtin_shufflevector(m - b, a - c, 1, 2, 9, 10, 5, 6, 13, 14);
    // Columns x0 (left) and x0 + 1 (right) of (gx row y0, gx row y0 + 1, gy ..., gy ...).
    const v8f left = __builtin_shufflevector(gx, gy, 0, 2, 8, 10, 4, 6, 12, 14);
    const v8f right = __builtin_shufflevector(gx, gy, 1, 3, 9, 11, 5, 7, 13, 15);
    v8i fxi, fyi, maski;
    Spread(fxs + s, &fxi);
    Spread(fys + s, &fyi);
    Spread(mask + s, &maski);
    const v8f fx = (v8f)fxi;
    const v8f g = left + fx * (right - left);  // (gx0, gx1, gy0, gy1) of each sample
    const v8f g0 = __builtin_shufflevector(g, g, 0, 2, 0, 2, 4, 6, 4, 6);
    const v8f g1 = __builtin_shufflevector(g, g, 1, 3, 1, 3, 5, 7, 5, 7);
    const v8f fy = (v8f)fyi;
    // (dx, dy, dx, dy) of each sample, or 0.
    const v8f d = (v8f)((v8i)(g0 + fy * (g1 - g0)) & maski);
    // (dx, dx', dy, dy'): each pair stored with one move.
    const v4f out = __builtin_shufflevector(d, d, 0, 4, 1, 5);
    float pairs[4];
    std::memcpy(pairs, &out, sizeof out);
    std::memcpy(dx + s, pairs, 2 * sizeof(float));
    std::memcpy(dy + s, pairs + 2, 2 * sizeof(float));
  }
  // 2. Weighted magnitude and orientation bin relative to the keypoint's (vectorisable).
  float mag[kSamples], obin[kSamples];
  const float to_bin = kBins / (2 * kPi);
  for (int s = 0; s < kSamples; ++s) {
    mag[s] = grid.weight[s] * std::sqrt(dx[s] * dx[s] + dy[s] * dy[s]);
    float o = (FastAtan2(dy[s], dx[s]) - angle) * to_bin;
    o = o < 0 ? o + kBins : o;
    obin[s] = o >= kBins ? o - kBins : o;
  }
  // 3. Trilinear interpolation into 4 x 4 spatial x 8 orientation bins: each sample's magnitude
  //    split between its two orientation bins as an 8-vector, added into its spatial bins.
  //    a) The lower orientation bin o0 and the two shares (vectorisable).
  int lower[kSamples];
  float share0[kSamples], share1[kSamples];
  for (int s = 0; s < kSamples; ++s) {
    lower[s] = std::min(static_cast<int>(obin[s]), kBins - 1);
    share1[s] = mag[s] * (obin[s] - lower[s]);
    share0[s] = mag[s] - share1[s];
  }
  //    b) Lane o0 gets share0, lane o0 + 1 (mod 8) share1, the others 0 (TwoLanes).
  float split[kSamples][kBins];
  for (int s = 0; s < kSamples; ++s) {
    v8f v;
    TwoLanes(lower[s], share0[s], share1[s], &v);
    std::memcpy(split[s], &v, sizeof v);
  }
  float hist[kWidth * kWidth * kBins];
  for (int br = 0; br < kWidth; ++br) {
    // The kWidth bins of a row at once (independent chains of additions, in flight together);
    // per bin, two running sums (even and odd entries of its square) that are added at the end.
    v8f even[kWidth] = {}, odd[kWidth] = {};
    for (int i = 0; i < kSpan * kSpan; i += 2) {
      const float* row = split[(kPerBin * br + i / kSpan) * kGrid + i % kSpan];
      for (int bc = 0; bc < kWidth; ++bc) {
        const std::array<float, kSpan* kSpan>& w = grid.splat[br * kWidth + bc];
        even[bc] += w[i] * *At(row + kPerBin * bc * kBins);
        odd[bc] += w[i + 1] * *At(row + (kPerBin * bc + 1) * kBins);
      }
    }
    for (int bc = 0; bc < kWidth; ++bc) {
      const v8f sum = even[bc] + odd[bc];
      std::memcpy(hist + (br * kWidth + bc) * kBins, &sum, sizeof sum);
    }
  }

  NormaliseToBytes(hist, out);
}

}  // namespace rgbdvo
