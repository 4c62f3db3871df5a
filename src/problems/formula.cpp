#include "mfree/problems/formula.hpp"

#include <fmt/format.h>
#include <muParser.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <optional>

#include "mfree/core/error.hpp"

namespace mfree {

namespace {

constexpr std::array<const char*, 7> variable_names{"x", "y", "X", "Y", "t", "z", "Z"};
/// The variables of a formula of `dimension`: the first 5 of variable_names, or all 7.
std::size_t variable_count(int dimension) { return dimension == 3 ? 7 : 5; }
std::string variable_list(int dimension) { return dimension == 3 ? "x, y, z, X, Y, Z, t" : "x, y, X, Y, t"; }
constexpr int max_threads = 1024;

bool is_identifier(const std::string& s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

/// Position of `name` as a whole word in `text` (text.size() if absent).
std::size_t token_position(const std::string& text, const std::string& name) {
  const auto word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  for (std::size_t at = text.find(name); at != std::string::npos; at = text.find(name, at + 1))
    if ((at == 0 || !word(text[at - 1])) && (at + name.size() == text.size() || !word(text[at + name.size()])))
      return at;
  return text.size();
}

/// One parser with its own variables: a thread evaluates through its own copy.
struct Evaluator {
  mu::Parser parser;
  double x = 0.0, y = 0.0, z = 0.0, t = 0.0;

  Evaluator(const std::string& expression, const Constants& constants, int dimension) {
    parser.DefineVar("x", &x);
    parser.DefineVar("y", &y);
    parser.DefineVar("X", &x);
    parser.DefineVar("Y", &y);
    parser.DefineVar("t", &t);
    if (dimension == 3) {
      parser.DefineVar("z", &z);
      parser.DefineVar("Z", &z);
    }
    parser.DefineConst("pi", M_PI);
    parser.DefineConst("e", M_E);
    for (const auto& [name, value] : constants) parser.DefineConst(name, value);
    parser.SetExpr(expression);
  }
};

}  // namespace

struct Formula::Impl {
  std::string expression, key;
  Constants constants;
  int dimension = 2;
  std::optional<double> value;  ///< set when the formula is a constant
  bool time = false;
  bool space = false;  ///< uses x, y, X or Y
  // Built on a thread's first call; each thread touches only its own entry.
  mutable std::array<std::unique_ptr<Evaluator>, max_threads> evaluators;

  Evaluator& mine() const {
    const int k = omp_in_parallel() ? omp_get_thread_num() : 0;
    if (k >= max_threads) throw NumericalError(fmt::format("{}: formula evaluated on thread {} (at most {})", key, k, max_threads));
    if (!evaluators[k]) evaluators[k] = std::make_unique<Evaluator>(expression, constants, dimension);
    return *evaluators[k];
  }
};

Formula::Formula(const std::string& expression, const Constants& constants, std::string key, int dimension) {
  auto impl = std::make_shared<Impl>();
  impl->expression = expression;
  impl->key = std::move(key);
  if (dimension != 2 && dimension != 3)
    throw InputError(fmt::format("{}: a formula has dimension 2 or 3, not {}", impl->key, dimension));
  impl->dimension = dimension;
  const auto variables_end = variable_names.begin() + static_cast<std::ptrdiff_t>(variable_count(dimension));
  for (const auto& [name, value] : constants) {
    if (!is_identifier(name))
      throw InputError(fmt::format("{}: constant name '{}' is not a name (letters, digits and _, not starting with a digit)",
                                   impl->key, name));
    for (auto v = variable_names.begin(); v != variables_end; ++v)
      if (name == *v)
        throw InputError(fmt::format("{}: constant '{}' would hide the variable {}", impl->key, name, *v));
    if (name == "pi" || name == "e") throw InputError(fmt::format("{}: constant '{}' is predefined", impl->key, name));
    if (!std::isfinite(value)) throw InputError(fmt::format("{}: constant '{}' is not finite", impl->key, name));
  }
  // A control character (a NUL ends the text muParser sees; a tab or newline is a typing
  // slip in a one-line formula) is refused with its position, before the parser sees it.
  const auto control = std::find_if(expression.begin(), expression.end(),
                                    [](char c) { return std::iscntrl(static_cast<unsigned char>(c)) != 0; });
  if (control != expression.end())
    throw InputError(
        fmt::format("{}: formula holds the control character {:#04x} at character {}; a formula is one "
                    "line of printable text",
                    impl->key, static_cast<unsigned>(static_cast<unsigned char>(*control)),
                    control - expression.begin() + 1));
  impl->constants = constants;
  try {
    Evaluator& e = impl->mine();
    // GetUsedVar parses the expression and lists every name it takes for a variable,
    // defined or not.
    const mu::varmap_type used = e.parser.GetUsedVar();
    for (const auto& [name, where] : used)
      if (std::find(variable_names.begin(), variables_end, name) == variables_end) {
        const std::size_t at = token_position(expression, name);
        throw InputError(
            fmt::format("{}: formula '{}' names \"{}\" (at character {}), which is no variable and no "
                        "constant; variables are {}, constants pi, e{}",
                        impl->key, expression, name, at + 1, variable_list(dimension),
                        constants.empty() ? std::string(" (the scene has no [constants])")
                                          : " and those of [constants]"));
      }
    impl->time = used.count("t") > 0;
    impl->space = used.count("x") + used.count("y") + used.count("X") + used.count("Y") + used.count("z") +
                      used.count("Z") >
                  0;
    if (used.empty()) {
      const double v = e.parser.Eval();
      if (!std::isfinite(v))
        throw InputError(fmt::format("{}: formula '{}' evaluates to {}", impl->key, expression, v));
      impl->value = v;
    }
  } catch (const mu::Parser::exception_type& err) {
    const int pos = err.GetPos();
    std::string where;
    if (pos >= 0) where = fmt::format(" (at character {}: '{}' <-- here)", pos + 1, expression.substr(0, static_cast<std::size_t>(pos) + 1));
    throw InputError(
        fmt::format("{}: formula '{}' does not parse: {}{}; variables are {}, constants pi, e "
                    "and those of [constants]",
                    impl->key, expression, err.GetMsg(), where, variable_list(dimension)));
  }
  impl_ = std::move(impl);
}

Formula Formula::constant(double c, std::string key) {
  if (!std::isfinite(c)) throw InputError(fmt::format("{}: value {} is not finite", key, c));
  return Formula(fmt::format("{}", c), {}, std::move(key));
}

Formula::Formula(const Formula&) = default;
Formula::Formula(Formula&&) noexcept = default;
Formula& Formula::operator=(const Formula&) = default;
Formula& Formula::operator=(Formula&&) noexcept = default;
Formula::~Formula() = default;

double Formula::operator()(const Vec2& x, double t) const {
  if (impl_->value) return *impl_->value;
  Evaluator& e = impl_->mine();
  e.x = x.x();
  e.y = x.y();
  e.t = t;
  const double v = e.parser.Eval();
  if (!std::isfinite(v))
    throw InputError(fmt::format("{}: formula '{}' is {} at (x, y) = ({:.6g}, {:.6g}), t = {:.6g}", impl_->key,
                                     impl_->expression, v, x.x(), x.y(), t));
  return v;
}

double Formula::operator()(const Vec3& x, double t) const {
  if (impl_->value) return *impl_->value;
  if (impl_->dimension != 3)
    throw Error(fmt::format("{}: a plane formula evaluated at a point in space", impl_->key));
  Evaluator& e = impl_->mine();
  e.x = x.x();
  e.y = x.y();
  e.z = x.z();
  e.t = t;
  const double v = e.parser.Eval();
  if (!std::isfinite(v))
    throw InputError(fmt::format("{}: formula '{}' is {} at (x, y, z) = ({:.6g}, {:.6g}, {:.6g}), t = {:.6g}",
                                 impl_->key, impl_->expression, v, x.x(), x.y(), x.z(), t));
  return v;
}

void Formula::evaluate(const std::vector<Vec2>& points, double t, std::vector<double>& out) const {
  out.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) out[i] = (*this)(points[i], t);
}

const std::string& Formula::expression() const { return impl_->expression; }
const std::string& Formula::key() const { return impl_->key; }
bool Formula::depends_on_time() const { return impl_->time; }
bool Formula::depends_on_space() const { return impl_->space; }
bool Formula::is_constant() const { return impl_->value.has_value(); }

}  // namespace mfree
