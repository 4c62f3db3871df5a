#include "mfree/apps/integration_study.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>
#include <ostream>

#include "mfree/core/error.hpp"
#include "mfree/core/parallel.hpp"
#include "mfree/geometry/tetrahedral_mesh.hpp"
#include "mfree/io/read_choice.hpp"
#include "mfree/io/solid_scene.hpp"
#include "mfree/problems/integration_functions.hpp"
#include "mfree/quadrature/background_lattice.hpp"
#include "mfree/quadrature/gauss_cells.hpp"
#include "mfree/quadrature/rk_quadrature.hpp"
#include "mfree/quadrature/tetrahedron_rule.hpp"
#include "mfree/quadrature/voronoi_weights.hpp"

namespace mfree {

const NameTable<WeightScheme>& weight_scheme_names() {
  static const NameTable<WeightScheme> table{{"rk", WeightScheme::rk},
                                             {"voronoi", WeightScheme::voronoi},
                                             {"gauss_cells", WeightScheme::gauss_cells},
                                             {"equal", WeightScheme::equal}};
  return table;
}

IntegrationStudySettings read_integration_study(const SceneTable& root) {
  IntegrationStudySettings s;
  if (const SceneTable d = root.table("domain"); d.has("box") || d.has("solid")) {
    s.solid = read_solid_domain(d);
  } else {
    const auto lo = d.numbers("lo", 2, -1e300, 1e300), hi = d.numbers("hi", 2, -1e300, 1e300);
    s.rectangle = Box{Vec2(lo[0], lo[1]), Vec2(hi[0], hi[1])};
    if (!(s.rectangle.hi.array() > s.rectangle.lo.array()).all())
      throw InputError(fmt::format("{}: domain.hi must exceed domain.lo in x and y", root.folder().string()));
    d.finish();
  }
  {
    const SceneTable t = root.table("study");
    for (double n : t.numbers("levels", 0, 2, 4000)) {
      if (n != std::floor(n)) throw InputError("study.levels: whole numbers of points expected");
      s.levels.push_back(static_cast<int>(n));
    }
    s.clouds = read_choices(t, "clouds", cloud_kind_names());
    s.perturbation = t.number_or("perturbation", s.perturbation, 0.0, 1.0);
    s.orders = read_choices(t, "orders", order_names());
    s.schemes = read_choices(t, "schemes", weight_scheme_names());
    if (s.solid && std::find(s.schemes.begin(), s.schemes.end(), WeightScheme::voronoi) != s.schemes.end())
      t.error("schemes", "Voronoi cells are plane only: a solid compares rk, gauss_cells and equal");
    s.functions = t.choices("functions", integration_functions<2>().names());
    s.seed = static_cast<std::uint64_t>(t.integer_or("seed", 1, 0, 1LL << 62));
    t.finish();
  }
  {
    const SceneTable k = root.table("kernel");
    s.window = read_choice_or(k, "window", window_names(), s.window);
    s.support = read_choice_or(k, "support", support_names(), s.support);
    s.factor_linear = k.number_or("factor_linear", s.factor_linear, 0.5, 10.0);
    s.factor_quadratic = k.number_or("factor_quadratic", s.factor_quadratic, 0.5, 10.0);
    s.random_factor_scale = k.number_or("random_factor_scale", s.random_factor_scale, 1.0, 5.0);
    k.finish();
  }
  {
    const SceneTable q = root.table("quadrature");
    s.lattice_refinement = static_cast<int>(q.integer_or("lattice_refinement", s.lattice_refinement, 1, 64));
    s.gauss_points = static_cast<int>(q.integer_or("gauss_points", s.gauss_points, 1, 10));
    q.finish();
  }
  root.finish();
  return s;
}

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

double measure(const Domain& d) { return d.area(); }
double measure(const Solid& s) { return s.measure(); }

/// Integral of x over the domain.
Vec2 first_moment(const Domain& d) { return d.first_moment(); }
Point<3> first_moment(const Solid& s) {
  const TetrahedralMesh* mesh = s.mesh();
  if (!mesh) return s.measure() * s.bounding_box().center();
  Point<3> m = Point<3>::Zero();
  for (Index k = 0; k < mesh->size(); ++k) {
    const Tetrahedron t = mesh->tetrahedron(k);
    m += tetrahedron_volume(t) * tetrahedron_centroid(t);
  }
  return m;
}

/// The integral of f over a solid's tetrahedra (6 Gauss points a direction of the collapsed
/// rule: degree 9), for a meshed solid; the box's closed form otherwise.
void integrate_over_solid(const Solid& solid, IntegrandOf<3>& integrand) {
  const TetrahedralMesh* mesh = solid.mesh();
  if (!mesh) return;
  const GaussLegendre1D g = gauss_legendre(6);
  double sum = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : sum)
  for (Index k = 0; k < mesh->size(); ++k) {
    QuadratureRule<3> rule;
    add_tetrahedron_rule(mesh->tetrahedron(k), g, rule);
    for (std::size_t p = 0; p < rule.size(); ++p) sum += rule.weights[p] * integrand.f(rule.points[p]);
  }
  integrand.integral = sum;
}

/// The study on one domain (a rectangle or a solid), dim its dimension.
template <int dim>
std::vector<IntegrationRow> run_levels(const IntegrationStudySettings& s, const DomainOf<dim>& domain,
                                       std::ostream& log) {
  const double volume = measure(domain);
  const Point<dim> moment = first_moment(domain);
  Point<dim> lo, hi;
  if constexpr (dim == 2) {
    lo = s.rectangle.lo;
    hi = s.rectangle.hi;
  } else {
    lo = domain.bounding_box().min();
    hi = domain.bounding_box().max();
  }
  const double diameter = (hi - lo).norm();
  std::vector<IntegrandOf<dim>> functions;
  for (const std::string& name : s.functions) {
    functions.push_back(integration_functions<dim>().value(name)(lo, hi));
    if constexpr (dim == 3) integrate_over_solid(domain, functions.back());
  }
  const double short_side = (hi - lo).minCoeff();
  std::vector<IntegrationRow> rows;

  const auto record = [&](const std::string& cloud, const std::string& order, const std::string& scheme,
                          int level, const std::vector<Point<dim>>& x, const std::vector<double>& w,
                          double seconds) {
    double sum = 0.0;
    Point<dim> first = Point<dim>::Zero();
    for (std::size_t k = 0; k < x.size(); ++k) {
      sum += w[k];
      first += w[k] * x[k];
    }
    const NegativeWeights neg = negative_weights(w);
    for (std::size_t i = 0; i < functions.size(); ++i) {
      const IntegrandOf<dim>& tf = functions[i];
      double integral = 0.0;
      for (std::size_t k = 0; k < x.size(); ++k) integral += w[k] * tf.f(x[k]);
      IntegrationRow r;
      r.function = s.functions[i];
      r.cloud = cloud;
      r.order = order;
      r.scheme = scheme;
      r.level = level;
      r.points = static_cast<Index>(x.size());
      const double per_point = volume / static_cast<double>(x.size());
      r.spacing = dim == 2 ? std::sqrt(per_point) : std::cbrt(per_point);
      r.error = std::abs(integral - tf.integral);
      r.relative_error = r.error / std::abs(tf.integral);
      r.area_error = std::abs(sum - volume) / volume;
      r.moment_error = (first - moment).cwiseAbs().maxCoeff() / (volume * diameter);
      r.seconds = seconds;
      r.negative = neg.count;
      r.most_negative = neg.most_negative;
      rows.push_back(r);
    }
  };

  const auto total_start = Clock::now();
  for (std::size_t li = 0; li < s.levels.size(); ++li) {
    const int level = s.levels[li];
    const double h = short_side / level;
    for (CloudKind kind : s.clouds) {
      CloudSettings cs;
      cs.kind = kind;
      cs.spacing = h;
      cs.perturbation = kind == CloudKind::perturbed ? s.perturbation : 0.0;
      cs.seed = s.seed + static_cast<std::uint64_t>(level);
      cs.cell_centred = true;
      const std::vector<Point<dim>> cloud = make_cloud(domain, cs);
      const std::string cname(to_string(kind));

      for (const WeightScheme scheme : s.schemes) {
        const std::string sname(weight_scheme_names().name(scheme));
        switch (scheme) {
          case WeightScheme::rk:
            for (RKOrder order : s.orders) {
              const auto t0 = Clock::now();
              RKSettings rs;
              rs.order = order;
              rs.window = s.window;
              rs.support = s.support;
              const double factor = order == RKOrder::linear ? s.factor_linear : s.factor_quadratic;
              rs.radius = factor * h;
              // Irregular clouds: nodes beside a gap reach across it (nodal_support_radii).
              if (kind != CloudKind::lattice)
                rs.node_radii = nodal_support_radii(cloud, h, factor * s.random_factor_scale);
              const RKShapeFunctions<dim> rk(cloud, rs);
              const BackgroundLattice<dim> lattice(domain, h / s.lattice_refinement,
                                                   order == RKOrder::linear ? 1 : 2);
              const std::vector<double> w = rk_quadrature_weights(rk, lattice);
              record(cname, std::string(to_string(order)), sname, level, cloud, w, seconds_since(t0));
            }
            break;
          case WeightScheme::voronoi:
            if constexpr (dim == 2) {
              const auto t0 = Clock::now();
              const std::vector<double> w = voronoi_weights(cloud, domain);
              record(cname, "-", sname, level, cloud, w, seconds_since(t0));
            }
            break;
          case WeightScheme::equal: {
            const auto t0 = Clock::now();
            const std::vector<double> w(cloud.size(), volume / static_cast<double>(cloud.size()));
            record(cname, "-", sname, level, cloud, w, seconds_since(t0));
            break;
          }
          case WeightScheme::gauss_cells:  // independent of the clouds: below
            break;
        }
      }
    }
    if (std::find(s.schemes.begin(), s.schemes.end(), WeightScheme::gauss_cells) != s.schemes.end()) {
      // Independent of the clouds: n^dim points per cell of side n h, as many points as a
      // lattice cloud of this level.
      const auto t0 = Clock::now();
      const QuadratureRule<dim> g = gauss_cell_rule(domain, s.gauss_points * h, s.gauss_points);
      record("-", "-", "gauss_cells", level, g.points, g.weights, seconds_since(t0));
    }
    log << fmt::format("  level {}/{}: {} points across, {:.1f} s elapsed, {} thread(s)\n", li + 1,
                       s.levels.size(), level, seconds_since(total_start), thread_count())
        << std::flush;
  }
  return rows;
}

}  // namespace

std::vector<IntegrationRow> run_integration_study(const IntegrationStudySettings& s, std::ostream& log) {
  if (s.solid) {
    const Solid& solid = *s.solid;
    log << fmt::format(
        "  solid: {}, volume {:.10g}\n",
        solid.mesh() ? fmt::format("{} tetrahedra", solid.mesh()->size()) : std::string("a box"),
        solid.measure());
    return run_levels<3>(s, solid, log);
  }
  return run_levels<2>(s, Domain::rectangle(s.rectangle.lo, s.rectangle.hi), log);
}

std::string integration_csv(const std::vector<IntegrationRow>& rows) {
  std::string out =
      "function,cloud,order,scheme,level,points,spacing,error,relative_error,area_error,seconds,"
      "negative_weights,most_negative,moment_error\n";
  for (const auto& r : rows)
    out += fmt::format("{},{},{},{},{},{},{:.9e},{:.9e},{:.9e},{:.3e},{:.6e},{},{:.6e},{:.3e}\n", r.function,
                       r.cloud, r.order, r.scheme, r.level, r.points, r.spacing, r.error, r.relative_error,
                       r.area_error, r.seconds, r.negative, r.most_negative, r.moment_error);
  return out;
}

std::string integration_report(const std::vector<IntegrationRow>& rows) {
  // Group rows into series (function, cloud, scheme, order), levels in order.
  std::map<std::string, std::vector<const IntegrationRow*>> series;
  for (const auto& r : rows)
    series[fmt::format("{:<3} {:<9} {:<11} {:<9}", r.function, r.cloud, r.scheme, r.order)].push_back(&r);
  std::string out = fmt::format("{:<3} {:<9} {:<11} {:<9} {:>8} {:>11} {:>10} {:>6} {:>9}  {}\n",
                                "f", "cloud", "scheme", "order", "points", "h", "error", "rate",
                                "time [s]", "negative weights (count, most negative)");
  for (const auto& [key, list] : series) {
    for (std::size_t k = 0; k < list.size(); ++k) {
      const IntegrationRow& r = *list[k];
      std::string rate = "";
      if (k > 0 && r.error > 0.0 && list[k - 1]->error > 0.0)
        rate = fmt::format("{:.2f}", std::log(list[k - 1]->error / r.error) /
                                         std::log(list[k - 1]->spacing / r.spacing));
      const std::string neg =
          r.order == "quadratic" ? fmt::format("{}, {:.3e}", r.negative, r.most_negative) : "";
      out += fmt::format("{} {:>8} {:>11.4e} {:>10.3e} {:>6} {:>9.4f}  {}\n", key, r.points,
                         r.spacing, r.error, rate, r.seconds, neg);
    }
  }
  // The rk weights integrate 1 and x exactly (the lattice's cut cells, the RK functions'
  // linear completeness): their sums against |Omega| and the first moment.
  double area = 0.0, moment = 0.0;
  for (const auto& r : rows)
    if (r.scheme == "rk") {
      area = std::max(area, r.area_error);
      moment = std::max(moment, r.moment_error);
    }
  out += fmt::format(
      "rk weights, every row: largest |sum w - |Omega|| / |Omega| {:.1e}, largest |sum w x - integral x| / "
      "(|Omega| diameter) {:.1e}\n",
      area, moment);
  return out;
}

}  // namespace mfree
