#include "rgbdvo/util/image_heap.hpp"

#include <catch2/catch.hpp>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#if defined(__linux__)
#include <unistd.h>
#endif

using namespace rgbdvo;

namespace {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kOwnMalloc = false;  // the sanitizer's allocator replaces glibc's
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
constexpr bool kOwnMalloc = false;
#else
constexpr bool kOwnMalloc = true;
#endif
#else
constexpr bool kOwnMalloc = true;
#endif

struct Mapping {
  std::uintptr_t begin = 0, end = 0;
  bool heap = false, huge_pages = false;
};

// The mapping of this process that holds the address `at`, from /proc/self/smaps.
Mapping MappingOf(std::uintptr_t at) {
  std::ifstream smaps("/proc/self/smaps");
  Mapping found, current;
  std::string line;
  while (std::getline(smaps, line)) {
    std::uintptr_t begin = 0, end = 0;
    char dash = 0;
    std::istringstream header(line);
    if (header >> std::hex >> begin >> dash >> end && dash == '-') {
      current = Mapping{begin, end, line.find("[heap]") != std::string::npos, false};
    } else if (line.rfind("VmFlags:", 0) == 0) {
      current.huge_pages = line.find(" hg") != std::string::npos;
      if (current.begin <= at && at < current.end) found = current;
    }
  }
  return found;
}

}  // namespace

TEST_CASE("The image heap keeps large blocks in the heap and advises its new room to huge pages") {
  const size_t bytes = size_t{64} << 20;
  const size_t advised = SetUpImageHeap(bytes);
#if defined(__GLIBC__) && defined(__linux__)
  if (!kOwnMalloc) {
    // Another allocator serves malloc: the heap is not glibc's to set up, nothing is advised.
    CHECK(advised == 0);
    return;
  }
  if (!std::ifstream("/sys/kernel/mm/transparent_hugepage/enabled")) {
    CHECK(advised == 0);
    return;
  }
  // Whole huge pages of the room the heap grew by: all of it but the alignment at either end.
  CHECK(advised % (size_t{2} << 20) == 0);
  CHECK(advised + (size_t{4} << 20) >= bytes);
  CHECK(advised <= bytes + (size_t{2} << 20));
  // A block of a few images now comes from the heap (glibc maps blocks this large by itself by
  // default), and the heap's new room is advised.
  void* block = std::malloc(size_t{8} << 20);
  REQUIRE(block != nullptr);
  const Mapping holder = MappingOf(reinterpret_cast<std::uintptr_t>(block));
  std::free(block);
  CHECK(holder.heap);
  // The heap's last whole huge page (the room ends at its end, aligned down).
  const std::uintptr_t end =
      reinterpret_cast<std::uintptr_t>(sbrk(0)) / (size_t{2} << 20) * (size_t{2} << 20);
  const Mapping top = MappingOf(end - 1);
  CHECK(top.heap);
  CHECK(top.huge_pages);
  CHECK(top.end - top.begin >= advised);
#else
  CHECK(advised == 0);
#endif
}
