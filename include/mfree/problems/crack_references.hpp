#pragma once
// Closed-form references of linear elastic fracture mechanics, for checking computed stress
// intensity factors and crack openings: Griffith's crack under remote stress, the handbook
// geometry factors of a crack in a strip (Tada, Paris & Irwin, The Stress Analysis of Cracks
// Handbook, 3rd ed., 2000), and Williams' near-tip field about a tip as an exact solution
// (galerkin/near_tip_field.hpp). Stresses in stress units, lengths in length units, K in
// stress * sqrt(length).

#include <functional>

#include "mfree/galerkin/exact_elasticity.hpp"
#include "mfree/galerkin/near_tip_field.hpp"
#include "mfree/materials/linear_elastic.hpp"

namespace mfree {

struct StressIntensityPair {
  double k1 = 0.0;
  double k2 = 0.0;
};

/// Griffith crack of length 2a in an infinite plate under uniaxial remote stress sigma whose
/// direction makes the angle beta (radians) with the crack line:
/// K_I = sigma sin^2(beta) sqrt(pi a), K_II = sigma sin(beta) cos(beta) sqrt(pi a) (the
/// normal and shear stresses on the crack plane times sqrt(pi a)). Throws InputError for
/// a <= 0.
StressIntensityPair griffith_inclined_crack(double stress, double half_length, double beta);

/// Centre crack of length 2a in a strip of width 2w under remote tension normal to the crack
/// (Tada et al., after Feddersen; 0.1 % for any a/w):
/// K_I = F sigma sqrt(pi a), F = [1 - 0.025 (a/w)^2 + 0.06 (a/w)^4] sqrt(sec(pi a / (2 w))).
/// Throws InputError unless 0 <= a/w < 1.
double centre_crack_strip_factor(double a_over_w);

/// Single edge crack of depth a in a strip of width w under remote tension (Tada et al.,
/// after Brown; 0.5 % for a/w <= 0.6): K_I = F sigma sqrt(pi a),
/// F = 1.12 - 0.231 (a/w) + 10.55 (a/w)^2 - 21.72 (a/w)^3 + 30.39 (a/w)^4.
/// Throws InputError unless 0 <= a/w <= 0.6 (the fit's range).
double edge_crack_strip_factor(double a_over_w);

/// Opening (upper face minus lower face displacement normal to the crack) of a Griffith crack
/// of length 2a under remote normal stress sigma_n on its plane, at distance s from its
/// centre: delta_n = 4 sigma_n sqrt(a^2 - s^2) / E' for |s| < a, 0 beyond; E' = E (plane
/// stress), E / (1 - nu^2) (plane strain). Throws InputError for a <= 0.
double griffith_crack_opening(double normal_stress, double half_length, double s,
                              const LinearElastic& material);

/// Williams' near-tip field of stress intensity factors k1, k2 about `tip` in global
/// coordinates, as an exact solution: displacement Q u'(x'), stress Q sigma' Q^T with
/// x' = Q^T (x - tip), zero body force. The crack lies along -e1 from the tip; a body built
/// around it with this field's tractions on its boundary has exactly these K. Singular at the
/// tip (the stress throws NumericalError there). Throws InputError for a bad tip or material.
ExactElasticity williams_near_tip_solution(const CrackTipFrame& tip, double k1, double k2,
                                           const LinearElastic& material);

/// The displacement gradient H(i, j) = u_i,j (global) of the same field: Q H'(x') Q^T.
std::function<Mat2(const Vec2&)> williams_near_tip_gradient(const CrackTipFrame& tip, double k1, double k2,
                                                            const LinearElastic& material);

}  // namespace mfree
