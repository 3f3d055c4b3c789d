// Asperity contact in a journal bearing (mixed lubrication): an effect a scene names
// (`effects.mixed_lubrication`), added to the film force where the film is thinner than a few
// roughnesses. Pure functions of the bearing state, like the force laws.
//
// ## Model (Greenwood & Tripp 1970)
// Two rough surfaces with composite RMS roughness σ [m] (σ² = σ_J² + σ_B²), asperity density
// η [1/m²], asperity summit radius β [m] and composite modulus E' [Pa]
// (1/E' = (1 − ν_J²)/E_J + (1 − ν_B²)/E_B) carry a nominal asperity pressure at the local
// film thickness h [m]
//     p_a(h) = K E' F_{5/2}(h/σ),      K = (16√2/15) π (η β σ)² √(σ/β),
//     F_n(H) = 1/√(2π) ∫_H^∞ (s − H)^n e^{−s²/2} ds     (Gaussian summit heights).
// F_{5/2}(0) = 2^{3/4} Γ(7/4)/√(2π) = 0.61664; dF_n/dH = −n F_{n−1}.
//
// ## Force on the journal
// With the force laws' convention (θ from the line of maximum film, h = c (1 + ε cos θ)) the
// pressure is symmetric about the line of centres, so the force is radial:
//     F_r = R_J L ∫_0^{2π} p_a(h(θ)) cos θ dθ = −W_a,      F_t = 0,
// W_a >= 0 the asperity load [N], pushing the journal back towards the bearing centre. The
// pressure is evaluated only where h < 8σ (F_{5/2}(8) ≈ 1e-17: below round-off of F_{5/2}(0)),
// by Gauss–Legendre quadrature over that arc. Off unless a scene names it; the film law is
// evaluated as without it (load sharing: the film and the asperities carry the load side by
// side, Johnson, Greenwood & Poon 1972). No friction torque is applied to the mechanism.
#pragma once

#include <array>
#include <string_view>
#include <utility>
#include <vector>

#include "lub/bearing/force_laws.hpp"
#include "lub/common/name_table.hpp"

namespace lub {

enum class AsperityModel { greenwood_tripp };

template <>
struct NameTable<AsperityModel> {
  static constexpr std::array<std::pair<AsperityModel, std::string_view>, 1> entries{{
      {AsperityModel::greenwood_tripp, "greenwood_tripp"},
  }};
};

/// The mixed-lubrication effect as a scene gives it (effects.mixed_lubrication).
struct AsperitySpec {
  AsperityModel model = AsperityModel::greenwood_tripp;
  double roughness_m = 0.0;              ///< σ, composite RMS roughness
  double asperity_density_per_m2 = 0.0;  ///< η
  double asperity_radius_m = 0.0;        ///< β
  double composite_modulus_Pa = 0.0;     ///< E'
  double boundary_friction = 0.0;        ///< μ_b, friction coefficient of the asperity contacts
  std::vector<int> joints;               ///< scene joint indices; empty: every film joint
};

/// The asperity law of one joint: p_a(h) = pressure_scale_Pa · F_{5/2}(h/σ).
struct AsperityLaw {
  double roughness_m = 0.0;        ///< σ
  double pressure_scale_Pa = 0.0;  ///< K E'
  double boundary_friction = 0.0;  ///< μ_b
};

/// Film thickness beyond which the asperity pressure is taken as zero, in units of σ.
inline constexpr double kAsperityCutoffRatio = 8.0;

AsperityLaw resolve_asperity(const AsperitySpec& spec);

/// F_{5/2}(H), H = h/σ (any H; 0 for H >= 8), and its derivative −(5/2) F_{3/2}(H), from a
/// table of both filled once by quadrature (cubic Hermite between nodes, error below 1e-10).
double greenwood_tripp_f52(double H, double* derivative = nullptr);

/// F_n(H) by direct quadrature of its definition (n > 0): the table's source, for checks.
double greenwood_tripp_integral(double n, double H);

/// Nominal asperity pressure p_a [Pa] at film thickness h [m].
double asperity_pressure_Pa(const AsperityLaw& law, double film_m);

/// Asperity load W_a >= 0 [N] on a journal at eccentricity ratio ε (radial force −W_a).
double asperity_load_N(const AsperityLaw& law, const BearingGeometry& g, double eps);

}  // namespace lub
