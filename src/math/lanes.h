// Small fixed-width vectors of doubles, floats and integers (GCC's vector extensions, which
// clang shares): arithmetic, comparisons (-1 / 0 per lane) and __builtin_convertvector work lane
// by lane, and the code is compiled for the target of the function it is inlined into — two
// SSE2 halves or one AVX register — so per-ray set-ups written once serve every instruction set
// of the BVH's traversal (accel/bvh_traversal.inc). A cast between two of these types of one
// size reinterprets the bits. Pass them by reference across functions: a 32-byte vector by
// value has a different ABI with and without AVX (GCC's -Wpsabi).
#pragma once

#include <cstdint>

namespace candela {

using Double4 = double __attribute__((vector_size(32)));
using Int64x4 = int64_t __attribute__((vector_size(32)));
using Float4 = float __attribute__((vector_size(16)));
using Int32x4 = int32_t __attribute__((vector_size(16)));

}  // namespace candela
