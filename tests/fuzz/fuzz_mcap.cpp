// Fuzz target: the MCAP reader (every record to the footer, chunks decompressed) and, on the
// same input read as <compression byte><declared size u16><data>, the chunk decompression on
// its own, so that mutations reach the zstd and lz4 paths without a valid file around them.
// The seeds have their CRCs zeroed (not checked) so mutations get past them.
#include <exception>

#include "fuzz_input.hpp"
#include "rgbdvo/io/mcap_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  rgbdvo::McapReaderOptions options;
  options.max_record_bytes = 16 << 20;  // a bound well inside libFuzzer's memory limit
  try {
    rgbdvo::McapReader reader(rgbdvo::fuzz::InputFile(data, size, ".mcap"), options);
    while (reader.Next()) {
    }
  } catch (const std::exception&) {
    // refused with a message: expected
  }
  if (size >= 3) {
    const char* compression = data[0] % 3 == 0 ? "" : data[0] % 3 == 1 ? "zstd" : "lz4";
    const uint64_t declared = data[1] | uint64_t{data[2]} << 8;
    try {
      const std::vector<uint8_t> out =
          rgbdvo::DecompressMcapChunk(compression, data + 3, size - 3, declared);
      if (out.size() != declared) __builtin_trap();  // the size is checked
    } catch (const std::exception&) {
      // refused with a message: expected
    }
  }
  return 0;
}
