#pragma once
// Run-time choice of vector code (internal). AVX code is compiled for functions marked
// SOFTDROP_AVX only, and run only where the processor has AVX (constraint_vector_width() says
// which width is in use), so the default build still runs on any x86-64.

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && defined(__SSE2__) && (defined(__GNUC__) || defined(__clang__))
#define SOFTDROP_AVX_DISPATCH 1
#define SOFTDROP_AVX __attribute__((target("avx")))
#include <immintrin.h>
#endif
