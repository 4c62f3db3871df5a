#include "mfree/galerkin/total_lagrangian.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <string>
#include <tuple>

#include "mfree/core/error.hpp"
#include "mfree/core/parallel.hpp"

namespace mfree {

namespace {

/// "(x, y)" or "(x, y, z)" for messages.
template <int dim>
std::string point_text(const Point<dim>& x) {
  return fmt::format("({:.6g})", fmt::join(x.begin(), x.end(), ", "));
}

/// f() at point k of `points` (`kind`: quadrature or boundary); a NumericalError of the
/// material (J <= 0) gets the point.
template <int dim, class F>
auto at_point(const char* kind, const std::vector<Point<dim>>& points, Index k, F&& f) {
  try {
    return f();
  } catch (const NumericalError& e) {
    throw NumericalError(fmt::format("{} at {} point {} {}; use smaller load or time steps", e.what(), kind,
                                     k, point_text<dim>(points[k])));
  }
}

template <int dim>
bool is_essential(const BoundaryCondition<dim>& c) {
  return c.type == BoundaryCondition<dim>::Type::displacement || c.type == BoundaryCondition<dim>::Type::slip;
}

/// The traction of a natural condition on the reference boundary: tbar, or -p N.
template <int dim>
Point<dim> dead_traction(const BoundaryCondition<dim>& c, const Point<dim>& x, const Point<dim>& n,
                         double t) {
  return c.type == BoundaryCondition<dim>::Type::pressure ? Point<dim>(-c.pressure(x, t) * n)
                                                          : c.value(x, n, t);
}

/// The regions of a domain (a plane domain's list is empty for one region, a solid's may
/// name its one region).
std::size_t domain_regions(const Domain& domain) { return domain.regions().size(); }
std::size_t domain_regions(const Solid& solid) { return std::max<std::size_t>(1, solid.regions().size()); }

/// R (a, b) = (b, -a): the rotation by -90 degrees that turns a tangent (body on its left)
/// into the outward normal.
Mat2 rotation_minus_90() {
  Mat2 r;
  r << 0.0, 1.0, -1.0, 0.0;
  return r;
}

/// [w]_x, the matrix of v -> w x v.
Tensor2<3> cross_matrix(const Point<3>& w) {
  Tensor2<3> m;
  m << 0.0, -w.z(), w.y(), w.z(), 0.0, -w.x(), -w.y(), w.x(), 0.0;
  return m;
}

/// sum_M t_M r(M): the contraction of a gradient with dim rows (one expression, so that
/// the plane sum rounds as it always has).
template <int dim, class Row>
auto contract(const Point<dim>& t, Row&& r) {
  if constexpr (dim == 2)
    return (t.x() * r(0) + t.y() * r(1)).eval();
  else
    return (t.x() * r(0) + t.y() * r(1) + t.z() * r(2)).eval();
}

/// Adds blocks sum over rows K of a dim x dim kernel to a block matrix on `pattern`, column
/// by column: node J's dim columns are written only by the thread that owns J, with the rows
/// holding J in increasing order, so no two threads touch one value and the sums are the
/// same on any thread count. column(k, slot_j) prepares what row K contributes to column J;
/// it returns block(slot_i) -> the dim x dim block (I, J). With symmetric = true only the
/// blocks I >= J are summed (rows are sorted: from J's own slot on) and the others copied,
/// K_IJ = K_JI^T: half the work, and the matrix symmetric to the last bit.
template <int dim, class Column>
void add_column_blocks(const GalerkinQuadrature<dim>& q, const RowIncidence& rows, const NodePattern& pattern,
                       bool symmetric, double* values, Column&& column) {
  const Index n = pattern.size();
  parallel_ranges(n, [&](int, Index begin, Index end) {
    std::vector<Index> at(n);  // at[I] = p with P_J[p] = I, for the current J
    for (Index j = begin; j < end; ++j) {
      const std::span<const Index> p = pattern.neighbours(j);
      for (std::size_t a = 0; a < p.size(); ++a) at[p[a]] = static_cast<Index>(a);
      // Column dim J + c holds (dim I, ..., dim I + dim - 1) at dim p, ... for I = P_J[p].
      std::array<double*, dim> col;
      col[0] = values + dim * dim * pattern.offsets[j];
      for (int c = 1; c < dim; ++c) col[c] = col[c - 1] + dim * p.size();
      const std::span<const Index> ks = rows.rows_of(j), slots = rows.slots_of(j);
      for (std::size_t e = 0; e < ks.size(); ++e) {
        const Index k = ks[e];
        const auto block = column(k, slots[e]);
        for (Index s = symmetric ? slots[e] : q.row_begin(k); s < q.row_end(k); ++s) {
          const Tensor2<dim> b = block(s);
          const std::int64_t a = dim * std::int64_t{at[q.nodes[s]]};
          for (int c = 0; c < dim; ++c)
            for (int r = 0; r < dim; ++r) col[c][a + r] += b(r, c);
        }
      }
    }
  });
  if (!symmetric) return;
  // Upper blocks I < J of column J from the lower blocks J > I of column I: reads and writes
  // never meet.
  parallel_blocks(n, 1024, [&](Index begin, Index end) {
    for (Index j = begin; j < end; ++j) {
      const std::span<const Index> p = pattern.neighbours(j);
      const std::int64_t size = static_cast<std::int64_t>(p.size());
      std::array<double*, dim> col;
      col[0] = values + dim * dim * pattern.offsets[j];
      for (int c = 1; c < dim; ++c) col[c] = col[c - 1] + dim * size;
      std::int64_t a = 0;
      for (; a < size && p[a] < j; ++a) {
        // K_IJ(r, c) = K_JI(c, r), entry (dim J + c, dim I + r) in column dim I + r.
        const Index i = p[a];
        const std::int64_t from = block_slot(pattern, dim, j, i, 0, 0);
        const std::int64_t column = dim * (pattern.offsets[i + 1] - pattern.offsets[i]);
        for (int r = 0; r < dim; ++r)
          for (int c = 0; c < dim; ++c) col[c][dim * a + r] = values[from + r * column + c];
      }
      // The diagonal block (p[a] = J, present whenever a row holds J): K_JJ(r, c) = K_JJ(c, r)
      // above its diagonal.
      if (a < size)
        for (int c = 1; c < dim; ++c)
          for (int r = 0; r < c; ++r) col[c][dim * a + r] = col[r][dim * a + c];
    }
  });
}

/// out_I = sum over the rows K holding I of value(k, slot): a gather per node, in parallel
/// and in a fixed order.
template <int dim, class Value>
Eigen::VectorXd gather_nodes(const RowIncidence& rows, Value&& value) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(dim * Eigen::Index{rows.node_count()});
  parallel_blocks(rows.node_count(), 512, [&](Index begin, Index end) {
    for (Index i = begin; i < end; ++i) {
      Point<dim> f = Point<dim>::Zero();
      const std::span<const Index> ks = rows.rows_of(i), slots = rows.slots_of(i);
      for (std::size_t e = 0; e < ks.size(); ++e) f += value(ks[e], slots[e]);
      out.segment<dim>(dim * i) = f;
    }
  });
  return out;
}

/// (A : (e_k g^T)) N for k = 0 .. dim - 1 as the columns of a dim x dim matrix: the traction
/// change of the increment phi e_k with gradient g.
template <int dim>
Tensor2<dim> traction_operator(const Tangent<dim>& a, const Point<dim>& g, const Point<dim>& n) {
  Tensor2<dim> t = Tensor2<dim>::Zero();
  for (int i = 0; i < dim; ++i)
    for (int k = 0; k < dim; ++k)
      for (int m = 0; m < dim; ++m)
        for (int l = 0; l < dim; ++l)
          t(i, k) += a(tensor_index<dim>(i, m), tensor_index<dim>(k, l)) * g[l] * n[m];
  return t;
}

}  // namespace

template <int dim>
TotalLagrangian<dim>::TotalLagrangian(SolidProblem<dim> problem, const DomainOf<dim>& domain, Index nodes,
                                      const GalerkinQuadrature<dim>& q,
                                      const std::vector<Point<dim>>* test_gradients,
                                      const BoundaryQuadrature<dim>& bq,
                                      const GalerkinQuadrature<dim>& at_boundary)
    : problem_(std::move(problem)),
      nodes_(nodes),
      q_(q),
      test_(test_gradients ? *test_gradients : q.grad),
      bq_(bq),
      at_boundary_(at_boundary),
      domain_rows_(q.offsets, q.nodes, nodes),
      boundary_rows_(boundary_offsets_, boundary_nodes_, nodes) {
  if (!(problem_.nitsche_beta > 0.0))
    throw InputError(fmt::format("Nitsche penalty beta must be positive, got {}", problem_.nitsche_beta));
  const std::size_t regions = domain_regions(domain);
  if (!problem_.region_materials.empty() && problem_.region_materials.size() != regions)
    throw Error(fmt::format("{} region materials for a domain of {} regions",
                            problem_.region_materials.size(), regions));
  const std::size_t laws = std::max<std::size_t>(1, problem_.region_materials.size());
  // The law of each point: its region's (points on an interface lie a little into their side).
  const auto law_at = [&](const std::vector<Point<dim>>& points, const char* kind) {
    std::vector<int> law(points.size(), 0);
    if constexpr (dim == 2) {
      if (laws == 1) return law;
      const double tolerance = 1e-9 * domain.bounding_box().size().norm();
      std::vector<double> off(points.size(), 0.0);
      parallel_blocks(static_cast<Index>(points.size()), 1024, [&](Index begin, Index end) {
        for (Index k = begin; k < end; ++k) std::tie(law[k], off[k]) = domain.nearest_region(points[k]);
      });
      for (std::size_t k = 0; k < law.size(); ++k)
        if (law[k] < 0 || off[k] > tolerance)
          throw Error(fmt::format("{} point {} {} lies in no region of the domain", kind, k,
                                  point_text<dim>(points[k])));
    } else {
      // A point on a face between two regions takes either law (on a tied interface the
      // points lie a little into their side).
      if (laws == 1) return law;
      parallel_blocks(static_cast<Index>(points.size()), 1024, [&](Index begin, Index end) {
        for (Index k = begin; k < end; ++k) law[k] = domain.region_at(points[k]);
      });
      for (std::size_t k = 0; k < law.size(); ++k)
        if (law[k] < 0)
          throw Error(fmt::format("{} point {} {} lies in no region of the solid", kind, k,
                                  point_text<dim>(points[k])));
    }
    return law;
  };
  law_of_point_ = law_at(q.points, "quadrature");
  law_of_boundary_ = law_at(bq.samples, "boundary");  // on an interface, the side of the face
  bool small_strain = true, symmetric_tangents = true;
  for (std::size_t l = 0; l < laws; ++l) {
    const Material& m = problem_.law(static_cast<int>(l));
    history_laws_ = history_laws_ || mfree::has_history(m);
    linear_ = linear_ && is_linear(m);
    small_strain = small_strain && is_small_strain(m);
    symmetric_tangents = symmetric_tangents && has_symmetric_tangent(m);
    reference_tangents_.push_back(mfree::tangent(m, Tensor2<dim>(Tensor2<dim>::Identity())));
    penalty_of_law_.push_back(problem_.nitsche_beta * p_wave_modulus(m) / problem_.spacing);
  }
  const bool linear = linear_;
  const bool dead_pressure = small_strain;
  traction_of_point_.assign(bq.size(), nullptr);
  follower_of_point_.assign(bq.size(), nullptr);
  reference_traction_.resize(at_boundary.nodes.size());
  std::vector<bool> seen(problem_.conditions.size(), false);
  // Nitsche's terms and the follower pressures couple the nodes of a boundary point's row
  // (outside the domain pattern when quadrature rows are narrower than the supports, as
  // with Gauss cells).
  const auto couple_row = [&](Index p) {
    boundary_nodes_.insert(boundary_nodes_.end(), at_boundary.nodes.begin() + at_boundary.row_begin(p),
                           at_boundary.nodes.begin() + at_boundary.row_end(p));
    boundary_offsets_.push_back(static_cast<Index>(boundary_nodes_.size()));
  };
  const std::vector<BoundarySelection<dim>> parts = condition_parts(problem_.conditions);
  for (Index p = 0; p < bq.size(); ++p) {
    const int part = boundary_part(domain, parts, bq.segment[p], bq.points[p]);
    if (part < 0) continue;
    seen[static_cast<std::size_t>(part)] = true;
    const BoundaryCondition<dim>* c = &problem_.conditions[static_cast<std::size_t>(part)];
    if (c->type == BoundaryCondition<dim>::Type::pressure && !dead_pressure) {
      follower_.emplace_back(p, c);
      follower_of_point_[p] = c;
      couple_row(p);
      continue;
    }
    if (!is_essential(*c)) {
      traction_of_point_[p] = c;
      continue;
    }
    const Point<dim>& n = bq.normals[p];
    nitsche_.push_back({p,
                        c->type == BoundaryCondition<dim>::Type::slip ? Tensor2<dim>(n * n.transpose())
                                                                      : Tensor2<dim>::Identity(),
                        c, penalty_of_law_[law_of_boundary_[p]]});
    for (Index s = at_boundary.row_begin(p); s < at_boundary.row_end(p); ++s)
      reference_traction_[s] =
          traction_operator(reference_tangents_[law_of_boundary_[p]], at_boundary.grad[s], n);
    couple_row(p);
  }
  // The ties: each interface point once, from its + face (plane: the first of the crack's
  // pair; solid: the `from` face, the first of the twins). Their rows couple the functions of
  // both faces.
  const auto plus_face = [&](Index p, Index q_twin) {
    if constexpr (dim == 2) {
      const BoundarySegment& segment = domain.boundary()[bq.segment[p]];
      return segment.a == domain.cracks()[segment.crack].points[segment.edge];
    } else {
      return p < q_twin;
    }
  };
  for (Index p = 0; p < bq.size(); ++p) {
    const Index q_twin = bq.twin.empty() ? -1 : bq.twin[p];
    if (q_twin < 0 || !plus_face(p, q_twin)) continue;
    ties_.push_back(
        {p, q_twin,
         std::max(penalty_of_law_[law_of_boundary_[p]], penalty_of_law_[law_of_boundary_[q_twin]])});
    for (const Index side : {p, q_twin}) {
      const Point<dim>& n = bq.normals[p];
      for (Index s = at_boundary.row_begin(side); s < at_boundary.row_end(side); ++s)
        reference_traction_[s] =
            traction_operator(reference_tangents_[law_of_boundary_[side]], at_boundary.grad[s], n);
    }
    std::vector<Index> row(at_boundary.nodes.begin() + at_boundary.row_begin(p),
                           at_boundary.nodes.begin() + at_boundary.row_end(p));
    row.insert(row.end(), at_boundary.nodes.begin() + at_boundary.row_begin(q_twin),
               at_boundary.nodes.begin() + at_boundary.row_end(q_twin));
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    boundary_nodes_.insert(boundary_nodes_.end(), row.begin(), row.end());
    boundary_offsets_.push_back(static_cast<Index>(boundary_nodes_.size()));
  }
  for (std::size_t c = 0; c < seen.size(); ++c)
    if (!seen[c])
      throw InputError(fmt::format("boundary condition '{}' holds at no boundary quadrature point (it selects {} of "
                                   "the boundary, or only where an earlier condition holds)",
                                   problem_.conditions[c].name,
                                   problem_.conditions[c].where.empty() ? "none" : "a little"));
  boundary_rows_ = RowIncidence(boundary_offsets_, boundary_nodes_, nodes);
  const RowIncidence* const sets[] = {&domain_rows_, &boundary_rows_};
  pattern_ = node_pattern(sets);
  // The domain blocks are summed for I >= J and copied, K_IJ = K_JI^T, only when that holds:
  // test = trial gradients and a tangent with major symmetry.
  domain_symmetric_ = test_gradients == nullptr && symmetric_tangents;
  // The algorithmic tangents of the plastic laws are not taken as symmetric (Drucker–Prager
  // with dilatancy below friction is not; J2's is only to round-off).
  symmetric_ = domain_symmetric_ && follower_.empty() &&
               (linear || (nitsche_.empty() && ties_.empty() && !history_laws_));
  if (history_laws_) {
    history_.domain.assign(q.size(), MaterialState<dim>{});
    history_.boundary.assign(nitsche_.size() + 2 * ties_.size(), MaterialState<dim>{});
  }
}

template <int dim>
MaterialUpdate<dim> TotalLagrangian<dim>::domain_update(Index k, const Tensor2<dim>& f,
                                                        bool with_tangent) const {
  static const MaterialState<dim> none;
  return at_point("quadrature", q_.points, k, [&] {
    return update(problem_.law(law_of_point_[k]), f, history_laws_ ? history_.domain[k] : none, with_tangent);
  });
}

template <int dim>
MaterialUpdate<dim> TotalLagrangian<dim>::boundary_update(std::size_t b, const Tensor2<dim>& f,
                                                          bool with_tangent) const {
  static const MaterialState<dim> none;
  return at_point("boundary", bq_.points, nitsche_[b].point, [&] {
    return update(problem_.law(law_of_boundary_[nitsche_[b].point]), f,
                  history_laws_ ? history_.boundary[b] : none, with_tangent);
  });
}

template <int dim>
Tensor2<dim> TotalLagrangian<dim>::boundary_deformation_gradient(Index point,
                                                                 const Eigen::VectorXd& d) const {
  Tensor2<dim> f = Tensor2<dim>::Identity();
  for (Index s = at_boundary_.row_begin(point); s < at_boundary_.row_end(point); ++s)
    f += d.segment<dim>(dim * at_boundary_.nodes[s]) * at_boundary_.grad[s].transpose();
  return f;
}

template <int dim>
void TotalLagrangian<dim>::commit_boundary(const Eigen::VectorXd& d) {
  std::vector<MaterialState<dim>> next(history_.boundary.size());
  for (std::size_t b = 0; b < nitsche_.size(); ++b)
    next[b] = boundary_update(b, boundary_deformation_gradient(nitsche_[b].point, d), false).state;
  for (std::size_t t = 0; t < ties_.size(); ++t)
    for (const int face : {0, 1}) next[tie_state(t, face)] = tie_update(t, face, d, false).state;
  history_.boundary = std::move(next);
}

template <int dim>
void TotalLagrangian<dim>::commit(const Eigen::VectorXd& d) {
  if (!history_laws_) return;
  parallel_blocks(q_.size(), 1024, [&](Index begin, Index end) {
    for (Index k = begin; k < end; ++k) history_.domain[k] = domain_update(k, deformation_gradient(k, d), false).state;
  });
  commit_boundary(d);
}

template <int dim>
Eigen::VectorXd TotalLagrangian<dim>::internal_force_committed(const Eigen::VectorXd& d) {
  if (!history_laws_) return internal_force(d);
  Eigen::VectorXd f = domain_force(d, &history_.domain);
  commit_boundary(d);
  return f;
}

template <int dim>
void TotalLagrangian<dim>::set_history(PointHistory<dim> history) {
  const std::size_t domain = history_laws_ ? static_cast<std::size_t>(q_.size()) : 0;
  const std::size_t boundary = history_laws_ ? nitsche_.size() + 2 * ties_.size() : 0;
  if (history.domain.size() != domain || history.boundary.size() != boundary)
    throw InputError(fmt::format("material history of {} quadrature and {} boundary points does not fit this model "
                                 "({} and {})",
                                 history.domain.size(), history.boundary.size(), domain, boundary));
  history_ = std::move(history);
}

template <int dim>
double TotalLagrangian<dim>::dissipated() const {
  double sum = 0.0;
  for (std::size_t k = 0; k < history_.domain.size(); ++k) sum += q_.weights[k] * history_.domain[k].dissipation;
  return sum;
}

template <int dim>
double TotalLagrangian<dim>::plastic_area() const {
  double sum = 0.0;
  for (std::size_t k = 0; k < history_.domain.size(); ++k)
    if (history_.domain[k].alpha > 0.0) sum += q_.weights[k];
  return sum;
}

template <int dim>
typename TotalLagrangian<dim>::PointResponse TotalLagrangian<dim>::response(Index k,
                                                                            const Eigen::VectorXd& d) const {
  const Tensor2<dim> f = deformation_gradient(k, d);
  const MaterialUpdate<dim> u = domain_update(k, f, false);
  return {cauchy_stress(problem_.law(law_of_point_[k]), u.stress, f), u.stress_zz, u.state};
}

template <int dim>
Tensor2<dim> TotalLagrangian<dim>::deformation_gradient(Index k, const Eigen::VectorXd& d) const {
  Tensor2<dim> f = Tensor2<dim>::Identity();
  for (Index s = q_.row_begin(k); s < q_.row_end(k); ++s)
    f += d.segment<dim>(dim * q_.nodes[s]) * q_.grad[s].transpose();
  return f;
}

template <int dim>
Eigen::VectorXd TotalLagrangian<dim>::internal_force(const Eigen::VectorXd& d) const {
  return domain_force(d, nullptr);
}

template <int dim>
Eigen::VectorXd TotalLagrangian<dim>::domain_force(const Eigen::VectorXd& d,
                                                   std::vector<MaterialState<dim>>* commit) const {
  std::vector<Tensor2<dim>> wp(q_.size());
  parallel_blocks(q_.size(), 1024, [&](Index begin, Index end) {
    for (Index k = begin; k < end; ++k) {
      const MaterialUpdate<dim> u = domain_update(k, deformation_gradient(k, d), false);  // reads state k
      wp[k] = q_.weights[k] * u.stress;
      if (commit) (*commit)[k] = u.state;  // then replaces it
    }
  });
  return gather_nodes<dim>(domain_rows_, [&](Index k, Index s) -> Point<dim> { return wp[k] * test_[s]; });
}

template <int dim>
Eigen::VectorXd TotalLagrangian<dim>::boundary_force(const Eigen::VectorXd& d, const LoadState& load) const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(dofs());
  for (std::size_t b = 0; b < nitsche_.size(); ++b) {
    const NitscheValues v = nitsche_values(b, d, load);
    const Index begin = at_boundary_.row_begin(v.point), end = at_boundary_.row_end(v.point);
    const double w = bq_.weights[v.point];
    for (Index s = begin; s < end; ++s) {
      const double phi = at_boundary_.phi[s];
      f.segment<dim>(dim * at_boundary_.nodes[s]) +=
          w * (-phi * v.traction - reference_traction_[s].transpose() * v.gap + v.penalty * phi * v.gap);
    }
  }
  add_tie_force(d, f);
  // Follower pressures: -f_I = p int phi_I cof(F) N dA.
  for (const auto& [p, c] : follower_) {
    const Index begin = at_boundary_.row_begin(p), end = at_boundary_.row_end(p);
    const Point<dim> load_at =
        bq_.weights[p] * load.factor * c->pressure(bq_.points[p], load.time) * follower_normal(p, d);
    for (Index s = begin; s < end; ++s)
      f.segment<dim>(dim * at_boundary_.nodes[s]) += at_boundary_.phi[s] * load_at;
  }
  return f;
}

template <int dim>
typename TotalLagrangian<dim>::NitscheValues TotalLagrangian<dim>::nitsche_values(
    std::size_t b, const Eigen::VectorXd& d, const LoadState& load) const {
  const NitschePoint& p = nitsche_[b];
  Point<dim> u = Point<dim>::Zero();
  for (Index s = at_boundary_.row_begin(p.point); s < at_boundary_.row_end(p.point); ++s)
    u += at_boundary_.phi[s] * d.segment<dim>(dim * at_boundary_.nodes[s]);
  const Point<dim>& n = bq_.normals[p.point];
  const Point<dim> gap =
      p.projection * (u - load.factor * p.condition->value(bq_.points[p.point], n, load.time));
  const Point<dim> traction =
      p.projection * (boundary_update(b, boundary_deformation_gradient(p.point, d), false).stress * n);
  return {p.point, p.condition, traction, gap, p.penalty};
}

template <int dim>
MaterialUpdate<dim> TotalLagrangian<dim>::tie_update(std::size_t tie, int face, const Eigen::VectorXd& d,
                                                     bool with_tangent) const {
  static const MaterialState<dim> none;
  const Index p = face == 0 ? ties_[tie].plus : ties_[tie].minus;
  return at_point("interface", bq_.points, p, [&] {
    return update(problem_.law(law_of_boundary_[p]), boundary_deformation_gradient(p, d),
                  history_laws_ ? history_.boundary[tie_state(tie, face)] : none, with_tangent);
  });
}

template <int dim>
void TotalLagrangian<dim>::add_tie_force(const Eigen::VectorXd& d, Eigen::VectorXd& f) const {
  // f_I = w [ -s_I phi_I {P} N - T0_I^T [[u]] / 2 + penalty s_I phi_I [[u]] ], s = +1 on the
  // + face, -1 on the other.
  for (std::size_t i = 0; i < ties_.size(); ++i) {
    const TiePoint& t = ties_[i];
    const Point<dim>& n = bq_.normals[t.plus];
    const Point<dim> mean = 0.5 * (tie_update(i, 0, d, false).stress + tie_update(i, 1, d, false).stress) * n;
    Point<dim> jump = Point<dim>::Zero();
    for (const TieSide side : {TieSide{t.plus, 1.0}, TieSide{t.minus, -1.0}})
      for (Index s = at_boundary_.row_begin(side.point); s < at_boundary_.row_end(side.point); ++s)
        jump += side.sign * at_boundary_.phi[s] * d.segment<dim>(dim * at_boundary_.nodes[s]);
    const double w = bq_.weights[t.plus];
    for (const TieSide side : {TieSide{t.plus, 1.0}, TieSide{t.minus, -1.0}})
      for (Index s = at_boundary_.row_begin(side.point); s < at_boundary_.row_end(side.point); ++s) {
        const double phi = side.sign * at_boundary_.phi[s];
        f.segment<dim>(dim * at_boundary_.nodes[s]) +=
            w * (-phi * mean - 0.5 * reference_traction_[s].transpose() * jump + t.penalty * phi * jump);
      }
  }
}

template <int dim>
void TotalLagrangian<dim>::add_tie_tangent(const Eigen::VectorXd& d, double* values) const {
  // K_IJ = w [ -s_I phi_I T_J / 2 - s_J phi_J T0_I^T / 2 + penalty s_I s_J phi_I phi_J ],
  // T_J = (A(F) : grad(phi_J e_k)) N of J's side.
  std::vector<Tensor2<dim>> traction;
  std::vector<Index> slots;
  std::vector<double> signs;
  for (std::size_t i = 0; i < ties_.size(); ++i) {
    const TiePoint& t = ties_[i];
    const Point<dim>& n = bq_.normals[t.plus];
    const double w = bq_.weights[t.plus];
    traction.clear();
    slots.clear();
    signs.clear();
    for (const TieSide side : {TieSide{t.plus, 1.0}, TieSide{t.minus, -1.0}}) {
      const Tangent<dim> a = linear_ ? reference_tangents_[law_of_boundary_[side.point]]
                                     : tie_update(i, side.sign > 0.0 ? 0 : 1, d, true).tangent;
      for (Index s = at_boundary_.row_begin(side.point); s < at_boundary_.row_end(side.point); ++s) {
        traction.push_back(linear_ ? reference_traction_[s] : traction_operator(a, at_boundary_.grad[s], n));
        slots.push_back(s);
        signs.push_back(side.sign);
      }
    }
    for (std::size_t a = 0; a < slots.size(); ++a) {
      const Index i = at_boundary_.nodes[slots[a]];
      const double phi_i = signs[a] * at_boundary_.phi[slots[a]];
      for (std::size_t b = 0; b < slots.size(); ++b) {
        const Index j = at_boundary_.nodes[slots[b]];
        const double phi_j = signs[b] * at_boundary_.phi[slots[b]];
        const Tensor2<dim> kij =
            w * (-0.5 * phi_i * traction[b] - 0.5 * phi_j * reference_traction_[slots[a]].transpose() +
                 t.penalty * phi_i * phi_j * Tensor2<dim>::Identity());
        for (int r = 0; r < dim; ++r)
          for (int c = 0; c < dim; ++c) values[block_slot(pattern_, dim, i, j, r, c)] += kij(r, c);
      }
    }
  }
}

template <int dim>
Point<dim> TotalLagrangian<dim>::follower_normal(Index p, const Eigen::VectorXd& d) const {
  if constexpr (dim == 2) {
    // R x,S with x,S = T + sum_J d_J (grad phi_J . T).
    const Vec2& t = bq_.tangents[p];
    Vec2 dx = t;
    for (Index s = at_boundary_.row_begin(p); s < at_boundary_.row_end(p); ++s)
      dx += d.segment<2>(2 * at_boundary_.nodes[s]) * at_boundary_.grad[s].dot(t);
    return rotation_minus_90() * dx;
  } else {
    // cof(F) has the columns F_1 x F_2, F_2 x F_0, F_0 x F_1 (F^T cof(F) = J I).
    const Tensor2<3> f = boundary_deformation_gradient(p, d);
    Tensor2<3> cof;
    for (int m = 0; m < 3; ++m) cof.col(m) = f.col((m + 1) % 3).cross(f.col((m + 2) % 3));
    return cof * bq_.normals[p];
  }
}

template <int dim>
Point<dim> TotalLagrangian<dim>::boundary_load(Index p, const Eigen::VectorXd& d,
                                               const LoadState& load) const {
  if (const BoundaryCondition<dim>* c = traction_of_point_[p])
    return load.factor * dead_traction(*c, bq_.points[p], bq_.normals[p], load.time);
  if (const BoundaryCondition<dim>* c = follower_of_point_[p])
    return -load.factor * c->pressure(bq_.points[p], load.time) * follower_normal(p, d);
  return Point<dim>::Zero();
}

template <int dim>
Eigen::VectorXd TotalLagrangian<dim>::external_force(const LoadState& load) const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(dofs());
  if (problem_.body_force) {
    std::vector<Point<dim>> wb(q_.size());
    parallel_blocks(q_.size(), 1024, [&](Index begin, Index end) {
      for (Index k = begin; k < end; ++k) wb[k] = q_.weights[k] * load.factor * problem_.body_force(q_.points[k], load.time);
    });
    f = gather_nodes<dim>(domain_rows_, [&](Index k, Index s) -> Point<dim> { return q_.phi[s] * wb[k]; });
  }
  for (Index p = 0; p < bq_.size(); ++p) {
    const BoundaryCondition<dim>* c = traction_of_point_[p];
    if (!c) continue;
    const Point<dim> t =
        bq_.weights[p] * load.factor * dead_traction(*c, bq_.points[p], bq_.normals[p], load.time);
    for (Index s = at_boundary_.row_begin(p); s < at_boundary_.row_end(p); ++s)
      f.segment<dim>(dim * at_boundary_.nodes[s]) += at_boundary_.phi[s] * t;
  }
  return f;
}

template <int dim>
void TotalLagrangian<dim>::tangent(const Eigen::VectorXd& d, const LoadState& load, SparseMatrix& k) const {
  std::fill(k.valuePtr(), k.valuePtr() + k.nonZeros(), 0.0);
  double* values = k.valuePtr();

  // Domain: w_K A(F_K), then K_IJ(i, k) = t_I,M [w A_iMkL g_J,L].
  std::vector<Tangent<dim>> wa(q_.size());
  const bool linear = linear_;
  parallel_blocks(q_.size(), 1024, [&](Index begin, Index end) {
    for (Index p = begin; p < end; ++p)
      wa[p] = q_.weights[p] * (linear ? reference_tangents_[law_of_point_[p]]
                                      : domain_update(p, deformation_gradient(p, d), true).tangent);
  });
  add_column_blocks<dim>(q_, domain_rows_, pattern_, domain_symmetric_, values, [&](Index kk, Index slot_j) {
    const Point<dim>& g = q_.grad[slot_j];
    Eigen::Matrix<double, dim * dim, dim> ag;  // ag(dim i + M, k) = w A_iMkL g_L
    for (int c = 0; c < dim; ++c)
      ag.col(c) = contract<dim>(g, [&](int l) { return wa[kk].col(tensor_index<dim>(c, l)); });
    return [this, ag](Index s) {
      const Point<dim>& t = test_[s];
      Tensor2<dim> b;
      for (int i = 0; i < dim; ++i)
        b.row(i) = contract<dim>(t, [&](int m) { return ag.row(tensor_index<dim>(i, m)); });
      return b;
    };
  });

  // Nitsche: K_IJ = w [ -phi_I Pi T_J(F) - T0_I^T Pi phi_J + penalty phi_I phi_J Pi ].
  std::vector<Tensor2<dim>> t;  // Pi T_J(F) for the functions of the row
  for (std::size_t b = 0; b < nitsche_.size(); ++b) {
    const NitschePoint& p = nitsche_[b];
    const Index begin = at_boundary_.row_begin(p.point), end = at_boundary_.row_end(p.point), m = end - begin;
    const Tangent<dim> a = linear
                               ? reference_tangents_[law_of_boundary_[p.point]]
                               : boundary_update(b, boundary_deformation_gradient(p.point, d), true).tangent;
    const Point<dim>& n = bq_.normals[p.point];
    const double w = bq_.weights[p.point];
    t.resize(m);
    for (Index c = 0; c < m; ++c) t[c] = p.projection * traction_operator(a, at_boundary_.grad[begin + c], n);
    for (Index ai = 0; ai < m; ++ai) {
      const Index i = at_boundary_.nodes[begin + ai];
      const double phi_i = at_boundary_.phi[begin + ai];
      const Tensor2<dim> t0p = reference_traction_[begin + ai].transpose() * p.projection;
      for (Index bj = 0; bj < m; ++bj) {
        const Index j = at_boundary_.nodes[begin + bj];
        const double phi_j = at_boundary_.phi[begin + bj];
        const Tensor2<dim> kij =
            w * (-phi_i * t[bj] - phi_j * t0p + p.penalty * phi_i * phi_j * p.projection);
        for (int r = 0; r < dim; ++r)
          for (int c = 0; c < dim; ++c) values[block_slot(pattern_, dim, i, j, r, c)] += kij(r, c);
      }
    }
  }

  add_tie_tangent(d, values);

  // Follower pressures: K_IJ = w p phi_I (grad phi_J . T) R in the plane,
  // w p phi_I [F (grad phi_J x N)]_x in space.
  for (const auto& [p, c] : follower_) {
    const Index begin = at_boundary_.row_begin(p), end = at_boundary_.row_end(p);
    const double wp = bq_.weights[p] * load.factor * c->pressure(bq_.points[p], load.time);
    if constexpr (dim == 2) {
      const Vec2& tangent = bq_.tangents[p];
      for (Index ai = begin; ai < end; ++ai)
        for (Index bj = begin; bj < end; ++bj) {
          const double c = wp * at_boundary_.phi[ai] * at_boundary_.grad[bj].dot(tangent);
          const Index i = at_boundary_.nodes[ai], j = at_boundary_.nodes[bj];
          values[block_slot(pattern_, 2, i, j, 0, 1)] += c;
          values[block_slot(pattern_, 2, i, j, 1, 0)] -= c;
        }
    } else {
      const Tensor2<3> f = boundary_deformation_gradient(p, d);
      const Point<3>& n = bq_.normals[p];
      for (Index bj = begin; bj < end; ++bj) {
        const Tensor2<3> dn = cross_matrix(f * at_boundary_.grad[bj].cross(n));
        const Index j = at_boundary_.nodes[bj];
        for (Index ai = begin; ai < end; ++ai) {
          const Tensor2<3> kij = wp * at_boundary_.phi[ai] * dn;
          const Index i = at_boundary_.nodes[ai];
          for (int r = 0; r < 3; ++r)
            for (int cc = 0; cc < 3; ++cc) values[block_slot(pattern_, 3, i, j, r, cc)] += kij(r, cc);
        }
      }
    }
  }
}

template <int dim>
double TotalLagrangian<dim>::strain_energy(const Eigen::VectorXd& d) const {
  std::vector<double> partial(thread_count(), 0.0);
  parallel_ranges(q_.size(), [&](int thread, Index begin, Index end) {
    double sum = 0.0;
    for (Index k = begin; k < end; ++k)
      sum += q_.weights[k] * at_point("quadrature", q_.points, k, [&] {
               return energy(problem_.law(law_of_point_[k]), deformation_gradient(k, d),
                             history_laws_ ? history_.domain[k] : MaterialState<dim>{});
             });
    partial[thread] = sum;
  });
  double total = 0.0;
  for (double s : partial) total += s;
  return total;
}

template <int dim>
std::vector<double> TotalLagrangian<dim>::point_densities() const {
  const std::size_t laws = std::max<std::size_t>(1, problem_.region_materials.size());
  for (std::size_t l = 0; l < laws; ++l)
    if (const double rho = problem_.density_of(static_cast<int>(l)); !(rho > 0.0))
      throw InputError(
          laws == 1
              ? fmt::format("the mass needs a positive density, got {}", rho)
              : fmt::format("the mass needs a positive density in every region; region {} has {}", l, rho));
  std::vector<double> rho(law_of_point_.size());
  for (std::size_t k = 0; k < rho.size(); ++k) rho[k] = problem_.density_of(law_of_point_[k]);
  return rho;
}

template <int dim>
SparseMatrix TotalLagrangian<dim>::mass_matrix() const {
  // The mass couples only nodes sharing a domain row: blocks rho0 w phi_I phi_J I_2.
  const std::vector<double> rho = point_densities();
  SparseMatrix m = zero_matrix();
  add_column_blocks<dim>(q_, domain_rows_, pattern_, true, m.valuePtr(), [&](Index k, Index slot_j) {
    const double c = rho[k] * q_.weights[k] * q_.phi[slot_j];
    return [this, c](Index s) -> Tensor2<dim> { return c * q_.phi[s] * Tensor2<dim>::Identity(); };
  });
  return m;
}

template <int dim>
Eigen::VectorXd TotalLagrangian<dim>::lumped_mass(const std::vector<Point<dim>>& node_positions) const {
  const std::vector<double> rho = point_densities();
  const Eigen::VectorXd m = gather_nodes<dim>(domain_rows_, [&](Index k, Index s) -> Point<dim> {
    return Point<dim>::Constant(rho[k] * q_.weights[k] * q_.phi[s]);
  });
  for (Index i = 0; i < nodes_; ++i)
    if (!(m[dim * i] > 0.0))
      throw NumericalError(fmt::format(
          "lumped mass of node {} at {} is {:.3e}, not positive: the row-sum mass needs "
          "shape functions with a positive integral{} (use linear RK, or the implicit scheme with the "
          "consistent mass{})",
          i, point_text<dim>(node_positions[i]), m[dim * i],
          problem_.region_densities.empty() ? ""
                                            : " weighted by the regions' densities (a function whose "
                                              "negative part lies in a denser region than its positive part)",
          problem_.region_densities.empty() ? "" : ", or a finer spacing"));
  return m;
}

template class TotalLagrangian<2>;
template class TotalLagrangian<3>;

}  // namespace mfree
