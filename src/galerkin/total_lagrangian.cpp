#include "mfree/galerkin/total_lagrangian.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <tuple>

#include "mfree/core/error.hpp"
#include "mfree/core/parallel.hpp"

namespace mfree {

namespace {

/// f() at point k of `points` (`kind`: quadrature or boundary); a NumericalError of the
/// material (J <= 0) gets the point.
template <class F>
auto at_point(const char* kind, const std::vector<Vec2>& points, Index k, F&& f) {
  try {
    return f();
  } catch (const NumericalError& e) {
    throw NumericalError(fmt::format("{} at {} point {} ({:.6g}, {:.6g}); use smaller load or time steps", e.what(),
                                     kind, k, points[k].x(), points[k].y()));
  }
}

bool is_essential(const BoundaryCondition& c) {
  return c.type == BoundaryCondition::Type::displacement || c.type == BoundaryCondition::Type::slip;
}

/// The traction of a natural condition on the reference boundary: tbar, or -p N.
Vec2 dead_traction(const BoundaryCondition& c, const Vec2& x, const Vec2& n, double t) {
  return c.type == BoundaryCondition::Type::pressure ? Vec2(-c.pressure(x, t) * n) : c.value(x, n, t);
}

/// R (a, b) = (b, -a): the rotation by -90 degrees that turns a tangent (body on its left)
/// into the outward normal.
Mat2 rotation_minus_90() {
  Mat2 r;
  r << 0.0, 1.0, -1.0, 0.0;
  return r;
}

/// Adds blocks sum over rows K of a 2 x 2 kernel to a block matrix on `pattern`, column by
/// column: node J's two columns are written only by the thread that owns J, with the rows
/// holding J in increasing order, so no two threads touch one value and the sums are the
/// same on any thread count. column(k, slot_j) prepares what row K contributes to column J;
/// it returns block(slot_i) -> the 2 x 2 block (I, J). With symmetric = true only the blocks
/// I >= J are summed (rows are sorted: from J's own slot on) and the others copied,
/// K_IJ = K_JI^T: half the work, and the matrix symmetric to the last bit.
template <class Column>
void add_column_blocks(const GalerkinQuadrature<2>& q, const RowIncidence& rows, const NodePattern& pattern,
                       bool symmetric, double* values, Column&& column) {
  const Index n = pattern.size();
  parallel_ranges(n, [&](int, Index begin, Index end) {
    std::vector<Index> at(n);  // at[I] = p with P_J[p] = I, for the current J
    for (Index j = begin; j < end; ++j) {
      const std::span<const Index> p = pattern.neighbours(j);
      for (std::size_t a = 0; a < p.size(); ++a) at[p[a]] = static_cast<Index>(a);
      // Column 2J holds (2I, 2I + 1) at 2p, 2p + 1 for I = P_J[p]; column 2J + 1 follows it.
      double* col0 = values + 4 * pattern.offsets[j];
      double* col1 = col0 + 2 * p.size();
      const std::span<const Index> ks = rows.rows_of(j), slots = rows.slots_of(j);
      for (std::size_t e = 0; e < ks.size(); ++e) {
        const Index k = ks[e];
        const auto block = column(k, slots[e]);
        for (Index s = symmetric ? slots[e] : q.row_begin(k); s < q.row_end(k); ++s) {
          const Eigen::Matrix2d b = block(s);
          const std::int64_t a = 2 * std::int64_t{at[q.nodes[s]]};
          col0[a] += b(0, 0);
          col0[a + 1] += b(1, 0);
          col1[a] += b(0, 1);
          col1[a + 1] += b(1, 1);
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
      double* col0 = values + 4 * pattern.offsets[j];
      double* col1 = col0 + 2 * size;
      std::int64_t a = 0;
      for (; a < size && p[a] < j; ++a) {
        // K_IJ(r, c) = K_JI(c, r), entry (2J + c, 2I + r) in column 2I + r.
        const Index i = p[a];
        const std::int64_t from = block_slot(pattern, 2, j, i, 0, 0);
        const std::int64_t column = 2 * (pattern.offsets[i + 1] - pattern.offsets[i]);
        for (int r = 0; r < 2; ++r) {
          col0[2 * a + r] = values[from + r * column];
          col1[2 * a + r] = values[from + r * column + 1];
        }
      }
      // The diagonal block (p[a] = J, present whenever a row holds J): K_JJ(0, 1) = K_JJ(1, 0).
      if (a < size) col1[2 * a] = col0[2 * a + 1];
    }
  });
}

/// out_I = sum over the rows K holding I of value(k, slot): a gather per node, in parallel
/// and in a fixed order.
template <class Value>
Eigen::VectorXd gather_nodes(const RowIncidence& rows, Value&& value) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(2 * Eigen::Index{rows.node_count()});
  parallel_blocks(rows.node_count(), 512, [&](Index begin, Index end) {
    for (Index i = begin; i < end; ++i) {
      Vec2 f = Vec2::Zero();
      const std::span<const Index> ks = rows.rows_of(i), slots = rows.slots_of(i);
      for (std::size_t e = 0; e < ks.size(); ++e) f += value(ks[e], slots[e]);
      out.segment<2>(2 * i) = f;
    }
  });
  return out;
}

/// (A : (e_k g^T)) N for k = 0, 1 as the columns of a 2 x 2 matrix: the traction change of
/// the increment phi e_k with gradient g.
Mat2 traction_operator(const Tangent<2>& a, const Vec2& g, const Vec2& n) {
  Mat2 t = Mat2::Zero();
  for (int i = 0; i < 2; ++i)
    for (int k = 0; k < 2; ++k)
      for (int m = 0; m < 2; ++m)
        for (int l = 0; l < 2; ++l) t(i, k) += a(tensor_index<2>(i, m), tensor_index<2>(k, l)) * g[l] * n[m];
  return t;
}

}  // namespace

std::vector<BoundarySelection> condition_parts(const std::vector<BoundaryCondition>& conditions) {
  std::vector<BoundarySelection> parts;
  for (const BoundaryCondition& c : conditions) parts.push_back(c.where);
  return parts;
}

TotalLagrangian::TotalLagrangian(SolidProblem problem, const Domain& domain, Index nodes,
                                 const GalerkinQuadrature<2>& q, const std::vector<Vec2>* test_gradients,
                                 const BoundaryQuadrature& bq, const GalerkinQuadrature<2>& at_boundary)
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
  const std::size_t regions = domain.regions().size();
  if (!problem_.region_materials.empty() && problem_.region_materials.size() != regions)
    throw Error(fmt::format("{} region materials for a domain of {} regions",
                            problem_.region_materials.size(), regions));
  const std::size_t laws = std::max<std::size_t>(1, problem_.region_materials.size());
  // The law of each point: its region's (points on an interface lie a little into their side).
  const auto law_at = [&](const std::vector<Vec2>& points, const char* kind) {
    std::vector<int> law(points.size(), 0);
    if (laws == 1) return law;
    const double tolerance = 1e-9 * domain.bounding_box().size().norm();
    std::vector<double> off(points.size(), 0.0);
    parallel_blocks(static_cast<Index>(points.size()), 1024, [&](Index begin, Index end) {
      for (Index k = begin; k < end; ++k) std::tie(law[k], off[k]) = domain.nearest_region(points[k]);
    });
    for (std::size_t k = 0; k < law.size(); ++k)
      if (law[k] < 0 || off[k] > tolerance)
        throw Error(fmt::format("{} point {} ({:.6g}, {:.6g}) lies in no region of the domain", kind, k,
                                points[k].x(), points[k].y()));
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
    reference_tangents_.push_back(mfree::tangent(m, Mat2(Mat2::Identity())));
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
  const auto& segments = domain.boundary();
  for (Index p = 0; p < bq.size(); ++p) {
    const BoundarySegment& seg = segments[bq.segment[p]];
    const double t = (bq.points[p] - seg.a).dot(seg.b - seg.a) / (seg.length * seg.length);
    const BoundaryCondition* c = nullptr;
    for (std::size_t k = 0; k < problem_.conditions.size() && !c; ++k)
      for (const BoundaryPiece& piece : problem_.conditions[k].where)
        if (piece.segment == bq.segment[p] && t >= piece.t0 && t <= piece.t1) {
          c = &problem_.conditions[k];
          seen[k] = true;
          break;
        }
    if (!c) continue;
    if (c->type == BoundaryCondition::Type::pressure && !dead_pressure) {
      follower_.emplace_back(p, c);
      follower_of_point_[p] = c;
      couple_row(p);
      continue;
    }
    if (!is_essential(*c)) {
      traction_of_point_[p] = c;
      continue;
    }
    const Vec2& n = bq.normals[p];
    nitsche_.push_back({p,
                        c->type == BoundaryCondition::Type::slip ? Mat2(n * n.transpose()) : Mat2::Identity(),
                        c, penalty_of_law_[law_of_boundary_[p]]});
    for (Index s = at_boundary.row_begin(p); s < at_boundary.row_end(p); ++s)
      reference_traction_[s] =
          traction_operator(reference_tangents_[law_of_boundary_[p]], at_boundary.grad[s], n);
    couple_row(p);
  }
  // The ties: each interface point once, from its + face (the first of the pair). Their rows
  // couple the functions of both faces.
  for (Index p = 0; p < bq.size(); ++p) {
    const Index q_twin = bq.twin.empty() ? -1 : bq.twin[p];
    if (q_twin < 0) continue;
    const Crack& crack = domain.cracks()[segments[bq.segment[p]].crack];
    if (segments[bq.segment[p]].a != crack.points[segments[bq.segment[p]].edge]) continue;  // the - face
    ties_.push_back(
        {p, q_twin,
         std::max(penalty_of_law_[law_of_boundary_[p]], penalty_of_law_[law_of_boundary_[q_twin]])});
    for (const Index side : {p, q_twin}) {
      const Vec2& n = bq.normals[p];
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
    history_.domain.assign(q.size(), MaterialState<2>{});
    history_.boundary.assign(nitsche_.size() + 2 * ties_.size(), MaterialState<2>{});
  }
}

MaterialUpdate<2> TotalLagrangian::domain_update(Index k, const Mat2& f, bool with_tangent) const {
  static const MaterialState<2> none;
  return at_point("quadrature", q_.points, k, [&] {
    return update(problem_.law(law_of_point_[k]), f, history_laws_ ? history_.domain[k] : none, with_tangent);
  });
}

MaterialUpdate<2> TotalLagrangian::boundary_update(std::size_t b, const Mat2& f, bool with_tangent) const {
  static const MaterialState<2> none;
  return at_point("boundary", bq_.points, nitsche_[b].point, [&] {
    return update(problem_.law(law_of_boundary_[nitsche_[b].point]), f,
                  history_laws_ ? history_.boundary[b] : none, with_tangent);
  });
}

Mat2 TotalLagrangian::boundary_deformation_gradient(Index point, const Eigen::VectorXd& d) const {
  Mat2 f = Mat2::Identity();
  for (Index s = at_boundary_.row_begin(point); s < at_boundary_.row_end(point); ++s)
    f += d.segment<2>(2 * at_boundary_.nodes[s]) * at_boundary_.grad[s].transpose();
  return f;
}

void TotalLagrangian::commit_boundary(const Eigen::VectorXd& d) {
  std::vector<MaterialState<2>> next(history_.boundary.size());
  for (std::size_t b = 0; b < nitsche_.size(); ++b)
    next[b] = boundary_update(b, boundary_deformation_gradient(nitsche_[b].point, d), false).state;
  for (std::size_t t = 0; t < ties_.size(); ++t)
    for (const int face : {0, 1}) next[tie_state(t, face)] = tie_update(t, face, d, false).state;
  history_.boundary = std::move(next);
}

void TotalLagrangian::commit(const Eigen::VectorXd& d) {
  if (!history_laws_) return;
  parallel_blocks(q_.size(), 1024, [&](Index begin, Index end) {
    for (Index k = begin; k < end; ++k) history_.domain[k] = domain_update(k, deformation_gradient(k, d), false).state;
  });
  commit_boundary(d);
}

Eigen::VectorXd TotalLagrangian::internal_force_committed(const Eigen::VectorXd& d) {
  if (!history_laws_) return internal_force(d);
  Eigen::VectorXd f = domain_force(d, &history_.domain);
  commit_boundary(d);
  return f;
}

void TotalLagrangian::set_history(PointHistory history) {
  const std::size_t domain = history_laws_ ? static_cast<std::size_t>(q_.size()) : 0;
  const std::size_t boundary = history_laws_ ? nitsche_.size() + 2 * ties_.size() : 0;
  if (history.domain.size() != domain || history.boundary.size() != boundary)
    throw InputError(fmt::format("material history of {} quadrature and {} boundary points does not fit this model "
                                 "({} and {})",
                                 history.domain.size(), history.boundary.size(), domain, boundary));
  history_ = std::move(history);
}

double TotalLagrangian::dissipated() const {
  double sum = 0.0;
  for (std::size_t k = 0; k < history_.domain.size(); ++k) sum += q_.weights[k] * history_.domain[k].dissipation;
  return sum;
}

double TotalLagrangian::plastic_area() const {
  double sum = 0.0;
  for (std::size_t k = 0; k < history_.domain.size(); ++k)
    if (history_.domain[k].alpha > 0.0) sum += q_.weights[k];
  return sum;
}

TotalLagrangian::PointResponse TotalLagrangian::response(Index k, const Eigen::VectorXd& d) const {
  const Mat2 f = deformation_gradient(k, d);
  const MaterialUpdate<2> u = domain_update(k, f, false);
  return {cauchy_stress(problem_.law(law_of_point_[k]), u.stress, f), u.stress_zz, u.state};
}

Mat2 TotalLagrangian::deformation_gradient(Index k, const Eigen::VectorXd& d) const {
  Mat2 f = Mat2::Identity();
  for (Index s = q_.row_begin(k); s < q_.row_end(k); ++s) f += d.segment<2>(2 * q_.nodes[s]) * q_.grad[s].transpose();
  return f;
}

Eigen::VectorXd TotalLagrangian::internal_force(const Eigen::VectorXd& d) const { return domain_force(d, nullptr); }

Eigen::VectorXd TotalLagrangian::domain_force(const Eigen::VectorXd& d,
                                              std::vector<MaterialState<2>>* commit) const {
  std::vector<Mat2> wp(q_.size());
  parallel_blocks(q_.size(), 1024, [&](Index begin, Index end) {
    for (Index k = begin; k < end; ++k) {
      const MaterialUpdate<2> u = domain_update(k, deformation_gradient(k, d), false);  // reads state k
      wp[k] = q_.weights[k] * u.stress;
      if (commit) (*commit)[k] = u.state;  // then replaces it
    }
  });
  return gather_nodes(domain_rows_, [&](Index k, Index s) -> Vec2 { return wp[k] * test_[s]; });
}

Eigen::VectorXd TotalLagrangian::boundary_force(const Eigen::VectorXd& d, const LoadState& load) const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(dofs());
  for (std::size_t b = 0; b < nitsche_.size(); ++b) {
    const NitscheValues v = nitsche_values(b, d, load);
    const Index begin = at_boundary_.row_begin(v.point), end = at_boundary_.row_end(v.point);
    const double w = bq_.weights[v.point];
    for (Index s = begin; s < end; ++s) {
      const double phi = at_boundary_.phi[s];
      f.segment<2>(2 * at_boundary_.nodes[s]) +=
          w * (-phi * v.traction - reference_traction_[s].transpose() * v.gap + v.penalty * phi * v.gap);
    }
  }
  add_tie_force(d, f);
  // Follower pressures: -f_I = p int phi_I R x,S dS, x,S = T + sum_J d_J (grad phi_J . T).
  const Mat2 r = rotation_minus_90();
  for (const auto& [p, c] : follower_) {
    const Index begin = at_boundary_.row_begin(p), end = at_boundary_.row_end(p);
    const Vec2 dx = follower_stretch(p, d);
    const Vec2 load_at = bq_.weights[p] * load.factor * c->pressure(bq_.points[p], load.time) * (r * dx);
    for (Index s = begin; s < end; ++s) f.segment<2>(2 * at_boundary_.nodes[s]) += at_boundary_.phi[s] * load_at;
  }
  return f;
}

TotalLagrangian::NitscheValues TotalLagrangian::nitsche_values(std::size_t b, const Eigen::VectorXd& d,
                                                               const LoadState& load) const {
  const NitschePoint& p = nitsche_[b];
  Vec2 u = Vec2::Zero();
  for (Index s = at_boundary_.row_begin(p.point); s < at_boundary_.row_end(p.point); ++s)
    u += at_boundary_.phi[s] * d.segment<2>(2 * at_boundary_.nodes[s]);
  const Vec2& n = bq_.normals[p.point];
  const Vec2 gap = p.projection * (u - load.factor * p.condition->value(bq_.points[p.point], n, load.time));
  const Vec2 traction =
      p.projection * (boundary_update(b, boundary_deformation_gradient(p.point, d), false).stress * n);
  return {p.point, p.condition, traction, gap, p.penalty};
}

MaterialUpdate<2> TotalLagrangian::tie_update(std::size_t tie, int face, const Eigen::VectorXd& d,
                                              bool with_tangent) const {
  static const MaterialState<2> none;
  const Index p = face == 0 ? ties_[tie].plus : ties_[tie].minus;
  return at_point("interface", bq_.points, p, [&] {
    return update(problem_.law(law_of_boundary_[p]), boundary_deformation_gradient(p, d),
                  history_laws_ ? history_.boundary[tie_state(tie, face)] : none, with_tangent);
  });
}

void TotalLagrangian::add_tie_force(const Eigen::VectorXd& d, Eigen::VectorXd& f) const {
  // f_I = w [ -s_I phi_I {P} N - T0_I^T [[u]] / 2 + penalty s_I phi_I [[u]] ], s = +1 on the
  // + face, -1 on the other.
  for (std::size_t i = 0; i < ties_.size(); ++i) {
    const TiePoint& t = ties_[i];
    const Vec2& n = bq_.normals[t.plus];
    const Vec2 mean = 0.5 * (tie_update(i, 0, d, false).stress + tie_update(i, 1, d, false).stress) * n;
    Vec2 jump = Vec2::Zero();
    for (const TieSide side : {TieSide{t.plus, 1.0}, TieSide{t.minus, -1.0}})
      for (Index s = at_boundary_.row_begin(side.point); s < at_boundary_.row_end(side.point); ++s)
        jump += side.sign * at_boundary_.phi[s] * d.segment<2>(2 * at_boundary_.nodes[s]);
    const double w = bq_.weights[t.plus];
    for (const TieSide side : {TieSide{t.plus, 1.0}, TieSide{t.minus, -1.0}})
      for (Index s = at_boundary_.row_begin(side.point); s < at_boundary_.row_end(side.point); ++s) {
        const double phi = side.sign * at_boundary_.phi[s];
        f.segment<2>(2 * at_boundary_.nodes[s]) +=
            w * (-phi * mean - 0.5 * reference_traction_[s].transpose() * jump + t.penalty * phi * jump);
      }
  }
}

void TotalLagrangian::add_tie_tangent(const Eigen::VectorXd& d, double* values) const {
  // K_IJ = w [ -s_I phi_I T_J / 2 - s_J phi_J T0_I^T / 2 + penalty s_I s_J phi_I phi_J ],
  // T_J = (A(F) : grad(phi_J e_k)) N of J's side.
  std::vector<Mat2> traction;
  std::vector<Index> slots;
  std::vector<double> signs;
  for (std::size_t i = 0; i < ties_.size(); ++i) {
    const TiePoint& t = ties_[i];
    const Vec2& n = bq_.normals[t.plus];
    const double w = bq_.weights[t.plus];
    traction.clear();
    slots.clear();
    signs.clear();
    for (const TieSide side : {TieSide{t.plus, 1.0}, TieSide{t.minus, -1.0}}) {
      const Tangent<2> a = linear_ ? reference_tangents_[law_of_boundary_[side.point]]
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
        const Mat2 kij =
            w * (-0.5 * phi_i * traction[b] - 0.5 * phi_j * reference_traction_[slots[a]].transpose() +
                 t.penalty * phi_i * phi_j * Mat2::Identity());
        for (int r = 0; r < 2; ++r)
          for (int c = 0; c < 2; ++c) values[block_slot(pattern_, 2, i, j, r, c)] += kij(r, c);
      }
    }
  }
}

Vec2 TotalLagrangian::follower_stretch(Index p, const Eigen::VectorXd& d) const {
  const Vec2& t = bq_.tangents[p];
  Vec2 dx = t;
  for (Index s = at_boundary_.row_begin(p); s < at_boundary_.row_end(p); ++s)
    dx += d.segment<2>(2 * at_boundary_.nodes[s]) * at_boundary_.grad[s].dot(t);
  return dx;
}

Vec2 TotalLagrangian::boundary_load(Index p, const Eigen::VectorXd& d, const LoadState& load) const {
  if (const BoundaryCondition* c = traction_of_point_[p])
    return load.factor * dead_traction(*c, bq_.points[p], bq_.normals[p], load.time);
  if (const BoundaryCondition* c = follower_of_point_[p])
    return -load.factor * c->pressure(bq_.points[p], load.time) *
           (rotation_minus_90() * follower_stretch(p, d));
  return Vec2::Zero();
}

Eigen::VectorXd TotalLagrangian::external_force(const LoadState& load) const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(dofs());
  if (problem_.body_force) {
    std::vector<Vec2> wb(q_.size());
    parallel_blocks(q_.size(), 1024, [&](Index begin, Index end) {
      for (Index k = begin; k < end; ++k) wb[k] = q_.weights[k] * load.factor * problem_.body_force(q_.points[k], load.time);
    });
    f = gather_nodes(domain_rows_, [&](Index k, Index s) -> Vec2 { return q_.phi[s] * wb[k]; });
  }
  for (Index p = 0; p < bq_.size(); ++p) {
    const BoundaryCondition* c = traction_of_point_[p];
    if (!c) continue;
    const Vec2 t = bq_.weights[p] * load.factor * dead_traction(*c, bq_.points[p], bq_.normals[p], load.time);
    for (Index s = at_boundary_.row_begin(p); s < at_boundary_.row_end(p); ++s)
      f.segment<2>(2 * at_boundary_.nodes[s]) += at_boundary_.phi[s] * t;
  }
  return f;
}

void TotalLagrangian::tangent(const Eigen::VectorXd& d, const LoadState& load, SparseMatrix& k) const {
  std::fill(k.valuePtr(), k.valuePtr() + k.nonZeros(), 0.0);
  double* values = k.valuePtr();

  // Domain: w_K A(F_K), then K_IJ(i, k) = t_I,M [w A_iMkL g_J,L].
  std::vector<Tangent<2>> wa(q_.size());
  const bool linear = linear_;
  parallel_blocks(q_.size(), 1024, [&](Index begin, Index end) {
    for (Index p = begin; p < end; ++p)
      wa[p] = q_.weights[p] * (linear ? reference_tangents_[law_of_point_[p]]
                                      : domain_update(p, deformation_gradient(p, d), true).tangent);
  });
  add_column_blocks(q_, domain_rows_, pattern_, domain_symmetric_, values, [&](Index kk, Index slot_j) {
    const Vec2& g = q_.grad[slot_j];
    Eigen::Matrix<double, 4, 2> ag;  // ag(2 i + M, k) = w A_iMkL g_L
    for (int c = 0; c < 2; ++c)
      ag.col(c) = wa[kk].col(tensor_index<2>(c, 0)) * g.x() + wa[kk].col(tensor_index<2>(c, 1)) * g.y();
    return [this, ag](Index s) {
      const Vec2& t = test_[s];
      Eigen::Matrix2d b;
      b.row(0) = t.x() * ag.row(tensor_index<2>(0, 0)) + t.y() * ag.row(tensor_index<2>(0, 1));
      b.row(1) = t.x() * ag.row(tensor_index<2>(1, 0)) + t.y() * ag.row(tensor_index<2>(1, 1));
      return b;
    };
  });

  // Nitsche: K_IJ = w [ -phi_I Pi T_J(F) - T0_I^T Pi phi_J + penalty phi_I phi_J Pi ].
  std::vector<Mat2> t;  // Pi T_J(F) for the functions of the row
  for (std::size_t b = 0; b < nitsche_.size(); ++b) {
    const NitschePoint& p = nitsche_[b];
    const Index begin = at_boundary_.row_begin(p.point), end = at_boundary_.row_end(p.point), m = end - begin;
    const Tangent<2> a = linear ? reference_tangents_[law_of_boundary_[p.point]]
                                : boundary_update(b, boundary_deformation_gradient(p.point, d), true).tangent;
    const Vec2& n = bq_.normals[p.point];
    const double w = bq_.weights[p.point];
    t.resize(m);
    for (Index c = 0; c < m; ++c) t[c] = p.projection * traction_operator(a, at_boundary_.grad[begin + c], n);
    for (Index ai = 0; ai < m; ++ai) {
      const Index i = at_boundary_.nodes[begin + ai];
      const double phi_i = at_boundary_.phi[begin + ai];
      const Mat2 t0p = reference_traction_[begin + ai].transpose() * p.projection;
      for (Index bj = 0; bj < m; ++bj) {
        const Index j = at_boundary_.nodes[begin + bj];
        const double phi_j = at_boundary_.phi[begin + bj];
        const Mat2 kij = w * (-phi_i * t[bj] - phi_j * t0p + p.penalty * phi_i * phi_j * p.projection);
        for (int r = 0; r < 2; ++r)
          for (int c = 0; c < 2; ++c) values[block_slot(pattern_, 2, i, j, r, c)] += kij(r, c);
      }
    }
  }

  add_tie_tangent(d, values);

  // Follower pressures: K_IJ = w p phi_I (grad phi_J . T) R.
  for (const auto& [p, c] : follower_) {
    const Index begin = at_boundary_.row_begin(p), end = at_boundary_.row_end(p);
    const Vec2& tangent = bq_.tangents[p];
    const double wp = bq_.weights[p] * load.factor * c->pressure(bq_.points[p], load.time);
    for (Index ai = begin; ai < end; ++ai)
      for (Index bj = begin; bj < end; ++bj) {
        const double c = wp * at_boundary_.phi[ai] * at_boundary_.grad[bj].dot(tangent);
        const Index i = at_boundary_.nodes[ai], j = at_boundary_.nodes[bj];
        values[block_slot(pattern_, 2, i, j, 0, 1)] += c;
        values[block_slot(pattern_, 2, i, j, 1, 0)] -= c;
      }
  }
}

double TotalLagrangian::strain_energy(const Eigen::VectorXd& d) const {
  std::vector<double> partial(thread_count(), 0.0);
  parallel_ranges(q_.size(), [&](int thread, Index begin, Index end) {
    double sum = 0.0;
    for (Index k = begin; k < end; ++k)
      sum += q_.weights[k] * at_point("quadrature", q_.points, k, [&] {
               return energy(problem_.law(law_of_point_[k]), deformation_gradient(k, d),
                             history_laws_ ? history_.domain[k] : MaterialState<2>{});
             });
    partial[thread] = sum;
  });
  double total = 0.0;
  for (double s : partial) total += s;
  return total;
}

std::vector<double> TotalLagrangian::point_densities() const {
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

SparseMatrix TotalLagrangian::mass_matrix() const {
  // The mass couples only nodes sharing a domain row: blocks rho0 w phi_I phi_J I_2.
  const std::vector<double> rho = point_densities();
  SparseMatrix m = zero_matrix();
  add_column_blocks(q_, domain_rows_, pattern_, true, m.valuePtr(), [&](Index k, Index slot_j) {
    const double c = rho[k] * q_.weights[k] * q_.phi[slot_j];
    return [this, c](Index s) -> Eigen::Matrix2d { return c * q_.phi[s] * Eigen::Matrix2d::Identity(); };
  });
  return m;
}

Eigen::VectorXd TotalLagrangian::lumped_mass(const std::vector<Vec2>& node_positions) const {
  const std::vector<double> rho = point_densities();
  const Eigen::VectorXd m = gather_nodes(domain_rows_, [&](Index k, Index s) -> Vec2 {
    return Vec2::Constant(rho[k] * q_.weights[k] * q_.phi[s]);
  });
  for (Index i = 0; i < nodes_; ++i)
    if (!(m[2 * i] > 0.0))
      throw NumericalError(fmt::format(
          "lumped mass of node {} at ({:.6g}, {:.6g}) is {:.3e}, not positive: the row-sum mass needs "
          "shape functions with a positive integral (use linear RK, or the implicit scheme with the "
          "consistent mass)",
          i, node_positions[i].x(), node_positions[i].y(), m[2 * i]));
  return m;
}

}  // namespace mfree
