#include "mfree/io/mpm_output.hpp"

#include <fmt/format.h>

#include <system_error>
#include <utility>

#include "mfree/core/error.hpp"
#include "mfree/io/vtk_output.hpp"

namespace mfree {

namespace {

/// The basis functions of an axis at its cell corners lo + k h, k = 0 .. cells. The far
/// corner is lo + cells h, the same expression as hi(), so it lies on the axis exactly.
std::vector<BSplineAxis::Values> at_corners(const BSplineAxis& axis) {
  std::vector<BSplineAxis::Values> values;
  values.reserve(static_cast<std::size_t>(axis.cells()) + 1);
  for (int k = 0; k <= axis.cells(); ++k) values.push_back(axis.evaluate(axis.lo() + k * axis.spacing()));
  return values;
}

/// Appends (time, file) to a series and rewrites its .pvd. The list changes only once the
/// file is written, so after a failure it still matches the .pvd on disk.
void append_step(const std::filesystem::path& pvd, std::vector<std::pair<double, std::string>>& steps, double time,
                 const std::string& file) {
  std::vector<std::pair<double, std::string>> next = steps;
  next.emplace_back(time, file);
  write_pvd(pvd, next);
  steps = std::move(next);
}

std::string particle_file(int frame) { return fmt::format("particles_{:04d}.vtu", frame); }
std::string grid_file(int frame) { return fmt::format("grid_{:04d}.vti", frame); }
std::string domain_file(int frame) { return fmt::format("domains_{:04d}.vtu", frame); }

}  // namespace

void MPMFrames::save(CheckpointState& state) const {
  std::vector<double> times, grid;
  for (std::size_t k = 0, g = 0; k < steps_.size(); ++k) {
    times.push_back(steps_[k].first);
    const bool has_grid = g < grid_steps_.size() && grid_steps_[g].second == grid_file(static_cast<int>(k));
    grid.push_back(has_grid ? 1.0 : 0.0);
    g += has_grid;
  }
  state.put("frames.time", std::move(times));
  state.put("frames.grid", std::move(grid));
}

void MPMFrames::restore(const CheckpointState& state, double time, std::size_t most) {
  const std::vector<double>& times = state.times("frames.time", time, most);
  const std::vector<long long> grid = state.integers("frames.grid", 0, 1, "0 or 1", times.size());
  steps_.clear();
  grid_steps_.clear();
  domain_steps_.clear();
  for (std::size_t k = 0; k < times.size(); ++k) {
    steps_.emplace_back(times[k], particle_file(static_cast<int>(k)));
    if (grid[k] != 0) grid_steps_.emplace_back(times[k], grid_file(static_cast<int>(k)));
    if (fields_.domains) domain_steps_.emplace_back(times[k], domain_file(static_cast<int>(k)));
  }
}

std::string particle_table(const Particles& P, const std::vector<MPMBody>& bodies) {
  std::string out = "body,X,Y,x,y,vx,vy,sxx,syy,sxy\n";
  for (Index p = 0; p < P.size(); ++p) {
    const Mat2& s = P.stress[p];
    if (!P.position[p].allFinite() || !P.velocity[p].allFinite() || !s.allFinite())
      throw NumericalError(fmt::format("particle table: particle {} has a non-finite position, velocity or stress", p));
    out += fmt::format("{},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e}\n",
                       bodies.at(static_cast<std::size_t>(P.body[p])).name, P.reference[p].x(), P.reference[p].y(),
                       P.position[p].x(), P.position[p].y(), P.velocity[p].x(), P.velocity[p].y(), s(0, 0), s(1, 1),
                       s(0, 1));
  }
  return out;
}

MPMFrames::MPMFrames(std::filesystem::path folder, MPMFrameFields fields, const ExactMotion<2>* exact,
                     std::vector<MPMMaterial> materials)
    : folder_(std::move(folder)), fields_(fields), exact_(exact), materials_(std::move(materials)) {
  if (fields_.error && exact_ == nullptr)
    throw InputError(fmt::format("MPM output to {}: the error fields need an exact solution, and this problem has none",
                                 folder_.string()));
  std::error_code ec;
  std::filesystem::create_directories(folder_, ec);
  if (ec) throw Error(fmt::format("cannot create the output folder {}: {}", folder_.string(), ec.message()));
}

void MPMFrames::write(const MPMSolver& solver) {
  const Particles& P = solver.particles();
  const double t = solver.time();
  std::vector<double> u, v, sigma, vm, ep, body, ue, se;
  for (Index p = 0; p < P.size(); ++p) {
    const Vec2 up = P.position[p] - P.reference[p];
    const Mat2& s = P.stress[p];
    if (fields_.displacement) u.insert(u.end(), {up.x(), up.y()});
    if (fields_.velocity) v.insert(v.end(), {P.velocity[p].x(), P.velocity[p].y()});
    if (fields_.stress) sigma.insert(sigma.end(), {s(0, 0), s(1, 1), s(0, 1)});
    if (fields_.von_mises) vm.push_back(von_mises(s, P.stress_zz[p]));
    if (fields_.plastic_strain) ep.push_back(P.state[p].alpha);
    if (fields_.body) body.push_back(P.body[p]);
    if (fields_.error) {
      // Errors at the particle's reference position: the exact motion is Lagrangian.
      const Vec2 eu = up - exact_->displacement(P.reference[p], t);
      const Mat2 es = s - exact_->cauchy_stress(P.reference[p], t);
      ue.insert(ue.end(), {eu.x(), eu.y()});
      se.insert(se.end(), {es(0, 0), es(1, 1), es(0, 1)});
    }
  }
  std::vector<PointField> fields;
  if (fields_.displacement) fields.push_back({"displacement", 2, std::move(u)});
  if (fields_.velocity) fields.push_back({"velocity", 2, std::move(v)});
  if (fields_.stress) fields.push_back({"stress", 3, std::move(sigma)});
  if (fields_.von_mises) fields.push_back({"von_mises", 1, std::move(vm)});
  if (fields_.plastic_strain) fields.push_back({"plastic_strain", 1, std::move(ep)});
  if (fields_.body) fields.push_back({"body", 1, std::move(body)});
  if (fields_.error) {
    fields.push_back({"displacement_error", 2, std::move(ue)});
    fields.push_back({"stress_error", 3, std::move(se)});
  }
  const int frame = frames();
  const std::string name = particle_file(frame);
  write_point_cloud_vtu(folder_ / name, P.position, fields);
  // Every data file before any series: a failure in one leaves the series as they were.
  const bool grid_frame = fields_.grid && !solver.grid_mass().empty();
  const std::string grid_name = grid_file(frame), domain_name = domain_file(frame);
  if (grid_frame) write_grid(solver, grid_name);
  if (fields_.domains) write_domains(solver, domain_name);
  append_step(series(), steps_, t, name);
  if (grid_frame) append_step(grid_series(), grid_steps_, t, grid_name);
  if (fields_.domains) append_step(domain_series(), domain_steps_, t, domain_name);
}

void MPMFrames::write_domains(const MPMSolver& solver, const std::string& name) const {
  const Particles& P = solver.particles();
  const ParticleBasis& basis = solver.basis();
  if (!uses_domains(basis.method()))
    throw InputError(fmt::format("MPM output to {}: method {} has no particle domains to write", folder_.string(),
                                 to_string(basis.method())));
  const auto n = static_cast<std::size_t>(P.size());
  std::vector<Vec2> corners;
  corners.reserve(4 * n);
  std::vector<std::array<Index, 4>> quads(n);
  std::vector<double> body;
  body.reserve(4 * n);
  for (Index p = 0; p < P.size(); ++p) {
    const DomainCorners c = basis.domain_corners(P, p);
    for (int k = 0; k < 4; ++k) {
      quads[static_cast<std::size_t>(p)][static_cast<std::size_t>(k)] = static_cast<Index>(corners.size());
      corners.push_back(c[static_cast<std::size_t>(k)]);
      body.push_back(P.body[p]);
    }
  }
  write_quads_vtu(folder_ / name, corners, quads, {{"body", 1, std::move(body)}});
}

void MPMFrames::write_grid(const MPMSolver& solver, const std::string& name) {
  const Grid& grid = solver.grid();
  const std::vector<BSplineAxis::Values> wx = at_corners(grid.x_axis()), wy = at_corners(grid.y_axis());
  const int terms_x = grid.x_axis().degree() + 1, terms_y = grid.y_axis().degree() + 1;
  const std::vector<Vec2>& nodal_velocity = solver.grid_velocity();
  const std::vector<double>& nodal_mass = solver.grid_mass();
  const double h = grid.spacing();
  std::vector<double> velocity, mass;
  velocity.reserve(2 * wx.size() * wy.size());
  mass.reserve(wx.size() * wy.size());
  // x fastest, as write_image_vti orders the points.
  for (const BSplineAxis::Values& y : wy) {
    for (const BSplineAxis::Values& x : wx) {
      Vec2 vh = Vec2::Zero();
      double mh = 0.0;
      for (int l = 0; l < terms_y; ++l) {
        for (int k = 0; k < terms_x; ++k) {
          const double n = x.value[k] * y.value[l];
          const auto i = static_cast<std::size_t>(grid.index(x.first + k, y.first + l));
          vh += n * nodal_velocity[i];
          mh += n * nodal_mass[i];
        }
      }
      velocity.insert(velocity.end(), {vh.x(), vh.y()});
      mass.push_back(mh / (h * h));
    }
  }
  write_image_vti(folder_ / name, grid.extent().lo, h, static_cast<int>(wx.size()), static_cast<int>(wy.size()),
                  {{"velocity", 2, std::move(velocity)}, {"mass", 1, std::move(mass)}});
}

}  // namespace mfree
