#include "rgbdvo/util/huge_page_buffer.hpp"

#include <catch2/catch.hpp>
#include <cstdint>
#include <utility>

using namespace rgbdvo;

TEST_CASE("A huge-page buffer holds what was asked on a huge page boundary and moves") {
  const HugePageBuffer empty;
  CHECK(empty.data() == nullptr);
  CHECK(empty.size() == 0);
  const size_t n = 3 * (size_t{1} << 20) + 5;  // 12 MiB and a little: not a whole huge page
  HugePageBuffer buffer(n);
  REQUIRE(buffer.data() != nullptr);
  CHECK(buffer.size() == n);
  CHECK(reinterpret_cast<std::uintptr_t>(buffer.data()) % (size_t{2} << 20) == 0);
  for (size_t i = 0; i < n; i += 4096) buffer.data()[i] = static_cast<float>(i);
  buffer.data()[n - 1] = -1.0f;
  float* const at = buffer.data();
  HugePageBuffer moved = std::move(buffer);
  CHECK(moved.data() == at);
  CHECK(moved.size() == n);
  CHECK(moved.data()[4096 * 100] == 4096.0f * 100);
  CHECK(moved.data()[n - 1] == -1.0f);
}
