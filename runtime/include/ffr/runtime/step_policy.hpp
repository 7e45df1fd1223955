#pragma once
// The rules by which a step accepts Newton iterates and projections and decides when to rebuild
// its tangent (FORMULATION.md section 9), gathered in one place. Each constant is a setting:
// its default, and the reason for it, are given with it. None is a property of one model; the
// measurements quoted are where the reasoning was checked.

namespace ffr::runtime {

struct NewtonPolicy {
  /// Tangents built in one step at most. The usual step needs one or two; a step that needs more
  /// is a hard one (a body started at speed), and beyond this many the step is failing anyway.
  int max_refreshes = 5;

  /// Multiplier passes inside one Newton iteration (newton_direction): the augmented-Lagrangian
  /// update sigma = alpha (Phi - Phi_q dq) with the factorised tangent, without a new evaluation.
  /// Without them the multipliers lag one penalty update per iteration, which converges only
  /// linearly where the penalty is weak against the tangent (a loop closed through an elastic
  /// body); the second pass (from the second iteration on, only while the first leaves the
  /// linearised violation above the tolerance) takes it to round-off, which lets an iterate be
  /// accepted right after a fresh tangent (kappa_life).
  int multiplier_passes = 2;

  /// An iteration whose increment is more than this fraction of the last one's is contracting
  /// slowly: the tangent is rebuilt for the next (up to max_refreshes). Newton with a tangent
  /// built at its iterate contracts quadratically; a factor 2 a pass is the least that is still
  /// worth more than a new tangent.
  double slow_contraction = 0.5;

  /// An update computed with a tangent built at an earlier iterate that grows the increment more
  /// than this factor is discarded and recomputed with a tangent built at the current iterate:
  /// applied, it can throw the iterate so far that no later tangent recovers.
  double rejected_growth = 2.0;

  /// A tangent built at the predictor has its constraint terms rebuilt at the second iterate
  /// when penalty * (first scaled increment) exceeds this. Why: the penalty term
  /// alpha Phi_q^T Phi_q dominates the tangent; built with the predictor's Phi_q it misses
  /// alpha (Phi_q' - Phi_q)^T Phi_q, an error of about penalty * increment against the penalty
  /// and more against the inertia of the free directions, most for the lightest bodies (alpha
  /// is one for all rows, scaled by the mean body mass). Measured where it bites: the vehicle
  /// example at h = 4 ms (35 kg wheels among bodies of 170 kg on average) had penalty * increment
  /// ~ 0.13, and the second and third updates then undid each other along the axles' and wheels'
  /// pitch (a contraction of 0.99, the two increments anti-parallel) until a refresh at the fourth:
  /// over its 15 s, 3.53 iterations a step at 1 and 0.2 (the same as with no rebuild), 2.12 at 0.1,
  /// 2.08 at 0.03 (rebuilt in 3058 of its 3750 steps, most of them over the rough road). The washing
  /// machine (0.2 kg bearing housings, h = 0.25 ms, 10 s): 2.75 iterations a step at 1, 2.04 at
  /// 0.1, 1.90 at 0.03 and 1.88 at 0.01, the tangents built a step 1.49 to 1.50; below 0.03 the
  /// vehicle at 2 ms (penalty * increment ~ 0.014) would rebuild at every step for nothing. The
  /// slider-crank benchmark (already above 1) and the beam pendulums (below 0.03) do not change.
  double predictor_tangent = 0.03;

  /// A tangent kept from an earlier step (reuse_jacobian) is not used for a first increment
  /// with penalty * (first scaled increment) above this: its penalty term is stale in the same
  /// way as the predictor's (predictor_tangent), and applied it can throw the iterate off
  /// altogether (the benchmark's crank at 150 rad/s, FORMULATION.md 9).
  double stale_tangent = 1.0;

  /// Steps over which Newton's quadratic constant kappa = inc_next / inc^2, measured after an
  /// update with a tangent built at its own iterate, is trusted to accept the next such update on
  /// its predicted error 2 kappa inc^2. After this many steps one step goes on to the next
  /// iteration, which measures kappa again. (The factor 2 is the margin on the estimate.)
  int kappa_life = 8;

  /// With reuse_jacobian, a step that needed more than this many iterations has the tangent
  /// rebuilt at the first iteration of the next step (the kept one has drifted too far).
  int reuse_max_iterations = 5;

  /// A step's first tangent takes the bushings' part of K and C from the last tangent built
  /// (Data::bushing_K) while that part has served fewer steps than this (1: built at every
  /// tangent); any later tangent of a step builds it again. Why: where bushings join a flexible
  /// body their tangent is the costliest part of the step (each spans both bodies' coordinates),
  /// and over a few steps it changes only with the bodies' turning and deflection (h times
  /// their rates), so Newton converges as fast with it. On the vehicle and the washing machine
  /// (tools/bench/examples) 4 leaves the Newton iterations and tangents unchanged and takes 16 %
  /// and 15 % off the step's instructions; the outputs move by 1e-4 of their range at most,
  /// a thousandth of the difference a halved step makes (not through Newton's tolerance: the
  /// projections use the tangent as their metric).
  int bushing_tangent_steps = 4;

  /// The constraint violation of the accepted iterate itself (before its update) may be this
  /// factor above `tolerance`: the update's linearised violation, which must be below
  /// `tolerance`, is what the accepted coordinates have, up to O(increment^2).
  double violation_factor = 1e3;
};

struct ProjectionPolicy {
  /// Passes of one projection at most (each a solve with the factorised tangent).
  int max_passes = 40;
  /// The constraint residual the passes aim for, as a fraction of `tolerance` (they stop earlier
  /// only where it stalls at round-off below `tolerance`).
  double residual_fraction = 1e-2;
  /// A pass whose scaled change is below this fraction of `newton_tolerance` is at round-off: its
  /// change stands for the error even when the passes no longer contract.
  double round_off_fraction = 1e-3;
};

struct StepPolicy {
  NewtonPolicy newton;
  ProjectionPolicy projection;
};

}  // namespace ffr::runtime
