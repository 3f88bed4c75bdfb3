#pragma once
// Rings laid out lane by lane (internal): up to kMaxLaneRegisters x 8 rings of n masses each,
// mass i of ring t at X[i * L + t], L = 8 x registers, so one group of eight lanes (an AVX-512
// register, or two AVX ones) holds mass i of eight rings. The functions here run AVX-512 or AVX
// code (stages_wide.cpp, lane_kernels.inc), whichever constraint_vector_width() says: call them
// only where it is at least VectorWidth::avx. Each lane gets the operations the one-ring code does,
// in the same order, so each ring gets the same bits with either.

#include <cstddef>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "lane_policy.hpp"
#include "simd_dispatch.hpp"  // SOFTDROP_AVX_DISPATCH: where these functions are defined
#include "softdrop/droplet.hpp"
#include "step_context.hpp"

namespace softdrop::lanes {

constexpr int kMaxLaneRegisters = 3;
constexpr int kMaxLanes = 8 * kMaxLaneRegisters;

/// f(std::integral_constant<int, registers>{}) for registers (groups of eight lanes) 1 to
/// kMaxLaneRegisters.
template <class F>
void with_registers(int registers, const F& f) {
  switch (registers) {
    case 3:
      f(std::integral_constant<int, 3>{});
      break;
    case 2:
      f(std::integral_constant<int, 2>{});
      break;
    case 1:
      f(std::integral_constant<int, 1>{});
      break;
    default:
      throw std::invalid_argument("lane registers = " + std::to_string(registers) + ": must be 1, 2 or 3");
  }
}

/// X[i L + t] = rings[t][i] for i < n, t < 8 registers.
void copy_in(double* const* rings, double* X, int n, int registers);
/// X[i L + t] += rings[t][i] for i < n, t < 8 registers (the same addition, lane by lane).
void add_in(const double* const* rings, double* X, int n, int registers);
/// rings[t][i] = X[i L + t]; a null rings[t] (a padding lane) is skipped. With `previous`, what
/// rings[t][i] held is moved to previous[t][i] first (non-null where rings[t] is).
void copy_out(double* const* rings, const double* X, int n, int registers, double* const* previous = nullptr);

/// The sequential order of the Provot constraint (apply_length_constraint) on every lane of X, Y:
/// passes until no ring changes or `iterations` passes; counts[t] gets ring t's corrections.
void constrain_sequential(double* X, double* Y, int n, int registers, int iterations, double dmin, double dmax,
                          int* counts);
/// The red-black order of the constraint, as constrain_sequential.
void constrain_red_black(double* X, double* Y, int n, int registers, int iterations, double dmin, double dmax,
                         int* counts);

/// gravity_stage, springs_stage and pressure_stage (ring_stages.hpp) on every lane: sets
/// FX, FY from X, Y, PX, PY and area[t] to ring t's area.
void forces_before_contacts(const StepContext& k, const double* X, const double* Y, const double* PX, const double* PY,
                            double* FX, double* FY, double* area, int n, int registers);
/// The spring forces of one ring (not lane by lane: its springs are the lanes), eight at a time, for
/// springs_stage: springs (i, i + 1), i from 0 to n - 2, into plus_x[i], plus_y[i]
/// (added to the first end; -0 for a spring of no length) and minus_x[i], minus_y[i] (subtracted
/// from the second; +0 then). The closing spring (n - 1, 0) is left to the caller. Needs n >= 9.
void ring_spring_forces(const StepContext& k, const double* x, const double* y, const double* px, const double* py,
                        int n, double* plus_x, double* plus_y, double* minus_x, double* minus_y);
/// viscosity_stage on every lane (adds to FX, FY).
void viscosity(const StepContext& k, const double* X, const double* Y, const double* PX, const double* PY, double* FX,
               double* FY, int n, int registers);
/// Simulation::centre_of_mass of every lane: cx[t], cy[t] for t < 8 registers.
void centres(const double* X, const double* Y, int n, int registers, double* cx, double* cy);
/// integrate_stage (position Verlet) on every lane.
void integrate(double h2m, double* X, double* Y, double* PX, double* PY, const double* FX, const double* FY, int n,
               int registers);

/// This thread's scratch of at least `doubles` doubles for lane-by-lane work that keeps nothing
/// between calls (the interleaved constraint's copy of its rings), grown when needed, so that it
/// allocates nothing once it has run. The lane-by-lane step keeps its block in memory of its own.
double* step_scratch(std::size_t doubles);

}  // namespace softdrop::lanes
