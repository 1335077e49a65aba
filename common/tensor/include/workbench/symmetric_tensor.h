#pragma once
// The one record of a symmetric tensor (stress [Pa], strain [-]) that every model and the
// comparison share, and the one von Mises stress. Header only, on the standard library alone: the
// embeddable agent library, the FEM and the comparison all include it.
#include <algorithm>
#include <array>
#include <cmath>

namespace workbench {

/// The components in Voigt order: the FEM result's (sigma_x ... tau_xz), compare::StressSlot's and
/// the agents' (agent::AgentState::stress). A 2D plane-stress tensor has zz = yz = xz = 0.
enum Voigt : int { kXX, kYY, kZZ, kXY, kYZ, kXZ, kVoigtCount };
using SymmetricTensor = std::array<double, kVoigtCount>;

/// Which operation order von_mises sums in. The value is the same; the last bits are not, and each
/// output keeps the bits it has always had (docs/compare.md, "Von Mises").
enum class VonMisesForm {
  General,     ///< 0.5 ((xx-yy)^2 + (yy-zz)^2 + (zz-xx)^2) + 3 (xy^2 + yz^2 + xz^2): the FEM, the comparison, 3D agents
  PlaneStress  ///< xx^2 - xx yy + yy^2 + 3 xy^2 (zz = yz = xz = 0), clamped at 0: the 2D agents
};

/// The von Mises stress of `s` (six components, Voigt order) [Pa].
inline double von_mises(const double* s, VonMisesForm form = VonMisesForm::General) {
  if (form == VonMisesForm::PlaneStress)
    return std::sqrt(std::max(0.0, s[kXX] * s[kXX] - s[kXX] * s[kYY] + s[kYY] * s[kYY] + 3 * s[kXY] * s[kXY]));
  const double dxy = s[kXX] - s[kYY], dyz = s[kYY] - s[kZZ], dzx = s[kZZ] - s[kXX];
  return std::sqrt(0.5 * (dxy * dxy + dyz * dyz + dzx * dzx) + 3 * (s[kXY] * s[kXY] + s[kYZ] * s[kYZ] + s[kXZ] * s[kXZ]));
}
inline double von_mises(const SymmetricTensor& s, VonMisesForm form = VonMisesForm::General) {
  return von_mises(s.data(), form);
}

}  // namespace workbench
