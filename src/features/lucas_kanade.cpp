#include "rgbdvo/features/lucas_kanade.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <stdexcept>
#if defined(__x86_64__)
#include <immintrin.h>
#elif defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <opencv2/video/tracking.hpp>

// The arithmetic follows OpenCV 4's lkpyramid.cpp (LKTrackerInvoker) step by step: the same
// fixed-point bilinear weights and rounding, and the float sums in the same order (its SSE2
// lanes included), so that the tracks are OpenCV's to the bit (tests/features). This file is
// compiled without contracting a * b + c into fused operations (CMakeLists.txt), as OpenCV's
// baseline build is.

namespace rgbdvo {

namespace {

constexpr int kWBits = 14;                    // bilinear weights in 1/2^14
constexpr float kFltScale = 1.f / (1 << 20);  // the sums' fixed point back to float
constexpr float kMinEigThreshold = 1e-4f;     // OpenCV's default

int Descale(int x, int n) { return (x + (1 << (n - 1))) >> n; }  // CV_DESCALE

struct Weights {
  int w00, w01, w10, w11;
};

Weights BilinearWeights(float a, float b) {
  Weights w{};
  w.w00 = cvRound((1.f - a) * (1.f - b) * (1 << kWBits));
  w.w01 = cvRound(a * (1.f - b) * (1 << kWBits));
  w.w10 = cvRound((1.f - a) * b * (1 << kWBits));
  w.w11 = (1 << kWBits) - w.w00 - w.w01 - w.w10;
  return w;
}

#if defined(__SSE2__)
// The weights as _mm_madd_epi16 operands: (w00, w01) and (w10, w11) in each pair of lanes.
struct PairedWeights {
  __m128i top, bottom;
};
PairedWeights Pair(const Weights& w) {
  const auto pair = [](int lo, int hi) {
    return _mm_set1_epi32(
        static_cast<int>((static_cast<uint32_t>(hi) << 16) | static_cast<uint16_t>(lo)));
  };
  return {pair(w.w00, w.w01), pair(w.w10, w.w11)};
}

// Eight int16 lanes sampled between four neighbours (v00 at the sample, v01 right of it, v10
// below, v11 below right) in OpenCV's fixed point: weighted, rounded, shifted right by `shift`,
// packed back to int16.
__m128i Bilinear(__m128i v00, __m128i v01, __m128i v10, __m128i v11, const PairedWeights& w,
                 int shift) {
  const __m128i round = _mm_set1_epi32(1 << (shift - 1));
  __m128i t0 =
      _mm_add_epi32(_mm_add_epi32(_mm_madd_epi16(_mm_unpacklo_epi16(v00, v01), w.top), round),
                    _mm_madd_epi16(_mm_unpacklo_epi16(v10, v11), w.bottom));
  __m128i t1 =
      _mm_add_epi32(_mm_add_epi32(_mm_madd_epi16(_mm_unpackhi_epi16(v00, v01), w.top), round),
                    _mm_madd_epi16(_mm_unpackhi_epi16(v10, v11), w.bottom));
  return _mm_packs_epi32(_mm_srai_epi32(t0, shift), _mm_srai_epi32(t1, shift));
}

// Eight pixels of an 8-bit image from p, x 32 (kWBits - 5 fraction bits kept), as int16.
__m128i BilinearPixels(const uchar* p, ptrdiff_t step, const PairedWeights& w) {
  const auto load8 = [](const uchar* q) {
    return _mm_unpacklo_epi8(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(q)),
                             _mm_setzero_si128());
  };
  return Bilinear(load8(p), load8(p + 1), load8(p + step), load8(p + step + 1), w, kWBits - 5);
}
#endif

// The derivative pyramid's level (OpenCV: pyramid[2 level + 1]) and how many levels a pyramid
// holds (without derivatives: one image per level).
int Levels(const TrackingPyramid& p) {
  const int n = static_cast<int>(p.size()) - 1;
  return HasDerivatives(p) ? n / 2 : n;
}
const cv::Mat& Image(const TrackingPyramid& p, int level) {
  return p[static_cast<size_t>(HasDerivatives(p) ? 2 * level : level)];
}

// One point's window at one level (LKTrackerInvoker before its iterations).
bool MakeWindow(const cv::Mat& I, const cv::Mat& dI, cv::Size win, cv::Point2f prev,
                int16_t* values, int16_t* derivs, float* a11, float* a12, float* a22,
                float* inv_det) {
  const cv::Point2f half((static_cast<float>(win.width) - 1) * 0.5f,
                         (static_cast<float>(win.height) - 1) * 0.5f);
  prev -= half;
  const cv::Point2i ip(cvFloor(prev.x), cvFloor(prev.y));
  if (ip.x < -win.width || ip.x >= dI.cols || ip.y < -win.height || ip.y >= dI.rows) return false;
  const Weights w =
      BilinearWeights(prev.x - static_cast<float>(ip.x), prev.y - static_cast<float>(ip.y));
  const ptrdiff_t step_i = static_cast<ptrdiff_t>(I.step[0]);
  const ptrdiff_t step_d = static_cast<ptrdiff_t>(dI.step[0] / sizeof(int16_t));
  // OpenCV sums x < width - width % 8 in four float lanes (pixel x to lane x % 4, eight pixels at
  // a time: the first four, then the next four), the rest in one float; then the lanes as
  // (l0 + l2) + (l1 + l3) onto that float.
  // OpenCV's vector loop takes eight pixels while eight are left.
  const int simd_end = win.width / 8 * 8;
  float l11[4] = {0, 0, 0, 0}, l12[4] = {0, 0, 0, 0}, l22[4] = {0, 0, 0, 0};
  float s11 = 0, s12 = 0, s22 = 0;
#if defined(__SSE2__)
  const PairedWeights pw = Pair(w);
  __m128 q11 = _mm_setzero_ps(), q12 = _mm_setzero_ps(), q22 = _mm_setzero_ps();
  // Four pixels' derivatives, bilinear, stored as (x, y) pairs and added to the sums' lanes.
  const auto four_derivs = [&](const int16_t* ds, int16_t* out) {
    const auto load = [](const int16_t* p) {
      return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
    };
    const __m128i pairs =  // x0 y0 x1 y1 x2 y2 x3 y3
        Bilinear(load(ds), load(ds + 2), load(ds + step_d), load(ds + step_d + 2), pw, kWBits);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out), pairs);
    const __m128 fx = _mm_cvtepi32_ps(_mm_srai_epi32(_mm_slli_epi32(pairs, 16), 16));
    const __m128 fy = _mm_cvtepi32_ps(_mm_srai_epi32(pairs, 16));
    q22 = _mm_add_ps(_mm_mul_ps(fy, fy), q22);
    q12 = _mm_add_ps(_mm_mul_ps(fx, fy), q12);
    q11 = _mm_add_ps(_mm_mul_ps(fx, fx), q11);
  };
#endif
  for (int y = 0; y < win.height; ++y) {
    const uchar* src = I.data + (y + ip.y) * step_i + ip.x;
    const int16_t* dsrc =
        reinterpret_cast<const int16_t*>(dI.data) + (y + ip.y) * step_d + 2 * ip.x;
    int16_t* v = values + y * win.width;
    int16_t* d = derivs + 2 * y * win.width;
    int x = 0;
#if defined(__SSE2__)
    for (; x < simd_end; x += 8) {
      _mm_storeu_si128(reinterpret_cast<__m128i*>(v + x), BilinearPixels(src + x, step_i, pw));
      four_derivs(dsrc + 2 * x, d + 2 * x);
      four_derivs(dsrc + 2 * x + 8, d + 2 * x + 8);
    }
#endif
    for (; x < win.width; ++x) {
      const int16_t* ds = dsrc + 2 * x;
      const int ival = Descale(src[x] * w.w00 + src[x + 1] * w.w01 + src[x + step_i] * w.w10 +
                                   src[x + step_i + 1] * w.w11,
                               kWBits - 5);
      const int ix = Descale(
          ds[0] * w.w00 + ds[2] * w.w01 + ds[step_d] * w.w10 + ds[step_d + 2] * w.w11, kWBits);
      const int iy = Descale(
          ds[1] * w.w00 + ds[3] * w.w01 + ds[step_d + 1] * w.w10 + ds[step_d + 3] * w.w11, kWBits);
      v[x] = static_cast<int16_t>(ival);
      d[2 * x] = static_cast<int16_t>(ix);
      d[2 * x + 1] = static_cast<int16_t>(iy);
      if (x < simd_end) {  // no SSE2: its lanes kept by hand
        const float fx = static_cast<float>(ix), fy = static_cast<float>(iy);
        const int lane = x % 4;
        l22[lane] = fy * fy + l22[lane];
        l12[lane] = fx * fy + l12[lane];
        l11[lane] = fx * fx + l11[lane];
      } else {
        s11 += static_cast<float>(ix * ix);
        s12 += static_cast<float>(ix * iy);
        s22 += static_cast<float>(iy * iy);
      }
    }
  }
#if defined(__SSE2__)
  _mm_storeu_ps(l11, q11);
  _mm_storeu_ps(l12, q12);
  _mm_storeu_ps(l22, q22);
#endif
  s11 += (l11[0] + l11[2]) + (l11[1] + l11[3]);
  s12 += (l12[0] + l12[2]) + (l12[1] + l12[3]);
  s22 += (l22[0] + l22[2]) + (l22[1] + l22[3]);
  const float A11 = s11 * kFltScale, A12 = s12 * kFltScale, A22 = s22 * kFltScale;
  const float D = A11 * A22 - A12 * A12;
  const float min_eig = (A22 + A11 - std::sqrt((A11 - A22) * (A11 - A22) + 4.f * A12 * A12)) /
                        static_cast<float>(2 * win.width * win.height);
  if (min_eig < kMinEigThreshold || D < FLT_EPSILON) return false;
  *a11 = A11;
  *a12 = A12;
  *a22 = A22;
  *inv_det = 1.f / D;
  return true;
}

// One window row's pixels x0 .. width - 1 as OpenCV's scalar loop adds them (ib: x, y sums).
// A pixel or a few a row: always inlined, a call would cost as much.
[[gnu::always_inline]] inline void MismatchTail(const uchar* jp, ptrdiff_t step_j,
                                                const int16_t* ip, const int16_t* dp, int x0,
                                                int width, const Weights& w, float* ib1,
                                                float* ib2) {
  for (int x = x0; x < width; ++x) {
    const int diff = Descale(jp[x] * w.w00 + jp[x + 1] * w.w01 + jp[x + step_j] * w.w10 +
                                 jp[x + step_j + 1] * w.w11,
                             kWBits - 5) -
                     ip[x];
    *ib1 += static_cast<float>(diff * dp[2 * x]);
    *ib2 += static_cast<float>(diff * dp[2 * x + 1]);
  }
}

#if defined(__SSE2__)
// Eight pixels' mismatch times the derivatives, as OpenCV's vector loop pairs them: the integer
// sums of pixels (0, 4), (1, 5) in p0 and (2, 6), (3, 7) in p1, each as (x, y) lanes, to float.
// diff: the eight sampled pixels less the window's; d0, d1: their eight (x, y) derivative pairs.
void PairProducts(__m128i diff, __m128i d0, __m128i d1, __m128* p0, __m128* p1) {
  const __m128i diff2 = _mm_unpacklo_epi16(diff, diff), diff1 = _mm_unpackhi_epi16(diff, diff);
  const __m128i g0 = _mm_unpacklo_epi16(d0, d1), g1 = _mm_unpackhi_epi16(d0, d1);
  const __m128i e0 = _mm_unpacklo_epi16(diff2, diff1), e1 = _mm_unpackhi_epi16(diff2, diff1);
  *p0 = _mm_cvtepi32_ps(_mm_madd_epi16(e0, g0));
  *p1 = _mm_cvtepi32_ps(_mm_madd_epi16(e1, g1));
}
#endif

#if defined(__SSE2__)
// OpenCV's float sums of a window's mismatch: lanes (x, y, x, y) filled row by row by its vector
// loop, and one float each for the pixels past it.
struct MismatchSums {
  __m128 q0 = _mm_setzero_ps(), q1 = _mm_setzero_ps();
  float b1 = 0, b2 = 0;
};

// One window row: its eight-pixel blocks (x < simd_end) as OpenCV's vector loop adds them, then
// the rest. jp: the row of J under the window; ip, dp: the window's values and derivatives.
void MismatchRow(const uchar* jp, ptrdiff_t step_j, const int16_t* ip, const int16_t* dp,
                 int simd_end, int width, const Weights& w, const PairedWeights& pw,
                 MismatchSums* s) {
  const auto load = [](const int16_t* p) {
    return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
  };
  for (int x = 0; x < simd_end; x += 8) {
    __m128 p0, p1;
    PairProducts(_mm_subs_epi16(BilinearPixels(jp + x, step_j, pw), load(ip + x)), load(dp + 2 * x),
                 load(dp + 2 * x + 8), &p0, &p1);
    s->q0 = _mm_add_ps(s->q0, p0);
    s->q1 = _mm_add_ps(s->q1, p1);
  }
  MismatchTail(jp, step_j, ip, dp, simd_end, width, w, &s->b1, &s->b2);
}

// The lanes onto the floats: lanes 0 and 2 hold the x sums, 1 and 3 the y sums.
void FinishSums(const MismatchSums& s, float* b1, float* b2) {
  float q[4];
  _mm_storeu_ps(q, _mm_add_ps(s.q0, s.q1));
  *b1 = (s.b1 + (q[0] + q[2])) * kFltScale;
  *b2 = (s.b2 + (q[1] + q[3])) * kFltScale;
}
#endif

#if defined(__x86_64__) && defined(__GNUC__)
#define RGBDVO_LK_AVX2 1
bool HasAvx2() {
  static const bool has = __builtin_cpu_supports("avx2") != 0;
  return has;
}

// 8 pixels of row a, then 8 of row b, as 16 int16 lanes.
__attribute__((target("avx2"))) __m256i TwoRows(const uchar* a, const uchar* b) {
  return _mm256_cvtepu8_epi16(
      _mm_unpacklo_epi64(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(a)),
                         _mm_loadl_epi64(reinterpret_cast<const __m128i*>(b))));
}
// 8 int16 of a, then 8 of b.
__attribute__((target("avx2"))) __m256i TwoRows(const int16_t* a, const int16_t* b) {
  return _mm256_inserti128_si256(
      _mm256_castsi128_si256(_mm_loadu_si128(reinterpret_cast<const __m128i*>(a))),
      _mm_loadu_si128(reinterpret_cast<const __m128i*>(b)), 1);
}

// Mismatch for windows of one eight-pixel block a row (9 to 15 px wide), two rows at a time: the
// integer work of both rows in one 256-bit pass, their float products still added row by row, so
// the sums are the same.
__attribute__((target("avx2"))) void MismatchTwoRows(const cv::Mat& J, cv::Size win, cv::Point2i at,
                                                     const Weights& w, const int16_t* values,
                                                     const int16_t* derivs, float* b1, float* b2) {
  const ptrdiff_t step_j = static_cast<ptrdiff_t>(J.step[0]);
  const PairedWeights pw = Pair(w);
  const __m256i top = _mm256_broadcastsi128_si256(pw.top);
  const __m256i bottom = _mm256_broadcastsi128_si256(pw.bottom);
  const __m256i round = _mm256_set1_epi32(1 << (kWBits - 5 - 1));
  MismatchSums s;
  int y = 0;
  for (; y + 1 < win.height; y += 2) {
    const uchar* r0 = J.data + (y + at.y) * step_j + at.x;
    const uchar* r1 = r0 + step_j;
    const uchar* r2 = r1 + step_j;
    const __m256i v00 = TwoRows(r0, r1), v01 = TwoRows(r0 + 1, r1 + 1);
    const __m256i v10 = TwoRows(r1, r2), v11 = TwoRows(r1 + 1, r2 + 1);
    __m256i t0 = _mm256_add_epi32(
        _mm256_add_epi32(_mm256_madd_epi16(_mm256_unpacklo_epi16(v00, v01), top), round),
        _mm256_madd_epi16(_mm256_unpacklo_epi16(v10, v11), bottom));
    __m256i t1 = _mm256_add_epi32(
        _mm256_add_epi32(_mm256_madd_epi16(_mm256_unpackhi_epi16(v00, v01), top), round),
        _mm256_madd_epi16(_mm256_unpackhi_epi16(v10, v11), bottom));
    const __m256i sampled =
        _mm256_packs_epi32(_mm256_srai_epi32(t0, kWBits - 5), _mm256_srai_epi32(t1, kWBits - 5));
    const int16_t* ip0 = values + y * win.width;
    const int16_t* ip1 = ip0 + win.width;
    const int16_t* dp0 = derivs + 2 * y * win.width;
    const int16_t* dp1 = dp0 + 2 * win.width;
    const __m256i diff = _mm256_subs_epi16(sampled, TwoRows(ip0, ip1));
    const __m256i d0 = TwoRows(dp0, dp1), d1 = TwoRows(dp0 + 8, dp1 + 8);
    const __m256i diff2 = _mm256_unpacklo_epi16(diff, diff);
    const __m256i diff1 = _mm256_unpackhi_epi16(diff, diff);
    const __m256i g0 = _mm256_unpacklo_epi16(d0, d1), g1 = _mm256_unpackhi_epi16(d0, d1);
    const __m256i e0 = _mm256_unpacklo_epi16(diff2, diff1);
    const __m256i e1 = _mm256_unpackhi_epi16(diff2, diff1);
    const __m256 p0 = _mm256_cvtepi32_ps(_mm256_madd_epi16(e0, g0));
    const __m256 p1 = _mm256_cvtepi32_ps(_mm256_madd_epi16(e1, g1));
    s.q0 = _mm_add_ps(s.q0, _mm256_castps256_ps128(p0));
    s.q1 = _mm_add_ps(s.q1, _mm256_castps256_ps128(p1));
    MismatchTail(r0, step_j, ip0, dp0, 8, win.width, w, &s.b1, &s.b2);
    s.q0 = _mm_add_ps(s.q0, _mm256_extractf128_ps(p0, 1));
    s.q1 = _mm_add_ps(s.q1, _mm256_extractf128_ps(p1, 1));
    MismatchTail(r1, step_j, ip1, dp1, 8, win.width, w, &s.b1, &s.b2);
  }
  for (; y < win.height; ++y)
    MismatchRow(J.data + (y + at.y) * step_j + at.x, step_j, values + y * win.width,
                derivs + 2 * y * win.width, 8, win.width, w, pw, &s);
  FinishSums(s, b1, b2);
}
#endif

// b = the window's mismatch in J at `at` (its top-left corner, inside J's border) times the
// window's derivatives, as OpenCV sums it.
void Mismatch(const cv::Mat& J, cv::Size win, cv::Point2i at, const Weights& w,
              const int16_t* values, const int16_t* derivs, float* b1, float* b2) {
  const ptrdiff_t step_j = static_cast<ptrdiff_t>(J.step[0]);
  // OpenCV's vector loop takes eight pixels while eight are left.
  const int simd_end = win.width / 8 * 8;
#if defined(RGBDVO_LK_AVX2)
  if (simd_end == 8 && HasAvx2()) {
    MismatchTwoRows(J, win, at, w, values, derivs, b1, b2);
    return;
  }
#endif
#if defined(__SSE2__)
  const PairedWeights pw = Pair(w);
  MismatchSums s;
  for (int y = 0; y < win.height; ++y)
    MismatchRow(J.data + (y + at.y) * step_j + at.x, step_j, values + y * win.width,
                derivs + 2 * y * win.width, simd_end, win.width, w, pw, &s);
  FinishSums(s, b1, b2);
#else
  float ib1 = 0, ib2 = 0;
  for (int y = 0; y < win.height; ++y)
    MismatchTail(J.data + (y + at.y) * step_j + at.x, step_j, values + y * win.width,
                 derivs + 2 * y * win.width, 0, win.width, w, &ib1, &ib2);
  *b1 = ib1 * kFltScale;
  *b2 = ib2 * kFltScale;
#endif
}

}  // namespace

bool HasDerivatives(const TrackingPyramid& p) {
  return p.size() > 1 && p.size() % 2 == 0 &&
         p[1].type() == CV_MAKETYPE(CV_16S, 2 * p[0].channels());
}

LkWindows MakeLkWindows(const TrackingPyramid& from, cv::Size window, int levels,
                        const std::vector<cv::Point2f>& points) {
  if (from.empty() || !HasDerivatives(from) || from[0].type() != CV_8UC1)
    throw std::invalid_argument(
        "Lucas-Kanade: windows are made from a CV_8UC1 pyramid with derivatives");
  if (window.width < 3 || window.height < 3)
    throw std::invalid_argument("Lucas-Kanade: window below 3 px");
  LkWindows w;
  w.window = window;
  w.levels = std::min(std::max(levels, 0), Levels(from));
  w.from = from;
  w.points = points;
  const size_t n = points.size(), slots = n * static_cast<size_t>(w.levels + 1);
  const size_t area = static_cast<size_t>(window.area());
  w.usable.assign(slots, 0);
  w.a11.assign(slots, 0);
  w.a12.assign(slots, 0);
  w.a22.assign(slots, 0);
  w.inv_det.assign(slots, 0);
  w.values.assign(slots * area, 0);
  w.derivs.assign(2 * slots * area, 0);
  for (int level = 0; level <= w.levels; ++level) {
    const cv::Mat& I = from[2 * static_cast<size_t>(level)];
    const cv::Mat& dI = from[2 * static_cast<size_t>(level) + 1];
    const float scale = static_cast<float>(1. / (1 << level));
    for (size_t i = 0; i < n; ++i) {
      const size_t s = static_cast<size_t>(level) * n + i;
      w.usable[s] =
          MakeWindow(I, dI, window, points[i] * scale, &w.values[s * area], &w.derivs[2 * s * area],
                     &w.a11[s], &w.a12[s], &w.a22[s], &w.inv_det[s])
              ? 1
              : 0;
    }
  }
  return w;
}

void TrackLkWindows(const LkWindows& w, const TrackingPyramid& to, int max_iterations,
                    double epsilon, std::vector<cv::Point2f>* next, std::vector<uchar>* found) {
  const size_t n = w.points.size();
  if (next->size() != n) throw std::invalid_argument("Lucas-Kanade: one start per point");
  found->assign(n, 1);
  if (n == 0) return;
  const int max_level = std::min(w.levels, Levels(to));
  max_iterations = std::min(std::max(max_iterations, 0), 100);
  epsilon = std::min(std::max(epsilon, 0.), 10.);
  epsilon *= epsilon;
#if !defined(__SSE2__)
  cv::calcOpticalFlowPyrLK(w.from, to, w.points, *next, *found, cv::noArray(), w.window, max_level,
                           cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS,
                                            max_iterations, std::sqrt(epsilon)),
                           cv::OPTFLOW_USE_INITIAL_FLOW);
  return;
#endif
  const cv::Size win = w.window;
  const cv::Point2f half((static_cast<float>(win.width) - 1) * 0.5f,
                         (static_cast<float>(win.height) - 1) * 0.5f);
  const size_t area = static_cast<size_t>(win.area());
  for (size_t i = 0; i < n; ++i) {
    cv::Point2f& out = (*next)[i];
    for (int level = max_level; level >= 0; --level) {
      const cv::Mat& J = Image(to, level);
      cv::Point2f at = level == max_level ? out * static_cast<float>(1. / (1 << level)) : out * 2.f;
      out = at;
      const size_t s = static_cast<size_t>(level) * n + i;
      if (!w.usable[s]) {
        if (level == 0) (*found)[i] = 0;
        continue;
      }
      const float A11 = w.a11[s], A12 = w.a12[s], A22 = w.a22[s], D = w.inv_det[s];
      const int16_t* values = &w.values[s * area];
      const int16_t* derivs = &w.derivs[2 * s * area];
      at -= half;
      cv::Point2f prev_delta;
      for (int j = 0; j < max_iterations; ++j) {
        const cv::Point2i ia(cvFloor(at.x), cvFloor(at.y));
        if (ia.x < -win.width || ia.x >= J.cols || ia.y < -win.height || ia.y >= J.rows) {
          if (level == 0) (*found)[i] = 0;
          break;
        }
        const Weights wt =
            BilinearWeights(at.x - static_cast<float>(ia.x), at.y - static_cast<float>(ia.y));
        float b1 = 0, b2 = 0;
        Mismatch(J, win, ia, wt, values, derivs, &b1, &b2);
        const cv::Point2f delta((A12 * b2 - A22 * b1) * D, (A12 * b1 - A11 * b2) * D);
        at += delta;
        out = at + half;
        if (delta.ddot(delta) <= epsilon) break;
        if (j > 0 && std::abs(delta.x + prev_delta.x) < 0.01 &&
            std::abs(delta.y + prev_delta.y) < 0.01) {
          out -= delta * 0.5f;
          break;
        }
        prev_delta = delta;
      }
    }
  }
}

}  // namespace rgbdvo
