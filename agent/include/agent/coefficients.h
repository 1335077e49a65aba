#pragma once
// The transfer coefficients of every rule set and the one table that describes them.
//
// agent::kCoefficients is the only list of coefficient names in the project: the library's range
// check, the case reader, the calibration (its parameters and bounds), the Python module's dicts,
// summary.json and docs/case-file.md's table all read it. Adding a coefficient is one member of
// Coefficients (or of a rule set's own struct) and one row here (README, "Adding a coefficient").
#include <array>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace agent {

/// The two readings of the seed's transfer rules and the project's extensions (docs/agent-model.md).
enum class RuleSet {
  Patent,      ///< literal: entry x alpha1, each step down x alpha2, friction alpha3 re-entered with alpha1
  Conserving,  ///< each agent splits its whole load between below (alpha2) and the outward sides (alpha3 each)
  Directional, ///< not the seed's: packets with slopes from a fan (agent/directional.h); uses gamma only
  /// not the seed's: bending, columns across the beam axis carry the section resultants to a clamp
  /// or two supports (agent/columns.h); 2D and 3D, no coefficient
  Columns,
  /// not the seed's: per load, the rule set that carries it (directional where a rigid face lies
  /// ahead, columns where the supports lie beside), the loads' states superposed. A study's choice
  /// (agent_study::carry_check): a LoadTransfer runs one rule set and refuses this one.
  Auto,
};

/// Every rule set, in the order of the enum.
constexpr std::array<RuleSet, 5> kRuleSets{RuleSet::Patent, RuleSet::Conserving, RuleSet::Directional, RuleSet::Columns,
                                           RuleSet::Auto};

/// The rule set's name in case files and reports ("patent", "conserving", "directional", "columns", "auto").
constexpr const char* rule_set_name(RuleSet r) {
  return r == RuleSet::Patent        ? "patent"
         : r == RuleSet::Conserving  ? "conserving"
         : r == RuleSet::Directional ? "directional"
         : r == RuleSet::Columns     ? "columns"
                                     : "auto";
}

/// How the directional rule set's packets go (docs/agent-model.md, "Paths"): turning toward the
/// place where they belong once the load fills the width (sigma_x from the tie scan), or straight
/// rays mirrored by the free sides (the first rule set). Named in kPathNames, in this order.
enum class Paths { Turning, Mirror };
inline constexpr const char* kPathNames[] = {"turning", "mirror"};

/// Whether the directional rule set's 2D stresses include the closed-form layers (Kirsch's shear
/// round a hole, the elastic half-plane's layer on a bonded base; docs/agent-model.md, "Agents
/// against closed forms") or leave them out: the agents alone. Named in kClosedFormNames, in this order.
enum class ClosedForms { Added, LeftOut };
inline constexpr const char* kClosedFormNames[] = {"added", "left_out"};

/// 2D turning paths near a free side (docs/agent-model.md, "Loads near a side"): each half of the
/// fan mapped onto the body's width on its own side, or both onto the wider side's width with the
/// paths that would cross the nearer side folded back as their image (its shear negated: a free
/// side holds none), or a blend: each row b = exp(-2 d / W) of each direction on its side path,
/// the rest on its image path (d the row's depth, W the loaded row's width). Named in
/// kNearSideNames, in this order.
enum class NearSide { Side, Image, Blend };
inline constexpr const char* kNearSideNames[] = {"side", "image", "blend"};

/// Coefficients of the directional rule set. The defaults are the calibrated ones
/// (docs/calibration.md): a case that names only the rule set gets the documented accuracy.
struct DirectionalCoefficients {
  int directions = 32;      ///< slopes in the fan per lateral axis; even (no straight-down packet)
  double fan_angle = 66.1;   ///< half-opening of the entry fan [degrees], in (0, 90)
  double fan_power = 2.59;    ///< 2D: entry weight of a packet at angle t from the load: cos(t)^fan_power
  /// 3D: the weight is the product over the two lateral axes of cos(t)^fan_power_3d (a point load
  /// spreads with a more concentrated fan than a line load: fitted separately)
  double fan_power_3d = 3.99;
  /// Lateral diffusion length [m]: each row adds diffusion_length * row height [m^2] of variance
  double diffusion_length = 2e-3;
  Paths paths = Paths::Turning;
  /// 3D turning paths: height of the bonded rigid face's local layer (sigma across = nu / (1 - nu)
  /// sigma along on the face) as a share of the width of the pressure on that face (2D takes the
  /// elastic half-plane's layer, which has no coefficient)
  double base_layer_3d = 0.25;
  /// Turning paths: Gaussian window [m] of the local quadratic fit that takes d/d(depth) of the
  /// shear for the tie scan (docs/research/stress-components.md)
  double window_length = 5e-3;
  ClosedForms closed_forms = ClosedForms::Added;  ///< 2D turning paths: the closed-form layers added, or the agents alone
  NearSide near_side = NearSide::Blend;  ///< 2D turning paths: the near side's packets on its own width, the fan's image, or a blend by depth
};

/// Which threshold a transfer drops loads by (docs/agent-model.md, "The threshold"): the seed's
/// absolute gamma [N], or gamma_relative, a share of the load entering the body. A case names one
/// of the two keys; naming neither gives the relative one (it carries the load at any scale).
enum class Threshold { Absolute, Relative };
/// "absolute" (gamma) or "relative" (gamma_relative): summaries say which acts.
constexpr const char* threshold_name(Threshold t) { return t == Threshold::Absolute ? "absolute" : "relative"; }

struct Coefficients {
  double alpha1 = 0.5;         ///< entry coefficient (seed: P1 = alpha1 P0)
  double alpha2 = 0.5;         ///< passing on in the load direction (P2 = alpha2 P1)
  double alpha3 = 0.25;        ///< friction to each side neighbour (P3 = alpha3 P0)
  double beta = 0.5;           ///< share of the Poisson expansion an agent keeps; 1 - beta is pushed out
  double gamma = 1e-3;         ///< absolute threshold [N]: a load at or below it is not passed on
  /// Relative threshold: gamma_relative x the load entering the body [N] (sum of the entry loads'
  /// magnitudes, pushes and pulls) is the gamma of the solve.
  double gamma_relative = 1e-9;
  Threshold threshold = Threshold::Relative;  ///< which of gamma, gamma_relative is in effect
  /// The absolute threshold [N] a solve whose loads enter with `entering` N in all drops loads by.
  double gamma_for(double entering) const { return threshold == Threshold::Absolute ? gamma : gamma_relative * entering; }
  /// Factor per agent on a sideways (Poisson) push as it is passed on; unset, it follows alpha2
  /// ("the same rule set turned 90 degrees", docs/agent-model.md). Read it through decay().
  std::optional<double> poisson_decay;
  double decay() const { return poisson_decay.value_or(alpha2); }
  DirectionalCoefficients directional;  ///< the directional rule set's own coefficients
};

/// The rule set of a name (rule_set_name's inverse), or nothing.
inline std::optional<RuleSet> rule_set_named(const std::string& name) {
  for (RuleSet r : kRuleSets)
    if (name == rule_set_name(r)) return r;
  return std::nullopt;
}

/// Bit of a rule set in CoefficientSpec::rules.
constexpr unsigned rule_bit(RuleSet r) { return 1u << unsigned(r); }

/// The upper end of a range without one (gamma: any value >= 0).
inline constexpr double kNoMax = 1e100;

/// One coefficient: its name in case files, Python and summaries, where it lives, its default,
/// the values it admits, its unit, the bounds a calibration searches by default, and the rule sets
/// that use it. A row of kCoefficients is written with the builder below, each field by name:
///   row("alpha2", "meaning").read_by(kSeedRules).range(0, 1).fit(0.01, 1.0).value(get, set)
struct CoefficientSpec {
  const char* name = "";
  const char* unit = "";     ///< SI; "" for a pure number
  const char* meaning = "";  ///< one line for docs/case-file.md and the Python help
  unsigned rules = 0;        ///< rule_bit() of every rule set whose transfer reads it
  double min = 0, max = 0;   ///< admissible values
  bool min_open = false, max_open = false;
  /// Fitted by a calibration (a real number a rule set reads). Not fitted: poisson_decay (unset
  /// by default: it follows alpha2), gamma_relative, and the choices `directions` and `paths`.
  bool fitted = false;
  double fit_min = 0, fit_max = 0;  ///< a calibration's default bounds (the range unless narrowed)
  bool integer = false;      ///< an integer (directions)
  bool optional = false;     ///< absent from a case, it stays unset (poisson_decay: then it follows alpha2)
  double (*get)(const Coefficients&) = nullptr;  ///< the value in effect (a named choice: its index)
  /// Sets the value; a threshold's key also selects its kind (gamma: absolute, gamma_relative: relative).
  void (*set)(Coefficients&, double) = nullptr;
  /// A choice among names (a case file gives the name, summaries the index): `choice_count` names;
  /// nullptr for a number. A choice is an integer in [0, choice_count - 1].
  const char* const* choices = nullptr;
  int choice_count = 0;
  /// Whether the value acts in `k` (nullptr: always); a case file lists only what acts.
  bool (*acts)(const Coefficients&) = nullptr;
  bool acts_in(const Coefficients& k) const { return !acts || acts(k); }
  /// The library's default (in effect: poisson_decay's is alpha2's).
  double default_value() const { return get(Coefficients{}); }
  bool used_by(RuleSet r) const { return rules & rule_bit(r); }
  /// The name of choice `v` ("" for a number or an index out of range).
  const char* choice_name(double v) const {
    return choices && v >= 0 && v < choice_count && v == int(v) ? choices[int(v)] : "";
  }
  /// "" when `v` is admissible, else why not ("must be in [0, 1] (got 2)").
  std::string problem(double v) const;

  // The builder: each returns the row with one more field set.
  constexpr CoefficientSpec measured_in(const char* u) const { return with([&](CoefficientSpec& c) { c.unit = u; }); }
  constexpr CoefficientSpec read_by(unsigned rule_bits) const { return with([&](CoefficientSpec& c) { c.rules = rule_bits; }); }
  /// Admits [lo, hi]; a calibration searches the same unless fit() or bounds() narrow it.
  constexpr CoefficientSpec range(double lo, double hi) const {
    return with([&](CoefficientSpec& c) { c.min = c.fit_min = lo, c.max = c.fit_max = hi; });
  }
  constexpr CoefficientSpec at_least(double lo) const { return range(lo, kNoMax); }
  constexpr CoefficientSpec open_min() const { return with([](CoefficientSpec& c) { c.min_open = true; }); }
  constexpr CoefficientSpec open_max() const { return with([](CoefficientSpec& c) { c.max_open = true; }); }
  constexpr CoefficientSpec open() const { return open_min().open_max(); }
  /// A calibration's default bounds, the coefficient not fitted.
  constexpr CoefficientSpec bounds(double lo, double hi) const {
    return with([&](CoefficientSpec& c) { c.fit_min = lo, c.fit_max = hi; });
  }
  /// Fitted by a calibration, by default within [lo, hi].
  constexpr CoefficientSpec fit(double lo, double hi) const {
    return bounds(lo, hi).with([](CoefficientSpec& c) { c.fitted = true; });
  }
  constexpr CoefficientSpec whole() const { return with([](CoefficientSpec& c) { c.integer = true; }); }
  constexpr CoefficientSpec unset_by_default() const { return with([](CoefficientSpec& c) { c.optional = true; }); }
  constexpr CoefficientSpec value(double (*read)(const Coefficients&), void (*write)(Coefficients&, double)) const {
    return with([&](CoefficientSpec& c) { c.get = read, c.set = write; });
  }
  /// A choice among `count` names (an integer index in [0, count - 1]).
  constexpr CoefficientSpec named(const char* const* names, int count) const {
    return range(0, count - 1).whole().with([&](CoefficientSpec& c) { c.choices = names, c.choice_count = count; });
  }
  constexpr CoefficientSpec acting_when(bool (*when)(const Coefficients&)) const {
    return with([&](CoefficientSpec& c) { c.acts = when; });
  }

 private:
  template <class F>
  constexpr CoefficientSpec with(F&& change) const {
    CoefficientSpec c = *this;
    change(c);
    return c;
  }
};

/// A row of kCoefficients: its name and meaning, the rest set by name (CoefficientSpec's builder).
constexpr CoefficientSpec row(const char* name, const char* meaning) {
  CoefficientSpec c;
  c.name = name;
  c.meaning = meaning;
  return c;
}

inline constexpr unsigned kSeedRules = rule_bit(RuleSet::Patent) | rule_bit(RuleSet::Conserving);
/// The directional rule set's coefficients are auto's too (the rule it chooses where a face lies ahead).
inline constexpr unsigned kDirectionalRules = rule_bit(RuleSet::Directional) | rule_bit(RuleSet::Auto);
inline constexpr unsigned kAllRules = kSeedRules | kDirectionalRules;

/// Every coefficient. The fitted ones come first, in the order of a calibration's parameter vector
/// (read a row by name: coefficient_index, find_coefficient).
inline constexpr std::array<CoefficientSpec, 17> kCoefficients{{
    row("alpha1", "entry coefficient: the entry agent takes alpha1 of the load (seed: P1 = alpha1 P0)")
        .read_by(rule_bit(RuleSet::Patent)).range(0, 1).fit(0.0, 1.0)
        .value([](const Coefficients& k) { return k.alpha1; }, [](Coefficients& k, double v) { k.alpha1 = v; }),
    row("alpha2", "share passed on in the load direction (P2 = alpha2 P1)")
        .read_by(kSeedRules).range(0, 1).fit(0.01, 1.0)  // the conserving split needs alpha2 + alpha3 > 0
        .value([](const Coefficients& k) { return k.alpha2; }, [](Coefficients& k, double v) { k.alpha2 = v; }),
    row("alpha3", "friction to each side neighbour (P3 = alpha3 P0)")
        .read_by(kSeedRules).range(0, 1).fit(0.0, 1.0)
        .value([](const Coefficients& k) { return k.alpha3; }, [](Coefficients& k, double v) { k.alpha3 = v; }),
    row("beta", "share of its Poisson expansion an agent keeps; 1 - beta is pushed out sideways")
        .read_by(kSeedRules).range(0, 1).fit(0.0, 1.0)
        .value([](const Coefficients& k) { return k.beta; }, [](Coefficients& k, double v) { k.beta = v; }),
    row("gamma", "absolute threshold: a load at or below it is not passed on (names the absolute threshold)")
        .measured_in("N").read_by(kAllRules).at_least(0).fit(0.0, 1e-2)
        .value([](const Coefficients& k) { return k.gamma; },
               [](Coefficients& k, double v) { k.gamma = v, k.threshold = Threshold::Absolute; })
        .acting_when([](const Coefficients& k) { return k.threshold == Threshold::Absolute; }),
    row("fan_angle", "half-opening of the entry fan")
        .measured_in("degrees").read_by(kDirectionalRules).range(0, 90).open().fit(20.0, 89.0)
        .value([](const Coefficients& k) { return k.directional.fan_angle; },
               [](Coefficients& k, double v) { k.directional.fan_angle = v; }),
    row("fan_power", "2D: a packet at angle t from the load enters with weight cos(t)^fan_power")
        .read_by(kDirectionalRules).range(0, 100).fit(0.0, 8.0)
        .value([](const Coefficients& k) { return k.directional.fan_power; },
               [](Coefficients& k, double v) { k.directional.fan_power = v; }),
    row("fan_power_3d", "3D: the weight is the product over both lateral axes of cos(t)^fan_power_3d")
        .read_by(kDirectionalRules).range(0, 100).fit(0.0, 8.0)
        .value([](const Coefficients& k) { return k.directional.fan_power_3d; },
               [](Coefficients& k, double v) { k.directional.fan_power_3d = v; }),
    row("diffusion_length", "lateral diffusion: each row adds diffusion_length x row height of variance")
        .measured_in("m").read_by(kDirectionalRules).range(0, 1).fit(0.0, 0.02)
        .value([](const Coefficients& k) { return k.directional.diffusion_length; },
               [](Coefficients& k, double v) { k.directional.diffusion_length = v; }),
    row("base_layer_3d", "3D turning paths: the bonded rigid face's layer, as a share of its pressure's width (2D: the half-plane's)")
        .read_by(kDirectionalRules).range(0, 10).fit(0.0, 1.0)
        .value([](const Coefficients& k) { return k.directional.base_layer_3d; },
               [](Coefficients& k, double v) { k.directional.base_layer_3d = v; }),
    row("window_length", "turning paths: window of the fit that takes the shear's derivative along the march")
        .measured_in("m").read_by(kDirectionalRules).range(0, 1).open_min().fit(1e-3, 0.02)
        .value([](const Coefficients& k) { return k.directional.window_length; },
               [](Coefficients& k, double v) { k.directional.window_length = v; }),
    row("poisson_decay", "factor per agent on a sideways (Poisson) push as it is passed on; unset: alpha2")
        .read_by(kSeedRules).range(0, 1).unset_by_default()
        .value([](const Coefficients& k) { return k.decay(); }, [](Coefficients& k, double v) { k.poisson_decay = v; }),
    row("gamma_relative", "relative threshold: gamma = gamma_relative x the load entering the body (the default)")
        .read_by(kAllRules).range(0, 1).open_max().bounds(0.0, 1e-3)
        .value([](const Coefficients& k) { return k.gamma_relative; },
               [](Coefficients& k, double v) { k.gamma_relative = v, k.threshold = Threshold::Relative; })
        .acting_when([](const Coefficients& k) { return k.threshold == Threshold::Relative; }),
    row("directions", "slopes in the fan per lateral axis, even (an odd fan has a straight-down packet)")
        .read_by(kDirectionalRules).range(2, 256).whole()
        .value([](const Coefficients& k) { return double(k.directional.directions); },
               [](Coefficients& k, double v) { k.directional.directions = int(v); }),
    row("paths", "how packets go: \"turning\" toward where they belong (sigma_x from the tie) or \"mirror\" (straight, mirrored by free sides)")
        .read_by(kDirectionalRules).named(kPathNames, 2)
        .value([](const Coefficients& k) { return double(k.directional.paths); },
               [](Coefficients& k, double v) { k.directional.paths = Paths(int(v)); }),
    row("closed_forms", "2D turning paths: \"added\" (Kirsch's shear round a hole, the half-plane's layer on a bonded base) or \"left_out\" (the agents alone)")
        .read_by(kDirectionalRules).named(kClosedFormNames, 2)
        .value([](const Coefficients& k) { return double(k.directional.closed_forms); },
               [](Coefficients& k, double v) { k.directional.closed_forms = ClosedForms(int(v)); }),
    row("near_side", "2D turning paths: \"side\" (each half of the fan on its own side's width), \"image\" (on the wider side's, folded back at the nearer side) or \"blend\" (each row exp(-2 depth / width) on the side paths, the rest on the image's)")
        .read_by(kDirectionalRules).named(kNearSideNames, 3)
        .value([](const Coefficients& k) { return double(k.directional.near_side); },
               [](Coefficients& k, double v) { k.directional.near_side = NearSide(int(v)); }),
}};

/// The place of the row named `name` in kCoefficients; throws std::invalid_argument for an unknown
/// name (at compile time where the name is a constant: coefficient_index("alpha2")).
constexpr std::size_t coefficient_index(std::string_view name) {
  for (std::size_t i = 0; i < kCoefficients.size(); ++i)
    if (name == kCoefficients[i].name) return i;
  throw std::invalid_argument("no coefficient named " + std::string(name));
}

/// What a rule set needs of its coefficients beyond their ranges: a constraint between
/// coefficients (or on one), naming its keys; a case file's error names the first.
struct CoefficientConstraint {
  unsigned rules;             ///< rule_bit() of the rule sets that need it
  const char* key;            ///< the coefficient an error names
  const char* other;          ///< the other coefficient it reads ("" for none)
  const char* need;           ///< what it needs, said after the key ("must be even (...)")
  bool (*holds)(const Coefficients&);
};
inline constexpr std::array<CoefficientConstraint, 2> kCoefficientConstraints{{
    {kDirectionalRules, "directions", "",
     "must be even (an odd fan has a straight-down packet: a spike under the load)",
     [](const Coefficients& k) { return k.directional.directions % 2 == 0; }},
    {rule_bit(RuleSet::Conserving), "alpha2", "alpha3",
     "must be > 0 where alpha3 is 0 (the conserving rule set splits by alpha2 + alpha3 > 0)",
     [](const Coefficients& k) { return k.alpha2 + k.alpha3 > 0; }},
}};

/// check_coefficients' error: `key` the coefficient it names, `problem` what is wrong with it
/// (what() is the key and the problem).
struct CoefficientError : std::invalid_argument {
  CoefficientError(const std::string& key_, const std::string& problem_)
      : std::invalid_argument(key_ + " " + problem_), key(key_), problem(problem_) {}
  std::string key, problem;
};

/// How many coefficients a calibration can fit: the first rows of kCoefficients.
constexpr std::size_t fitted_count() {
  std::size_t n = 0;
  while (n < kCoefficients.size() && kCoefficients[n].fitted) ++n;
  return n;
}
inline constexpr std::size_t kFittedCount = fitted_count();
static_assert([] {
  for (std::size_t i = kFittedCount; i < kCoefficients.size(); ++i)
    if (kCoefficients[i].fitted) return false;
  return true;
}(), "the fitted coefficients come first in kCoefficients");

/// The row of a coefficient by name, or nullptr.
const CoefficientSpec* find_coefficient(const std::string& name);

/// Throws CoefficientError naming the first coefficient the rule set uses that lies outside its
/// range, or the first of kCoefficientConstraints the rule set needs that does not hold.
/// Coefficients a rule set does not use are not read by it and not checked.
void check_coefficients(const Coefficients& k, RuleSet rules);

}  // namespace agent
