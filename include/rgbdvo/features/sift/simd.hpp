#pragma once
// RGBDVO_SIMD_CLONES before a hot function compiles it twice, for x86-64-v3 (AVX2, FMA) and for
// the baseline, and picks one at load time by the CPU (GCC/Clang function multiversioning): the
// loops in it are vectorised 8 floats wide where the CPU allows, and the binary still runs
// everywhere. Elsewhere it expands to nothing.

#if defined(__x86_64__) && defined(__GNUC__) && defined(__linux__)
#define RGBDVO_SIMD_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define RGBDVO_SIMD_CLONES
#endif
