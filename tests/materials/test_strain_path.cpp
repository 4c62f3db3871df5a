// Material-point paths (materials/strain_path.hpp), the two tests of
// verification/material-point/ read from their scenes (io/path_scene.hpp):
//   - uniaxial strain through yield, unloading and reverse yield, against the closed form
//     (for a radial path with linear hardening the radial return is exact: round-off);
//   - tension then shear at constant axial strain, against a Runge–Kutta integration of the
//     continuum rate equations, and the return's first-order convergence to it;
// and wrong path scenes refused, naming the key.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include "../test_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/io/path_scene.hpp"
#include "mfree/materials/strain_path.hpp"

using namespace mfree;

namespace {

const std::string scenes = mfree::testing::source_dir() + "/verification/material-point/";

/// A symmetric plane-strain tensor (xx, yy, zz, xy); xz = yz = 0.
using Sym = Eigen::Vector4d;

/// a : b (the shear component counts twice).
double contract(const Sym& a, const Sym& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + 2.0 * a[3] * b[3]; }
double norm(const Sym& a) { return std::sqrt(contract(a, a)); }

Sym stress_of(const PathRecord& r) { return {r.cauchy(0, 0), r.cauchy(1, 1), r.stress_zz, r.cauchy(0, 1)}; }
Sym plastic_strain_of(const PathRecord& r) {
  const Mat2& e = r.state.plastic_strain;
  return {e(0, 0), e(1, 1), r.state.plastic_strain_zz, e(0, 1)};
}

const J2Plasticity& linear_j2(const PathScene& scene) {
  const auto* law = std::get_if<J2Plasticity>(&scene.material.material);
  REQUIRE(law);
  REQUIRE(law->kinematics == Kinematics::small_strain);
  REQUIRE(law->isotropic_modulus > 0.0);
  REQUIRE(law->kinematic_modulus > 0.0);
  REQUIRE(law->saturation_stress == 0.0);  // linear hardening
  return *law;
}

// ---------------------------------------------------------------------------------------
// Uniaxial strain eps_yy = e(t), the other strains zero (README: the closed form).
// dev eps = sqrt(2/3) e d with the unit direction d = (-1, 2, -1, 0) / sqrt(6): the plastic
// strain is q d, the back stress 2/3 H_kin q d, alpha grows by sqrt(2/3) |dq|. Writing
// a = sqrt(2/3), c = 2 mu + 2/3 (H_iso + H_kin), and the scalar relative stress
// x = 2 mu (a e - q) - 2/3 H_kin q, yield is |x| = a k(alpha), k = sigma_y + H_iso alpha:
//   loading (e from 0 to -e_max, t <= 1): q = -gamma, gamma = max(0, a (2 mu |e| - sigma_y) / c)
//   unloading: elastic at q_1 = -gamma_1 until x = +a k_1, i.e. e_r = -e_max + k_1 / mu
//   reverse yield (e > e_r): q = q_1 + 2 mu a (e - e_r) / c
//   sigma_yy = lambda e + 2 mu (e - 2 q / sqrt 6),  sigma_xx = sigma_zz = lambda e + 2 mu q / sqrt 6.
struct UniaxialExact {
  Sym stress, plastic_strain;
  double alpha = 0.0;
  double stored_energy = 0.0;  // 1/2 sigma : (eps - eps_p)
  double plastic_work = 0.0;   // int sigma : deps_p
};

UniaxialExact uniaxial_exact(const J2Plasticity& j, double e_max, double t, double e) {
  const double mu = j.lame.mu, lambda = j.lame.lambda, sy = j.yield_stress;
  const double h_iso = j.isotropic_modulus, h_kin = j.kinematic_modulus, h = h_iso + h_kin;
  const double a = std::sqrt(2.0 / 3.0), c = 2.0 * mu + 2.0 / 3.0 * h, s6 = std::sqrt(6.0);
  const double gamma_1 = std::max(0.0, a * (2.0 * mu * e_max - sy) / c);
  const double alpha_1 = a * gamma_1, k_1 = sy + h_iso * alpha_1, q_1 = -gamma_1;
  // Plastic work: sigma : deps_p = 2 mu (a e - q) dq; on the loading branch that is
  // (a sigma_y + 2/3 H gamma) dgamma, on the reverse branch (a k_1 + 2/3 H_kin q_1 + 2/3 H dq) dq.
  UniaxialExact x;
  double q = 0.0;
  if (t <= 1.0) {
    const double gamma = std::max(0.0, a * (2.0 * mu * -e - sy) / c);
    q = -gamma;
    x.alpha = a * gamma;
    x.plastic_work = a * sy * gamma + h / 3.0 * gamma * gamma;
  } else {
    const double e_r = -e_max + k_1 / mu;
    const double dq = e <= e_r ? 0.0 : 2.0 * mu * a * (e - e_r) / c;
    q = q_1 + dq;
    x.alpha = alpha_1 + a * dq;
    x.plastic_work = a * sy * gamma_1 + h / 3.0 * gamma_1 * gamma_1 + (a * k_1 + 2.0 / 3.0 * h_kin * q_1) * dq +
                     h / 3.0 * dq * dq;
  }
  x.plastic_strain = Sym(-q, 2.0 * q, -q, 0.0) / s6;
  const Sym elastic = Sym(0.0, e, 0.0, 0.0) - x.plastic_strain;
  x.stress = Sym(lambda * e, lambda * e, lambda * e, 0.0) + 2.0 * mu * elastic;
  x.stored_energy = 0.5 * contract(x.stress, elastic);
  return x;
}

// ---------------------------------------------------------------------------------------
// The continuum rate equations of small-strain J2 with linear isotropic and kinematic
// hardening (Simo & Hughes 1998, section 2.3; de Souza Neto et al. 2008, section 7.3), with
// the yield condition |xi| = sqrt(2/3) k(alpha) holding (xi = dev sigma - beta, n = xi / |xi|):
//   dgamma/dt  = 2 mu <n : deps/dt> / (2 mu + 2/3 (H_iso + H_kin))   (loading; 0 when elastic)
//   dsigma/dt  = lambda tr(deps/dt) 1 + 2 mu deps/dt - 2 mu dgamma/dt n   (= C^ep : deps/dt)
//   dbeta/dt   = 2/3 H_kin dgamma/dt n,  deps_p/dt = dgamma/dt n,  dalpha/dt = sqrt(2/3) dgamma/dt
// integrated by the classical Runge–Kutta method, the state y = (sigma, beta, eps_p, alpha).
using RateState = Eigen::Matrix<double, 13, 1>;

struct RateEquations {
  const J2Plasticity& law;

  RateState rate(const RateState& y, const Sym& strain_rate, bool on_yield_surface) const {
    const double mu = law.lame.mu, lambda = law.lame.lambda;
    const Sym sigma = y.segment<4>(0), beta = y.segment<4>(4);
    const double mean = (sigma[0] + sigma[1] + sigma[2]) / 3.0;
    const Sym xi = Sym(sigma[0] - mean, sigma[1] - mean, sigma[2] - mean, sigma[3]) - beta;
    double dgamma = 0.0;
    Sym n = Sym::Zero();
    if (on_yield_surface) {
      n = xi / norm(xi);
      dgamma = std::max(0.0, 2.0 * mu * contract(n, strain_rate) /
                                 (2.0 * mu + 2.0 / 3.0 * (law.isotropic_modulus + law.kinematic_modulus)));
    }
    const double volumetric = lambda * (strain_rate[0] + strain_rate[1] + strain_rate[2]);
    RateState dy;
    dy.segment<4>(0) = Sym(volumetric, volumetric, volumetric, 0.0) + 2.0 * mu * strain_rate - 2.0 * mu * dgamma * n;
    dy.segment<4>(4) = 2.0 / 3.0 * law.kinematic_modulus * dgamma * n;
    dy.segment<4>(8) = dgamma * n;
    dy[12] = std::sqrt(2.0 / 3.0) * dgamma;
    return dy;
  }
};

/// The tension–shear path of the test: eps_yy = e1 min(t, 1), eps_xy = g1 max(t - 1, 0) / 2,
/// integrated piece by piece (elastic tension to the yield time t_y, plastic tension to
/// t = 1, shear to t = 2: the rates are smooth within each) in RK4 steps of at most h.
class TensionShearReference {
 public:
  TensionShearReference(const J2Plasticity& law, double e1, double g1, double h)
      : equations_{law}, e1_(e1), g1_(g1), h_(h), yield_time_(law.yield_stress / (2.0 * law.lame.mu * e1)) {}

  void advance_to(double t_end) {
    while (t_ < t_end) {
      const double stop = std::min(t_end, t_ < yield_time_ ? yield_time_ : t_ < 1.0 ? 1.0 : 2.0);
      const bool tension = t_ < 1.0;
      const Sym rate = tension ? Sym(0.0, e1_, 0.0, 0.0) : Sym(0.0, 0.0, 0.0, 0.5 * g1_);
      const bool plastic = t_ >= yield_time_;
      const long steps = std::max(1L, static_cast<long>(std::ceil((stop - t_) / h_)));
      const double dt = (stop - t_) / static_cast<double>(steps);
      for (long k = 0; k < steps; ++k) {
        const RateState k1 = equations_.rate(y_, rate, plastic);
        const RateState k2 = equations_.rate(y_ + 0.5 * dt * k1, rate, plastic);
        const RateState k3 = equations_.rate(y_ + 0.5 * dt * k2, rate, plastic);
        const RateState k4 = equations_.rate(y_ + dt * k3, rate, plastic);
        y_ += dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
      }
      steps_ += steps;
      t_ = stop;
    }
  }
  [[nodiscard]] Sym stress() const { return y_.segment<4>(0); }
  [[nodiscard]] Sym plastic_strain() const { return y_.segment<4>(8); }
  [[nodiscard]] double alpha() const { return y_[12]; }
  [[nodiscard]] long steps() const { return steps_; }

 private:
  RateEquations equations_;
  double e1_, g1_, h_, yield_time_;
  double t_ = 0.0;
  RateState y_ = RateState::Zero();
  long steps_ = 0;
};

/// Largest relative differences of a run from the reference at its recorded increments.
struct PathErrors {
  double stress = 0.0, plastic_strain = 0.0, alpha = 0.0;
};

PathErrors tension_shear_errors(const std::vector<PathRecord>& rows, const J2Plasticity& law, double e1, double g1,
                                double h) {
  TensionShearReference reference(law, e1, g1, h);
  PathErrors worst;
  for (const PathRecord& r : rows) {
    reference.advance_to(r.time);
    if (reference.alpha() == 0.0) {
      // Elastic so far: no plastic strain in either; the stress of Hooke's law.
      CHECK(r.state.alpha == 0.0);
      CHECK(norm(stress_of(r) - reference.stress()) <= 1e-12 * norm(reference.stress()) + 1e-300);
      continue;
    }
    worst.stress = std::max(worst.stress, norm(stress_of(r) - reference.stress()) / norm(reference.stress()));
    worst.plastic_strain = std::max(worst.plastic_strain, norm(plastic_strain_of(r) - reference.plastic_strain()) /
                                                              norm(reference.plastic_strain()));
    worst.alpha = std::max(worst.alpha, std::abs(r.state.alpha - reference.alpha()) / reference.alpha());
  }
  return worst;
}

}  // namespace

TEST_CASE("material-point path: uniaxial strain through yield, unloading and reverse yield is the closed form",
          "[materials][plasticity]") {
  const PathScene scene = read_path_scene(scenes + "uniaxial.toml");
  const J2Plasticity& law = linear_j2(scene);
  // The scene's path is the README's: F = diag(1, 1 - eps(t)), eps(t) = 0.01 (t <= 1 ? t : 2 - t),
  // and its turning point t = 1 is an increment (the return is exact between turning points).
  for (const double t : {0.0, 0.25, 1.0, 1.5, 2.0, 3.0}) {
    const Mat2 f = scene.deformation(t);
    CHECK(f(0, 0) == 1.0);
    CHECK(f(0, 1) == 0.0);
    CHECK(f(1, 0) == 0.0);
    CHECK(f(1, 1) == Approx(1.0 - 0.01 * (t <= 1.0 ? t : 2.0 - t)).margin(1e-15));
  }
  REQUIRE(scene.path.end_time == 3.0);
  REQUIRE(scene.path.increments % 3 == 0);
  const double e_max = 1.0 - scene.deformation(1.0)(1, 1);  // 0.01, as the strain the law sees

  const std::vector<PathRecord> rows = run_strain_path(scene.material.material, scene.deformation_path(), scene.path);
  REQUIRE(rows.size() == static_cast<std::size_t>(scene.path.increments) + 1);
  double worst_stress = 0.0, worst_alpha = 0.0, worst_plastic = 0.0, worst_energy = 0.0;
  double alpha_at_turn = 0.0;
  bool elastic_unloading = false;
  for (const PathRecord& r : rows) {
    const double e = r.deformation(1, 1) - 1.0;  // eps_yy
    const UniaxialExact x = uniaxial_exact(law, e_max, r.time, e);
    if (r.time == 0.0) {
      CHECK(stress_of(r).norm() == 0.0);
      continue;
    }
    worst_stress = std::max(worst_stress, norm(stress_of(r) - x.stress) / norm(x.stress));
    if (x.alpha > 0.0) {
      worst_alpha = std::max(worst_alpha, std::abs(r.state.alpha - x.alpha) / x.alpha);
      worst_plastic = std::max(worst_plastic, norm(plastic_strain_of(r) - x.plastic_strain) / norm(x.plastic_strain));
    } else {
      CHECK(r.state.alpha == 0.0);
    }
    worst_energy = std::max(worst_energy, std::abs(r.stored_energy - x.stored_energy) / x.stored_energy);
    CHECK(r.cauchy(0, 1) == 0.0);
    if (r.time == 1.0) alpha_at_turn = r.state.alpha;
    if (r.time > 1.0 && r.time < 1.2 && r.state.alpha == alpha_at_turn) elastic_unloading = true;
  }
  // Round-off: the radial return is the closed form at every increment.
  CHECK(worst_stress < 1e-10);
  CHECK(worst_alpha < 1e-10);
  CHECK(worst_plastic < 1e-10);
  CHECK(worst_energy < 1e-10);
  // The path does what the README says: yield in compression, elastic unloading, reverse yield.
  CHECK(alpha_at_turn > 0.0);
  CHECK(elastic_unloading);
  const PathRecord& end = rows.back();
  CHECK(end.state.alpha > alpha_at_turn);
  CHECK(end.state.plastic_strain(1, 1) > rows[1000 * scene.path.increments / 3000].state.plastic_strain(1, 1));
  // The plastic work sums sigma_{n+1} : dE_p (first order in the increment): within 1e-3 of
  // the integral here, and above it (the integrand grows along each plastic branch).
  const double work = uniaxial_exact(law, e_max, end.time, end.deformation(1, 1) - 1.0).plastic_work;
  CHECK(end.state.dissipation == Approx(work).epsilon(1e-3));
  CHECK(end.state.dissipation > work);
}

TEST_CASE("material-point path: tension then shear converges at first order to the integrated rate equations",
          "[materials][plasticity]") {
  const PathScene scene = read_path_scene(scenes + "tension_shear.toml");
  const J2Plasticity& law = linear_j2(scene);
  // The scene's path is the test's: F_yy = 1 + e1 min(t, 1), F_xy = g1 max(t - 1, 0).
  const double e1 = 0.008, g1 = 0.01;
  for (const double t : {0.0, 0.5, 1.0, 1.25, 2.0}) {
    const Mat2 f = scene.deformation(t);
    CHECK(f(0, 0) == 1.0);
    CHECK(f(1, 0) == 0.0);
    CHECK(f(0, 1) == Approx(g1 * std::max(t - 1.0, 0.0)).margin(1e-15));
    CHECK(f(1, 1) == Approx(1.0 + e1 * std::min(t, 1.0)).margin(1e-15));
  }
  REQUIRE(scene.path.end_time == 2.0);
  const double h = 1e-5;  // RK4 step: 2e5 steps over the path, error far below 1e-12

  SECTION("10^6 increments: stress, plastic strain and alpha within 1e-6 of the reference along the path") {
    REQUIRE(scene.path.increments == 1000000);
    const std::vector<PathRecord> rows = run_strain_path(scene.material.material, scene.deformation_path(), scene.path);
    REQUIRE(rows.size() == scene.path.recorded());
    REQUIRE(rows.back().time == 2.0);
    // The reference is converged: four times its step changes it by 5e-12 (RK4: its own
    // error is 4^4 = 256 times smaller).
    TensionShearReference reference(law, e1, g1, h), coarse(law, e1, g1, 4.0 * h);
    reference.advance_to(2.0);
    coarse.advance_to(2.0);
    CHECK(reference.steps() >= 200000);
    CHECK(norm(coarse.stress() - reference.stress()) < 1e-10 * norm(reference.stress()));
    CHECK(norm(coarse.plastic_strain() - reference.plastic_strain()) < 1e-10 * norm(reference.plastic_strain()));
    const PathErrors e = tension_shear_errors(rows, law, e1, g1, h);
    CHECK(e.stress < 1e-6);
    CHECK(e.plastic_strain < 1e-6);
    CHECK(e.alpha < 1e-6);
    // The shear turned the stress: sigma_xy has grown, and the axial stress relaxed below its
    // value at the end of the tension.
    const PathRecord& end = rows.back();
    const auto at_one = std::find_if(rows.begin(), rows.end(), [](const PathRecord& r) { return r.time >= 1.0; });
    REQUIRE(at_one != rows.end());
    CHECK(end.cauchy(0, 1) > 0.5 * law.yield_stress / std::sqrt(3.0));
    CHECK(end.cauchy(1, 1) < at_one->cauchy(1, 1));
  }

  SECTION("the return's error falls at first order: 10 times the increments, a tenth of the error") {
    std::vector<PathErrors> errors;
    for (const int n : {2000, 20000}) {
      StrainPathSettings s = scene.path;
      s.increments = n;
      s.record_every = n;  // increments 0 and N
      const std::vector<PathRecord> rows = run_strain_path(scene.material.material, scene.deformation_path(), s);
      REQUIRE(rows.size() == 2);
      errors.push_back(tension_shear_errors(rows, law, e1, g1, h));
    }
    INFO("stress errors " << errors[0].stress << ", " << errors[1].stress << "; plastic strain " << errors[0].plastic_strain
                          << ", " << errors[1].plastic_strain);
    CHECK(errors[0].stress / errors[1].stress == Approx(10.0).epsilon(0.05));
    CHECK(errors[0].plastic_strain / errors[1].plastic_strain == Approx(10.0).epsilon(0.05));
    CHECK(errors[0].alpha / errors[1].alpha == Approx(10.0).epsilon(0.05));
  }
}

TEST_CASE("material-point path: J <= 0 on the way is a numerical error naming the increment and its time",
          "[materials][plasticity]") {
  const PathScene scene = read_path_scene(scenes + "uniaxial.toml");
  StrainPathSettings s;
  s.end_time = 2.0;
  s.increments = 8;
  // F_yy = 1 - t: J = 0 at t = 1, increment 4.
  const DeformationPath collapse = [](double t) { return Mat2(Eigen::DiagonalMatrix<double, 2>(1.0, 1.0 - t).toDenseMatrix()); };
  const std::string what =
      testing::message_of<NumericalError>([&] { (void)run_strain_path(scene.material.material, collapse, s); });
  CHECK_THAT(what, Catch::Contains("increment 4 of 8 (t = 1)"));
  CHECK_THAT(what, Catch::Contains("J"));
  s.record_every = 3;
  CHECK(s.recorded() == 4);  // 0, 3, 6 and 8
  s.record_every = 0;
  CHECK_THROWS_AS(run_strain_path(scene.material.material, collapse, s), InputError);
}

TEST_CASE("material-point path scenes: wrong input is refused naming the key", "[materials][plasticity][io]") {
  const std::string file = scenes + "uniaxial.toml";
  CHECK(is_path_scene(file));
  CHECK(is_path_scene(scenes + "tension_shear.toml"));
  const auto error = [&](const std::string& setting) {
    return testing::message_of<InputError>([&] { (void)read_path_scene(file, {setting}); });
  };
  // A material point has no position: x, y, X, Y are refused, also beside t.
  for (const std::string f : {"x", "1 + 0.01 * y", "1 + t * X"}) {
    const std::string what = error("path.deformation_gradient=[1, \"" + f + "\", 0, 1]");
    INFO(what);
    CHECK_THAT(what, Catch::Contains("key 'path.deformation_gradient[1]'"));
    CHECK_THAT(what, Catch::Contains("no position"));
  }
  CHECK_THAT(error("path.increments=0"), Catch::Contains("key 'path.increments'") && Catch::Contains("out of range"));
  CHECK_THAT(error("path.increments=2.5"), Catch::Contains("key 'path.increments'"));
  CHECK_THAT(error("path.end_time=0"), Catch::Contains("key 'path.end_time'"));
  CHECK_THAT(error("path.record_every=0"), Catch::Contains("key 'path.record_every'"));
  CHECK_THAT(error("path.deformation_gradient=[1, 0, 1]"), Catch::Contains("key 'path.deformation_gradient'"));
  CHECK_THAT(error("path.deformation_gradient=[1, 0, 0, \"1 - s\"]"), Catch::Contains("path.deformation_gradient[3]"));
  CHECK_THAT(error("path.increment=10"), Catch::Contains("key 'path.increment'") && Catch::Contains("unknown key"));
  CHECK_THAT(error("material.density=7800"), Catch::Contains("key 'material.density'"));
  CHECK_THAT(error("material.yield_stress=-1"), Catch::Contains("key 'material.yield_stress'"));
  // A formula that is not finite at an end of the path fails when the scene is read.
  CHECK_THAT(error("path.deformation_gradient=[1, 0, 0, \"1 + 1 / t\"]"), Catch::Contains("path.deformation_gradient[3]"));
  // The scene as written reads.
  CHECK(error("path.record_every=10") == "<nothing thrown>");
}
