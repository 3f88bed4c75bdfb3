#pragma once
// How many droplets a thread steps together, for the vector width in use
// (constraint_vector_width()). Every choice here changes speed only: each droplet gets the same
// bits however many step beside it. The measurements behind each number: bench/README.md,
// "Constants of the step" and "Lanes of a search".

#include <cstddef>

#include "softdrop/droplet.hpp"

namespace softdrop {

/// Rings apply_length_constraint_interleaved takes at once: a ring per vector lane, up to three
/// registers side by side (24 with AVX-512, 12 with AVX, 6 with SSE2, 1 without).
int interleaved_ring_capacity();

/// Droplets per thread that run_interleaved steps fastest together: 24 with AVX-512 or AVX, which
/// step them as lane-by-lane blocks of up to three groups of eight; otherwise
/// interleaved_ring_capacity(). The default of BatchOptions::lanes.
int interleaved_lanes();

/// The fewest droplets worth a lane-by-lane block with `width`; fewer step faster one by one:
/// 3 with AVX-512, 6 with AVX (whose groups of eight are two registers each).
std::size_t fewest_block_droplets(VectorWidth width);

/// Droplets each thread of a speculating search steps together, when its options leave it to the
/// program: `per_generation` candidates a generation, `threads` threads. 8 on 1 and 2 threads; 4
/// at per_generation = 1 with SSE2 alone (there the lanes only hide the sequential constraint's
/// chain). With the red-black order, 1 with SSE2 alone and with AVX at per_generation = 1 on
/// several threads. More threads keep the droplets in flight of 2 threads, over fewer lanes each:
/// more lanes run further ahead, so more speculative work is thrown away, and slow each droplet,
/// which delays the decisions the rest waits for.
int speculative_lanes(int per_generation, int threads, ConstraintOrder order);

}  // namespace softdrop
