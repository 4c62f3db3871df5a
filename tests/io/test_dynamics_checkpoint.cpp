#include <catch2/catch.hpp>

#include "../test_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/io/dynamics_checkpoint.hpp"

using namespace mfree;
using mfree::testing::message_of;

namespace {

/// A progress of `dofs` unknowns with two plastic points whose every number differs.
template <int dim>
DynamicsProgress<dim> progress(int dofs) {
  DynamicsProgress<dim> p;
  p.step = 7;
  p.d = Eigen::VectorXd::LinSpaced(dofs, -1.0, 1.0);
  p.v = 2.0 * p.d;
  p.a = 3.0 * p.d;
  p.v_half = 4.0 * p.d;
  p.g = 5.0 * p.d;
  p.work = 0.25;
  p.energy = {{0.0, 1.0, 2.0, 3.0, 4.0}, {1e-3, 5.0, 6.0, 7.0, 8.0}};
  for (int k = 0; k < 2; ++k) {
    MaterialState<dim> m;
    m.plastic_strain = Tensor2<dim>::NullaryExpr(
        [k](Eigen::Index i, Eigen::Index j) { return 1e-3 * static_cast<double>(1 + k + 3 * i + 7 * j); });
    m.plastic_strain_zz = dim == 2 ? -0.5e-3 * (k + 1) : 0.0;
    m.alpha = 0.01 * (k + 1);
    m.dissipation = 17.0 * (k + 1);
    p.history.domain.push_back(m);
  }
  p.history.boundary = {p.history.domain[1]};
  p.newton_iterations = 11;
  p.factorisations = 3;
  p.tangent = Eigen::VectorXd::LinSpaced(5, 0.5, 2.5);
  return p;
}

template <int dim>
void check_round_trip() {
  const DynamicsProgress<dim> p = progress<dim>(3 * dim);
  CheckpointState s;
  save_progress(s, p);
  REQUIRE(s.get("history.domain").size() == 2 * (dim * dim + 3));
  const DynamicsProgress<dim> q = restore_progress<dim>(s, 7);
  CHECK(q.step == 7);
  CHECK(q.d == p.d);
  CHECK(q.v == p.v);
  CHECK(q.a == p.a);
  CHECK(q.v_half == p.v_half);
  CHECK(q.g == p.g);
  CHECK(q.work == p.work);
  REQUIRE(q.energy.size() == 2);
  CHECK(q.energy[1].strain == 6.0);
  CHECK(q.energy[1].dissipated == 8.0);
  REQUIRE(q.history.domain.size() == 2);
  REQUIRE(q.history.boundary.size() == 1);
  for (std::size_t k = 0; k < 2; ++k) {
    CHECK(q.history.domain[k].plastic_strain == p.history.domain[k].plastic_strain);
    CHECK(q.history.domain[k].plastic_strain_zz == p.history.domain[k].plastic_strain_zz);
    CHECK(q.history.domain[k].alpha == p.history.domain[k].alpha);
    CHECK(q.history.domain[k].dissipation == p.history.domain[k].dissipation);
  }
  CHECK(q.history.boundary[0].plastic_strain == p.history.domain[1].plastic_strain);
  CHECK(q.newton_iterations == 11);
  CHECK(q.factorisations == 3);
  CHECK(q.tangent == p.tangent);
}

}  // namespace

TEST_CASE("dynamics checkpoints: the integrator's state comes back bit for bit, plane and solid",
          "[io][checkpoint]") {
  check_round_trip<2>();
  check_round_trip<3>();
  // The plane's layout of a material state (7 numbers: xx, yx, xy, yy, zz, alpha, dissipation),
  // the one earlier checkpoints hold.
  CheckpointState s;
  save_progress(s, progress<2>(4));
  const std::vector<double>& h = s.get("history.domain");
  CHECK(h[1] == 1e-3 * (1 + 3));  // E_p,yx of point 0
  CHECK(h[2] == 1e-3 * (1 + 7));  // E_p,xy
  CHECK(h[4] == -0.5e-3);
  CHECK(h[5] == 0.01);
}

TEST_CASE("dynamics checkpoints: broken material states and error records are refused", "[io][checkpoint]") {
  CheckpointState s;
  s.source = "cut.checkpoints/step_0000000007/state.bin";
  save_progress(s, progress<3>(9));
  std::vector<double> h = s.get("history.domain");
  // A plane checkpoint's states (7 numbers) in a solid run.
  s.put("history.domain", std::vector<double>(14, 0.0));
  CHECK_THAT(message_of<InputError>([&] { (void)restore_progress<3>(s, 7); }),
             Catch::Contains("array 'history.domain': it holds 14 numbers, not 12 per point"));
  h[12 + 10] = -1e-3;  // alpha of point 1
  s.put("history.domain", h);
  CHECK_THAT(message_of<InputError>([&] { (void)restore_progress<3>(s, 7); }),
             Catch::Contains("value 22 is -0.001, not an equivalent plastic strain (0 or more)"));
  CHECK_THAT(message_of<InputError>([&] { (void)restore_progress<3>(s, 8); }),
             Catch::Contains("array 'step': value 0 is 7, not the checkpoint's step 8"));

  save_errors(s, {{1e-3, 0.1, 0.2, 0.3}, {2e-3, 0.4, 0.5, 0.6}});
  CHECK(restore_errors(s, 20, 2e-3, 2).back().stress == 0.6);
  CHECK_THAT(message_of<InputError>([&] { (void)restore_errors(s, 10, 1e-3, 2); }),
             Catch::Contains("array 'errors': value 4 is 0.002, after the run's time 0.001 s at step 10"));
  CHECK_THAT(message_of<InputError>([&] { (void)restore_errors(s, 20, 2e-3, 1); }),
             Catch::Contains("it holds 8 numbers, not 4 for each of at most 1 error times"));
  s.put("errors", std::vector<double>{1e-3, -0.1, 0.2, 0.3});
  CHECK_THAT(message_of<InputError>([&] { (void)restore_errors(s, 20, 2e-3, 2); }),
             Catch::Contains("value 1 is -0.1, not a time or an error (0 or more)"));
}
