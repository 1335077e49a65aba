// The coefficient table's checks (agent/coefficients.h).
#include <agent/coefficients.h>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace agent {

namespace {
std::string shortest(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  double back = 0;
  for (int p = 1; p <= 17; ++p) {  // the fewest digits that read back as v
    std::ostringstream t;
    t.precision(p);
    t << v;
    if (std::istringstream(t.str()) >> back && back == v) return t.str();
  }
  return s.str();
}
}  // namespace

std::string CoefficientSpec::problem(double v) const {
  const bool inside = std::isfinite(v) && (min_open ? v > min : v >= min) && (max_open ? v < max : v <= max) &&
                      (!integer || v == std::floor(v));
  if (inside) return "";
  if (choices) {  // a named choice: its names, not its index
    std::string names;
    for (int i = 0; i < choice_count; ++i) names += std::string(i ? ", " : "") + "\"" + choices[i] + "\"";
    return "must be one of " + names + " (got index " + shortest(v) + ")";
  }
  std::string range;
  if (max >= kNoMax)
    range = min_open ? "> " + shortest(min) : ">= " + shortest(min);
  else
    range = "in " + std::string(min_open ? "(" : "[") + shortest(min) + ", " + shortest(max) + (max_open ? ")" : "]");
  return std::string("must be ") + (integer ? "an integer " : "") + range + (*unit ? std::string(" ") + unit : "") +
         " (got " + shortest(v) + ")";
}

const CoefficientSpec* find_coefficient(const std::string& name) {
  for (const auto& c : kCoefficients)
    if (name == c.name) return &c;
  return nullptr;
}

void check_coefficients(const Coefficients& k, RuleSet rules) {
  for (const auto& c : kCoefficients)
    if (c.used_by(rules))
      if (const auto why = c.problem(c.get(k)); !why.empty()) throw CoefficientError(c.name, why);
  for (const auto& constraint : kCoefficientConstraints)
    if ((constraint.rules & rule_bit(rules)) && !constraint.holds(k))
      throw CoefficientError(constraint.key, constraint.need);
}

}  // namespace agent
