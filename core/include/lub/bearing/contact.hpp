// Dry contact between journal and bearing when the film collapses: an effect a scene switches
// on (`effects.contact`), with a smooth hand-over from the film force. Pure functions of the
// bearing state, like the force laws.
//
// ## Model
// Penetration δ = c (ε − ε_a)⁺ [m] and its rate δ̇ = c ε̇ [m/s], with ε_a the start of the
// hand-over band [ε_a, ε_b] (0 < ε_a < ε_b < 1): the surfaces are taken to touch when the film
// thickness c(1 − ε) falls to c(1 − ε_a) — the composite roughness, the film's last support.
// Normal force on the journal, towards the bearing centre (F_r = −F_n, F_t = 0; no friction):
//     F_n = K δ^n (1 + χ δ̇),  clamped at 0 (no adhesion when separating fast),
// the Hunt–Crossley form with a hysteresis damping factor χ [s/m] from the coefficient of
// restitution c_e:
//     lankarani_nikravesh:  χ = 3 (1 − c_e²)/(4 v_ref)    (Lankarani & Nikravesh 1990)
//     hunt_crossley:        χ = 3 (1 − c_e)/(2 v_ref)      (Hunt & Crossley 1975)
// The published models divide by the impact velocity δ̇⁻ of each impact; a force law that is a
// pure function of the state cannot remember it, so the scene sets a reference impact speed
// v_ref and the restitution is exact for impacts at that speed (slower impacts dissipate
// less, faster ones more). Stiffness K [N/m^n] given, or for a journal inside a bearing (conformal
// cylinders, Flores et al. 2006, after Hertz):
//     K = 4/(3 (σ_J + σ_B)) · (R_J R_B/(R_B − R_J))^(1/2),   σ = (1 − ν²)/E,   n = 1.5.
//
// ## Hand-over
// Film weight ω_f(ε) = 1 − S((ε − ε_a)/(ε_b − ε_a)), S the C² smootherstep 6x⁵ − 15x⁴ + 10x³
// clamped to [0, 1]; total force = ω_f · film + contact. Below ε_a the film alone acts (the
// contact is zero there too); above ε_b the contact alone acts and the film law is not
// evaluated at all, so no film law ever sees ε >= ε_b (< 1). The total is C² in ε (C¹ where
// the contact force starts, like δ^1.5 itself) and continuous in ε̇, w wherever the film law is.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lub/bearing/force_laws.hpp"

namespace lub {

enum class ContactModel { lankarani_nikravesh, hunt_crossley };

template <>
struct NameTable<ContactModel> {
  static constexpr std::array<std::pair<ContactModel, std::string_view>, 2> entries{{
      {ContactModel::lankarani_nikravesh, "lankarani_nikravesh"},
      {ContactModel::hunt_crossley, "hunt_crossley"},
  }};
};

/// Elastic constants of one body's surface material.
struct ContactMaterial {
  double youngs_modulus_Pa = 0.0;  ///< E > 0
  double poisson_ratio = 0.0;      ///< ν in [0, 0.5)
};

/// The contact effect as a scene gives it (effects.contact).
struct ContactSpec {
  ContactModel model = ContactModel::lankarani_nikravesh;
  std::optional<double> stiffness;               ///< K [N/m^n], or from the materials:
  std::optional<ContactMaterial> journal_material, bearing_material;
  double exponent = 1.5;                         ///< n
  double restitution = 0.9;                      ///< c_e in (0, 1]
  double reference_impact_speed_m_s = 1.0;       ///< v_ref > 0
  double handover_start_eps = 0.97;              ///< ε_a: contact starts, film starts fading
  double handover_end_eps = 0.995;               ///< ε_b: film gone (< 1)
  std::vector<int> joints;                       ///< scene joint indices; empty: every film joint
};

/// The contact law of one joint, resolved from the spec and that joint's geometry.
struct ContactLaw {
  double stiffness = 0.0;        ///< K [N/m^n]
  double exponent = 1.5;         ///< n
  double damping_s_per_m = 0.0;  ///< χ
  double eps_start = 0.97;       ///< ε_a
  double eps_end = 0.995;        ///< ε_b
};

/// K for a journal of radius R_J inside a bearing of radius R_B (formula above).
double conformal_cylinder_stiffness(double journal_radius_m, double bearing_radius_m,
                                    const ContactMaterial& journal, const ContactMaterial& bearing);

/// Resolves `spec` for a joint of geometry `g`.
ContactLaw resolve_contact(const ContactSpec& spec, const BearingGeometry& g);

/// ω_f(ε): 1 for ε <= ε_a, 0 for ε >= ε_b, smootherstep between.
double film_weight(const ContactLaw& law, double eps);

/// F_n >= 0 [N] at eccentricity ratio ε and rate ε̇ for radial clearance c [m].
double contact_normal_force_N(const ContactLaw& law, double clearance_m, double eps, double eps_dot);

/// Elastic energy stored in the contact [J]: ∫ K δ^n dδ = K δ^(n+1)/(n + 1) (the damping part
/// of F_n dissipates). For energy balances: the film/contact work of a run that ends in
/// contact includes this recoverable part.
double contact_elastic_energy_J(const ContactLaw& law, double clearance_m, double eps);

/// Total force on the journal with the contact effect: ω_f · film(s) + contact, where
/// `film(const BearingState&)` returns the film law's FilmForce and is called only when
/// ε < ε_b. `contact_N` (optional) receives F_n.
template <class Film>
FilmForce force_with_contact(const ContactLaw& law, double clearance_m, const BearingState& s,
                             Film&& film, double* contact_N = nullptr) {
  FilmForce f;
  const double wf = film_weight(law, s.eps);
  if (wf > 0.0) {
    const FilmForce ff = film(s);
    f.radial_N = wf * ff.radial_N;
    f.tangential_N = wf * ff.tangential_N;
  }
  const double fn = contact_normal_force_N(law, clearance_m, s.eps, s.eps_dot);
  f.radial_N -= fn;
  if (contact_N) *contact_N = fn;
  return f;
}

}  // namespace lub
