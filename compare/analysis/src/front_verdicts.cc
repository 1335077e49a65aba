// The front's verdicts: domination, speed-up at equal error, the crossover (docs/front.md).
#include <compare/front_verdicts.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace compare {

namespace {

/// The point's error in `metric`; NaN (no verdict, on no front) where it has none or does not model the field.
double error_of(const FrontPoint& p, const std::string& metric) {
  const auto it = p.errors.find(metric);
  return it == p.errors.end() || p.not_modelled.count(metric) ? NAN : it->second;
}

double floor_of(const std::map<std::string, double>& floors, const std::string& metric) {
  const auto it = floors.find(metric);
  return it == floors.end() || !std::isfinite(it->second) ? 0.0 : it->second;
}

/// Whether `q` is at least as fast and as accurate as `p` in `metric`, and better in one.
bool dominates(const FrontPoint& q, const FrontPoint& p, const std::string& metric) {
  const double eq = error_of(q, metric), ep = error_of(p, metric);
  if (!std::isfinite(eq)) return false;
  return q.seconds_min <= p.seconds_min && eq <= ep && (q.seconds_min < p.seconds_min || eq < ep);
}

/// The cheapest point of `points` that dominates `p`, or null.
const FrontPoint* cheapest_dominating(const std::vector<FrontPoint>& points, const FrontPoint& p,
                                      const std::string& metric) {
  const FrontPoint* best = nullptr;
  for (const auto& q : points)
    if (&q != &p && dominates(q, p, metric) && (!best || q.seconds_min < best->seconds_min)) best = &q;
  return best;
}

/// The speed-up (or its bound) of the fast model's point `p` against the FEM front.
void set_speedup(FrontVerdict& v, const FrontPoint& p, const std::vector<const FrontPoint*>& fem,
                 const std::string& metric) {
  if (fem.empty()) return;
  const double e = error_of(p, metric);
  if (const auto t = time_at_error(fem, metric, e)) {
    v.speedup = *t / p.seconds_min;
  } else if (e > error_of(*fem.front(), metric)) {
    v.speedup_at_most = fem.front()->seconds_min / p.seconds_min;
  } else {
    v.speedup_at_least = fem.back()->seconds_min / p.seconds_min;
  }
}

/// The fast model's families, in order of appearance: (model, rule set) of every point not the FEM's.
std::vector<std::pair<std::string, std::string>> fast_families(const std::vector<FrontPoint>& points) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& p : points) {
    const std::pair<std::string, std::string> family{p.model, p.rule_set};
    if (p.model != "fem" && std::find(out.begin(), out.end(), family) == out.end()) out.push_back(family);
  }
  return out;
}

/// The crossover of two fronts: sampled at log-spaced errors over the range both reach.
FrontCrossover crossover(const std::vector<const FrontPoint*>& fast, const std::vector<const FrontPoint*>& fem,
                         const std::string& metric) {
  FrontCrossover c;
  if (fast.empty() || fem.empty()) {
    c.note = "no front to compare: one model has no error above the reference's floor";
    return c;
  }
  const double lo = std::max(error_of(*fast.back(), metric), error_of(*fem.back(), metric));
  const double hi = std::min(error_of(*fast.front(), metric), error_of(*fem.front(), metric));
  if (!(lo <= hi)) {
    c.note = "the two fronts share no range of errors";
    return c;
  }
  constexpr int kSamples = 200;
  for (int i = 0; i <= kSamples; ++i) {  // from the smallest shared error up
    const double e = lo * std::pow(hi / lo, double(i) / kSamples);
    const auto ta = time_at_error(fast, metric, e), tf = time_at_error(fem, metric, e);
    if (ta && tf && *ta < *tf) {
      c.fem_cheaper_below = e;
      c.note = i == 0 ? "the fast model is cheaper at every error both reach; the FEM alone reaches below this"
                      : "the FEM is cheaper below this error, the fast model above it";
      return c;
    }
  }
  c.fem_cheaper_below = hi;
  c.note = "the FEM is cheaper at every error both reach";
  return c;
}

}  // namespace

std::vector<const FrontPoint*> family_front(const std::vector<FrontPoint>& points, const std::string& metric,
                                            const std::string& model, const std::string& rule_set, double floor) {
  std::vector<const FrontPoint*> family;
  for (const auto& p : points) {
    const double e = error_of(p, metric);
    if (p.model == model && (rule_set.empty() || p.rule_set == rule_set) && std::isfinite(e) && e > floor)
      family.push_back(&p);
  }
  std::vector<const FrontPoint*> front;
  for (const FrontPoint* p : family)
    if (std::none_of(family.begin(), family.end(), [&](const FrontPoint* q) { return dominates(*q, *p, metric); }))
      front.push_back(p);
  std::sort(front.begin(), front.end(), [&](const FrontPoint* a, const FrontPoint* b) {
    return error_of(*a, metric) > error_of(*b, metric);
  });
  return front;
}

std::optional<double> time_at_error(const std::vector<const FrontPoint*>& front, const std::string& metric,
                                    double error) {
  for (std::size_t i = 0; i < front.size(); ++i) {
    const double e0 = error_of(*front[i], metric);
    if (error == e0) return front[i]->seconds_min;
    if (i + 1 == front.size()) break;
    const double e1 = error_of(*front[i + 1], metric);
    if (error < e0 && error > e1) {
      const double t0 = front[i]->seconds_min, t1 = front[i + 1]->seconds_min;
      const double s = std::log(error / e0) / std::log(e1 / e0);
      return t0 * std::pow(t1 / t0, s);
    }
  }
  return std::nullopt;
}

std::vector<FrontVerdict> front_verdicts(const std::vector<FrontPoint>& points, const std::vector<std::string>& metrics,
                                         const std::map<std::string, double>& floors) {
  std::vector<FrontVerdict> out;
  for (const auto& metric : metrics) {
    const double floor = floor_of(floors, metric);
    const auto fem = family_front(points, metric, "fem", "", floor);
    for (const auto& p : points) {
      const double e = error_of(p, metric);
      if (!std::isfinite(e)) continue;
      FrontVerdict v;
      v.point = p.label;
      v.metric = metric;
      v.below_floor = e <= floor;
      if (!v.below_floor) {
        if (const FrontPoint* q = cheapest_dominating(points, p, metric)) v.dominated_by = q->label;
        if (p.model != "fem") set_speedup(v, p, fem, metric);
      }
      out.push_back(std::move(v));
    }
  }
  return out;
}

std::vector<FrontCrossover> front_crossovers(const std::vector<FrontPoint>& points,
                                             const std::vector<std::string>& metrics,
                                             const std::map<std::string, double>& floors) {
  std::vector<FrontCrossover> out;
  for (const auto& metric : metrics) {
    const double floor = floor_of(floors, metric);
    const auto fem = family_front(points, metric, "fem", "", floor);
    for (const auto& [model, rules] : fast_families(points)) {
      auto c = crossover(family_front(points, metric, model, rules, floor), fem, metric);
      c.metric = metric;
      c.model = model;
      c.rule_set = rules;
      out.push_back(std::move(c));
    }
  }
  return out;
}

}  // namespace compare
