#pragma once
// The own error of a progressive reference (ppm), estimated from the renders that make it
// (docs/accuracy.md, "The floor of a progressive reference").
//
// A progressive estimator X_N after N stages (ppm's passes) has noise and a bias that falls as
// N^-p (ppm: R^2 shrinks as N^-(1 - alpha), p = 1/3). The reference is made of two halves A and B
// with independent seeds; each half's render also returns its images at N/8 and N/64 stages
// (RenderOptions::checkpoints: the same render stopped early, at no cost). With g = 8^p:
//
// - Plain: each half's estimate is X = L_N. One stage earlier the estimate is X' = L_{N/8},
//   whose bias is g times X's. So E[X - X'] = b (1 - g): the bias of X is -E[X - X'] / (g - 1).
// - Richardson: X = (g L_N - L_{N/8}) / (g - 1), in which the N^-p term cancels; X' is the same
//   combination one stage earlier, (g L_{N/8} - L_{N/64}) / (g - 1). What remains of the bias, c,
//   falls at least as fast as N^-p where the expansion holds, so c_{N/8} >= g c_N and
//   |c_N| <= |E[X - X']| / (g - 1): an upper estimate. Where the bias falls more slowly than N^-p
//   (the edges of caustics, where the radius straddles the edge) neither form holds.
//
// The plain estimator does not take p on trust where the N/64 stage is there too: the bias's
// RMS one stage earlier, from the same split of L_{N/8} - L_{N/64}, over this stage's gives the
// measured ratio g'. The bound uses g' between sqrt(g) and g: a bias that falls more slowly is a
// larger bias for the same D. p is the order of R^2 (a kernel estimate's blur where the radiance
// is smooth); at a discontinuity, an edge or a caustic line thinner than R, the blur is of order
// R, i.e. p/2, and nothing falls more slowly than that once the radius has begun to shrink. A g'
// below sqrt(g) comes from the first stages (N/64 of 2048 is 32 passes), before that regime.
// (Richardson would need N/512 to measure its residual's rate; it keeps g.)
//
// In both, the reference is (X_A + X_B) / 2 and, per channel value,
//   noise^2 = (X_A - X_B)^2 / 4                                   (unbiased for Var of the mean),
//   bias^2  = (Dbar^2 - (D_A - D_B)^2 / 4) / (g - 1)^2,           D_h = X_h - X'_h,
// the second the bias/variance split of two seeds applied to D (unbiased; it can be negative per
// value, and is clamped at 0 only after averaging). The bias's mean over values comes with a 95%
// upper bound (the clamped mean + 1.96 standard errors), which the floor uses: a floor should err
// high. Pixels are not independent (one photon lights its neighbours, and the bias sits in
// blobs along the caustics), so the standard error comes from the spread of blocks' means rather
// than single pixels': the largest over blocks of 8, 16, 32, ... pixels a side while 16 blocks
// remain (block_mean_upper). It can still understate where the bias sits in fewer blobs than that.

#include "tracer/image.h"

#include <string>
#include <vector>

namespace harness {

/// How a progressive reference combines its stages.
enum class ReferenceEstimator {
  Plain,       ///< The halves' mean at N stages.
  Richardson,  ///< The halves' mean of (g L_N - L_{N/8}) / (g - 1): the N^-p bias cancelled.
};

/// "plain" or "richardson".
const char* estimator_name(ReferenceEstimator e);

/// Parses "plain" or "richardson"; throws std::invalid_argument naming the value otherwise.
ReferenceEstimator parse_estimator(const std::string& name);

/// The ratio of stages between checkpoints: N, N/8, N/64.
inline constexpr int kStageRatio = 8;



/// Checkpoints an estimator needs below N: 1 (N/8) for plain, 2 (also N/64) for Richardson.
int estimator_depth(ReferenceEstimator e);

/// What N must be divisible by for those checkpoints: 8 for plain, 64 for Richardson.
long long estimator_divisor(ReferenceEstimator e);

/// One half's images after N, N/8 and N/64 stages (n64: needed by Richardson; plain measures
/// its bias's rate with it where it is there).
struct HalfStages {
  tracer::Image n;
  tracer::Image n8;
  tracer::Image n64;
};

/// A mean over channel values with the 95% upper bound of its estimate.
struct MeanEstimate {
  double value = 0.0;  ///< The estimate (clamped at 0).
  double upper = 0.0;  ///< Its 95% upper bound: value + 1.96 standard errors of the mean.
};

/// Blocks a standard error needs at least: fewer give too rough a spread.
inline constexpr int kMinBlocks = 16;

/// The mean per channel value of per-pixel sums `s` (three channel values each) of a width x
/// height image, clamped at 0, and its 95% upper bound: that plus 1.96 standard errors, the
/// largest standard error of the means of square blocks of 8, 16, 32, ... pixels a side that
/// still make kMinBlocks blocks (smaller sides where 8 does not). Throws std::invalid_argument
/// when `s` does not hold width x height values.
MeanEstimate block_mean_upper(const std::vector<double>& s, int width, int height);

/// A progressive reference and its own error.
struct ProgressiveReference {
  tracer::Image image;    ///< (X_A + X_B) / 2.
  double noise_mse = 0.0; ///< Its noise, mean squared, radiance^2.
  double noise_rel = 0.0; ///< The same weighted by 1 / (r^2 + eps), r this image.
  MeanEstimate bias_mse;  ///< Its bias, mean squared, radiance^2.
  MeanEstimate bias_rel;  ///< The same weighted by 1 / (r^2 + eps).
  double bias_order = 0.0; ///< The order p the bias bound used: the theory's, or lower as measured.
};

/// Combines two halves' stages with estimator `e` for a bias of order `order` (p > 0) and
/// estimates the result's noise and bias as described at the top of this file. The relative
/// measures use `epsilon`. Throws std::invalid_argument when the images' sizes differ or an
/// image the estimator needs is missing.
ProgressiveReference progressive_reference(const HalfStages& a, const HalfStages& b, double order,
                                           ReferenceEstimator e, double epsilon);

}  // namespace harness
