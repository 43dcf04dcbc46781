#include "rgbdvo/features/sift/gaussian_blur.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "rgbdvo/util/simd.hpp"

namespace rgbdvo {
namespace {

// 8 floats, GCC/Clang vector extension: one AVX register where the CPU has them, two SSE
// registers otherwise. Loaded through a type of any alignment that may alias the floats; never
// passed by value between functions, since the AVX2 clone and the baseline would pass it in
// different registers (clang refuses such calls).
typedef float v8f __attribute__((vector_size(32)));
typedef float v8f_unaligned __attribute__((vector_size(32), aligned(4), may_alias));
// The 8 floats at p, read as `*At(p)`.
inline const v8f_unaligned* At(const float* p) { return reinterpret_cast<const v8f_unaligned*>(p); }
inline void Store(float* p, const v8f& v) { std::memcpy(p, &v, sizeof v); }

// Index i of a row or column of n reflected without repeating the edge: -1 -> 1, n -> n - 2.
int Reflect101(int i, int n) {
  if (n == 1) return 0;
  while (i < 0 || i >= n) i = i < 0 ? -i : 2 * n - 2 - i;
  return i;
}

// out[x] = sum_j k[|j|] in[x + j], j = -r..r, for x in [0, cols); `in` is valid on [-r, cols + r).
RGBDVO_SIMD_CLONES void BlurRow(const float* in, float* out, int cols, const float* k, int r) {
  int x = 0;
  for (; x + 32 <= cols; x += 32) {  // 4 accumulators: fewer loads of k per output
    const float* p = in + x;
    v8f a = k[0] * *At(p), b = k[0] * *At(p + 8), c = k[0] * *At(p + 16), d = k[0] * *At(p + 24);
    for (int j = 1; j <= r; ++j) {
      const float kj = k[j];
      a += kj * (*At(p - j) + *At(p + j));
      b += kj * (*At(p + 8 - j) + *At(p + 8 + j));
      c += kj * (*At(p + 16 - j) + *At(p + 16 + j));
      d += kj * (*At(p + 24 - j) + *At(p + 24 + j));
    }
    Store(out + x, a);
    Store(out + x + 8, b);
    Store(out + x + 16, c);
    Store(out + x + 24, d);
  }
  for (; x < cols; ++x) {
    float a = k[0] * in[x];
    for (int j = 1; j <= r; ++j) a += k[j] * (in[x - j] + in[x + j]);
    out[x] = a;
  }
}

// out[x] = sum_j k[|j|] rows[r + j][x]; diff[x] = out[x] - src[x] when diff is not null.
RGBDVO_SIMD_CLONES void BlurColumns(const float* const* rows, float* out, const float* src,
                                    float* diff, int cols, const float* k, int r) {
  const float* centre = rows[r];
  int x = 0;
  for (; x + 32 <= cols; x += 32) {  // 4 accumulators: fewer loads of k and row pointers
    v8f a = k[0] * *At(centre + x), b = k[0] * *At(centre + x + 8), c = k[0] * *At(centre + x + 16),
        d = k[0] * *At(centre + x + 24);
    for (int j = 1; j <= r; ++j) {
      const float kj = k[j];
      const float* up = rows[r - j] + x;
      const float* down = rows[r + j] + x;
      a += kj * (*At(up) + *At(down));
      b += kj * (*At(up + 8) + *At(down + 8));
      c += kj * (*At(up + 16) + *At(down + 16));
      d += kj * (*At(up + 24) + *At(down + 24));
    }
    Store(out + x, a);
    Store(out + x + 8, b);
    Store(out + x + 16, c);
    Store(out + x + 24, d);
    if (diff) {
      Store(diff + x, a - *At(src + x));
      Store(diff + x + 8, b - *At(src + x + 8));
      Store(diff + x + 16, c - *At(src + x + 16));
      Store(diff + x + 24, d - *At(src + x + 24));
    }
  }
  for (; x < cols; ++x) {
    float a = k[0] * centre[x];
    for (int j = 1; j <= r; ++j) a += k[j] * (rows[r - j][x] + rows[r + j][x]);
    out[x] = a;
    if (diff) diff[x] = a - src[x];
  }
}

// Two output rows at once from rows[0 .. 2r + 1]: out0 is centred on rows[r], out1 on
// rows[r + 1]; out_i[x] = sum_j k[|j|] rows[r + i + j][x], diff_i[x] = out_i[x] - src_i[x] when
// diff0 (and diff1) are not null. The 2r rows both outputs need are read once from memory
// (cache) instead of twice. Each output takes exactly the operations, in the same order, that
// it would take alone, so the two rows are bit-identical to two single-row passes.
RGBDVO_SIMD_CLONES void BlurColumns2(const float* const* rows, float* out0, float* out1,
                                     const float* src0, const float* src1, float* diff0,
                                     float* diff1, int cols, const float* k, int r) {
  const float* c0 = rows[r];
  const float* c1 = rows[r + 1];
  int x = 0;
  for (; x + 32 <= cols; x += 32) {  // 4 accumulators per output row
    v8f a = k[0] * *At(c0 + x), b = k[0] * *At(c0 + x + 8), c = k[0] * *At(c0 + x + 16),
        d = k[0] * *At(c0 + x + 24);
    v8f e = k[0] * *At(c1 + x), f = k[0] * *At(c1 + x + 8), g = k[0] * *At(c1 + x + 16),
        h = k[0] * *At(c1 + x + 24);
    for (int j = 1; j <= r; ++j) {
      const float kj = k[j];
      const float* up0 = rows[r - j] + x;
      const float* down0 = rows[r + j] + x;
      const float* up1 = rows[r + 1 - j] + x;
      const float* down1 = rows[r + 1 + j] + x;
      a += kj * (*At(up0) + *At(down0));
      b += kj * (*At(up0 + 8) + *At(down0 + 8));
      c += kj * (*At(up0 + 16) + *At(down0 + 16));
      d += kj * (*At(up0 + 24) + *At(down0 + 24));
      e += kj * (*At(up1) + *At(down1));
      f += kj * (*At(up1 + 8) + *At(down1 + 8));
      g += kj * (*At(up1 + 16) + *At(down1 + 16));
      h += kj * (*At(up1 + 24) + *At(down1 + 24));
    }
    Store(out0 + x, a);
    Store(out0 + x + 8, b);
    Store(out0 + x + 16, c);
    Store(out0 + x + 24, d);
    Store(out1 + x, e);
    Store(out1 + x + 8, f);
    Store(out1 + x + 16, g);
    Store(out1 + x + 24, h);
    if (diff0) {
      Store(diff0 + x, a - *At(src0 + x));
      Store(diff0 + x + 8, b - *At(src0 + x + 8));
      Store(diff0 + x + 16, c - *At(src0 + x + 16));
      Store(diff0 + x + 24, d - *At(src0 + x + 24));
      Store(diff1 + x, e - *At(src1 + x));
      Store(diff1 + x + 8, f - *At(src1 + x + 8));
      Store(diff1 + x + 16, g - *At(src1 + x + 16));
      Store(diff1 + x + 24, h - *At(src1 + x + 24));
    }
  }
  for (; x < cols; ++x) {
    float a = k[0] * c0[x];
    for (int j = 1; j <= r; ++j) a += k[j] * (rows[r - j][x] + rows[r + j][x]);
    out0[x] = a;
    if (diff0) diff0[x] = a - src0[x];
  }
  for (x = cols - cols % 32; x < cols; ++x) {
    float a = k[0] * c1[x];
    for (int j = 1; j <= r; ++j) a += k[j] * (rows[r + 1 - j][x] + rows[r + 1 + j][x]);
    out1[x] = a;
    if (diff1) diff1[x] = a - src1[x];
  }
}

}  // namespace

void GaussianBlur32f(const cv::Mat& src, cv::Mat& dst, double sigma, int radius,
                     cv::Mat* difference) {
  if (src.type() != CV_32FC1) throw std::invalid_argument("GaussianBlur32f: src must be CV_32FC1");
  if (!(sigma > 0) || radius < 1)
    throw std::invalid_argument("GaussianBlur32f: sigma must be > 0 and radius >= 1");
  const int rows = src.rows, cols = src.cols;
  dst.create(rows, cols, CV_32F);
  if (difference) difference->create(rows, cols, CV_32F);
  if (dst.data == src.data) throw std::invalid_argument("GaussianBlur32f: dst must not be src");

  std::vector<float> kernel(radius + 1);
  double sum = 0;
  for (int j = 0; j <= radius; ++j) sum += (j ? 2 : 1) * std::exp(-0.5 * j * j / (sigma * sigma));
  for (int j = 0; j <= radius; ++j)
    kernel[j] = static_cast<float>(std::exp(-0.5 * j * j / (sigma * sigma)) / sum);

  // Horizontally blurred rows, in a ring of 2r + 2 (the rows two output rows need), each row
  // blurred once; the image's row is copied with r reflected pixels on each side first. The
  // rows of a window, once reflected, are distinct and span at most 2r + 2 indices, so they
  // never share a slot.
  const int ring = 2 * radius + 2;
  std::vector<float> padded(cols + 2 * radius), blurred(static_cast<size_t>(ring) * cols);
  std::vector<int> slot_row(ring, -1);
  std::vector<const float*> window(ring);
  const auto horizontal = [&](int y) -> const float* {
    y = Reflect101(y, rows);
    const int slot = y % ring;
    float* out = blurred.data() + static_cast<size_t>(slot) * cols;
    if (slot_row[slot] != y) {
      const float* in = src.ptr<float>(y);
      std::memcpy(padded.data() + radius, in, cols * sizeof(float));
      for (int j = 1; j <= radius; ++j) {
        padded[radius - j] = in[Reflect101(-j, cols)];
        padded[radius + cols - 1 + j] = in[Reflect101(cols - 1 + j, cols)];
      }
      BlurRow(padded.data() + radius, out, cols, kernel.data(), radius);
      slot_row[slot] = y;
    }
    return out;
  };
  const auto diff_row = [&](int y) { return difference ? difference->ptr<float>(y) : nullptr; };
  int y = 0;
  for (; y + 2 <= rows; y += 2) {
    for (int j = -radius; j <= radius + 1; ++j) window[j + radius] = horizontal(y + j);
    BlurColumns2(window.data(), dst.ptr<float>(y), dst.ptr<float>(y + 1), src.ptr<float>(y),
                 src.ptr<float>(y + 1), diff_row(y), diff_row(y + 1), cols, kernel.data(), radius);
  }
  if (y < rows) {
    for (int j = -radius; j <= radius; ++j) window[j + radius] = horizontal(y + j);
    BlurColumns(window.data(), dst.ptr<float>(y), src.ptr<float>(y), diff_row(y), cols,
                kernel.data(), radius);
  }
}

}  // namespace rgbdvo
