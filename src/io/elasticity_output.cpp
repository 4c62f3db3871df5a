#include "mfree/io/elasticity_output.hpp"

#include "mfree/geometry/domain_triangulation.hpp"
#include "mfree/io/vtk_output.hpp"

namespace mfree {

namespace {

std::vector<double> flatten(const std::vector<Vec2>& v) {
  std::vector<double> out;
  out.reserve(2 * v.size());
  for (const Vec2& x : v) out.insert(out.end(), {x.x(), x.y()});
  return out;
}

/// Displacement, stress and von Mises fields at points, from u^h = sum phi_I d_I and its
/// true gradients; exact values and errors when known. Only the fields asked for.
std::vector<PointField> sampled_fields(const ElasticityScene& scene, const ElasticityResult& r,
                                       const std::vector<Vec2>& points, const GalerkinQuadrature<2>* given,
                                       const std::optional<ExactElasticity>& exact) {
  const OutputSettings& o = scene.output;
  const bool need_stress = o.wants("stress") || o.wants("von_mises");
  const GalerkinQuadrature<2> sampled =
      given ? GalerkinQuadrature<2>{} : sample_shape_functions(*r.trial, points, need_stress);
  const GalerkinQuadrature<2>& at = given ? *given : sampled;
  std::vector<PointField> f;
  if (o.wants("displacement") || o.wants("error")) {
    std::vector<Vec2> u(points.size());
    for (Index k = 0; k < at.size(); ++k) u[k] = displacement_at(at, k, r.coefficients);
    if (o.wants("displacement")) f.push_back({"displacement", 2, flatten(u)});
    if (o.wants("error") && exact) {
      std::vector<Vec2> ue(points.size()), err(points.size());
      for (std::size_t k = 0; k < points.size(); ++k) {
        ue[k] = exact->displacement(points[k]);
        err[k] = u[k] - ue[k];
      }
      f.push_back({"exact_displacement", 2, flatten(ue)});
      f.push_back({"displacement_error", 2, flatten(err)});
    }
  }
  if (need_stress) {
    std::vector<double> s, vm, se;
    for (Index k = 0; k < at.size(); ++k) {
      const LinearElastic& m = scene.settings.problem.law_at(scene.domain, points[k]);
      const Eigen::Vector3d sk = m.voigt_tangent() * strain_at(at, k, r.coefficients);
      s.insert(s.end(), {sk[0], sk[1], sk[2]});
      vm.push_back(m.von_mises(sk));
      if (o.wants("error") && exact) {
        const Eigen::Vector3d ek = sk - exact->stress(points[k]);
        se.insert(se.end(), {ek[0], ek[1], ek[2]});
      }
    }
    if (o.wants("stress")) f.push_back({"stress_xx_yy_xy", 3, s});
    if (o.wants("von_mises")) f.push_back({"von_mises", 1, vm});
    if (!se.empty()) f.push_back({"stress_error_xx_yy_xy", 3, se});
  }
  return f;
}

}  // namespace

std::vector<std::filesystem::path> write_elasticity_fields(const ElasticityScene& scene, const ElasticityResult& r) {
  const std::optional<ExactElasticity> exact = scene.exact();
  const std::filesystem::path dir = scene.output.folder;
  write_point_cloud_vtu(dir / "nodes.vtu", r.nodes, sampled_fields(scene, r, r.nodes, nullptr, exact));
  std::vector<PointField> qf = sampled_fields(scene, r, r.quadrature.points, &r.quadrature, exact);
  if (scene.output.wants("weights")) qf.push_back({"weight", 1, r.quadrature.weights});
  write_point_cloud_vtu(dir / "quadrature.vtu", r.quadrature.points, qf);
  const Triangulation tri = triangulate_domain(scene.domain, r.nodes);
  write_triangles_vtu(dir / "field.vtu", tri.points, tri.triangles,
                      sampled_fields(scene, r, tri.samples, nullptr, exact));
  return {dir / "nodes.vtu", dir / "quadrature.vtu", dir / "field.vtu"};
}

}  // namespace mfree
