#pragma once
// Run-time choice of vector code (internal). AVX and AVX-512 code is compiled for functions marked
// SOFTDROP_AVX or SOFTDROP_AVX512 only, and run only where the processor has it
// (constraint_vector_width() says which width is in use), so the default build still runs on any
// x86-64.

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && defined(__SSE2__) && (defined(__GNUC__) || defined(__clang__))
#define SOFTDROP_AVX_DISPATCH 1
#define SOFTDROP_AVX __attribute__((target("avx")))
#define SOFTDROP_AVX512 __attribute__((target("avx512f")))
#include <immintrin.h>

#include "lane_policy.hpp"
#endif
