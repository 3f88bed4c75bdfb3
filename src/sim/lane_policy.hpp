#pragma once
// The step's vector width, and how many droplets a thread steps together for it. Every choice here
// changes speed only: each droplet gets the same bits at every width and however many step beside
// it. The measurements behind each number: bench/README.md, "Constants of the step" and "Lanes of a
// search". Private to the library: tests and benchmarks include it to check and time the widths.

#include <cstddef>

#include "softdrop/droplet.hpp"

namespace softdrop {

/// The sequential order on several rings at once: each ring ends exactly as
/// apply_length_constraint(ring, ..., ConstraintOrder::sequential) leaves it, and corrections[r]
/// is its return value. The sequential pass is a chain of dependent square roots and divisions;
/// the chains of different rings are independent. With AVX-512 or AVX, rings of one size go link
/// by link together, up to interleaved_lanes() of them, as lanes of the lane-by-lane layout
/// (lane_layout.hpp); otherwise one after another.
void apply_length_constraint_interleaved(DropletState* const* rings, int count, double rest_length, double max_strain,
                                         int iterations, int* corrections);

/// Vector width of the step's vector code (the constraint and the spring forces): doubles per
/// instruction. Every width gives the same bits, since each lane does the scalar operations in the
/// same order; the widest the processor has (AVX-512 where it has AVX-512F, else AVX on most
/// x86-64 since 2011, else SSE2, which every x86-64 has) is found at start-up. AVX-512 serves the
/// red-black constraint (eight springs at once); the rest uses AVX at that width. With AVX-512 or
/// AVX, run_interleaved steps droplets as lane-by-lane blocks (eight droplets to a group).
enum class VectorWidth { scalar = 1, sse2 = 2, avx = 4, avx512 = 8 };
VectorWidth constraint_vector_width();
/// Uses at most `width` from now on (never more than the processor has), for all threads; returns
/// the width in use. For tests and benchmarks that check or time the narrower paths.
VectorWidth limit_constraint_vector_width(VectorWidth width);

/// Droplets per thread that run_interleaved steps fastest together: 24 with AVX-512 or AVX, which
/// step them as lane-by-lane blocks of up to three groups of eight (and constrain the others' rings
/// as lanes too); otherwise 1. The default of BatchOptions::lanes.
int interleaved_lanes();
/// BatchOptions::lanes as a batch steps them: `requested`, or interleaved_lanes() when it is 0.
int batch_lanes(int requested);

/// The fewest droplets worth a lane-by-lane block (with AVX-512 or AVX): 3. Fewer step faster
/// one by one.
std::size_t fewest_block_droplets();
/// The fewest rings of one size apply_length_constraint_interleaved constrains as lanes with
/// `width`; fewer go one by one, which is faster: 3 with AVX-512, 4 with AVX.
int fewest_lane_rings(VectorWidth width);

/// Droplets each thread of a speculating search steps together, when its options leave it to the
/// program: `per_generation` candidates a generation, `threads` threads. 8 on 1 and 2 threads; 1
/// with SSE2 alone, where the droplets step one at a time, and with the red-black order and AVX at
/// per_generation = 1 on several threads. More threads keep the droplets in flight of 2 threads, over fewer lanes each:
/// more lanes run further ahead, so more speculative work is thrown away, and slow each droplet,
/// which delays the decisions the rest waits for.
int speculative_lanes(int per_generation, int threads, ConstraintOrder order);

}  // namespace softdrop
