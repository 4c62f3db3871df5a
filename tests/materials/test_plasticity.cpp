// Plastic laws (J2, Drucker–Prager): the consistent tangent against central differences of
// the stress update on elastic, plastic and unloading steps; objectivity under superposed
// rotations; the textbook radial return in closed form (uniaxial strain, loading through
// yield and unloading) at small strain and in the logarithmic strain space; the branches of
// the Drucker–Prager return (cone, cutoff, apex) and the plastic work.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <vector>

#include "mfree/core/error.hpp"
#include "mfree/materials/drucker_prager.hpp"
#include "mfree/materials/j2_plasticity.hpp"
#include "mfree/materials/material.hpp"

using namespace mfree;

namespace {

const Lame steel = lame_constants(200e9, 0.3);

J2Plasticity j2(Kinematics k, double h_iso, double h_kin, double saturation) {
  J2Plasticity m;
  m.lame = steel;
  m.yield_stress = 250e6;
  m.isotropic_modulus = h_iso;
  m.kinematic_modulus = h_kin;
  if (saturation > 0.0) {
    m.saturation_stress = saturation;
    m.saturation_rate = 40.0;
  }
  m.kinematics = k;
  m.validate();
  return m;
}

DruckerPrager sand(Kinematics k, double cohesion, double cutoff) {
  DruckerPrager m;
  m.lame = lame_constants(50e6, 0.3);
  m.friction_angle = 30.0 * std::numbers::pi / 180.0;
  m.dilatancy_angle = 5.0 * std::numbers::pi / 180.0;
  m.cohesion = cohesion;
  m.tension_cutoff = cutoff;
  m.kinematics = k;
  m.validate();
  return m;
}

/// Largest |A - A_fd| / |A| with A_fd by central differences of P, step 1e-7 |F|.
template <class Law>
double tangent_error(const Law& law, const Mat2& f, const MaterialState<2>& state) {
  const MaterialUpdate<2> u = law.update(f, state, true);
  Tangent<2> fd;
  const double h = 1e-7;
  for (int k = 0; k < 4; ++k) {
    Mat2 plus = f, minus = f;
    plus(k / 2, k % 2) += h;
    minus(k / 2, k % 2) -= h;
    const Mat2 dp = (law.update(plus, state, false).stress - law.update(minus, state, false).stress) / (2 * h);
    for (int r = 0; r < 4; ++r) fd(r, k) = dp(r / 2, r % 2);
  }
  return (u.tangent - fd).norm() / u.tangent.norm();
}

Mat2 rotation(double angle) {
  Mat2 q;
  q << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  return q;
}

/// A general plane deformation: stretch and shear, rotated by `angle` (small-strain laws are
/// not objective: they take it unrotated).
Mat2 deformation(double stretch, double shear, double angle = 0.0) {
  Mat2 f;
  f << 1.0 + stretch, shear, 0.3 * shear, 1.0 - 0.4 * stretch;
  return rotation(angle) * f;
}

}  // namespace

TEST_CASE("J2: the consistent tangent matches central differences on elastic, plastic and unloading steps", "[materials]") {
  for (const Kinematics k : {Kinematics::small_strain, Kinematics::logarithmic, Kinematics::multiplicative}) {
    std::vector<J2Plasticity> laws{j2(k, 0.0, 0.0, 0.0), j2(k, 2e9, 0.0, 0.0), j2(k, 1e9, 0.0, 400e6)};
    if (k != Kinematics::multiplicative) laws.push_back(j2(k, 1e9, 3e9, 0.0));  // kinematic hardening
    for (const J2Plasticity& law : laws) {
      INFO("kinematics " << static_cast<int>(k) << ", H_iso " << law.isotropic_modulus << ", H_kin "
                         << law.kinematic_modulus << ", saturation " << law.saturation_stress);
      const double angle = k == Kinematics::small_strain ? 0.0 : 0.4;
      const auto deformation = [&](double stretch, double shear) { return ::deformation(stretch, shear, angle); };
      const MaterialState<2> virgin;
      // Elastic: well below yield (strain 2e-4 against a yield strain of about 1.6e-3).
      const Mat2 elastic = deformation(2e-4, 1e-4);
      CHECK(law.update(elastic, virgin, false).state.alpha == 0.0);
      CHECK(tangent_error(law, elastic, virgin) < 1e-6);
      // Plastic: through yield, from the virgin state.
      const Mat2 loaded = deformation(0.02, 0.01);
      const MaterialUpdate<2> plastic = law.update(loaded, virgin, false);
      CHECK(plastic.state.alpha > 0.0);
      CHECK(tangent_error(law, loaded, virgin) < 1e-6);
      // Unloading: from the plastic state back towards F = I (elastic), and a second plastic
      // step further on from it.
      const Mat2 unloaded = deformation(0.019, 0.0095);
      CHECK(law.update(unloaded, plastic.state, false).state.alpha == plastic.state.alpha);
      CHECK(tangent_error(law, unloaded, plastic.state) < 1e-6);
      CHECK(tangent_error(law, deformation(0.03, 0.02), plastic.state) < 1e-6);
    }
  }
}

TEST_CASE("J2 and Drucker–Prager at finite strain are objective: P(QF) = Q P(F), the state unchanged", "[materials]") {
  for (const Kinematics k : {Kinematics::logarithmic, Kinematics::multiplicative}) {
  INFO("kinematics " << static_cast<int>(k));
  const J2Plasticity metal = j2(k, 1e9, k == Kinematics::logarithmic ? 3e9 : 0.0, 400e6);
  const DruckerPrager soil = sand(k, 20e3, 1e300);
  const Mat2 f = deformation(0.05, 0.04, 0.4);
  for (const double angle : {0.3, 1.7, -2.9}) {
    const Mat2 q = rotation(angle);
    const MaterialUpdate<2> a = metal.update(f, {}, false), b = metal.update(Mat2(q * f), {}, false);
    CHECK((b.stress - q * a.stress).norm() <= 1e-12 * a.stress.norm());
    CHECK((b.state.plastic_strain - a.state.plastic_strain).norm() <= 1e-12 * a.state.plastic_strain.norm());
    CHECK(b.state.alpha == Approx(a.state.alpha).epsilon(1e-12));
    const MaterialUpdate<2> c = soil.update(f, {}, false), d = soil.update(Mat2(q * f), {}, false);
    CHECK((d.stress - q * c.stress).norm() <= 1e-12 * c.stress.norm());
    CHECK(d.state.alpha == Approx(c.state.alpha).epsilon(1e-12));
  }
  }
}

TEST_CASE("Drucker–Prager, multiplicative: simple shear keeps its friction at any shear strain", "[materials]") {
  // Confined by a vertical compression, then sheared at constant height (F = [[1, g], [0, 1 - c]]):
  // a cohesionless, non-dilatant soil flows at a fixed ratio sigma_xy / sigma_yy (about sin phi
  // for plane strain with psi = 0). The multiplicative law bounds the Kirchhoff stress itself,
  // so the ratio stays; the additive split of the Lagrangian log strain bounds a stress whose
  // push-forward loses its shear part (ratio 0.07 at g = 10).
  DruckerPrager soil = sand(Kinematics::multiplicative, 0.0, 1e300);
  soil.dilatancy_angle = 0.0;
  const double squeeze = 2e-3;
  const auto ratio_at = [&](double until) {
    MaterialState<2> state;
    MaterialUpdate<2> u;
    const int steps = static_cast<int>(until / 0.005);
    for (int n = 1; n <= steps; ++n) {
      Mat2 f;
      f << 1.0, until * n / steps, 0.0, 1.0 - squeeze;
      u = soil.update(f, state, false);
      state = u.state;
    }
    Mat2 f;
    f << 1.0, until, 0.0, 1.0 - squeeze;
    const Mat2 sigma = u.stress * f.transpose() / f.determinant();
    return std::abs(sigma(0, 1) / sigma(1, 1));
  };
  const double early = ratio_at(0.3), late = ratio_at(10.0);
  INFO("sigma_xy / sigma_yy at shear 0.3: " << early << ", at shear 10: " << late);
  CHECK(early == Approx(std::sin(30.0 * std::numbers::pi / 180.0)).epsilon(0.1));
  CHECK(std::abs(late - early) <= 0.02 * early);
}

TEST_CASE("J2 is the textbook radial return: uniaxial strain through yield and back, in closed form", "[materials]") {
  // Uniaxial strain e (the other strains zero): dev e = e (2, -1, -1) / 3, n = (2, -1, -1) / sqrt(6),
  // |xi^tr| = 2 mu sqrt(2/3) e. For monotonic loading from the virgin state with linear
  // hardening, dgamma = (2 mu sqrt(2/3) e - sqrt(2/3) sigma_y) / (2 mu + 2/3 (H_iso + H_kin)),
  // T_xx = lambda e + 2 mu (e - 2 dgamma / sqrt(6)), T_yy = T_zz = lambda e + 2 mu dgamma / sqrt(6).
  const double h_iso = 2e9, h_kin = 3e9, mu = steel.mu, lambda = steel.lambda;
  const double sy = 250e6, s23 = std::sqrt(2.0 / 3.0), s6 = std::sqrt(6.0);
  const auto closed = [&](double e) {
    const double dgamma = std::max(0.0, (2 * mu * s23 * e - s23 * sy) / (2 * mu + 2.0 / 3.0 * (h_iso + h_kin)));
    return std::pair{lambda * e + 2 * mu * (e - 2 * dgamma / s6), dgamma};
  };
  for (const Kinematics k : {Kinematics::small_strain, Kinematics::logarithmic}) {
    const J2Plasticity law = j2(k, h_iso, h_kin, 0.0);
    // The strain of each kinematics: e = F_xx - 1, or ln F_xx; P_xx = T_xx, or T_xx / F_xx.
    const auto stretch = [&](double e) { return k == Kinematics::small_strain ? 1.0 + e : std::exp(e); };
    const auto first_piola = [&](double t, double e) { return k == Kinematics::small_strain ? t : t / stretch(e); };
    for (const double e : {0.5e-3, 4e-3, 0.02}) {
      const MaterialUpdate<2> one =
          law.update(Eigen::DiagonalMatrix<double, 2>(stretch(e), 1.0).toDenseMatrix(), {}, false);
      // In 200 increments: the same (the path is radial).
      MaterialState<2> s;
      MaterialUpdate<2> many;
      for (int n = 1; n <= 200; ++n) {
        many = law.update(Eigen::DiagonalMatrix<double, 2>(stretch(e * n / 200), 1.0).toDenseMatrix(), s, false);
        s = many.state;
      }
      const auto [txx, dgamma] = closed(e);
      INFO("kinematics " << static_cast<int>(k) << ", e = " << e);
      CHECK(one.stress(0, 0) == Approx(first_piola(txx, e)).epsilon(1e-12));
      CHECK(many.stress(0, 0) == Approx(first_piola(txx, e)).epsilon(1e-10));
      CHECK(one.state.plastic_strain(0, 0) == Approx(2 * dgamma / s6).epsilon(1e-12).margin(1e-300));
      CHECK(one.state.alpha == Approx(s23 * dgamma).epsilon(1e-12).margin(1e-300));
      CHECK(one.state.plastic_strain_zz == Approx(-dgamma / s6).epsilon(1e-12).margin(1e-300));
    }
    // Unloading from e = 0.004 to 0.002 is elastic (reverse yielding would start below
    // e = 0.72e-3): the plastic strain stays, T_xx = lambda e + 2 mu (e - e_p,xx).
    const MaterialUpdate<2> loaded =
        law.update(Eigen::DiagonalMatrix<double, 2>(stretch(0.004), 1.0).toDenseMatrix(), {}, false);
    const MaterialUpdate<2> back = law.update(
        Eigen::DiagonalMatrix<double, 2>(stretch(0.002), 1.0).toDenseMatrix(), loaded.state, false);
    CHECK(back.state.alpha == loaded.state.alpha);
    const double unloaded = lambda * 0.002 + 2 * mu * (0.002 - loaded.state.plastic_strain(0, 0));
    CHECK(back.stress(0, 0) == Approx(first_piola(unloaded, 0.002)).epsilon(1e-12));
    // The plastic work: T : dE_p summed; one radial step dissipates T_{n+1} : dE_p.
    CHECK(loaded.state.dissipation > 0.0);
  }
}

TEST_CASE("J2 in the logarithmic space tends to the small-strain return as the strains shrink", "[materials]") {
  const J2Plasticity small = j2(Kinematics::small_strain, 1e9, 3e9, 400e6);
  J2Plasticity finite = small;
  finite.kinematics = Kinematics::logarithmic;
  double previous = 1.0;
  for (const double scale : {1e-2, 1e-3, 1e-4}) {
    // A plastic step: the yield stress scaled with the strain keeps it plastic.
    J2Plasticity a = small, b = finite;
    a.yield_stress = b.yield_stress = 0.3 * scale * 2 * steel.mu;
    a.saturation_stress = b.saturation_stress = 0.5 * scale * 2 * steel.mu;
    Mat2 f;
    f << 1.0 + scale, 0.7 * scale, -0.2 * scale, 1.0 - 0.5 * scale;
    const MaterialUpdate<2> u = a.update(f, {}, false), v = b.update(f, {}, false);
    CHECK(u.state.alpha > 0.0);
    const double difference = (u.stress - v.stress).norm() / u.stress.norm();
    CHECK(difference < 5 * scale);  // first order in the strain
    CHECK(difference < previous);
    previous = difference;
  }
}

TEST_CASE("Drucker–Prager: cone, cutoff and apex returns; the tangent on each; associative and not", "[materials]") {
  for (const Kinematics k : {Kinematics::small_strain, Kinematics::logarithmic, Kinematics::multiplicative}) {
    const DruckerPrager cohesive = sand(k, 20e3, 1e300);  // cutoff at the apex
    const DruckerPrager cut = sand(k, 20e3, 5e3);          // cutoff below the apex
    const double eta = cohesive.eta(), xi = cohesive.xi();
    const auto invariants = [&](const MaterialUpdate<2>& u, const Mat2& f) {
      // p and sqrt(J2) of the Cauchy stress (with sigma_zz), for the checks below.
      const Mat2 sigma = k == Kinematics::small_strain ? u.stress : Mat2(u.stress * f.transpose() / f.determinant());
      const double p = (sigma.trace() + u.stress_zz) / 3.0;
      const double sxx = sigma(0, 0) - p, syy = sigma(1, 1) - p, szz = u.stress_zz - p;
      return std::pair{p, std::sqrt(0.5 * (sxx * sxx + syy * syy + szz * szz) + sigma(0, 1) * sigma(0, 1))};
    };
    INFO("kinematics " << static_cast<int>(k));
    // Shear under confinement: the cone; sqrt(J2) + eta p = xi c after the return.
    Mat2 shear;
    shear << 0.998, 0.02, 0.0, 0.997;
    const MaterialUpdate<2> cone = cohesive.update(shear, {}, true);
    CHECK(cone.state.alpha > 0.0);
    if (k == Kinematics::small_strain) {
      const auto [p, q] = invariants(cone, shear);
      CHECK(q + eta * p == Approx(xi * 20e3).epsilon(1e-10));
    }
    CHECK(tangent_error(cohesive, shear, {}) < 1e-6);
    // Pure expansion: past the apex, the stress is the apex, p = xi c / eta, s = 0.
    const Mat2 expansion = Eigen::DiagonalMatrix<double, 2>(1.01, 1.01).toDenseMatrix();
    const MaterialUpdate<2> apex = cohesive.update(expansion, {}, false);
    if (k == Kinematics::small_strain) {
      const auto [p, q] = invariants(apex, expansion);
      CHECK(p == Approx(xi * 20e3 / eta).epsilon(1e-12));
      CHECK(q <= 1e-9 * p);
    }
    // With the cutoff below the apex: p = p_t, and the shear kept when inside the cone there.
    const Mat2 stretch = Eigen::DiagonalMatrix<double, 2>(1.001, 1.0).toDenseMatrix();
    const MaterialUpdate<2> cutoff = cut.update(stretch, {}, true);
    if (k == Kinematics::small_strain) {
      const auto [p, q] = invariants(cutoff, stretch);
      CHECK(p == Approx(5e3).epsilon(1e-12));
      CHECK(q + eta * p <= xi * 20e3 * (1 + 1e-12));
    }
    CHECK(tangent_error(cut, stretch, {}) < 1e-6);
    CHECK(tangent_error(cohesive, Mat2(Eigen::DiagonalMatrix<double, 2>(0.99, 0.995).toDenseMatrix()), {}) < 1e-6);
    // Plastic work is never negative, and an associative law dilates more than psi = 5 degrees.
    CHECK(cone.state.dissipation >= 0.0);
    DruckerPrager associative = cohesive;
    associative.dilatancy_angle = associative.friction_angle;
    const MaterialUpdate<2> dilating = associative.update(shear, {}, false);
    // The plastic volume change ln J_p: tr E_p, or -1/2 ln det C_p^-1 (multiplicative: the state
    // holds C_p^-1 - I).
    const auto volume = [&](const MaterialState<2>& st) {
      if (k != Kinematics::multiplicative) return st.plastic_strain.trace() + st.plastic_strain_zz;
      return -0.5 * std::log((Mat2::Identity() + st.plastic_strain).determinant() * (1.0 + st.plastic_strain_zz));
    };
    const double dilation = volume(dilating.state), less = volume(cone.state);
    CHECK(dilation > less);
    CHECK(less > 0.0);
  }
  DruckerPrager bad = sand(Kinematics::small_strain, 0.0, 1e300);
  bad.dilatancy_angle = 0.7;
  CHECK_THROWS_AS(bad.validate(), InputError);
}

TEST_CASE("plastic_strain() is one measure for every kinematics: coaxial stretches agree", "[materials]") {
  // On a stretch along fixed axes both finite-strain forms follow the same return in the same
  // principal log strains, so 1/2 ln C_p of the multiplicative state (which holds C_p^-1 - I)
  // must equal the logarithmic state's E_p.
  const Mat2 f1 = Eigen::Vector2d(1.03, 0.98).asDiagonal(), f2 = Eigen::Vector2d(1.05, 0.97).asDiagonal();
  const Material log_law = j2(Kinematics::logarithmic, 1e9, 0.0, 400e6), mult_law = j2(Kinematics::multiplicative, 1e9, 0.0, 400e6);
  MaterialState<2> a, b;
  for (const Mat2& f : {f1, f2}) {
    a = update(log_law, f, a, false).state;
    b = update(mult_law, f, b, false).state;
  }
  const auto [ea, za] = plastic_strain(log_law, a);
  const auto [eb, zb] = plastic_strain(mult_law, b);
  INFO("E_p " << ea << " zz " << za << " against 1/2 ln C_p " << eb << " zz " << zb);
  REQUIRE(ea.norm() > 1e-3);
  CHECK((ea - eb).norm() <= 1e-10 * ea.norm());
  CHECK(std::abs(za - zb) <= 1e-10 * ea.norm());
  CHECK(plastic_strain(Material(NeoHookean{steel}), a).first.norm() == 0.0);
}
