#include "mfree/apps/integration_study.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <functional>
#include <map>
#include <numbers>
#include <ostream>

#include "mfree/core/error.hpp"
#include "mfree/core/parallel.hpp"
#include "mfree/io/read_choice.hpp"
#include "mfree/problems/integration_functions.hpp"
#include "mfree/quadrature/background_lattice.hpp"
#include "mfree/quadrature/gauss_cells.hpp"
#include "mfree/quadrature/rk_quadrature.hpp"
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
  {
    const SceneTable d = root.table("domain");
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
    s.functions = t.choices("functions", integration_functions().names());
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

}  // namespace

std::vector<IntegrationRow> run_integration_study(const IntegrationStudySettings& s, std::ostream& log) {
  const Domain domain = Domain::rectangle(s.rectangle.lo, s.rectangle.hi);
  const double area = domain.area();
  std::vector<Integrand> functions;
  for (const std::string& name : s.functions) functions.push_back(integration_functions().value(name)(s.rectangle));
  const double short_side = s.rectangle.size().minCoeff();
  std::vector<IntegrationRow> rows;

  const auto record = [&](const std::string& cloud, const std::string& order, const std::string& scheme,
                          int level, const std::vector<Vec2>& x, const std::vector<double>& w,
                          double seconds) {
    double sum = 0.0;
    for (double wk : w) sum += wk;
    const NegativeWeights neg = negative_weights(w);
    for (std::size_t i = 0; i < functions.size(); ++i) {
      const Integrand& tf = functions[i];
      double integral = 0.0;
      for (std::size_t k = 0; k < x.size(); ++k) integral += w[k] * tf.f(x[k]);
      IntegrationRow r;
      r.function = s.functions[i];
      r.cloud = cloud;
      r.order = order;
      r.scheme = scheme;
      r.level = level;
      r.points = static_cast<Index>(x.size());
      r.spacing = std::sqrt(area / static_cast<double>(x.size()));
      r.error = std::abs(integral - tf.integral);
      r.relative_error = r.error / std::abs(tf.integral);
      r.area_error = std::abs(sum - area) / area;
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
      const std::vector<Vec2> cloud = make_cloud(domain, cs);
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
              const RKShapeFunctions<2> rk(cloud, rs);
              const BackgroundLattice<2> lattice(domain, h / s.lattice_refinement,
                                                 order == RKOrder::linear ? 1 : 2);
              const std::vector<double> w = rk_quadrature_weights(rk, lattice);
              record(cname, std::string(to_string(order)), sname, level, cloud, w, seconds_since(t0));
            }
            break;
          case WeightScheme::voronoi: {
            const auto t0 = Clock::now();
            const std::vector<double> w = voronoi_weights(cloud, domain);
            record(cname, "-", sname, level, cloud, w, seconds_since(t0));
            break;
          }
          case WeightScheme::equal: {
            const auto t0 = Clock::now();
            const std::vector<double> w(cloud.size(), area / static_cast<double>(cloud.size()));
            record(cname, "-", sname, level, cloud, w, seconds_since(t0));
            break;
          }
          case WeightScheme::gauss_cells:  // independent of the clouds: below
            break;
        }
      }
    }
    if (std::find(s.schemes.begin(), s.schemes.end(), WeightScheme::gauss_cells) != s.schemes.end()) {
      // Independent of the clouds: n x n points per cell of side n h, as many points as a
      // lattice cloud of this level.
      const auto t0 = Clock::now();
      const QuadratureRule<2> g = gauss_cell_rule(domain, s.gauss_points * h, s.gauss_points);
      record("-", "-", "gauss_cells", level, g.points, g.weights, seconds_since(t0));
    }
    log << fmt::format("  level {}/{}: {} points across, {:.1f} s elapsed, {} thread(s)\n", li + 1,
                       s.levels.size(), level, seconds_since(total_start), thread_count())
        << std::flush;
  }
  return rows;
}

std::string integration_csv(const std::vector<IntegrationRow>& rows) {
  std::string out =
      "function,cloud,order,scheme,level,points,spacing,error,relative_error,area_error,seconds,"
      "negative_weights,most_negative\n";
  for (const auto& r : rows)
    out += fmt::format("{},{},{},{},{},{},{:.9e},{:.9e},{:.9e},{:.3e},{:.6e},{},{:.6e}\n", r.function,
                       r.cloud, r.order, r.scheme, r.level, r.points, r.spacing, r.error,
                       r.relative_error, r.area_error, r.seconds, r.negative, r.most_negative);
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
  return out;
}

}  // namespace mfree
