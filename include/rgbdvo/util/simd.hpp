#pragma once
// RGBDVO_SIMD_CLONES before a hot function compiles it twice, for x86-64-v3 (AVX2, FMA) and for
// the baseline, and picks one at load time by the CPU (GCC/Clang function multiversioning): the
// loops in it are vectorised 8 floats wide where the CPU allows, and the binary still runs
// everywhere. Elsewhere it expands to nothing, and under ThreadSanitizer: the load-time choice
// (an ifunc resolver) runs before the sanitizer's runtime is set up, and crashes it.

#if defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define RGBDVO_UNDER_TSAN 1
#endif
#endif
#if defined(__SANITIZE_THREAD__)
#define RGBDVO_UNDER_TSAN 1
#endif

#if defined(__x86_64__) && defined(__GNUC__) && defined(__linux__) && !defined(RGBDVO_UNDER_TSAN)
#define RGBDVO_SIMD_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define RGBDVO_SIMD_CLONES
#endif
